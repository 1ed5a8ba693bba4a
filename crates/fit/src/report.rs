//! The result of a fit, as written to fit.json (the contract of
//! docs/ARCHITECTURE.md, "Contract", extended), plus the curves the command
//! line writes as CSV.

use serde::Serialize;

pub use crate::analysis::ModulusPoint;
use crate::regularization::LambdaRule;
pub use crate::shift::{LogShift, ShiftRecord};
pub use crate::temperature_set::law::{LawCandidate, ShiftChoice};

/// The recovered Prony series at the reference state.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModelRecord {
    /// Always "prony".
    pub kind: &'static str,
    /// Glassy modulus E1 = E0 + Σ H_k, Pa.
    #[serde(rename = "E1")]
    pub glassy_modulus: f64,
    /// Static modulus E0, Pa.
    #[serde(rename = "E0")]
    pub static_modulus: f64,
    /// Relaxation times τ_k, s.
    pub tau: Vec<f64>,
    /// Strengths H_k, Pa.
    #[serde(rename = "H")]
    pub strengths: Vec<f64>,
    /// Whether the data determine each H_k (see `analysis`); undetermined
    /// terms shape E* only outside the window and are not results.
    pub determined: Vec<bool>,
    /// 1σ of ln H_k from the curvature of V.
    #[serde(rename = "ln_H_sigma")]
    pub ln_strength_sigma: Vec<f64>,
}

/// The frequency window the data determine, rad/s.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Window {
    /// rad/s.
    pub omega_min: f64,
    /// rad/s.
    pub omega_max: f64,
}

/// The smoothness weight and how it was chosen.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LambdaRecord {
    /// λ.
    pub value: f64,
    /// The rule.
    pub rule: LambdaRule,
    /// (λ, misfit, effective parameters) along the path, for L-curve plots.
    pub path: Vec<[f64; 3]>,
    /// (λ, criterion) along the path for the marginal-likelihood and GCV
    /// rules (−2 ln p(data | λ) up to a constant, or GCV).
    pub criterion: Vec<[f64; 2]>,
}

/// How the number of terms was chosen.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TermsRecord {
    /// Number of relaxation times.
    pub count: usize,
    /// Terms per decade of the grid.
    pub per_decade: f64,
    /// "per_decade", "count", "explicit" or "aicc" (the corrected Akaike
    /// criterion over 1, 2, 3 per decade).
    pub rule: String,
    /// AICc per candidate density when the rule is "aicc".
    pub candidates: Vec<[f64; 2]>,
}

/// The anchor as used.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AnchorRecord {
    /// "E0", "E_at" or "contact_radius".
    pub source: &'static str,
    /// rad/s.
    pub omega: f64,
    /// |E*(ω)|, Pa.
    #[serde(rename = "E")]
    pub modulus: f64,
}

/// How well the data determine the modulus scale of a fit without an
/// anchor (fit.json `scale`; absent when an anchor fixes the scale). From
/// the profile of the data misfit over E0 with the shape refitted at each
/// E0 ([`crate::driver`]'s `profile`), within the range of E0 where the
/// model's assumptions hold.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScaleRecord {
    /// "data" when the 2σ interval (an open end closed by `range`) spans at
    /// most a factor [`crate::driver::SCALE_FACTOR_LIMIT`] either side of
    /// its geometric centre, else
    /// "undetermined" (the fit is refused unless the user allows an
    /// unanchored result; `--allow-unanchored`).
    pub status: &'static str,
    /// E0 of the fit, Pa.
    #[serde(rename = "E0")]
    pub static_modulus: f64,
    /// Lower end of the 2σ interval of E0 (profile Δχ² ≤ 4), Pa; None when
    /// the data fit as well down to the lowest E0 profiled.
    #[serde(rename = "E0_low")]
    pub low: Option<f64>,
    /// Upper end of the 2σ interval, Pa; None when open upward.
    #[serde(rename = "E0_high")]
    pub high: Option<f64>,
    /// The range of E0 profiled, Pa: from the smallest E0 at which the
    /// rubbery Hertz contact stays within R/5 (and E0 ≥ 10 kPa) up to
    /// E1_max.
    #[serde(rename = "E0_range")]
    pub range: [f64; 2],
    /// (E0 in Pa, Δχ² against the profile's best) of every profiled E0.
    pub profile: Vec<[f64; 2]>,
    /// What the profile says, in words (with the anchors that would fix an
    /// undetermined scale).
    pub reason: String,
}

impl ScaleRecord {
    /// Whether the data leave the scale undetermined.
    pub fn is_undetermined(&self) -> bool {
        self.status == "undetermined"
    }
}

