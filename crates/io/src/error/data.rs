//! The errors of a measured-data file ([`DataError`], reached as
//! [`super::IoError::Data`]): one variant per cause, with the place as
//! data — a text file's line or a workbook's sheet, row and cell
//! ([`RowRef`], [`CellRef`]) — and the column as its header names it
//! ([`ColumnName`]). The causes inside a file do not name the file:
//! [`DataError::InFile`] does, and `{:#}` prints it first, as
//! `data file PATH: line 7: column `v`: "abc" is not a number`
//! (docs/ARCHITECTURE.md, "Contract", "Measured data").

use std::fmt;
use std::path::PathBuf;

use rollfit_fit::data::SIGMA_REQUIREMENT;
use thiserror::Error;

use crate::data::quantity::Quantity;

/// A row of a measured-data file as messages name it: `line 7` in a text
/// file, `sheet "Run 1", row 7` in a workbook.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RowRef {
    /// The workbook's sheet (`None`: a text file).
    pub sheet: Option<String>,
    /// The line of a text file or the row of a sheet, from 1.
    pub number: u64,
}

impl RowRef {
    /// Line `number` of a text file.
    pub fn line(number: usize) -> RowRef {
        RowRef {
            sheet: None,
            number: number as u64,
        }
    }
}

impl fmt::Display for RowRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.sheet {
            None => write!(f, "line {}", self.number),
            Some(name) => write!(f, "sheet {name:?}, row {}", self.number),
        }
    }
}

/// A cell: `line 7` in a text file (the message names the column beside
/// it), `sheet "Run 1", cell B7` in a workbook.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CellRef {
    /// Its row.
    pub row: RowRef,
    /// Its column, from 0.
    pub column: usize,
}

impl CellRef {
    /// Line `number` of a text file (the message names the column).
    pub fn line(number: usize) -> CellRef {
        CellRef {
            row: RowRef::line(number),
            column: 0,
        }
    }
}

impl fmt::Display for CellRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.row.sheet {
            None => write!(f, "line {}", self.row.number),
            Some(name) => write!(
                f,
                "sheet {name:?}, cell {}{}",
                column_letter(self.column),
                self.row.number
            ),
        }
    }
}

/// Several rows: `lines 7, 12`, `sheet "Run 1", rows 7, 12` (the first 20,
/// then how many in all).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RowsRef {
    /// The workbook's sheet (`None`: a text file).
    pub sheet: Option<String>,
    /// The lines or rows, from 1.
    pub numbers: Vec<u64>,
}

impl fmt::Display for RowsRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const SHOWN: usize = 20;
        let numbers = &self.numbers;
        let mut list: Vec<String> = numbers.iter().take(SHOWN).map(u64::to_string).collect();
        if numbers.len() > SHOWN {
            list.push(format!("… ({} in all)", numbers.len()));
        }
        let plural = if numbers.len() == 1 { "" } else { "s" };
        match &self.sheet {
            None => write!(f, "line{plural} {}", list.join(", ")),
            Some(name) => write!(f, "sheet {name:?}, row{plural} {}", list.join(", ")),
        }
    }
}

/// A column read, as messages name it: `` `v` `` when its header is the
/// canonical name, else `` `velocity (mm/s)` (v) ``.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ColumnName {
    /// The header as written.
    pub header: String,
    /// The quantity it holds.
    pub quantity: Quantity,
}

impl fmt::Display for ColumnName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let key = self.quantity.key();
        if self.header == key {
            write!(f, "`{key}`")
        } else {
            write!(f, "`{}` ({key})", self.header)
        }
    }
}

