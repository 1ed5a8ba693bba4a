//! ∂μ/∂(E1, H_k) from the one-pass Jacobian against central finite
//! differences, on fixed random Prony series (seeded LCG, no extra crates).

use rollfit_testkit::jacobian::{assert_matches_difference, perturbed};
use rollfit_testkit::materials::{Lcg, random_prony};
use rollfit_testkit::scenes::ball_or_roller;

use rollfit_model::{ContactSize, Prony, Scene, Shape};

fn build(shape: Shape, contact: ContactSize, film: Option<f64>, p: Prony) -> Scene<Prony> {
    ball_or_roller(shape, contact, film, p, 1e-10)
}

#[test]
fn jacobian_matches_finite_differences() {
    let mut rng = Lcg(20261121);
    let speeds = [1e-7, 1e-4, 3e-3, 0.1, 10.0];
    for (shape, contact, film) in [
        (Shape::Sphere, ContactSize::Dynamic, None),
        (Shape::Cylinder, ContactSize::Dynamic, None),
        (Shape::Sphere, ContactSize::Static, None),
        (Shape::Cylinder, ContactSize::Static, Some(2e-4)),
    ] {
        // Relaxation times a decade apart from 1e-8 s, jittered by 0.5 decade.
        let p = random_prony(&mut rng, 15, -8.0, 0.5);
        let scene = build(shape, contact, film, p.clone());
        let jac = scene.friction_with_gradient(&speeds).unwrap();
        let np = jac.parameter_count;
        for q in 0..np {
            let base = if q == 0 {
                p.glassy_modulus()
            } else {
                p.strengths()[q - 1].max(1e5)
            };
            let delta = 1e-5 * base;
            let plus = build(shape, contact, film, perturbed(&p, q, delta))
                .friction_sweep(&speeds)
                .unwrap();
            let minus = build(shape, contact, film, perturbed(&p, q, -delta))
                .friction_sweep(&speeds)
                .unwrap();
            for i in 0..speeds.len() {
                let fd_column = (plus[i] - minus[i]) / (2.0 * delta);
                let what = format!("{shape:?} {contact:?} v={}", speeds[i]);
                assert_matches_difference(&jac, i, q, fd_column, base, 1e-6, &what);
            }
        }
        // μ from the gradient pass equals the plain sweep.
        let plain = scene.friction_sweep(&speeds).unwrap();
        for (a, b) in plain.iter().zip(&jac.mu) {
            assert!((a / b - 1.0).abs() < 1e-13);
        }
    }
}

/// ∂μ/∂ln v (the time-scale column used for temperature shifts) against a
/// central difference of μ in ln v, for each shape, contact choice and film.
#[test]
fn speed_derivative_matches_finite_differences() {
    let mut rng = Lcg(720_261_121);
    let speeds = [1e-7, 1e-4, 3e-3, 0.1, 10.0];
    let h: f64 = 1e-4;
    for (shape, contact, film) in [
        (Shape::Sphere, ContactSize::Dynamic, None),
        (Shape::Cylinder, ContactSize::Dynamic, None),
        (Shape::Sphere, ContactSize::Static, None),
        (Shape::Cylinder, ContactSize::Static, Some(2e-4)),
    ] {
        let p = random_prony(&mut rng, 15, -8.0, 0.5);
        let scene = build(shape, contact, film, p);
        let jac = scene.friction_with_gradient(&speeds).unwrap();
        let up: Vec<f64> = speeds.iter().map(|v| v * h.exp()).collect();
        let down: Vec<f64> = speeds.iter().map(|v| v * (-h).exp()).collect();
        let plus = scene.friction_sweep(&up).unwrap();
        let minus = scene.friction_sweep(&down).unwrap();
        for i in 0..speeds.len() {
            let fd = (plus[i] - minus[i]) / (2.0 * h);
            let scale = jac.mu[i].abs();
            assert!(
                (jac.d_ln_speed[i] - fd).abs() <= 1e-6 * scale,
                "{shape:?} {contact:?} film {film:?} v = {}: ∂μ/∂ln v {} vs difference {fd}",
                speeds[i],
                jac.d_ln_speed[i]
            );
        }
    }
}
