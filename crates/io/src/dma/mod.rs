//! DMA data: storage and loss moduli measured by dynamic mechanical analysis
//! (or an oscillatory shear rheometer), read from a file as Young's moduli
//! and grouped into isotherms.
//!
//! Three file forms (docs/ARCHITECTURE.md, "Contract", "DMA files"), in
//! two sources of rows:
//! - text, decoded by [`crate::text_file`] (UTF-8, UTF-16 with a
//!   byte-order mark, Latin-1):
//!   - CSV ([`csv_form`]): a frequency column `f` (Hz) or `omega`
//!     (rad/s), storage and loss columns `E_storage`, `E_loss` (Young's) or
//!     `G_storage`, `G_loss` (shear), optional `T` (°C). Unit-suffixed
//!     spellings such as `omega_rad_s`, `f_Hz`, `G_storage_Pa`,
//!     `E_loss_MPa`, `T_C` or `T_K` are read with their unit;
//!   - the TA Instruments TRIOS "LIMS" text export ([`trios`]), which
//!     carries its own units and says (through its variables and
//!     instrument) whether the moduli are shear or tensile;
//! - a workbook (.xlsx, .xlsm, .xlsb, .xls, .ods, told by its extension or
//!   first bytes; `sheet.rs`): the first sheet or the one named, with the
//!   CSV's column names or an instrument's (`f` [Hz], `T` [°C], `E'`, `E''`
//!   [MPa], `G'`, `G''`: the Netzsch/GABO Eplexor "Excel Export", a names
//!   row and a units row below title rows).
//!
//! CSV and workbook rows meet in one column recognition (`header.rs`):
//! every name and unit is defined once, for both. Shear moduli become Young's moduli with the fit's Poisson's
//! ratio ν, frequency-independent as everywhere in rollfit:
//!
//! E*(ω) = 2 (1 + ν) G*(ω),
//!
//! so E′ = 2(1+ν) G′, E″ = 2(1+ν) G″ and tan δ is unchanged.
//!
//! Points at several temperatures are grouped into isotherms
//! ([`isotherm`]: by a step column, else by gaps over 1 K between their
//! temperatures, never into one spanning more than 2 K); moving them to a fit's reference state is the report
//! crate's (`rollfit_report::dma_shift`), building a master curve of them
//! the fit crate's (`rollfit_fit::master`).
//!
//! What is checked when reading (`checks.rs`): the file is whole and in one
//! encoding (a cut-off or damaged file is refused with its line, see
//! [`csv_form`] and [`trios`]), ω > 0, E′ > 0, every number finite. A
//! point with E″ ≤ 0 is dropped with a warning naming its line and column
//! rather than refusing the whole file: a negative loss modulus is not
//! physical (E″ ≥ 0 for a passive solid), and real exports carry one now
//! and then where the loss angle is below the instrument's phase
//! resolution (the 468MP adhesive's coldest point, glassy, reads
//! E″ = −30 MPa against E′ = 550 MPa); every metric compares logarithms or
//! ratios of E″, which a zero or negative E″ has none of.
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley 1980,
//!   Ch. 1 (E = 2(1+ν)G) and Ch. 11 (reduced variables).
//! - TA Instruments, *TRIOS Software: Export to LIMS*, the "LIMS" text
//!   export format (sections, `Variables`/`Units` lines, `Data point`
//!   rows).

use std::path::{Path, PathBuf};

use crate::error::IoError;

mod blocks;
mod checks;
pub mod csv_form;
pub mod files;
mod form;
mod header;
pub mod isotherms;
mod moduli;
mod point;
pub mod relaxation;
mod sheet;
pub mod stated_temperature;
pub mod time_files;
mod time_isotherms;
pub mod trios;
mod vocabulary;

use rollfit_fit::master::grouping::{Grouping, group, group_steps};

use crate::data::workbook::is_workbook;
pub use files::{DmaFile, DmaInput, TemperatureOrigin, read_files};
use form::{FormRead, Place};
pub use header::modulus_unit;
pub use isotherms::{DmaIsotherms, group_isotherms, master_refused};
pub use point::{DmaOptions, DmaPoint, DmaWlf, ModulusKind, WLF_USAGE};