/// Why a measured-data file cannot be read. The first three variants and
/// [`DataError::Measurements`]' caller name the file; every other variant
/// is a cause inside [`DataError::InFile`].
#[derive(Debug, Error)]
pub enum DataError {
    // ------------------------------------------------------------ the file
    /// The file could not be read.
    #[error("cannot open data file {}", path.display())]
    Open {
        path: PathBuf,
        source: std::io::Error,
    },
    /// `--sheet` (or a manifest's `sheet`) given for a text file.
    #[error(
        "data file {}: a sheet ({sheet:?}) was given, but the file is text, not a workbook \
         (.xlsx, .xlsm, .xlsb, .xls, .ods)",
        path.display()
    )]
    SheetOfText { path: PathBuf, sheet: String },
    /// What is wrong inside the file (the source, one of the variants
    /// below).
    #[error("data file {}", path.display())]
    InFile {
        path: PathBuf,
        source: Box<DataError>,
    },
    /// Measurements the fit library refuses (its message; the caller
    /// names the file).
    #[error(transparent)]
    Measurements(rollfit_fit::FitError),

    // ------------------------------------------------------------ text
    /// A UTF-16 byte-order mark and an odd number of bytes.
    #[error("the file starts with a UTF-16 byte-order mark but has an odd number of bytes")]
    OddUtf16,
    /// A UTF-16 byte-order mark and something else than UTF-16.
    #[error("the file is not valid UTF-16 text")]
    NotUtf16 { source: std::string::FromUtf16Error },
    /// Nothing but comments and blank lines.
    #[error(
        "the file is empty: expected a header row (v, mu, optionally sigma and T) and data rows"
    )]
    Empty,
    /// No row names a speed and a friction column; `row` is the first row
    /// (`found` its cells), `delimiter` the one guessed in a text file.
    #[error(
        "{row} (header): {}; found {}{}",
        missing_columns(missing),
        quoted_list(found),
        delimiter.map_or(String::new(), |d| format!(" (delimiter {})", delimiter_name(d)))
    )]
    NoHeader {
        row: RowRef,
        /// The quantities the row does not name (speed, friction or both).
        missing: Vec<Quantity>,
        /// Its non-empty cells.
        found: Vec<String>,
        /// The delimiter of a text file.
        delimiter: Option<char>,
    },
    /// A header column of a quantity in a unit not understood.
    #[error(
        "{row} (header): column {header:?}: unknown {} unit {unit:?}; units understood: {}",
        quantity.what(),
        quantity.units()
    )]
    UnknownUnit {
        /// The header row.
        row: RowRef,
        /// The header cell.
        header: String,
        quantity: Quantity,
        /// The unit as written.
        unit: String,
    },
    /// A unit in the units row below the header not understood.
    #[error(
        "{cell}: column {header:?}: unknown {} unit {unit:?} in the units row; units \
         understood: {}",
        quantity.what(),
        quantity.units()
    )]
    UnknownUnitInUnitsRow {
        cell: CellRef,
        /// The column's header.
        header: String,
        quantity: Quantity,
        /// The unit as written.
        unit: String,
    },
    /// Two columns of one quantity.
    #[error(
        "{row} (header): two {} columns, {first:?} ({}) and {second:?} ({}): keep one",
        quantity.what(),
        column_of(row, *first_index),
        column_of(row, *second_index)
    )]
    TwoColumns {
        /// The header row.
        row: RowRef,
        quantity: Quantity,
        /// The first column's header and index (from 0).
        first: String,
        first_index: usize,
        /// The second's.
        second: String,
        second_index: usize,
    },

    // ------------------------------------------------------------ rows
    /// A row with a value beyond the header's columns.
    #[error(
        "{row}: malformed row: {fields} fields, the header ({header_row}) has {width}{}",
        if *comma_delimited {
            "; if the numbers have decimal commas (0,0123), a comma-delimited file is \
             ambiguous: export with ';' as the delimiter, or with decimal points"
        } else {
            ""
        }
    )]
    ExtraFields {
        row: RowRef,
        /// Its fields, trailing empty ones left out.
        fields: usize,
        header_row: RowRef,
        /// The header's cells.
        width: usize,
        /// The file is comma-delimited (decimal commas may be the cause).
        comma_delimited: bool,
    },
    /// A row that ends before a column read.
    #[error(
        "{row}: malformed row: {fields} field{}, the header ({header_row}) has {width}",
        if *fields == 1 { "" } else { "s" }
    )]
    MissingFields {
        row: RowRef,
        fields: usize,
        header_row: RowRef,
        width: usize,
    },
    /// A workbook formula without a saved result: refused, not skipped, as
    /// its value is one the user means.
    #[error(
        "{cell}: column {column}: the cell holds a formula (={formula}) the file saved no result \
         for; open it in Excel or LibreOffice and save, so its value is stored"
    )]
    FormulaWithoutValue {
        cell: CellRef,
        column: ColumnName,
        /// As written, without its `=`.
        formula: String,
    },
    /// A workbook value that is no number (a boolean, a date).
    #[error("{cell}: column {column}: {what} is not a number")]
    NonNumericValue {
        cell: CellRef,
        column: ColumnName,
        /// The value described ("the boolean TRUE").
        what: String,
    },
    /// A decimal comma in a comma-delimited file.
    #[error(
        "{cell}: column {column}: {text:?}: a decimal comma in a comma-delimited file is \
         ambiguous; export with ';' as the delimiter, or with decimal points"
    )]
    AmbiguousDecimalComma {
        cell: CellRef,
        column: ColumnName,
        text: String,
    },
    /// Several commas, or a comma and a point, in a number.
    #[error(
        "{cell}: column {column}: {text:?} is not a number (thousands separators are not \
         understood)"
    )]
    ThousandsSeparator {
        cell: CellRef,
        column: ColumnName,
        text: String,
    },
    /// Text that is not a number.
    #[error("{cell}: column {column}: {text:?} is not a number")]
    NotANumber {
        cell: CellRef,
        column: ColumnName,
        text: String,
    },
    /// `inf` and the like.
    #[error("{cell}: column {column}: {text:?} is not a finite number")]
    NotFinite {
        cell: CellRef,
        column: ColumnName,
        text: String,
    },
    /// A value outside its quantity's range (the fit library's
    /// requirement); a converted value is shown in SI too.
    #[error(
        "{cell}: column {column} = {text}{}: {requirement}{}",
        if *converted { format!(" ({value:e} {} in SI)", column.quantity.key()) } else { String::new() },
        why_positive(column.quantity, *value)
    )]
    OutOfRange {
        cell: CellRef,
        column: ColumnName,
        /// The cell as written.
        text: String,
        /// Its value in SI.
        value: f64,
        /// The column's unit was converted (and the value is positive).
        converted: bool,
        /// What the value must be ("must be greater than zero").
        requirement: &'static str,
    },
    /// A standard deviation too small against its row's μ.
    #[error("{cell}: column {column} = {sigma:e}: {SIGMA_REQUIREMENT}")]
    SigmaTooSmall {
        cell: CellRef,
        column: ColumnName,
        sigma: f64,
    },
    /// Every row had an empty or NaN cell.
    #[error(
        "no data rows left: every row has an empty or NaN cell in {} ({rows}): nothing to fit",
        key_list(quantities)
    )]
    AllRowsSkipped {
        /// The quantities with empty cells.
        quantities: Vec<Quantity>,
        rows: RowsRef,
    },
    /// A header and no rows below it.
    #[error("the file has a header but no data rows: nothing to fit")]
    NoDataRows,

    // ------------------------------------------------------------ workbooks
    /// calamine cannot open the workbook (what it said is shown, not a
    /// source, as the message always had it).
    #[error("cannot read the file as a workbook (.xlsx, .xlsm, .xlsb, .xls, .ods): {error}")]
    NotWorkbook { error: calamine::Error },
    /// A workbook without sheets.
    #[error("the workbook has no sheets")]
    NoSheets,
    /// `--sheet` names no sheet of the workbook.
    #[error("no sheet {wanted:?}: the workbook has {}", quoted_list(sheets))]
    NoSuchSheet {
        wanted: String,
        /// The workbook's sheets.
        sheets: Vec<String>,
    },
    /// calamine cannot read the sheet.
    #[error("sheet {sheet:?}: cannot read it: {error}")]
    UnreadableSheet {
        sheet: String,
        error: calamine::Error,
    },
    /// A sheet with nothing but comments and empty rows.
    #[error(
        "sheet {sheet:?} is empty: expected a header row (v, mu, optionally sigma and T) and \
         data rows"
    )]
    EmptySheet { sheet: String },
}

