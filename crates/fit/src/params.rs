//! Fit settings, unchecked and validated (the linfa pattern): a
//! [`FitParams`] is what a user asks for; [`FitParams::check`] turns it into
//! [`ValidFitParams`] against the rolling set-up, so that no invalid setting
//! can reach the numerics.

use std::sync::Arc;

use rollfit_model::exact::exact_body;
use rollfit_model::modulus::FreeShift;
use rollfit_model::{ModelError, Prony, VerticalShift};

use crate::cancel::Cancel;
use crate::dma_rows::DmaRows;
use crate::error::FitError;
use crate::progress::Observer;

mod anchor;

use anchor::{modulus, reduce_anchor};

/// The optimiser.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Levenberg–Marquardt on the residual vector with the analytic
    /// Jacobian (trust region, MINPACK's algorithm): the robust default.
    LevenbergMarquardt,
    /// argmin's L-BFGS with a Moré–Thuente line search on V(θ).
    Lbfgs,
    /// argmin's Nelder–Mead simplex on V(θ), the paper's "amoeba".
    NelderMead,
}

impl Method {
    /// The name used in scene files, on the command line and in fit.json.
    pub fn name(self) -> &'static str {
        match self {
            Method::LevenbergMarquardt => "levenberg-marquardt",
            Method::Lbfgs => "lbfgs",
            Method::NelderMead => "nelder-mead",
        }
    }

    /// Parses a method name; "auto" and "lm" select Levenberg–Marquardt.
    pub fn parse(name: &str) -> Result<Self, FitError> {
        match name {
            "auto" | "lm" | "levenberg-marquardt" => Ok(Method::LevenbergMarquardt),
            "lbfgs" | "l-bfgs" => Ok(Method::Lbfgs),
            "nelder-mead" | "amoeba" => Ok(Method::NelderMead),
            other => Err(FitError::setting(
                "method",
                format!(
                    "unknown method \"{other}\" (use \"auto\", \"levenberg-marquardt\", \
                     \"lbfgs\" or \"nelder-mead\")"
                ),
            )),
        }
    }
}

/// The physics of the model μ(v; E*) the data are fitted with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Physics {
    /// Persson's Eq. (11) (cylinder) or (17) (sphere), fast and with an
    /// analytic Jacobian; 4–10 % off the exact μ near the friction maximum
    /// of a broad rubber, an error the fit absorbs into E*(ω).
    #[default]
    Approximate,
    /// The exact steady rolling contact of the same body, reached by
    /// defect correction around fits with the approximate model
    /// ([`crate::exact_physics`]); needs a body with an exact solution
    /// (`rollfit_model::exact::exact_body`) on a half-space.
    Exact,
}

impl Physics {
    /// The name used in scene files, on the command line and in fit.json.
    pub fn name(self) -> &'static str {
        match self {
            Physics::Approximate => "approximate",
            Physics::Exact => "exact",
        }
    }
}

/// A known point of the modulus scale, used as a constraint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ScaleAnchor {
    /// Known static Young's modulus E0, Pa.
    StaticModulus(f64),
    /// Known |E| (Young's, Pa) at angular frequency `omega` (rad/s).
    ModulusAt {
        /// rad/s.
        omega: f64,
        /// |E*(ω)|, Pa.
        modulus: f64,
    },
    /// A contact radius (half-width for a cylinder) `radius` (m) measured at
    /// rolling speed `speed` (m/s).
    ContactRadius {
        /// m/s.
        speed: f64,
        /// m.
        radius: f64,
    },
}

/// How the relaxation times are chosen.
#[derive(Debug, Clone, PartialEq)]
pub enum TermRule {
    /// τ_k log-spaced at this many per decade over the rule of
    /// [`crate::tau_grid`] (default 2).
    PerDecade(f64),
    /// Exactly this many τ_k over the same extent.
    Count(usize),
    /// 1, 2 or 3 per decade, chosen by the corrected Akaike criterion.
    Auto,
    /// Given relaxation times, s.
    Explicit(Vec<f64>),
}

