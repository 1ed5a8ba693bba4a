//! The three optimisers, behind one small interface: each takes the
//! problem and a start θ₀ and returns a [`SolverRun`] that says honestly how
//! it ended — iterations, objective evaluations, wall time, and whether it
//! converged or why it stopped (budget, stall, line-search failure).
//!
//! - [`levenberg_marquardt`]: the robust default (a careful study on this
//!   problem found it the only one of the three that reliably reaches the
//!   noise floor).
//! - [`lbfgs`]: argmin's L-BFGS on V(θ) with the exact gradient 2Jᵀr.
//! - [`nelder_mead`]: argmin's Nelder–Mead simplex on V(θ), the paper's
//!   "amoeba"; derivative-free, and slow in many dimensions.

pub mod lbfgs;
pub mod levenberg_marquardt;
pub mod nelder_mead;

use serde::Serialize;

use crate::error::FitError;
use crate::params::Method;
use crate::problem::Problem;

/// Why a solver stopped.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    /// A convergence test passed; the text says which.
    Converged(String),
    /// The evaluation budget ran out.
    Budget,
    /// No further progress possible at the requested tolerances.
    Stall(String),
    /// The line search failed to find an acceptable step.
    LineSearchFailure(String),
    /// The forward model failed at a trial point.
    ModelFailure(String),
    /// An exploratory start given up as hopeless (the text says why).
    Abandoned(String),
}

impl StopReason {
    /// True for [`StopReason::Converged`].
    pub fn converged(&self) -> bool {
        matches!(self, StopReason::Converged(_))
    }

    /// One line for people.
    pub fn describe(&self) -> String {
        match self {
            StopReason::Converged(how) => format!("converged ({how})"),
            StopReason::Budget => "stopped: evaluation budget used up".into(),
            StopReason::Stall(why) => format!("stalled: {why}"),
            StopReason::LineSearchFailure(why) => format!("line search failed: {why}"),
            StopReason::ModelFailure(why) => format!("forward model failed: {why}"),
            StopReason::Abandoned(why) => format!("abandoned: {why}"),
        }
    }
}

/// The record of one solver run.
#[derive(Debug, Clone, PartialEq)]
pub struct SolverRun {
    /// The method that ran.
    pub method: Method,
    /// Best parameters found.
    pub theta: Vec<f64>,
    /// V at `theta`.
    pub objective: f64,
    /// Solver iterations.
    pub iterations: usize,
    /// Objective (forward-model) evaluations.
    pub evaluations: usize,
    /// Wall time, s.
    pub wall_time_s: f64,
    /// How it ended.
    pub stop: StopReason,
    /// (evaluations, best V so far), for convergence plots.
    pub history: Vec<(usize, f64)>,
}

/// How tightly a run converges: `Path` for the fits that only locate λ,
/// `Final` for the fit that is reported.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Tolerance {
    /// Relative reduction of 1e-6 (step 1e-8).
    Path,
    /// Relative reduction and step of 1e-8.
    Final,
}

/// Default evaluation budget of a method in `dimension` free parameters.
pub fn default_budget(method: Method, dimension: usize) -> usize {
    match method {
        Method::LevenbergMarquardt => 100 * (dimension + 1),
        Method::Lbfgs => 2000,
        Method::NelderMead => 20_000,
    }
}

/// Runs `method` on `problem` from `start` with `budget` evaluations.
pub(crate) fn run(
    method: Method,
    problem: &Problem<'_>,
    start: &[f64],
    budget: usize,
    tolerance: Tolerance,
) -> SolverRun {
    let clock = std::time::Instant::now();
    problem.reset(budget);
    let (iterations, mut stop) = match method {
        Method::LevenbergMarquardt => levenberg_marquardt::minimize(problem, start, tolerance),
        Method::Lbfgs => lbfgs::minimize(problem, start),
        Method::NelderMead => nelder_mead::minimize(problem, start),
    };
    if problem.abandoned.get()
        && let Some((at, above)) = problem.abandon_above.get()
    {
        stop = StopReason::Abandoned(format!("V still above {above:.4e} after {at} evaluations"));
    }
    let (objective, theta) = problem
        .best
        .borrow()
        .clone()
        .unwrap_or((f64::INFINITY, start.to_vec()));
    SolverRun {
        method,
        theta,
        objective,
        iterations,
        evaluations: problem.evaluations.get(),
        wall_time_s: clock.elapsed().as_secs_f64(),
        stop,
        history: problem.history.borrow().clone(),
    }
}

/// Maps an error raised inside a solver to a stop reason, by its type.
pub(crate) fn stop_from_error(error: &FitError) -> StopReason {
    match error {
        FitError::BudgetExhausted(_) => StopReason::Budget,
        other => StopReason::ModelFailure(other.to_string()),
    }
}

/// The stop reason of an error that came back through argmin: the fit's
/// own error when the problem raised it (carried as the error's value, see
/// `problem::to_argmin`), else a line-search failure in argmin's words.
pub(crate) fn stop_from_argmin(error: &argmin::core::Error) -> StopReason {
    match error.downcast_ref::<FitError>() {
        Some(e) => stop_from_error(e),
        None => StopReason::LineSearchFailure(error.to_string()),
    }
}
