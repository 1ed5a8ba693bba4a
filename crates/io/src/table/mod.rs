//! Modulus tables: a measured master curve of Young's modulus, the
//! material of a scene's `model = "table"` (docs/ARCHITECTURE.md,
//! "Contract", "Scene file": "A table file is any DMA file form holding one
//! temperature").
//!
//! Plain form (`plain.rs`): a CSV with a header row, then one row per
//! frequency. Columns: a frequency, either `omega` (rad/s) or `f` (Hz), and
//! `E_storage`, `E_loss` (Pa). Other columns (e.g. `tan_delta` in a
//! `modulus.csv` written by `rollfit fit`) are ignored. Lines starting with
//! `#` are comments. Frequencies must be positive and strictly increasing,
//! moduli positive: the model interpolates in log–log, where zero and
//! negative values have no place.
//!
//! Every other form the DMA reader accepts ([`crate::dma`]) is read by it
//! (`dma_form.rs`), so that the formats are defined once: shear columns
//! `G_storage`, `G_loss` (E = 2(1+ν)G with the scene's ν), unit-suffixed
//! names (`omega_rad_s`, `f_Hz`, `G_storage_kPa`, `E_loss_MPa`, `T_C`,
//! `T_K`), a temperature column, and the TA TRIOS LIMS text export. The
//! header decides: a UTF-8 CSV whose header has `omega` or `f`,
//! `E_storage` and `E_loss` and no temperature column (`T`, `T_C`, `T_K`)
//! is a plain table; anything else goes to the DMA reader (which decodes
//! Latin-1 and UTF-16 exports too). From there:
//! - a table is one master curve: a file with several temperatures
//!   (isotherms within 0.5 K) is refused, naming them; one temperature
//!   is read as the master curve at that temperature;
//! - rows are sorted by frequency (sweeps often run downwards), and a
//!   frequency given twice is refused, naming both lines;
//! - a point with E″ ≤ 0 is dropped (not refused), named in
//!   [`ModulusTable::notes`] with its line.
//!
//! The model checks the same things again; checking here as well is what
//! lets an error name the line of the file.
//! [`explain_contact_map`] turns the model's contact-map error into the
//! table lines that cause it. Column names come from
//! [`crate::fit_dir::columns`] and [`crate::columns`], where their writers
//! take them.

mod contact_map;
mod dma_form;
mod plain;
mod storage_rise;

use std::path::Path;

use crate::columns::{F, G_LOSS, G_STORAGE, OMEGA_MEASURED};
use crate::dma::ModulusKind;
use crate::error::IoError;
use crate::fit_dir::columns::{E_LOSS, E_STORAGE, OMEGA, T};
use crate::text_file::{Encodings, decode};

pub use contact_map::explain_contact_map;
pub use plain::parse;

/// A master curve as read: angular frequency (rad/s), storage and loss
/// Young's moduli (Pa), in increasing frequency.
#[derive(Debug, Clone, PartialEq)]
pub struct ModulusTable {
    /// Angular frequencies ω, rad/s, strictly increasing.
    pub omega: Vec<f64>,
    /// Storage modulus E′(ω), Pa.
    pub storage: Vec<f64>,
    /// Loss modulus E″(ω), Pa.
    pub loss: Vec<f64>,
    /// The file line (from 1) of each row, for messages.
    pub lines: Vec<usize>,
    /// How the file was read where that is worth saying (shear moduli
    /// converted with ν, the one temperature of the file) and what was
    /// left out (points with E″ ≤ 0, with their lines): the DMA reader's
    /// notes and warnings, each naming the file. Empty for a plain table.
    pub notes: Vec<String>,
}

/// Reads and checks the modulus table at `path`, in any form described in
/// the module documentation; errors name the file (and the line where
/// there is one). `poisson` (the scene's `[substrate] poisson`) converts
/// shear moduli and is used only for them; `kind` overrides the shear or
/// tensile decision for a TRIOS export (a CSV says it with its column
/// names).
pub fn read(path: &Path, poisson: f64, kind: Option<ModulusKind>) -> Result<ModulusTable, IoError> {
    read_sheet(path, poisson, kind, None)
}

