//! Fit settings as users write them, parsed once for every front door.
//!
//! The scene's `[fit]` table, a batch manifest (`[defaults]` and each
//! `[[entry]]`) and the flags of `rollfit fit` and `rollfit batch` name the
//! same settings with the same spellings. Each front door hands every value
//! it finds, with the key it was written under, to [`FitSettings::set`]:
//! that one function knows the keys, their aliases and their syntax, and
//! each setting's text form is its type's [`FromStr`]. What the value means
//! for the fit is checked by [`FitParams::check`] alone: a front door runs
//! it on each setting as it reads it ([`FitSettings::check`], so that a
//! value out of range is refused where it was written), and the fit runs it
//! again on everything against the rolling set-up.
//!
//! | key | value | |
//! |---|---|---|
//! | `method` | `"auto"`, `"levenberg-marquardt"` (`"lm"`), `"lbfgs"` (`"l-bfgs"`), `"nelder-mead"` (`"amoeba"`) | |
//! | `lambda` | a number ≥ 0, or `"auto"` | |
//! | `seed` | a whole number ≥ 0 | |
//! | `starts` | a whole number | |
//! | `terms` | a count N, `"auto"`, or a density `"X/decade"` | aliases: `terms_per_decade = X`, `tau = [τ1, τ2, …]` |
//! | `max_evaluations` | a whole number | |
//! | `tolerance` | the forward model's relative quadrature tolerance | |
//! | `E1_max` | upper bound of the glassy modulus, Pa | |
//! | `shift` | `"auto"` (default), `"wlf"`, `"arrhenius"` or `"free"` (temperature sets) | |
//! | `T_ref` | reference temperature of the master curve, °C | |
//! | `cross_check` | `true` or `false` | |
//! | `physics` | `"approximate"` (Eq. (11)/(17), the default) or `"exact"` (defect correction, [`crate::exact_physics`]) | |
//!
//! Where a file format gives a number, the value arrives as a number
//! ([`SettingValue::Number`]); text from a command line or a quoted TOML
//! value arrives as [`SettingValue::Text`] and goes through `FromStr`, so
//! `terms = "2/decade"`, `--terms 2/decade` and `terms_per_decade = 2` are
//! the same setting. The scale anchors (`E0`, `E_at`, `contact_radius`) are
//! measurements rather than settings and stay with the scene reader.
//!
//! ```
//! use rollfit_fit::{FitParams, FitSettings, SettingValue, TermRule};
//!
//! let mut scene = FitSettings::default();
//! scene.set("terms_per_decade", SettingValue::Number(2.0))?;
//! let mut flags = FitSettings::default();
//! flags.set("terms", SettingValue::Text("2/decade"))?;
//! flags.set("starts", SettingValue::Text("1"))?;
//! flags.check()?;
//! assert_eq!(flags.terms, scene.terms);
//!
//! let mut params = FitParams::default();
//! flags.over(&scene).apply(&mut params);
//! assert_eq!((params.terms, params.starts), (TermRule::PerDecade(2.0), 1));
//! # Ok::<(), rollfit_fit::FitError>(())
//! ```

use std::str::FromStr;

use rollfit_model::{ContactSize, Geometry, Shape, Substrate};

use crate::error::FitError;
use crate::params::{
    FitParams, FrictionFactor, Lambda, Method, Physics, RollingSetup, ShiftKind, TermRule,
};

/// What `lambda` takes, for messages.
const LAMBDA_FORMS: &str =
    "a finite number ≥ 0 (0 switches the smoothness penalty off) or \"auto\"";

/// What `terms` takes, for messages.
const TERMS_FORMS: &str = "a whole number of terms, \"auto\" or a density such as \"2/decade\"";

impl FromStr for Method {
    type Err = FitError;

    /// A solver name; "auto" and "lm" select Levenberg–Marquardt.
    fn from_str(text: &str) -> Result<Self, FitError> {
        Method::parse(text.trim())
    }
}

impl FromStr for Lambda {
    type Err = FitError;

    /// `"auto"` or a finite number ≥ 0.
    fn from_str(text: &str) -> Result<Self, FitError> {
        let text = text.trim();
        if text == "auto" {
            return Ok(Lambda::Auto);
        }
        match text.parse::<f64>() {
            Ok(l) => fixed_lambda(l, &format!("{text:?}")),
            Err(_) => Err(refuse_lambda(&format!("{text:?}"))),
        }
    }
}