/// The smoothness weight λ on ln H_k.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Lambda {
    /// Data-driven: the discrepancy principle when σ is measured, else the
    /// marginal likelihood with the noise level profiled out (see
    /// [`crate::regularization`]).
    Auto,
    /// A fixed λ ≥ 0 (0 switches the penalty off).
    Fixed(f64),
}

/// What a user asks of a fit (unchecked).
#[derive(Debug, Clone, PartialEq)]
pub struct FitParams {
    /// Optimiser.
    pub method: Method,
    /// Relaxation-time rule.
    pub terms: TermRule,
    /// Scale anchor, if any.
    pub anchor: Option<ScaleAnchor>,
    /// Upper bound of the glassy modulus E1, Pa.
    pub e1_max: f64,
    /// Smoothness weight.
    pub lambda: Lambda,
    /// Seed of the multi-start perturbations.
    pub seed: u64,
    /// Number of starts: 1 runs the neutral start alone; k ≥ 2 adds four
    /// bump-shaped spectra and k − 1 seeded perturbations of the neutral
    /// start (see [`crate::driver`]).
    pub starts: usize,
    /// Budget of objective evaluations per solver run (None: the method's
    /// default).
    pub max_evaluations: Option<usize>,
    /// Relative tolerance of the forward model's quadrature.
    pub model_tolerance: f64,
    /// A starting material (E1, H, τ) to begin from instead of the neutral
    /// start, e.g. the scene's `[material]`.
    pub start: Option<StartMaterial>,
    /// How a temperature set (data at several temperatures) is shifted;
    /// ignored for data at one temperature.
    pub shift: ShiftSettings,
    /// The model's physics: Eq. (11)/(17), or the exact contact.
    pub physics: Physics,
    /// In a joint fit with DMA data: μ_measured = κ μ_theory with κ = 1 or
    /// fitted ([`crate::joint`]).
    pub friction_factor: FrictionFactor,
    /// In a joint fit: the relative σ of the DMA moduli E′ and E″ (None:
    /// estimated from the DMA master curve's residuals).
    pub dma_sigma: Option<f64>,
}

/// Accepted relative standard deviations of E′ and E″ (`dma_sigma`): from
/// 1e-5 (beyond any DMA) to 1 (a factor e, no measurement).
pub const DMA_SIGMA_RANGE: (f64, f64) = (1e-5, 1.0);

/// The factor κ in μ_measured = κ μ_theory of a joint fit with DMA data.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FrictionFactor {
    /// κ = 1: the rolling friction is the bulk hysteresis of the DMA's
    /// material.
    #[default]
    One,
    /// κ fitted with its σ: friction beyond the bulk viscoelasticity shows
    /// up as κ ≠ 1.
    Free,
}

/// The time–temperature shift fitted to a temperature set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShiftKind {
    /// WLF: log10 a_T = −C1 (T − T_ref)/(C2 + T − T_ref), C1 and C2 fitted.
    Wlf,
    /// Arrhenius: log10 a_T = E_a/(R ln 10) (1/T − 1/T_ref), E_a fitted.
    Arrhenius,
    /// One free log10 a_T per temperature, 0 at T_ref.
    Free,
    /// The law the data support: WLF, else Arrhenius, else free shifts,
    /// each law tested against the free shifts ([`crate::temperature_set::law`]).
    Auto,
}