impl From<DataError> for super::IoError {
    fn from(e: DataError) -> Self {
        super::IoError::transparent(super::ErrorKind::Content, e)
    }
}

/// How a message names a delimiter: `tab`, `';'`, `','`.
pub(crate) fn delimiter_name(delimiter: char) -> &'static str {
    match delimiter {
        '\t' => "tab",
        ';' => "';'",
        _ => "','",
    }
}

/// The spreadsheet letter of column `index` (from 0): A, …, Z, AA, AB, ….
pub fn column_letter(index: usize) -> String {
    let mut n = index + 1;
    let mut letters = Vec::new();
    while n > 0 {
        let rem = (n - 1) % 26;
        letters.push(char::from(b'A' + rem as u8));
        n = (n - 1) / 26;
    }
    letters.iter().rev().collect()
}

/// `column 3` in a text file, `column C` in a sheet.
fn column_of(row: &RowRef, index: usize) -> String {
    match row.sheet {
        None => format!("column {}", index + 1),
        Some(_) => format!("column {}", column_letter(index)),
    }
}

/// `"a", "b"`.
fn quoted_list(items: &[String]) -> String {
    let quoted: Vec<String> = items.iter().map(|i| format!("{i:?}")).collect();
    quoted.join(", ")
}

/// `no speed column (…) and no friction column (…)`.
fn missing_columns(missing: &[Quantity]) -> String {
    let parts: Vec<String> = missing
        .iter()
        .map(|q| format!("no {} column ({})", q.what(), q.understood()))
        .collect();
    parts.join(" and ")
}

/// `v`, `v or mu`, `v, mu, sigma or T`.
pub(crate) fn key_list(quantities: &[Quantity]) -> String {
    let keys: Vec<&str> = quantities.iter().map(|q| q.key()).collect();
    match keys.split_last() {
        Some((last, [])) => last.to_string(),
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
        None => String::new(),
    }
}

/// Why a value must be positive, where a requirement of the fit library
/// does not say it.
fn why_positive(quantity: Quantity, value: f64) -> &'static str {
    match quantity {
        _ if value > 0.0 => "",
        Quantity::Friction => " (the fit weighs residuals relative to μ and needs μ > 0)",
        Quantity::Sigma => " (a standard deviation of zero would give the point infinite weight)",
        _ => "",
    }
}