/// A fixed λ: finite and ≥ 0 (`shown`: the value as the message shows it).
fn fixed_lambda(l: f64, shown: &str) -> Result<Lambda, FitError> {
    if l.is_finite() && l >= 0.0 {
        Ok(Lambda::Fixed(l))
    } else {
        Err(refuse_lambda(shown))
    }
}

fn refuse_lambda(shown: &str) -> FitError {
    FitError::setting("lambda", format!("expected {LAMBDA_FORMS}, got {shown}"))
}

impl FromStr for TermRule {
    type Err = FitError;

    /// A count N, `"auto"` or a density `"X/decade"`.
    fn from_str(text: &str) -> Result<Self, FitError> {
        let text = text.trim();
        if text == "auto" {
            return Ok(TermRule::Auto);
        }
        if let Some(density) = text.strip_suffix("/decade") {
            return match density.trim().parse::<f64>() {
                Ok(d) if d.is_finite() && d > 0.0 => Ok(TermRule::PerDecade(d)),
                _ => Err(FitError::setting(
                    "terms",
                    format!(
                        "expected a positive number of terms per decade before \"/decade\", \
                         got {text:?}"
                    ),
                )),
            };
        }
        text.parse::<usize>().map(TermRule::Count).map_err(|_| {
            FitError::setting("terms", format!("expected {TERMS_FORMS}, got {text:?}"))
        })
    }
}

impl FromStr for ShiftKind {
    type Err = FitError;

    /// `"auto"`, `"wlf"`, `"arrhenius"` or `"free"`.
    fn from_str(text: &str) -> Result<Self, FitError> {
        match text.trim() {
            "auto" => Ok(ShiftKind::Auto),
            "wlf" => Ok(ShiftKind::Wlf),
            "arrhenius" => Ok(ShiftKind::Arrhenius),
            "free" => Ok(ShiftKind::Free),
            other => Err(FitError::setting(
                "shift",
                format!(
                    "unknown shift {other:?} (use \"auto\", \"wlf\", \"arrhenius\" or \"free\")"
                ),
            )),
        }
    }
}

impl FromStr for Physics {
    type Err = FitError;

    /// `"approximate"` or `"exact"`.
    fn from_str(text: &str) -> Result<Self, FitError> {
        match text.trim() {
            "approximate" => Ok(Physics::Approximate),
            "exact" => Ok(Physics::Exact),
            other => Err(FitError::setting(
                "physics",
                format!("unknown physics {other:?} (use \"approximate\" or \"exact\")"),
            )),
        }
    }
}

impl FromStr for FrictionFactor {
    type Err = FitError;

    /// `"one"` (κ = 1) or `"free"` (κ fitted).
    fn from_str(text: &str) -> Result<Self, FitError> {
        match text.trim() {
            "one" | "1" => Ok(FrictionFactor::One),
            "free" => Ok(FrictionFactor::Free),
            other => Err(FitError::setting(
                "friction_factor",
                format!("unknown friction factor {other:?} (use \"one\" or \"free\")"),
            )),
        }
    }
}

/// A setting's value as a front door found it.
#[derive(Debug, Clone, PartialEq)]
pub enum SettingValue<'a> {
    /// Text: a command-line argument or a quoted value in a file.
    Text(&'a str),
    /// A number written as a number in a file.
    Number(f64),
    /// A whole number written as such in a file.
    Integer(i64),
    /// `true` or `false` in a file.
    Boolean(bool),
    /// A list of numbers in a file.
    Numbers(Vec<f64>),
}

