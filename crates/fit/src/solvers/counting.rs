//! The objective as one solver run sees it: evaluations counted against a
//! budget, the best point and the convergence history kept, and a hopeless
//! exploratory start abandoned.
//!
//! The objective ([`crate::objective`]) is a pure function of θ; a run's
//! bookkeeping lives here, in a wrapper made afresh for every run (as
//! argmin's `core::Problem` counts the evaluations of the problem it wraps).
//! The wrapper is what the solvers are given: Levenberg–Marquardt reads its
//! residuals and Jacobian, argmin's solvers its `CostFunction` V = Σ r² and
//! `Gradient` 2Jᵀr.
//!
//! A run ends in one of two typed ways the wrapper decides ([`Halt`]): the
//! budget is used up, or the start was abandoned. Once either holds, every
//! further evaluation is refused with that reason, which ends any solver;
//! the stop reason is read from the type, never from an error's text.
//!
//! The solvers only take `&self` (argmin's traits do), so the counters are
//! cells; they belong to this one run and die with it.

use std::cell::{Cell, RefCell};
use std::fmt;

use argmin::core::{CostFunction, Error as ArgminError, Gradient};
use nalgebra::DVector;

use super::outcome::StopReason;
use crate::error::FitError;
use crate::objective::{Evaluation, Objective};

/// V reported to argmin at a trial point the forward model refuses (an
/// absurd material a long line-search step or a simplex move produced): a
/// very poor but finite value, so the line search backtracks and the simplex
/// contracts instead of the run ending. Running out of budget still ends it.
const REFUSED_OBJECTIVE: f64 = 1e30;

/// When an exploratory start is given up: its best V is still above
/// `above` after `after` evaluations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Abandonment {
    /// Evaluations after which the test applies.
    pub after: usize,
    /// The best V must be at or below this by then.
    pub above: f64,
}

impl Abandonment {
    /// The stop reason of an abandoned run.
    pub(crate) fn stop_reason(&self) -> StopReason {
        StopReason::Abandoned(format!(
            "V still above {:.4e} after {} evaluations",
            self.above, self.after
        ))
    }
}

/// Why a run may evaluate no further.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Halt {
    /// The budget of this many evaluations is used up.
    Budget(usize),
    /// The start was abandoned as hopeless.
    Abandoned(Abandonment),
}

impl Halt {
    /// The stop reason of a run that ended this way.
    pub(crate) fn stop_reason(&self) -> StopReason {
        match self {
            Halt::Budget(_) => StopReason::Budget,
            Halt::Abandoned(rule) => rule.stop_reason(),
        }
    }
}

impl fmt::Display for Halt {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Halt::Budget(budget) => {
                write!(f, "the budget of {budget} objective evaluations is used up")
            }
            Halt::Abandoned(rule) => write!(
                f,
                "abandoned: V still above {:.4e} after {} evaluations",
                rule.above, rule.after
            ),
        }
    }
}

/// Carried through argmin as its error's value, so that the solver drivers
/// recover it by type ([`stop_from_argmin`]).
impl std::error::Error for Halt {}

/// An evaluation that gave no residuals.
#[derive(Debug)]
pub(crate) enum Refusal {
    /// The run is over: the solver must stop.
    Halted(Halt),
    /// The objective failed at this θ (a material or shift the forward
    /// model refuses): the solver may back off and go on.
    Failed(FitError),
}

impl Refusal {
    /// The stop reason of a run that ended on this refusal.
    pub(crate) fn stop_reason(&self) -> StopReason {
        match self {
            Refusal::Halted(halt) => halt.stop_reason(),
            Refusal::Failed(error) => StopReason::ModelFailure(error.to_string()),
        }
    }
}

/// What a finished run leaves: its best point and its record.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Tally {
    /// The best (V, θ) evaluated, if any evaluation succeeded.
    pub best: Option<(f64, Vec<f64>)>,
    /// Evaluations made (refused ones not counted).
    pub evaluations: usize,
    /// (evaluations, best V so far) after every successful evaluation.
    pub history: Vec<(usize, f64)>,
    /// The rule under which the run was abandoned, if it was.
    pub abandoned: Option<Abandonment>,
}

/// The objective with one run's budget, best point, history and
/// abandonment.
pub(crate) struct Counted<'o, 'a> {
    objective: &'o Objective<'a>,
    budget: usize,
    abandonment: Option<Abandonment>,
    evaluations: Cell<usize>,
    best: RefCell<Option<(f64, Vec<f64>)>>,
    history: RefCell<Vec<(usize, f64)>>,
    abandoned: Cell<bool>,
}

