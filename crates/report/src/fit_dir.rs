//! A fit result directory as `rollfit fit` writes it (DESIGN.md §4):
//! fit.json, mu.csv and modulus.csv, read back for pictures and
//! comparisons.
//!
//! Only the contract's keys are required; everything rollfit adds beyond
//! them (bands, runs, shift, warnings) is optional, so a fit.json written
//! by another program that honours the contract can be reported too. The
//! master curve is rebuilt from the Prony series, so it can be drawn and
//! compared outside the window modulus.csv covers.

use std::path::{Path, PathBuf};

use num_complex::Complex64;
use rollfit_model::{Prony, ViscoelasticModulus};
use serde::Deserialize;

use crate::error::ReportError;

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
    /// "wlf" or "free".
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
    /// 1σ.
    #[serde(default, rename = "log_aT_sigma")]
    pub log_shift_sigma: f64,
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

/// One row of mu.csv.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionRow {
    /// Rolling speed, m/s.
    pub speed: f64,
    /// Measured μ.
    pub mu_measured: f64,
    /// Fitted μ.
    pub mu_fit: f64,
    /// Standard deviation of the measured μ, when known.
    pub sigma: Option<f64>,
    /// Temperature, °C (temperature sets).
    pub temperature: Option<f64>,
    /// v·a_T, m/s (temperature sets).
    pub reduced_speed: Option<f64>,
}

/// One row of modulus.csv: the master curve over the window with bands.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModulusRow {
    /// rad/s.
    pub omega: f64,
    /// E′, Pa.
    pub storage: f64,
    /// E″, Pa.
    pub loss: f64,
    /// tan δ.
    pub tan_delta: f64,
    /// 1σ of E′, Pa.
    pub storage_sigma: Option<f64>,
    /// 1σ of E″, Pa.
    pub loss_sigma: Option<f64>,
    /// 1σ of tan δ.
    pub tan_delta_sigma: Option<f64>,
}

/// A fit directory read back.
#[derive(Debug, Clone)]
pub struct FitDir {
    /// The directory.
    pub dir: PathBuf,
    /// fit.json.
    pub summary: FitSummary,
    /// mu.csv.
    pub friction: Vec<FrictionRow>,
    /// modulus.csv.
    pub modulus: Vec<ModulusRow>,
    /// The master curve at the reference state, rebuilt from fit.json.
    pub master_curve: Prony,
}

impl FitDir {
    /// Reads DIR/fit.json, DIR/mu.csv and DIR/modulus.csv.
    pub fn read(dir: &Path) -> Result<FitDir, ReportError> {
        if !dir.is_dir() {
            return Err(ReportError::format(
                dir,
                "not a fit directory (run `rollfit fit SCENE DATA -o DIR` first)",
            ));
        }
        let json_path = dir.join("fit.json");
        let text =
            std::fs::read_to_string(&json_path).map_err(|e| ReportError::io(&json_path, e))?;
        let summary: FitSummary = serde_json::from_str(&text).map_err(|e| {
            ReportError::line(&json_path, e.line(), format!("not a rollfit fit.json: {e}"))
        })?;
        if summary.model.kind != "prony" {
            return Err(ReportError::format(
                &json_path,
                format!(
                    "model.kind = \"{}\": only \"prony\" master curves can be reported",
                    summary.model.kind
                ),
            ));
        }
        let master_curve = Prony::new(
            summary.model.glassy_modulus,
            summary.model.strengths.clone(),
            summary.model.tau.clone(),
        )
        .map_err(|source| ReportError::Model {
            path: json_path.clone(),
            source,
        })?;
        let window = summary.window;
        if !(window.omega_min > 0.0 && window.omega_max > window.omega_min) {
            return Err(ReportError::format(
                &json_path,
                format!(
                    "window: omega_min = {}, omega_max = {}: need 0 < omega_min < omega_max",
                    window.omega_min, window.omega_max
                ),
            ));
        }
        let friction = read_friction(&dir.join("mu.csv"))?;
        let modulus = read_modulus(&dir.join("modulus.csv"))?;
        Ok(FitDir {
            dir: dir.to_path_buf(),
            summary,
            friction,
            modulus,
            master_curve,
        })
    }

    /// E*(ω) of the master curve at the reference state (Young's, Pa).
    pub fn modulus_at(&self, omega: f64) -> Complex64 {
        self.master_curve.modulus(omega)
    }

    /// Whether the fit is a temperature set (fit.json has a shift).
    pub fn is_temperature_set(&self) -> bool {
        self.summary.shift.is_some()
    }
}

/// A numeric CSV with named columns: '#' lines skipped, line numbers kept.
pub(crate) struct Table {
    pub path: PathBuf,
    pub header: Vec<String>,
    /// (line number, values) per data row.
    pub rows: Vec<(usize, Vec<f64>)>,
}

