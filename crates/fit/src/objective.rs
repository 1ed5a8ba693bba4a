//! The objective of Eq. (B3) as a residual vector, with its exact Jacobian.
//!
//! V(θ) = Σ_i [(μ_th(v_i; θ) − μ_i)/s_i]² + λ Σ_k (Δ² ln H_k)² + P(θ),
//!
//! s_i = σ_i when measured, else μ_i (relative weights, g_i = 1/μ_i²). The
//! second term is the smoothness penalty on the log-spectrum: second
//! differences of ln H_k on the log-spaced τ grid, which leave a power-law
//! spectrum free and penalise wiggles (the ill-posedness of Appendix B shows
//! up as neighbouring H_k trading off wildly). P keeps the glassy modulus
//! below E1_max: w·max(0, ln(E1/E1_max)), squared.
//!
//! ∂μ_th/∂θ comes from the forward model's one-pass Jacobian
//! ([`rollfit_model::Scene::friction_with_gradient`]) through the chain rule
//! of [`crate::parametrization`]. With vertical factors b_T a row at T is
//! the master curve under the load F/b_T ([`crate::vertical`]): the rows
//! are evaluated in groups of one load, with the same chain rule.
//!
//! The objective is a pure function of θ at a given λ: it holds no budget,
//! best point or history. The solvers see it through
//! [`crate::solvers::counting`], which counts evaluations against a budget,
//! keeps the best point and the history, and abandons hopeless starts; that
//! wrapper serves Levenberg–Marquardt (as residuals and Jacobian) and
//! argmin's solvers (as `CostFunction` V and `Gradient` 2Jᵀr).

use nalgebra::{DMatrix, DVector};
use rollfit_model::{Prony, Scene, VerticalShift};

use crate::data::Measurements;
use crate::error::FitError;
use crate::joint::DmaBlock;
use crate::parametrization::{Mapped, Parametrization};
use crate::params::RollingSetup;
use crate::quality::speed_ordered_groups;
use crate::shift::ShiftParam;
use crate::vertical::{LoadGroups, scene_under_load};

/// Weight of the E1_max penalty: one per cent above the bound costs as much
/// as a hundred standard deviations of misfit.
const BOUND_WEIGHT: f64 = 1e3;

/// Width (in ln E1) over which the bound residual turns from quadratic to
/// linear.
const BOUND_SOFTNESS: f64 = 0.01;

/// x²/(x + δ) and its derivative, for x ≥ 0.
fn smooth_excess(x: f64) -> (f64, f64) {
    let d = BOUND_SOFTNESS;
    (x * x / (x + d), x * (x + 2.0 * d) / ((x + d) * (x + d)))
}

/// V(θ) at one λ, as residuals and their Jacobian.
pub(crate) struct Objective<'a> {
    pub setup: &'a RollingSetup,
    pub data: &'a Measurements,
    /// s_i: σ_i when measured, else μ_i.
    pub scales: Vec<f64>,
    pub param: Parametrization,
    /// The temperature shift of a temperature set; its parameters follow
    /// the material's in θ.
    pub shift: Option<ShiftParam>,
    pub lambda: f64,
    pub e1_max: f64,
    /// The forward model's relative tolerance.
    pub tolerance: f64,
    /// A temperature set's known vertical factors (None: b_T = 1).
    pub vertical: Option<&'a VerticalShift>,
    /// A joint fit's DMA rows, after the rolling rows ([`crate::joint`]).
    pub dma: Option<DmaBlock>,
    /// Whether θ ends with ln κ, the rolling rows' μ being κ μ_th.
    pub friction_factor: bool,
    /// Whether the residuals are in units of a known σ (λ by the
    /// discrepancy principle, noise variance 1), else of weights known up
    /// to a common noise level (λ and that level by the marginal
    /// likelihood).
    pub noise_known: bool,
}

/// Residuals (and Jacobian) at one θ.
#[derive(Debug, Clone)]
pub(crate) struct Evaluation {
    /// Data residuals (rolling, then DMA), then smoothness, then the bound.
    pub residuals: DVector<f64>,
    /// ∂residuals/∂θ.
    pub jacobian: Option<DMatrix<f64>>,
    /// μ_th(v_i).
    pub mu: Vec<f64>,
    /// Σ data residuals² (χ² when σ is measured), rolling and DMA.
    pub misfit: f64,
}

