//! Speed of a batch (`rollfit batch`): 100 independent single-temperature
//! fits on a rayon pool of one thread and of two; and eight fits of the
//! bundled temperature set on two threads (throughput). The target: on 2
//! cores the batch is at least 1.8× faster than on one, and its results are
//! identical to running the fits one by one.
//!
//! The 100 data sets are synthetic measurements of the bundled broad rubber
//! (data/hn-rubber.toml: Havriliak–Negami truth, 41 speeds over 8 decades,
//! 1 % noise, σ known) with noise seeds 0…99; each is fitted with the
//! default settings and the bundled scene's scale anchor (|E| = 6.26e7 Pa
//! at 10 rad/s), as `rollfit batch` would with a manifest of 100 entries.
//! Before timing, the two-thread results are checked against the serial
//! ones (model, objective and misfit, bit for bit).

use criterion::{Criterion, criterion_group, criterion_main};
use rayon::prelude::*;
use rollfit_fit::{
    FitParams, FitReport, Measurements, ScaleAnchor, ShiftKind, ShiftSettings, ValidFitParams, fit,
};
use std::hint::black_box;

use rollfit_testkit::materials::hn_rubber;
use rollfit_testkit::rolling::{setup, synthetic, temperature_set};

const FITS: u64 = 100;

/// Fits every data set on a local pool of `threads` threads, in order.
fn batch(data: &[Measurements], params: &ValidFitParams, threads: usize) -> Vec<FitReport> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        data.par_iter()
            .with_max_len(1)
            .map(|d| fit(d, params).unwrap())
            .collect()
    })
}

fn benches(c: &mut Criterion) {
    let params = FitParams {
        anchor: Some(ScaleAnchor::ModulusAt {
            omega: 10.0,
            modulus: 6.26e7,
        }),
        ..FitParams::default()
    }
    .check(setup())
    .unwrap();
    let data: Vec<Measurements> = (0..FITS)
        .map(|seed| synthetic(hn_rubber(), 0.01, seed))
        .collect();

    // The results do not depend on the number of threads.
    let serial: Vec<FitReport> = data.iter().map(|d| fit(d, &params).unwrap()).collect();
    let parallel = batch(&data, &params, 2);
    assert_eq!(serial.len(), parallel.len());
    for (i, (s, p)) in serial.iter().zip(&parallel).enumerate() {
        assert_eq!(s.model, p.model, "data set {i}: model");
        assert_eq!(s.objective, p.objective, "data set {i}: objective");
        assert_eq!(s.misfit, p.misfit, "data set {i}: misfit");
        assert_eq!(
            s.misfit_per_point, p.misfit_per_point,
            "data set {i}: misfit per point"
        );
        assert_eq!(s.mu_fit, p.mu_fit, "data set {i}: fitted μ");
    }

    let mut group = c.benchmark_group("batch100");
    group.sample_size(10);
    for threads in [1, 2] {
        group.bench_function(format!("threads{threads}"), |b| {
            b.iter(|| batch(black_box(&data), &params, threads))
        });
    }
    group.finish();
    temperature_sets(c);
}

/// The throughput: fits per minute of the bundled temperature set
/// (data/hn-rubber-tset.toml: 5 temperatures × 41 speeds, WLF about
/// 20 °C, |E| at 10 rad/s, the cross-check on, as `rollfit batch` fits
/// it), eight noise seeds on a pool of two threads. Fits per minute =
/// 8 × 60 s / the median time.
fn temperature_sets(c: &mut Criterion) {
    let params = FitParams {
        anchor: Some(ScaleAnchor::ModulusAt {
            omega: 10.0,
            modulus: 6.26e7,
        }),
        shift: ShiftSettings {
            kind: ShiftKind::Wlf,
            t_ref: Some(20.0),
            ..ShiftSettings::default()
        },
        ..FitParams::default()
    }
    .check(setup())
    .unwrap();
    let data: Vec<Measurements> = (0..TEMPERATURE_SETS)
        .map(|seed| temperature_set(hn_rubber(), &[-20.0, 0.0, 20.0, 40.0, 60.0], 0.01, seed))
        .collect();
    let mut group = c.benchmark_group("batch_tset8");
    group.sample_size(10);
    group.bench_function("threads2", |b| {
        b.iter(|| batch(black_box(&data), &params, 2))
    });
    group.finish();
}

/// Temperature sets in the throughput bench.
const TEMPERATURE_SETS: u64 = 8;

criterion_group!(batch_benches, benches);
criterion_main!(batch_benches);