/// One solver run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunRecord {
    /// What the run was for ("lambda path", "refine", "start 2", …).
    pub stage: String,
    /// Method name.
    pub method: &'static str,
    /// λ of the run.
    pub lambda: f64,
    /// V at the end.
    pub objective: f64,
    /// Solver iterations.
    pub iterations: usize,
    /// Objective evaluations.
    pub evaluations: usize,
    /// Wall time, s.
    pub wall_time_s: f64,
    /// Whether it converged.
    pub converged: bool,
    /// How it ended.
    pub stop_reason: String,
    /// (evaluations, best V so far) at each evaluation that improved V,
    /// for convergence plots.
    pub history: Vec<[f64; 2]>,
}

/// The cross-check of a temperature set's shifts.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShiftCrossCheck {
    /// How the single-temperature shifts were found.
    pub method: String,
    /// Per temperature: the joint fit's and the single fits' log10 a_T.
    pub temperatures: Vec<CrossCheckRow>,
    /// RMS of (single − joint) over the temperatures, decades.
    pub rms_difference: f64,
    /// Largest |single − joint|, decades.
    pub max_difference: f64,
}

impl ShiftCrossCheck {
    /// The temperatures whose single and joint shifts differ by more than
    /// their combined σ allows (`beyond_sigma`).
    pub fn disagreeing(&self) -> impl Iterator<Item = &CrossCheckRow> {
        self.temperatures.iter().filter(|r| r.beyond_sigma)
    }
}

/// One temperature of the cross-check.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CrossCheckRow {
    /// °C.
    #[serde(rename = "T")]
    pub temperature: f64,
    /// log10 a_T of the joint fit.
    #[serde(rename = "log_aT_joint")]
    pub log_shift_joint: f64,
    /// log10 a_T from overlapping the single-temperature fits (relative to
    /// T_ref through the chain of neighbours).
    #[serde(rename = "log_aT_single")]
    pub log_shift_single: f64,
    /// single − joint, decades.
    pub difference: f64,
    /// The single-temperature fit's misfit per point.
    pub single_misfit_per_point: f64,
    /// 1σ of `log_aT_single`, decades, from the single fits' tan δ bands
    /// (null when those fits do not determine it).
    #[serde(rename = "log_aT_single_sigma")]
    pub log_shift_single_sigma: Option<f64>,
    /// 1σ of `log_aT_joint`, decades (null when not determined).
    #[serde(rename = "log_aT_joint_sigma")]
    pub log_shift_joint_sigma: Option<f64>,
    /// The combined 1σ of `difference`, decades (null when either is
    /// undetermined).
    pub difference_sigma: Option<f64>,
    /// |difference| above three times `difference_sigma`: the joint shift
    /// at this temperature is questioned.
    pub beyond_sigma: bool,
    /// What limits the single-temperature fit (few speeds, low μ, μ
    /// written with few digits); empty when nothing does.
    pub single_fit_limits: Vec<String>,
}

/// How a fit with `physics = "exact"` reached the exact contact
/// (fit.json's `physics`, written only then; see
/// [`crate::exact_physics`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PhysicsRecord {
    /// Always "exact": a fit with Eq. (11)/(17) alone has no record.
    pub kind: &'static str,
    /// Refits with the corrected model after the first, approximate fit
    /// (none when r is within the tolerance of 1 at its modulus).
    pub iterations: usize,
    /// Exact solutions computed (one per speed on the master curve and
    /// iteration).
    pub exact_solves: usize,
    /// Whether the correction stopped changing: max_i |Δr_i/r_i| of the
    /// last iteration at most `tolerance`.
    pub converged: bool,
    /// max_i |r_i − 1| of the final correction r_i = μ_exact/μ_approx.
    pub max_correction: f64,
    /// The relative accuracy asked of each exact μ: a tenth of the data's
    /// relative σ, within 1e-5 … 1e-3.
    pub accuracy: f64,
    /// The largest relative error the exact solutions estimated for
    /// themselves (final iteration).
    pub max_error_estimate: f64,
    /// The convergence tolerance on max_i |Δr_i/r_i| (= `accuracy`).
    pub tolerance: f64,
    /// max_i |Δr_i/r_i| of the last iteration (with no refit: max_i |r_i − 1|
    /// at the approximate fit, which had r ≡ 1).
    pub last_change: f64,
    /// r_i = μ_exact/μ_approx at the fitted modulus per data row (mu.csv's
    /// `exact_correction`, not fit.json).
    #[serde(skip)]
    pub correction: Vec<f64>,
}

