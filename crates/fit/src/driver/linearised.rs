//! The fit at another λ predicted from one fit's Gauss–Newton
//! linearisation, without running the solver.
//!
//! At the optimum θ̂ of V_λ₀ the residuals are, to first order in Δ = θ − θ̂,
//!
//! ```text
//! r_d(θ) ≈ r_d + J_d Δ                     (data, N rows)
//! r_s(θ; λ) ≈ √(λ/λ₀) (r_s + J_s Δ)        (smoothness: √λ times second differences of ln H)
//! r_b(θ) ≈ r_b + J_b Δ                     (the E1_max bound)
//! ```
//!
//! so the fit at λ is, in that model, the linear least-squares problem
//! min_Δ ‖r_d + J_dΔ‖² + (λ/λ₀)‖r_s + J_sΔ‖² + ‖r_b + J_bΔ‖², solved here by
//! the SVD of the stacked n-column matrix: microseconds, against a few
//! forward-model evaluations for each solver run it replaces. Its misfit,
//! residual signs and curvature are those a run at λ would report, to the
//! accuracy of the linearisation, which is what smoothing-spline codes rely
//! on when they choose λ from one decomposition (Wahba 1990, §4).
//!
//! The λ rules use it to locate λ between path points; a solver run at the
//! located λ, started from the predicted θ, then confirms it
//! ([`super::lambda`]).
//!
//! # References
//! - G. Wahba, *Spline Models for Observational Data*, SIAM 1990, ch. 4.
//! - Å. Björck, *Numerical Methods for Least Squares Problems*, SIAM 1996,
//!   §2.1 and §9.2 (Gauss–Newton).

use nalgebra::{DMatrix, DVector};

use crate::analysis::curvature;
use crate::error::FitError;
use crate::objective::{Evaluation, Objective};
use crate::quality::{RUNS_P_VALUE, runs_test};
use crate::regularization::Trial;

/// Singular values below this fraction of the largest are treated as zero
/// in the least-squares solve: directions the data and the penalty leave
/// undetermined keep their value rather than running off.
const RELATIVE_RANK_TOLERANCE: f64 = 1e-12;

/// One fit's residuals and Jacobian, split into the data, smoothness and
/// bound rows.
pub(super) struct Linearisation {
    /// λ₀ of the fit.
    lambda: f64,
    /// θ̂ of the fit.
    theta: Vec<f64>,
    residuals: DVector<f64>,
    jacobian: DMatrix<f64>,
    /// N: data rows.
    data_count: usize,
    /// Rows of the smoothness penalty.
    smoothness_count: usize,
    /// Whether σ was measured (the curvature's noise variance is then 1).
    known_sigma: bool,
}

impl Linearisation {
    /// The linearisation of `objective` at `trial`'s θ and λ, from the
    /// evaluation `e` there (with its Jacobian).
    pub(super) fn of(
        objective: &Objective<'_>,
        trial: &Trial,
        e: Evaluation,
    ) -> Result<Self, FitError> {
        let jacobian = e
            .jacobian
            .ok_or(FitError::Internal("the forward model returned no Jacobian"))?;
        // The SVD of a matrix holding NaN never converges: a shift or
        // modulus beyond the floating-point range is refused here.
        if jacobian
            .iter()
            .chain(e.residuals.iter())
            .any(|x| !x.is_finite())
        {
            return Err(FitError::setting(
                "shift",
                "the residuals or their derivatives are not finite numbers at this fit's shift \
                 (a reduced speed or frequency beyond the floating-point range)",
            ));
        }
        let data_count = objective.data_rows();
        Ok(Linearisation {
            lambda: trial.lambda,
            theta: trial.theta.clone(),
            smoothness_count: e.residuals.len() - data_count - 1,
            residuals: e.residuals,
            jacobian,
            data_count,
            known_sigma: objective.noise_known,
        })
    }

    /// λ₀ of the fit linearised.
    pub(super) fn lambda(&self) -> f64 {
        self.lambda
    }

    /// θ̂ of the fit linearised.
    pub(super) fn theta(&self) -> &[f64] {
        &self.theta
    }

