//! fit.json as read back (docs/ARCHITECTURE.md, "Contract", "Fit folder"):
//! the keys the reports use, the contract's required and everything else
//! optional, and the checks serde cannot make.
//!
//! A fit.json edited by hand is checked where a wrong value would be read
//! as something else rather than fail: Poisson's ratio in [0, 0.5], the
//! shift model "wlf" (with C1, C2 > 0 and C2 + T − T_ref > 0 at its
//! temperatures), "arrhenius" (with E_a > 0, without C1, C2) or "free"
//! (without any of them). Errors name fit.json and the
//! line of the key (`shift.log_aT[2].T`).

use std::path::{Path, PathBuf};

use serde::{Deserialize, Deserializer};

use rollfit_model::modulus::Arrhenius;

use super::json_error::line_of_key;
use super::quality::{CondensedSummary, QualitySummary, ScaleSummary};
use crate::error::IoError;
use crate::error::place;

/// fit.json, the keys the report uses.
#[derive(Debug, Clone, Deserialize)]
pub struct FitSummary {
    /// The recovered Prony series.
    pub model: ModelSummary,
    /// Poisson's ratio used by the fit.
    pub poisson: f64,
    /// The window the data determine, rad/s.
    pub window: WindowSummary,
    /// The optimiser.
    pub method: String,
    /// V at the optimum.
    pub objective: f64,
    /// Iterations of the final run.
    pub iterations: usize,
    /// Whether the final run converged.
    pub converged: bool,
    /// Wall time of the fit, s.
    pub wall_time_s: f64,
    /// How the final run ended.
    #[serde(default)]
    pub stop_reason: Option<String>,
    /// Weighted misfit per point.
    #[serde(default)]
    pub misfit_per_point: Option<f64>,
    /// Evaluations of all runs.
    #[serde(default)]
    pub evaluations: Option<usize>,
    /// The smoothness weight.
    #[serde(default)]
    pub lambda: Option<LambdaSummary>,
    /// The scale anchor.
    #[serde(default)]
    pub anchor: Option<AnchorSummary>,
    /// Effective number of parameters.
    #[serde(default)]
    pub effective_parameters: Option<f64>,
    /// The time–temperature shift of a temperature set.
    #[serde(default)]
    pub shift: Option<ShiftSummary>,
    /// Warnings of the fit.
    #[serde(default)]
    pub warnings: Vec<String>,
    /// Every solver run.
    #[serde(default)]
    pub runs: Vec<RunSummary>,
    /// (evaluations, best V) of the final run.
    #[serde(default)]
    pub history: Vec<[f64; 2]>,
    /// Where the fit's inputs came from.
    #[serde(default)]
    pub input: Option<InputSummary>,
    /// How a fit with `physics = "exact"` reached the exact contact
    /// (absent: the approximate physics of Eq. (11)/(17)).
    #[serde(default)]
    pub physics: Option<PhysicsSummary>,
    /// A joint fit with DMA data (`dma`): each part's χ², the
    /// compatibility test, κ and the DMA points with the joint curve
    /// (absent: a fit of rolling data alone).
    #[serde(default)]
    pub joint: Option<rollfit_fit::JointRecord>,
    /// The goodness-of-fit verdict, its tests and the noise they assume.
    #[serde(default)]
    pub fit_quality: Option<QualitySummary>,
    /// Without an anchor: how well the data determine the modulus scale.
    #[serde(default)]
    pub scale: Option<ScaleSummary>,
    /// Dense data: how the rows were condensed to bins before the fit.
    #[serde(default)]
    pub condensed: Option<CondensedSummary>,
}

/// fit.json's `physics` (fits with `physics = "exact"`).
#[derive(Debug, Clone, Deserialize)]
pub struct PhysicsSummary {
    /// "exact".
    pub kind: String,
    /// Refits with the corrected model.
    #[serde(default)]
    pub iterations: Option<usize>,
    /// Exact solutions computed.
    #[serde(default)]
    pub exact_solves: Option<usize>,
    /// Whether the correction stopped changing.
    #[serde(default)]
    pub converged: Option<bool>,
    /// max |μ_exact/μ_approx − 1|.
    #[serde(default)]
    pub max_correction: Option<f64>,
    /// The relative accuracy asked of each exact μ.
    #[serde(default)]
    pub accuracy: Option<f64>,
}

/// The Prony series of fit.json: E*(ω) = E1 − Σ H_k/(1 + iωτ_k).
#[derive(Debug, Clone, Deserialize)]
pub struct ModelSummary {
    /// Always "prony" for rollfit.
    pub kind: String,
    /// Glassy modulus, Pa.
    #[serde(rename = "E1")]
    pub glassy_modulus: f64,
    /// Relaxation times, s.
    pub tau: Vec<f64>,
    /// Strengths, Pa.
    #[serde(rename = "H")]
    pub strengths: Vec<f64>,
    /// Whether the data determine each strength (all true when absent).
    #[serde(default)]
    pub determined: Vec<bool>,
    /// 1σ of ln H_k.
    #[serde(default, rename = "ln_H_sigma")]
    pub ln_strength_sigma: Vec<f64>,
}

