//! A causal Prony series fitted to a shifted DMA master curve: E′ and E″
//! together, non-negative, smooth, with the smoothness chosen from the data.
//!
//! The model is the one `rollfit fit` recovers from μ(v) (Eq. B2),
//!
//!   E*(ω) = E0 + Σ_k H_k iωτ_k/(1 + iωτ_k),
//!
//! on a fixed grid of [`TAU_PER_DECADE`] log-spaced τ_k per decade covering
//! 1/ω over the data's range widened by a decade on each side (the grid of
//! the causality check in `rollfit-report`, so that as λ → 0 this fit
//! tends to that check's best causal fit and its misfit to the check's
//! floor). Non-negativity (E0, H_k ≥ 0, which makes the series causal and
//! passive) is kept, as in the rolling fit, by fitting θ = (ln E0, ln H_k).
//!
//! The objective, for N points with measured E′_i, E″_i at reduced ω_i,
//!
//!   V(θ) = Σ_i [ln E′(ω_i) − ln E′_i]² + [ln E″(ω_i) − ln E″_i]²
//!          + λ Σ_k (Δ² ln H_k)²,
//!
//! weighs E′ and E″ by their relative errors, as a DMA's scatter is (a per
//! cent of the modulus, whatever its size), and penalises the second
//! differences of the log-spectrum exactly as the rolling fit does
//! (`crate::problem`). It is minimised by Levenberg–Marquardt (on the
//! normal equations, see `minimize` for why) with the analytic Jacobian
//!
//!   ∂ln E′/∂ln H_k = H_k ω²τ_k²/(1 + ω²τ_k²)/E′,  ∂ln E″/∂ln H_k = H_k ωτ_k/(1 + ω²τ_k²)/E″,
//!   ∂ln E′/∂ln E0 = E0/E′.
//!
//! λ: the marginal likelihood with the noise level profiled out (GML,
//! [`crate::regularization`]), the rule of a rolling fit without measured
//! σ, over a warm-started path of decreasing λ and refined by golden
//! section in ln λ. The DMA's noise level is not known either, and its
//! points are many (hundreds), where GML picks the λ whose residuals look
//! like noise.
//!
//! Start: Ferry's first approximation of the relaxation spectrum,
//! H(τ) ≈ (2/π) E″(1/τ), times the grid's spacing in ln τ, read from the
//! data's E″ (averaged in third-decade bins, held constant beyond the data
//! and falling a decade per decade there), and E0 half the smallest E′.
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 4 (approximate spectra from E″).
//! - N.W. Tschoegl, *The Phenomenological Theory of Linear Viscoelastic
//!   Behavior*, Springer 1989, ch. 3–4 (Prony series).
//! - G. Wahba, Ann. Statist. 13 (1985) 1378–1402 (GML).
//! - J.J. Moré, Lecture Notes in Mathematics 630 (1978) 105–116 (LM).

use nalgebra::{DMatrix, DVector};
use rollfit_model::{Prony, ViscoelasticModulus};

use super::condense::condense;
use crate::analysis::pseudo_inverse;
use crate::error::FitError;
use crate::regularization::{LambdaRule, Trial};

/// Relaxation times per decade (the causality check's grid).
pub const TAU_PER_DECADE: f64 = 3.0;

/// λ of the path: 10^2 down to 10^−10, one per decade (the penalty's
/// scale is set by relative errors of a per cent or so: λ ≈ 1e-4 balances
/// one second difference of 1 against 100 points at 1 %).
const LAMBDA_PATH: std::ops::RangeInclusive<i32> = -10..=2;

/// E0 ≥ this times Σ H_k (see `fit_prony`).
pub const STATIC_FLOOR: f64 = 1e-9;

/// Golden-section steps of the λ refinement in ln λ.
const REFINEMENTS: usize = 5;

/// The relaxation-time grid for data over [ω_lo, ω_hi] (rad/s): τ from
/// 1/(10 ω_hi) to 10/ω_lo, [`TAU_PER_DECADE`] per decade, ends included.
pub fn tau_grid(omega_lo: f64, omega_hi: f64) -> Vec<f64> {
    let (lo, hi) = ((0.1 / omega_hi).log10(), (10.0 / omega_lo).log10());
    let intervals = ((hi - lo) * TAU_PER_DECADE).ceil().max(1.0) as usize;
    (0..=intervals)
        .map(|k| 10f64.powf(lo + (hi - lo) * k as f64 / intervals as f64))
        .collect()
}

