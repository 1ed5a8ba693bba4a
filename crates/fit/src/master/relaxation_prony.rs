//! A Prony series fitted to a relaxation master curve E(t): non-negative,
//! smooth, with the smoothness chosen from the data — the time-domain twin
//! of [`super::prony_fit`], sharing its grid, penalty, λ rule and solver.
//!
//! The relaxation modulus of the series of Eq. (B2),
//! E*(ω) = E0 + Σ_k H_k iωτ_k/(1 + iωτ_k), is (Tschoegl 1989, ch. 3;
//! Ferry 1980, ch. 3)
//!
//!   E(t) = E0 + Σ_k H_k e^(−t/τ_k),   H_k ≥ 0, E0 ≥ 0,
//!
//! so one set (E0, H_k, τ_k) describes both the stress relaxation and the
//! dynamic moduli exactly: the series fitted here is the material
//! `rollfit forward` uses, without any approximate interconversion (Park &
//! Schapery 1999 fit the series in one domain and evaluate it in the other
//! for the same reason).
//!
//! For N points (t_i, E_i) at reduced times the objective is
//!
//!   V(θ) = Σ_i [ln E(t_i) − ln E_i]² + λ Σ_k (Δ² ln H_k)²,
//!
//! θ = (ln E0, ln H_k), relative errors as a DMA's scatter is, with the
//! Jacobian ∂ln E/∂ln H_k = H_k e^(−t/τ_k)/E, ∂ln E/∂ln E0 = E0/E. The τ
//! grid is the frequency fit's for ω = 1/t (τ from t_min/10 to 10 t_max,
//! [`super::TAU_PER_DECADE`] per decade); λ is chosen by the marginal
//! likelihood over the same path ([`super::prony_fit`]).
//!
//! Why the penalty matters more here than for E′, E″: the kernel e^(−t/τ)
//! is smoother than the storage kernel, so neighbouring H_k are even less
//! distinguishable from E(t) alone (the inversion of a Laplace transform;
//! Tschoegl ch. 4). The smoothed spectrum is what the data determine.
//!
//! Start: Alfrey's first approximation of the spectrum,
//! H(τ) ≈ −dE(t)/d ln t at t = τ (Ferry ch. 4), times the grid's spacing in
//! ln τ, read from the data binned in third decades, falling a decade per
//! decade beyond the data; E0 half the smallest E.
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 3 (relaxation modulus of a discrete spectrum), ch. 4
//!   (approximate spectra).
//! - N.W. Tschoegl, *The Phenomenological Theory of Linear Viscoelastic
//!   Behavior*, Springer 1989, ch. 3–4.
//! - S.W. Park, R.A. Schapery, "Methods of interconversion between linear
//!   viscoelastic material functions. Part I", Int. J. Solids Struct. 36
//!   (1999) 1653–1675.

use rollfit_model::Prony;

use super::prony_fit::{Data, Problem, regularised, series_of, tau_grid};
use crate::error::FitError;
use crate::regularization::LambdaRule;

/// The series fitted to E(t) and how it was chosen.
#[derive(Debug, Clone)]
pub struct RelaxationFit {
    /// The series (E1 = E0 + Σ H_k).
    pub prony: Prony,
    /// The smoothness weight λ chosen.
    pub lambda: f64,
    /// How λ was chosen.
    pub rule: LambdaRule,
    /// RMS log10 misfit of the quantity fitted (E(t), or D(t) of a creep
    /// run), decades.
    pub misfit: f64,
    /// Whether the final Levenberg–Marquardt run converged.
    pub converged: bool,
    /// How the series was fitted, in words (summaries, master.json).
    pub method: &'static str,
}

/// How the relaxation series is fitted, for summaries and master.json.
pub const RELAXATION_METHOD: &str = "the Prony series E(t) fitted to E(t) in log E by \
    Levenberg–Marquardt, smoothness λ by the marginal likelihood";

/// The shortest and longest of `time` (s), once there are at least three
/// points with a `values` (of `quantity`) each.
pub(super) fn time_span(
    time: &[f64],
    values: &[f64],
    quantity: &str,
) -> Result<(f64, f64), FitError> {
    let n = time.len();
    if n < 3 || values.len() != n {
        return Err(FitError::InsufficientData(format!(
            "a Prony series needs at least three points of {quantity} (got {n})"
        )));
    }
    let t_lo = time.iter().fold(f64::INFINITY, |m, &t| m.min(t));
    let t_hi = time.iter().fold(0.0f64, |m, &t| m.max(t));
    Ok((t_lo, t_hi))
}

