//! What a form's reader ([`super::csv_form`], [`super::trios`]) hands to the
//! checks every form shares ([`super::checks`]).

use super::point::ModulusKind;
use crate::error::{CellRef, ColumnRef, RowRef, column_letter};

/// One point as a reader found it, before the checks common to all forms.
pub(crate) struct RawPoint {
    /// Line in the file, counting from 1.
    pub line: usize,
    /// rad/s.
    pub omega: f64,
    /// Pa, shear or Young's as the file says.
    pub storage: f64,
    /// Pa.
    pub loss: f64,
    /// °C.
    pub temperature: Option<f64>,
    /// The step (segment, set) it was measured in, as the file labels it,
    /// when the file has a step column.
    pub step: Option<String>,
}

/// The columns (or variables) of the three moduli fields, for messages.
pub(crate) struct FieldNames {
    pub omega: ColumnRef,
    pub storage: ColumnRef,
    pub loss: ColumnRef,
}

/// What a form's reader found: the points before the common checks.
pub(crate) struct FormRead {
    pub points: Vec<RawPoint>,
    pub kind: ModulusKind,
    pub names: FieldNames,
    pub warnings: Vec<String>,
    /// The lines above the header (number, text): titles and metadata, where
    /// a file may state its temperature.
    pub preamble: Vec<(usize, String)>,
}

/// Where the rows of a DMA table are: the file, and for a workbook the
/// sheet; how messages name a row, a cell and a column there.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Place<'a> {
    pub path: &'a std::path::Path,
    /// The sheet of a workbook (`None`: a text file).
    pub sheet: Option<&'a str>,
}

impl Place<'_> {
    /// `line N` of a text file, `sheet "S", row N` of a workbook.
    pub fn row(&self, number: usize) -> RowRef {
        RowRef {
            sheet: self.sheet.map(str::to_string),
            number: number as u64,
        }
    }

    /// `line N` of a text file, `sheet "S", cell C7` of a workbook.
    pub fn cell(&self, number: usize, column: usize) -> CellRef {
        CellRef {
            row: self.row(number),
            column,
        }
    }

    /// `column 3 (E_storage)` in a text file, `column C (E'')` in a sheet
    /// (`index` from 0).
    pub fn column(&self, index: usize, name: &str) -> ColumnRef {
        match self.sheet {
            None => ColumnRef::numbered(index + 1, name),
            Some(_) => ColumnRef::named(format!("{} ({name})", column_letter(index))),
        }
    }
}