/// The fitted series and how it was chosen.
#[derive(Debug, Clone)]
pub struct PronyFit {
    /// The series (E1 = E0 + Σ H_k).
    pub prony: Prony,
    /// The smoothness weight λ chosen.
    pub lambda: f64,
    /// How λ was chosen.
    pub rule: LambdaRule,
    /// RMS log10 misfit of E′ (decades).
    pub misfit_storage: f64,
    /// RMS log10 misfit of E″ (decades).
    pub misfit_loss: f64,
    /// Whether the final Levenberg–Marquardt run converged.
    pub converged: bool,
    /// Effective number of parameters the data fix at the chosen λ (the
    /// trace of the influence matrix): a joint fit's compatibility test
    /// counts the DMA part's parameters with it.
    pub effective_parameters: f64,
}

/// What the series is fitted to.
#[derive(Clone)]
pub(super) enum Data<'a> {
    /// ln E′ and ln E″ at reduced ω (rad/s): the module doc.
    Frequency {
        omega: &'a [f64],
        ln_storage: Vec<f64>,
        ln_loss: Vec<f64>,
        /// √n_b of condensed bins ([`super::condense`]), the weight of
        /// each point's rows; None for points as measured.
        root_count: Option<Vec<f64>>,
    },
    /// ln E(t) at reduced t (s): [`super::relaxation_prony`].
    Time {
        time: &'a [f64],
        ln_modulus: Vec<f64>,
    },
    /// ln D(t), the tensile creep compliance, at reduced t (s), fitted
    /// through the series' exact creep compliance
    /// ([`super::creep_rows`]).
    Creep {
        time: &'a [f64],
        ln_compliance: Vec<f64>,
    },
}

/// The least-squares problem at one λ.
#[derive(Clone)]
pub(super) struct Problem<'a> {
    pub data: Data<'a>,
    pub tau: &'a [f64],
    pub lambda: f64,
}

/// Residuals and Jacobian at θ.
struct Evaluation {
    residuals: DVector<f64>,
    jacobian: DMatrix<f64>,
}

impl Problem<'_> {
    /// Residual rows of the data (before the penalty's).
    pub(super) fn data_count(&self) -> usize {
        match &self.data {
            Data::Frequency { omega, .. } => 2 * omega.len(),
            Data::Time { time, .. } | Data::Creep { time, .. } => time.len(),
        }
    }

    fn evaluate(&self, theta: &[f64]) -> Evaluation {
        let count = self.data_count();
        let terms = self.tau.len();
        let rows = count + terms.saturating_sub(2);
        let mut residuals = DVector::zeros(rows);
        let mut jacobian = DMatrix::zeros(rows, terms + 1);
        let e0 = theta[0].exp();
        let h: Vec<f64> = theta[1..].iter().map(|t| t.exp()).collect();
        match &self.data {
            Data::Frequency {
                omega,
                ln_storage,
                ln_loss,
                root_count,
            } => frequency_rows(
                (omega, ln_storage, ln_loss, root_count.as_deref()),
                self.tau,
                (e0, &h),
                &mut residuals,
                &mut jacobian,
            ),
            Data::Time { time, ln_modulus } => time_rows(
                (time, ln_modulus),
                self.tau,
                (e0, &h),
                &mut residuals,
                &mut jacobian,
            ),
            Data::Creep {
                time,
                ln_compliance,
            } => super::creep_rows::creep_rows(
                (time, ln_compliance),
                self.tau,
                // The floor `series_of` gives E0: the series must be a solid.
                (e0.max(STATIC_FLOOR * h.iter().sum::<f64>()), &h),
                &mut residuals,
                &mut jacobian,
            ),
        }
        let root = self.lambda.sqrt();
        for k in 0..terms.saturating_sub(2) {
            let row = count + k;
            residuals[row] = root * (theta[k + 1] - 2.0 * theta[k + 2] + theta[k + 3]);
            jacobian[(row, k + 1)] = root;
            jacobian[(row, k + 2)] = -2.0 * root;
            jacobian[(row, k + 3)] = root;
        }
        Evaluation {
            residuals,
            jacobian,
        }
    }

    /// The λ-path record of the optimum θ: misfit, penalised objective,
    /// influence trace and ln det(J_dᵀJ_d + λLᵀL).
    fn trial(&self, theta: Vec<f64>) -> Trial {
        let e = self.evaluate(&theta);
        let n = self.data_count();
        let misfit = e.residuals.rows(0, n).norm_squared();
        let penalised = e.residuals.norm_squared();
        let h = e.jacobian.transpose() * &e.jacobian;
        let jd = e.jacobian.rows(0, n);
        let hd = jd.transpose() * jd;
        let (h_inv, log_det) = pseudo_inverse(&h);
        Trial {
            lambda: self.lambda,
            theta,
            misfit,
            effective_parameters: (h_inv * hd).trace(),
            penalised,
            log_det,
            penalty_rank: self.tau.len().saturating_sub(2),
            free: self.tau.len() + 1,
            // Not asked: λ of a DMA fit is chosen by a criterion, not by
            // the discrepancy principle.
            random_signs: true,
        }
    }
}

