//! What a solver run reports, and how tightly it runs.

use serde::Serialize;

use crate::params::Method;

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
