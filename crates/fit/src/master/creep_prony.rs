//! A Prony series fitted to a creep master curve D(t) through its exact
//! creep compliance: the series is the relaxation modulus
//! E(t) = E0 + Σ_k H_k e^(−t/τ_k) of [`super::relaxation_prony`] (the same
//! non-negative, smooth object, so material.toml carries it unchanged), and
//! the data it is fitted to are its creep compliance.
//!
//! The creep compliance of the series is exact
//! (`rollfit_model::exact::CreepCompliance::from_prony`): with
//! Ẽ(s) = E1 − Σ_k H_k/(1 + sτ_k) the s-multiplied Laplace transform of
//! E(t), sJ̄(s) = 1/Ẽ(s) (Tschoegl 1989, ch. 4; Ferry 1980, ch. 3) gives
//!
//!   D(t) = 1/E1 + Σ_j c_j (1 − e^(−t/λ_j)),
//!
//! the retardation times λ_j the zeros of
//! F(λ) = Ẽ(−1/λ) = E0 − Σ_k H_k τ_k/(λ − τ_k), one between each pair of
//! neighbouring τ_k and one above the largest, and c_j = 1/(λ_j F′(λ_j)),
//! F′(λ) = Σ_k H_k τ_k/(λ − τ_k)². No approximation D ≈ 1/E(t) enters:
//! that one is off by up to the ratio of the compliances across a
//! transition (Park & Schapery 1999).
//!
//! For N points (t_i, D_i) at reduced times the objective is the
//! relaxation fit's with ln D in place of ln E,
//!
//!   V(θ) = Σ_i [ln D(t_i; θ) − ln D_i]² + λ Σ_k (Δ² ln H_k)²,
//!
//! θ = (ln E0, ln H_k), minimised by the same Levenberg–Marquardt with λ
//! by the marginal likelihood ([`super::prony_fit`]). The Jacobian is
//! analytic, by the implicit function theorem on F(λ_j; θ) = 0:
//!
//!   ∂λ_j/∂θ_p = −(∂F/∂θ_p)/F′(λ_j),
//!   ∂F/∂ln E0 = E0,  ∂F/∂ln H_k = −H_k τ_k/(λ_j − τ_k),
//!   ∂c_j/∂θ_p = −c_j² [∂G/∂θ_p + (F′ + λ_j F″) ∂λ_j/∂θ_p],
//!   G = λ F′(λ),  ∂G/∂ln H_k = λ H_k τ_k/(λ − τ_k)²,  F″ = −2 Σ H_k τ_k/(λ − τ_k)³,
//!   ∂(1/E1)/∂θ_p = −(∂E1/∂θ_p)/E1²,
//!
//! and ∂D(t)/∂θ_p sums them with ∂D/∂c_j = 1 − e^(−t/λ_j) and
//! ∂D/∂λ_j = −c_j (t/λ_j²) e^(−t/λ_j).
//!
//! The τ grid: the relaxation times of a series lie below its retardation
//! times, by up to the ratio of its compliances (one term: λ = τ E1/E0),
//! so the grid of the relaxation fit for 1/t over the data is widened
//! downwards by the ratio r = D_max/D_min of the data: τ from
//! t_min/(10 r) to 10 t_max.
//!
//! Start: the relaxation fit's start (Alfrey's approximation) read from
//! 1/D(t), which is the first approximation E(t) ≈ 1/D(t) — only where the
//! iteration begins.
//!
//! # References
//! - N.W. Tschoegl, *The Phenomenological Theory of Linear Viscoelastic
//!   Behavior*, Springer 1989, ch. 3–4 (retardation from relaxation
//!   spectra of discrete series).
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 3.
//! - S.W. Park, R.A. Schapery, "Methods of interconversion between linear
//!   viscoelastic material functions. Part I", Int. J. Solids Struct. 36
//!   (1999) 1653–1675.

use nalgebra::{DMatrix, DVector};
use rollfit_model::Prony;
use rollfit_model::exact::{CreepCompliance, NEGLIGIBLE_SHARE};

