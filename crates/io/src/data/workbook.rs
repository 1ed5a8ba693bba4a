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
use crate::error::IoError;
use crate::error::data::quoted_list;

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
    pub fn open(bytes: Vec<u8>) -> Result<Book, IoError> {
        let sheets = calamine::open_workbook_auto_from_rs(Cursor::new(bytes)).map_err(|error| {
            err!("cannot read the file as a workbook (.xlsx, .xlsm, .xlsb, .xls, .ods): {error}")
        })?;
        Ok(Book { sheets })
    }

    /// The names of its sheets, in order.
    pub fn names(&self) -> Vec<String> {
        self.sheets.sheet_names()
    }

    /// The sheet `wanted` (see [`choose_sheet`]) or the first.
    pub fn choose(&self, wanted: Option<&str>, notes: &mut Vec<String>) -> Result<String, IoError> {
        choose_sheet(&self.names(), wanted, notes)
    }

    /// The rows of the sheet `name`, numbered as the spreadsheet shows
    /// them, `#` comment rows and rows without a cell left out.
    pub fn rows(&mut self, name: &str) -> Result<Vec<Row>, IoError> {
        let unreadable =
            |error: calamine::Error| err!("sheet {sheet:?}: cannot read it: {error}", sheet = name);
        let cells = match &mut self.sheets {
            calamine::Sheets::Xlsx(book) => xlsx_cells(book, name).map_err(unreadable)?,
            calamine::Sheets::Xlsb(book) => xlsb_cells(book, name).map_err(unreadable)?,
            _ => self.range_cells(name).map_err(unreadable)?,
        };
        Ok(rows_of(cells)
            .into_iter()
            .filter(|row| !is_comment(row))
            .collect())
    }

    /// The cells of the sheet `name` from calamine's rectangular range
    /// (.xls, whose reader builds it while opening the file, and .ods,
    /// whose reader caps it at 1e8 cells and refuses more).
    fn range_cells(&mut self, name: &str) -> Result<Vec<Placed>, calamine::Error> {
        let range = self.sheets.worksheet_range(name)?;
        // Formulas only matter where the file holds no result for them; a
        // form without formulas (or one calamine cannot read them from)
        // leaves every empty cell empty.
        let formulas = self.sheets.worksheet_formula(name).ok();
        let formula_at = |pos: (u32, u32)| {
            let formula = formulas.as_ref()?.get_value(pos)?.trim();
            (!formula.is_empty()).then(|| Cell::Formula(formula.to_string()))
        };
        Ok(range
            .used_cells()
            .filter_map(|(i, j, data)| {
                let (row0, column0) = range.start().unwrap_or((0, 0));
                let pos = (row0 + i as u32, column0 + j as u32);
                match data {
                    Data::Empty => formula_at(pos).map(|c| (pos, c)),
                    data => Some((pos, cell(data))),
                }
            })
            .collect())
    }
}

/// A cell and its (row, column), both from 0.
type Placed = ((u32, u32), Cell);

/// The cells of an .xlsx sheet that hold a value or a formula, as the
/// file lists them: memory follows the cells, not the sheet's extent (a
/// stray cell at XFD1048576 spans 1.7e10 cells).
fn xlsx_cells<RS: std::io::Read + std::io::Seek>(
    book: &mut calamine::Xlsx<RS>,
    name: &str,
) -> Result<Vec<Placed>, calamine::Error> {
    let mut reader = match book.worksheet_cells_reader(name) {
        // A chart sheet has no cells (calamine's range is empty too).
        Err(calamine::XlsxError::NotAWorksheet(_)) => return Ok(Vec::new()),
        reader => reader?,
    };
    let mut cells = Vec::new();
    while let Some(found) = reader.next_cell_with_formula()? {
        let data = Data::from(found.value);
        let formula = found.formula.filter(|f| !f.trim().is_empty());
        match (data, formula) {
            (Data::Empty, Some(f)) => cells.push((found.pos, Cell::Formula(f.trim().to_string()))),
            (Data::Empty, None) => {}
            (data, _) => cells.push((found.pos, cell(&data))),
        }
    }
    Ok(cells)
}

