//! Workbooks as measured data (docs/ARCHITECTURE.md, "Contract", "Measured
//! data"): Excel (.xlsx, .xlsm, .xlsb, .xls) and OpenDocument (.ods), read
//! with calamine. A file is a workbook by its extension or, whatever its
//! name, by its first bytes (a zip archive or an OLE compound file), so an
//! .xlsx saved as `data.csv` is still read.
//!
//! The first sheet is read, or the one named (`rollfit fit --sheet NAME`,
//! matched exactly, else case-insensitively). Cells hold numbers or numeric
//! text (decimal commas allowed: there is no delimiter to confuse them
//! with); rows whose first cell with anything in it is text starting with
//! `#` are comments; the header is found and read as in a text file.
//! Empty cells and spreadsheet errors (#DIV/0!, #N/A) are cells without a
//! value; booleans and dates are not numbers. Messages name the sheet and
//! the cell: `sheet "Run 1", cell B7`.

use std::io::Cursor;
use std::path::Path;

use calamine::{Data, Reader};

use super::DataTable;
use super::cell::{Cell, Row, is_comment_or_blank};
use super::header_row::find_header;
use super::rows::table;
use super::source::Source;
use crate::error::DataError;

/// The extensions read as workbooks (compared in lower case).
const EXTENSIONS: [&str; 6] = ["xlsx", "xlsm", "xlsb", "xls", "xla", "ods"];

/// The start of a zip archive (.xlsx, .xlsm, .xlsb, .ods).
const ZIP: [u8; 4] = *b"PK\x03\x04";
/// The start of an OLE compound file (.xls).
const OLE: [u8; 8] = [0xD0, 0xCF, 0x11, 0xE0, 0xA1, 0xB1, 0x1A, 0xE1];

/// Whether `path` with content `bytes` is a workbook.
pub(crate) fn is_workbook(path: &Path, bytes: &[u8]) -> bool {
    has_workbook_extension(path) || bytes.starts_with(&ZIP) || bytes.starts_with(&OLE)
}

pub(crate) fn has_workbook_extension(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| EXTENSIONS.contains(&e.to_lowercase().as_str()))
}

/// A workbook opened: its sheets, read as rows of cells. Shared by
/// measured data and DMA files (`crate::dma::sheet`), so that both read
/// cells, comments and sheets alike.
pub(crate) struct Book {
    sheets: calamine::Sheets<Cursor<Vec<u8>>>,
}

impl Book {
    /// The workbook `bytes`.
    pub fn open(bytes: Vec<u8>) -> Result<Book, DataError> {
        let sheets = calamine::open_workbook_auto_from_rs(Cursor::new(bytes))
            .map_err(|error| DataError::NotWorkbook { error })?;
        Ok(Book { sheets })
    }

    /// The names of its sheets, in order.
    pub fn names(&self) -> Vec<String> {
        self.sheets.sheet_names()
    }

    /// The sheet `wanted` (see [`choose_sheet`]) or the first.
    pub fn choose(
        &self,
        wanted: Option<&str>,
        notes: &mut Vec<String>,
    ) -> Result<String, DataError> {
        choose_sheet(&self.names(), wanted, notes)
    }

    /// The rows of the sheet `name`, numbered as the spreadsheet shows
    /// them, `#` comment rows left out.
    pub fn rows(&mut self, name: &str) -> Result<Vec<Row>, DataError> {
        let range =
            self.sheets
                .worksheet_range(name)
                .map_err(|error| DataError::UnreadableSheet {
                    sheet: name.to_string(),
                    error,
                })?;
        // Formulas only matter where the file holds no result for them; a
        // form without formulas (or one calamine cannot read them from)
        // leaves every empty cell empty.
        let formulas = self.sheets.worksheet_formula(name).ok();
        let formula_at = |row: u32, column: u32| {
            let formula = formulas.as_ref()?.get_value((row, column))?.trim();
            (!formula.is_empty()).then(|| Cell::Formula(formula.to_string()))
        };
        let (row0, column0) = range.start().unwrap_or((0, 0));
        Ok(range
            .rows()
            .enumerate()
            .map(|(i, cells)| Row {
                number: u64::from(row0) + i as u64 + 1,
                cells: std::iter::repeat_n(Cell::Empty, column0 as usize)
                    .chain(cells.iter().enumerate().map(|(j, data)| match data {
                        Data::Empty => {
                            formula_at(row0 + i as u32, column0 + j as u32).unwrap_or(Cell::Empty)
                        }
                        data => cell(data),
                    }))
                    .collect(),
            })
            .filter(|row| !is_comment(row))
            .collect())
    }
}

/// Reads the sheet `wanted` (default: the first) of the workbook `bytes`.
pub(super) fn parse(
    path: &Path,
    bytes: Vec<u8>,
    wanted: Option<&str>,
) -> Result<DataTable, DataError> {
    let mut notes = Vec::new();
    if !has_workbook_extension(path) {
        notes.push("the file is a workbook (by its content), read as one".to_string());
    }
    let mut book = Book::open(bytes)?;
    let name = book.choose(wanted, &mut notes)?;
    let rows = book.rows(&name)?;
    if rows.iter().all(Row::is_blank) {
        return Err(DataError::EmptySheet { sheet: name });
    }
    let header = find_header(&rows);
    table(&Source::Sheet { name }, rows, header, notes)
}

/// The sheet to read of `names`: `wanted` (matched exactly, else
/// case-insensitively when that matches one), or the first, with a note
/// when there are others.
fn choose_sheet(
    names: &[String],
    wanted: Option<&str>,
    notes: &mut Vec<String>,
) -> Result<String, DataError> {
    let listed = || {
        names
            .iter()
            .map(|n| format!("{n:?}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let Some(wanted) = wanted else {
        let first = names.first().ok_or(DataError::NoSheets)?.clone();
        if names.len() > 1 {
            notes.push(format!(
                "sheet {first:?}, the first of {} ({}); choose another with --sheet",
                names.len(),
                listed()
            ));
        }
        return Ok(first);
    };
    let folded: Vec<&String> = names
        .iter()
        .filter(|n| n.to_lowercase() == wanted.to_lowercase())
        .collect();
    names
        .iter()
        .find(|n| *n == wanted)
        .or(match folded.as_slice() {
            [one] => Some(*one),
            _ => None,
        })
        .cloned()
        .ok_or_else(|| DataError::NoSuchSheet {
            wanted: wanted.to_string(),
            sheets: names.to_vec(),
        })
}

/// A row whose first cell with anything in it is text starting with `#`.
fn is_comment(row: &Row) -> bool {
    match row.cells.iter().find(|c| !c.is_empty()) {
        Some(Cell::Text(t)) => is_comment_or_blank(t),
        _ => false,
    }
}

fn cell(data: &Data) -> Cell {
    match data {
        Data::Empty => Cell::Empty,
        Data::Int(i) => Cell::Number(*i as f64),
        Data::Float(x) => Cell::Number(*x),
        Data::String(s) => Cell::text(s),
        Data::Error(e) => Cell::Error(e.to_string()),
        Data::Bool(b) => Cell::Other(format!("the boolean {}", if *b { "TRUE" } else { "FALSE" })),
        Data::DateTime(d) => Cell::Other(format!("the date/time {d}")),
        Data::DateTimeIso(s) | Data::DurationIso(s) => Cell::Other(format!("the date/time {s}")),
    }
}

#[cfg(test)]
pub(super) mod tests;
