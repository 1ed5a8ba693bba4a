//! The finite-difference check of the friction Jacobian ∂μ/∂(E1, H_k):
//! a Prony series with one parameter moved, and the comparison of the
//! analytic column with the difference quotient.

use rollfit_model::{FrictionJacobian, Prony};

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
