//! Nelder–Mead (argmin) on V(θ): the paper's "amoeba".
//!
//! A simplex of n + 1 points moves by reflection, expansion, contraction
//! and shrinkage; no derivatives are used. The initial simplex steps each
//! log-parameter by 0.5 (a factor 1.65 in H_k). In sixteen or more
//! dimensions the method needs tens of thousands of evaluations on this
//! problem and often does not converge within its budget; the run says so.
//!
//! # References
//! - J.A. Nelder, R. Mead, "A simplex method for function minimization",
//!   Computer Journal 7 (1965) 308–313.

use argmin::core::{CostFunction, Executor, State, TerminationReason, TerminationStatus};
use argmin::solver::neldermead::NelderMead;
use nalgebra::DVector;

use super::counting::{Counted, stop_from_argmin};
use super::outcome::StopReason;

/// Edge of the initial simplex in log-parameters.
const SIMPLEX_STEP: f64 = 0.5;

/// Minimises from `start`; returns (iterations, stop reason).
pub(crate) fn minimize(counted: &Counted<'_, '_>, start: &[f64]) -> (usize, StopReason) {
    let x0 = DVector::from_column_slice(start);
    let mut simplex = vec![x0.clone()];
    for j in 0..start.len() {
        let mut x = x0.clone();
        x[j] += SIMPLEX_STEP;
        simplex.push(x);
    }
    let solver = match NelderMead::new(simplex).with_sd_tolerance(1e-10) {
        Ok(s) => s,
        Err(e) => return (0, StopReason::Stall(e.to_string())),
    };
    let budget = counted.budget() as u64;
    // argmin evaluates the whole initial simplex before its first iteration
    // and panics when the budget refuses one of those evaluations: a budget
    // that cannot pay for the simplex ends the run at its start point, as
    // the other methods end a run their budget cuts short.
    if budget <= start.len() as u64 {
        let _ = counted.cost(&x0);
        return (0, StopReason::Budget);
    }
    let result = Executor::new(counted, solver)
        .configure(|state| state.max_iters(budget))
        .run();
    match result {
        Ok(result) => {
            let state = result.state();
            let stop = match state.get_termination_status() {
                TerminationStatus::Terminated(TerminationReason::SolverConverged) => {
                    StopReason::Converged("simplex spread of V below 1e-10".into())
                }
                TerminationStatus::Terminated(TerminationReason::MaxItersReached) => {
                    StopReason::Budget
                }
                TerminationStatus::Terminated(other) => StopReason::Stall(other.text().into()),
                TerminationStatus::NotTerminated => StopReason::Stall("not terminated".into()),
            };
            (state.get_iter() as usize, stop)
        }
        Err(e) => (counted.recorded(), stop_from_argmin(&e)),
    }
}