/// Reduced ω, ln E′, ln E″ and the rows' weights √n_b (None: 1).
type FrequencyData<'a> = (&'a [f64], &'a [f64], &'a [f64], Option<&'a [f64]>);

/// The rows of ln E′ (0..n) and ln E″ (n..2n) at θ = (ln E0, ln H_k).
fn frequency_rows(
    (omega, ln_storage, ln_loss, root_count): FrequencyData<'_>,
    tau: &[f64],
    (e0, h): (f64, &[f64]),
    residuals: &mut DVector<f64>,
    jacobian: &mut DMatrix<f64>,
) {
    let n = omega.len();
    let terms = tau.len();
    for i in 0..n {
        let omega = omega[i];
        let (mut storage, mut loss) = (e0, 0.0);
        for (k, (&tau, &hk)) in tau.iter().zip(h).enumerate() {
            let x = omega * tau;
            let d = 1.0 / (1.0 + x * x);
            let (s, l) = (hk * x * x * d, hk * x * d);
            storage += s;
            loss += l;
            jacobian[(i, k + 1)] = s;
            jacobian[(n + i, k + 1)] = l;
        }
        // E″ of a series is positive at every ω > 0 (every H_k > 0).
        let loss = loss.max(f64::MIN_POSITIVE);
        jacobian[(i, 0)] = e0;
        for k in 0..=terms {
            jacobian[(i, k)] /= storage;
            jacobian[(n + i, k)] /= loss;
        }
        residuals[i] = storage.ln() - ln_storage[i];
        residuals[n + i] = loss.ln() - ln_loss[i];
        if let Some(root_count) = root_count {
            for row in [i, n + i] {
                residuals[row] *= root_count[i];
                jacobian.row_mut(row).scale_mut(root_count[i]);
            }
        }
    }
}

/// The rows of ln E(t) at θ: E(t) = E0 + Σ H_k e^(−t/τ_k), so
/// ∂ln E/∂ln H_k = H_k e^(−t/τ_k)/E and ∂ln E/∂ln E0 = E0/E.
fn time_rows(
    (time, ln_modulus): (&[f64], &[f64]),
    tau: &[f64],
    (e0, h): (f64, &[f64]),
    residuals: &mut DVector<f64>,
    jacobian: &mut DMatrix<f64>,
) {
    for (i, &t) in time.iter().enumerate() {
        let mut modulus = e0;
        jacobian[(i, 0)] = e0;
        for (k, (&tau, &hk)) in tau.iter().zip(h).enumerate() {
            let term = hk * (-t / tau).exp();
            modulus += term;
            jacobian[(i, k + 1)] = term;
        }
        for k in 0..=tau.len() {
            jacobian[(i, k)] /= modulus;
        }
        residuals[i] = modulus.ln() - ln_modulus[i];
    }
}

/// Levenberg–Marquardt steps before a run gives up.
const MAX_ITERATIONS: usize = 300;

