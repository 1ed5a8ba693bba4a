//! The CSV form of a DMA file (docs/ARCHITECTURE.md, "Contract", "DMA
//! files"): a header line, optionally a units row below it, then one point
//! per line; `#` lines are comments, columns other than the ones
//! [`super::header`] names are ignored (they need not even be numbers).
//!
//! The dialect is the measured-data reader's ([`crate::data::dialect`]):
//! cells separated by `,`, `;` or tab, the header the first line naming a
//! frequency, a storage and a loss modulus (title lines above it are
//! skipped, with a note), and decimal commas (`1,5;2,3e6`) read with `;` or
//! tab between the cells.
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
use crate::csv_columns::LineIndex;
use crate::data::dialect;
use crate::error::field_count_tail;
use crate::error::{ColumnRef, IoError};

/// The columns only DMA files have, defined with the other shared names.
pub use crate::columns::{F, G_LOSS, G_STORAGE};

/// Parses the CSV text of `path`: the points, and notes on how the file
/// was read (its delimiter, title lines).
pub(crate) fn parse(
    path: &Path,
    text: &str,
    told: header::Told,
) -> Result<(FormRead, Vec<String>), IoError> {
    // No header the vocabulary knows: the first line is read as one, for
    // the message naming what it lacks.
    let Some((delimiter, start, found)) = dialect::dialect_of(text, super::sheet::is_header) else {
        return Err(err!("{}: empty: no header line", path.display()));
    };
    if found.is_none()
        && let Some(read) = parse_aligned(path, text, told)
    {
        return read;
    }
    let mut notes = dialect_notes(path, delimiter, found.as_ref());
    let decimal_comma = dialect::decimal_comma(delimiter);
    let body = &text[start..];
    let mut reader = crate::csv_columns::reader_with(body, false, true, delimiter);
    let lines = LineIndex::new(text);
    let line_of = |position: Option<&csv::Position>| lines.csv_line_after(start, position);
    let not_csv = |e: csv::Error| {
        err!(
            "{}, line {line}: not CSV: {error}",
            path.display(),
            error = e,
            line = line_of(e.position())
        )
    };
    let mut records = reader.records();
    let (header_line, names): (usize, Vec<String>) = loop {
        match records.next() {
            None => {
                return Err(err!("{}: empty: no header line", path.display()));
            }
            Some(Err(e)) => return Err(not_csv(e)),
            Some(Ok(r)) if r.iter().all(str::is_empty) => continue,
            Some(Ok(r)) => {
                let line = line_of(r.position());
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
            let line = line_of(r.position());
            let cells = r.iter().map(str::to_string).collect();
            records.next();
            Some((line, cells))
        }
        _ => None,
    };
    let units = units
        .as_ref()
        .map(|(line, cells)| (*line, cells.as_slice()));
    notes.extend(super::relaxation::ignored_time_columns(path, &names));
    let header = header::columns(&place, header_line, names, units, told)?;
    notes.extend(header.notes(path));
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
    let mut ragged = Ragged::default();
    for record in records {
        let record = record.map_err(not_csv)?;
        let line = line_of(record.position());
        if record.iter().all(str::is_empty) {
            continue;
        }
        let cut = unterminated == Some(line);
        let at = Row {
            line,
            cut,
            decimal_comma,
        };
        let said = (&mut warnings, &mut ragged);
        points.push(row(path, at, &header, &record, said)?);
    }
    notes.extend(ragged.notes(path, header.names.len()));
    let mut read = header.form(path, points, warnings)?;
    read.preamble = text[..start]
        .lines()
        .enumerate()
        .map(|(i, line)| (i + 1, line.to_string()))
        .filter(|(_, line)| !line.trim().is_empty())
        .collect();
    Ok((read, notes))
}

/// No header by one delimiter: numbers aligned in columns by runs of
/// spaces, as a printout or an old instrument writes them, read as
/// separated by them (None: no header that way either).
fn parse_aligned(
    path: &Path,
    text: &str,
    told: header::Told,
) -> Option<Result<(FormRead, Vec<String>), IoError>> {
    let aligned = dialect::aligned(text)?;
    dialect::dialect_of(&aligned, super::sheet::is_header)?.2?;
    Some(parse(path, &aligned, told).map(|(read, mut notes)| {
        let said = "columns aligned with runs of spaces: read as separated by them";
        notes.insert(0, format!("{}: {said}", path.display()));
        (read, notes)
    }))
}

/// What the dialect detection decided, as notes: title lines skipped, a
/// delimiter other than `,`.
fn dialect_notes(path: &Path, delimiter: char, found: Option<&dialect::Found>) -> Vec<String> {
    let mut notes = Vec::new();
    let Some(found) = found else {
        return notes;
    };
    if found.index > 0 {
        notes.push(format!(
            "{}: header on line {}; the {} line{} above it (titles) ignored",
            path.display(),
            found.line.number,
            found.index,
            if found.index == 1 { "" } else { "s" }
        ));
    }
    if delimiter != ',' {
        notes.push(format!(
            "{}: columns separated by {}, decimal commas allowed",
            path.display(),
            if delimiter == ';' { "`;`" } else { "tabs" }
        ));
    }
    notes
}

/// Rows whose cell count differs from the header's where no column read
/// is missing: an export's header that names more columns than its rows
/// fill, or rows ending in empty cells. Each: (first line, count).
#[derive(Default)]
struct Ragged {
    short: Option<(usize, usize)>,
    trailing: Option<(usize, usize)>,
}

impl Ragged {
    /// What was read past, as notes.
    fn notes(&self, path: &Path, width: usize) -> Vec<String> {
        let path = path.display();
        let mut notes = Vec::new();
        if let Some((line, count)) = self.short {
            notes.push(format!(
                "{path}: {count} row(s) hold fewer cells than the header's {width} columns (the \
                 first on line {line}): the missing trailing cells, of columns not read, are empty"
            ));
        }
        if let Some((line, count)) = self.trailing {
            notes.push(format!(
                "{path}: {count} row(s) end with empty cells beyond the header's {width} columns \
                 (the first on line {line}): ignored"
            ));
        }
        notes
    }
}

/// Where a record is and how its numbers read.
struct Row {
    /// Its line in the file.
    line: usize,
    /// The record is the file's last line and has no line break.
    cut: bool,
    /// A number may have a decimal comma (`;` or tab between the cells).
    decimal_comma: bool,
}

/// The point of the record at `at`.
fn row(
    path: &Path,
    at: Row,
    header: &Header,
    record: &csv::StringRecord,
    (warnings, ragged): (&mut Vec<String>, &mut Ragged),
) -> Result<RawPoint, IoError> {
    let Row {
        line,
        cut: last_and_cut,
        decimal_comma,
    } = at;
    let width = header.names.len();
    let read = [&header.omega, &header.storage, &header.loss]
        .into_iter()
        .chain(&header.temperature)
        .chain(&header.step)
        .map(|c| c.index)
        .max()
        .unwrap_or(0);
    let empty_beyond = record.iter().skip(width).all(str::is_empty);
    if record.len() > read && record.len() < width && !last_and_cut {
        ragged.short.get_or_insert((line, 0)).1 += 1;
    } else if record.len() > width && empty_beyond {
        ragged.trailing.get_or_insert((line, 0)).1 += 1;
    } else if record.len() != width {
        let missing: Vec<ColumnRef> = header.names[record.len().min(width)..]
            .iter()
            .enumerate()
            .map(|(i, n)| ColumnRef::numbered(record.len() + i + 1, n))
            .collect();
        return Err(err!(
            "{}, line {line}: {found} fields, but the header has {expected} columns{}",
            path.display(),
            field_count_tail(&missing, last_and_cut),
            expected = width,
            found = record.len()
        ));
    }
    if last_and_cut {
        warnings.push(format!(
            "{}, line {line}: the file ends without a line break after this row: if the file was cut off, its last number may be incomplete",
            path.display()
        ));
    }
    let value = |c: &Column| -> Result<f64, IoError> {
        let v = c.number(path, line, &record[c.index], decimal_comma)?;
        Ok(c.convert(v))
    };
    Ok(RawPoint {
        line,
        omega: value(&header.omega)?,
        storage: value(&header.storage)?,
        loss: value(&header.loss)?,
        temperature: header.temperature.as_ref().map(&value).transpose()?,
        step: header
            .step
            .as_ref()
            .map(|c| record[c.index].to_string())
            .filter(|s| !s.is_empty()),
    })
}