/// The settings a user gave (None: not given), from any front door.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FitSettings {
    /// `method`.
    pub method: Option<Method>,
    /// `lambda`.
    pub lambda: Option<Lambda>,
    /// `seed`.
    pub seed: Option<u64>,
    /// `starts`.
    pub starts: Option<usize>,
    /// `terms` (or `terms_per_decade`, `tau`).
    pub terms: Option<TermRule>,
    /// `max_evaluations`.
    pub max_evaluations: Option<usize>,
    /// `tolerance`: the forward model's relative quadrature tolerance.
    pub tolerance: Option<f64>,
    /// `E1_max`, Pa.
    pub e1_max: Option<f64>,
    /// `shift`.
    pub shift: Option<ShiftKind>,
    /// `T_ref`, °C.
    pub t_ref: Option<f64>,
    /// `cross_check`.
    pub cross_check: Option<bool>,
    /// `physics`.
    pub physics: Option<Physics>,
    /// `friction_factor`: κ of a joint fit, `"one"` or `"free"`.
    pub friction_factor: Option<FrictionFactor>,
    /// `dma_sigma`: the relative σ of the DMA moduli of a joint fit.
    pub dma_sigma: Option<f64>,
    /// `dma`: the DMA file of a joint fit, as written (a front door reads
    /// it, relative to the file that names it, and hands the isotherms to
    /// [`crate::ValidFitParams::with_dma`]).
    pub dma: Option<String>,
    /// The key `terms` was set under, to refuse two spellings of it.
    terms_key: Option<&'static str>,
}

/// The keys [`FitSettings::set`] knows, canonical spellings first.
pub const SETTING_KEYS: [&str; 17] = [
    "method",
    "lambda",
    "seed",
    "starts",
    "terms",
    "max_evaluations",
    "tolerance",
    "E1_max",
    "shift",
    "T_ref",
    "cross_check",
    "physics",
    "dma",
    "dma_sigma",
    "friction_factor",
    "terms_per_decade",
    "tau",
];

impl FitSettings {
    /// Sets `key` from `value`: the one parser of fit settings. Unknown
    /// keys, values of the wrong kind or syntax, and a second spelling of
    /// the relaxation times are refused, naming the key.
    pub fn set(&mut self, key: &str, value: SettingValue<'_>) -> Result<(), FitError> {
        match key {
            "method" => {
                let name = text_of(key, &value, "a solver name such as \"lbfgs\"")?;
                self.method = Some(name.parse()?);
            }
            "lambda" => {
                self.lambda = Some(match value {
                    SettingValue::Number(l) => fixed_lambda(l, &l.to_string())?,
                    SettingValue::Integer(l) => fixed_lambda(l as f64, &l.to_string())?,
                    SettingValue::Text(text) => text.parse()?,
                    other => return Err(wrong_kind(key, &other, LAMBDA_FORMS)),
                })
            }
            "seed" => self.seed = Some(whole(key, &value)?),
            "starts" => self.starts = Some(whole(key, &value)?),
            "max_evaluations" => self.max_evaluations = Some(whole(key, &value)?),
            "terms" => {
                let rule = match value {
                    SettingValue::Integer(n) => {
                        TermRule::Count(usize::try_from(n).map_err(|_| {
                            FitError::setting(key, format!("{n} terms: use 2 to 200"))
                        })?)
                    }
                    SettingValue::Text(text) => text.parse()?,
                    other => return Err(wrong_kind(key, &other, TERMS_FORMS)),
                };
                self.set_terms("terms", rule)?;
            }
            "terms_per_decade" => {
                let density = number(key, &value)?;
                if !(density.is_finite() && density > 0.0) {
                    return Err(FitError::setting(
                        key,
                        format!("terms_per_decade = {density}: must be greater than zero"),
                    ));
                }
                self.set_terms("terms_per_decade", TermRule::PerDecade(density))?;
            }
            "tau" => match value {
                SettingValue::Numbers(tau) => {
                    if let Some((i, t)) = tau
                        .iter()
                        .enumerate()
                        .find(|(_, t)| !(t.is_finite() && **t > 0.0))
                    {
                        return Err(FitError::setting(
                            key,
                            format!("tau[{i}] = {t}: relaxation times must be greater than zero"),
                        ));
                    }
                    self.set_terms("tau", TermRule::Explicit(tau))?
                }
                other => return Err(wrong_kind(key, &other, "a list of relaxation times, s")),
            },
            "tolerance" => self.tolerance = Some(number(key, &value)?),
            "E1_max" => self.e1_max = Some(number(key, &value)?),
            "T_ref" => self.t_ref = Some(number(key, &value)?),
            "shift" => {
                self.shift = Some(
                    text_of(key, &value, "\"auto\", \"wlf\", \"arrhenius\" or \"free\"")?
                        .parse()?,
                )
            }
            "cross_check" => match value {
                SettingValue::Boolean(b) => self.cross_check = Some(b),
                SettingValue::Text(t @ ("true" | "false")) => self.cross_check = Some(t == "true"),
                other => return Err(wrong_kind(key, &other, "true or false")),
            },
            "physics" => {
                let name = text_of(key, &value, "\"approximate\" or \"exact\"")?;
                self.physics = Some(name.parse()?);
            }
            "friction_factor" => {
                let name = text_of(key, &value, "\"one\" or \"free\"")?;
                self.friction_factor = Some(name.parse()?);
            }
            "dma_sigma" => self.dma_sigma = Some(number(key, &value)?),
            "dma" => {
                let path = text_of(key, &value, "the path of a DMA file")?;
                if path.trim().is_empty() {
                    return Err(FitError::setting(key, "the DMA file's path is empty"));
                }
                self.dma = Some(path.to_string());
            }
            other => {
                return Err(FitError::setting(
                    other,
                    format!("unknown fit setting (known: {})", SETTING_KEYS.join(", ")),
                ));
            }
        }
        Ok(())
    }

