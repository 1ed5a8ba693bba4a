//! The numbers of a fit.json for a summary row, read leniently
//! (docs/ARCHITECTURE.md, "Data flow", `batch`): a batch summary lists
//! whatever of them a result holds, including results written before a key
//! existed, and fails only on a file that is not JSON.

use std::path::Path;

use serde_json::Value;

use super::columns::FIT_JSON;
use crate::error::IoError;

/// What a batch summary shows of a fit.json; each number `None` when the
/// key is absent or not a number.
#[derive(Debug, Clone, PartialEq)]
pub struct Digest {
    /// `objective`.
    pub objective: Option<f64>,
    /// `misfit_per_point`.
    pub misfit_per_point: Option<f64>,
    /// `window.omega_min`, rad/s.
    pub omega_min: Option<f64>,
    /// `window.omega_max`, rad/s.
    pub omega_max: Option<f64>,
    /// `wall_time_s`.
    pub wall_time_s: Option<f64>,
    /// `converged`.
    pub converged: Option<bool>,
    /// `stop_reason`.
    pub stop_reason: Option<String>,
    /// `fit_quality.verdict` is "poor" or "invalid" (results written
    /// before fit_quality existed have no verdict).
    pub poor_fit: bool,
    /// `scale.status` is "undetermined": an unanchored fit whose data do
    /// not determine the modulus scale.
    pub undetermined_scale: bool,
    /// `fit_quality.reasons`.
    pub reasons: Vec<String>,
    /// `shift.C1` and `shift.C2`, when both are numbers.
    pub wlf: Option<(f64, f64)>,
    /// `input.scene`, `input.data` and `joint.dma_source`: the files the
    /// result was fitted to, as given.
    pub inputs: RecordedInputs,
}

/// The input files a fit.json names, as given.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RecordedInputs {
    pub scene: Option<String>,
    pub data: Option<String>,
    /// A joint fit's DMA file.
    pub dma: Option<String>,
}

impl Digest {
    /// The digest of DIR/fit.json, or an error saying why it cannot be
    /// read (the batch then counts the entry as failed).
    pub fn read(dir: &Path) -> Result<Digest, IoError> {
        let path = dir.join(FIT_JSON);
        // The cause the batch summary shows: what the system said, why
        // the file was refused, or what serde_json said.
        let unreadable = |source: std::io::Error| err!("{source}").system(source);
        let report: Value = crate::input_file::read_input(&path, "result", unreadable)
            .map_err(|e| e.to_string())
            .and_then(|bytes| serde_json::from_slice(&bytes).map_err(|e| e.to_string()))
            .map_err(|cause| {
                err!(
                    "cannot read the result {}: {cause} (remove it or give --force to refit)",
                    path.display()
                )
            })?;
        let number = |v: &Value| v.as_f64();
        let text = |v: &Value| v.as_str().map(str::to_string);
        Ok(Digest {
            objective: number(&report["objective"]),
            misfit_per_point: number(&report["misfit_per_point"]),
            omega_min: number(&report["window"]["omega_min"]),
            omega_max: number(&report["window"]["omega_max"]),
            wall_time_s: number(&report["wall_time_s"]),
            converged: report["converged"].as_bool(),
            stop_reason: report["stop_reason"].as_str().map(str::to_string),
            poor_fit: matches!(
                report["fit_quality"]["verdict"].as_str(),
                Some("poor" | "invalid")
            ),
            undetermined_scale: report["scale"]["status"].as_str() == Some("undetermined"),
            reasons: report["fit_quality"]["reasons"]
                .as_array()
                .map(|r| {
                    r.iter()
                        .filter_map(Value::as_str)
                        .map(str::to_string)
                        .collect()
                })
                .unwrap_or_default(),
            wlf: number(&report["shift"]["C1"]).zip(number(&report["shift"]["C2"])),
            inputs: RecordedInputs {
                scene: text(&report["input"]["scene"]),
                data: text(&report["input"]["data"]),
                dma: text(&report["joint"]["dma_source"]),
            },
        })
    }
}
