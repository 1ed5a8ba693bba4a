//! The workbook form of a DMA file (docs/ARCHITECTURE.md, "Contract", "DMA
//! files"): a sheet of an Excel (.xlsx, .xlsm, .xlsb, .xls) or
//! OpenDocument (.ods) workbook, opened and turned into rows of cells by
//! the measured-data reader's workbook code ([`crate::data::workbook`]),
//! so that sheets, cells, comments and spreadsheet errors are read alike
//! for both.
//!
//! The header is the first row, above the first row of numbers, that
//! names a frequency, a storage and a loss modulus ([`header::is_header`]):
//! title and metadata rows above it, as an instrument's export writes
//! them, are skipped. A units row right below it (the Netzsch/GABO Eplexor
//! "Excel Export": `[Hz]`, `[°C]`, `[MPa]`, `[-]`) gives the units of the
//! columns whose names carry none. From there the columns are
//! [`super::header`]'s, as for CSV text.
//!
//! Rows below: numbers or numeric text (decimal commas allowed: no
//! delimiter to confuse them with). A row with an empty cell or a
//! spreadsheet error (#DIV/0!, #N/A) or NaN text in a column read is
//! skipped, with one warning listing the rows, as the measured-data reader
//! does; text that is no number is refused naming the sheet and cell
//! (`sheet "Sheet1", cell C7`). A sheet without such a header (an empty
//! one too) is refused with the header cells found on every sheet, for
//! choosing another.

use std::path::Path;

use super::form::{FormRead, Place, RawPoint};
use super::header::{self, Column, Header};
use crate::data::cell::{Cell, NotNumber, Row, parse_number};
use crate::data::dialect::header_index;
use crate::data::workbook::{Book, has_workbook_extension};
use crate::error::{IoError, RowsRef};

/// The points of the sheet `wanted` (default: the first) of the workbook
/// `bytes`, the sheet's name, and notes on how it was read.
pub(super) fn parse(
    path: &Path,
    bytes: Vec<u8>,
    wanted: Option<&str>,
    told: header::Told,
) -> Result<(FormRead, String, Vec<String>), IoError> {
    let workbook = |error: IoError| -> IoError { err!("{}: {error}", path.display()) };
    let mut notes = Vec::new();
    if !has_workbook_extension(path) {
        notes.push("the file is a workbook (by its content), read as one".to_string());
    }
    let mut book = Book::open(bytes).map_err(workbook)?;
    let sheet = book.choose(wanted, &mut notes).map_err(workbook)?;
    let rows = book.rows(&sheet).map_err(workbook)?;
    let place = Place {
        path,
        sheet: Some(&sheet),
    };
    let Some(at) = find_header(&rows) else {
        return Err(no_columns(path, &sheet, &mut book));
    };
    let names = texts(&rows[at]);
    let titles = rows[..at].iter().filter(|r| !r.is_blank()).count();
    if titles > 0 {
        notes.push(format!(
            "header on {}; the {titles} row{} above it (titles) ignored",
            place.row(row_number(&rows[at])),
            if titles == 1 { "" } else { "s" }
        ));
    }
    let below = rows.get(at + 1).map(texts);
    let units = below
        .as_deref()
        .filter(|cells| header::is_units_row(&names, cells))
        .map(|cells| (row_number(&rows[at + 1]), cells));
    if let Some((number, _)) = units {
        notes.push(format!(
            "units from {}, below the header",
            place.row(number)
        ));
    }
    let first_data = at + 1 + usize::from(units.is_some());
    let header = header::columns(&place, row_number(&rows[at]), names, units, told)?;
    let mut read = read_rows(&place, &rows[first_data..], &header)?;
    read.preamble = rows[..at]
        .iter()
        .filter(|r| !r.is_blank())
        .map(|r| (row_number(r), texts(r).join(" ")))
        .collect();
    read.warnings.splice(0..0, header_warning(path, &header));
    let notes = notes
        .into_iter()
        .map(|n| format!("{}: {n}", path.display()))
        .chain(header.notes(path))
        .collect();
    Ok((read, sheet, notes))
}

/// The warning of a header with both Young's and shear columns.
fn header_warning(path: &Path, header: &Header) -> Option<String> {
    header.both.then(|| {
        format!(
            "{}: both Young's (E) and shear (G) columns; the Young's ones are used",
            path.display()
        )
    })
}

/// The row number of `row` as the rest of the DMA reader counts lines.
fn row_number(row: &Row) -> usize {
    usize::try_from(row.number).unwrap_or(usize::MAX)
}

/// The cells of `row` as header texts ("" for an empty cell).
pub(super) fn texts(row: &Row) -> Vec<String> {
    row.cells.iter().map(Cell::name).collect()
}

/// The index of the header row among `rows`: the first naming a
/// frequency, a storage and a loss modulus, searched until the first row
/// of numbers.
fn find_header(rows: &[Row]) -> Option<usize> {
    header_index(rows, |row| *row, is_header).map(|(i, _)| i)
}

/// Whether `row` names a frequency, a storage and a loss modulus.
pub(super) fn is_header(row: &Row) -> bool {
    header::is_header(&texts(row))
}

/// The cells of the row of `rows` most like a header: of the rows above
/// the first row of numbers, the one with the most text cells.
fn header_like(rows: &[Row]) -> Vec<String> {
    let text_cells = |row: &Row| {
        row.cells
            .iter()
            .filter(|c| matches!(c, Cell::Text(_)))
            .count()
    };
    rows.iter()
        .take_while(|row| !row.is_numeric())
        .filter(|row| !row.is_blank())
        .fold(None::<&Row>, |best, row| match best {
            Some(b) if text_cells(b) >= text_cells(row) => Some(b),
            _ => Some(row),
        })
        .map(Row::names)
        .unwrap_or_default()
}