/// A DMA file read, its moduli as Young's moduli in Pa.
#[derive(Debug, Clone)]
pub struct DmaData {
    /// The file; of several files, the folder holding them.
    pub path: PathBuf,
    /// The points in file order, as measured.
    pub points: Vec<DmaPoint>,
    /// The file line (from 1) of each entry of `points`, same order: for
    /// messages about a point. In a workbook, the row of the sheet.
    pub lines: Vec<usize>,
    /// The step (set, segment) of each point, numbered from 0 in order of
    /// appearance, when the file has a step column with a label for every
    /// point: it groups the isotherms ([`DmaData::grouping`]).
    pub steps: Option<Vec<u32>>,
    /// The sheet read, for a workbook (`None`: a text file).
    pub sheet: Option<String>,
    /// What the file held (before conversion to Young's).
    pub kind: ModulusKind,
    /// "csv", "rheocompass", "trios-lims" or "workbook" ("mixed" of
    /// several files).
    pub format: &'static str,
    /// Points dropped, columns or steps skipped, and how the file was
    /// read where that was a decision (shear or tensile, ν).
    pub warnings: Vec<String>,
    /// How the file was read where the file itself said so (a CSV's shear
    /// columns converted with ν): worth knowing, nothing to check.
    pub notes: Vec<String>,
    /// Each file read, in order: its points and where their temperature
    /// came from.
    pub files: Vec<DmaFile>,
}

impl DmaData {
    /// Reads a DMA file: a workbook (by its extension or first bytes) from
    /// its first sheet, TRIOS LIMS when its first line is `[Version]` or
    /// mentions the LIMS export, CSV otherwise. Shear moduli become
    /// Young's with `poisson` (the fit's ν).
    pub fn read(path: &Path, poisson: f64, options: &DmaOptions) -> Result<DmaData, IoError> {
        DmaData::read_sheet(path, poisson, options, None)
    }

    /// [`DmaData::read`], with the sheet of a workbook to read (`None`:
    /// the first); a sheet named for a text file is an error.
    pub fn read_sheet(
        path: &Path,
        poisson: f64,
        options: &DmaOptions,
        sheet: Option<&str>,
    ) -> Result<DmaData, IoError> {
        // Not the DMA file's fault: said as the number's own.
        rollfit_model::check_poisson(poisson).map_err(|problem| {
            err!(
                "{problem} (converting shear moduli of {} to Young's)",
                path.display()
            )
        })?;
        let (reads, format, sheet, notes) = read_form(path, options, sheet)?;
        let blocks = reads.len() > 1;
        let mut all: Option<DmaData> = None;
        for read in reads {
            let data = DmaData::of_form(path, read, (format, &sheet), poisson, blocks)?;
            all = Some(match all {
                None => data,
                Some(so_far) => files::join(so_far, data),
            });
        }
        let mut data = all.ok_or_else(|| err!("{}: no data points", path.display()))?;
        data.notes.splice(0..0, notes);
        Ok(data)
    }