    fn set_terms(&mut self, key: &'static str, rule: TermRule) -> Result<(), FitError> {
        if let Some(first) = self.terms_key.filter(|&k| k != key) {
            return Err(FitError::setting(
                key,
                format!(
                    "`{first}` and `{key}` each choose the relaxation times: give at most one \
                     of terms, terms_per_decade and tau"
                ),
            ));
        }
        self.terms = Some(rule);
        self.terms_key = Some(key);
        Ok(())
    }

    /// These settings over `below`: what these leave unset comes from
    /// `below` (an entry over a manifest's defaults over the flags, the
    /// flags over a scene's `[fit]`).
    pub fn over(&self, below: &FitSettings) -> FitSettings {
        FitSettings {
            method: self.method.or(below.method),
            lambda: self.lambda.or(below.lambda),
            seed: self.seed.or(below.seed),
            starts: self.starts.or(below.starts),
            terms: self.terms.clone().or_else(|| below.terms.clone()),
            max_evaluations: self.max_evaluations.or(below.max_evaluations),
            tolerance: self.tolerance.or(below.tolerance),
            e1_max: self.e1_max.or(below.e1_max),
            shift: self.shift.or(below.shift),
            t_ref: self.t_ref.or(below.t_ref),
            cross_check: self.cross_check.or(below.cross_check),
            physics: self.physics.or(below.physics),
            friction_factor: self.friction_factor.or(below.friction_factor),
            dma_sigma: self.dma_sigma.or(below.dma_sigma),
            dma: self.dma.clone().or_else(|| below.dma.clone()),
            terms_key: if self.terms.is_some() {
                self.terms_key
            } else {
                below.terms_key
            },
        }
    }

    /// Checks the ranges of the given settings by [`FitParams::check`]:
    /// applied to the default parameters (which are valid, so only a given
    /// setting can fail) with a neutral rolling set-up (no setting's range
    /// depends on it). A front door calls it after each [`FitSettings::set`]
    /// so that a value out of range is refused where it was written; the
    /// fit checks everything again against the real set-up, and with it
    /// what depends on the body rather than on a range: whether
    /// `physics = "exact"` has an exact solution for it.
    pub fn check(&self) -> Result<(), FitError> {
        let mut params = FitParams::default();
        self.apply(&mut params);
        params.check_ranges(neutral_setup()).map(|_| ())
    }

    /// Whether these settings give the value that [`FitParams::check`]
    /// refused under `key` (the key of a [`FitError::InvalidSetting`]), so
    /// that a front door can say where the value came from. The
    /// relaxation times answer to `terms`, `tau` and `tau[i]`.
    pub fn gives(&self, key: &str) -> bool {
        match key {
            "method" => self.method.is_some(),
            "lambda" => self.lambda.is_some(),
            "seed" => self.seed.is_some(),
            "starts" => self.starts.is_some(),
            "terms" | "terms_per_decade" | "tau" => self.terms.is_some(),
            key if key.starts_with("tau[") => self.terms.is_some(),
            "max_evaluations" => self.max_evaluations.is_some(),
            "tolerance" => self.tolerance.is_some(),
            "E1_max" => self.e1_max.is_some(),
            "shift" => self.shift.is_some(),
            "T_ref" => self.t_ref.is_some(),
            "cross_check" => self.cross_check.is_some(),
            "physics" => self.physics.is_some(),
            "friction_factor" => self.friction_factor.is_some(),
            "dma_sigma" => self.dma_sigma.is_some(),
            "dma" => self.dma.is_some(),
            _ => false,
        }
    }

