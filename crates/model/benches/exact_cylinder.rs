//! Speed of the exact rolling-cylinder solution (target: one point in
//! under 50 ms at default settings): the paper's Fig. 2 cylinder
//! (R = 1 cm, f_N = 100 N/m, standard linear solid E0 = 1 MPa, E1 = 10 MPa,
//! τ = 1 s, ν = 0) at four speeds: vτ/a0 = 0.001 (thin edge layers, more
//! than the 128 terms of the cap would be needed: the graded mesh, also
//! timed with the a-posteriori error estimate, which adds a solve on a
//! finer mesh) and 0.01 (105
//! terms), 1 (near the friction maximum) and 100 (24 terms each); and the stiff
//! solid E1/E0 = 1000 at vτ/a0 = 1 (its edge layers follow the relaxation
//! time τE0/E1: 106 terms).
//!
//! Target: one point with a 200-term Prony series in ≤ 0.5 s:
//! `prony200_v*`, a broad rubber (relaxation times log-spaced over 1e-12 … 1e8 s, E0 = 2 MPa, E1 = 2 GPa, ν = 0.5) under the same
//! cylinder at 1e-6, 1e-3 and 1 m/s (the graded mesh,
//! 190 … 330 nodes).
//!
//! Stiff solids at low speed (the cost per speed on the graded mesh): `sls1e4_v1e-4` and `sls1e4_v0.3`, the same cylinder on a standard
//! linear solid E0 = 1 MPa, E1 = 10 GPa, τ = 1 s at vτ/a0 = 1e-4 (200
//! nodes) and 0.3 (a decade below the friction maximum, 128 nodes), plain
//! and with the a-posteriori error estimate (a second solve on q + 2 nodes
//! per panel).

use criterion::{Criterion, criterion_group, criterion_main};
use rollfit_model::StandardLinearSolid;
use rollfit_model::exact::RollingCylinder;
use rollfit_testkit::materials::rubber_200;
use std::hint::black_box;

fn benches(c: &mut Criterion) {
    let sls = StandardLinearSolid::new(1e6, 1e7, 1.0).unwrap().to_prony();
    let cylinder = RollingCylinder::new(&sls, 0.0, 0.01, 100.0).unwrap();
    let a0 = cylinder.static_half_width();
    let mut group = c.benchmark_group("exact_cylinder");
    group.sample_size(20);
    for (name, reduced) in [
        ("sls_v0.001", 0.001),
        ("sls_v0.01", 0.01),
        ("sls_v1", 1.0),
        ("sls_v100", 100.0),
    ] {
        let v = reduced * a0;
        group.bench_function(name, |b| b.iter(|| cylinder.solve(black_box(v)).unwrap()));
    }
    let v = 0.001 * a0;
    group.bench_function("sls_v0.001_with_error_estimate", |b| {
        b.iter(|| cylinder.solve_with_error_estimate(black_box(v)).unwrap())
    });
    let stiff = StandardLinearSolid::new(1e6, 1e9, 1.0).unwrap().to_prony();
    let stiff_cylinder = RollingCylinder::new(&stiff, 0.0, 0.01, 100.0).unwrap();
    let v = stiff_cylinder.static_half_width();
    group.bench_function("sls1000_v1", |b| {
        b.iter(|| stiff_cylinder.solve(black_box(v)).unwrap())
    });
    let stiffer = StandardLinearSolid::new(1e6, 1e10, 1.0).unwrap().to_prony();
    let stiffer_cylinder = RollingCylinder::new(&stiffer, 0.0, 0.01, 100.0).unwrap();
    let a0 = stiffer_cylinder.static_half_width();
    for (name, reduced) in [("sls1e4_v1e-4", 1e-4), ("sls1e4_v0.3", 0.3)] {
        let v = reduced * a0;
        group.bench_function(name, |b| {
            b.iter(|| stiffer_cylinder.solve(black_box(v)).unwrap())
        });
        group.bench_function(format!("{name}_with_error_estimate"), |b| {
            b.iter(|| {
                stiffer_cylinder
                    .solve_with_error_estimate(black_box(v))
                    .unwrap()
            })
        });
    }
    group.finish();
}

fn many_terms(c: &mut Criterion) {
    let cylinder = RollingCylinder::new(&rubber_200(), 0.5, 0.01, 100.0).unwrap();
    let mut group = c.benchmark_group("exact_cylinder");
    group.sample_size(10);
    for (name, v) in [
        ("prony200_v1e-6", 1e-6),
        ("prony200_v1e-3", 1e-3),
        ("prony200_v1", 1.0),
    ] {
        group.bench_function(name, |b| b.iter(|| cylinder.solve(black_box(v)).unwrap()));
    }
    group.finish();
}

criterion_group!(exact, benches, many_terms);
criterion_main!(exact);
