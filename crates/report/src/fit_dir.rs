//! A fit result directory as `rollfit fit` writes it (docs/ARCHITECTURE.md,
//! "Contract", "Fit folder"): fit.json, mu.csv and modulus.csv, read back
//! for pictures and comparisons.
//!
//! Only the contract's keys are required; everything rollfit adds beyond
//! them (bands, runs, shift, warnings) is optional, so a fit.json written
//! by another program that honours the contract can be reported too. The
//! master curve is rebuilt from the Prony series, so it can be drawn and
//! compared outside the window modulus.csv covers.
//!
//! A fit.json edited by hand is checked where a wrong value would be read
//! as something else rather than fail: Poisson's ratio in (−1, 0.5], the
//! shift model "wlf" (with C1, C2 > 0 and C2 + T − T_ref > 0 at its
//! temperatures) or "free" (without them). Errors name fit.json and the
//! key (`shift.log_aT[2].T`); serde's own errors get the key too, since
//! "invalid type: null" alone does not say which of forty numbers is null
//! (serde_json writes a NaN as null).

use std::path::{Path, PathBuf};

use num_complex::Complex64;
use rollfit_model::{Prony, ViscoelasticModulus};
use serde::Deserialize;

use crate::error::{ReportError, read_utf8};

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

impl FitSummary {
    /// What serde cannot check: values that would otherwise be read as
    /// something else (see the module doc). `text` is fit.json, for lines.
    fn check(&self, path: &Path, text: &str) -> Result<(), ReportError> {
        let refuse = |key: &str, message: String| match line_of_key(text, key) {
            Some(line) => ReportError::line(path, line, message),
            None => ReportError::format(path, message),
        };
        let nu = self.poisson;
        if !(nu > -1.0 && nu <= 0.5) {
            return Err(refuse(
                "poisson",
                format!("poisson = {nu}: Poisson's ratio must lie in (−1, 0.5]"),
            ));
        }
        let Some(shift) = &self.shift else {
            return Ok(());
        };
        match (shift.model.as_str(), shift.c1, shift.c2) {
            ("wlf", Some(c1), Some(c2)) => {
                if c1 <= 0.0 {
                    return Err(refuse(
                        "shift.C1",
                        format!("shift.C1 = {c1}: the WLF constant C1 must be > 0"),
                    ));
                }
                if c2 <= 0.0 {
                    return Err(refuse(
                        "shift.C2",
                        format!("shift.C2 = {c2}: the WLF constant C2 must be > 0 K"),
                    ));
                }
                for (i, s) in shift.log_shift.iter().enumerate() {
                    let denominator = c2 + s.temperature - shift.t_ref;
                    if denominator <= 0.0 {
                        let key = format!("shift.log_aT[{i}].T");
                        return Err(refuse(
                            &key,
                            format!(
                                "{key} = {} °C: C2 + T − T_ref = {denominator} K is not positive (C2 = {c2} K, T_ref = {} °C): the WLF shift diverges at T_ref − C2 = {} °C and means nothing below",
                                s.temperature,
                                shift.t_ref,
                                shift.t_ref - c2
                            ),
                        ));
                    }
                }
            }
            ("wlf", c1, _) => {
                let key = if c1.is_none() { "C1" } else { "C2" };
                return Err(refuse(
                    "shift.model",
                    format!("shift.model = \"wlf\" needs the key shift.{key}"),
                ));
            }
            ("free", None, None) => {}
            ("free", c1, _) => {
                let key = if c1.is_some() { "C1" } else { "C2" };
                return Err(refuse(
                    &format!("shift.{key}"),
                    format!(
                        "shift.{key} does not belong to shift.model = \"free\" (it takes T_ref and log_aT; a WLF shift is model \"wlf\")"
                    ),
                ));
            }
            (other, _, _) => {
                return Err(refuse(
                    "shift.model",
                    format!(
                        "shift.model = \"{other}\": unknown shift model; allowed: \"wlf\", \"free\""
                    ),
                ));
            }
        }
        Ok(())
    }
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
        let text = read_utf8(&json_path)?;
        let summary: FitSummary =
            serde_json::from_str(&text).map_err(|e| json_error(&json_path, &text, &e))?;
        summary.check(&json_path, &text)?;
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

/// A serde error of fit.json with the key it is about: the line, the
/// column, the key's path (`model.H[3]`) and what is wrong, a null where a
/// number belongs said plainly.
fn json_error(path: &Path, text: &str, e: &serde_json::Error) -> ReportError {
    let (line, column) = (e.line(), e.column());
    let full = e.to_string();
    let message = full
        .strip_suffix(&format!(" at line {line} column {column}"))
        .unwrap_or(&full);
    // serde_json counts lines from 1 and columns from 1, in bytes.
    let line_start: usize = text
        .split_inclusive('\n')
        .take(line.saturating_sub(1))
        .map(str::len)
        .sum();
    let at = line_start + column.saturating_sub(1);
    let key = key_at(text, at + 1);
    let literal = |t: &str| {
        text.get(at..).is_some_and(|r| r.starts_with(t))
            || text
                .get(at.saturating_sub(1)..)
                .is_some_and(|r| r.starts_with(t))
    };
    let non_finite = message.starts_with("number out of range")
        || ["NaN", "Infinity", "-Infinity"].into_iter().any(literal);
    let what = match (message.strip_prefix("invalid type: null, expected "), &key) {
        (Some(expected), Some(key)) => match expected {
            "f64" => format!(
                "`{key}` is null where a number is required (a NaN or infinity written as null?)"
            ),
            "usize" | "u64" => format!("`{key}` is null where a count is required"),
            other => format!("`{key}` is null where {other} is required"),
        },
        (None, Some(key)) if non_finite => {
            format!("`{key}`: {message}: a number must be finite (JSON has no NaN or infinity)")
        }
        (None, Some(key)) => format!("`{key}`: {message}"),
        (_, None) => message.to_string(),
    };
    ReportError::line(
        path,
        line,
        format!("column {column}: not a rollfit fit.json: {what}"),
    )
}

/// One open container while scanning JSON text.
enum Frame {
    /// The key being read, if any.
    Object(Option<String>),
    /// The index of the element being read.
    Array(usize),
}

/// Scans JSON `text` (assumed well-formed up to where it is stopped) and
/// calls `visit` with the path of every value as it starts and the byte
/// offset there; `visit` returns true to stop. Returns the open frames at
/// the stop (or at `end`).
fn scan_json(text: &str, end: usize, mut visit: impl FnMut(&[Frame], usize) -> bool) -> Vec<Frame> {
    let bytes = text.as_bytes();
    let end = end.min(bytes.len());
    let mut stack: Vec<Frame> = Vec::new();
    let mut expect_key = false;
    let mut i = 0;
    while i < end {
        let b = bytes[i];
        match b {
            b'{' | b'[' => {
                if visit(&stack, i) {
                    return stack;
                }
                stack.push(if b == b'{' {
                    Frame::Object(None)
                } else {
                    Frame::Array(0)
                });
                expect_key = b == b'{';
            }
            b'}' | b']' => {
                stack.pop();
                expect_key = false;
            }
            b',' => match stack.last_mut() {
                Some(Frame::Object(key)) => {
                    *key = None;
                    expect_key = true;
                }
                Some(Frame::Array(index)) => *index += 1,
                None => {}
            },
            b':' => expect_key = false,
            b'"' => {
                let start = i + 1;
                let mut j = start;
                while j < bytes.len() && bytes[j] != b'"' {
                    j += if bytes[j] == b'\\' { 2 } else { 1 };
                }
                let j = j.min(bytes.len());
                if expect_key {
                    if let Some(Frame::Object(key)) = stack.last_mut() {
                        *key = Some(text[start..j].to_string());
                    }
                } else if visit(&stack, i) {
                    return stack;
                }
                i = j;
            }
            b' ' | b'\t' | b'\n' | b'\r' => {}
            _ => {
                if visit(&stack, i) {
                    return stack;
                }
                while i + 1 < end && !b",}] \t\n\r".contains(&bytes[i + 1]) {
                    i += 1;
                }
            }
        }
        i += 1;
    }
    stack
}

/// `shift.log_aT[2].T` for a stack of frames.
fn path_of(stack: &[Frame]) -> String {
    let mut path = String::new();
    for frame in stack {
        match frame {
            Frame::Object(Some(key)) => {
                if !path.is_empty() {
                    path.push('.');
                }
                path.push_str(key);
            }
            Frame::Object(None) => {}
            Frame::Array(index) => path.push_str(&format!("[{index}]")),
        }
    }
    path
}

/// The path of the value serde_json stopped at, `end` bytes into `text`
/// (just past the character it reported), `None` at the top level.
fn key_at(text: &str, end: usize) -> Option<String> {
    let stack = scan_json(text, end, |_, _| false);
    Some(path_of(&stack)).filter(|p| !p.is_empty())
}

/// The line (from 1) where the value of `key` (a path as [`path_of`]
/// writes it) starts in `text`.
fn line_of_key(text: &str, key: &str) -> Option<usize> {
    let mut found = None;
    scan_json(text, text.len(), |stack, offset| {
        if path_of(stack) == key {
            found = Some(offset);
        }
        found.is_some()
    });
    found.map(|offset| text[..offset].matches('\n').count() + 1)
}

/// The line (from 1) where a CSV record read from `text` starts. The csv
/// crate's position is where it began to read: before the comment and
/// blank lines it skipped, and after a CRLF break at its '\n', which put
/// rows of CRLF files and rows below a comment one or more lines early.
pub fn csv_line(text: &str, position: Option<&csv::Position>) -> usize {
    let Some(position) = position else {
        return 0;
    };
    let bytes = text.as_bytes();
    let mut i = (position.byte() as usize).min(bytes.len());
    loop {
        while i < bytes.len() && (bytes[i] == b'\n' || bytes[i] == b'\r') {
            i += 1;
        }
        if i < bytes.len() && bytes[i] == b'#' {
            i = bytes[i..]
                .iter()
                .position(|&b| b == b'\n')
                .map_or(bytes.len(), |n| i + n);
            continue;
        }
        break;
    }
    bytes[..i].iter().filter(|&&b| b == b'\n').count() + 1
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
        let text = read_utf8(path)?;
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
                ReportError::line(path, csv_line(text, e.position()), format!("not CSV: {e}"))
            })?;
            let line = csv_line(text, record.position());
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};

    /// A fit folder of its own under the system's temporary folder,
    /// removed on drop.
    struct Folder(PathBuf);

    impl Folder {
        /// fit.json as given, with a valid mu.csv and modulus.csv.
        fn new(name: &str, fit_json: &[u8]) -> Folder {
            static COUNTER: AtomicUsize = AtomicUsize::new(0);
            let n = COUNTER.fetch_add(1, Ordering::Relaxed);
            let path = std::env::temp_dir().join(format!(
                "rollfit-report-fitdir-{}-{name}-{n}",
                std::process::id()
            ));
            let _ = std::fs::remove_dir_all(&path);
            std::fs::create_dir_all(&path).unwrap();
            std::fs::write(path.join("fit.json"), fit_json).unwrap();
            std::fs::write(path.join("mu.csv"), "v,mu_measured,mu_fit\n1e-3,0.1,0.1\n").unwrap();
            std::fs::write(
                path.join("modulus.csv"),
                "omega,E_storage,E_loss,tan_delta\n1,1e6,1e5,0.1\n10,2e6,2e5,0.1\n",
            )
            .unwrap();
            Folder(path)
        }

        fn error(&self) -> String {
            match FitDir::read(&self.0) {
                Ok(_) => panic!("{}: expected an error", self.0.display()),
                Err(e) => e.to_string(),
            }
        }
    }

    impl Drop for Folder {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    /// A temperature set's fit.json, one key per line (line numbers below
    /// count on it).
    const GOOD: &str = r#"{
  "model": {"kind": "prony", "E1": 1e9, "tau": [0.001, 0.01], "H": [4e8, 5e8]},
  "poisson": 0.5,
  "window": {"omega_min": 0.1, "omega_max": 1000.0},
  "method": "test",
  "objective": 0.0,
  "iterations": 3,
  "converged": true,
  "wall_time_s": 0.5,
  "shift": {"model": "wlf", "T_ref": 20.0, "C1": 8.86, "C2": 101.6,
    "log_aT": [{"T": 0.0, "log_aT": 1.26}, {"T": 40.0, "log_aT": -1.2}]}
}
"#;

    fn edited(name: &str, from: &str, to: &str) -> Folder {
        assert!(GOOD.contains(from), "{from}");
        Folder::new(name, GOOD.replacen(from, to, 1).as_bytes())
    }

    fn assert_contains(text: &str, fragments: &[&str]) {
        for f in fragments {
            assert!(text.contains(f), "{f:?} not in:\n{text}");
        }
    }

    #[test]
    fn the_unedited_fit_json_reads() {
        let folder = Folder::new("good", GOOD.as_bytes());
        let fit = FitDir::read(&folder.0).unwrap();
        assert_eq!(fit.summary.shift.unwrap().model, "wlf");
        assert_eq!(fit.summary.iterations, 3);
    }

    /// Issue 14, hole 5: an unknown shift model was read as WLF.
    #[test]
    fn unknown_or_incomplete_shift_models_are_refused() {
        let e = edited("foo", r#""model": "wlf""#, r#""model": "foo""#).error();
        assert_contains(
            &e,
            &[
                "fit.json, line 10",
                "shift.model = \"foo\": unknown shift model; allowed: \"wlf\", \"free\"",
            ],
        );
        let e = edited("noc2", r#", "C2": 101.6"#, "").error();
        assert_contains(
            &e,
            &[
                "fit.json, line 10",
                "shift.model = \"wlf\" needs the key shift.C2",
            ],
        );
        let e = edited("free", r#""model": "wlf""#, r#""model": "free""#).error();
        assert_contains(
            &e,
            &[
                "fit.json, line 10",
                "shift.C1 does not belong to shift.model = \"free\"",
            ],
        );
        let free = GOOD.replacen(r#""model": "wlf", "#, r#""model": "free", "#, 1);
        let free = free.replacen(r#", "C1": 8.86, "C2": 101.6"#, "", 1);
        let folder = Folder::new("free-ok", free.as_bytes());
        assert_eq!(
            FitDir::read(&folder.0)
                .unwrap()
                .summary
                .shift
                .unwrap()
                .model,
            "free"
        );
    }

    /// Issue 14, hole 5: ν and WLF constants outside their range were
    /// accepted, and a bad ν was blamed on the DMA file later.
    #[test]
    fn poisson_and_wlf_constants_out_of_range_are_refused_naming_fit_json() {
        for (name, nu) in [("nu1", "1"), ("nu-1", "-1"), ("nu06", "0.6")] {
            let e = edited(name, r#""poisson": 0.5"#, &format!(r#""poisson": {nu}"#)).error();
            assert_contains(
                &e,
                &[
                    "fit.json, line 3",
                    &format!("poisson = {nu}: Poisson's ratio must lie in (−1, 0.5]"),
                ],
            );
        }
        let e = edited("c2", r#""C2": 101.6"#, r#""C2": -5"#).error();
        assert_contains(
            &e,
            &[
                "fit.json, line 10",
                "shift.C2 = -5: the WLF constant C2 must be > 0 K",
            ],
        );
        let e = edited("c1", r#""C1": 8.86"#, r#""C1": 0"#).error();
        assert_contains(&e, &["fit.json, line 10", "shift.C1 = 0"]);
        // C2 = 10 K: the WLF form diverges at 10 °C, above the 0 °C isotherm.
        let e = edited("pole", r#""C2": 101.6"#, r#""C2": 10"#).error();
        assert_contains(
            &e,
            &[
                "fit.json, line 11",
                "shift.log_aT[0].T = 0 °C: C2 + T − T_ref = -10 K is not positive",
                "diverges at T_ref − C2 = 10 °C",
            ],
        );
    }

    /// Issue 14, hole 5: null (a NaN as serde_json writes it) or a
    /// non-finite number where a number belongs: the key, not only
    /// "invalid type: null".
    #[test]
    fn null_and_non_finite_numbers_are_refused_naming_the_key() {
        let e = edited("objective", r#""objective": 0.0"#, r#""objective": null"#).error();
        assert_contains(
            &e,
            &[
                "fit.json, line 6",
                "`objective` is null where a number is required",
            ],
        );
        let e = edited("tau", "[0.001, 0.01]", "[0.001, null]").error();
        assert_contains(
            &e,
            &[
                "fit.json, line 2",
                "`model.tau[1]` is null where a number is required",
            ],
        );
        let e = edited("iterations", r#""iterations": 3"#, r#""iterations": null"#).error();
        assert_contains(
            &e,
            &["fit.json, line 7", "`iterations` is null where a count"],
        );
        let e = edited("shiftT", r#"{"T": 40.0"#, r#"{"T": null"#).error();
        assert_contains(&e, &["fit.json, line 11", "`shift.log_aT[1].T` is null"]);
        let e = edited("huge", r#""E1": 1e9"#, r#""E1": 1e999"#).error();
        assert_contains(
            &e,
            &[
                "fit.json, line 2",
                "`model.E1`",
                "out of range",
                "must be finite",
            ],
        );
        let e = edited("nan", r#""wall_time_s": 0.5"#, r#""wall_time_s": NaN"#).error();
        assert_contains(&e, &["fit.json, line 9", "`wall_time_s`", "must be finite"]);
        let e = edited("inf", r#""objective": 0.0"#, r#""objective": -Infinity"#).error();
        assert_contains(&e, &["fit.json, line 6", "`objective`", "must be finite"]);
        let e = edited("converged", r#""converged": true"#, r#""converged": null"#).error();
        assert_contains(
            &e,
            &[
                "fit.json, line 8",
                "`converged` is null where a boolean is required",
            ],
        );
        let e = edited("missing", r#""E1": 1e9, "#, "").error();
        assert_contains(&e, &["fit.json, line 2", "`model`", "missing field `E1`"]);
    }

    /// Issue 14, hole 4: "stream did not contain valid UTF-8" said neither
    /// where nor which byte.
    #[test]
    fn invalid_utf8_in_a_fit_folder_is_located_by_line_and_offset() {
        let mut bytes = GOOD.as_bytes().to_vec();
        let offset = GOOD.find("test").unwrap();
        bytes[offset] = 0xFF;
        let line_start = GOOD[..offset].rfind('\n').unwrap() + 1;
        let folder = Folder::new("json-bytes", &bytes);
        assert_contains(
            &folder.error(),
            &[
                "fit.json, line 5",
                &format!(
                    "not UTF-8: byte 0xFF at byte offset {offset} (byte {} of the line)",
                    offset - line_start + 1
                ),
            ],
        );
        let folder = Folder::new("csv-bytes", GOOD.as_bytes());
        let mut mu = b"v,mu_measured,mu_fit\n1e-3,0.1,0.1\n2e-3,0.".to_vec();
        let offset = mu.len();
        mu.extend(b"\xE9,0.1\n");
        std::fs::write(folder.0.join("mu.csv"), mu).unwrap();
        assert_contains(
            &folder.error(),
            &[
                "mu.csv, line 3",
                &format!("not UTF-8: byte 0xE9 at byte offset {offset} (byte 8 of the line)"),
            ],
        );
    }
}
