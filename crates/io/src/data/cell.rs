//! The cells of measured data (docs/ARCHITECTURE.md, "Contract", "Measured
//! data"): text or a workbook's value; what counts as no value (empty,
//! `NaN`, `NA`, `n/a`, `null`, `-`, a spreadsheet error such as `#N/A` or
//! `#DIV/0!`), which skips the row; `#` comments (but not a line starting
//! with `#N/A`); and a cell read as a number, with a decimal comma where
//! the file allows one (not in a comma-delimited file; never with a
//! thousands separator).

use super::source::Source;
use crate::error::{CellRef, ColumnName, IoError};

/// One cell of a row.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Cell {
    Empty,
    /// Text as written, trimmed (never empty).
    Text(String),
    /// A number of a workbook cell.
    Number(f64),
    /// A workbook's error value, as Excel shows it (`#DIV/0!`, `#N/A`):
    /// no value.
    Error(String),
    /// A workbook formula whose result the file does not hold (a file
    /// written by a program that does not compute, e.g. openpyxl), as
    /// written without its `=`: a value the user means, that cannot be read.
    Formula(String),
    /// Something else of a workbook (a boolean, a date), described.
    Other(String),
}

impl Cell {
    /// The cell of `text`, trimmed.
    pub fn text(text: &str) -> Cell {
        let text = text.trim();
        if text.is_empty() {
            Cell::Empty
        } else {
            Cell::Text(text.to_string())
        }
    }

    pub fn is_empty(&self) -> bool {
        *self == Cell::Empty
    }

    /// The cell as a header name.
    pub fn name(&self) -> String {
        match self {
            Cell::Text(t) => t.clone(),
            Cell::Number(x) => x.to_string(),
            Cell::Empty | Cell::Error(_) | Cell::Formula(_) => String::new(),
            Cell::Other(what) => what.clone(),
        }
    }

    /// Whether the cell holds a number or no value (a data row's cell).
    fn is_numeric(&self) -> bool {
        match self {
            Cell::Number(_) | Cell::Error(_) | Cell::Formula(_) => true,
            Cell::Text(t) => no_value(t) || t.replace(',', ".").parse::<f64>().is_ok(),
            Cell::Empty | Cell::Other(_) => false,
        }
    }
}

/// A row of the file (comments and blank lines left out) with its line or
/// row number.
#[derive(Debug, Clone)]
pub(crate) struct Row {
    pub number: u64,
    pub cells: Vec<Cell>,
}

impl Row {
    pub fn is_blank(&self) -> bool {
        self.cells.iter().all(Cell::is_empty)
    }

    /// A row of numbers: data, not a header or a title.
    pub fn is_numeric(&self) -> bool {
        !self.is_blank() && self.cells.iter().all(|c| c.is_empty() || c.is_numeric())
    }

    /// Its non-empty cells as names, for a message.
    pub fn names(&self) -> Vec<String> {
        self.cells
            .iter()
            .filter(|c| !c.is_empty())
            .map(Cell::name)
            .collect()
    }

    /// The number of empty cells at its end.
    pub fn trailing_empty(&self) -> usize {
        self.cells.iter().rev().take_while(|c| c.is_empty()).count()
    }
}

/// A `#` comment or a blank line (a line starting with a spreadsheet error
/// value such as `#N/A` is data).
pub(super) fn is_comment_or_blank(line: &str) -> bool {
    let line = line.trim();
    line.is_empty() || (line.starts_with('#') && !starts_with_error_value(line))
}

const ERROR_VALUES: [&str; 7] = [
    "#n/a", "#div/0!", "#value!", "#ref!", "#name?", "#num!", "#null!",
];

fn starts_with_error_value(text: &str) -> bool {
    let lower = text.to_lowercase();
    ERROR_VALUES.iter().any(|e| lower.starts_with(e))
}

/// A cell that holds no value: NaN, NA, n/a, null, -, a spreadsheet error.
fn no_value(text: &str) -> bool {
    let lower = text.trim().to_lowercase();
    matches!(
        lower.as_str(),
        "nan" | "-nan" | "+nan" | "na" | "n/a" | "n.a." | "null" | "none" | "-" | "--" | "—"
    ) || ERROR_VALUES.contains(&lower.as_str())
}