use super::prony_fit::{Data, Problem, STATIC_FLOOR, regularised, series_of, tau_grid};
use super::relaxation_prony::{RelaxationFit, start};
use crate::error::FitError;
use crate::regularization::LambdaRule;

/// How the creep series is fitted, for summaries and master.json.
pub const CREEP_METHOD: &str = "the exact creep compliance of the Prony series E(t) \
    (retardation times from the zeros of its Laplace transform) fitted to D(t) in log D by \
    Levenberg–Marquardt, smoothness λ by the marginal likelihood; start E(t) ≈ 1/D(t)";

/// Fits a smooth non-negative Prony series E(t) whose creep compliance
/// follows D(t) (1/Pa, > 0) at reduced times `time` (s, > 0); see the
/// module doc. The misfit is RMS log10 D, decades.
pub fn fit_creep_prony(time: &[f64], compliance: &[f64]) -> Result<RelaxationFit, FitError> {
    let n = time.len();
    if n < 3 || compliance.len() != n {
        return Err(FitError::InsufficientData(format!(
            "a Prony series needs at least three points of D(t) (got {n})"
        )));
    }
    let t_lo = time.iter().fold(f64::INFINITY, |m, &t| m.min(t));
    let t_hi = time.iter().fold(0.0f64, |m, &t| m.max(t));
    let d_lo = compliance.iter().fold(f64::INFINITY, |m, &d| m.min(d));
    let d_hi = compliance.iter().fold(0.0f64, |m, &d| m.max(d));
    let ratio = (d_hi / d_lo).max(1.0);
    let tau = tau_grid(1.0 / t_hi, ratio / t_lo);
    let modulus: Vec<f64> = compliance.iter().map(|d| 1.0 / d).collect();
    let mut problem = Problem {
        data: Data::Creep {
            time,
            ln_compliance: compliance.iter().map(|d| d.ln()).collect(),
        },
        tau: &tau,
        lambda: 0.0,
    };
    let from = start(time, &modulus, &tau);
    let (theta, lambda, converged) = regularised(&mut problem, from);
    let whole = std::iter::once(0..n).collect::<Vec<_>>();
    let (prony, misfit) = series_of(&problem, &theta, &whole)?;
    Ok(RelaxationFit {
        prony,
        lambda,
        rule: LambdaRule::MarginalLikelihood,
        misfit: misfit[0],
        converged,
        method: CREEP_METHOD,
    })
}

/// The rows of ln D(t) at θ = (ln E0, ln H_k) with their analytic
/// Jacobian (module doc). A θ whose series is not a solid (E0 not
/// representable) gives NaN residuals, which the minimiser refuses.
pub(super) fn creep_rows(
    (time, ln_compliance): (&[f64], &[f64]),
    tau: &[f64],
    (e0, h): (f64, &[f64]),
    residuals: &mut DVector<f64>,
    jacobian: &mut DMatrix<f64>,
) {
    let sum: f64 = h.iter().sum();
    let e0 = e0.max(STATIC_FLOOR * sum);
    let e1 = e0 + sum;
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

    /// The creep compliance of a two-term series over seven decades, no
    /// noise: the fitted series' own creep compliance follows it to a
    /// fraction of a per cent.
    #[test]
    fn follows_a_noiseless_creep_compliance() {
        let truth = Prony::new(1e9, vec![6e8, 3.9e8], vec![1e-2, 1.0]).unwrap();
        let creep = CreepCompliance::from_prony(&truth);
        let time: Vec<f64> = (0..=70)
            .map(|i| 10f64.powf(-3.0 + 0.1 * i as f64))
            .collect();
        let compliance: Vec<f64> = time.iter().map(|&t| creep.at(t)).collect();
        let fit = fit_creep_prony(&time, &compliance).unwrap();
        let fitted = CreepCompliance::from_prony(&fit.prony);
        let worst = time
            .iter()
            .zip(&compliance)
            .map(|(&t, &d)| (fitted.at(t) / d - 1.0).abs())
            .fold(0.0, f64::max);
        assert!(worst < 5e-3, "largest relative error {worst}");
    }
}
