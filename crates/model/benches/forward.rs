//! Speed of the forward model: one μ(v) for sphere and cylinder, μ with its
//! 16 partial derivatives, a 41-point sweep with its full Jacobian, and
//! sweeps of 41 and 4001 speeds —
//! 15-term Prony series, dynamic contact, default tolerance 1e-6, one core.
//! The cylinder's 41-point sweep also runs on a film 0.1 mm thick (ν = ½,
//! about 0.15 static contact half-widths), to time the film's own grid
//! step (BENCHMARKS.md "Cylinder films").
//! The sphere's sweep also runs on films d/r0 = 1e-3 … 10 (BENCHMARKS.md
//! "Films under a ball").
//! Then the same series as a table of 10 rows a decade (the knot-splitting
//! quadrature of `friction/knots.rs`): one μ and a 41-point sweep.

use criterion::{Criterion, criterion_group, criterion_main};
use rollfit_model::kernel::{KernelTable, step_for_tolerance};
use rollfit_model::{
    ContactSize, Geometry, Prony, Scene, Shape, Substrate, TabulatedModulus, ViscoelasticModulus,
};
use std::hint::black_box;

fn prony15() -> Prony {
    // One term per decade from 1e-9 s to 1e5 s, a broad rubber-like spectrum.
    let tau: Vec<f64> = (0..15).map(|k| 10f64.powi(k - 9)).collect();
    let h: Vec<f64> = (0..15)
        .map(|k| 3e6 * (-(((k as f64) - 5.0) / 4.0).powi(2)).exp() * 20.0 + 1e5)
        .collect();
    let e1 = 2e6 + h.iter().sum::<f64>();
    Prony::new(e1, h, tau).unwrap()
}

/// [`prony15`] sampled at 10 rows a decade from 1e-8 to 1e12 rad/s (four
/// decades beyond its relaxation rates on either side).
fn table15() -> TabulatedModulus {
    let p = prony15();
    let omega: Vec<f64> = (0..=200)
        .map(|i| 10f64.powf(-8.0 + i as f64 / 10.0))
        .collect();
    let e: Vec<_> = omega.iter().map(|&w| p.modulus(w)).collect();
    TabulatedModulus::new(
        omega,
        e.iter().map(|z| z.re).collect(),
        e.iter().map(|z| z.im).collect(),
    )
    .unwrap()
}

fn scene(shape: Shape) -> Scene<Prony> {
    scene_of(shape, None, prony15())
}

fn scene_of<M: ViscoelasticModulus>(
    shape: Shape,
    film_thickness: Option<f64>,
    material: M,
) -> Scene<M> {
    let load = if shape == Shape::Sphere { 1.0 } else { 200.0 };
    Scene::new(
        Geometry {
            shape,
            radius: 0.005,
            load,
        },
        Substrate {
            poisson: 0.5,
            film_thickness,
        },
        ContactSize::Dynamic,
        material,
    )
    .unwrap()
}

fn benches(c: &mut Criterion) {
    for shape in [Shape::Sphere, Shape::Cylinder] {
        // Build the kernel tables outside the timed loops.
        let _ = KernelTable::get(shape, step_for_tolerance(1e-6));
    }
    let sphere = scene(Shape::Sphere);
    let cylinder = scene(Shape::Cylinder);
    let v = 1e-3;
    c.bench_function("mu_sphere", |b| {
        b.iter(|| sphere.friction(black_box(v)).unwrap())
    });
    c.bench_function("mu_cylinder", |b| {
        b.iter(|| cylinder.friction(black_box(v)).unwrap())
    });
    c.bench_function("mu_and_gradient_sphere", |b| {
        b.iter(|| sphere.friction_with_gradient(black_box(&[v])).unwrap())
    });
    c.bench_function("mu_and_gradient_cylinder", |b| {
        b.iter(|| cylinder.friction_with_gradient(black_box(&[v])).unwrap())
    });
    let speeds: Vec<f64> = (0..41)
        .map(|i| 1e-6 * 10f64.powf(i as f64 * 6.0 / 40.0))
        .collect();
    c.bench_function("sweep41_jacobian_sphere", |b| {
        b.iter(|| sphere.friction_with_gradient(black_box(&speeds)).unwrap())
    });
    c.bench_function("sweep41_jacobian_cylinder", |b| {
        b.iter(|| cylinder.friction_with_gradient(black_box(&speeds)).unwrap())
    });
    c.bench_function("sweep41_sphere", |b| {
        b.iter(|| sphere.friction_sweep(black_box(&speeds)).unwrap())
    });
    c.bench_function("sweep41_cylinder", |b| {
        b.iter(|| cylinder.friction_sweep(black_box(&speeds)).unwrap())
    });
    let film_cylinder = scene_of(Shape::Cylinder, Some(1e-4), prony15());
    // Builds the kernel table of the film's grid step outside the timing.
    film_cylinder.friction(v).unwrap();
    c.bench_function("sweep41_film_cylinder", |b| {
        b.iter(|| film_cylinder.friction_sweep(black_box(&speeds)).unwrap())
    });
    c.bench_function("sweep41_jacobian_film_cylinder", |b| {
        b.iter(|| {
            film_cylinder
                .friction_with_gradient(black_box(&speeds))
                .unwrap()
        })
    });
    // The sweep the Python module's `scene.mu(v)` is timed against
    // (crates/python/bench/bench.py, BENCHMARKS.md "Python").
    let dense: Vec<f64> = (0..4001)
        .map(|i| 1e-6 * 10f64.powf(i as f64 * 6.0 / 4000.0))
        .collect();
    c.bench_function("sweep4001_sphere", |b| {
        b.iter(|| sphere.friction_sweep(black_box(&dense)).unwrap())
    });
    // Films under the ball: the same 41-speed sweep on films
    // d/r0 = 1e-3 … 10 thick, against `sweep41_sphere`. The film kernel's
    // rows are built by the warm-up (once per process), as the half-space
    // tables are above.
    let r0 = sphere.static_contact_size();
    for ratio in [1e-3, 1e-2, 0.1, 1.0, 10.0] {
        let film = scene_of(Shape::Sphere, Some(ratio * r0), prony15());
        let _ = film.friction_sweep(&speeds).unwrap();
        c.bench_function(&format!("sweep41_sphere_film_{ratio:e}"), |b| {
            b.iter(|| film.friction_sweep(black_box(&speeds)).unwrap())
        });
    }
    let table_sphere = scene_of(Shape::Sphere, None, table15());
    let table_cylinder = scene_of(Shape::Cylinder, None, table15());
    // The kernels' tables outside the timed loops.
    let _ = table_sphere.friction(v).unwrap();
    let _ = table_cylinder.friction(v).unwrap();
    c.bench_function("mu_table_sphere", |b| {
        b.iter(|| table_sphere.friction(black_box(v)).unwrap())
    });
    c.bench_function("mu_table_cylinder", |b| {
        b.iter(|| table_cylinder.friction(black_box(v)).unwrap())
    });
    c.bench_function("sweep41_table_sphere", |b| {
        b.iter(|| table_sphere.friction_sweep(black_box(&speeds)).unwrap())
    });
}

criterion_group!(forward, benches);
criterion_main!(forward);
