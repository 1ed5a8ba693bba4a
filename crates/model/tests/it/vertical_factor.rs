//! The vertical factor of time–temperature superposition against the
//! identity it rests on (`modulus::shift`): with ν fixed, a
//! modulus b E* under load F gives the same μ(v) as E* under F/b, for the
//! sphere and the cylinder, the dynamic and the static contact size, on a
//! half-space and on a film, and for the exact rolling cylinder. The scaled
//! side is computed two ways — the `Shifted` wrapper and the Prony series
//! with E1 and every H_k multiplied by b — so the test checks the wrapper
//! against an independent construction as well as the physics.

use rollfit_testkit::scenes;

use rollfit_model::exact::RollingCylinder;
use rollfit_model::{ContactSize, Prony, Scene, Shape, Shifted, ViscoelasticModulus};
use rollfit_testkit::materials::rippled_prony;

/// A broad 12-term series, one term per decade (fixed).
fn broad_prony() -> Prony {
    rippled_prony(12, -8, 0.15)
}

fn scene<M: ViscoelasticModulus>(
    shape: Shape,
    load: f64,
    film: Option<f64>,
    contact: ContactSize,
    material: M,
) -> Scene<M> {
    scenes::scene(shape, 0.005, load, 0.5, film, contact, material)
        .with_tolerance(1e-10)
        .unwrap()
}

/// μ(v; b E, F) = μ(v; E, F/b) to 1e-10 (found: a few ulps), over eight decades of speed, with
/// b = 10^±0.2 and a horizontal shift besides.
#[test]
fn a_vertical_factor_is_a_load_divided_by_it() {
    let prony = broad_prony();
    let speeds: Vec<f64> = (0..9).map(|i| 1e-7 * 10f64.powi(i)).collect();
    let (log_a, mut worst) = (0.7, 0.0f64);
    for shape in [Shape::Sphere, Shape::Cylinder] {
        let load = if shape == Shape::Sphere { 1.0 } else { 200.0 };
        for contact in [ContactSize::Dynamic, ContactSize::Static] {
            for film in [None, Some(2e-3)] {
                for log_b in [0.2, -0.2] {
                    let b = 10f64.powf(log_b);
                    let wrapped = Shifted::new(prony.clone(), log_a)
                        .unwrap()
                        .with_vertical(log_b)
                        .unwrap();
                    let series = prony.shifted(log_a).unwrap().scaled(log_b).unwrap();
                    let lighter = Shifted::new(prony.clone(), log_a).unwrap();
                    let mu_wrapped = scene(shape, load, film, contact, wrapped)
                        .friction_sweep(&speeds)
                        .unwrap();
                    let mu_series = scene(shape, load, film, contact, series)
                        .friction_sweep(&speeds)
                        .unwrap();
                    let mu_lighter = scene(shape, load / b, film, contact, lighter)
                        .friction_sweep(&speeds)
                        .unwrap();
                    for i in 0..speeds.len() {
                        for other in [mu_series[i], mu_lighter[i]] {
                            let rel = (mu_wrapped[i] / other - 1.0).abs();
                            worst = worst.max(rel);
                            assert!(
                                rel < 1e-10,
                                "{shape:?} {contact:?} film {film:?} b = {b}: v = {}: {} vs {other}",
                                speeds[i],
                                mu_wrapped[i]
                            );
                        }
                    }
                    // Not a vacuous identity: b changes μ by far more than
                    // the tolerance.
                    let unscaled = scene(shape, load, film, contact, prony.shifted(log_a).unwrap())
                        .friction_sweep(&speeds)
                        .unwrap();
                    assert!((mu_wrapped[4] / unscaled[4] - 1.0).abs() > 1e-2);
                }
            }
        }
    }
    eprintln!("largest relative difference {worst:e}");
}

/// The exact rolling cylinder (Hunter 1961) obeys the same identity: its
/// pressure scales with the load and the strain with p/E.
#[test]
fn the_exact_cylinder_obeys_the_same_identity() {
    let prony = broad_prony();
    let log_b: f64 = 0.25;
    let b = 10f64.powf(log_b);
    let stiffer = RollingCylinder::new(&prony.scaled(log_b).unwrap(), 0.5, 0.005, 200.0).unwrap();
    let lighter = RollingCylinder::new(&prony, 0.5, 0.005, 200.0 / b).unwrap();
    for v in [1e-5, 1e-3, 1e-1] {
        let (x, y) = (stiffer.solve(v).unwrap().mu, lighter.solve(v).unwrap().mu);
        assert!((x / y - 1.0).abs() < 1e-6, "v = {v}: {x} vs {y}");
    }
}
