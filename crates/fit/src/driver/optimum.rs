//! What the chosen fit on one τ grid says about the material: curvature,
//! probed window, determined terms, the master curve with its bands, the
//! shift with its errors, goodness of fit and warnings (the method is
//! [`crate::analysis`]'s).

use nalgebra::DMatrix;

use crate::analysis::{
    Curvature, add_bias, curvature, modulus_of, modulus_point, probed_window, residual_dof,
};
use crate::error::FitError;
use crate::objective::Objective;
use crate::parametrization::{Mapped, Parametrization};
use crate::params::{Method, ValidFitParams};
use crate::quality::{FitQuality, assess};
use crate::regularization::{LambdaRule, Trial};
use crate::report::{LambdaRecord, ModelRecord, ModulusPoint, RunRecord, ShiftRecord, Window};
use crate::solvers::{SolverRun, StopReason};

/// Points per decade of the reported master curve.
const CURVE_DENSITY: f64 = 10.0;

/// The fit chosen on one τ grid and how it was reached.
pub(super) struct Chosen {
    /// The fit at the chosen λ.
    pub trial: Trial,
    /// The solver run that produced it.
    pub run: SolverRun,
    /// How λ was chosen.
    pub rule: LambdaRule,
    /// (λ, misfit, effective parameters) of every fit along the λ path.
    pub path: Vec<[f64; 3]>,
    /// (λ, criterion) along the path for the criterion rules.
    pub criterion: Vec<[f64; 2]>,
    /// Every solver run on the grid.
    pub runs: Vec<RunRecord>,
    /// θ of the fit at λ/10, for the smoothing bias of the bands.
    pub less_smoothed: Option<Vec<f64>>,
    /// The noise variance of the marginal likelihood at its minimum (σ
    /// unknown, λ by that rule): the fit's noise estimate.
    pub evidence_noise_variance: Option<f64>,
}

/// The analysed optimum on one τ grid.
#[derive(Debug, Clone)]
pub(super) struct Optimum {
    /// The master curve's Prony series.
    pub model: ModelRecord,
    /// The window the data's speeds probe.
    pub probed_window: Window,
    /// The fitted shift of a temperature set.
    pub shift: Option<ShiftRecord>,
    /// θ of the shift (for refits that continue from it).
    pub shift_theta: Vec<f64>,
    /// The optimiser.
    pub method: Method,
    /// V at the optimum.
    pub objective: f64,
    /// Σ r_i² over the data.
    pub misfit: f64,
    /// misfit/N.
    pub misfit_per_point: f64,
    /// Iterations of the final run.
    pub iterations: usize,
    /// How the final run ended.
    pub stop: StopReason,
    /// λ and how it was chosen.
    pub lambda: LambdaRecord,
    /// Effective number of parameters.
    pub effective_parameters: f64,
    /// √(s²).
    pub noise: f64,
    /// Goodness of fit.
    pub fit_quality: FitQuality,
    /// Things the user must know.
    pub warnings: Vec<String>,
    /// Every solver run.
    pub runs: Vec<RunRecord>,
    /// (evaluations, best V) of the final run.
    pub history: Vec<[f64; 2]>,
    /// The master curve over the probed window with 1σ bands.
    pub curve: Vec<ModulusPoint>,
    /// μ at the data speeds.
    pub mu: Vec<f64>,
    /// κ and its 1σ, when fitted (a joint fit's `friction_factor`).
    pub friction_factor: Option<(f64, f64)>,
}

/// κ and its 1σ, when fitted: the covariance's σ, scaled by the rolling
/// rows' own noise level where it exceeds the common one
/// ([`rolling_noise_ratio`]), and widened like the shifts' by the
/// smoothing bias (the change of κ in the fit at λ/10), added in
/// quadrature.
fn friction_factor(
    objective: &Objective<'_>,
    chosen: &Chosen,
    jac: &DMatrix<f64>,
    residuals: &nalgebra::DVector<f64>,
    c: &Curvature,
) -> Option<(f64, f64)> {
    let k = objective.friction_factor_index()?;
    let value = chosen.trial.theta[k].exp();
    let bias = chosen
        .less_smoothed
        .as_ref()
        .map_or(0.0, |less| less[k].exp() - value);
    let ratio = rolling_noise_ratio(jac, residuals, objective.data.len(), c);
    let variance = ratio * value * value * c.covariance[(k, k)].max(0.0) + bias * bias;
    Some((value, variance.sqrt()))
}

