//! Writing a fit folder (docs/ARCHITECTURE.md, "Contract", "Fit folder"):
//! mu.csv, modulus.csv and fit.json, checked and encoded before the disk is
//! touched, to be swapped in together, fit.json last. [`FitFiles`] holds all
//! three in memory (for callers that keep them); [`FitFolder`] holds
//! modulus.csv and fit.json and writes mu.csv row by row as the folder is
//! filled ([`MuCsv`]), for data of a million rows.

use rollfit_fit::{FitReport, ModulusPoint};
use serde::Serialize;

use super::columns::{
    ABS_E, ABS_E_SIGMA, E_LOSS, E_LOSS_SIGMA, E_STORAGE, E_STORAGE_SIGMA, FIT_JSON,
    MODULUS_COLUMNS, MODULUS_CSV, MU_CSV, OMEGA, TAN_DELTA, TAN_DELTA_SIGMA,
};
use super::mu_csv::{Measured, MuCsv};
use crate::csv_text::csv_bytes;
use crate::error::IoError;
use crate::output::FileContent;

/// A column of modulus.csv and its value in a curve point.
type ModulusColumn = (&'static str, fn(&ModulusPoint) -> f64);

/// Each column of modulus.csv with its value in a curve point, in the
/// order of [`MODULUS_COLUMNS`].
pub(super) const MODULUS_VALUES: [ModulusColumn; 9] = [
    (OMEGA, |p| p.omega),
    (E_STORAGE, |p| p.storage),
    (E_LOSS, |p| p.loss),
    (TAN_DELTA, |p| p.tan_delta),
    (ABS_E, |p| p.magnitude),
    (E_STORAGE_SIGMA, |p| p.storage_sigma),
    (E_LOSS_SIGMA, |p| p.loss_sigma),
    (TAN_DELTA_SIGMA, |p| p.tan_delta_sigma),
    (ABS_E_SIGMA, |p| p.magnitude_sigma),
];

/// Where a fit came from, for fit.json's `input` and `rollfit_version`.
#[derive(Debug, Clone)]
pub struct FitInput {
    /// The scene file, as given.
    pub scene: String,
    /// The data file, as given.
    pub data: String,
    /// The one temperature of the data's `T` column, °C.
    pub temperature: Option<f64>,
    /// The version of rollfit that made the fit.
    pub rollfit_version: &'static str,
}

/// fit.json: the report (in the fit library's field order) plus where it
/// came from.
#[derive(Serialize)]
struct FitJson<'a> {
    #[serde(flatten)]
    report: &'a FitReport,
    input: InputJson<'a>,
    rollfit_version: &'a str,
}

/// fit.json's `input`.
#[derive(Serialize)]
struct InputJson<'a> {
    scene: &'a str,
    data: &'a str,
    points: usize,
    /// The one temperature of the data's `T` column, °C.
    #[serde(rename = "T", skip_serializing_if = "Option::is_none")]
    temperature: Option<f64>,
}

/// A fit folder's three files, encoded but not yet written.
#[derive(Debug, Clone)]
pub struct FitFiles {
    mu_csv: Vec<u8>,
    modulus_csv: Vec<u8>,
    fit_json: Vec<u8>,
}

impl FitFiles {
    /// Encodes mu.csv, modulus.csv and fit.json of `report`, a fit of
    /// `measured`.
    pub fn encode(
        report: &FitReport,
        measured: &Measured<'_>,
        input: &FitInput,
    ) -> Result<FitFiles, IoError> {
        let folder = FitFolder::encode(report, measured, input)?;
        Ok(FitFiles {
            mu_csv: MuCsv::new(*measured, report).encode()?,
            modulus_csv: folder.modulus_csv,
            fit_json: folder.fit_json,
        })
    }

    /// (file name, content) in the order they are written, fit.json last.
    pub fn named(&self) -> [(&'static str, &[u8]); 3] {
        [
            (MU_CSV, self.mu_csv.as_slice()),
            (MODULUS_CSV, &self.modulus_csv),
            (FIT_JSON, &self.fit_json),
        ]
    }
}

fn fit_json(report: &FitReport, input: &FitInput) -> Result<Vec<u8>, IoError> {
    let value = FitJson {
        report,
        input: InputJson {
            scene: &input.scene,
            data: &input.data,
            points: report.mu_fit.len(),
            temperature: input.temperature,
        },
        rollfit_version: input.rollfit_version,
    };
    let mut bytes = serde_json::to_vec_pretty(&value).map_err(|source| {
        err!("cannot encode the fit report")
            .caused_by(source)
            .internal()
    })?;
    bytes.push(b'\n');
    Ok(bytes)
}

fn modulus_csv(report: &FitReport) -> Result<Vec<u8>, IoError> {
    csv_bytes(
        &MODULUS_COLUMNS,
        report
            .curve
            .iter()
            .map(|p| MODULUS_VALUES.iter().map(|(_, value)| value(p)).collect()),
    )
}

/// A fit folder's modulus.csv and fit.json, encoded, with its mu.csv
/// checked but written only as the folder is filled ([`FitFolder::files`]).
#[derive(Debug, Clone)]
pub struct FitFolder {
    modulus_csv: Vec<u8>,
    fit_json: Vec<u8>,
}

impl FitFolder {
    /// Encodes modulus.csv and fit.json of `report`, a fit of `measured`,
    /// and checks its mu.csv ([`MuCsv::check`]).
    pub fn encode(
        report: &FitReport,
        measured: &Measured<'_>,
        input: &FitInput,
    ) -> Result<FitFolder, IoError> {
        MuCsv::new(*measured, report).check()?;
        Ok(FitFolder {
            modulus_csv: modulus_csv(report)?,
            fit_json: fit_json(report, input)?,
        })
    }

    /// (file name, content) in the order they are written, fit.json last,
    /// with `mu_csv` (of the same report and data as [`FitFolder::encode`]
    /// was given) written as it is encoded.
    pub fn files<'a>(&'a self, mu_csv: &'a MuCsv<'a>) -> [(&'static str, &'a dyn FileContent); 3] {
        [
            (MU_CSV, mu_csv),
            (MODULUS_CSV, &self.modulus_csv),
            (FIT_JSON, &self.fit_json),
        ]
    }
}