/// Settings of a temperature-set fit.
#[derive(Debug, Clone, PartialEq)]
pub struct ShiftSettings {
    /// The shift model.
    pub kind: ShiftKind,
    /// Reference temperature of the master curve, °C (None: the measured
    /// temperature in the middle of the set). A free shift needs it to be
    /// one of the measured temperatures.
    pub t_ref: Option<f64>,
    /// Starting WLF constants (C1, C2 in K), e.g. from the scene's
    /// `[material.shift]` (None: estimated from the data).
    pub wlf_start: Option<(f64, f64)>,
    /// Also fit each temperature alone and estimate the shifts by
    /// overlapping the single-temperature tan δ curves (a cross-check).
    pub cross_check: bool,
    /// Known vertical factors b_T (a scene's `[material.shift]` `log_bT`
    /// or `vertical`): each temperature's modulus is b_T times the master
    /// curve's (`crate::vertical`). None: b_T = 1. Their T_ref must be the
    /// fit's.
    pub vertical: Option<VerticalShift>,
    /// A law the scene asked for that the fit does not have
    /// (`[material.shift] model = "wlf-arrhenius"`), with why `kind` is
    /// fitted instead: said in the warnings and in fit.json's
    /// `shift_choice` (`chosen_by = "substitute"`), never silently.
    pub substituted: Option<ShiftSubstitute>,
}

/// A requested shift law replaced by another ([`ShiftSettings::substituted`]).
#[derive(Debug, Clone, PartialEq)]
pub struct ShiftSubstitute {
    /// The law asked for, as the scene names it ("wlf-arrhenius").
    pub requested: &'static str,
    /// Where it was asked for ("[material.shift] model").
    pub key: &'static str,
    /// Why the fitted law replaces it, and what that law gives instead.
    pub reason: String,
}

impl Default for ShiftSettings {
    fn default() -> Self {
        ShiftSettings {
            kind: ShiftKind::Auto,
            t_ref: None,
            wlf_start: None,
            cross_check: true,
            vertical: None,
            substituted: None,
        }
    }
}

/// A Prony series used as a starting point; it is re-expressed on the fit's
/// τ grid by matching E*(ω) at the grid frequencies.
#[derive(Debug, Clone, PartialEq)]
pub struct StartMaterial {
    /// Static modulus E0, Pa.
    pub static_modulus: f64,
    /// Glassy modulus E1, Pa.
    pub glassy_modulus: f64,
}

impl Default for FitParams {
    fn default() -> Self {
        FitParams {
            method: Method::LevenbergMarquardt,
            terms: TermRule::PerDecade(2.0),
            anchor: None,
            e1_max: 1e10,
            lambda: Lambda::Auto,
            seed: 0,
            starts: 3,
            max_evaluations: None,
            model_tolerance: 1e-6,
            start: None,
            shift: ShiftSettings::default(),
            physics: Physics::Approximate,
            friction_factor: FrictionFactor::One,
            dma_sigma: None,
        }
    }
}

/// The rolling set-up a fit works in: everything of a scene but the material.
pub use rollfit_model::RollingSetup;

/// A scale anchor reduced to one known |E| at one frequency (ω = 0 for the
/// static modulus).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModulusAnchor {
    /// rad/s (0 for E0).
    pub omega: f64,
    /// |E*(ω)|, Young's, Pa.
    pub modulus: f64,
    /// Where it came from, for reports: "E0", "E_at" or "contact_radius".
    pub source: &'static str,
}