    /// Writes the given settings into `params`; the others keep their
    /// values. Ranges are checked by [`FitParams::check`].
    pub fn apply(&self, params: &mut FitParams) {
        if let Some(method) = self.method {
            params.method = method;
        }
        if let Some(lambda) = self.lambda {
            params.lambda = lambda;
        }
        if let Some(seed) = self.seed {
            params.seed = seed;
        }
        if let Some(starts) = self.starts {
            params.starts = starts;
        }
        if let Some(terms) = &self.terms {
            params.terms = terms.clone();
        }
        if let Some(budget) = self.max_evaluations {
            params.max_evaluations = Some(budget);
        }
        if let Some(tolerance) = self.tolerance {
            params.model_tolerance = tolerance;
        }
        if let Some(e1_max) = self.e1_max {
            params.e1_max = e1_max;
        }
        if let Some(kind) = self.shift {
            params.shift.kind = kind;
            // The law is now the one asked for here, not a substitute.
            params.shift.substituted = None;
        }
        if let Some(t_ref) = self.t_ref {
            params.shift.t_ref = Some(t_ref);
        }
        if let Some(cross_check) = self.cross_check {
            params.shift.cross_check = cross_check;
        }
        if let Some(physics) = self.physics {
            params.physics = physics;
        }
        if let Some(factor) = self.friction_factor {
            params.friction_factor = factor;
        }
        if let Some(sigma) = self.dma_sigma {
            params.dma_sigma = Some(sigma);
        }
    }
}

/// A rolling set-up no setting's range depends on (a 5 mm ball at 1 N on a
/// rubber half-space).
pub(crate) fn neutral_setup() -> RollingSetup {
    RollingSetup {
        geometry: Geometry {
            shape: Shape::Sphere,
            radius: 0.005,
            load: 1.0,
        },
        substrate: Substrate {
            poisson: 0.5,
            film_thickness: None,
        },
        contact: ContactSize::Dynamic,
    }
}

/// The text of `value`; `what` says what the text names, for the message.
fn text_of<'v>(key: &str, value: &'v SettingValue<'_>, what: &str) -> Result<&'v str, FitError> {
    match value {
        SettingValue::Text(text) => Ok(text),
        other => Err(wrong_kind(key, other, &format!("text ({what})"))),
    }
}

fn number(key: &str, value: &SettingValue<'_>) -> Result<f64, FitError> {
    match value {
        SettingValue::Number(x) => Ok(*x),
        SettingValue::Integer(n) => Ok(*n as f64),
        SettingValue::Text(text) => text
            .trim()
            .parse::<f64>()
            .map_err(|_| FitError::setting(key, format!("expected a number, got {text:?}"))),
        other => Err(wrong_kind(key, other, "a number")),
    }
}

fn whole<T: TryFrom<i64> + FromStr>(key: &str, value: &SettingValue<'_>) -> Result<T, FitError> {
    let refuse =
        |shown: String| FitError::setting(key, format!("expected a whole number ≥ 0, got {shown}"));
    match value {
        SettingValue::Integer(n) => T::try_from(*n).map_err(|_| refuse(n.to_string())),
        SettingValue::Text(text) => text.trim().parse().map_err(|_| refuse(format!("{text:?}"))),
        other => Err(wrong_kind(key, other, "a whole number ≥ 0")),
    }
}

