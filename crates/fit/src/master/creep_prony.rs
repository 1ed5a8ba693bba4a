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
//! ∂D/∂λ_j = −c_j (t/λ_j²) e^(−t/λ_j) ([`super::creep_rows`]).
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

use super::prony_fit::{Data, Problem, regularised, series_of, tau_grid};
use super::relaxation_prony::{RelaxationFit, start, time_span};
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
    let (t_lo, t_hi) = time_span(time, compliance, "D(t)")?;
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
    let whole = std::iter::once(0..time.len()).collect::<Vec<_>>();
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

#[cfg(test)]
mod tests {
    use super::*;
    use rollfit_model::Prony;
    use rollfit_model::exact::CreepCompliance;

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
