//! The choice of λ on one τ grid: the path, when to stop walking it, and
//! where the rule's λ lies between its points (the rules themselves are
//! described in [`crate::regularization`]).
//!
//! - Discrepancy principle (σ measured): the walk down the path stops at
//!   the first λ with χ² ≤ N whose residual signs pass the runs test
//!   ([`meets_discrepancy`]); bisection in ln λ between it and the λ before
//!   keeps the largest such λ ([`bisect_discrepancy`]). The runs condition
//!   is there because a fit at χ² ≤ N can still cut through a feature of
//!   μ(v) with residuals in long runs, and the smoothest fit the noise
//!   cannot tell from the data must pass both tests it is judged by.
//!   Smoothing explains a pattern only while the fit leaves more than the
//!   noise: the walk also stops once χ² ≤ N − t, and a pattern still
//!   there is the model's (the λ is then Morozov's alone, and the verdict
//!   says so). The target N − t in place of N smooths less and fits more
//!   of the noise: the worst tan δ error of a 40-seed study grows
//!   about threefold (figures in BENCHMARKS.md, "The choice of λ").
//! - Marginal likelihood (σ unknown): the walk stops two decades past the
//!   criterion's minimum, which is located between the path points by the
//!   parabola through the best one and its neighbours (criterion against
//!   ln λ); λ is chosen there, and the noise is the restricted-likelihood
//!   estimate σ̂² = V̂/(N − m₀) the criterion profiles out at the same λ
//!   ([`criterion_minimum`]).
//!
//! The λ of the marginal likelihood is its minimum, not the smoothest λ
//! near it: a λ leaned to the smooth side leaves a smoothing bias in the
//! residuals about as large as the noise on sparse data, and the noise
//! estimate then reads that bias as noise. A noise draw that happens to
//! look smooth puts the minimum at a small λ and the fit follows the
//! draw; no λ recovers that draw's own scatter, so no lean is worth its
//! bias (the comparison is in BENCHMARKS.md, "The choice of λ").

use crate::error::FitError;
use crate::params::{Lambda, ValidFitParams};
use crate::regularization::{LambdaRule, REFINEMENTS, Trial, path};

/// Fits that may confirm a λ located on a linearisation
/// ([`bisect_discrepancy`]).
const CONFIRMATIONS: usize = 2;
use crate::solvers::SolverRun;

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

/// Whether `trial` meets the discrepancy principle: χ² ≤ N and residual
/// signs that pass the runs test.
pub(super) fn meets_discrepancy(trial: &Trial, n: usize) -> bool {
    trial.misfit <= discrepancy_target(n) && trial.random_signs
}

/// Whether the walk down the path may stop at `latest`, after the path
/// points `trials`: for the discrepancy principle where it is met, or where
/// χ² ≤ N − t (the fit leaves no more than the noise: a pattern left is
/// not the smoothing's); else past the criterion's minimum by two decades
/// of rising criterion.
pub(super) fn path_walked(
    rule: LambdaRule,
    n: usize,
    trials: &[(Trial, SolverRun)],
    latest: &Trial,
) -> bool {
    match rule {
        LambdaRule::Discrepancy => {
            meets_discrepancy(latest, n) || latest.misfit <= n as f64 - latest.effective_parameters
        }
        _ => {
            let k = trials.len();
            k >= 2
                && latest.criterion(rule, n) > trials[k - 1].0.criterion(rule, n)
                && trials[k - 1].0.criterion(rule, n) > trials[k - 2].0.criterion(rule, n)
        }
    }
}

/// The minimum of the criterion of `rule` over the path `trials`: its λ,
/// the θ of the best path point to start from, and for the marginal
/// likelihood the noise variance it profiles out there.
pub(super) struct CriterionMinimum {
    /// λ at the minimum.
    pub lambda: f64,
    /// θ of the best path point.
    pub from: Vec<f64>,
    /// σ̂² = V̂/(N − m₀) at the minimum ([`Trial::evidence_noise_variance`]).
    pub noise_variance: Option<f64>,
}

