//! The choice of λ on one τ grid: the path, when to stop walking it, and
//! the refinement of the rule's λ between its points (the rules themselves
//! are described in [`crate::regularization`]).
//!
//! - Discrepancy principle (σ measured): the walk down the path stops at
//!   the first λ with χ² ≤ N; bisection in ln λ between it and the λ
//!   before keeps the largest λ with χ² ≤ N.
//! - Marginal likelihood (σ unknown): the walk stops two decades past the
//!   criterion's minimum; the λ chosen is the smoothest whose criterion is
//!   within [`EVIDENCE_TOLERANCE`] of the best (interpolated in ln λ).

use crate::error::FitError;
use crate::params::{Lambda, ValidFitParams};
use crate::regularization::{LambdaRule, REFINEMENTS, Trial, path};
use crate::solvers::SolverRun;

/// How much worse than the best (in −2 ln p, twice the log Bayes factor)
/// the chosen λ may be: the smoothest λ the data do not reject with strong
/// evidence (2 ln B < 6 on the scale of Kass and Raftery). On 15 speeds the
/// marginal likelihood's minimum is shallow toward small λ, and a noise
/// draw that happens to look smooth pulls it there: in one seed of ten the
/// fit then absorbed two thirds of the noise, estimated it at a third of
/// its size and drew bands three times too narrow. Leaning to the smooth
/// side within the evidence's own resolution avoids that; the smoothing
/// bias it adds is in the bands (analysis).
///
/// # References
/// - R.E. Kass, A.E. Raftery, "Bayes factors", J. Amer. Statist. Assoc.
///   90 (1995) 773–795.
const EVIDENCE_TOLERANCE: f64 = 6.0;

/// The λ path: [`path`], or from `params.path_top` down.
pub(super) fn lambda_path(params: &ValidFitParams) -> Vec<f64> {
    match params.path_top {
        Some(top) => std::iter::once(top)
            .chain(path().into_iter().filter(|&l| l < top * 0.999))
            .collect(),
        None => path(),
    }
}

/// The first λ fitted: the fixed λ, or the top of the path.
pub(super) fn first_lambda(params: &ValidFitParams) -> f64 {
    match params.lambda {
        Lambda::Fixed(lambda) => lambda,
        Lambda::Auto => lambda_path(params)[0],
    }
}

/// The misfit the discrepancy principle aims at: χ² = N (Morozov). (The
/// variant N − t, t the effective parameters, was tried on the bundled
/// rubber: it picks λ a hundred times smaller and lets tan δ wiggle by
/// ±3 % without improving |E|.)
pub(super) fn discrepancy_target(n: usize) -> f64 {
    n as f64
}

/// Whether the walk down the path may stop at `latest`, after the path
/// points `trials`: at χ² ≤ N for the discrepancy principle, else past the
/// criterion's minimum by two decades of rising criterion.
pub(super) fn path_walked(
    rule: LambdaRule,
    n: usize,
    trials: &[(Trial, SolverRun)],
    latest: &Trial,
) -> bool {
    match rule {
        LambdaRule::Discrepancy => latest.misfit <= discrepancy_target(n),
        _ => {
            let k = trials.len();
            k >= 2
                && latest.criterion(rule, n) > trials[k - 1].0.criterion(rule, n)
                && trials[k - 1].0.criterion(rule, n) > trials[k - 2].0.criterion(rule, n)
        }
    }
}

/// The largest λ whose criterion is within [`EVIDENCE_TOLERANCE`] of the
/// best path point (interpolated linearly in ln λ between the bracketing
/// path points), with the θ of the nearest path point at or below it to
/// start from.
pub(super) fn smoothest_acceptable(
    rule: LambdaRule,
    n: usize,
    trials: &[(Trial, SolverRun)],
) -> (f64, Vec<f64>) {
    let score = |k: usize| trials[k].0.criterion(rule, n);
    let best = (0..trials.len())
        .min_by(|&a, &b| score(a).total_cmp(&score(b)))
        .unwrap_or(0);
    let limit = score(best) + EVIDENCE_TOLERANCE;
    // The path runs from large to small λ: walk back from the best point to
    // the first (largest-λ) point still within the limit.
    let mut k = best;
    while k > 0 && score(k - 1) <= limit {
        k -= 1;
    }
    let from = trials[k].0.theta.clone();
    if k == 0 {
        return (trials[0].0.lambda, from);
    }
    // Between trials[k − 1] (above the limit) and trials[k] (within).
    let (x0, x1) = (trials[k - 1].0.lambda.ln(), trials[k].0.lambda.ln());
    let (y0, y1) = (score(k - 1), score(k));
    let fraction = ((limit - y1) / (y0 - y1)).clamp(0.0, 1.0);
    let x = x1 + fraction * (x0 - x1);
    (
        if x.is_finite() {
            x.exp()
        } else {
            trials[k].0.lambda
        },
        from,
    )
}

