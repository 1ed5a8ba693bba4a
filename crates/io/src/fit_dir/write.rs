//! Writing a fit folder (docs/ARCHITECTURE.md, "Contract", "Fit folder"):
//! mu.csv, modulus.csv and fit.json, encoded completely in memory
//! ([`FitFiles::encode`]) to be swapped in together, fit.json last
//! ([`FitFiles::named`], for [`crate::output::replace_folder`]).

use rollfit_fit::{FitReport, ModulusPoint};
use serde::Serialize;

use super::columns::{
    ABS_E, ABS_E_SIGMA, E_LOSS, E_LOSS_SIGMA, E_STORAGE, E_STORAGE_SIGMA, EXACT_CORRECTION,
    FIT_JSON, LOG_AT, MODULUS_COLUMNS, MODULUS_CSV, MU_CSV, MU_FIT, MU_MEASURED, OMEGA, RESIDUAL,
    SIGMA, T, TAN_DELTA, TAN_DELTA_SIGMA, V, V_REDUCED,
};
use crate::csv_text::csv_bytes;
use crate::error::{Fault, IoError};

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

/// The measured data of a fit, which mu.csv repeats row by row in the
/// data's order.
#[derive(Debug, Clone, Copy)]
pub struct Measured<'a> {
    /// Speeds, m/s.
    pub speeds: &'a [f64],
    /// Measured μ.
    pub friction: &'a [f64],
    /// Standard deviations of μ, when the data have them.
    pub sigma: Option<&'a [f64]>,
    /// Temperatures, °C, when the data have them.
    pub temperature: Option<&'a [f64]>,
}

impl Measured<'_> {
    /// The one temperature of the `T` column, °C, which fit.json's
    /// `input.T` records: None without a `T` column or for a temperature
    /// set (several temperatures, which the report's shift lists).
    pub fn single_temperature(&self) -> Option<f64> {
        let mut distinct: Vec<f64> = Vec::new();
        for &t in self.temperature.into_iter().flatten() {
            if !distinct.contains(&t) {
                distinct.push(t);
            }
        }
        match distinct.as_slice() {
            [t] => Some(*t),
            _ => None,
        }
    }
}

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
        Ok(FitFiles {
            mu_csv: mu_csv(measured, report)?,
            modulus_csv: modulus_csv(report)?,
            fit_json: fit_json(report, input)?,
        })
    }

    /// (file name, content) in the order they are written, fit.json last.
    pub fn named(&self) -> [(&'static str, &[u8]); 3] {
        [
            (MU_CSV, self.mu_csv.as_slice()),
            (MODULUS_CSV, self.modulus_csv.as_slice()),
            (FIT_JSON, self.fit_json.as_slice()),
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
    let mut bytes = serde_json::to_vec_pretty(&value).map_err(|source| Fault::JsonEncode {
        what: "fit report",
        source,
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

/// mu.csv: v, mu_measured, mu_fit, [sigma], residual = (μ_fit − μ)/μ, for
/// a temperature set T, log_aT and v_reduced = v·a_T (the speed on the
/// master curve at T_ref), and with `physics = "exact"` exact_correction
/// (μ_exact/μ_approx), in the data's order.
fn mu_csv(measured: &Measured<'_>, report: &FitReport) -> Result<Vec<u8>, IoError> {
    let points = measured.speeds.len();
    let correction = report.physics.as_ref().map(|p| &p.correction);
    for fitted in [Some(&report.mu_fit), correction].into_iter().flatten() {
        if fitted.len() != points {
            return Err(Fault::FittedCount {
                fitted: fitted.len(),
                points,
            }
            .into());
        }
    }
    let mut header = vec![V, MU_MEASURED, MU_FIT];
    if measured.sigma.is_some() {
        header.push(SIGMA);
    }
    header.push(RESIDUAL);
    let shift = report.shift.as_ref();
    if shift.is_some() {
        header.extend([T, LOG_AT, V_REDUCED]);
    }
    if correction.is_some() {
        header.push(EXACT_CORRECTION);
    }
    let mut rows = Vec::with_capacity(points);
    for i in 0..points {
        let (v, mu, fit) = (measured.speeds[i], measured.friction[i], report.mu_fit[i]);
        let mut row = vec![v, mu, fit];
        if let Some(sigma) = measured.sigma {
            row.push(sigma[i]);
        }
        row.push((fit - mu) / mu);
        if let Some(shift) = shift {
            // Rows without a T column under a shift are a joint fit's
            // rolling data, measured at T_ref (the fit's own rule).
            let t = measured.temperature.map_or(shift.t_ref(), |t| t[i]);
            let log_a = shift
                .log_shifts()
                .iter()
                .min_by(|a, b| {
                    (a.temperature - t)
                        .abs()
                        .total_cmp(&(b.temperature - t).abs())
                })
                .map_or(f64::NAN, |s| s.log_shift);
            row.extend([t, log_a, v * 10f64.powf(log_a)]);
        }
        if let Some(correction) = correction {
            row.push(correction[i]);
        }
        rows.push(row);
    }
    csv_bytes(&header, rows)
}