/// The cells of an .xlsb sheet that hold a value or a formula (as
/// [`xlsx_cells`]; the formulas are a second pass over the sheet).
fn xlsb_cells<RS: std::io::Read + std::io::Seek>(
    book: &mut calamine::Xlsb<RS>,
    name: &str,
) -> Result<Vec<Placed>, calamine::Error> {
    let mut cells = Vec::new();
    let mut empty = std::collections::BTreeSet::new();
    {
        let mut reader = book.worksheet_cells_reader(name)?;
        while let Some(found) = reader.next_cell()? {
            match Data::from(found.get_value().clone()) {
                Data::Empty => {
                    empty.insert(found.get_position());
                }
                data => cells.push((found.get_position(), cell(&data))),
            }
        }
    }
    if !empty.is_empty()
        && let Ok(mut reader) = book.worksheet_cells_reader(name)
    {
        while let Ok(Some(found)) = reader.next_formula() {
            let formula = found.get_value().trim();
            if !formula.is_empty() && empty.contains(&found.get_position()) {
                cells.push((found.get_position(), Cell::Formula(formula.to_string())));
            }
        }
    }
    Ok(cells)
}

/// Rows of `cells`, ascending, each as wide as its last cell (the rows
/// without a cell left out: every reader skips blank rows).
fn rows_of(mut cells: Vec<Placed>) -> Vec<Row> {
    cells.sort_by_key(|(pos, _)| *pos);
    let mut rows: Vec<Row> = Vec::new();
    for ((row, column), value) in cells {
        let number = u64::from(row) + 1;
        if rows.last().is_none_or(|r| r.number != number) {
            rows.push(Row {
                number,
                cells: Vec::new(),
            });
        }
        let Some(last) = rows.last_mut() else {
            continue;
        };
        let column = column as usize;
        if let Some(twice) = last.cells.get_mut(column) {
            // A position listed twice: the later record stands.
            *twice = value;
            continue;
        }
        last.cells.resize(column, Cell::Empty);
        last.cells.push(value);
    }
    rows
}

/// Reads the sheet `wanted` (default: the first) of the workbook `bytes`.
pub(super) fn parse(
    path: &Path,
    bytes: Vec<u8>,
    wanted: Option<&str>,
) -> Result<DataTable, IoError> {
    let mut notes = Vec::new();
    if !has_workbook_extension(path) {
        notes.push("the file is a workbook (by its content), read as one".to_string());
    }
    let mut book = Book::open(bytes)?;
    let name = book.choose(wanted, &mut notes)?;
    let rows = book.rows(&name)?;
    if rows.iter().all(Row::is_blank) {
        return Err(err!(
            "sheet {sheet:?} is empty: expected a header row (v, mu, optionally sigma and T) and \
         data rows",
            sheet = name
        ));
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
) -> Result<String, IoError> {
    let listed = || {
        names
            .iter()
            .map(|n| format!("{n:?}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let Some(wanted) = wanted else {
        let first = names
            .first()
            .ok_or(err!("the workbook has no sheets"))?
            .clone();
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
        .ok_or_else(|| {
            err!(
                "no sheet {wanted:?}: the workbook has {}",
                quoted_list(names),
            )
        })
}

/// A row whose first cell with anything in it is text starting with `#`.
fn is_comment(row: &Row) -> bool {
    match row.cells.iter().find(|c| !c.is_empty()) {
        Some(Cell::Text(t)) => is_comment_or_blank(t),
        _ => false,
    }
}

/// What to do about a number shown as a date: spreadsheets turn a typed
/// number into a date when the column is formatted as dates.
const DATE_FIX: &str = " (a cell formatted as a date or time: format the column as \"Number\" \
                        in the spreadsheet and save it again)";

fn cell(data: &Data) -> Cell {
    match data {
        Data::Empty => Cell::Empty,
        Data::Int(i) => Cell::Number(*i as f64),
        Data::Float(x) => Cell::Number(*x),
        Data::String(s) => Cell::text(s),
        Data::Error(e) => Cell::Error(e.to_string()),
        Data::Bool(b) => Cell::Other(format!("the boolean {}", if *b { "TRUE" } else { "FALSE" })),
        Data::DateTime(d) => Cell::Other(format!("the date/time {d}{DATE_FIX}")),
        Data::DateTimeIso(s) | Data::DurationIso(s) => {
            Cell::Other(format!("the date/time {s}{DATE_FIX}"))
        }
    }
}

#[cfg(test)]
pub(super) mod tests;