/// The minimum of the criterion of `rule` over the path `trials` (a
/// criterion rule; at least one trial). The path points are a decade apart:
/// the minimum is located by the parabola through the best point and its
/// neighbours (criterion against ln λ), and ln σ̂² is read there off the
/// parabola through the same three points (both vary smoothly with ln λ);
/// at an end of the path, the end point is taken.
pub(super) fn criterion_minimum(
    rule: LambdaRule,
    n: usize,
    trials: &[(Trial, SolverRun)],
) -> CriterionMinimum {
    let score = |k: usize| trials[k].0.criterion(rule, n);
    let best = (0..trials.len())
        .min_by(|&a, &b| score(a).total_cmp(&score(b)))
        .unwrap_or(0);
    let ln_lambda = |k: usize| trials[k].0.lambda.ln();
    let ln_noise = |k: usize| trials[k].0.evidence_noise_variance(n).ln();
    let (at, ln_noise_at) = if best == 0 || best + 1 == trials.len() {
        (ln_lambda(best), ln_noise(best))
    } else {
        let around = [best - 1, best, best + 1];
        let x = around.map(ln_lambda);
        let vertex = parabola_vertex(x, around.map(score)).unwrap_or(x[1]);
        (vertex, parabola_at(x, around.map(ln_noise), vertex))
    };
    CriterionMinimum {
        lambda: at.exp(),
        from: trials[best].0.theta.clone(),
        noise_variance: (rule == LambdaRule::MarginalLikelihood).then(|| ln_noise_at.exp()),
    }
}

/// The abscissa of the vertex of the parabola through (x_k, y_k), or None
/// when the three points are not convex (the vertex is then no minimum).
fn parabola_vertex(x: [f64; 3], y: [f64; 3]) -> Option<f64> {
    let d01 = (y[1] - y[0]) / (x[1] - x[0]);
    let d12 = (y[2] - y[1]) / (x[2] - x[1]);
    let curvature = (d12 - d01) / (x[2] - x[0]);
    // p(t) = y0 + d01 (t − x0) + curvature (t − x0)(t − x1): p′ = 0 at
    // t = (x0 + x1)/2 − d01/(2 curvature).
    let vertex = 0.5 * (x[0] + x[1]) - d01 / (2.0 * curvature);
    (curvature > 0.0 && vertex.is_finite()).then_some(vertex)
}

/// The parabola through (x_k, y_k) at `t` (Lagrange form).
fn parabola_at(x: [f64; 3], y: [f64; 3], t: f64) -> f64 {
    (0..3)
        .map(|i| {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            y[i] * (t - x[j]) * (t - x[k]) / ((x[i] - x[j]) * (x[i] - x[k]))
        })
        .sum()
}

/// The fits the refinement of λ asks for.
pub(super) trait Refinement {
    /// The fit at `lambda` from `from`.
    fn refine_at(&mut self, lambda: f64, from: &[f64]) -> Result<(Trial, SolverRun), FitError>;
    /// The trial at `lambda` predicted from the linearisation at `base`
    /// (a fit's own trial), without a solver run
    /// ([`super::linearised`]); its θ is where a fit at `lambda` starts.
    fn predict(&mut self, lambda: f64, base: &Trial) -> Result<Trial, FitError>;
}

