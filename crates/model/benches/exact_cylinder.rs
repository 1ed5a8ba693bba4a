//! Speed of the exact rolling-cylinder solution (issue 6 target: one point
//! in under 50 ms at default settings): the paper's Fig. 2 cylinder
//! (R = 1 cm, f_N = 100 N/m, standard linear solid E0 = 1 MPa, E1 = 10 MPa,
//! τ = 1 s, ν = 0) at four speeds: vτ/a0 = 0.001 (thin edge layers, the
//! 128 terms of the cap do not resolve them: also timed with the
//! a-posteriori error estimate, which adds a 96-term solve) and 0.01 (105
//! terms), 1 (near the friction maximum) and 100 (24 terms each); and the stiff
//! solid E1/E0 = 1000 at vτ/a0 = 1 (its edge layers follow the relaxation
//! time τE0/E1: 106 terms).

use criterion::{Criterion, criterion_group, criterion_main};
use rollfit_model::StandardLinearSolid;
use rollfit_model::exact::RollingCylinder;
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
    group.finish();
}

criterion_group!(exact, benches);
criterion_main!(exact);
