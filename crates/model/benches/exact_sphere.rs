//! Speed of the exact rolling sphere (target: ≤ 1 s per speed at
//! a requested accuracy of 1e-3, ≤ 10 s at 1e-4, on one core): Persson's
//! Fig. 2 sphere (R = 1 cm, F = 0.15 N, standard linear solid E0 = 1 MPa,
//! E1 = 10 MPa, τ = 1 s, ν = 0) at vτ/r0 = 1 (near the friction maximum)
//! and 0.01 (the low-speed side, longer set iteration), each with the
//! settings `SphereSettings::for_accuracy(1e-3)` and `(1e-4)`.
//!
//! Run on one core (the FFTs are otherwise parallel):
//!
//! `RAYON_NUM_THREADS=1 cargo bench -p rollfit-model --bench exact_sphere`

use criterion::{Criterion, criterion_group, criterion_main};
use rollfit_model::StandardLinearSolid;
use rollfit_model::exact::{RollingSphere, SphereSettings};
use std::hint::black_box;

fn benches(c: &mut Criterion) {
    let sls = StandardLinearSolid::new(1e6, 1e7, 1.0).unwrap().to_prony();
    let mut group = c.benchmark_group("exact_sphere");
    group.sample_size(10);
    for accuracy in [1e-3, 1e-4] {
        let settings = SphereSettings::for_accuracy(accuracy);
        let sphere = RollingSphere::with_settings(&sls, 0.0, 0.01, 0.15, settings).unwrap();
        let r0 = sphere.static_contact_radius();
        for reduced in [1.0, 0.01] {
            let v = reduced * r0;
            group.bench_function(format!("sls10_v{reduced}_eps{accuracy:e}"), |b| {
                b.iter(|| sphere.solve(black_box(v)).unwrap())
            });
        }
    }
    group.finish();
}

criterion_group!(exact, benches);
criterion_main!(exact);