/// Settings that passed [`FitParams::check`].
#[derive(Debug, Clone, PartialEq)]
pub struct ValidFitParams {
    pub(crate) method: Method,
    pub(crate) terms: TermRule,
    pub(crate) anchor: Option<ModulusAnchor>,
    pub(crate) e1_max: f64,
    pub(crate) lambda: Lambda,
    pub(crate) seed: u64,
    pub(crate) starts: usize,
    pub(crate) max_evaluations: Option<usize>,
    pub(crate) model_tolerance: f64,
    pub(crate) start: Option<StartMaterial>,
    pub(crate) shift: ShiftSettings,
    pub(crate) physics: Physics,
    pub(crate) setup: RollingSetup,
    /// Whether the fit estimates the bands' smoothing bias and cuts the
    /// window to what the data determine (off for the internal refits of a
    /// scale profile, which need neither).
    pub(crate) bands: bool,
    /// Whether a fit at a fixed λ may stop at the λ path's looser
    /// tolerance (the steps of a scale profile, which compare misfits to a
    /// tenth of a noise unit, not to the last digit).
    pub(crate) coarse: bool,
    /// The largest λ of the λ path (None: the path's own top): a temperature
    /// set's joint fit starts where its shifts are determined.
    pub(crate) path_top: Option<f64>,
    /// Read before every solver run: set, it ends the fit.
    pub(crate) cancel: Cancel,
    /// Told what the fit does (exact solves); watches only.
    pub(crate) progress: Observer,
    /// κ of a joint fit.
    pub(crate) friction_factor: FrictionFactor,
    /// The relative σ of the DMA moduli, when given.
    pub(crate) dma_sigma: Option<f64>,
    /// The DMA isotherms of a joint fit ([`ValidFitParams::with_dma`]).
    pub(crate) dma: Option<Arc<DmaRows>>,
    /// Whether an unanchored fit profiles its scale (off for a joint fit's
    /// rolling part alone, whose χ² is all that is read).
    pub(crate) profile: bool,
    /// λ by the marginal likelihood even with measured σ (a joint fit's
    /// rolling part alone: the compatibility test compares minima, which
    /// the discrepancy principle does not give, `crate::joint`).
    pub(crate) evidence: bool,
}

impl ValidFitParams {
    /// The optimiser.
    pub fn method(&self) -> Method {
        self.method
    }
    /// The scale anchor as a known |E| at one frequency.
    pub fn anchor(&self) -> Option<ModulusAnchor> {
        self.anchor
    }
    /// The rolling set-up.
    pub fn setup(&self) -> &RollingSetup {
        &self.setup
    }
    /// The model's physics.
    pub fn physics(&self) -> Physics {
        self.physics
    }
    /// The same settings, cancelled when `flag` is set (from any thread):
    /// the fit then ends at its next solver run with
    /// [`FitError::Cancelled`]. Never set, it changes nothing.
    pub fn with_cancel(mut self, flag: Cancel) -> ValidFitParams {
        self.cancel = flag;
        self
    }
    /// The same settings, with `observer` told the fit's progress (its
    /// exact solves, [`crate::progress`]). It changes no number.
    pub fn with_progress(mut self, observer: Observer) -> ValidFitParams {
        self.progress = observer;
        self
    }
    /// The same settings for a joint fit with the DMA isotherms `dma`
    /// ([`crate::joint`]): one master curve and shift law fitted to both.
    /// The exact physics is refused here (its defect correction acts on the
    /// rolling rows alone and has not been extended to the DMA part).
    pub fn with_dma(mut self, dma: DmaRows) -> Result<ValidFitParams, FitError> {
        if self.physics == Physics::Exact {
            return Err(FitError::setting(
                "dma",
                "a joint fit with DMA data uses the approximate physics (Eq. (11)/(17)); \
                 physics = \"exact\" is not available with `dma`",
            ));
        }
        self.dma = Some(Arc::new(dma));
        Ok(self)
    }
    /// The DMA isotherms of a joint fit.
    pub fn dma(&self) -> Option<&DmaRows> {
        self.dma.as_deref()
    }
    /// Whether the residuals of `data` are in units of a known σ: a σ
    /// column, outside a joint fit and its parts (module doc of
    /// `crate::joint`).
    pub(crate) fn noise_known(&self, data: &crate::data::Measurements) -> bool {
        data.sigma().is_some() && self.dma.is_none() && !self.evidence
    }
    /// Whether the modulus scale is fixed by something beside the rolling
    /// data: an anchor or DMA data.
    pub(crate) fn scale_fixed(&self) -> bool {
        self.anchor.is_some() || self.dma.is_some()
    }
}

