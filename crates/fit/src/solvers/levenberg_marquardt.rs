//! Levenberg–Marquardt on the residual vector r(θ) with the analytic
//! Jacobian.
//!
//! Each step solves min ‖J δ + r‖² + μ‖D δ‖² (a trust region in the scaled
//! norm ‖Dδ‖, D from the Jacobian's column norms), accepting it when the
//! actual reduction of ‖r‖² agrees with the predicted one. Because the
//! misfit is a sum of squares whose Jacobian is exact, the method converges
//! quadratically near a small-residual minimum and is insensitive to the
//! poor scaling that defeats L-BFGS here.
//!
//! The `levenberg-marquardt` crate (a port of MINPACK's lmder, on nalgebra)
//! does the work; this module adapts the problem to it.
//!
//! # References
//! - J.J. Moré, "The Levenberg–Marquardt algorithm: implementation and
//!   theory", in *Numerical Analysis*, Lecture Notes in Mathematics 630,
//!   Springer 1978, pp. 105–116.
//! - J. Nocedal, S.J. Wright, *Numerical Optimization*, 2nd ed., Springer
//!   2006, §10.3.

use std::cell::Cell;

use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt, TerminationReason};
use nalgebra::{DMatrix, DVector, Dyn, Owned};

use super::counting::{Counted, Refusal};
use super::outcome::{StopReason, Tolerance};
use crate::objective::Evaluation;

/// Relative reduction of V and relative step below which a run has
/// converged: far below anything noise lets one resolve (a change of V by
/// 1e-8 is 1e-6 of one σ² over 41 points), and looser settings do not save
/// time where the problem is well conditioned, while tighter ones cost
/// thousands of evaluations at small λ where it is not.
const LM_TOLERANCE: f64 = 1e-8;

/// The tolerance on the relative reduction of V of the fits along the λ
/// path, which only locate λ: their criterion values change by far less
/// than between path points. (The step tolerance stays at
/// [`LM_TOLERANCE`]: MINPACK's step test fires as soon as the trust region
/// has shrunk, and at 1e-5 it ended path fits after a few rejected steps,
/// far from their minimum.)
const PATH_TOLERANCE: f64 = 1e-6;

/// Residual reported at trial points the forward model refuses.
const REFUSED_RESIDUAL: f64 = 1e8;

/// Initial trust-region radius relative to ‖Dθ‖: small, because θ holds
/// logarithms and a step of a few units already changes H_k by e^k.
const STEP_BOUND: f64 = 0.1;

struct Adapter<'c, 'o, 'a> {
    counted: &'c Counted<'o, 'a>,
    theta: DVector<f64>,
    current: Result<Evaluation, Refusal>,
    jacobians: Cell<usize>,
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Adapter<'_, '_, '_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, theta: &DVector<f64>) {
        self.theta.copy_from(theta);
        // The Jacobian costs about 1.4 μ-evaluations in the forward model's
        // one-pass scheme, so it is computed with every trial point.
        self.current = self.counted.evaluate(theta.as_slice(), true);
    }

    fn params(&self) -> DVector<f64> {
        self.theta.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        match &self.current {
            Ok(e) => Some(e.residuals.clone()),
            // A trial point the forward model refuses (an absurd material far
            // outside the trust region's intent) is reported as a very poor
            // point, so the trust region shrinks instead of the run ending;
            // a halted run (budget, abandonment) still ends.
            Err(Refusal::Halted(_)) => None,
            Err(Refusal::Failed(_)) => Some(DVector::from_element(
                self.counted.objective().residual_count(),
                REFUSED_RESIDUAL,
            )),
        }
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        self.jacobians.set(self.jacobians.get() + 1);
        self.current.as_ref().ok().and_then(|e| e.jacobian.clone())
    }
}

/// Minimises from `start`; returns (iterations, stop reason).
pub(crate) fn minimize(
    counted: &Counted<'_, '_>,
    start: &[f64],
    tolerance: Tolerance,
) -> (usize, StopReason) {
    let tol = match tolerance {
        Tolerance::Path => PATH_TOLERANCE,
        Tolerance::Final => LM_TOLERANCE,
    };
    let theta = DVector::from_column_slice(start);
    // Evaluated at the start once, as `set_params` would.
    let adapter = Adapter {
        counted,
        theta,
        current: counted.evaluate(start, true),
        jacobians: Cell::new(0),
    };
    let n = start.len();
    let budget = counted.budget();
    let solver = LevenbergMarquardt::new()
        .with_ftol(tol)
        .with_xtol(LM_TOLERANCE)
        .with_gtol(1e-12)
        .with_stepbound(STEP_BOUND)
        .with_patience((budget / (n + 1)).max(1));
    let (adapter, report) = solver.minimize(adapter);
    let stop = match report.termination {
        TerminationReason::Converged { ftol, xtol } => StopReason::Converged(match (ftol, xtol) {
            (true, true) => format!("relative reduction and step below {tol:e}"),
            (true, false) => format!("relative reduction of V below {tol:e}"),
            _ => format!("relative step below {LM_TOLERANCE:e}"),
        }),
        TerminationReason::Orthogonal => {
            StopReason::Converged("residuals orthogonal to the Jacobian".into())
        }
        TerminationReason::ResidualsZero => StopReason::Converged("zero residuals".into()),
        TerminationReason::LostPatience => StopReason::Budget,
        TerminationReason::NoImprovementPossible(what) => StopReason::Stall(format!(
            "no further improvement possible in {what} at machine precision"
        )),
        TerminationReason::User(_) | TerminationReason::Numerical(_) => match &adapter.current {
            Err(refusal) => refusal.stop_reason(),
            Ok(_) => StopReason::ModelFailure("non-finite residuals".into()),
        },
        other => StopReason::Stall(format!("{other:?}")),
    };
    (adapter.jacobians.get(), stop)
}
