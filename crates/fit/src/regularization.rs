//! The data-driven choice of the smoothness weight λ.
//!
//! Fits are computed along a decreasing path λ_j = 10^{4−j} (warm-started,
//! so each costs a few Levenberg–Marquardt steps), then refined in ln λ.
//!
//! - Discrepancy principle (σ measured): the largest λ whose misfit
//!   χ²(λ) = Σ r_i² does not exceed N, the expected χ² of the truth; the
//!   smoothest model the noise cannot tell from the data. Bisection in ln λ
//!   between the last λ above and the first below refines it.
//! - Generalised cross-validation (σ unknown): the λ minimising
//!   GCV(λ) = N·misfit/(N − t(λ))², t the influence trace of
//!   [`crate::analysis`]; golden-section refinement in ln λ.
//!
//! # References
//! - V.A. Morozov, "On the solution of functional equations by the method of
//!   regularization", Soviet Math. Dokl. 7 (1966) 414–417.
//! - G.H. Golub, M. Heath, G. Wahba, "Generalized cross-validation as a
//!   method for choosing a good ridge parameter", Technometrics 21 (1979)
//!   215–223.

use serde::Serialize;

/// Largest λ of the path.
pub const LAMBDA_MAX: f64 = 1e4;
/// Number of path points (one per decade).
pub const PATH_LENGTH: usize = 13;
/// Refinement steps in ln λ.
pub const REFINEMENTS: usize = 5;

/// How λ was chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LambdaRule {
    /// Given by the user.
    Fixed,
    /// Morozov's discrepancy principle, χ² = N.
    Discrepancy,
    /// Generalised cross-validation.
    Gcv,
}

/// One fit along the λ path.
#[derive(Debug, Clone)]
pub(crate) struct Trial {
    pub lambda: f64,
    pub theta: Vec<f64>,
    /// Σ data residuals².
    pub misfit: f64,
    /// Influence trace t(λ).
    pub effective_parameters: f64,
}

impl Trial {
    /// GCV(λ) for N data points.
    pub fn gcv(&self, n: usize) -> f64 {
        let dof = (n as f64 - self.effective_parameters).max(0.5);
        n as f64 * self.misfit / (dof * dof)
    }
}

/// The λ values of the path.
pub(crate) fn path() -> Vec<f64> {
    (0..PATH_LENGTH)
        .map(|j| LAMBDA_MAX * 10f64.powi(-(j as i32)))
        .collect()
}
