//! L-BFGS (argmin) on V(θ) with the exact gradient 2Jᵀr.
//!
//! The inverse Hessian is approximated from the last m = 10 steps and
//! gradient changes; a Moré–Thuente line search enforces the strong Wolfe
//! conditions. Positivity is kept by the log-parametrisation, since argmin's
//! L-BFGS has no bounds. On this ill-conditioned least-squares problem the
//! method can stop early when the line search finds no acceptable step; the
//! run then reports a line-search failure rather than convergence.
//!
//! # References
//! - D.C. Liu, J. Nocedal, "On the limited memory BFGS method for large
//!   scale optimization", Math. Programming 45 (1989) 503–528.
//! - J.J. Moré, D.J. Thuente, "Line search algorithms with guaranteed
//!   sufficient decrease", ACM TOMS 20 (1994) 286–307.

use argmin::core::{Executor, State, TerminationReason, TerminationStatus};
use argmin::solver::linesearch::MoreThuenteLineSearch;
use argmin::solver::quasinewton::LBFGS;
use nalgebra::DVector;

use super::counting::{Counted, stop_from_argmin};
use super::outcome::StopReason;

/// Minimises from `start`; returns (iterations, stop reason).
pub(crate) fn minimize(counted: &Counted<'_, '_>, start: &[f64]) -> (usize, StopReason) {
    // argmin's tolerances are absolute; scale them by V at the start so that
    // σ-weighted (V ~ N) and relative (V ~ N·1e-4) residuals stop alike.
    let v0 = match counted.evaluate(start, false) {
        Ok(e) => e.objective(),
        Err(refusal) => return (0, refusal.stop_reason()),
    };
    let line_search = MoreThuenteLineSearch::new();
    let solver = match LBFGS::new(line_search, 10)
        .with_tolerance_grad(1e-8 * v0.sqrt())
        .and_then(|s| s.with_tolerance_cost(1e-12 * v0))
    {
        Ok(s) => s,
        Err(e) => return (0, StopReason::Stall(e.to_string())),
    };
    let budget = counted.budget() as u64;
    let result = Executor::new(counted, solver)
        .configure(|state| {
            state
                .param(DVector::from_column_slice(start))
                .max_iters(budget)
        })
        .run();
    match result {
        Ok(result) => {
            let state = result.state();
            let iterations = state.get_iter() as usize;
            let stop = match state.get_termination_status() {
                TerminationStatus::Terminated(TerminationReason::SolverConverged) => {
                    StopReason::Converged("gradient or cost change below tolerance".into())
                }
                TerminationStatus::Terminated(TerminationReason::MaxItersReached) => {
                    StopReason::Budget
                }
                // The line search ends the run in its own words when an
                // evaluation is refused; the wrapper says why.
                TerminationStatus::Terminated(TerminationReason::SolverExit(text)) => {
                    match counted.halt() {
                        Some(halt) => halt.stop_reason(),
                        None => StopReason::LineSearchFailure(text.clone()),
                    }
                }
                TerminationStatus::Terminated(other) => StopReason::Stall(other.text().into()),
                TerminationStatus::NotTerminated => StopReason::Stall("not terminated".into()),
            };
            (iterations, stop)
        }
        Err(e) => (counted.recorded(), stop_from_argmin(&e)),
    }
}