/// rad/s.
#[derive(Debug, Clone, Copy, Deserialize)]
pub struct WindowSummary {
    /// rad/s.
    pub omega_min: f64,
    /// rad/s.
    pub omega_max: f64,
}

/// The smoothness weight.
#[derive(Debug, Clone, Deserialize)]
pub struct LambdaSummary {
    /// λ.
    pub value: f64,
    /// How it was chosen.
    #[serde(default)]
    pub rule: Option<String>,
}

/// The scale anchor.
#[derive(Debug, Clone, Deserialize)]
pub struct AnchorSummary {
    /// "E0", "E_at" or "contact_radius".
    pub source: String,
    /// rad/s.
    pub omega: f64,
    /// |E*|, Pa.
    #[serde(rename = "E")]
    pub modulus: f64,
}

/// The shift of a temperature set.
#[derive(Debug, Clone, Deserialize)]
pub struct ShiftSummary {
    /// "wlf", "arrhenius" or "free".
    pub model: String,
    /// °C.
    #[serde(rename = "T_ref")]
    pub t_ref: f64,
    /// WLF C1.
    #[serde(default, rename = "C1")]
    pub c1: Option<f64>,
    /// WLF C2, K.
    #[serde(default, rename = "C2")]
    pub c2: Option<f64>,
    /// 1σ of C1.
    #[serde(default, rename = "C1_sigma")]
    pub c1_sigma: Option<f64>,
    /// 1σ of C2, K.
    #[serde(default, rename = "C2_sigma")]
    pub c2_sigma: Option<f64>,
    /// Arrhenius activation energy, J/mol.
    #[serde(default, rename = "E_a")]
    pub activation_energy: Option<f64>,
    /// 1σ of E_a, J/mol.
    #[serde(default, rename = "E_a_sigma")]
    pub activation_energy_sigma: Option<f64>,
    /// log10 a_T per measured temperature.
    #[serde(rename = "log_aT")]
    pub log_shift: Vec<LogShiftSummary>,
}

/// log10 a_T at one temperature.
#[derive(Debug, Clone, Copy, Deserialize)]
pub struct LogShiftSummary {
    /// °C.
    #[serde(rename = "T")]
    pub temperature: f64,
    /// log10 a_T.
    #[serde(rename = "log_aT")]
    pub log_shift: f64,
    /// 1σ (NaN where fit.json has null: a shift the data do not
    /// determine).
    #[serde(default, rename = "log_aT_sigma", deserialize_with = "null_as_nan")]
    pub log_shift_sigma: f64,
}

/// A number, or null read as NaN (a σ fit.json could not write).
fn null_as_nan<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(deserializer)?.unwrap_or(f64::NAN))
}

impl FitSummary {
    /// What serde cannot check: values that would otherwise be read as
    /// something else (see the module doc). `text` is fit.json, for lines.
    pub(super) fn check(&self, path: &Path, text: &str) -> Result<(), IoError> {
        let at = |key: &str| (path.to_path_buf(), line_of_key(text, key));
        if let Err(problem) = rollfit_model::check_poisson(self.poisson) {
            let (path, line) = at("poisson");
            return Err(err!("{}: {problem}", place(&path, line)));
        }
        let Some(shift) = &self.shift else {
            return Ok(());
        };
        match (shift.model.as_str(), shift.c1, shift.c2) {
            ("wlf", Some(c1), Some(c2)) => check_wlf(shift, c1, c2, &at),
            ("wlf", c1, _) => {
                let (path, line) = at("shift.model");
                let key = if c1.is_none() { "C1" } else { "C2" };
                Err(err!(
                    "{}: shift.model = \"wlf\" needs the key shift.{key}",
                    place(&path, line)
                ))
            }
            ("arrhenius", None, None) => match shift.activation_energy {
                Some(e) if e > 0.0 => Ok(()),
                value => {
                    let (path, line) = at(if value.is_some() {
                        "shift.E_a"
                    } else {
                        "shift.model"
                    });
                    Err({
                        let path = &path;
                        let line = &line;
                        let value = &value;
                        err!(
                            "{}: shift.model = \"arrhenius\" needs a positive shift.E_a (J/mol){}",
                            place(path, *line),
                            value.map_or_else(String::new, |v| format!(", got {v}"))
                        )
                    })
                }
            },
            ("arrhenius", c1, _) => {
                let key = if c1.is_some() { "C1" } else { "C2" };
                let (path, line) = at(&format!("shift.{key}"));
                Err(err!(
                    "{}: shift.{key} does not belong to shift.model = \"arrhenius\" (it takes T_ref, E_a \
         and log_aT)",
                    place(&path, line)
                ))
            }
            ("free", None, None) if shift.activation_energy.is_none() => Ok(()),
            ("free", None, None) => {
                let (path, line) = at("shift.E_a");
                Err(err!(
                    "{}: shift.{key} does not belong to shift.model = \"free\" (it takes T_ref and log_aT; a \
         WLF shift is model \"wlf\", an Arrhenius one \"arrhenius\")",
                    place(&path, line),
                    key = "E_a"
                ))
            }
            ("free", c1, _) => {
                let key = if c1.is_some() { "C1" } else { "C2" };
                let (path, line) = at(&format!("shift.{key}"));
                Err(err!(
                    "{}: shift.{key} does not belong to shift.model = \"free\" (it takes T_ref and log_aT; a \
         WLF shift is model \"wlf\", an Arrhenius one \"arrhenius\")",
                    place(&path, line)
                ))
            }
            (other, _, _) => {
                let (path, line) = at("shift.model");
                Err(err!(
                    "{}: shift.model = \"{model}\": unknown shift model; allowed: \"wlf\", \"arrhenius\", \
         \"free\"",
                    place(&path, line),
                    model = other
                ))
            }
        }
    }
}