    /// The data of one form read (a file, or one result block of it when
    /// `block`), shear moduli converted with `poisson`.
    fn of_form(
        path: &Path,
        read: FormRead,
        (format, sheet): (&'static str, &Option<String>),
        poisson: f64,
        block: bool,
    ) -> Result<DmaData, IoError> {
        let FormRead {
            points: mut raw,
            kind,
            names,
            mut warnings,
            preamble,
        } = read;
        let mut notes = Vec::new();
        let temperature = stated_temperature(path, &mut raw, &preamble);
        let factor = match kind {
            ModulusKind::Young => 1.0,
            ModulusKind::Shear => {
                let conversion = format!(
                    "{}: shear moduli G′, G″ converted to Young's with E = 2(1+ν)G, ν = {poisson} (the fit's)",
                    path.display()
                );
                // A TRIOS file's kind was inferred (a warning); a CSV's
                // or a sheet's column names state it (a note).
                if format == "trios-lims" {
                    warnings.push(conversion);
                } else {
                    notes.push(conversion);
                }
                2.0 * (1.0 + poisson)
            }
        };
        let place = Place {
            path,
            sheet: sheet.as_deref(),
        };
        let (points, lines, steps) =
            checks::check_points(&place, raw, &names, factor, &mut warnings)?;
        let files = vec![DmaFile {
            path: path.to_path_buf(),
            points: 0..points.len(),
            temperature,
            block: block.then(|| preamble.first().map_or(0, |(line, _)| *line)),
        }];
        Ok(DmaData {
            path: path.to_path_buf(),
            files,
            points,
            lines,
            steps,
            sheet: sheet.clone(),
            kind,
            format,
            warnings,
            notes,
        })
    }

    /// The points grouped into isotherms, by step where the file has a
    /// step column, else by the gaps between their temperatures, and the
    /// temperature ramp that formed none, if any (the rule:
    /// [`rollfit_fit::master::grouping`]).
    pub fn grouping(&self) -> Grouping {
        match &self.steps {
            Some(steps) => group_steps(&self.temperatures_of_points(), steps),
            None => group(self.points.iter().map(|p| p.temperature)),
        }
    }

    /// The temperature of each point (°C), in file order.
    pub fn temperatures_of_points(&self) -> Vec<Option<f64>> {
        self.points.iter().map(|p| p.temperature).collect()
    }

    /// The file the point `index` of [`DmaData::points`] was read from.
    pub fn file_of(&self, index: usize) -> &Path {
        self.source_of(index)
            .map_or(self.path.as_path(), |f| f.path.as_path())
    }

    /// The file, or result block, the point `index` was read from.
    pub fn source_of(&self, index: usize) -> Option<&DmaFile> {
        self.files.iter().find(|f| f.points.contains(&index))
    }

    /// The isotherms' temperatures (°C, ascending; see
    /// [`DmaData::grouping`]).
    pub fn temperatures(&self) -> Vec<f64> {
        self.grouping()
            .isotherms
            .iter()
            .map(|i| i.temperature)
            .collect()
    }
}

/// Where the temperature of the points `raw` comes from: their T column,
/// else a line of `preamble` or the file's name that states one, which is
/// then given to every point (the module doc of [`files`]).
fn stated_temperature(
    path: &Path,
    raw: &mut [form::RawPoint],
    preamble: &[(usize, String)],
) -> TemperatureOrigin {
    if raw.iter().any(|p| p.temperature.is_some()) {
        return TemperatureOrigin::Column;
    }
    let lines = preamble.iter().map(|(n, l)| (*n, l.as_str()));
    let (origin, t) = match stated_temperature::in_lines(lines) {
        Some((line, t)) => (TemperatureOrigin::Line(line, t), t),
        None => match stated_temperature::in_file_name(path) {
            Some(t) => (TemperatureOrigin::FileName(t), t),
            None => return TemperatureOrigin::None,
        },
    };
    for p in raw {
        p.temperature = Some(t);
    }
    origin
}

/// What the options tell the column recognition.
fn told(options: &DmaOptions) -> header::Told {
    header::Told {
        kind: options.kind,
        modulus_unit: options.modulus_unit,
    }
}

/// What the file's form reads: the points (of each result block, for a
/// RheoCompass export), the form's name, the sheet read (a workbook's)
/// and the notes of reading it.
type Form = (Vec<FormRead>, &'static str, Option<String>, Vec<String>);

/// Reads `path` in its form: a workbook's sheet `sheet`, else decoded
/// text as TRIOS LIMS or CSV.
fn read_form(path: &Path, options: &DmaOptions, sheet: Option<&str>) -> Result<Form, IoError> {
    let bytes = crate::input_file::read_input(path, "DMA file", |source| {
        err!("{}: {source}", path.display()).system(source)
    })?;
    let (mut reads, format, sheet, notes) = if is_workbook(path, &bytes) {
        let (read, name, notes) = sheet::parse(path, bytes, sheet, told(options))?;
        (vec![read], "workbook", Some(name), notes)
    } else if let Some(sheet) = sheet {
        return Err(err!(
            "{}: a sheet ({sheet:?}) was given, but the DMA file is text, not a workbook (.xlsx, \
         .xlsm, .xlsb, .xls, .ods)",
            path.display(),
        ));
    } else {
        let crate::text_file::Text {
            text,
            notes: decoded,
        } = crate::text_file::decode_file(path, bytes)?;
        if trios::is_lims(&text) {
            let read = trios::parse(path, &text, options)?;
            return Ok((vec![read], "trios-lims", None, decoded));
        }
        let mut notes = decoded;
        match blocks::result_blocks(&text) {
            Some(blocks) => {
                notes.push(format!(
                    "{}: an Anton Paar RheoCompass export of {} result block(s): each one isotherm",
                    path.display(),
                    blocks.len()
                ));
                let mut reads = Vec::with_capacity(blocks.len());
                for block in &blocks {
                    let (read, said) = csv_form::parse(path, block, told(options))?;
                    for note in said {
                        if !notes.contains(&note) {
                            notes.push(note);
                        }
                    }
                    reads.push(read);
                }
                (reads, "rheocompass", None, notes)
            }
            None => {
                let (read, said) = csv_form::parse(path, &text, told(options))?;
                notes.extend(said);
                (vec![read], "csv", None, notes)
            }
        }
    };
    for read in &mut reads {
        if options.kind.is_some_and(|k| k != read.kind) {
            read.warnings.push(format!(
                "{}: the column names say {} moduli; the requested modulus kind applies where they do not and is ignored",
                path.display(),
                read.kind.name()
            ));
        }
    }
    Ok((reads, format, sheet, notes))
}