/// The error of a sheet without DMA columns: the header cells found on
/// every sheet of the workbook.
fn no_columns(path: &Path, sheet: &str, book: &mut Book) -> IoError {
    let found: Vec<(String, Vec<String>)> = book
        .names()
        .into_iter()
        .map(|name| {
            let cells = book
                .rows(&name)
                .map(|r| header_like(&r))
                .unwrap_or_default();
            (name, cells)
        })
        .collect();
    err!(
        "{}: sheet {sheet:?}: no header row naming a frequency (f [Hz], omega [rad/s]), a storage \
         and a loss modulus (E', E'' or E_storage, E_loss; shear G', G'' or G_storage, G_loss), \
         each with its unit in the name or in a units row below; {}",
        path.display(),
        sheets_found(&found),
    )
}

/// The points of `rows`, the rows below the header (and units row).
fn read_rows(place: &Place, rows: &[Row], header: &Header) -> Result<FormRead, IoError> {
    let mut points = Vec::new();
    let mut skipped = Vec::new();
    let mut first_error = None;
    for row in rows.iter().filter(|r| !r.is_blank()) {
        let number = row_number(row);
        let read = |c: &Column| value(place, row, number, c);
        let (omega, storage, loss) = (
            read(&header.omega)?,
            read(&header.storage)?,
            read(&header.loss)?,
        );
        let temperature = header.temperature.as_ref().map(read).transpose()?;
        match (omega, storage, loss, temperature) {
            (Some(omega), Some(storage), Some(loss), None | Some(Some(_))) => {
                points.push(RawPoint {
                    line: number,
                    omega,
                    storage,
                    loss,
                    temperature: temperature.flatten(),
                    step: header.step.as_ref().and_then(|c| step_label(row, c)),
                });
            }
            _ => {
                skipped.push(row.number);
                if first_error.is_none() {
                    first_error = spreadsheet_error(place, row, header);
                }
            }
        }
    }
    let mut warnings = Vec::new();
    if !skipped.is_empty() {
        let rows = RowsRef {
            sheet: place.sheet.map(str::to_string),
            numbers: skipped,
        };
        warnings.push(format!(
            "{}: skipped {} with an empty cell, NaN or a spreadsheet error (#DIV/0!, #N/A) in a \
             column read{}",
            place.path.display(),
            rows,
            first_error.map_or(String::new(), |e| format!("; the first error: {e}"))
        ));
    }
    header.form(place.path, points, warnings)
}

/// The label of the step column `c` in `row` (None: empty).
fn step_label(row: &Row, c: &Column) -> Option<String> {
    let label = row.cells.get(c.index)?.name();
    (!label.is_empty()).then_some(label)
}

/// Where `row` holds a spreadsheet error in a column read, and which: `sheet
/// "S", cell C7: E'' [MPa]: the cell holds the Excel error #DIV/0!`.
fn spreadsheet_error(place: &Place, row: &Row, header: &Header) -> Option<String> {
    let columns = [&header.omega, &header.storage, &header.loss];
    columns
        .into_iter()
        .chain(header.temperature.as_ref())
        .find_map(|c| match row.cells.get(c.index) {
            Some(Cell::Error(error)) => Some(format!(
                "{}: {}: the cell holds the Excel error {error}",
                place.cell(row_number(row), c.index),
                c.reference
            )),
            _ => None,
        })
}

/// The value of column `c` in `row` (number `number`), in SI; None for no
/// value (empty, NaN, a spreadsheet error).
fn value(place: &Place, row: &Row, number: usize, c: &Column) -> Result<Option<f64>, IoError> {
    let cell = row.cells.get(c.index).unwrap_or(&Cell::Empty);
    let path = place.path.to_path_buf();
    let at = Box::new(place.cell(number, c.index));
    let column = c.reference.clone();
    match parse_number(cell, true) {
        Ok(number) => Ok(number.map(|n| c.convert(n.value))),
        Err(NotNumber::Formula(formula)) => Err(err!(
            "{}, {cell}: {column}: the cell holds a formula (={formula}) the file saved no result \
         for; open it in Excel or LibreOffice and save, so its value is stored",
            path.display(),
            cell = at
        )),
        Err(NotNumber::NotFinite(text)) => Err(err!(
            "{}, {cell}: {column}: {text} is not a finite number",
            path.display(),
            cell = at
        )),
        Err(
            NotNumber::Other(text)
            | NotNumber::AmbiguousComma(text)
            | NotNumber::Thousands(text)
            | NotNumber::Text(text),
        ) => Err(err!(
            "{}, {cell}: {column}: \"{text}\" is not a number",
            path.display(),
            cell = at
        )),
    }
}

/// The header cells found on each sheet of a workbook: `sheet "A" has
/// "f", "x"; sheet "B" is empty`.
fn sheets_found(found: &[(String, Vec<String>)]) -> String {
    let sheets: Vec<String> = found
        .iter()
        .map(|(sheet, cells)| {
            if cells.is_empty() {
                format!("sheet {sheet:?} has no header cells")
            } else {
                let cells: Vec<String> = cells.iter().map(|c| format!("{c:?}")).collect();
                format!("sheet {sheet:?} has {}", cells.join(", "))
            }
        })
        .collect();
    format!("found: {}", sheets.join("; "))
}