/// Bisection in ln λ between the last path point that fails the
/// discrepancy principle and the first that meets it; keeps the largest λ
/// that meets it. When the walk ended without meeting it (at χ² ≤ N − t
/// with the signs still in runs, or at the path's end), Morozov's χ² ≤ N
/// alone is bisected, and failing that the path's best end is kept.
///
/// The bisection runs on the linearisation of the latest fit next to the
/// bracket ([`Refinement::predict`]), and a fit at the λ it locates
/// confirms it: when that fit meets the principle it closes the bracket
/// from below, else from above, and the bisection runs again on the new
/// fit's linearisation (closer to the crossing, so more accurate), at most
/// [`CONFIRMATIONS`] fits in all, after which the largest λ that a fit met
/// stands; a bisection that locates nothing above it ends the search. A
/// fit per bisection step would cost [`REFINEMENTS`] fits; the
/// linearisation at the path point a decade away predicts χ² within the
/// bisection's own resolution (10^(1/32)) on the recovery and sparse
/// studies, so one confirming fit is the rule.
pub(super) fn bisect_discrepancy(
    n: usize,
    mut trials: Vec<(Trial, SolverRun)>,
    fits: &mut impl Refinement,
) -> Result<(Trial, SolverRun), FitError> {
    let last = trials.len() - 1;
    let morozov = |t: &Trial, n: usize| t.misfit <= discrepancy_target(n);
    let meets: &dyn Fn(&Trial, usize) -> bool = if meets_discrepancy(&trials[last].0, n) {
        &meets_discrepancy
    } else {
        &morozov
    };
    let first = trials.iter().position(|t| meets(&t.0, n));
    let Some(first) = first.filter(|&k| k > 0) else {
        // Met at the largest λ, or never: keep that point, or the path's
        // best end.
        let best = match first {
            Some(k) => trials.swap_remove(k),
            None => trials
                .into_iter()
                .min_by(|a, b| a.0.misfit.total_cmp(&b.0.misfit))
                .ok_or(FitError::Internal("empty λ path"))?,
        };
        return Ok(best);
    };
    // Between trials[first − 1] (fails) and trials[first] (meets).
    let mut fails_at = trials[first - 1].0.lambda;
    let mut meeting = trials.swap_remove(first);
    let mut base = meeting.0.clone();
    for _ in 0..CONFIRMATIONS {
        let mut below = meeting.0.lambda;
        let mut above = fails_at;
        let mut located: Option<Trial> = None;
        for _ in 0..REFINEMENTS {
            let lambda = (above * below).sqrt();
            let predicted = fits.predict(lambda, &base)?;
            if meets(&predicted, n) {
                below = lambda;
                located = Some(predicted);
            } else {
                above = lambda;
            }
        }
        let Some(located) = located else {
            return Ok(meeting);
        };
        let confirmed = fits.refine_at(located.lambda, &located.theta)?;
        base = confirmed.0.clone();
        if meets(&confirmed.0, n) {
            meeting = confirmed;
        } else {
            fails_at = located.lambda;
        }
    }
    Ok(meeting)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::Method;
    use crate::solvers::StopReason;

    /// A converged solver run that ended at `theta` (the tests' trials
    /// need one beside them).
    fn run_at(theta: Vec<f64>) -> SolverRun {
        SolverRun {
            method: Method::LevenbergMarquardt,
            theta,
            objective: 0.0,
            iterations: 0,
            evaluations: 0,
            wall_time_s: 0.0,
            stop: StopReason::Converged("test".into()),
            history: Vec::new(),
        }
    }

    /// The parabola through three points of a quadratic is the quadratic:
    /// its vertex and values are exact, on uneven spacing too; a concave
    /// triple has no minimum.
    #[test]
    fn parabola_through_a_quadratic_is_exact() {
        let q = |x: f64| 3.0 * (x - 0.3) * (x - 0.3) + 2.0;
        let x = [1.7, 0.0, -1.1];
        assert!((parabola_vertex(x, x.map(q)).unwrap() - 0.3).abs() < 1e-12);
        assert!((parabola_at(x, x.map(q), -0.4) - q(-0.4)).abs() < 1e-12);
        assert!(parabola_vertex(x, x.map(|x| -q(x))).is_none());
    }

    /// The marginal likelihood's minimum between path points a decade
    /// apart, and σ̂² = V̂/(N − m₀) there: path points whose criterion is
    /// (ln λ − ln 0.02)² and whose V̂ is a power of λ give λ = 0.02 and
    /// V̂(0.02)/(N − m₀) exactly; a minimum at the path's end is the end.
    #[test]
    fn the_evidence_minimum_lies_between_path_points() {
        let (n, free, rank) = (15usize, 20usize, 18usize);
        let dof = (n - (free - rank)) as f64;
        let penalised = |lambda: f64| 0.012 * lambda.powf(0.2);
        let trial = |lambda: f64| {
            let x = lambda.ln();
            let criterion = (x - 0.02f64.ln()).powi(2);
            let log_det = criterion - dof * penalised(lambda).ln() + rank as f64 * x;
            let t = Trial {
                lambda,
                theta: vec![x],
                misfit: penalised(lambda),
                effective_parameters: 4.0,
                penalised: penalised(lambda),
                log_det,
                penalty_rank: rank,
                free,
                random_signs: true,
            };
            (t, run_at(vec![x]))
        };
        let trials: Vec<_> = [1.0, 0.1, 0.01, 1e-3].map(trial).into();
        let rule = LambdaRule::MarginalLikelihood;
        for (k, (t, _)) in trials.iter().enumerate() {
            let expected = (t.lambda.ln() - 0.02f64.ln()).powi(2);
            assert!((t.criterion(rule, n) - expected).abs() < 1e-9, "{k}");
        }
        let minimum = criterion_minimum(rule, n, &trials);
        assert!(
            (minimum.lambda / 0.02 - 1.0).abs() < 1e-9,
            "{}",
            minimum.lambda
        );
        let noise = minimum.noise_variance.unwrap();
        assert!(
            (noise / (penalised(0.02) / dof) - 1.0).abs() < 1e-9,
            "{noise}"
        );
        // The best path point (0.01) starts the fit.
        assert_eq!(minimum.from, vec![0.01f64.ln()]);
        let end = criterion_minimum(rule, n, &trials[2..]);
        assert!((end.lambda / trials[2].0.lambda - 1.0).abs() < 1e-12);
    }

    /// A fit whose misfit is 20 + 10 log10 λ (χ² ≤ N = 31 up to λ = 12.6)
    /// and whose signs pass the runs test up to λ = 3.
    struct Synthetic {
        signs_up_to: f64,
    }

    impl Synthetic {
        fn trial(&self, lambda: f64) -> (Trial, SolverRun) {
            let t = Trial {
                lambda,
                theta: vec![lambda.ln()],
                misfit: 20.0 + 10.0 * lambda.log10(),
                effective_parameters: 5.0,
                penalised: 0.0,
                log_det: 0.0,
                penalty_rank: 1,
                free: 3,
                random_signs: lambda <= self.signs_up_to,
            };
            let run = run_at(t.theta.clone());
            (t, run)
        }
    }

    impl Refinement for Synthetic {
        fn refine_at(&mut self, lambda: f64, _: &[f64]) -> Result<(Trial, SolverRun), FitError> {
            Ok(self.trial(lambda))
        }

        fn predict(&mut self, lambda: f64, _: &Trial) -> Result<Trial, FitError> {
            Ok(self.trial(lambda).0)
        }
    }

    /// The discrepancy principle keeps the largest λ with χ² ≤ N whose
    /// signs pass the runs test (3 here, to the bisection's 10^(1/32));
    /// when the signs pass nowhere on the walk, Morozov's χ² ≤ N alone
    /// (12.6).
    #[test]
    fn the_discrepancy_principle_asks_random_signs_too() {
        let n = 31;
        let mut fits = Synthetic { signs_up_to: 3.0 };
        let trials = [100.0, 10.0, 1.0].map(|l| fits.trial(l)).into();
        let (chosen, _) = bisect_discrepancy(n, trials, &mut fits).unwrap();
        assert!(
            chosen.lambda <= 3.0 && chosen.lambda >= 3.0 / 1.08,
            "{}",
            chosen.lambda
        );
        let mut fits = Synthetic { signs_up_to: 0.0 };
        let trials = [100.0, 10.0, 1.0].map(|l| fits.trial(l)).into();
        let (chosen, _) = bisect_discrepancy(n, trials, &mut fits).unwrap();
        let morozov = 10f64.powf(1.1);
        assert!(
            chosen.lambda <= morozov && chosen.lambda >= morozov / 1.08,
            "{}",
            chosen.lambda
        );
    }
}