    /// The trial a fit at `lambda` would give in the linear model, with the
    /// runs test over `groups` (rows by temperature, by speed).
    pub(super) fn predict(&self, lambda: f64, groups: &[Vec<usize>]) -> Trial {
        let (n, k) = (self.data_count, self.smoothness_count);
        let scale = (lambda / self.lambda).sqrt();
        let mut a = self.jacobian.clone();
        let mut b = -self.residuals.clone();
        a.rows_mut(n, k).scale_mut(scale);
        b.rows_mut(n, k).scale_mut(scale);
        let svd = a.clone().svd(true, true);
        let floor = svd.singular_values.max() * RELATIVE_RANK_TOLERANCE;
        let step = svd
            .solve(&b, floor)
            .unwrap_or_else(|_| DVector::zeros(self.theta.len()));
        let predicted = &a * &step - &b;
        let data: Vec<f64> = predicted.rows(0, n).iter().copied().collect();
        let misfit = data.iter().map(|r| r * r).sum::<f64>();
        let smoothness = predicted.rows(n, k).norm_squared();
        let c = curvature(&a, n, misfit, self.known_sigma.then_some(1.0));
        let random_signs = runs_test(&data, groups).is_none_or(|r| r.p_value >= RUNS_P_VALUE);
        Trial {
            lambda,
            theta: self
                .theta
                .iter()
                .zip(step.iter())
                .map(|(t, d)| t + d)
                .collect(),
            misfit,
            effective_parameters: c.effective_parameters,
            penalised: misfit + smoothness,
            log_det: c.log_det,
            penalty_rank: k,
            free: self.theta.len(),
            random_signs,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::Measurements;
    use crate::parametrization::Parametrization;
    use crate::params::{Method, ModulusAnchor};
    use crate::quality::speed_ordered_groups;
    use crate::solvers::counting::Counted;
    use crate::solvers::{Tolerance, run};
    use rollfit_model::{Prony, Scene, ViscoelasticModulus};

    /// The fit at `lambda` from `from` to the final tolerance: its trial
    /// (λ, θ and misfit; the rest unused here).
    fn fitted(objective: &mut Objective<'_>, lambda: f64, from: &[f64]) -> Trial {
        objective.lambda = lambda;
        let r = run(
            Method::LevenbergMarquardt,
            Counted::new(objective, 5000),
            from,
            Tolerance::Final,
        );
        let misfit = objective.evaluate(&r.theta, false).unwrap().misfit;
        Trial {
            lambda,
            theta: r.theta,
            misfit,
            effective_parameters: 0.0,
            penalised: 0.0,
            log_det: 0.0,
            penalty_rank: 0,
            free: 0,
            random_signs: true,
        }
    }

    /// The slow oracle: the misfit a fit at a neighbouring λ reaches,
    /// against the linearisation's prediction from the fit at λ₀. At λ₀
    /// itself the prediction is the fit (no step); at λ₀·2 and λ₀/2 it is
    /// within 2 % of the refit's misfit and far closer to it than the
    /// misfit at λ₀ (which is what "no prediction" would say).
    #[test]
    fn predictions_match_refits_at_neighbouring_lambdas() {
        let setup = crate::params::example_setup();
        let tau: Vec<f64> = (0..9).map(|k| 10f64.powf(k as f64 - 6.0)).collect();
        let truth = Prony::new(
            1e9,
            tau.iter()
                .map(|t| 2e8 * (-(t.log10() + 2.0).powi(2) / 4.0).exp())
                .collect(),
            tau.clone(),
        )
        .unwrap();
        let speeds: Vec<f64> = (0..25).map(|i| 1e-8 * 10f64.powf(0.3 * i as f64)).collect();
        let scene = Scene::new(
            setup.geometry,
            setup.substrate,
            setup.contact,
            truth.clone(),
        )
        .unwrap();
        // A fixed, deterministic 1 % wiggle for noise.
        let mu: Vec<f64> = scene
            .friction_sweep(&speeds)
            .unwrap()
            .iter()
            .enumerate()
            .map(|(i, m)| m * (1.0 + 0.01 * (1.7 * i as f64).sin()))
            .collect();
        let sigma = mu.iter().map(|m| 0.01 * m).collect();
        let data = Measurements::new(speeds, mu, Some(sigma), None).unwrap();
        let anchor = ModulusAnchor {
            omega: 0.0,
            modulus: truth.static_modulus(),
            source: "E0",
        };
        let param = Parametrization::new(tau.clone(), Some(anchor));
        let start = param.theta_of(truth.static_modulus(), &vec![1e8; tau.len()]);
        let mut objective = Objective {
            setup: &setup,
            data: &data,
            scales: data.residual_scales(),
            param,
            shift: None,
            lambda: 1.0,
            e1_max: 1e10,
            tolerance: 1e-8,
            vertical: None,
            dma: None,
            friction_factor: false,
            noise_known: true,
        };
        let groups = speed_ordered_groups(&data);
        let lambda = 10.0;
        let base = fitted(&mut objective, lambda, &start);
        objective.lambda = lambda;
        let e = objective.evaluate(&base.theta, true).unwrap();
        let linearisation = Linearisation::of(&objective, &base, e).unwrap();
        let same = linearisation.predict(lambda, &groups);
        assert!(
            (same.misfit / base.misfit - 1.0).abs() < 1e-6,
            "{}",
            same.misfit
        );
        for t in same.theta.iter().zip(&base.theta) {
            assert!((t.0 - t.1).abs() < 1e-4, "{t:?}");
        }
        for other in [2.0 * lambda, 0.5 * lambda] {
            let predicted = linearisation.predict(other, &groups);
            let refit = fitted(&mut objective, other, &base.theta);
            let error = (predicted.misfit / refit.misfit - 1.0).abs();
            let unpredicted = (base.misfit / refit.misfit - 1.0).abs();
            assert!(
                error < 0.02 && error < 0.2 * unpredicted,
                "λ {other}: predicted {} against the refit's {} (at λ₀ {})",
                predicted.misfit,
                refit.misfit,
                base.misfit
            );
        }
    }
}
