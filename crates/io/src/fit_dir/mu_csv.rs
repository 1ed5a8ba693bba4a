//! mu.csv (docs/ARCHITECTURE.md, "Contract", "Fit folder"): v,
//! mu_measured, mu_fit, [sigma], residual = (μ_fit − μ)/μ, for a
//! temperature set T, log_aT and v_reduced = v·a_T (the speed on the master
//! curve at T_ref), and with `physics = "exact"` exact_correction
//! (μ_exact/μ_approx), one row per measured row in the data's order.
//!
//! The rows are checked before anything is written ([`MuCsv::check`]) and
//! then encoded one at a time into the file ([`FileContent`]): a logger's
//! file of a million rows gives a mu.csv several times its size, which
//! need never be held in memory.

use std::io::{self, Write};

use rollfit_fit::FitReport;

use super::columns::{
    EXACT_CORRECTION, LOG_AT, MU_FIT, MU_MEASURED, RESIDUAL, SIGMA, T, V, V_REDUCED,
};
use crate::csv_text::number;
use crate::error::IoError;
use crate::output::FileContent;

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

/// mu.csv of the fit `report` of `measured`.
#[derive(Debug, Clone, Copy)]
pub struct MuCsv<'a> {
    measured: Measured<'a>,
    report: &'a FitReport,
}

impl<'a> MuCsv<'a> {
    /// mu.csv of `report`, a fit of `measured`.
    pub fn new(measured: Measured<'a>, report: &'a FitReport) -> Self {
        MuCsv { measured, report }
    }

    fn correction(&self) -> Option<&'a [f64]> {
        self.report
            .physics
            .as_ref()
            .map(|p| p.correction.as_slice())
    }

    fn header(&self) -> Vec<&'static str> {
        let mut header = vec![V, MU_MEASURED, MU_FIT];
        if self.measured.sigma.is_some() {
            header.push(SIGMA);
        }
        header.push(RESIDUAL);
        if self.report.shift.is_some() {
            header.extend([T, LOG_AT, V_REDUCED]);
        }
        if self.correction().is_some() {
            header.push(EXACT_CORRECTION);
        }
        header
    }

    /// The values of row `i` into `row` (cleared first).
    fn row(&self, i: usize, row: &mut Vec<f64>) {
        let measured = &self.measured;
        let (v, mu, fit) = (
            measured.speeds[i],
            measured.friction[i],
            self.report.mu_fit[i],
        );
        row.clear();
        row.extend([v, mu, fit]);
        if let Some(sigma) = measured.sigma {
            row.push(sigma[i]);
        }
        row.push((fit - mu) / mu);
        if let Some(shift) = self.report.shift.as_ref() {
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
        if let Some(correction) = self.correction() {
            row.push(correction[i]);
        }
    }

    /// Refuses, before anything is written, fitted values that do not
    /// match the rows one to one, and a cell that is not a finite number
    /// (naming its row and column): no reader of mu.csv could use it.
    pub fn check(&self) -> Result<(), IoError> {
        let points = self.measured.speeds.len();
        for fitted in [Some(self.report.mu_fit.as_slice()), self.correction()]
            .into_iter()
            .flatten()
        {
            if fitted.len() != points {
                return Err(err!(
                    "the fit returned {fitted} fitted values for {points} data points",
                    fitted = fitted.len()
                )
                .internal());
            }
        }
        let header = self.header();
        let mut row = Vec::with_capacity(header.len());
        for i in 0..points {
            self.row(i, &mut row);
            if let Some(k) = row.iter().position(|v| !v.is_finite()) {
                return Err(err!(
                    "the output's row {row} has {column} = {value}: not a finite number (refused rather than \
         written)",
                    column = header[k],
                    row = i + 1,
                    value = number(row[k])
                ));
            }
        }
        Ok(())
    }

    /// The whole of mu.csv in memory, checked.
    pub fn encode(&self) -> Result<Vec<u8>, IoError> {
        self.check()?;
        let mut bytes = Vec::new();
        self.write_to(&mut bytes)
            .map_err(|source| IoError::from(csv::Error::from(source)))?;
        Ok(bytes)
    }
}

impl FileContent for MuCsv<'_> {
    fn write_to(&self, out: &mut dyn Write) -> io::Result<()> {
        let mut writer = csv::Writer::from_writer(out);
        writer.write_record(self.header())?;
        let mut row = Vec::new();
        for i in 0..self.measured.speeds.len() {
            self.row(i, &mut row);
            writer.write_record(row.iter().map(|&v| number(v)))?;
        }
        writer.flush()
    }
}