impl Table {
    pub(crate) fn read(path: &Path) -> Result<Table, ReportError> {
        let text = std::fs::read_to_string(path).map_err(|e| ReportError::io(path, e))?;
        Table::parse(path, &text)
    }

    pub(crate) fn parse(path: &Path, text: &str) -> Result<Table, ReportError> {
        let mut reader = csv::ReaderBuilder::new()
            .comment(Some(b'#'))
            .trim(csv::Trim::All)
            .has_headers(false)
            .flexible(true)
            .from_reader(text.as_bytes());
        let mut header: Option<Vec<String>> = None;
        let mut rows = Vec::new();
        for record in reader.records() {
            let record = record.map_err(|e| {
                let line = e.position().map_or(0, |p| p.line() as usize);
                ReportError::line(path, line, format!("not CSV: {e}"))
            })?;
            let line = record.position().map_or(0, |p| p.line() as usize);
            if record.iter().all(str::is_empty) {
                continue;
            }
            let Some(names) = &header else {
                header = Some(record.iter().map(str::to_string).collect());
                continue;
            };
            if record.len() != names.len() {
                return Err(ReportError::line(
                    path,
                    line,
                    format!(
                        "{} fields, but the header has {} columns",
                        record.len(),
                        names.len()
                    ),
                ));
            }
            let mut values = Vec::with_capacity(record.len());
            for (name, field) in names.iter().zip(record.iter()) {
                let value: f64 = field.parse().map_err(|_| {
                    ReportError::line(
                        path,
                        line,
                        format!("column {name}: \"{field}\" is not a number"),
                    )
                })?;
                if !value.is_finite() {
                    return Err(ReportError::line(
                        path,
                        line,
                        format!("column {name}: {field} is not a finite number"),
                    ));
                }
                values.push(value);
            }
            rows.push((line, values));
        }
        let Some(header) = header else {
            return Err(ReportError::format(path, "empty: no header line"));
        };
        if rows.is_empty() {
            return Err(ReportError::format(path, "no data rows below the header"));
        }
        Ok(Table {
            path: path.to_path_buf(),
            header,
            rows,
        })
    }

    /// The index of the first present column among `names`.
    pub(crate) fn find(&self, names: &[&str]) -> Option<usize> {
        names
            .iter()
            .find_map(|n| self.header.iter().position(|h| h == n))
    }

    pub(crate) fn require(&self, name: &str) -> Result<usize, ReportError> {
        self.find(&[name]).ok_or_else(|| {
            ReportError::format(
                &self.path,
                format!(
                    "no column `{name}` (the header has: {})",
                    self.header.join(", ")
                ),
            )
        })
    }
}

fn read_friction(path: &Path) -> Result<Vec<FrictionRow>, ReportError> {
    let table = Table::read(path)?;
    let v = table.require("v")?;
    let measured = table.require("mu_measured")?;
    let fitted = table.require("mu_fit")?;
    let sigma = table.find(&["sigma"]);
    let temperature = table.find(&["T"]);
    let reduced = table.find(&["v_reduced"]);
    table
        .rows
        .iter()
        .map(|(line, row)| {
            if row[v] <= 0.0 {
                return Err(ReportError::line(
                    path,
                    *line,
                    format!("column v: {} is not a positive speed", row[v]),
                ));
            }
            Ok(FrictionRow {
                speed: row[v],
                mu_measured: row[measured],
                mu_fit: row[fitted],
                sigma: sigma.map(|i| row[i]),
                temperature: temperature.map(|i| row[i]),
                reduced_speed: reduced.map(|i| row[i]),
            })
        })
        .collect()
}

fn read_modulus(path: &Path) -> Result<Vec<ModulusRow>, ReportError> {
    let table = Table::read(path)?;
    let omega = table.require("omega")?;
    let storage = table.require("E_storage")?;
    let loss = table.require("E_loss")?;
    let tan_delta = table.require("tan_delta")?;
    let storage_sigma = table.find(&["E_storage_sigma"]);
    let loss_sigma = table.find(&["E_loss_sigma"]);
    let tan_delta_sigma = table.find(&["tan_delta_sigma"]);
    let mut previous = 0.0;
    table
        .rows
        .iter()
        .map(|(line, row)| {
            if row[omega] <= previous {
                return Err(ReportError::line(
                    path,
                    *line,
                    format!(
                        "column omega: {} does not increase (frequencies must be positive and ascending)",
                        row[omega]
                    ),
                ));
            }
            previous = row[omega];
            Ok(ModulusRow {
                omega: row[omega],
                storage: row[storage],
                loss: row[loss],
                tan_delta: row[tan_delta],
                storage_sigma: storage_sigma.map(|i| row[i]),
                loss_sigma: loss_sigma.map(|i| row[i]),
                tan_delta_sigma: tan_delta_sigma.map(|i| row[i]),
            })
        })
        .collect()
}
