//! The errors of a modulus table, the material of a scene's
//! `model = "table"` ([`TableError`], reached as [`super::IoError::Table`];
//! docs/ARCHITECTURE.md, "Contract", "Scene file"). Messages start with
//! `modulus table PATH` and speak the scene's words: `[substrate] poisson`
//! and `[material] modulus` where the DMA reader, serving `rollfit
//! compare`, says "the fit's" ν and `--dma-modulus` ([`in_scene_words`]).
//! The causes a plain table's reader finds name no file:
//! [`TableError::Plain`] does, and `{:#}` prints it first.

use std::path::PathBuf;

use thiserror::Error;

use super::IoError;
use crate::columns::{F, OMEGA_MEASURED};
use crate::fit_dir::columns::{E_LOSS, E_STORAGE, OMEGA};

/// One temperature of a table that holds several: its (mean) temperature,
/// points and first and last line.
#[derive(Debug, Clone, PartialEq)]
pub struct TableIsotherm {
    /// °C.
    pub temperature: f64,
    /// Points at it.
    pub points: usize,
    /// The first and last file line of its points.
    pub lines: (usize, usize),
}

/// Why a modulus table cannot be read.
#[derive(Debug, Error)]
pub enum TableError {
    // ------------------------------------------------------------ the file
    /// The file could not be read.
    #[error("cannot read modulus table {}", path.display())]
    Read {
        path: PathBuf,
        source: std::io::Error,
    },
    /// A plain table (`omega` or `f`, `E_storage`, `E_loss`) refused: the
    /// source says why (a cause below, or a CSV error of
    /// [`crate::csv_columns`]).
    #[error("modulus table {}", path.display())]
    Plain { path: PathBuf, source: Box<IoError> },
    /// Another DMA form refused by the DMA reader: its message (which
    /// names the file and line), in the scene's words; shown, not a
    /// source, as the message always had it.
    #[error("modulus table {}", in_scene_words(&error.to_string()))]
    Dma { error: Box<IoError> },
    /// Shear moduli and a Poisson's ratio that cannot convert them.
    #[error(
        "modulus table {}: holds shear moduli G′, G″; converting them to Young's moduli \
         (E = 2(1+ν)G) needs [substrate] poisson in [0, 0.5], not {poisson}",
        path.display()
    )]
    ShearWithoutPoisson { path: PathBuf, poisson: f64 },
    /// Points at several temperatures: not one master curve.
    #[error(
        "modulus table {}: {} temperatures: {}; a table is one master curve at one temperature. \
         {}",
        path.display(),
        isotherms.len(),
        list_isotherms(isotherms),
        advice(path, *shifted_points)
    )]
    SeveralTemperatures {
        path: PathBuf,
        /// In increasing temperature.
        isotherms: Vec<TableIsotherm>,
        /// The file has the column of master.csv's shifted points.
        shifted_points: bool,
    },
    /// One frequency twice (after sorting the DMA points).
    #[error(
        "modulus table {}, lines {} and {}: the same frequency ω = {omega} rad/s twice; a master \
         curve has one modulus per frequency: remove or average the repeated rows",
        path.display(),
        lines.0,
        lines.1
    )]
    RepeatedFrequency {
        path: PathBuf,
        /// The two lines, the first first.
        lines: (usize, usize),
        /// rad/s.
        omega: f64,
    },
    /// E′ falling with ω beyond scatter (table/storage_rise.rs).
    #[error(
        "modulus table {}, line {line}: E_storage = {storage:.4e} Pa at ω = {omega:.4e} rad/s is \
         {:.0} % below E_storage = {peak_storage:.4e} Pa at line {peak_line} (ω = \
         {peak_omega:.4e} rad/s): the storage modulus of a viscoelastic solid rises with \
         frequency (every relaxation term adds H ω²τ²/(1+ω²τ²)), and a fall of more than 20 % is \
         no measurement scatter; check that the columns are E_storage and E_loss, the \
         frequencies in the unit the header names, and the rows one material at one temperature",
        path.display(),
        100.0 * (1.0 - storage / peak_storage)
    )]
    StorageFalls {
        path: PathBuf,
        /// The row refused: its line, ω (rad/s) and E′ (Pa).
        line: usize,
        omega: f64,
        storage: f64,
        /// The row of the largest E′ before it.
        peak_line: usize,
        peak_omega: f64,
        peak_storage: f64,
    },
    /// Fewer than two points left from a DMA form.
    #[error(
        "modulus table {}: the table has {rows} usable data row(s): at least two frequencies \
         are needed to interpolate",
        path.display()
    )]
    TooFewPoints { path: PathBuf, rows: usize },

    // ------------------------------------------------------------ plain
    /// Both `omega` and `f`.
    #[error("the header has both `{OMEGA}` (rad/s) and `{F}` (Hz): keep one frequency column")]
    BothFrequencies,
    /// Neither `omega` nor `f`.
    #[error(
        "the header has no frequency column: expected `{OMEGA}` (rad/s) or `{F}` (Hz), found {}",
        backquoted(header)
    )]
    NoFrequency { header: Vec<String> },
    /// A modulus column missing; `shear`: the header has `G_` columns.
    #[error(
        "the header has no `{name}` column{}",
        if *shear {
            format!(
                ": a material table holds Young's moduli {E_STORAGE}, {E_LOSS} (Pa); convert \
                 shear moduli with E = 2(1 + ν) G"
            )
        } else {
            format!(" (Pa); found {}", backquoted(header))
        }
    )]
    NoModulus {
        /// `E_storage` or `E_loss`.
        name: &'static str,
        shear: bool,
        header: Vec<String>,
    },
    /// A row the csv crate cannot read.
    #[error("malformed row")]
    MalformedRow { source: csv::Error },
    /// A value ≤ 0.
    #[error(
        "line {line}: column `{column}` = {value}: must be greater than zero (the table is \
         interpolated in log-log)"
    )]
    NotPositive {
        line: u64,
        column: String,
        value: f64,
    },
    /// A modulus above 1e13 Pa.
    #[error(
        "line {line}: column `{column}` = {value:e}: above 1e13 Pa, stiffer than any solid \
         (diamond: about 1.2e12 Pa); is the column in Pa?"
    )]
    ModulusTooLarge {
        line: u64,
        column: String,
        value: f64,
    },
    /// ω outside 1e-30 … 1e30 rad/s (`value` as in the file, Hz for `f`).
    #[error(
        "line {line}: frequency {column} = {value:e}: outside 1e-30 … 1e30 rad/s, beyond any \
         master curve"
    )]
    FrequencyOutOfRange {
        line: u64,
        column: String,
        value: f64,
    },
    /// A frequency not above the previous row's.
    #[error(
        "line {line}: frequency {column} = {value} does not exceed the one on line {previous}: \
         rows must be in strictly increasing frequency"
    )]
    NotIncreasing {
        line: u64,
        column: String,
        value: f64,
        /// The previous row's line.
        previous: u64,
    },
    /// Fewer than two rows.
    #[error("the table has {rows} data row(s): at least two frequencies are needed to interpolate")]
    TooFewRows { rows: usize },
}