/// Minimises V at the problem's λ from `start` by Levenberg–Marquardt on
/// the normal equations: (JᵀJ + μ D) δ = −Jᵀr with Marquardt's scaling
/// D = diag(JᵀJ), μ lowered after an accepted step and raised after a
/// rejected one. Returns (θ, converged): converged when a step lowers V by
/// less than `tolerance` relatively, or none can lower it.
///
/// Why not the `levenberg-marquardt` crate, as the rolling fit does: its
/// pivoted QR of the whole 2N × (n + 1) Jacobian took three quarters of the
/// run here (3 ms a step for 340 points; N is hundreds, n ≈ 50), where the
/// n × n normal equations cost a tenth of that. Their squared condition is
/// harmless here: the penalty and the damping μ D keep the system positive
/// definite, and Cholesky refusing a step only raises μ.
fn minimize(problem: &Problem<'_>, start: &[f64], tolerance: f64) -> (Vec<f64>, bool) {
    let mut theta = DVector::from_column_slice(start);
    let mut current = problem.evaluate(start);
    let mut value = current.residuals.norm_squared();
    if !value.is_finite() {
        return (start.to_vec(), false);
    }
    let mut damping = 1e-3;
    for _ in 0..MAX_ITERATIONS {
        let jt = current.jacobian.transpose();
        let normal = &jt * &current.jacobian;
        let gradient = &jt * &current.residuals;
        let largest = normal.diagonal().max();
        let scale: DVector<f64> = normal.diagonal().map(|d| d.max(1e-12 * largest));
        let mut accepted = None;
        for _ in 0..30 {
            let mut system = normal.clone();
            for k in 0..system.nrows() {
                system[(k, k)] += damping * scale[k];
            }
            let Some(cholesky) = system.cholesky() else {
                damping *= 10.0;
                continue;
            };
            let step = -cholesky.solve(&gradient);
            let trial = &theta + &step;
            let evaluation = problem.evaluate(trial.as_slice());
            let trial_value = evaluation.residuals.norm_squared();
            if trial_value.is_finite() && trial_value < value {
                damping = (damping * 0.3).max(1e-12);
                accepted = Some((trial, evaluation, trial_value));
                break;
            }
            damping *= 10.0;
            if damping > 1e16 {
                break;
            }
        }
        let Some((trial, evaluation, trial_value)) = accepted else {
            // No step lowers V: a minimum to machine precision.
            return (theta.as_slice().to_vec(), true);
        };
        let reduction = (value - trial_value) / value;
        theta = trial;
        current = evaluation;
        value = trial_value;
        if reduction < tolerance {
            return (theta.as_slice().to_vec(), true);
        }
    }
    (theta.as_slice().to_vec(), false)
}

/// Ferry's first-approximation start (module doc).
fn start(omega: &[f64], storage: &[f64], loss: &[f64], tau: &[f64]) -> Vec<f64> {
    // Third-decade bins of log E″ against log ω.
    let mut bins: std::collections::BTreeMap<i64, (f64, usize)> = Default::default();
    for (w, l) in omega.iter().zip(loss) {
        let entry = bins.entry((w.log10() * 3.0).floor() as i64).or_default();
        entry.0 += l.log10();
        entry.1 += 1;
    }
    let binned: Vec<(f64, f64)> = bins
        .iter()
        .map(|(&b, &(sum, count))| ((b as f64 + 0.5) / 3.0, sum / count as f64))
        .collect();
    let log_loss_at = |x: f64| -> f64 {
        let (first, last) = (binned[0], binned[binned.len() - 1]);
        if x <= first.0 {
            return first.1 - (first.0 - x);
        }
        if x >= last.0 {
            return last.1 - (x - last.0);
        }
        let k = binned.partition_point(|p| p.0 <= x);
        let (a, b) = (binned[k - 1], binned[k]);
        a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0)
    };
    let spacing = if tau.len() > 1 {
        (tau[1] / tau[0]).ln()
    } else {
        1.0
    };
    let e0 = 0.5 * storage.iter().fold(f64::INFINITY, |m, &s| m.min(s));
    std::iter::once(e0.ln())
        .chain(tau.iter().map(|t| {
            let h = 2.0 / std::f64::consts::PI * 10f64.powf(log_loss_at(-t.log10())) * spacing;
            h.ln()
        }))
        .collect()
}