/// A number read from a cell: its value, its decimal text (for exact
/// powers of ten) and the text shown in messages.
pub(crate) struct Number {
    pub value: f64,
    pub decimal: String,
    pub shown: String,
    /// A decimal comma was read as a point.
    pub comma: bool,
}

/// Why a cell that holds something is not a finite number; each carries
/// the cell's text (or what it is, for a boolean or a date).
pub(crate) enum NotNumber {
    /// A boolean or a date of a workbook.
    Other(String),
    /// A decimal comma where commas separate the columns.
    AmbiguousComma(String),
    /// Two commas, or a comma and a point.
    Thousands(String),
    /// Text that is no number.
    Text(String),
    /// NaN or infinite.
    NotFinite(String),
    /// A formula without a saved result ([`Cell::Formula`]).
    Formula(String),
}

/// The number in `cell`; None for no value (empty, NaN, NA, a spreadsheet
/// error); why not for anything else that is not a finite number. Decimal
/// commas are read when `decimal_comma` allows them. The one reading of a
/// cell for measured data and DMA workbooks alike.
pub(crate) fn parse_number(cell: &Cell, decimal_comma: bool) -> Result<Option<Number>, NotNumber> {
    let (value, decimal, shown) = match cell {
        Cell::Empty | Cell::Error(_) => return Ok(None),
        Cell::Formula(formula) => return Err(NotNumber::Formula(formula.clone())),
        Cell::Other(what) => return Err(NotNumber::Other(what.clone())),
        Cell::Number(x) => (*x, format!("{x:e}"), x.to_string()),
        Cell::Text(text) => {
            if no_value(text) {
                return Ok(None);
            }
            let mut decimal = text.clone();
            if text.contains(',') {
                if !decimal_comma {
                    return Err(NotNumber::AmbiguousComma(text.clone()));
                }
                if text.matches(',').count() > 1 || text.contains('.') {
                    return Err(NotNumber::Thousands(text.clone()));
                }
                decimal = text.replace(',', ".");
            }
            let Ok(value) = decimal.parse::<f64>() else {
                return Err(NotNumber::Text(text.clone()));
            };
            (value, decimal, text.clone())
        }
    };
    if !value.is_finite() {
        return Err(NotNumber::NotFinite(shown));
    }
    let comma = matches!(cell, Cell::Text(t) if *t != decimal);
    Ok(Some(Number {
        value,
        decimal,
        shown,
        comma,
    }))
}

/// The number in `cell` (see [`parse_number`]) for measured data: an error
/// at `at` (the cell and its column) for anything that is not a finite
/// number. Decimal commas are read where `source` allows them, and
/// `decimal_commas` is set when one was.
pub(super) fn number(
    cell: &Cell,
    source: &Source,
    decimal_commas: &mut bool,
    at: &dyn Fn() -> (CellRef, ColumnName),
) -> Result<Option<Number>, IoError> {
    let number = parse_number(cell, source.decimal_comma()).map_err(|problem| {
        let (cell, column) = at();
        match problem {
            NotNumber::Other(what) => err!("{cell}: column {column}: {what} is not a number"),
            NotNumber::AmbiguousComma(text) => {
                err!("{cell}: column {column}: {text:?}: a decimal comma in a comma-delimited file is \
         ambiguous; export with ';' as the delimiter, or with decimal points")
            }
            NotNumber::Thousands(text) => err!("{cell}: column {column}: {text:?} is not a number (thousands separators are not \
         understood)"),
            NotNumber::Text(text) => err!("{cell}: column {column}: {text:?} is not a number"),
            NotNumber::NotFinite(text) => err!("{cell}: column {column}: {text:?} is not a finite number"),
            NotNumber::Formula(formula) => err!("{cell}: column {column}: the cell holds a formula (={formula}) the file saved no result \
         for; open it in Excel or LibreOffice and save, so its value is stored"),
        }
    })?;
    if number.as_ref().is_some_and(|n| n.comma) {
        *decimal_commas = true;
    }
    Ok(number)
}
