//! The rows of a creep fit ([`super::creep_prony`], whose module doc
//! states the method): ln D(t_i) of the exact creep compliance of the
//! Prony series θ = (ln E0, ln H_k) on a τ grid, minus the data's ln D_i,
//! with the analytic Jacobian by the implicit function theorem on the
//! retardation times' equation F(λ_j; θ) = E0 − Σ_k H_k τ_k/(λ_j − τ_k) = 0:
//!
//!   ∂λ_j/∂θ_p = −(∂F/∂θ_p)/F′(λ_j),   c_j = 1/(λ_j F′(λ_j)),
//!   ∂c_j/∂θ_p = −c_j² [∂G/∂θ_p + (F′ + λ_j F″) ∂λ_j/∂θ_p],  G = λ F′(λ),
//!   ∂D(t)/∂θ_p = ∂(1/E1)/∂θ_p + Σ_j (1 − e^(−t/λ_j)) ∂c_j/∂θ_p
//!                − c_j (t/λ_j²) e^(−t/λ_j) ∂λ_j/∂θ_p.
//!
//! # References
//! - N.W. Tschoegl, *The Phenomenological Theory of Linear Viscoelastic
//!   Behavior*, Springer 1989, ch. 4.

use nalgebra::{DMatrix, DVector};
use rollfit_model::Prony;
use rollfit_model::exact::{CreepCompliance, NEGLIGIBLE_SHARE};

/// The rows of ln D(t) at θ = (ln E0, ln H_k) with their analytic
/// Jacobian (module doc); `e0` as the series takes it (floored by the
/// caller). A θ whose series is not a solid (E0 not representable) gives
/// NaN residuals, which the minimiser refuses.
pub(super) fn creep_rows(
    (time, ln_compliance): (&[f64], &[f64]),
    tau: &[f64],
    (e0, h): (f64, &[f64]),
    residuals: &mut DVector<f64>,
    jacobian: &mut DMatrix<f64>,
) {
    let e1 = e0 + h.iter().sum::<f64>();
    let Ok(prony) = Prony::new(e1, h.to_vec(), tau.to_vec()) else {
        residuals.rows_mut(0, time.len()).fill(f64::NAN);
        return;
    };
    let creep = CreepCompliance::from_prony(&prony);
    let parameters = tau.len() + 1;
    // ∂(1/E1)/∂θ: E1 = E0 + Σ H_k.
    let j0 = 1.0 / e1;
    let mut d_instantaneous = vec![-j0 * j0 * e0; parameters];
    for (k, &hk) in h.iter().enumerate() {
        d_instantaneous[k + 1] = -j0 * j0 * hk;
    }
    let kept: Vec<bool> = h.iter().map(|&hk| hk > NEGLIGIBLE_SHARE * e1).collect();
    let retardations = creep.retardation_times.len();
    let mut d_lambda = DMatrix::zeros(retardations, parameters);
    let mut d_strength = DMatrix::zeros(retardations, parameters);
    for (j, (&lambda, &c)) in creep
        .retardation_times
        .iter()
        .zip(&creep.strengths)
        .enumerate()
    {
        let (mut f1, mut f2) = (0.0, 0.0);
        for k in (0..tau.len()).filter(|&k| kept[k]) {
            let d = lambda - tau[k];
            f1 += h[k] * tau[k] / (d * d);
            f2 -= 2.0 * h[k] * tau[k] / (d * d * d);
        }
        let dg_dlambda = f1 + lambda * f2;
        // ∂F/∂θ_p and ∂G/∂θ_p (G's explicit dependence).
        let mut row_lambda = vec![0.0; parameters];
        let mut row_strength = vec![0.0; parameters];
        for p in 0..parameters {
            let (df, dg) = match p {
                0 => (e0, 0.0),
                _ if kept[p - 1] => {
                    let k = p - 1;
                    let d = lambda - tau[k];
                    (-h[k] * tau[k] / d, lambda * h[k] * tau[k] / (d * d))
                }
                // A dropped term enters F through E1 alone.
                _ => (h[p - 1], 0.0),
            };
            let dl = -df / f1;
            row_lambda[p] = dl;
            row_strength[p] = -c * c * (dg + dg_dlambda * dl);
        }
        // A retardation time within rounding of a relaxation time gives
        // non-finite derivatives; its term then moves with nothing.
        if row_lambda
            .iter()
            .chain(&row_strength)
            .all(|v| v.is_finite())
        {
            for p in 0..parameters {
                d_lambda[(j, p)] = row_lambda[p];
                d_strength[(j, p)] = row_strength[p];
            }
        }
    }
    let n = time.len();
    let mut rise = DMatrix::zeros(n, retardations);
    let mut slope = DMatrix::zeros(n, retardations);
    for (i, &t) in time.iter().enumerate() {
        for (j, (&lambda, &c)) in creep
            .retardation_times
            .iter()
            .zip(&creep.strengths)
            .enumerate()
        {
            let decay = (-t / lambda).exp();
            rise[(i, j)] = -(-t / lambda).exp_m1();
            slope[(i, j)] = -c * t / (lambda * lambda) * decay;
        }
    }
    let derivatives = rise * d_strength + slope * d_lambda;
    for (i, &t) in time.iter().enumerate() {
        let compliance = creep.at(t);
        for p in 0..parameters {
            jacobian[(i, p)] = (derivatives[(i, p)] + d_instantaneous[p]) / compliance;
        }
        residuals[i] = compliance.ln() - ln_compliance[i];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The analytic Jacobian against central differences of the rows, on a
    /// series with a term far below its neighbours (a retardation time
    /// close to its relaxation time).
    #[test]
    fn jacobian_matches_differences() {
        let tau = [1e-3, 1e-2, 1e-1, 1.0, 10.0];
        let theta = [
            1e6f64.ln(),
            3e7f64.ln(),
            1e8f64.ln(),
            1e2f64.ln(),
            5e7f64.ln(),
            2e6f64.ln(),
        ];
        let time: Vec<f64> = (0..25)
            .map(|i| 10f64.powf(-4.0 + 0.25 * i as f64))
            .collect();
        let ln_data = vec![0.0; time.len()];
        let rows = |theta: &[f64]| {
            let h: Vec<f64> = theta[1..].iter().map(|t| t.exp()).collect();
            let mut r = DVector::zeros(time.len());
            let mut jac = DMatrix::zeros(time.len(), theta.len());
            creep_rows(
                (&time, &ln_data),
                &tau,
                (theta[0].exp(), &h),
                &mut r,
                &mut jac,
            );
            (r, jac)
        };
        let (_, analytic) = rows(&theta);
        for p in 0..theta.len() {
            let step = 1e-6;
            let (mut up, mut down) = (theta, theta);
            up[p] += step;
            down[p] -= step;
            let numeric = (rows(&up).0 - rows(&down).0) / (2.0 * step);
            for i in 0..time.len() {
                let (a, b) = (analytic[(i, p)], numeric[i]);
                assert!(
                    (a - b).abs() < 1e-6 + 1e-5 * b.abs(),
                    "θ_{p}, t = {}: analytic {a}, differences {b}",
                    time[i]
                );
            }
        }
    }
}
