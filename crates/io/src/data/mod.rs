//! Measured rolling friction (docs/ARCHITECTURE.md, "Contract", "Measured
//! data"): a table with a header row naming a speed column and a friction
//! column, optionally the standard deviation of μ and the temperature;
//! other columns are ignored, so the output of `rollfit forward --noise`
//! (v, mu, sigma, mu_exact, ...) and mu.csv of a fit (v, mu_measured, ...)
//! are read directly.
//!
//! What labs write is read as it is:
//!
//! - Text (CSV, `text.rs`) with `,`, `;` or tab between the columns,
//!   detected from the header; with `;` or tab, numbers may have decimal
//!   commas (`0,0123`, the European spreadsheet export). A comma-delimited
//!   file with decimal commas is ambiguous and refused. UTF-8 (a byte-order
//!   mark is ignored), UTF-16 with a byte-order mark, and, when the file is
//!   not UTF-8, Latin-1. Lines starting with `#` are comments; lines before
//!   the header that are not (titles such as `Measurement 2024-03-01`) are
//!   skipped: the header is the first line naming both a speed and a
//!   friction column (`header_row.rs`).
//! - Workbooks (.xlsx, .xlsm, .xlsb, .xls, .ods; `workbook.rs`): the first
//!   sheet, or the one `--sheet` names; numbers or numeric text.
//! - Header names (`headers.rs`, units in `units.rs`): the speed `v`,
//!   `velocity`, `speed`, `rolling speed`, with a unit in brackets,
//!   parentheses or after an underscore (`velocity (mm/s)`, `speed [m/s]`,
//!   `v_um_s`: m/s, cm/s, mm/s, µm/s, nm/s, per s, ms, min or h); the
//!   friction `mu`, `µ`, `COF`, `friction coefficient` (dimensionless, or
//!   in %); its standard deviation `sigma`, `std`, `sd`, `mu_std`,
//!   `sigma_mu`, `COF std`; the temperature `T`, `temperature`, `T_C`,
//!   `T (°C)`, `T_K`, `T (K)`, `T_F` (a lone lowercase `t` is time and
//!   ignored). Case, spaces, underscores and brackets do not matter. A row
//!   right below the header holding only units (`mm/s;-`) gives the units
//!   of the columns whose names have none. Values are converted to m/s and
//!   °C; every conversion and every name other than the canonical `v`,
//!   `mu`, `sigma`, `T` is stated in [`DataTable::notes`]. A speed or
//!   temperature unit not understood, or two columns of one quantity, are
//!   errors.
//! - Rows with an empty or NaN cell (`NaN`, `nan`, `NA`, `n/a`, `#N/A`,
//!   `null`, `-`, or a spreadsheet error such as `#DIV/0!`; `cell.rs`) in
//!   any column read — v, mu, and sigma or T when the file has them — are
//!   skipped, with one warning listing their lines in
//!   [`DataTable::warnings`]; a row without a sigma has no weight, and one
//!   without a T no place in a temperature set. Rows and trailing columns
//!   that are entirely empty (`v;mu;;`, `;;;`) are ignored silently.
//!
//! Every other value must be a finite number; v, mu and sigma must be
//! greater than zero (the default weights are relative, 1/μ²), and each
//! within the ranges of `rollfit_fit::data`. Repeated speeds and unsorted
//! rows are normal in real data and kept as they are, in file order
//! (`rows.rs`). Errors name the file, the line (for a
//! workbook the sheet and the cell) and the column, and when a column is
//! missing list the columns found.

pub(crate) mod cell;
pub(crate) mod dialect;
mod header_row;
mod headers;
pub(crate) mod quantity;
mod rows;
mod source;
mod text;
pub(crate) mod workbook;

use std::path::Path;

use rollfit_fit::Measurements;

use crate::error::{ErrorKind, IoError};

pub use quantity::Quantity;

/// A measurement as read, in file order, with the file line of each row.
#[derive(Debug, Clone, PartialEq)]
pub struct DataTable {
    /// Speeds v, m/s.
    pub speeds: Vec<f64>,
    /// Friction coefficients μ.
    pub friction: Vec<f64>,
    /// Standard deviations of μ, when the file has a `sigma` column.
    pub sigma: Option<Vec<f64>>,
    /// Temperatures, °C, when the file has a `T` column.
    pub temperature: Option<Vec<f64>>,
    /// The file line of each row (for a workbook its row number), for
    /// messages.
    pub lines: Vec<u64>,
    /// How the file was read, one sentence each (no prefix, no file name):
    /// encoding, sheet, header line, delimiter and decimal commas, and each
    /// column's name and unit conversion.
    pub notes: Vec<String>,
    /// What was left out (rows with empty or NaN cells), one sentence each.
    pub warnings: Vec<String>,
}

impl DataTable {
    /// The validated measurements of the fit library; its refusal is
    /// the fit library's own message (the caller names the file).
    pub fn measurements(&self) -> Result<Measurements, IoError> {
        Measurements::new(
            self.speeds.clone(),
            self.friction.clone(),
            self.sigma.clone(),
            self.temperature.clone(),
        )
        .map_err(|e| IoError::transparent(ErrorKind::Content, e))
    }

    /// The distinct temperatures of a `T` column, in order of appearance.
    pub fn temperatures(&self) -> Vec<f64> {
        let mut distinct: Vec<f64> = Vec::new();
        for &t in self.temperature.iter().flatten() {
            if !distinct.contains(&t) {
                distinct.push(t);
            }
        }
        distinct
    }
}

/// Reads and checks the measurement at `path` (text, or the first sheet of
/// a workbook); errors name the file.
pub fn read(path: &Path) -> Result<DataTable, IoError> {
    read_sheet(path, None)
}

/// Reads and checks the measurement at `path`; `sheet` names the sheet of
/// a workbook (default: the first), and is an error for a text file.
/// Errors name the file.
pub fn read_sheet(path: &Path, sheet: Option<&str>) -> Result<DataTable, IoError> {
    let bytes = crate::input_file::read_input(path, "data file", |source| {
        err!("cannot open data file {}", path.display()).system(source)
    })?;
    let in_file = |cause: IoError| -> IoError {
        err!("data file {}", path.display())
            .in_file(path)
            .caused_by(cause)
    };
    if workbook::is_workbook(path, &bytes) {
        return workbook::parse(path, bytes, sheet).map_err(in_file);
    }
    if let Some(sheet) = sheet {
        return Err(err!(
            "data file {}: a sheet ({sheet:?}) was given, but the file is text, not a workbook \
         (.xlsx, .xlsm, .xlsb, .xls, .ods)",
            path.display(),
        ));
    }
    text::parse_bytes(bytes).map_err(in_file)
}

#[cfg(test)]
mod tests;