fn positive(key: &str, value: f64) -> Result<f64, FitError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(FitError::setting(
            key,
            format!("{value} must be a finite number greater than zero"),
        ))
    }
}

impl FitParams {
    /// Validates every setting against the rolling set-up and reduces the
    /// scale anchor to a known |E| at one frequency. The settings are
    /// checked group by group in a fixed order, so that of several invalid
    /// settings the same one is always reported; `physics = "exact"` last,
    /// against the set-up's body and substrate.
    pub fn check(self, setup: RollingSetup) -> Result<ValidFitParams, FitError> {
        let valid = self.check_ranges(setup)?;
        check_physics(valid.physics, &setup)?;
        Ok(valid)
    }

    /// [`Self::check`] without the one check that depends on the body and
    /// not on a setting's own range: whether an exact solution exists for
    /// `physics = "exact"`. [`crate::FitSettings::check`] checks the
    /// settings as they are read, against a neutral set-up.
    pub(crate) fn check_ranges(self, setup: RollingSetup) -> Result<ValidFitParams, FitError> {
        let e1_max = modulus("E1_max", self.e1_max)?;
        let anchor = match self.anchor {
            None => None,
            Some(anchor) => Some(reduce_anchor(anchor, &setup, e1_max)?),
        };
        check_terms(&self.terms)?;
        self.check_runs()?;
        let model_tolerance = positive("tolerance", self.model_tolerance)?;
        if let Some(s) = &self.start {
            check_start(s)?;
        }
        check_shift(&self.shift)?;
        if let Some(sigma) = self.dma_sigma
            && !(sigma.is_finite() && (DMA_SIGMA_RANGE.0..=DMA_SIGMA_RANGE.1).contains(&sigma))
        {
            return Err(FitError::setting(
                "dma_sigma",
                format!(
                    "{sigma} must lie in 1e-5 … 1: the relative standard deviation of E′ and E″ \
                     (0.01 for 1 %)"
                ),
            ));
        }
        Ok(ValidFitParams {
            method: self.method,
            terms: self.terms,
            anchor,
            e1_max,
            lambda: self.lambda,
            seed: self.seed,
            starts: self.starts,
            max_evaluations: self.max_evaluations,
            model_tolerance,
            start: self.start,
            shift: self.shift,
            physics: self.physics,
            setup,
            bands: true,
            coarse: false,
            path_top: None,
            cancel: Cancel::default(),
            progress: Observer::default(),
            friction_factor: self.friction_factor,
            dma_sigma: self.dma_sigma,
            dma: None,
            profile: true,
            evidence: false,
        })
    }

    /// λ, the number of starts and the evaluation budget.
    fn check_runs(&self) -> Result<(), FitError> {
        if let Lambda::Fixed(l) = self.lambda
            && !(l.is_finite() && l >= 0.0)
        {
            return Err(FitError::setting(
                "lambda",
                format!("{l} must be a finite number ≥ 0"),
            ));
        }
        if self.starts == 0 || self.starts > 100 {
            return Err(FitError::setting(
                "starts",
                format!("{} starts: use 1 to 100", self.starts),
            ));
        }
        if let Some(0) = self.max_evaluations {
            return Err(FitError::setting("max_evaluations", "must be at least 1"));
        }
        Ok(())
    }
}

/// The relaxation-time rule.
fn check_terms(terms: &TermRule) -> Result<(), FitError> {
    match terms {
        TermRule::PerDecade(d) => {
            if !(d.is_finite() && *d >= 0.5 && *d <= 10.0) {
                return Err(FitError::setting(
                    "terms",
                    format!("{d} terms per decade: use 0.5 to 10"),
                ));
            }
        }
        TermRule::Count(n) => {
            if *n < 2 || *n > 200 {
                return Err(FitError::setting(
                    "terms",
                    format!("{n} terms: use 2 to 200"),
                ));
            }
        }
        TermRule::Auto => {}
        TermRule::Explicit(tau) => {
            if tau.len() < 2 {
                return Err(FitError::setting(
                    "tau",
                    "give at least two relaxation times",
                ));
            }
            for (i, &t) in tau.iter().enumerate() {
                positive(&format!("tau[{i}]"), t)?;
                if i > 0 && t <= tau[i - 1] {
                    return Err(FitError::setting(
                        "tau",
                        format!("relaxation times must increase (tau[{i}] = {t})"),
                    ));
                }
            }
        }
    }
    Ok(())
}