/// Fits a smooth non-negative Prony series to E(t) (Pa, > 0) at reduced
/// times `time` (s, > 0); see the module doc.
pub fn fit_relaxation_prony(time: &[f64], modulus: &[f64]) -> Result<RelaxationFit, FitError> {
    let (t_lo, t_hi) = time_span(time, modulus, "E(t)")?;
    let tau = tau_grid(1.0 / t_hi, 1.0 / t_lo);
    let mut problem = Problem {
        data: Data::Time {
            time,
            ln_modulus: modulus.iter().map(|e| e.ln()).collect(),
        },
        tau: &tau,
        lambda: 0.0,
    };
    let from = start(time, modulus, &tau);
    let (theta, lambda, converged) = regularised(&mut problem, from);
    let whole = std::iter::once(0..time.len()).collect::<Vec<_>>();
    let (prony, misfit) = series_of(&problem, &theta, &whole)?;
    Ok(RelaxationFit {
        prony,
        lambda,
        rule: LambdaRule::MarginalLikelihood,
        misfit: misfit[0],
        converged,
        method: RELAXATION_METHOD,
    })
}

/// Alfrey's first-approximation start (module doc); also the creep fit's,
/// from 1/D(t).
pub(super) fn start(time: &[f64], modulus: &[f64], tau: &[f64]) -> Vec<f64> {
    // Third-decade bins of E against log t.
    let mut bins: std::collections::BTreeMap<i64, (f64, usize)> = Default::default();
    for (t, e) in time.iter().zip(modulus) {
        let entry = bins.entry((t.log10() * 3.0).floor() as i64).or_default();
        entry.0 += e;
        entry.1 += 1;
    }
    let binned: Vec<(f64, f64)> = bins
        .iter()
        .map(|(&b, &(sum, count))| ((b as f64 + 0.5) / 3.0, sum / count as f64))
        .collect();
    let largest = modulus.iter().fold(0.0f64, |m, &e| m.max(e));
    // A flat or noisy stretch gives no slope: a floor well below the data
    // keeps ln H finite, and the penalty fills it in from its neighbours.
    let floor = 1e-6 * largest;
    // −dE/d ln t between neighbouring bins, at their midpoints (log10 t).
    let slopes: Vec<(f64, f64)> = binned
        .windows(2)
        .map(|w| {
            let slope = -(w[1].1 - w[0].1) / ((w[1].0 - w[0].0) * std::f64::consts::LN_10);
            (0.5 * (w[0].0 + w[1].0), slope.max(floor))
        })
        .collect();
    let spacing = if tau.len() > 1 {
        (tau[1] / tau[0]).ln()
    } else {
        1.0
    };
    let spectrum_at = |x: f64| -> f64 {
        let Some((&first, &last)) = slopes.first().zip(slopes.last()) else {
            return 0.1 * largest;
        };
        if x <= first.0 {
            return first.1 * 10f64.powf(-(first.0 - x));
        }
        if x >= last.0 {
            return last.1 * 10f64.powf(-(x - last.0));
        }
        let k = slopes.partition_point(|p| p.0 <= x);
        let (a, b) = (slopes[k - 1], slopes[k]);
        a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0)
    };
    let e0 = 0.5 * modulus.iter().fold(f64::INFINITY, |m, &e| m.min(e));
    std::iter::once(e0.ln())
        .chain(
            tau.iter()
                .map(|t| (spectrum_at(t.log10()) * spacing).max(floor).ln()),
        )
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A two-term series sampled without noise over five decades: the
    /// smooth fit follows E(t) to a fraction of a per cent.
    #[test]
    fn follows_a_noiseless_relaxation() {
        let truth = Prony::new(1e7, vec![4e6, 4e6], vec![1e-2, 1.0]).unwrap();
        let time: Vec<f64> = (0..=50)
            .map(|i| 10f64.powf(-3.0 + 0.1 * i as f64))
            .collect();
        let modulus: Vec<f64> = time.iter().map(|&t| truth.relaxation_modulus(t)).collect();
        let fit = fit_relaxation_prony(&time, &modulus).unwrap();
        let worst = time
            .iter()
            .zip(&modulus)
            .map(|(&t, &e)| (fit.prony.relaxation_modulus(t) / e - 1.0).abs())
            .fold(0.0, f64::max);
        assert!(worst < 5e-3, "largest relative error {worst}");
    }
}