/// [`read`], with the sheet of a workbook to read (`None`: the first); a
/// workbook is the DMA reader's.
pub fn read_sheet(
    path: &Path,
    poisson: f64,
    kind: Option<ModulusKind>,
    sheet: Option<&str>,
) -> Result<ModulusTable, IoError> {
    let table = read_form(path, poisson, kind, sheet)?;
    storage_rise::check(path, &table)?;
    Ok(table)
}

/// The table at `path` in its form (the module doc), before the checks
/// every form shares.
fn read_form(
    path: &Path,
    poisson: f64,
    kind: Option<ModulusKind>,
    sheet: Option<&str>,
) -> Result<ModulusTable, IoError> {
    let bytes = crate::input_file::read_input(path, "modulus table", |source| {
        err!("cannot read modulus table {}", path.display()).system(source)
    })?;
    if sheet.is_some() || crate::data::workbook::is_workbook(path, &bytes) {
        return dma_form::read(path, poisson, kind, sheet, false);
    }
    // Text that is not UTF-8 (a Latin-1 or UTF-16 export) is the DMA
    // reader's: it reads all the encodings, with notes.
    let decoded = decode(bytes, Encodings::Utf8).ok();
    let text = decoded.as_ref().map(|read| read.text.as_str());
    if let Some(text) = text
        && is_plain(text)
    {
        return parse(text).map_err(|e| {
            err!("modulus table {}", path.display())
                .in_file(path)
                .caused_by(e)
        });
    }
    // master.csv of `rollfit master`: every DMA point moved to the
    // reference, the isotherm of each in `T`, scattered where isotherms
    // overlap. Its smooth curve is modulus.csv beside it.
    let shifted_points = text
        .and_then(header_names)
        .is_some_and(|h| h.iter().any(|n| n == OMEGA_MEASURED));
    dma_form::read(path, poisson, kind, None, shifted_points)
}

/// Column names the DMA reader reads and the plain reader does not (see
/// [`crate::dma::csv_form`]): shear moduli, a temperature, and
/// unit-suffixed spellings, including the contradictory `omega_Hz` and
/// `f_rad_s` it refuses with a message saying why.
fn is_dma_column(name: &str) -> bool {
    const MODULI: [&str; 4] = [E_STORAGE, E_LOSS, G_STORAGE, G_LOSS];
    const PA: [&str; 4] = ["Pa", "kPa", "MPa", "GPa"];
    let suffixed = |base: &str, units: &[&str]| {
        name.strip_prefix(base)
            .and_then(|rest| rest.strip_prefix('_'))
            .is_some_and(|unit| units.contains(&unit))
    };
    name == G_STORAGE
        || name == G_LOSS
        || name == T
        || MODULI.iter().any(|base| suffixed(base, &PA))
        || suffixed(OMEGA, &["rad_s", "Hz"])
        || suffixed(F, &["Hz", "rad_s"])
        || suffixed(T, &["C", "K"])
}

/// The header row of the CSV `text` (comments skipped), or `None` when
/// there is none to read.
fn header_names(text: &str) -> Option<Vec<String>> {
    let mut reader = crate::csv_columns::reader(text, true, false);
    let header = reader.headers().ok()?;
    Some(header.iter().map(str::to_string).collect())
}

/// Whether `text` is for the plain reader: its header names a plain column
/// (`omega`, `f`, `E_storage`, `E_loss`) and none that only the DMA reader
/// reads (so that a plain table with a column missing or misspelt gets the
/// plain reader's message). A text without a header is the plain reader's
/// to refuse, with its message; a TRIOS export's first line names no plain
/// column.
fn is_plain(text: &str) -> bool {
    let Some(header) = header_names(text) else {
        return true;
    };
    let plain = |name: &String| [OMEGA, F, E_STORAGE, E_LOSS].contains(&name.as_str());
    header.iter().all(String::is_empty)
        || (header.iter().any(plain) && !header.iter().any(|h| is_dma_column(h)))
}

#[cfg(test)]
mod tests;