/// The probed window `window` (rad/s), widened to a joint fit's DMA points
/// at their reduced frequencies: they probe E* there.
fn with_dma_window(
    objective: &Objective<'_>,
    theta: &[f64],
    mapped: &Mapped,
    window: (f64, f64),
) -> (f64, f64) {
    let Some(d) = &objective.dma else {
        return window;
    };
    let n_material = objective.param.free_count();
    let shift = objective.shift.as_ref().map(|s| (s, &theta[n_material..]));
    d.values(mapped, objective.param.tau(), shift)
        .reduced_omega
        .iter()
        .fold(window, |(lo, hi), &w| (lo.min(w), hi.max(w)))
}

/// A joint fit's rolling rows' noise variance at the optimum over the
/// common one s², at least 1: Helmert's variance component
/// s_R² = χ²_R/(N_R − p_R), p_R = Σ_{i ∈ R} J_i H⁺ J_iᵀ the rows' share of
/// the effective parameters. κ is fixed by the rolling rows, whose σ is
/// often estimated from fewer rows than the DMA's; the common s², set
/// mostly by the DMA rows, would understate κ's σ when the rolling σ was
/// estimated low.
fn rolling_noise_ratio(
    jac: &DMatrix<f64>,
    residuals: &nalgebra::DVector<f64>,
    rolling: usize,
    c: &Curvature,
) -> f64 {
    let s2 = c.noise_variance;
    let mut share = 0.0;
    let mut chi2 = 0.0;
    for i in 0..rolling {
        let row = jac.row(i);
        share += (row * &c.covariance * row.transpose())[(0, 0)] / s2;
        chi2 += residuals[i] * residuals[i];
    }
    let variance = chi2 / (rolling as f64 - share).max(1.0);
    (variance / s2).max(1.0)
}

/// The material at the optimum and its curvature.
struct Material<'p> {
    param: &'p Parametrization,
    mapped: Mapped,
    curvature: Curvature,
    omega_min: f64,
    omega_max: f64,
}

/// Curvature, window, determined terms, bands and the record of `chosen`,
/// the fit of `objective` under `params`.
pub(super) fn analyse(
    params: &ValidFitParams,
    objective: &mut Objective<'_>,
    chosen: Chosen,
) -> Result<Optimum, FitError> {
    objective.lambda = chosen.trial.lambda;
    let e = objective.evaluate(&chosen.trial.theta, true)?;
    let jac = e
        .jacobian
        .as_ref()
        .ok_or(FitError::Internal("the forward model returned no Jacobian"))?;
    let sigma_known = objective.noise_known;
    let n_rows = objective.data_rows();
    let noise_variance = match (sigma_known, &objective.dma) {
        (true, _) => Some(1.0),
        (false, Some(_)) => chosen.evidence_noise_variance,
        (false, None) => Some(e.misfit / residual_dof(jac, n_rows)),
    };
    let c = curvature(jac, n_rows, e.misfit, noise_variance);
    let param = &objective.param;
    let n_material = param.free_count();
    let mapped = param.map(&chosen.trial.theta[..n_material]);
    let prony = param.prony(&mapped)?;
    let window = probed_window(
        &params.setup,
        &prony,
        objective.reduced_range(&chosen.trial.theta),
    );
    let (omega_min, omega_max) = with_dma_window(objective, &chosen.trial.theta, &mapped, window);
    let n_shift = objective.shift.as_ref().map_or(0, |s| s.count());
    let shift_theta = chosen.trial.theta[n_material..].to_vec();
    let friction_factor = friction_factor(objective, &chosen, jac, &e.residuals, &c);
    let shift = objective.shift.as_ref().map(|s| {
        let mut block = c
            .covariance
            .view((n_material, n_material), (n_shift, n_shift))
            .into_owned();
        // A shift parameter that moving by one unit (a decade, or a factor
        // e of a law's constant) changes the misfit by less than one noise
        // unit is not determined by the data: the pseudo-inverse gives it
        // no variance, the truth is that it has no bound.
        for k in 0..n_shift {
            if c.sensitivity[n_material + k] < c.noise_variance {
                block[(k, k)] = f64::INFINITY;
            }
        }
        let mut record = s.record(&shift_theta, &block);
        if let Some(less) = &chosen.less_smoothed {
            record.add_bias(&s.record(&less[n_material..], &block));
        }
        record
    });
    let material = Material {
        param,
        mapped,
        curvature: c,
        omega_min,
        omega_max,
    };
    let model = material.record();
    let curve = material.curve(chosen.less_smoothed.as_deref())?;
    let c = &material.curvature;
    let mut warnings = fit_warnings(n_rows, params, &chosen, e.misfit, &model);
    let fit_quality = assess(
        &e.residuals.as_slice()[..n_rows],
        &objective.runs_groups(),
        c.effective_parameters,
        // A joint fit's residuals are in units of each part's σ (given,
        // or estimated from that part alone): its χ² is judged in them.
        sigma_known || objective.dma.is_some(),
        c.noise_variance.sqrt(),
    );
    warnings.extend(
        fit_quality
            .reasons
            .iter()
            .map(|r| format!("fit quality: {r}")),
    );
    Ok(Optimum {
        model,
        probed_window: Window {
            omega_min,
            omega_max,
        },
        shift,
        shift_theta,
        method: chosen.run.method,
        objective: e.objective(),
        misfit: e.misfit,
        misfit_per_point: e.misfit / n_rows as f64,
        iterations: chosen.run.iterations,
        stop: chosen.run.stop,
        lambda: LambdaRecord {
            value: chosen.trial.lambda,
            rule: chosen.rule,
            path: chosen.path,
            criterion: chosen.criterion,
        },
        effective_parameters: c.effective_parameters,
        noise: c.noise_variance.sqrt(),
        fit_quality,
        warnings,
        runs: chosen.runs,
        history: chosen
            .run
            .history
            .iter()
            .map(|&(k, v)| [k as f64, v])
            .collect(),
        curve,
        mu: e.mu,
        friction_factor,
    })
}

