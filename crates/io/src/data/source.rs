//! Where the rows of a measured-data file come from — a text file with its
//! delimiter, or a workbook's sheet — and so how its places are named in
//! messages ([`crate::error::RowRef`], [`crate::error::CellRef`]) and
//! whether `0,5` is a number (docs/ARCHITECTURE.md, "Contract", "Measured
//! data": decimal commas with `;` or tab, and in workbooks).

use crate::error::{CellRef, RowRef, RowsRef};

/// Where the rows come from.
pub(super) enum Source {
    /// A text file, its columns separated by `delimiter`.
    Text { delimiter: char },
    /// The sheet `name` of a workbook.
    Sheet { name: String },
}

impl Source {
    /// The sheet's name (`None` for a text file).
    fn sheet(&self) -> Option<String> {
        match self {
            Source::Text { .. } => None,
            Source::Sheet { name } => Some(name.clone()),
        }
    }

    /// Line or row `number`.
    pub fn row(&self, number: u64) -> RowRef {
        RowRef {
            sheet: self.sheet(),
            number,
        }
    }

    /// The cell of row `number`, column `column` (from 0).
    pub fn cell(&self, number: u64, column: usize) -> CellRef {
        CellRef {
            row: self.row(number),
            column,
        }
    }

    /// Several lines or rows.
    pub fn rows(&self, numbers: &[u64]) -> RowsRef {
        RowsRef {
            sheet: self.sheet(),
            numbers: numbers.to_vec(),
        }
    }

    /// The delimiter of a text file.
    pub fn delimiter(&self) -> Option<char> {
        match self {
            Source::Text { delimiter } => Some(*delimiter),
            Source::Sheet { .. } => None,
        }
    }

    /// What a row is called: "line" or "row".
    pub fn row_word(&self) -> &'static str {
        match self {
            Source::Text { .. } => "line",
            Source::Sheet { .. } => "row",
        }
    }

    /// Whether `0,5` is a number: not with a comma between the columns.
    pub fn decimal_comma(&self) -> bool {
        match self {
            Source::Text { delimiter } => decimal_comma(*delimiter),
            Source::Sheet { .. } => true,
        }
    }
}

/// Whether a number may have a decimal comma with this delimiter between
/// the cells: not when the comma itself separates them.
pub(crate) fn decimal_comma(delimiter: char) -> bool {
    delimiter != ','
}