/// Everything a fit produced.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FitReport {
    /// The master curve.
    pub model: ModelRecord,
    /// Poisson's ratio used.
    pub poisson: f64,
    /// The window the data determine (at T_ref for a temperature set): the
    /// part of the probed window where tan δ is known to better than
    /// 10 % (1σ, bias included; `analysis::DETERMINED_RELATIVE_SIGMA`).
    pub window: Window,
    /// The window the data's speeds probe (v_min/r … 20 v_max/r), of which
    /// `window` is the determined part.
    pub probed_window: Window,
    /// The time–temperature shift of a temperature set.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shift: Option<ShiftRecord>,
    /// With `shift = "auto"`: which law was chosen and why.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shift_choice: Option<ShiftChoice>,
    /// The optimiser.
    pub method: &'static str,
    /// V at the optimum: weighted misfit plus smoothness penalty.
    pub objective: f64,
    /// The weighted misfit Σ r_i² alone (χ² when σ is measured).
    pub misfit: f64,
    /// misfit/N.
    pub misfit_per_point: f64,
    /// Whether the residuals are in units of measured σ (else relative).
    pub sigma_weights: bool,
    /// Iterations of the final run.
    pub iterations: usize,
    /// Evaluations of all runs.
    pub evaluations: usize,
    /// Whether the final run converged.
    pub converged: bool,
    /// How the final run ended.
    pub stop_reason: String,
    /// Wall time of the whole fit, s.
    pub wall_time_s: f64,
    /// Smoothness weight.
    pub lambda: LambdaRecord,
    /// Number of terms.
    pub terms: TermsRecord,
    /// Scale anchor, if any.
    pub anchor: Option<AnchorRecord>,
    /// Effective number of parameters the data fix.
    pub effective_parameters: f64,
    /// Estimated noise: √(s²), in σ units or relative.
    pub noise: f64,
    /// Goodness of fit: χ² and runs tests, and the verdict.
    pub fit_quality: crate::quality::FitQuality,
    /// E0 and E1 where they lie beyond the window the data determine, with
    /// the one-sided 2σ bound the window gives ([`crate::extrapolation`]);
    /// they never judge the fit.
    pub extrapolated: Vec<crate::extrapolation::Extrapolation>,
    /// Seed of the multi-start.
    pub seed: u64,
    /// Things the user must know.
    pub warnings: Vec<String>,
    /// Every solver run.
    pub runs: Vec<RunRecord>,
    /// (evaluations, best V) of the final run.
    pub history: Vec<[f64; 2]>,
    /// Without an anchor: (factor c, misfit, λ_p) of the scale profile's
    /// refits with E0 pinned to c times the result's E0, the shape refitted
    /// at one λ_p (`driver`'s profile); those within one noise unit of the
    /// best widen the bands.
    pub scale_profile: Vec<[f64; 3]>,
    /// Without an anchor: how well the data determine the modulus scale.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scale: Option<ScaleRecord>,
    /// For a temperature set: the shifts estimated again by fitting each
    /// temperature alone and overlapping the tan δ curves.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shift_cross_check: Option<ShiftCrossCheck>,
    /// Dense data: how the rows were condensed to bins before the fit.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub condensed: Option<crate::condense::CondensedRecord>,
    /// With `physics = "exact"`: how the exact contact was reached (absent
    /// with the approximate physics, whose fit.json is unchanged).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub physics: Option<PhysicsRecord>,
    /// With DMA data (`dma`): the joint fit's account of its two sources
    /// (absent otherwise, so that fit.json is unchanged).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint: Option<crate::joint::JointRecord>,
    /// θ of the shift at the optimum (for refits that continue from it).
    #[serde(skip)]
    pub(crate) shift_theta: Vec<f64>,
    /// The master curve over the window with 1σ bands (written to
    /// modulus.csv, not to fit.json).
    #[serde(skip)]
    pub curve: Vec<ModulusPoint>,
    /// μ of the fit at the data speeds (mu.csv): of the exact contact at
    /// the fitted modulus with `physics = "exact"`.
    #[serde(skip)]
    pub mu_fit: Vec<f64>,
}

impl FitReport {
    /// The master curve and its 1σ bands at `omega` (rad/s): [`Self::curve`]
    /// (modulus.csv's rows, 10 per decade over the determined window)
    /// interpolated linearly in ln ω, every column alike, so that at a
    /// row's ω it is that row exactly. None outside the curve's ω range
    /// (or for a NaN ω): the bands are not known there.
    pub fn band_at(&self, omega: f64) -> Option<ModulusPoint> {
        let curve = &self.curve;
        let (first, last) = (curve.first()?, curve.last()?);
        if !(omega >= first.omega && omega <= last.omega) {
            return None;
        }
        // The first row at or above ω; ω lies in [rows k − 1, k].
        let k = curve.partition_point(|p| p.omega < omega);
        let upper = &curve[k];
        if upper.omega == omega || k == 0 {
            return Some(*upper);
        }
        let lower = &curve[k - 1];
        let t = (omega / lower.omega).ln() / (upper.omega / lower.omega).ln();
        let (a, b) = (lower.values(), upper.values());
        let at = |i: usize| a[i] + t * (b[i] - a[i]);
        Some(ModulusPoint {
            omega,
            storage: at(1),
            loss: at(2),
            tan_delta: at(3),
            magnitude: at(4),
            storage_sigma: at(5),
            loss_sigma: at(6),
            tan_delta_sigma: at(7),
            magnitude_sigma: at(8),
        })
    }