/// The WLF constants of `shift` and their divergence below its listed
/// temperatures; `at` gives fit.json and the line of a key.
fn check_wlf(
    shift: &ShiftSummary,
    c1: f64,
    c2: f64,
    at: &dyn Fn(&str) -> (PathBuf, Option<usize>),
) -> Result<(), IoError> {
    if c1 <= 0.0 {
        let (path, line) = at("shift.C1");
        return Err(err!(
            "{}: shift.C1 = {value}: the WLF constant C1 must be > 0",
            place(&path, line),
            value = c1
        ));
    }
    if c2 <= 0.0 {
        let (path, line) = at("shift.C2");
        return Err(err!(
            "{}: shift.C2 = {value}: the WLF constant C2 must be > 0 K",
            place(&path, line),
            value = c2
        ));
    }
    for (index, s) in shift.log_shift.iter().enumerate() {
        let denominator = c2 + s.temperature - shift.t_ref;
        if denominator <= 0.0 {
            let (path, line) = at(&format!("shift.log_aT[{index}].T"));
            return Err(err!(
                "{}: shift.log_aT[{index}].T = {temperature} °C: C2 + T − T_ref = {denominator} K is not \
         positive (C2 = {c2} K, T_ref = {t_ref} °C): the WLF shift diverges at T_ref − C2 = {} °C \
         and means nothing below",
                place(&path, line),
                shift.t_ref - c2,
                t_ref = shift.t_ref,
                temperature = s.temperature
            ));
        }
    }
    Ok(())
}

impl ShiftSummary {
    /// log10 a_T at `t` (°C): WLF when the constants are given, else the
    /// listed value at a listed temperature, linear in T between listed
    /// ones, and `None` outside the listed range (a free shift says nothing
    /// there).
    pub fn log_shift_at(&self, t: f64) -> Option<f64> {
        if let (Some(c1), Some(c2)) = (self.c1, self.c2) {
            let dt = t - self.t_ref;
            return (c2 + dt > 0.0).then(|| -c1 * dt / (c2 + dt));
        }
        if let (Some(energy), "arrhenius") = (self.activation_energy, self.model.as_str()) {
            return Arrhenius::new(self.t_ref, energy)
                .and_then(|law| law.log10_shift(t))
                .ok();
        }
        let mut points: Vec<(f64, f64)> = self
            .log_shift
            .iter()
            .map(|s| (s.temperature, s.log_shift))
            .collect();
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        let tolerance = 1e-6;
        for pair in points.windows(2) {
            let ((t0, l0), (t1, l1)) = (pair[0], pair[1]);
            if t >= t0 - tolerance && t <= t1 + tolerance {
                let s = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
                return Some(l0 + s * (l1 - l0));
            }
        }
        points
            .first()
            .filter(|p| points.len() == 1 && (p.0 - t).abs() <= tolerance)
            .map(|p| p.1)
    }
}

/// One solver run.
#[derive(Debug, Clone, Deserialize)]
pub struct RunSummary {
    /// What the run was for.
    pub stage: String,
    /// Method name.
    pub method: String,
    /// V at the end.
    pub objective: f64,
    /// Objective evaluations.
    pub evaluations: usize,
    /// Whether it converged.
    pub converged: bool,
    /// (evaluations, best V so far) where V improved.
    #[serde(default)]
    pub history: Vec<[f64; 2]>,
}

/// Where the fit's inputs came from.
#[derive(Debug, Clone, Deserialize)]
pub struct InputSummary {
    /// Scene file.
    #[serde(default)]
    pub scene: Option<String>,
    /// Data file.
    #[serde(default)]
    pub data: Option<String>,
    /// Number of data points.
    #[serde(default)]
    pub points: Option<usize>,
}
