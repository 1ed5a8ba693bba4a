//! ∂μ/∂(E1, H_k) from the one-pass Jacobian against central finite
//! differences, on fixed random Prony series (seeded LCG, no extra crates).

use rollfit_model::{ContactSize, Geometry, Prony, Scene, Shape, Substrate};

struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn random_prony(rng: &mut Lcg, terms: usize) -> Prony {
    let tau: Vec<f64> = (0..terms)
        .map(|k| 10f64.powf(k as f64 - 8.0 + 0.5 * rng.next()))
        .collect();
    let h: Vec<f64> = (0..terms)
        .map(|_| 1e6 * 10f64.powf(2.0 * rng.next()))
        .collect();
    let e0 = 1e6 * (1.0 + 4.0 * rng.next());
    Prony::new(e0 + h.iter().sum::<f64>(), h, tau).unwrap()
}

fn build(shape: Shape, contact: ContactSize, film: Option<f64>, p: Prony) -> Scene<Prony> {
    let load = if shape == Shape::Sphere { 1.0 } else { 200.0 };
    Scene::new(
        Geometry {
            shape,
            radius: 0.005,
            load,
        },
        Substrate {
            poisson: 0.5,
            film_thickness: film,
        },
        contact,
        p,
    )
    .unwrap()
    .with_tolerance(1e-10)
    .unwrap()
}

fn perturbed(p: &Prony, q: usize, delta: f64) -> Prony {
    let mut e1 = p.glassy_modulus();
    let mut h = p.strengths().to_vec();
    if q == 0 {
        e1 += delta;
    } else {
        h[q - 1] += delta;
        e1 += delta; // keep E0 fixed so the perturbation stays a valid solid
    }
    Prony::new(e1, h, p.relaxation_times().to_vec()).unwrap()
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
        let p = random_prony(&mut rng, 15);
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
                // The perturbation of H_k moves E1 too: combine columns.
                let analytic = if q == 0 {
                    jac.jacobian[i * np]
                } else {
                    jac.jacobian[i * np + q] + jac.jacobian[i * np]
                };
                let scale = jac.mu[i] / base;
                assert!(
                    (analytic - fd_column).abs() <= 2e-5 * scale.abs() + 1e-6 * analytic.abs(),
                    "{shape:?} {contact:?} v={} p{q}: analytic {analytic:e} fd {fd_column:e}",
                    speeds[i]
                );
            }
        }
        // μ from the gradient pass equals the plain sweep.
        let plain = scene.friction_sweep(&speeds).unwrap();
        for (a, b) in plain.iter().zip(&jac.mu) {
            assert!((a / b - 1.0).abs() < 1e-13);
        }
    }
}