/// A value of a kind `key` does not take, in serde's words (what a file's
/// reader has always said): "invalid type: integer `3`, expected …".
fn wrong_kind(key: &str, value: &SettingValue<'_>, expected: &str) -> FitError {
    let kind = match value {
        SettingValue::Text(t) => format!("string {t:?}"),
        SettingValue::Number(x) => format!("floating point `{x}`"),
        SettingValue::Integer(n) => format!("integer `{n}`"),
        SettingValue::Boolean(b) => format!("boolean `{b}`"),
        SettingValue::Numbers(_) => "a list".into(),
    };
    FitError::setting(key, format!("invalid type: {kind}, expected {expected}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn set(pairs: &[(&str, SettingValue<'_>)]) -> Result<FitSettings, FitError> {
        let mut s = FitSettings::default();
        for (key, value) in pairs {
            s.set(key, value.clone())?;
        }
        Ok(s)
    }

    #[test]
    fn the_three_spellings_of_a_density_are_one_setting() {
        let text = set(&[("terms", SettingValue::Text("2/decade"))]).unwrap();
        let number = set(&[("terms_per_decade", SettingValue::Number(2.0))]).unwrap();
        let integer = set(&[("terms_per_decade", SettingValue::Integer(2))]).unwrap();
        assert_eq!(text.terms, Some(TermRule::PerDecade(2.0)));
        assert_eq!(number.terms, text.terms);
        assert_eq!(integer.terms, text.terms);
        assert_eq!(
            set(&[("terms", SettingValue::Integer(24))]).unwrap().terms,
            Some(TermRule::Count(24))
        );
        assert_eq!("auto".parse::<TermRule>().unwrap(), TermRule::Auto);
        assert_eq!(" 12 ".parse::<TermRule>().unwrap(), TermRule::Count(12));
    }

    #[test]
    fn two_spellings_of_the_relaxation_times_are_refused() {
        let e = set(&[
            ("terms", SettingValue::Integer(20)),
            ("tau", SettingValue::Numbers(vec![1e-3, 1e-2])),
        ])
        .unwrap_err()
        .to_string();
        assert!(e.contains("`terms` and `tau`"), "{e}");
        // The same key twice is a layering, not a conflict.
        assert!(
            set(&[
                ("terms", SettingValue::Integer(20)),
                ("terms", SettingValue::Text("auto")),
            ])
            .is_ok()
        );
    }

    #[test]
    fn method_aliases_and_refusals() {
        for (text, method) in [
            ("auto", Method::LevenbergMarquardt),
            ("lm", Method::LevenbergMarquardt),
            ("l-bfgs", Method::Lbfgs),
            ("amoeba", Method::NelderMead),
        ] {
            assert_eq!(text.parse::<Method>().unwrap(), method);
        }
        let e = "newton".parse::<Method>().unwrap_err().to_string();
        assert!(e.contains("unknown method \"newton\""), "{e}");
        let e = set(&[("method", SettingValue::Integer(3))])
            .unwrap_err()
            .to_string();
        assert!(e.contains("`method`") && e.contains("expected text"), "{e}");
    }

    #[test]
    fn lambda_takes_numbers_and_auto_and_refuses_negatives() {
        assert_eq!(
            set(&[("lambda", SettingValue::Number(0.5))])
                .unwrap()
                .lambda,
            Some(Lambda::Fixed(0.5))
        );
        assert_eq!("auto".parse::<Lambda>().unwrap(), Lambda::Auto);
        for bad in ["-1", "nan", "inf", "big"] {
            assert!(bad.parse::<Lambda>().is_err(), "{bad}");
        }
    }

    #[test]
    fn unknown_keys_and_wrong_kinds_name_the_key() {
        let e = set(&[("lamda", SettingValue::Number(1.0))])
            .unwrap_err()
            .to_string();
        assert!(e.contains("`lamda`") && e.contains("unknown"), "{e}");
        let e = set(&[("seed", SettingValue::Integer(-1))])
            .unwrap_err()
            .to_string();
        assert!(e.contains("`seed`") && e.contains("-1"), "{e}");
        let e = set(&[("shift", SettingValue::Text("williams"))])
            .unwrap_err()
            .to_string();
        assert!(e.contains("`shift`") && e.contains("\"arrhenius\""), "{e}");
        for (text, kind) in [
            ("auto", ShiftKind::Auto),
            ("wlf", ShiftKind::Wlf),
            ("arrhenius", ShiftKind::Arrhenius),
            ("free", ShiftKind::Free),
        ] {
            assert_eq!(
                set(&[("shift", SettingValue::Text(text))]).unwrap().shift,
                Some(kind)
            );
        }
    }

    /// `physics` takes its two names as text, refuses others naming the
    /// key, layers like every setting, and is checked as a setting (its
    /// body, which the neutral set-up does not have, only by the fit).
    #[test]
    fn physics_takes_approximate_or_exact() {
        let exact = set(&[("physics", SettingValue::Text("exact"))]).unwrap();
        assert_eq!(exact.physics, Some(Physics::Exact));
        assert!(exact.gives("physics") && exact.check().is_ok());
        assert_eq!(
            " approximate".parse::<Physics>().unwrap(),
            Physics::Approximate
        );
        assert_eq!(Physics::default(), Physics::Approximate);
        let e = set(&[("physics", SettingValue::Text("exakt"))])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`physics`") && e.contains("\"exakt\"") && e.contains("\"exact\""),
            "{e}"
        );
        let e = set(&[("physics", SettingValue::Boolean(true))])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`physics`") && e.contains("expected text"),
            "{e}"
        );
        let mut params = FitParams::default();
        FitSettings::default().over(&exact).apply(&mut params);
        assert_eq!(params.physics, Physics::Exact);
        let mut params = FitParams::default();
        FitSettings::default().apply(&mut params);
        assert_eq!(params.physics, Physics::Approximate);
    }

    #[test]
    fn relaxation_times_must_be_positive() {
        let e = set(&[("tau", SettingValue::Numbers(vec![1.0, -2.0]))])
            .unwrap_err()
            .to_string();
        assert!(e.contains("`tau`") && e.contains("tau[1] = -2"), "{e}");
        let e = set(&[("terms_per_decade", SettingValue::Integer(0))])
            .unwrap_err()
            .to_string();
        assert!(e.contains("terms_per_decade = 0"), "{e}");
    }

    #[test]
    fn check_refuses_ranges_by_the_fit_rules_and_names_the_key() {
        assert!(FitSettings::default().check().is_ok());
        let e = set(&[("starts", SettingValue::Integer(0))])
            .unwrap()
            .check()
            .unwrap_err()
            .to_string();
        assert!(e.contains("`starts`") && e.contains("use 1 to 100"), "{e}");
        let e = set(&[("terms", SettingValue::Integer(1))])
            .unwrap()
            .check()
            .unwrap_err()
            .to_string();
        assert!(e.contains("`terms`") && e.contains("use 2 to 200"), "{e}");
        let s = set(&[("terms", SettingValue::Text("3/decade"))]).unwrap();
        assert!(s.check().is_ok());
        assert!(s.gives("terms") && s.gives("tau") && s.gives("tau[2]"));
        assert!(!s.gives("starts") && !s.gives("E0"));
    }

    #[test]
    fn a_lower_layer_keeps_its_spelling_only_where_it_gives_the_terms() {
        let scene = set(&[("tau", SettingValue::Numbers(vec![1.0, 2.0]))]).unwrap();
        let flags = set(&[("terms", SettingValue::Integer(20))]).unwrap();
        let mut both = flags.over(&scene);
        assert_eq!(both.terms, Some(TermRule::Count(20)));
        // Setting `terms` again is a layering, not a second spelling.
        assert!(both.set("terms", SettingValue::Text("auto")).is_ok());
        let mut below = FitSettings::default().over(&scene);
        let e = below
            .set("terms", SettingValue::Integer(20))
            .unwrap_err()
            .to_string();
        assert!(e.contains("`tau` and `terms`"), "{e}");
    }

    #[test]
    fn layers_fill_what_is_unset_and_apply_keeps_defaults() {
        let entry = set(&[("starts", SettingValue::Integer(1))]).unwrap();
        let defaults = set(&[
            ("starts", SettingValue::Integer(5)),
            ("seed", SettingValue::Text("7")),
        ])
        .unwrap();
        let layered = entry.over(&defaults);
        assert_eq!((layered.starts, layered.seed), (Some(1), Some(7)));
        let mut params = FitParams::default();
        layered.apply(&mut params);
        assert_eq!((params.starts, params.seed), (1, 7));
        assert_eq!(params.lambda, FitParams::default().lambda);
    }
}
