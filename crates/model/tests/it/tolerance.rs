//! The tolerance dial: μ computed at a requested relative tolerance agrees
//! with μ at the finest setting (1e-12) to within that tolerance, for random
//! Prony series (seeded LCG), both shapes, both contact rules, and speeds
//! from deep in the low-speed tail (where the oscillatory kernel tails
//! matter most) to well above the friction peak.

use rollfit_testkit::materials::{Lcg, random_prony};
use rollfit_testkit::scenes::ball_or_roller;

use rollfit_model::{ContactSize, Prony, Scene, Shape};

fn scene(shape: Shape, contact: ContactSize, material: Prony, tolerance: f64) -> Scene<Prony> {
    ball_or_roller(shape, contact, None, material, tolerance)
}

#[test]
fn requested_tolerance_is_met() {
    let mut rng = Lcg(20261121);
    let tolerances = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8];
    let mut worst_ratio = 0.0f64;
    for case in 0..6 {
        let terms = 3 + 2 * case;
        // A random broad solid: relaxation times about a decade apart from
        // 1e-6 s, strengths over two decades, E1/E0 between about 10 and 3000.
        let material = random_prony(&mut rng, terms, -6.0, 0.8);
        for shape in [Shape::Sphere, Shape::Cylinder] {
            for contact in [ContactSize::Dynamic, ContactSize::Static] {
                // Speeds in units of the natural speed r0/τ_max, 1e-9 … 1e3.
                let natural = scene(shape, contact, material.clone(), 1e-6).static_contact_size()
                    / material.relaxation_times().last().unwrap();
                let speeds: Vec<f64> = (0..13)
                    .map(|i| natural * 10f64.powf(-9.0 + i as f64 + 0.3 * rng.uniform()))
                    .collect();
                let exact = scene(shape, contact, material.clone(), 1e-12)
                    .friction_sweep(&speeds)
                    .unwrap();
                for &tolerance in &tolerances {
                    let mu = scene(shape, contact, material.clone(), tolerance)
                        .friction_sweep(&speeds)
                        .unwrap();
                    for ((&v, &m), &e) in speeds.iter().zip(&mu).zip(&exact) {
                        let error = (m / e - 1.0).abs();
                        worst_ratio = worst_ratio.max(error / tolerance);
                        assert!(
                            error <= tolerance,
                            "case {case} {shape:?} {contact:?} v = {v:e}: error {error:e} \
                             at tolerance {tolerance:e}"
                        );
                    }
                }
            }
        }
    }
    eprintln!("worst error / tolerance: {worst_ratio:.3}");
}
