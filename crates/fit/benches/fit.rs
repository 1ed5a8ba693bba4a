//! Speed of the inverse fit: an anchored (E0 known), regularised fit of 41
//! synthetic points of the bundled broad rubber (Havriliak–Negami truth, 1 %
//! noise, σ known so λ follows the discrepancy principle), default τ grid
//! (two per decade, 31 terms), default method (Levenberg–Marquardt, three
//! starts), including the λ choice. One core.

use criterion::{Criterion, criterion_group, criterion_main};
use rollfit_fit::{FitParams, ScaleAnchor, fit};
use std::hint::black_box;

#[path = "../tests/common/mod.rs"]
mod common;

use common::{hn_rubber, setup, synthetic};

fn benches(c: &mut Criterion) {
    let params = FitParams {
        anchor: Some(ScaleAnchor::StaticModulus(2e6)),
        ..FitParams::default()
    }
    .check(setup())
    .unwrap();
    let measured = synthetic(hn_rubber(), 0.01, 1);
    let mut group = c.benchmark_group("fit");
    group.sample_size(10);
    group.bench_function("anchored_regularised_41_points", |b| {
        b.iter(|| fit(black_box(&measured), &params).unwrap())
    });
    group.finish();
}

criterion_group!(fit_benches, benches);
criterion_main!(fit_benches);