impl<'o, 'a> Counted<'o, 'a> {
    /// A run of at most `budget` evaluations of `objective`.
    pub(crate) fn new(objective: &'o Objective<'a>, budget: usize) -> Self {
        Counted {
            objective,
            budget,
            abandonment: None,
            evaluations: Cell::new(0),
            best: RefCell::new(None),
            history: RefCell::new(Vec::new()),
            abandoned: Cell::new(false),
        }
    }

    /// The same run, abandoned under `rule` when it is given.
    pub(crate) fn abandoning(mut self, rule: Option<Abandonment>) -> Self {
        self.abandonment = rule;
        self
    }

    /// The objective evaluated.
    pub(crate) fn objective(&self) -> &Objective<'a> {
        self.objective
    }

    /// The evaluations allowed.
    pub(crate) fn budget(&self) -> usize {
        self.budget
    }

    /// Successful evaluations so far (the history's length).
    pub(crate) fn recorded(&self) -> usize {
        self.history.borrow().len()
    }

    /// Why the next evaluation would be refused, if it would be.
    pub(crate) fn halt(&self) -> Option<Halt> {
        match self.abandonment {
            Some(rule) if self.abandoned.get() => Some(Halt::Abandoned(rule)),
            _ if self.evaluations.get() >= self.budget => Some(Halt::Budget(self.budget)),
            _ => None,
        }
    }

    /// Residuals, and the Jacobian when `with_jacobian`; counted against
    /// the budget and recorded when they exist.
    pub(crate) fn evaluate(
        &self,
        theta: &[f64],
        with_jacobian: bool,
    ) -> Result<Evaluation, Refusal> {
        if let Some(halt) = self.halt() {
            return Err(Refusal::Halted(halt));
        }
        self.evaluations.set(self.evaluations.get() + 1);
        let evaluation = self
            .objective
            .evaluate(theta, with_jacobian)
            .map_err(Refusal::Failed)?;
        self.record(theta, evaluation.objective());
        Ok(evaluation)
    }

    fn record(&self, theta: &[f64], objective: f64) {
        let mut best = self.best.borrow_mut();
        if best.as_ref().is_none_or(|(v, _)| objective < *v) {
            *best = Some((objective, theta.to_vec()));
        }
        let best_value = best.as_ref().map_or(objective, |(v, _)| *v);
        let evaluations = self.evaluations.get();
        self.history.borrow_mut().push((evaluations, best_value));
        if let Some(rule) = self.abandonment
            && evaluations >= rule.after
            && best_value > rule.above
        {
            self.abandoned.set(true);
        }
    }

    /// The run's best point and record.
    pub(crate) fn into_tally(self) -> Tally {
        Tally {
            best: self.best.into_inner(),
            evaluations: self.evaluations.get(),
            history: self.history.into_inner(),
            abandoned: self.abandonment.filter(|_| self.abandoned.get()),
        }
    }
}

/// The stop reason of an error that came back through argmin: the run's
/// own [`Halt`] when the wrapper raised it (carried as the error's value),
/// else a line-search failure in argmin's words.
pub(crate) fn stop_from_argmin(error: &argmin::core::Error) -> StopReason {
    match error.downcast_ref::<Halt>() {
        Some(halt) => halt.stop_reason(),
        None => StopReason::LineSearchFailure(error.to_string()),
    }
}

impl CostFunction for &Counted<'_, '_> {
    type Param = DVector<f64>;
    type Output = f64;

    fn cost(&self, theta: &Self::Param) -> Result<f64, ArgminError> {
        match self.evaluate(theta.as_slice(), false) {
            Ok(e) => Ok(e.objective()),
            Err(Refusal::Failed(_)) => Ok(REFUSED_OBJECTIVE),
            Err(Refusal::Halted(halt)) => Err(ArgminError::new(halt)),
        }
    }
}

impl Gradient for &Counted<'_, '_> {
    type Param = DVector<f64>;
    type Gradient = DVector<f64>;

    fn gradient(&self, theta: &Self::Param) -> Result<Self::Gradient, ArgminError> {
        match self.evaluate(theta.as_slice(), true) {
            Ok(e) => {
                let jac = e
                    .jacobian
                    .ok_or_else(|| ArgminError::msg("the model returned no Jacobian"))?;
                Ok(2.0 * jac.transpose() * e.residuals)
            }
            Err(Refusal::Failed(_)) => Ok(DVector::zeros(theta.len())),
            Err(Refusal::Halted(halt)) => Err(ArgminError::new(halt)),
        }
    }
}

#[cfg(test)]
mod tests;
