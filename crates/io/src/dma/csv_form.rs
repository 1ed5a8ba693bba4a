//! The CSV form of a DMA file (docs/ARCHITECTURE.md, "Contract", "DMA
//! files"): a header line, optionally a units row below it, then one point
//! per line; `#` lines are comments, columns other than the ones
//! [`super::header`] names are ignored (they need not even be numbers).
//!
//! The columns, their names and units are [`super::header`]'s, shared
//! with workbooks: frequency `omega` (rad/s) or `f` (Hz), storage and loss
//! `E_storage`, `E_loss` (Young's) or `G_storage`, `G_loss` (shear),
//! optional `T` (°C), with unit suffixes such as `omega_rad_s`, `f_Hz`,
//! `G_storage_Pa`, `E_loss_MPa`, `T_C`, `T_K`. When both Young's and shear
//! columns are present the Young's ones are used (no ν needed). `omega`,
//! `E_storage`, `E_loss` and `T` are the names of a fit folder's tables
//! too ([`crate::fit_dir::columns`]), so a fit's modulus.csv reads here as
//! it is.
//!
//! Every line below the header must have the header's number of fields
//! and a finite number in each column read; a file cut off in its last
//! line is refused or, when only its line break is missing, flagged.

use std::path::Path;

use super::form::{FormRead, Place, RawPoint};
use super::header::{self, Column, Header};
use crate::csv_columns::{LineIndex, dma_number, not_csv};
use crate::error::{ColumnRef, IoError};

/// The columns only DMA files have, defined with the other shared names.
pub use crate::columns::{F, G_LOSS, G_STORAGE};

/// Parses the CSV text of `path`.
pub(crate) fn parse(path: &Path, text: &str) -> Result<FormRead, IoError> {
    let mut reader = crate::csv_columns::reader(text, false, true);
    let lines = LineIndex::new(text);
    let mut records = reader.records();
    let (header_line, names): (usize, Vec<String>) = loop {
        match records.next() {
            None => {
                return Err(IoError::NoHeader {
                    path: path.to_path_buf(),
                });
            }
            Some(Err(e)) => return Err(not_csv(path, text, e)),
            Some(Ok(r)) if r.iter().all(str::is_empty) => continue,
            Some(Ok(r)) => {
                let line = lines.csv_line(r.position());
                break (line, r.iter().map(str::to_string).collect());
            }
        }
    };
    let place = Place { path, sheet: None };
    // A units row below the header (an instrument's text export).
    let mut records = records.peekable();
    let units: Option<(usize, Vec<String>)> = match records.peek() {
        Some(Ok(r))
            if header::is_units_row(&names, &r.iter().map(str::to_string).collect::<Vec<_>>()) =>
        {
            let line = lines.csv_line(r.position());
            let cells = r.iter().map(str::to_string).collect();
            records.next();
            Some((line, cells))
        }
        _ => None,
    };
    let units = units
        .as_ref()
        .map(|(line, cells)| (*line, cells.as_slice()));
    let header = header::columns(&place, header_line, names, units)?;
    let mut warnings = Vec::new();
    if header.both {
        warnings.push(format!(
            "{}: both Young's (E_…) and shear (G_…) columns; the Young's ones are used",
            path.display()
        ));
    }
    // A file cut off inside its last row loses that row's tail: cells (a
    // count that no longer matches the header) or digits (which may still
    // parse). Only a missing final line break tells the second kind, and
    // CSV files written by hand lack one often enough that it is a warning.
    let unterminated = (!text.ends_with(['\n', '\r']))
        .then(|| text.lines().count())
        .filter(|&n| n > 0);
    let mut points = Vec::new();
    for record in records {
        let record = record.map_err(|e| not_csv(path, text, e))?;
        let line = lines.csv_line(record.position());
        if record.iter().all(str::is_empty) {
            continue;
        }
        let cut = unterminated == Some(line);
        points.push(row(path, line, cut, &header, &record, &mut warnings)?);
    }
    header.form(path, points, warnings)
}

/// The point of the record on line `line`; `last_and_cut`: the record is
/// the file's last line and has no line break.
fn row(
    path: &Path,
    line: usize,
    last_and_cut: bool,
    header: &Header,
    record: &csv::StringRecord,
    warnings: &mut Vec<String>,
) -> Result<RawPoint, IoError> {
    let width = header.names.len();
    if record.len() != width {
        let missing = header.names[record.len().min(width)..]
            .iter()
            .enumerate()
            .map(|(i, n)| ColumnRef::numbered(record.len() + i + 1, n))
            .collect();
        return Err(IoError::FieldCount {
            path: path.to_path_buf(),
            line,
            found: record.len(),
            expected: width,
            missing,
            cut: last_and_cut,
        });
    }
    if last_and_cut {
        warnings.push(format!(
            "{}, line {line}: the file ends without a line break after this row: if the file was cut off, its last number may be incomplete",
            path.display()
        ));
    }
    let value = |c: &Column| -> Result<f64, IoError> {
        let v = dma_number(path, line, || c.reference.clone(), &record[c.index])?;
        Ok(c.convert(v))
    };
    Ok(RawPoint {
        line,
        omega: value(&header.omega)?,
        storage: value(&header.storage)?,
        loss: value(&header.loss)?,
        temperature: header.temperature.as_ref().map(&value).transpose()?,
    })
}