/// The series at the λ the marginal likelihood chooses (module doc):
/// a warm-started path of decreasing λ from `start`, a golden-section
/// refinement in ln λ, and a final tight minimisation. Returns (θ, λ,
/// converged). Shared by the frequency and the time-domain fits.
pub(super) fn regularised(problem: &mut Problem<'_>, start: Vec<f64>) -> (Vec<f64>, f64, bool) {
    let count = problem.data_count();
    let rule = LambdaRule::MarginalLikelihood;
    let mut from = start;
    let score = |t: &Trial| t.criterion(rule, count);
    let mut trials: Vec<Trial> = Vec::new();
    for exponent in LAMBDA_PATH.rev() {
        problem.lambda = 10f64.powi(exponent);
        let (theta, _) = minimize(problem, &from, 1e-6);
        from = theta.clone();
        trials.push(problem.trial(theta));
        // Past the minimum by two decades of rising criterion (as the
        // rolling fit's path): the small-λ fits are the costly ones.
        let k = trials.len();
        if k >= 3
            && score(&trials[k - 1]) > score(&trials[k - 2])
            && score(&trials[k - 2]) > score(&trials[k - 3])
        {
            break;
        }
    }
    let best = (0..trials.len())
        .min_by(|&a, &b| score(&trials[a]).total_cmp(&score(&trials[b])))
        .unwrap_or(0);
    // Golden section in ln λ between the best point's neighbours.
    let lo = trials[(best + 1).min(trials.len() - 1)].lambda.ln();
    let hi = trials[best.saturating_sub(1)].lambda.ln();
    let mut chosen = trials[best].clone();
    let (mut a, mut b) = (lo, hi);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let mut evaluate = |ln_lambda: f64, from: &[f64]| -> Trial {
        problem.lambda = ln_lambda.exp();
        let (theta, _) = minimize(problem, from, 1e-6);
        problem.trial(theta)
    };
    let mut c = evaluate(b - g * (b - a), &chosen.theta);
    let mut d = evaluate(a + g * (b - a), &chosen.theta);
    for _ in 0..REFINEMENTS {
        if score(&c) < score(&d) {
            b = d.lambda.ln();
            d = c;
            c = evaluate(b - g * (b - a), &d.theta);
        } else {
            a = c.lambda.ln();
            c = d;
            d = evaluate(a + g * (b - a), &c.theta);
        }
    }
    for t in [c, d] {
        if score(&t) < score(&chosen) {
            chosen = t;
        }
    }
    problem.lambda = chosen.lambda;
    let (theta, converged) = minimize(problem, &chosen.theta, 1e-10);
    (theta, chosen.lambda, converged)
}

/// Fits a causal, smooth Prony series to E′, E″ (Pa, > 0) at reduced
/// frequencies `omega` (rad/s, > 0); see the module doc.
pub fn fit_prony(omega: &[f64], storage: &[f64], loss: &[f64]) -> Result<PronyFit, FitError> {
    let n = omega.len();
    let full = (omega, storage, loss);
    if n < 3 || storage.len() != n || loss.len() != n {
        return Err(FitError::InsufficientData(format!(
            "a Prony series needs at least three points with E′ and E″ (got {n})"
        )));
    }
    let omega_lo = omega.iter().fold(f64::INFINITY, |m, &w| m.min(w));
    let omega_hi = omega.iter().fold(0.0f64, |m, &w| m.max(w));
    let tau = tau_grid(omega_lo, omega_hi);
    let condensed = condense(omega, storage, loss);
    let (omega, storage, loss) = condensed.as_ref().map_or((omega, storage, loss), |c| {
        (c.omega.as_slice(), c.storage.as_slice(), c.loss.as_slice())
    });
    let bins = omega.len();
    let mut problem = Problem {
        data: Data::Frequency {
            omega,
            ln_storage: storage.iter().map(|s| s.ln()).collect(),
            ln_loss: loss.iter().map(|l| l.ln()).collect(),
            root_count: condensed
                .as_ref()
                .map(|c| c.count.iter().map(|n| n.sqrt()).collect()),
        },
        tau: &tau,
        lambda: 0.0,
    };
    let from = start(omega, storage, loss, &tau);
    let (theta, lambda, converged) = regularised(&mut problem, from);
    let (prony, mut misfit) = series_of(&problem, &theta, &[0..bins, bins..2 * bins])?;
    if condensed.is_some() {
        // The misfit over the points as measured, not over the bins.
        misfit = points_misfit(&prony, full);
    }
    problem.lambda = lambda;
    let effective_parameters = problem.trial(theta).effective_parameters;
    Ok(PronyFit {
        prony,
        lambda,
        rule: LambdaRule::MarginalLikelihood,
        misfit_storage: misfit[0],
        misfit_loss: misfit[1],
        converged,
        effective_parameters,
    })
}

/// RMS log10 misfit (decades) of `prony` against E′ and E″ at every point.
fn points_misfit(prony: &Prony, (omega, storage, loss): (&[f64], &[f64], &[f64])) -> Vec<f64> {
    let (mut sum_storage, mut sum_loss) = (0.0, 0.0);
    for i in 0..omega.len() {
        let e = prony.modulus(omega[i]);
        sum_storage += (e.re / storage[i]).log10().powi(2);
        sum_loss += (e.im.max(f64::MIN_POSITIVE) / loss[i]).log10().powi(2);
    }
    let n = omega.len() as f64;
    vec![(sum_storage / n).sqrt(), (sum_loss / n).sqrt()]
}

