//! Helpers shared by the integration tests (tolerance.rs, gradient.rs,
//! film_sphere.rs, limits.rs): a seeded LCG and random Prony series (no
//! extra crates), scene builders, and the parameter perturbation and check
//! of the finite-difference tests of ∂μ/∂(E1, H_k).
//!
//! Each test file is its own crate and uses only some of these helpers; the
//! rest would be reported as dead code in that crate.
#![allow(dead_code)]

use rollfit_model::{
    ContactSize, FrictionJacobian, Geometry, Prony, Scene, Shape, Substrate, ViscoelasticModulus,
};

/// A 64-bit linear congruential generator (Knuth's MMIX constants).
pub struct Lcg(pub u64);

impl Lcg {
    /// The next number, uniform in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A random broad solid: `terms` relaxation times a decade apart, the k-th
/// at 10^(k + `first_log_tau` + `jitter`·u) s (u uniform in [0, 1));
/// strengths over two decades from 1 MPa; E0 between 1 and 5 MPa.
pub fn random_prony(rng: &mut Lcg, terms: usize, first_log_tau: f64, jitter: f64) -> Prony {
    let tau: Vec<f64> = (0..terms)
        .map(|k| 10f64.powf(k as f64 + first_log_tau + jitter * rng.next()))
        .collect();
    let h: Vec<f64> = (0..terms)
        .map(|_| 1e6 * 10f64.powf(2.0 * rng.next()))
        .collect();
    let e0 = 1e6 * (1.0 + 4.0 * rng.next());
    Prony::new(e0 + h.iter().sum::<f64>(), h, tau).unwrap()
}

/// A scene of the given shape, radius (m), load (N or N/m), Poisson ratio,
/// film thickness and contact rule, at the default tolerance.
pub fn scene<M: ViscoelasticModulus>(
    shape: Shape,
    radius: f64,
    load: f64,
    nu: f64,
    film: Option<f64>,
    contact: ContactSize,
    material: M,
) -> Scene<M> {
    Scene::new(
        Geometry {
            shape,
            radius,
            load,
        },
        Substrate {
            poisson: nu,
            film_thickness: film,
        },
        contact,
        material,
    )
    .unwrap()
}

/// A 5 mm ball under 1 N or roller under 200 N/m on an incompressible
/// solid (optionally a film of that thickness), at `tolerance`.
pub fn ball_or_roller(
    shape: Shape,
    contact: ContactSize,
    film: Option<f64>,
    material: Prony,
    tolerance: f64,
) -> Scene<Prony> {
    let load = if shape == Shape::Sphere { 1.0 } else { 200.0 };
    scene(shape, 0.005, load, 0.5, film, contact, material)
        .with_tolerance(tolerance)
        .unwrap()
}

/// `p` with parameter `q` moved by `delta`: E1 for q = 0, otherwise H_q
/// (with E1 by as much, so that E0 stays fixed and the solid valid).
pub fn perturbed(p: &Prony, q: usize, delta: f64) -> Prony {
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

/// Checks d μ(v_i)/d δ of `perturbed(p, q, δ)` from the Jacobian against
/// its finite difference `fd`: they agree to 2e-5 μ/`base` plus `relative`
/// of the Jacobian's value. `what` names the case in the message.
pub fn assert_matches_difference(
    jac: &FrictionJacobian,
    i: usize,
    q: usize,
    fd: f64,
    base: f64,
    relative: f64,
    what: &str,
) {
    // The perturbation of H_k moves E1 too: combine columns.
    let np = jac.parameter_count;
    let analytic = if q == 0 {
        jac.jacobian[i * np]
    } else {
        jac.jacobian[i * np + q] + jac.jacobian[i * np]
    };
    let scale = jac.mu[i] / base;
    assert!(
        (analytic - fd).abs() <= 2e-5 * scale.abs() + relative * analytic.abs(),
        "{what} p{q}: analytic {analytic:e} fd {fd:e}"
    );
}