/// A starting material.
fn check_start(s: &StartMaterial) -> Result<(), FitError> {
    positive("material.E0", s.static_modulus)?;
    if !(s.glassy_modulus.is_finite() && s.glassy_modulus > s.static_modulus) {
        return Err(FitError::setting(
            "material.E1",
            "the starting glassy modulus must exceed the static one",
        ));
    }
    Ok(())
}

/// The settings of a temperature-set fit.
fn check_shift(shift: &ShiftSettings) -> Result<(), FitError> {
    if let Some(t) = shift.t_ref
        && !t.is_finite()
    {
        return Err(FitError::setting(
            "T_ref",
            format!("{t} must be a finite temperature"),
        ));
    }
    if let Some((c1, c2)) = shift.wlf_start {
        positive("C1", c1)?;
        positive("C2", c2)?;
    }
    if let Some(vertical) = &shift.vertical {
        // b_T = 1 at the vertical factors' own T_ref; a master curve at
        // another temperature would need them renormalised.
        let t = vertical.t_ref();
        if shift
            .t_ref
            .is_none_or(|fit| (fit - t).abs() > FreeShift::TEMPERATURE_TOLERANCE)
        {
            return Err(FitError::setting(
                "T_ref",
                format!(
                    "the vertical factors b_T are relative to T_ref = {t} °C (b_T = 1 there), \
                     so the master curve must be fitted at T_ref = {t} °C, not at {}",
                    shift
                        .t_ref
                        .map_or("the middle temperature".to_string(), |f| format!("{f} °C"))
                ),
            ));
        }
    }
    Ok(())
}

/// `physics = "exact"` needs an exact solution for the set-up: a body
/// that `exact_body` solves, on a half-space (no film). Its own refusal is
/// passed on, naming the key.
fn check_physics(physics: Physics, setup: &RollingSetup) -> Result<(), FitError> {
    if physics == Physics::Approximate {
        return Ok(());
    }
    if let Some(thickness) = setup.substrate.film_thickness {
        return Err(FitError::setting(
            "physics",
            format!(
                "\"exact\" needs a half-space: there is no exact rolling solution for a film \
                 (substrate thickness {thickness} m) on a rigid base; use \"approximate\""
            ),
        ));
    }
    // Whether a body exists depends on the shape alone; a probe material
    // (E0 = 1 MPa, E1 = 1 GPa, τ = 1 s) asks without building the fit's.
    let probe = Prony::new(1e9, vec![1e9 - 1e6], vec![1.0])?;
    let g = setup.geometry;
    match exact_body(
        g.shape,
        &probe,
        setup.substrate.poisson,
        g.radius,
        g.load,
        1e-3,
    ) {
        Ok(_) => Ok(()),
        Err(ModelError::ExactNotAvailable { why }) => Err(FitError::setting(
            "physics",
            format!("\"exact\": {why}; use \"approximate\""),
        )),
        Err(other) => Err(FitError::setting("physics", format!("\"exact\": {other}"))),
    }
}

/// The bundled example's set-up (a 5 mm steel ball at 1 N on a thick rubber,
/// ν = 0.5, dynamic contact), shared by the unit tests: the neutral set-up
/// the settings are checked against.
#[cfg(test)]
pub(crate) fn example_setup() -> RollingSetup {
    crate::settings::neutral_setup()
}