    /// The first number of the report that is not finite, by its key in
    /// fit.json (`curve` and `mu_fit` name modulus.csv's and mu.csv's
    /// columns): JSON has no NaN or ∞, and a reader of the result files must
    /// be able to trust every number in them. The σ of a shift are exempt:
    /// an undetermined one is not finite and is written as null.
    pub fn first_non_finite(&self) -> Option<String> {
        let bad = |x: &f64| !x.is_finite();
        let pairs = |v: &[[f64; 2]]| v.iter().flatten().any(bad);
        let mut scalars: Vec<(&str, f64)> = vec![
            ("objective", self.objective),
            ("misfit", self.misfit),
            ("misfit_per_point", self.misfit_per_point),
            ("noise", self.noise),
            ("effective_parameters", self.effective_parameters),
            ("poisson", self.poisson),
            ("window.omega_min", self.window.omega_min),
            ("window.omega_max", self.window.omega_max),
            ("probed_window.omega_min", self.probed_window.omega_min),
            ("probed_window.omega_max", self.probed_window.omega_max),
            ("lambda.value", self.lambda.value),
            ("terms.per_decade", self.terms.per_decade),
            ("model.glassy_modulus", self.model.glassy_modulus),
            ("model.static_modulus", self.model.static_modulus),
            ("wall_time_s", self.wall_time_s),
        ];
        if let Some(a) = &self.anchor {
            scalars.extend([("anchor.omega", a.omega), ("anchor.modulus", a.modulus)]);
        }
        if let Some(p) = &self.physics {
            scalars.extend([
                ("physics.max_correction", p.max_correction),
                ("physics.accuracy", p.accuracy),
                ("physics.max_error_estimate", p.max_error_estimate),
                ("physics.tolerance", p.tolerance),
                ("physics.last_change", p.last_change),
            ]);
        }
        if let Some(shift) = &self.shift {
            scalars.extend(shift.constants());
        }
        if let Some((key, value)) = scalars.iter().find(|(_, x)| bad(x)) {
            return Some(format!("{key} = {value}"));
        }
        let vectors: [(&str, bool); 11] = [
            (
                "shift_choice.candidates",
                self.shift_choice.as_ref().is_some_and(|c| !c.all_finite()),
            ),
            ("model.tau", self.model.tau.iter().any(bad)),
            ("model.strengths", self.model.strengths.iter().any(bad)),
            (
                "model.ln_strength_sigma",
                self.model.ln_strength_sigma.iter().any(bad),
            ),
            (
                "shift.log_aT",
                self.shift
                    .as_ref()
                    .is_some_and(|s| s.log_shifts().iter().any(|l| bad(&l.log_shift))),
            ),
            (
                "runs (objective, lambda, history)",
                self.runs.iter().any(|r| {
                    bad(&r.objective) || bad(&r.lambda) || bad(&r.wall_time_s) || pairs(&r.history)
                }),
            ),
            (
                "lambda.path, lambda.criterion, terms.candidates, history or scale_profile",
                self.lambda.path.iter().flatten().any(bad)
                    || pairs(&self.lambda.criterion)
                    || pairs(&self.terms.candidates)
                    || pairs(&self.history)
                    || self.scale_profile.iter().flatten().any(bad),
            ),
            (
                "curve (modulus.csv)",
                self.curve.iter().any(|p| p.values().iter().any(bad)),
            ),
            ("mu_fit (mu.csv)", self.mu_fit.iter().any(bad)),
            (
                "physics.correction (mu.csv exact_correction)",
                self.physics
                    .as_ref()
                    .is_some_and(|p| p.correction.iter().any(bad)),
            ),
            (
                "shift_cross_check",
                self.shift_cross_check.as_ref().is_some_and(|c| {
                    bad(&c.rms_difference)
                        || bad(&c.max_difference)
                        || c.temperatures.iter().any(|r| {
                            [
                                r.log_shift_joint,
                                r.log_shift_single,
                                r.difference,
                                r.single_misfit_per_point,
                            ]
                            .iter()
                            .any(bad)
                        })
                }),
            ),
        ];
        vectors
            .iter()
            .find(|(_, b)| *b)
            .map(|(key, _)| format!("{key} holds a value that is not finite"))
    }
}
