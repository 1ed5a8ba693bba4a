//! Speed of the inverse fit: an anchored (E0 known), regularised fit of 41
//! synthetic points of the bundled broad rubber (Havriliak–Negami truth, 1 %
//! noise, σ known so λ follows the discrepancy principle), default τ grid
//! (two per decade, 31 terms), default method (Levenberg–Marquardt, three
//! starts), including the λ choice. One core.
//!
//! And a joint fit of a temperature set: 5 temperatures (−20 … 60 °C) × 41
//! speeds of the same rubber under a WLF shift (C1 = 8.86, C2 = 101.6 K at
//! 20 °C), 1 % noise, |E| at 10 rad/s as the anchor, default grid (two per
//! decade over the combined ~16 decades, 48 terms), C1 and C2 fitted; with
//! and without the single-temperature cross-check.
//!
//! And laboratory-shaped data 15 speeds over 5 decades of the
//! bundled rubber under its ball, 3 % noise, no sigma column (λ by the
//! marginal likelihood), |E| at the middle speed's contact frequency as the
//! anchor; and the same sweep logged as 10 000 rows (condensed to bins of
//! 1/20 decade before the fit).
//!
//! And a temperature set: 7 temperatures (−25 … 65 °C) × 21 speeds
//! (1e-8 … 1 m/s), 1 % noise, σ known, |E| at 10 rad/s as the anchor, the
//! joint fit with WLF and with free shifts, without the cross-check.
//!
//! And `physics = "exact"` 41 speeds over 8 decades around the
//! friction maximum of a broad rubber (200-term smooth spectrum,
//! E1/E0 = 1000) under a 5 mm cylinder at 1000 N/m, μ of the exact
//! contact with 1 % noise (seed 1), E0 anchored; defect correction with
//! the exact solves on both cores (rayon), the rest as above; and the same
//! under a 5 mm ball at 1 N with 1 % and 0.1 % noise. Run alone:
//! `cargo bench -p rollfit-fit --bench fit -- exact_physics`.
//!
//! And the joint fit of DMA isotherms and rolling friction: the
//! two-process truth of tests/joint.rs, six isotherms × ten frequencies
//! (1 % noise) and four temperatures × twelve speeds (2 % noise, no σ
//! column, no anchor), `shift = "auto"` at 20 °C, with κ = 1 and with κ
//! fitted; the whole joint fit (the DMA master curve, the rolling part
//! alone, both together). Run alone, on one core:
//! `taskset -c 1 cargo bench -p rollfit-fit --bench fit -- joint_dma`.

use criterion::{Criterion, SamplingMode, criterion_group, criterion_main};
use rollfit_fit::{
    DmaRows, FitParams, FrictionFactor, Physics, ScaleAnchor, ShiftKind, ShiftSettings, fit,
};
use rollfit_model::ViscoelasticModulus;
use std::hint::black_box;

use rollfit_testkit::materials::{hn_rubber, rubber_200};
use rollfit_testkit::rolling::{
    self, exact_and_approximate, exact_cylinder_setup, setup, sparse, synthetic, temperature_set,
    with_noise,
};

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
    let lab = sparse(setup(), hn_rubber(), 1e-6, 5.0, 15, 0.03, 1);
    let omega = 10f64.powf(-3.5) / rollfit_fit::tau_grid::contact_size(&setup(), 2e6);
    let lab_params = FitParams {
        anchor: Some(ScaleAnchor::ModulusAt {
            omega,
            modulus: hn_rubber().modulus(omega).norm(),
        }),
        ..FitParams::default()
    }
    .check(setup())
    .unwrap();
    group.bench_function("sparse_15_points_no_sigma", |b| {
        b.iter(|| fit(black_box(&lab), &lab_params).unwrap())
    });
    let dense = sparse(setup(), hn_rubber(), 1e-6, 5.0, 10_000, 0.03, 1);
    group.bench_function("dense_10000_rows_no_sigma", |b| {
        b.iter(|| fit(black_box(&dense), &lab_params).unwrap())
    });
    let set = temperature_set(hn_rubber(), &[-20.0, 0.0, 20.0, 40.0, 60.0], 0.01, 1);
    for (name, cross_check) in [
        ("joint_5x41_wlf", false),
        ("joint_5x41_wlf_with_cross_check", true),
    ] {
        let params = FitParams {
            anchor: Some(ScaleAnchor::ModulusAt {
                omega: 10.0,
                modulus: hn_rubber().modulus(10.0).norm(),
            }),
            shift: ShiftSettings {
                t_ref: Some(20.0),
                cross_check,
                ..ShiftSettings::default()
            },
            ..FitParams::default()
        }
        .check(setup())
        .unwrap();
        group.bench_function(name, |b| b.iter(|| fit(black_box(&set), &params).unwrap()));
    }
    // The temperature set: 7 temperatures × 21 speeds, WLF and free shifts, the
    // joint fit alone (its evaluation counts: tests/fit_cost.rs).
    let set = rolling::set_7x21(1);
    for (name, kind) in [
        ("joint_7x21_wlf", ShiftKind::Wlf),
        ("joint_7x21_free", ShiftKind::Free),
    ] {
        let params = rolling::set_7x21_params(kind);
        group.bench_function(name, |b| b.iter(|| fit(black_box(&set), &params).unwrap()));
    }
    group.finish();
    exact_physics(c);
}