/// The fits the refinement of λ asks for.
pub(super) trait Refinement {
    /// The fit at `lambda` from `from`.
    fn refine_at(&mut self, lambda: f64, from: &[f64]) -> Result<(Trial, SolverRun), FitError>;
}

/// Refines λ between path points: bisection for the discrepancy principle,
/// golden-section search on the criterion otherwise.
pub(super) fn refine(
    rule: LambdaRule,
    n: usize,
    trials: Vec<(Trial, SolverRun)>,
    fits: &mut impl Refinement,
) -> Result<(Trial, SolverRun), FitError> {
    match rule {
        LambdaRule::Discrepancy => bisect_discrepancy(n, trials, fits),
        LambdaRule::Gcv | LambdaRule::MarginalLikelihood | LambdaRule::Fixed => {
            golden_section(rule, n, trials, fits)
        }
    }
}

/// Bisection in ln λ between the last path point with χ² > N and the
/// first with χ² ≤ N; keeps the largest λ with χ² ≤ N.
fn bisect_discrepancy(
    n: usize,
    mut trials: Vec<(Trial, SolverRun)>,
    fits: &mut impl Refinement,
) -> Result<(Trial, SolverRun), FitError> {
    let last = trials.len() - 1;
    if trials[last].0.misfit > discrepancy_target(n) || last == 0 {
        // Never reached χ² = N (or already at the largest λ): keep the
        // path's best end.
        let best = trials
            .into_iter()
            .min_by(|a, b| a.0.misfit.total_cmp(&b.0.misfit))
            .ok_or(FitError::Internal("empty λ path"))?;
        return Ok(best);
    }
    // Between trials[last − 1] (χ² > N) and trials[last] (χ² ≤ N).
    let mut above = trials[last - 1].clone();
    let mut below = trials.swap_remove(last);
    for _ in 0..REFINEMENTS {
        let lambda = (above.0.lambda * below.0.lambda).sqrt();
        let from = below.0.theta.clone();
        let t = fits.refine_at(lambda, &from)?;
        if t.0.misfit <= discrepancy_target(n) {
            below = t;
        } else {
            above = t;
        }
    }
    Ok(below)
}

/// Golden-section search in ln λ over the path points next to the best
/// one, on the criterion of `rule`.
fn golden_section(
    rule: LambdaRule,
    n: usize,
    mut trials: Vec<(Trial, SolverRun)>,
    fits: &mut impl Refinement,
) -> Result<(Trial, SolverRun), FitError> {
    let score = |t: &(Trial, SolverRun)| t.0.criterion(rule, n);
    let best = trials
        .iter()
        .enumerate()
        .min_by(|a, b| score(a.1).total_cmp(&score(b.1)))
        .map(|(i, _)| i)
        .unwrap_or(0);
    let lo = trials[best.saturating_sub(1)].0.lambda.ln();
    let hi = trials[(best + 1).min(trials.len() - 1)].0.lambda.ln();
    let mut incumbent = trials.swap_remove(best);
    if lo == hi {
        return Ok(incumbent);
    }
    let (mut a, mut b) = (lo.min(hi), lo.max(hi));
    let golden = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..REFINEMENTS {
        let c = b - golden * (b - a);
        let d = a + golden * (b - a);
        let from = incumbent.0.theta.clone();
        let tc = fits.refine_at(c.exp(), &from)?;
        let td = fits.refine_at(d.exp(), &from)?;
        if score(&tc) < score(&td) {
            b = d;
            if score(&tc) < score(&incumbent) {
                incumbent = tc;
            }
        } else {
            a = c;
            if score(&td) < score(&incumbent) {
                incumbent = td;
            }
        }
    }
    Ok(incumbent)
}