impl From<TableError> for IoError {
    fn from(e: TableError) -> Self {
        IoError::transparent(super::ErrorKind::Content, e)
    }
}

/// A message of the DMA reader in the words of a scene file: the DMA
/// reader serves `rollfit compare` and `report`, where ν is the fit's and
/// the modulus kind a command-line flag; here they are `[substrate]
/// poisson` and `[material] modulus`. (A rewording the DMA reader's text
/// no longer matches is left as it is: still true, in the other words.)
pub(crate) fn in_scene_words(message: &str) -> String {
    message
        .replace("(the fit's)", "([substrate] poisson)")
        .replace("--dma-modulus shear", "[material] modulus = \"shear\"")
        .replace("--dma-modulus young", "[material] modulus = \"young\"")
}

/// A temperature as a message shows it: to 0.1 K (an isotherm's mean,
/// within a controller's scatter), without trailing zeros.
pub(crate) fn celsius(t: f64) -> String {
    // + 0.0: −0.02 °C shows as 0, not −0.
    format!("{} °C", (t * 10.0).round() / 10.0 + 0.0)
}

/// With a few isotherms each with its points and lines; a whole
/// temperature programme by its temperatures.
fn list_isotherms(isotherms: &[TableIsotherm]) -> String {
    let listed: Vec<String> = if isotherms.len() <= 6 {
        isotherms
            .iter()
            .map(|i| {
                format!(
                    "{} ({} point(s), lines {}–{})",
                    celsius(i.temperature),
                    i.points,
                    i.lines.0,
                    i.lines.1
                )
            })
            .collect()
    } else {
        isotherms.iter().map(|i| celsius(i.temperature)).collect()
    };
    listed.join(", ")
}

/// What to do with a table of several temperatures.
fn advice(path: &std::path::Path, shifted_points: bool) -> String {
    if shifted_points {
        format!(
            "This looks like the master.csv of `rollfit master` (column {OMEGA_MEASURED}): its \
             points scatter where the isotherms overlap; give the smooth master curve beside it, \
             modulus.csv, as the table instead"
        )
    } else {
        format!(
            "Use [material] model = \"dma\", file = \"…\" to shift the isotherms into a master \
             curve, or build one with `rollfit master {}`",
            path.display()
        )
    }
}

/// `` `a`, `b` `` (as [`crate::csv_columns::list`]).
fn backquoted(header: &[String]) -> String {
    let names: Vec<String> = header.iter().map(|h| format!("`{h}`")).collect();
    names.join(", ")
}