/// The defect-corrected fit of 41 points of exact-contact data at σ = 1 %
/// and, for the sphere, 0.1 % (cost targets: at most 5 s for a
/// cylinder, 60 s for a sphere). The data are made only when a bench is
/// selected, once per body: the exact truth costs about 5 s (cylinder) and
/// a few minutes (sphere) itself.
/// The sphere alone: `cargo bench -p rollfit-fit --bench fit -- exact_physics_sphere`
/// (ten fits each).
fn exact_physics(c: &mut Criterion) {
    let mut group = c.benchmark_group("fit");
    // Seconds per fit: one fit per sample, not 1 + 2 + … + 10.
    group.sample_size(10).sampling_mode(SamplingMode::Flat);
    // The truth's accuracy: a tenth of the noise and below for the
    // sphere, whose cost grows like 1/accuracy.
    let cylinder = std::cell::OnceCell::new();
    let sphere = std::cell::OnceCell::new();
    for (name, setup, accuracy, truth, noise) in [
        (
            "exact_physics_cylinder_41_points",
            exact_cylinder_setup(),
            1e-6,
            &cylinder,
            0.01,
        ),
        (
            "exact_physics_sphere_41_points",
            setup(),
            1e-4,
            &sphere,
            0.01,
        ),
        (
            "exact_physics_sphere_41_points_sigma_0.1pct",
            setup(),
            1e-4,
            &sphere,
            0.001,
        ),
    ] {
        let params = FitParams {
            anchor: Some(ScaleAnchor::StaticModulus(2e6)),
            physics: Physics::Exact,
            ..FitParams::default()
        }
        .check(setup)
        .unwrap();
        let mut data = None;
        group.bench_function(name, |b| {
            let measured = data.get_or_insert_with(|| {
                let truth = truth
                    .get_or_init(|| exact_and_approximate(setup, &rubber_200(), accuracy).unwrap());
                with_noise(&truth.speeds, &truth.exact, noise, 1)
            });
            b.iter(|| fit(black_box(&*measured), &params).unwrap())
        });
    }
    group.finish();
}

fn joint_benches(c: &mut Criterion) {
    use rollfit_testkit::joint_case::{dma_isotherms, rolling, truth};
    let truth = truth();
    let isotherms = dma_isotherms(&truth, 0.01, 1);
    let rows = rolling(&truth, 1.0, 101);
    let mut group = c.benchmark_group("fit");
    group.sample_size(10);
    for (name, friction_factor) in [
        ("joint_dma_6x10_rolling_4x12", FrictionFactor::One),
        ("joint_dma_6x10_rolling_4x12_kappa", FrictionFactor::Free),
    ] {
        let params = FitParams {
            shift: ShiftSettings {
                t_ref: Some(20.0),
                ..ShiftSettings::default()
            },
            friction_factor,
            ..FitParams::default()
        }
        .check(setup())
        .unwrap()
        .with_dma(DmaRows::new(isotherms.clone(), "synthetic").unwrap())
        .unwrap();
        group.bench_function(name, |b| b.iter(|| fit(black_box(&rows), &params).unwrap()));
    }
    group.finish();
}

criterion_group!(fit_benches, benches, joint_benches);
criterion_main!(fit_benches);
