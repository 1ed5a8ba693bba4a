//! The data-driven choice of the smoothness weight λ.
//!
//! Fits are computed along a decreasing path λ_j = 10^{4−j} (warm-started,
//! so each costs a few Levenberg–Marquardt steps), then refined in ln λ.
//!
//! - Discrepancy principle (σ measured): the largest λ whose misfit
//!   χ²(λ) = Σ r_i² does not exceed N, the expected χ² of the truth, and
//!   whose residual signs pass the runs test of [`crate::quality`]; the
//!   smoothest model the noise cannot tell from the data by either of the
//!   tests its fit is judged by. Bisection in ln λ between the last λ that
//!   fails and the first that passes refines it. (Residual whiteness as a
//!   condition on λ: Hansen, Kilmer and Kjeldsen; Rust and O'Leary. The
//!   driver's λ module says where the runs condition stops.)
//! - Marginal likelihood (σ unknown, the default): the λ that makes the
//!   data most probable when the noise level is integrated out. In the
//!   Gaussian linearisation at the optimum θ̂(λ), with data Jacobian J_d,
//!   penalty matrix L of rank k (second differences of ln H_k: k = n − 2),
//!   m₀ = p − k unpenalised directions of the p free parameters (a power-law
//!   spectrum, and the scale without an anchor), H = J_dᵀJ_d + λLᵀL and the
//!   penalised objective V̂ = misfit + λ‖Lθ̂‖²,
//!
//!     −2 ln p(data | λ) = (N − m₀) ln V̂ + ln det H − k ln λ + const,
//!
//!   after profiling the noise variance σ̂² = V̂/(N − m₀) (Wahba's GML, the
//!   restricted likelihood of the smoothing-spline literature). It asks the
//!   noise level of the data rather than assuming it, and unlike GCV it has
//!   no tendency to run to λ → 0 on few points, where GCV's minimum is
//!   shallow and often at the interpolating end. Its minimum is located
//!   between the path points by a parabola in ln λ (the driver's λ
//!   module).
//!
//!   The profiled σ̂² at the criterion's minimum is the restricted (REML)
//!   estimate of the noise: for a linear model with the smoothness prior
//!   that λ expresses, V̂ = yᵀ(I − A)y (A the influence matrix) has the
//!   expectation σ²(N − m₀), so V̂/(N − m₀) is unbiased there. It is the
//!   noise estimate of a fit without a sigma column
//!   (`Trial::evidence_noise_variance`, taken at the criterion's minimum).
//! - Generalised cross-validation (kept for comparison): the λ minimising
//!   GCV(λ) = N·misfit/(N − t(λ))², t the influence trace of
//!   `analysis`.
//!
//! # References
//! - V.A. Morozov, "On the solution of functional equations by the method of
//!   regularization", Soviet Math. Dokl. 7 (1966) 414–417.
//! - G. Wahba, "A comparison of GCV and GML for choosing the smoothing
//!   parameter in the generalized spline smoothing problem", Ann. Statist.
//!   13 (1985) 1378–1402.
//! - D.J.C. MacKay, "Bayesian interpolation", Neural Comput. 4 (1992)
//!   415–447.
//! - P.C. Hansen, M.E. Kilmer, R.H. Kjeldsen, "Exploiting residual
//!   information in the parameter choice for discrete ill-posed problems",
//!   BIT 46 (2006) 41–59.
//! - B.W. Rust, D.P. O'Leary, "Residual periodograms for choosing
//!   regularization parameters for ill-posed problems", Inverse Problems
//!   24 (2008) 034005.
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
    /// Marginal likelihood with the noise level profiled out (GML).
    MarginalLikelihood,
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
    /// Penalised objective V̂ = misfit + λ‖Lθ‖² (without the E1 bound).
    pub penalised: f64,
    /// ln det(J_dᵀJ_d + λLᵀL).
    pub log_det: f64,
    /// Rank k of the penalty.
    pub penalty_rank: usize,
    /// Free parameters p.
    pub free: usize,
    /// Whether the residual signs pass the runs test of
    /// [`crate::quality`] at its level (or are too few to test).
    pub random_signs: bool,
}

impl Trial {
    /// GCV(λ) for N data points.
    pub fn gcv(&self, n: usize) -> f64 {
        let dof = (n as f64 - self.effective_parameters).max(0.5);
        n as f64 * self.misfit / (dof * dof)
    }

    /// −2 ln p(data | λ) up to a constant (the module doc).
    pub fn marginal_likelihood(&self, n: usize) -> f64 {
        let unpenalised = self.free.saturating_sub(self.penalty_rank) as f64;
        let dof = (n as f64 - unpenalised).max(1.0);
        dof * self.penalised.max(f64::MIN_POSITIVE).ln() + self.log_det
            - self.penalty_rank as f64 * self.lambda.max(f64::MIN_POSITIVE).ln()
    }

    /// The noise variance the marginal likelihood profiles out,
    /// σ̂² = V̂/(N − m₀) (the module doc), in units of the residuals (for
    /// relative residuals: the relative variance of μ).
    pub fn evidence_noise_variance(&self, n: usize) -> f64 {
        let unpenalised = self.free.saturating_sub(self.penalty_rank) as f64;
        self.penalised / (n as f64 - unpenalised).max(1.0)
    }

    /// The criterion `rule` minimises (GCV for a fixed λ: unused).
    pub fn criterion(&self, rule: LambdaRule, n: usize) -> f64 {
        match rule {
            LambdaRule::MarginalLikelihood => self.marginal_likelihood(n),
            _ => self.gcv(n),
        }
    }
}

/// The λ values of the path.
pub(crate) fn path() -> Vec<f64> {
    (0..PATH_LENGTH)
        .map(|j| LAMBDA_MAX * 10f64.powi(-(j as i32)))
        .collect()
}
