//! The errors of a DMA file that is a workbook ([`DmaSheetError`],
//! reached as [`super::IoError::DmaSheet`]): the sheets and their header
//! rows (docs/ARCHITECTURE.md, "Contract", "DMA files"). The causes inside
//! a sheet that the CSV form shares — a cell that is no number, a value
//! out of range, a unit not known — are [`super::IoError`]'s own, with the
//! sheet and cell as their place.

use std::path::PathBuf;

use thiserror::Error;

use super::{CellRef, ColumnRef, DataError};

/// Why a workbook DMA file cannot be read, beyond its cells.
#[derive(Debug, Error)]
pub enum DmaSheetError {
    /// A workbook without a header row naming DMA columns on the sheet
    /// read; lists the header cells found on every sheet.
    #[error(
        "{}: sheet {sheet:?}: no header row naming a frequency (f [Hz], omega [rad/s]), a storage \
         and a loss modulus (E', E'' or E_storage, E_loss; shear G', G'' or G_storage, G_loss), \
         each with its unit in the name or in a units row below; {}",
        path.display(),
        sheets_found(found)
    )]
    NoColumns {
        path: PathBuf,
        /// The sheet read.
        sheet: String,
        /// Every sheet's name and the cells of its most header-like row.
        found: Vec<(String, Vec<String>)>,
    },
    /// A formula without a saved result in a column read (the measured
    /// data's [`DataError::FormulaWithoutValue`]).
    #[error(
        "{}, {cell}: {column}: the cell holds a formula (={formula}) the file saved no result \
         for; open it in Excel or LibreOffice and save, so its value is stored",
        path.display()
    )]
    FormulaWithoutValue {
        path: PathBuf,
        cell: Box<CellRef>,
        column: ColumnRef,
        /// As written, without its `=`.
        formula: String,
    },
    /// A workbook whose sheets cannot be read: not a workbook, no such
    /// sheet. The measured-data reader's message, shown (not a source:
    /// `rollfit master` and a scene show a DMA error's text alone).
    #[error("{}: {error}", path.display())]
    Workbook {
        path: PathBuf,
        error: Box<DataError>,
    },
    /// A sheet named for a DMA file that is text.
    #[error(
        "{}: a sheet ({sheet:?}) was given, but the DMA file is text, not a workbook (.xlsx, \
         .xlsm, .xlsb, .xls, .ods)",
        path.display()
    )]
    SheetOfText { path: PathBuf, sheet: String },
}

impl From<DmaSheetError> for super::IoError {
    fn from(e: DmaSheetError) -> Self {
        super::IoError::transparent(super::ErrorKind::Content, e)
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