/// The series of θ on the problem's τ grid, and the RMS log10 misfit
/// (decades) of each range of its data rows.
pub(super) fn series_of(
    problem: &Problem<'_>,
    theta: &[f64],
    ranges: &[std::ops::Range<usize>],
) -> Result<(Prony, Vec<f64>), FitError> {
    let h: Vec<f64> = theta[1..].iter().map(|t| t.exp()).collect();
    let sum: f64 = h.iter().sum();
    // Data without a rubbery plateau (a liquid, or isotherms that stop
    // short of it) drive ln E0 down without bound; a floor far below any
    // measured modulus keeps E1 − Σ H representable.
    let e0 = theta[0].exp().max(STATIC_FLOOR * sum);
    let prony = Prony::new(e0 + sum, h, problem.tau.to_vec())?;
    let e = problem.evaluate(theta);
    let rms = |rows: std::ops::Range<usize>| {
        let len = rows.len() as f64;
        (rows.map(|i| e.residuals[i].powi(2)).sum::<f64>() / len).sqrt() / std::f64::consts::LN_10
    };
    Ok((prony, ranges.iter().cloned().map(rms).collect()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};
    use rollfit_model::{HavriliakNegami, ViscoelasticModulus};

    /// A broad Havriliak–Negami rubber sampled over 12 decades with 1 %
    /// scatter: the fitted series follows the truth (not the noise) to
    /// well under the noise, and its misfit is the noise level.
    #[test]
    fn recovers_a_broad_rubber_through_noise() {
        let (truth, omega, storage, loss) = noisy_broad_rubber(300, 3);
        let fit = fit_prony(&omega, &storage, &loss).unwrap();
        // 1 % is 0.0043 decades.
        assert!(
            fit.misfit_storage < 0.0055 && fit.misfit_loss < 0.0055,
            "{fit:?}"
        );
        let worst = largest_error(&fit, &truth, &omega);
        assert!(worst < 0.01, "largest error against the truth {worst}");
    }

    /// The same rubber sampled 100 times as densely (30 000 points, fitted
    /// on their bins, `condense`): the misfit over the points is the 1 %
    /// noise, and the series is closer to the truth than the sparse fit's
    /// bound by the √100 the points add.
    #[test]
    fn a_dense_sampling_is_fitted_on_its_bins() {
        let (truth, omega, storage, loss) = noisy_broad_rubber(30_000, 4);
        let fit = fit_prony(&omega, &storage, &loss).unwrap();
        let noise = 1.01f64.log10();
        for misfit in [fit.misfit_storage, fit.misfit_loss] {
            assert!((misfit / noise - 1.0).abs() < 0.03, "{fit:?}");
        }
        let worst = largest_error(&fit, &truth, &omega);
        assert!(worst < 0.001, "largest error against the truth {worst}");
    }

    /// A broad Havriliak–Negami rubber at `count` frequencies over 12
    /// decades with 1 % scatter (seeded): (truth, ω, E′, E″).
    fn noisy_broad_rubber(
        count: usize,
        seed: u64,
    ) -> (HavriliakNegami, Vec<f64>, Vec<f64>, Vec<f64>) {
        let truth = HavriliakNegami::new(2e6, 2e9, 1e-3, 0.55, 0.4).unwrap();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let normal = Normal::new(0.0, 0.01).unwrap();
        let omega: Vec<f64> = (0..count)
            .map(|i| 10f64.powf(-4.0 + 12.0 * i as f64 / (count - 1) as f64))
            .collect();
        let (mut storage, mut loss) = (Vec::new(), Vec::new());
        for &w in &omega {
            let e = truth.modulus(w);
            storage.push(e.re * (1.0 + normal.sample(&mut rng)));
            loss.push(e.im * (1.0 + normal.sample(&mut rng)));
        }
        (truth, omega, storage, loss)
    }

    /// The largest |ln| error of the fit's E′ and E″ against the truth at
    /// every 7th frequency.
    fn largest_error(fit: &PronyFit, truth: &HavriliakNegami, omega: &[f64]) -> f64 {
        let mut worst: f64 = 0.0;
        for &w in omega.iter().step_by(7) {
            let (e, t) = (fit.prony.modulus(w), truth.modulus(w));
            worst = worst
                .max((e.re / t.re).ln().abs())
                .max((e.im / t.im).ln().abs());
        }
        worst
    }
}