impl Evaluation {
    /// V = Σ r².
    pub fn objective(&self) -> f64 {
        self.residuals.norm_squared()
    }
}

impl Objective<'_> {
    /// Rows of the residual vector.
    pub fn residual_count(&self) -> usize {
        self.data_rows() + self.smoothness_count() + 1
    }

    /// Rows of data residuals: the rolling rows, then two per DMA point.
    pub fn data_rows(&self) -> usize {
        self.data.len() + self.dma.as_ref().map_or(0, |d| 2 * d.points())
    }

    /// The data residuals' groups for the runs test: the rolling rows by
    /// temperature and speed, then each isotherm's E′ and E″ rows by ω.
    pub fn runs_groups(&self) -> Vec<Vec<usize>> {
        let mut groups = speed_ordered_groups(self.data);
        if let Some(d) = &self.dma {
            let n = self.data.len();
            for g in d.isotherm_groups() {
                groups.push(g.iter().map(|i| n + 2 * i).collect());
                groups.push(g.iter().map(|i| n + 2 * i + 1).collect());
            }
        }
        groups
    }

    /// Index in θ of ln κ, when κ is fitted.
    pub fn friction_factor_index(&self) -> Option<usize> {
        self.friction_factor.then(|| self.free_count() - 1)
    }

    /// The shift's parameters within θ.
    /// The refusal of a shift at θ that left the floating-point range.
    fn shift_beyond_range(&self, theta: &[f64]) -> FitError {
        match &self.shift {
            Some(shift) => shift.beyond_range(self.shift_theta(theta)),
            None => FitError::setting(
                "v",
                "a speed is not a positive finite number after the load's shift",
            ),
        }
    }

    fn shift_theta<'t>(&self, theta: &'t [f64]) -> &'t [f64] {
        let n = self.param.free_count();
        &theta[n..n + self.shift.as_ref().map_or(0, |s| s.count())]
    }

    fn smoothness_count(&self) -> usize {
        self.param.terms().saturating_sub(2)
    }

    /// Free parameters: the material's, then the shift's.
    pub fn free_count(&self) -> usize {
        self.param.free_count()
            + self.shift.as_ref().map_or(0, |s| s.count())
            + usize::from(self.friction_factor)
    }

    /// The speeds at which the master curve is evaluated: the measured ones,
    /// times a_T for a temperature set; and ∂ln a_T/∂θ_s per point.
    pub fn reduced_speeds(&self, theta: &[f64]) -> (Vec<f64>, Vec<Vec<f64>>) {
        match &self.shift {
            None => (self.data.speeds().to_vec(), Vec::new()),
            Some(shift) => {
                let (ln_a, grads) = shift.point_shifts(self.shift_theta(theta));
                let v = self
                    .data
                    .speeds()
                    .iter()
                    .zip(&ln_a)
                    .map(|(v, l)| v * l.exp())
                    .collect();
                (v, grads)
            }
        }
    }

    /// Smallest and largest reduced speed at θ, m/s.
    pub fn reduced_range(&self, theta: &[f64]) -> (f64, f64) {
        self.reduced_speeds(theta)
            .0
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            })
    }

    /// The scene for a mapped θ, under the set-up's load times
    /// `load_factor` (1/b_T of a row's temperature, else 1).
    pub fn scene(&self, m: &Mapped, load_factor: f64) -> Result<Scene<Prony>, FitError> {
        scene_under_load(
            self.setup,
            self.param.prony(m)?,
            self.tolerance,
            load_factor,
        )
    }

    /// Residuals, and the Jacobian when `with_jacobian`.
    pub fn evaluate(&self, theta: &[f64], with_jacobian: bool) -> Result<Evaluation, FitError> {
        if theta.iter().any(|t| !t.is_finite()) {
            return Err(FitError::setting(
                "parameters",
                "the optimiser produced a non-finite parameter",
            ));
        }
        let n_material = self.param.free_count();
        let m = self.param.map(&theta[..n_material]);
        let groups = LoadGroups::of(self.data, self.vertical)?;
        let scene_at = |factor: f64| self.scene(&m, factor);
        let n_data = self.data.len();
        let n_free = self.free_count();
        let (speeds, shift_grads) = self.reduced_speeds(theta);
        if speeds.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
            return Err(self.shift_beyond_range(theta));
        }
        let rows = self.residual_count();
        let kappa = self.friction_factor_index().map_or(1.0, |k| theta[k].exp());
        let mut residuals = DVector::zeros(rows);
        let mut jacobian = with_jacobian.then(|| DMatrix::zeros(rows, n_free));
        let mu = if let Some(jac) = jacobian.as_mut() {
            let fj = match &groups {
                Some(g) => g.friction_with_gradient(scene_at, &speeds)?,
                None => scene_at(1.0)?.friction_with_gradient(&speeds)?,
            };
            let np = fj.parameter_count;
            let mut grad_p = vec![0.0; np];
            let mut grad_theta = vec![0.0; n_material];
            for i in 0..n_data {
                let row = &fj.jacobian[i * np..(i + 1) * np];
                // Model parameters (E1, H) → (E0, H): E1 = E0 + ΣH.
                grad_p[0] = row[0];
                for k in 1..np {
                    grad_p[k] = row[k] + row[0];
                }
                self.param.pullback(&m, &grad_p, &mut grad_theta);
                // κ multiplies the quotients (κ = 1 leaves them bit for
                // bit as without a friction factor).
                let s = self.scales[i];
                for (j, g) in grad_theta.iter().enumerate() {
                    jac[(i, j)] = kappa * (g / s);
                }
                if let Some(d_ln_a) = shift_grads.get(i) {
                    for (k, d) in d_ln_a.iter().enumerate() {
                        jac[(i, n_material + k)] = kappa * (fj.d_ln_speed[i] * d / s);
                    }
                }
                if let Some(k) = self.friction_factor_index() {
                    jac[(i, k)] = kappa * (fj.mu[i] / s);
                }
            }
            fj.mu
        } else {
            match &groups {
                Some(g) => g.friction_sweep(scene_at, &speeds)?,
                None => scene_at(1.0)?.friction_sweep(&speeds)?,
            }
        };
        let mu: Vec<f64> = mu.into_iter().map(|m| kappa * m).collect();
        let mut misfit = 0.0;
        for i in 0..n_data {
            let r = (mu[i] - self.data.friction()[i]) / self.scales[i];
            residuals[i] = r;
            misfit += r * r;
        }
        let dma_misfit = match &self.dma {
            Some(d) => {
                let shift = self.shift.as_ref().map(|s| (s, self.shift_theta(theta)));
                d.fill(
                    &self.param,
                    &m,
                    shift,
                    &mut residuals,
                    jacobian.as_mut(),
                    n_data,
                )?
            }
            None => 0.0,
        };
        misfit += dma_misfit;
        self.penalties(theta, &m, &mut residuals, jacobian.as_mut());
        Ok(Evaluation {
            residuals,
            jacobian,
            mu,
            misfit,
        })
    }

    /// The smoothness rows, √λ (θ_{k+1} − 2θ_k + θ_{k−1}) over the ln H_k,
    /// after the data rows, and the glassy-modulus bound in the last row,
    /// with their Jacobian when given.
    fn penalties(
        &self,
        theta: &[f64],
        m: &Mapped,
        residuals: &mut DVector<f64>,
        mut jacobian: Option<&mut DMatrix<f64>>,
    ) {
        let n_data = self.data_rows();
        let rows = self.residual_count();
        let n_material = self.param.free_count();
        let root_lambda = self.lambda.sqrt();
        let first = self.param.first_strength();
        for k in 0..self.smoothness_count() {
            let row = n_data + k;
            let (a, b, c) = (first + k, first + k + 1, first + k + 2);
            residuals[row] = root_lambda * (theta[a] - 2.0 * theta[b] + theta[c]);
            if let Some(jac) = jacobian.as_mut() {
                jac[(row, a)] = root_lambda;
                jac[(row, b)] = -2.0 * root_lambda;
                jac[(row, c)] = root_lambda;
            }
        }
        // Glassy-modulus bound.
        let row = rows - 1;
        let e1 = m.glassy_modulus();
        let excess = (e1 / self.e1_max).ln();
        if excess > 0.0 {
            // r = w x²/(x + δ): zero with zero slope at the bound, w x − w δ
            // beyond it. The kink of w·max(0, x) stalled Levenberg–Marquardt
            // on the bound (its step test fired with E1 pinned there).
            let (value, slope) = smooth_excess(excess);
            residuals[row] = BOUND_WEIGHT * value;
            if let Some(jac) = jacobian.as_mut() {
                let ones = vec![1.0; self.param.terms() + 1];
                let mut d = vec![0.0; n_material];
                self.param.pullback(m, &ones, &mut d);
                for (j, dj) in d.iter().enumerate() {
                    jac[(row, j)] = BOUND_WEIGHT * slope * dj / e1;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::ModulusAnchor;

    /// The objective at λ = 0.3 with a tight model tolerance.
    fn test_objective<'a>(
        setup: &'a RollingSetup,
        data: &'a Measurements,
        param: Parametrization,
        shift: Option<ShiftParam>,
        e1_max: f64,
    ) -> Objective<'a> {
        Objective {
            setup,
            data,
            scales: data.residual_scales(),
            param,
            shift,
            lambda: 0.3,
            e1_max,
            tolerance: 1e-10,
            vertical: None,
            dma: None,
            friction_factor: false,
            noise_known: data.sigma().is_some(),
        }
    }

    /// The residual Jacobian against central finite differences, with and
    /// without scale anchors, on a fixed θ with the E1 bound active.
    #[test]
    fn jacobian_matches_finite_differences() {
        let setup = crate::params::example_setup();
        let speeds: Vec<f64> = (0..9).map(|i| 1e-7 * 10f64.powi(i)).collect();
        let mu: Vec<f64> = speeds
            .iter()
            .map(|v| 0.01 + 0.001 * v.log10().abs())
            .collect();
        let data = Measurements::new(speeds, mu, None, None).unwrap();
        let tau: Vec<f64> = (0..8).map(|k| 10f64.powf(k as f64 - 5.0)).collect();
        for anchor in [
            None,
            Some(ModulusAnchor {
                omega: 0.0,
                modulus: 2e6,
                source: "E0",
            }),
            Some(ModulusAnchor {
                omega: 30.0,
                modulus: 5e7,
                source: "E_at",
            }),
        ] {
            let param = Parametrization::new(tau.clone(), anchor);
            let n = param.free_count();
            let theta: Vec<f64> = (0..n)
                .map(|k| {
                    if anchor.is_none() && k == 0 {
                        14.5
                    } else {
                        3.0 + 0.4 * (k as f64).sin()
                    }
                })
                .collect();
            let objective = test_objective(&setup, &data, param, None, 1e8);
            assert_jacobian(&objective, &theta, &format!("{anchor:?}"));
        }
    }

    /// The master curve's Prony series at θ (its material part).
    fn prony_at(objective: &Objective<'_>, theta: &[f64]) -> Prony {
        let n_material = objective.param.free_count();
        objective
            .param
            .prony(&objective.param.map(&theta[..n_material]))
            .unwrap()
    }

    /// Every column of the residual Jacobian at `theta` against central
    /// finite differences; `case` names the case in a failure.
    fn assert_jacobian(objective: &Objective<'_>, theta: &[f64], case: &str) {
        let jac = objective.evaluate(theta, true).unwrap().jacobian.unwrap();
        for j in 0..theta.len() {
            let step = 1e-5;
            let mut up = theta.to_vec();
            let mut dn = theta.to_vec();
            up[j] += step;
            dn[j] -= step;
            let ru = objective.evaluate(&up, false).unwrap().residuals;
            let rd = objective.evaluate(&dn, false).unwrap().residuals;
            for i in 0..ru.len() {
                let fd = (ru[i] - rd[i]) / (2.0 * step);
                assert!(
                    (jac[(i, j)] - fd).abs() <= 1e-5 * (1.0 + fd.abs()),
                    "{case} row {i} column {j}: {} vs {fd}",
                    jac[(i, j)]
                );
            }
        }
    }

    /// Three temperatures × five speeds.
    fn temperature_set() -> Measurements {
        let mut speeds = Vec::new();
        let mut temps = Vec::new();
        for t in [0.0, 20.0, 45.0] {
            for i in 0..5 {
                speeds.push(1e-6 * 10f64.powi(i));
                temps.push(t);
            }
        }
        let mu: Vec<f64> = speeds
            .iter()
            .map(|v| 0.02 + 0.001 * v.log10().abs())
            .collect();
        Measurements::new(speeds, mu, None, Some(temps)).unwrap()
    }

    /// The objective of a temperature set with shift `kind` about 20 °C,
    /// anchored, and a fixed θ (material, then WLF-like shifts).
    fn set_objective<'a>(
        setup: &'a RollingSetup,
        data: &'a Measurements,
        kind: crate::params::ShiftKind,
    ) -> (Objective<'a>, Vec<f64>) {
        let settings = crate::params::ShiftSettings {
            kind,
            t_ref: Some(20.0),
            ..crate::params::ShiftSettings::default()
        };
        let shift = ShiftParam::new(data, &settings).unwrap();
        let tau: Vec<f64> = (0..8).map(|k| 10f64.powf(k as f64 - 6.0)).collect();
        let anchor = Some(ModulusAnchor {
            omega: 0.0,
            modulus: 2e6,
            source: "E0",
        });
        let param = Parametrization::new(tau, anchor);
        let mut theta: Vec<f64> = (0..param.free_count())
            .map(|k| 3.0 + 0.4 * (k as f64).sin())
            .collect();
        theta.extend(shift.theta_of_wlf(8.86, 101.6));
        (test_objective(setup, data, param, Some(shift), 1e10), theta)
    }

    /// Vertical factors 10^−0.15 at 0 °C and 10^0.2 at 45 °C about 20 °C.
    fn vertical_table() -> rollfit_model::VerticalShift {
        rollfit_model::VerticalShift::table(20.0, vec![(0.0, -0.15), (45.0, 0.2)]).unwrap()
    }

    /// A temperature set's Jacobian (WLF and free shifts, with and without
    /// vertical factors), material and shift columns, against central
    /// finite differences.
    #[test]
    fn shift_jacobian_matches_finite_differences() {
        use crate::params::ShiftKind;
        let setup = crate::params::example_setup();
        let data = temperature_set();
        let table = vertical_table();
        for kind in [ShiftKind::Wlf, ShiftKind::Free] {
            for vertical in [None, Some(&table)] {
                let (mut objective, theta) = set_objective(&setup, &data, kind);
                objective.vertical = vertical;
                assert_jacobian(&objective, &theta, &format!("{kind:?} {vertical:?}"));
            }
        }
    }

    /// A joint objective (DMA rows at temperatures the rolling rows lack,
    /// known vertical factors, κ fitted): every column of its Jacobian,
    /// the DMA rows' and κ's among them, against central finite
    /// differences, with WLF and free shifts.
    #[test]
    fn joint_jacobian_matches_finite_differences() {
        use crate::joint::{DmaBlock, DmaRows};
        use crate::master::Isotherm;
        use crate::params::{ShiftKind, ShiftSettings};
        let setup = crate::params::example_setup();
        let data = temperature_set();
        let isotherm = |t: f64, scale: f64| Isotherm {
            temperature: t,
            omega: vec![0.6, 6.0, 60.0, 600.0],
            storage: vec![3e6 * scale, 5e6 * scale, 2e7 * scale, 9e7 * scale],
            loss: vec![4e5 * scale, 1e6 * scale, 6e6 * scale, 3e7 * scale],
        };
        let rows = DmaRows::new(
            vec![
                isotherm(-10.0, 2.0),
                isotherm(20.0, 1.0),
                isotherm(45.0, 0.7),
            ],
            "test",
        )
        .unwrap();
        let vertical =
            rollfit_model::VerticalShift::table(20.0, vec![(-10.0, -0.1), (45.0, 0.2)]).unwrap();
        for kind in [ShiftKind::Wlf, ShiftKind::Free] {
            let settings = ShiftSettings {
                kind,
                t_ref: Some(20.0),
                ..ShiftSettings::default()
            };
            let temps = vec![-10.0, 0.0, 20.0, 45.0];
            let shift = ShiftParam::over(&data, temps, &settings).unwrap();
            let tau: Vec<f64> = (0..8).map(|k| 10f64.powf(k as f64 - 6.0)).collect();
            let param = Parametrization::new(tau, None);
            let mut theta: Vec<f64> = (0..param.free_count())
                .map(|k| {
                    if k == 0 {
                        14.0
                    } else {
                        15.0 + 0.4 * (k as f64).sin()
                    }
                })
                .collect();
            theta.extend(shift.theta_of_wlf(8.86, 101.6));
            theta.push(0.2);
            let block = DmaBlock::new(&rows, Some(&shift), 0.02, Some(&vertical)).unwrap();
            let mut objective = test_objective(&setup, &data, param, Some(shift), 1e10);
            objective.dma = Some(block);
            objective.friction_factor = true;
            assert_eq!(objective.free_count(), theta.len());
            assert_eq!(objective.data_rows(), data.len() + 24);
            assert_jacobian(&objective, &theta, &format!("joint {kind:?}"));
            // The DMA residuals against the model's own Prony series at
            // ω a_T, times b_T, and κ against the rolling rows' μ.
            let e = objective.evaluate(&theta, false).unwrap();
            let n_material = objective.param.free_count();
            let prony = prony_at(&objective, &theta);
            let s = objective.shift.as_ref().unwrap();
            let (log_a, _) = s.log_shifts(&theta[n_material..]);
            let mut row = data.len();
            for (t, w, e1, e2) in rows.points() {
                let j = crate::shift::index_of(s.temperatures(), t).unwrap();
                let b = 10f64.powf(vertical.log10_factor(t).unwrap());
                let m =
                    rollfit_model::ViscoelasticModulus::modulus(&prony, w * 10f64.powf(log_a[j]));
                for (fit, measured) in [(m.re, e1), (m.im, e2)] {
                    let expected = (b * fit / measured).ln() / 0.02;
                    assert!((e.residuals[row] - expected).abs() < 1e-9, "row {row}");
                    row += 1;
                }
            }
            objective.friction_factor = false;
            let plain = objective
                .evaluate(&theta[..theta.len() - 1], false)
                .unwrap();
            for (k, p) in e.mu.iter().zip(&plain.mu) {
                assert!((k / p - 0.2f64.exp()).abs() < 1e-12);
            }
        }
    }

    /// A temperature set with vertical factors: each row's μ is that of the
    /// master curve times b_T at v a_T, computed here directly with the
    /// model's `Shifted` wrapper (b_T applied to the modulus, the load
    /// unchanged), where the objective divides the load by b_T.
    #[test]
    fn vertical_factors_scale_each_temperature() {
        use rollfit_model::Shifted;
        let setup = crate::params::example_setup();
        let data = temperature_set();
        let vertical = vertical_table();
        let (mut objective, theta) = set_objective(&setup, &data, crate::params::ShiftKind::Wlf);
        objective.vertical = Some(&vertical);
        let e = objective.evaluate(&theta, false).unwrap();
        let prony = prony_at(&objective, &theta);
        let (reduced, _) = objective.reduced_speeds(&theta);
        let (speeds, temps) = (data.speeds(), data.temperature().unwrap());
        for i in 0..speeds.len() {
            let log_a = (reduced[i] / speeds[i]).log10();
            let log_b = vertical.log10_factor(temps[i]).unwrap();
            let modulus = Shifted::new(prony.clone(), log_a)
                .unwrap()
                .with_vertical(log_b)
                .unwrap();
            let direct = Scene::new(setup.geometry, setup.substrate, setup.contact, modulus)
                .unwrap()
                .with_tolerance(1e-10)
                .unwrap()
                .friction(speeds[i])
                .unwrap();
            assert!(
                (e.mu[i] / direct - 1.0).abs() < 1e-8,
                "row {i}: {} vs {direct}",
                e.mu[i]
            );
        }
        // b_T matters here: without it μ differs by far more.
        objective.vertical = None;
        let plain = objective.evaluate(&theta, false).unwrap();
        assert!((plain.mu[0] / e.mu[0] - 1.0).abs() > 1e-2);
    }
}