impl Material<'_> {
    /// The Prony series with which terms the data determine and the 1σ of
    /// each ln H_k.
    fn record(&self) -> ModelRecord {
        let (param, c) = (self.param, &self.curvature);
        let first = param.first_strength();
        let determined: Vec<bool> = param
            .tau()
            .iter()
            .enumerate()
            .map(|(k, &tau)| {
                let omega = 1.0 / tau;
                let near = omega >= self.omega_min / 10.0 && omega <= self.omega_max * 10.0;
                near && c.sensitivity[first + k] >= c.noise_variance
            })
            .collect();
        let ln_strength_sigma = (0..param.terms())
            .map(|k| c.covariance[(first + k, first + k)].max(0.0).sqrt())
            .collect();
        ModelRecord {
            kind: "prony",
            glassy_modulus: self.mapped.glassy_modulus(),
            static_modulus: self.mapped.static_modulus,
            tau: param.tau().to_vec(),
            strengths: self.mapped.strengths.clone(),
            determined,
            ln_strength_sigma,
        }
    }

    /// The master curve over the probed window with its 1σ bands, widened
    /// by the smoothing bias against the `less_smoothed` θ when given.
    fn curve(&self, less_smoothed: Option<&[f64]>) -> Result<Vec<ModulusPoint>, FitError> {
        let param = self.param;
        let n_material = param.free_count();
        // The material's block of the covariance is its marginal covariance.
        let material_covariance: DMatrix<f64> = self
            .curvature
            .covariance
            .view((0, 0), (n_material, n_material))
            .into_owned();
        let (omega_min, omega_max) = (self.omega_min, self.omega_max);
        let decades = (omega_max / omega_min).log10();
        let points = (decades * CURVE_DENSITY).ceil().max(1.0) as usize + 1;
        let other = less_smoothed.map(|theta| param.map(&theta[..n_material]));
        Ok((0..points)
            .map(|i| {
                let omega =
                    omega_min * (omega_max / omega_min).powf(i as f64 / (points - 1) as f64);
                let mut point = modulus_point(param, &self.mapped, &material_covariance, omega);
                if let Some(other) = &other {
                    add_bias(&mut point, modulus_of(other, param.tau(), omega));
                }
                point
            })
            .collect())
    }
}

/// The warnings about the chosen fit itself: no convergence,
/// the noise floor not reached, E1 at its bound, undetermined terms.
fn fit_warnings(
    n_rows: usize,
    params: &ValidFitParams,
    chosen: &Chosen,
    misfit: f64,
    model: &ModelRecord,
) -> Vec<String> {
    let mut warnings = Vec::new();
    if !chosen.run.stop.converged() {
        warnings.push(format!(
            "the final {} run did not converge: {}",
            chosen.run.method.name(),
            chosen.run.stop.describe()
        ));
    }
    if chosen.rule == LambdaRule::Discrepancy && misfit > n_rows as f64 * 1.5 {
        warnings.push(format!(
            "χ²/N = {:.2} stays above 1 at every λ: the model does not reach the noise floor \
             (underestimated σ, or physics the model lacks)",
            misfit / n_rows as f64
        ));
    }
    if model.glassy_modulus > 0.999 * params.e1_max {
        warnings.push(format!(
            "the glassy modulus E1 sits at its bound E1_max = {:e} Pa",
            params.e1_max
        ));
    }
    let determined = &model.determined;
    let undetermined = determined.iter().filter(|d| !**d).count();
    if undetermined > 0 {
        warnings.push(format!(
            "{undetermined} of {} relaxation times are not determined by the data \
             (marked in model.determined); they only extend E* outside the window",
            determined.len()
        ));
    }
    warnings
}
