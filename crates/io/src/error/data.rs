//! How the messages of the measured-data and DMA readers name a place
//! and a column: a text file's line or a workbook's sheet, row and cell
//! ([`RowRef`], [`CellRef`], [`RowsRef`]), a column as its header names it
//! ([`ColumnName`]), and the lists and reasons those messages share.

use std::fmt;

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
pub(crate) fn column_of(row: &RowRef, index: usize) -> String {
    match row.sheet {
        None => format!("column {}", index + 1),
        Some(_) => format!("column {}", column_letter(index)),
    }
}

/// `"a", "b"`.
pub(crate) fn quoted_list(items: &[String]) -> String {
    let quoted: Vec<String> = items.iter().map(|i| format!("{i:?}")).collect();
    quoted.join(", ")
}

/// `no speed column (…) and no friction column (…)`.
pub(crate) fn missing_columns(missing: &[Quantity]) -> String {
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
pub(crate) fn why_positive(quantity: Quantity, value: f64) -> &'static str {
    match quantity {
        _ if value > 0.0 => "",
        Quantity::Friction => " (the fit weighs residuals relative to μ and needs μ > 0)",
        Quantity::Sigma => " (a standard deviation of zero would give the point infinite weight)",
        _ => "",
    }
}
