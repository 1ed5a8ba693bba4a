//! The three optimisers, behind one small interface: each takes the
//! objective, wrapped for one run, and a start θ₀ and returns a
//! [`SolverRun`] that says honestly how it ended — iterations, objective
//! evaluations, wall time, and whether it converged or why it stopped
//! (budget, abandonment, stall, line-search failure).
//!
//! - [`levenberg_marquardt`]: the robust default (a careful study on this
//!   problem found it the only one of the three that reliably reaches the
//!   noise floor).
//! - [`lbfgs`]: argmin's L-BFGS on V(θ) with the exact gradient 2Jᵀr.
//! - [`nelder_mead`]: argmin's Nelder–Mead simplex on V(θ), the paper's
//!   "amoeba"; derivative-free, and slow in many dimensions.
//!
//! Each run sees the objective through `counting::Counted`, which owns the
//! run's evaluation count, budget, best point, history and abandonment, and
//! tells by type why a run could evaluate no further.

pub(crate) mod counting;
pub mod lbfgs;
pub mod levenberg_marquardt;
pub mod nelder_mead;
mod outcome;

pub use outcome::{SolverRun, StopReason, Tolerance};

use crate::params::Method;
use counting::Counted;

/// Default evaluation budget of a method in `dimension` free parameters.
pub fn default_budget(method: Method, dimension: usize) -> usize {
    match method {
        Method::LevenbergMarquardt => 100 * (dimension + 1),
        Method::Lbfgs => 2000,
        Method::NelderMead => 20_000,
    }
}

/// Runs `method` on `counted` (the objective with this run's budget and
/// abandonment) from `start`.
pub(crate) fn run(
    method: Method,
    counted: Counted<'_, '_>,
    start: &[f64],
    tolerance: Tolerance,
) -> SolverRun {
    let clock = std::time::Instant::now();
    let (iterations, stop) = match method {
        Method::LevenbergMarquardt => levenberg_marquardt::minimize(&counted, start, tolerance),
        Method::Lbfgs => lbfgs::minimize(&counted, start),
        Method::NelderMead => nelder_mead::minimize(&counted, start),
    };
    let tally = counted.into_tally();
    // A solver may end on a test of its own in the step that abandoned the
    // start; the abandonment is still why the run ended.
    let stop = match tally.abandoned {
        Some(rule) => rule.stop_reason(),
        None => stop,
    };
    let (objective, theta) = tally.best.unwrap_or((f64::INFINITY, start.to_vec()));
    SolverRun {
        method,
        theta,
        objective,
        iterations,
        evaluations: tally.evaluations,
        wall_time_s: clock.elapsed().as_secs_f64(),
        stop,
        history: tally.history,
    }
}
