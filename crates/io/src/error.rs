//! The one error type of the io crate, [`IoError`]: one variant per cause,
//! carrying the file, line, column or key as data; internal faults
//! ([`Fault`]) apart. Messages are what a user reads after `error: `
//! (docs/ARCHITECTURE.md, "Contract", "Commands"): the file, `, line N`
//! where one line is at fault, what is wrong and, where it helps, what to
//! do. A system error is the [`std::error::Error::source`], which the
//! command line's `{:#}` prints after a colon. Each reader has an enum of
//! its own, reached as one variant of [`IoError`]: measured data
//! ([`DataError`]), modulus tables ([`TableError`]), TRIOS exports
//! ([`TriosError`]), DMA workbooks ([`DmaSheetError`]), the DMA master
//! curve ([`DmaMasterError`]), relaxation files ([`RelaxationError`]),
//! scenes ([`SceneError`]), manifests ([`ManifestError`]), input files
//! ([`InputError`]) and result folders ([`FolderError`]).

use std::path::PathBuf;

use thiserror::Error;

mod boxed;
pub(crate) mod data;
mod fault;
mod folder;
mod input;
pub(crate) mod manifest;
pub(crate) mod master;
mod parts;
pub(crate) mod relaxation;
pub(crate) mod scene;
mod sheet;
pub(crate) mod table;
mod trios;

pub use boxed::{DmaUnknownUnit, DuplicateQuantity, UnknownUnit};
pub use data::{CellRef, ColumnName, DataError, RowRef, RowsRef, column_letter};
pub use fault::Fault;
pub use folder::FolderError;
pub use input::InputError;
pub use manifest::{EntryProblem, EntryRef, ManifestError, TomlPlace};
pub use master::{DmaMasterError, TurnPoint};
pub use parts::{ColumnRef, Contradiction, InvalidText, SkippedStep, StepRef};
use parts::{field_count_tail, found_byte, holders_note, null_expected, place};
pub use relaxation::RelaxationError;
pub use scene::SceneError;
pub use sheet::DmaSheetError;
pub use table::{TableError, TableIsotherm};
pub use trios::TriosError;

/// Everything that can stop reading or writing a rollfit file.
///
/// The fields name the same things throughout: `path` is the file (or
/// folder) the error is about, `line` the line at fault, counting from 1
/// (an `Option` where it is the line of a JSON key, which may not be
/// found), `column` and `step` the column and TRIOS step, `text` a cell as
/// found, `value` a number as found, `header` the header row as found, and
/// `source` what the system or the library named said. The two causes with
/// the most context are boxed ([`DuplicateQuantity`], [`UnknownUnit`]), so
/// that every `Result<_, IoError>` stays small.
#[derive(Debug, Error)]
pub enum IoError {
    // ------------------------------------------------------------ reading
    /// A file could not be read. The system's message is in the text and is
    /// also the source, so `{:#}` shows it twice; kept so, as every message
    /// was kept when the readers moved here.
    #[error("{}: {source}", path.display())]
    Read {
        path: PathBuf,
        source: std::io::Error,
    },
    /// A text input (scene file, manifest) could not be read.
    #[error("cannot read {kind} {}", path.display())]
    ReadText {
        /// What the file is, for the message ("scene file").
        kind: &'static str,
        path: PathBuf,
        source: std::io::Error,
    },
    /// A text input (scene file, manifest) that is not UTF-8.
    #[error(
        "{kind} {}, line {line}: not UTF-8: byte 0x{byte:02X} at byte offset {offset} (byte \
         {byte_in_line} of the line); save the file as UTF-8 text",
        path.display()
    )]
    TextNotUtf8 {
        /// What the file is ("scene file", "manifest").
        kind: &'static str,
        path: PathBuf,
        /// Line of the first invalid byte.
        line: usize,
        /// Its offset in the file, from 0.
        offset: usize,
        /// The byte.
        byte: u8,
        /// Its place in the line, from 1.
        byte_in_line: usize,
    },
    /// Bytes that are not text in the file's encoding: the line, the byte
    /// offset in the file (from 0) and the byte of the line (from 1), so
    /// that a hex editor and a text editor both find it.
    #[error(
        "{}, line {line}: {problem}: {} at byte offset {offset} (byte {byte_in_line} of the line)",
        path.display(),
        found_byte(*found)
    )]
    InvalidText {
        path: PathBuf,
        line: usize,
        /// What is wrong there.
        problem: InvalidText,
        /// The byte found (`None`: the end of the file).
        found: Option<u8>,
        /// Offset in the file, from 0.
        offset: usize,
        /// Place in the line, from 1.
        byte_in_line: usize,
    },
    /// A UTF-16 file (byte-order mark) with an unpaired surrogate.
    #[error(
        "{}, line {line}: not UTF-16 although the file starts with a UTF-16 byte-order mark: \
         unpaired surrogate 0x{unit:04X} at byte offset {offset}",
        path.display()
    )]
    UnpairedSurrogate {
        path: PathBuf,
        line: usize,
        /// The code unit.
        unit: u16,
        /// Its offset in the file.
        offset: usize,
    },
    /// A UTF-16 file (byte-order mark) with an odd number of bytes.
    #[error(
        "{}, line {line}: UTF-16 file (byte-order mark) with an odd number of bytes ({length}): \
         the last character is cut off at byte offset {offset}; the file looks truncated",
        path.display()
    )]
    OddUtf16Length {
        path: PathBuf,
        /// The last line.
        line: usize,
        /// Bytes in the file.
        length: usize,
        /// Offset of the lone last byte.
        offset: usize,
    },

    // ------------------------------------------------------------ CSV tables
    /// A line the csv crate cannot read.
    #[error("{}, line {line}: not CSV: {error}", path.display())]
    NotCsv {
        path: PathBuf,
        line: usize,
        /// What the csv crate said (shown, not a source: the message
        /// always carried it as text).
        error: csv::Error,
    },
    /// A table without a header line.
    #[error("{}: empty: no header line", path.display())]
    NoHeader { path: PathBuf },
    /// A header and no data.
    #[error("{}: no data rows below the header", path.display())]
    NoRows { path: PathBuf },
    /// A row whose number of fields is not the header's.
    #[error(
        "{}, line {line}: {found} fields, but the header has {expected} columns{}",
        path.display(),
        field_count_tail(missing, *cut)
    )]
    FieldCount {
        path: PathBuf,
        line: usize,
        /// Fields in the row.
        found: usize,
        /// Columns in the header.
        expected: usize,
        /// The columns without a value, when the reader names them.
        missing: Vec<ColumnRef>,
        /// The row is the file's last and has no line break: cut off.
        cut: bool,
    },
    /// A cell that is not a number.
    #[error("{}, {cell}: {column}: \"{text}\" is not a number", path.display())]
    NotANumber {
        path: PathBuf,
        /// A text file's line, or a sheet's cell (boxed: the error stays
        /// small).
        cell: Box<CellRef>,
        column: ColumnRef,
        text: String,
    },
    /// A cell that is NaN or infinite.
    #[error("{}, {cell}: {column}: {text} is not a finite number", path.display())]
    NotFinite {
        path: PathBuf,
        /// A text file's line, or a sheet's cell (boxed: the error stays
        /// small).
        cell: Box<CellRef>,
        column: ColumnRef,
        text: String,
    },
    /// A required column is absent.
    #[error("{}: no column `{name}` (the header has: {})", path.display(), header.join(", "))]
    MissingColumn {
        path: PathBuf,
        /// The column required.
        name: &'static str,
        header: Vec<String>,
    },
    /// The csv crate cannot read a header row (the caller names the file).
    #[error("cannot read the header row")]
    CsvHeader {
        /// What the csv crate said.
        source: csv::Error,
    },
    /// A table without a header row (the caller names the file).
    #[error("the table is empty: expected a header row ({expected}) and data rows")]
    EmptyTable {
        /// The columns expected, for the message.
        expected: &'static str,
    },
    /// A header naming one column twice (the caller names the file).
    #[error("the header names column `{name}` twice")]
    DuplicateColumn { name: String },
    /// A cell that is not a finite number (the caller names the file).
    #[error("line {line}: column `{column}`: {text:?} is not a finite number")]
    CellNotFinite {
        /// The line.
        line: u64,
        /// The column's name.
        column: String,
        text: String,
    },

    // ------------------------------------------------------------ fit folder
    /// The folder given is not a folder.
    #[error("{}: not a fit directory (run `rollfit fit SCENE DATA -o DIR` first)", dir.display())]
    NotFitFolder { dir: PathBuf },
    /// fit.json has null where a value is required.
    #[error(
        "{}, line {line}: column {column}: not a rollfit fit.json: `{key}` is null where {}",
        path.display(),
        null_expected(expected)
    )]
    FitJsonNull {
        path: PathBuf,
        line: usize,
        /// Column of the value (bytes, from 1).
        column: usize,
        /// Its key (`model.tau[1]`).
        key: String,
        /// What serde expected ("f64", "usize", "a boolean").
        expected: String,
    },
    /// fit.json has a number JSON cannot hold (NaN, infinity, 1e999).
    #[error(
        "{}, line {line}: column {column}: not a rollfit fit.json: `{key}`: {message}: a number \
         must be finite (JSON has no NaN or infinity)",
        path.display()
    )]
    FitJsonNonFinite {
        path: PathBuf,
        line: usize,
        column: usize,
        key: String,
        /// What serde_json said.
        message: String,
    },
    /// fit.json is not the JSON of a fit (serde's error, with the key).
    #[error(
        "{}, line {line}: column {column}: not a rollfit fit.json: {}{message}",
        path.display(),
        key.as_ref().map_or(String::new(), |k| format!("`{k}`: "))
    )]
    FitJsonDecode {
        path: PathBuf,
        /// Line where serde stopped.
        line: usize,
        /// Column where serde stopped.
        column: usize,
        /// The key there, if inside an object or array.
        key: Option<String>,
        /// What serde_json said (without its position).
        message: String,
    },
    /// Poisson's ratio outside [0, 0.5] (`problem`: shown, not a source).
    #[error("{}: {problem}", place(path, *line))]
    PoissonOutOfRange {
        path: PathBuf,
        line: Option<usize>,
        problem: rollfit_model::PoissonOutOfRange,
    },
    /// WLF C1 ≤ 0.
    #[error("{}: shift.C1 = {value}: the WLF constant C1 must be > 0", place(path, *line))]
    WlfC1NotPositive {
        path: PathBuf,
        line: Option<usize>,
        value: f64,
    },
    /// WLF C2 ≤ 0.
    #[error("{}: shift.C2 = {value}: the WLF constant C2 must be > 0 K", place(path, *line))]
    WlfC2NotPositive {
        path: PathBuf,
        line: Option<usize>,
        value: f64,
    },
    /// A listed temperature at or below the WLF divergence T_ref − C2.
    #[error(
        "{}: shift.log_aT[{index}].T = {temperature} °C: C2 + T − T_ref = {denominator} K is not \
         positive (C2 = {c2} K, T_ref = {t_ref} °C): the WLF shift diverges at T_ref − C2 = {} °C \
         and means nothing below",
        place(path, *line),
        t_ref - c2
    )]
    WlfPole {
        path: PathBuf,
        line: Option<usize>,
        /// Index in `shift.log_aT`.
        index: usize,
        /// °C.
        temperature: f64,
        /// C2 + T − T_ref, K.
        denominator: f64,
        /// K.
        c2: f64,
        /// °C.
        t_ref: f64,
    },
    /// A WLF shift without one of its constants.
    #[error("{}: shift.model = \"wlf\" needs the key shift.{key}", place(path, *line))]
    WlfKeyMissing {
        path: PathBuf,
        /// Line of `shift.model`, when found.
        line: Option<usize>,
        /// "C1" or "C2".
        key: &'static str,
    },
    /// A free shift with a constant of a law.
    #[error(
        "{}: shift.{key} does not belong to shift.model = \"free\" (it takes T_ref and log_aT; a \
         WLF shift is model \"wlf\", an Arrhenius one \"arrhenius\")",
        place(path, *line)
    )]
    FreeShiftWithWlfKey {
        path: PathBuf,
        line: Option<usize>,
        /// "C1", "C2" or "E_a".
        key: &'static str,
    },
    /// An Arrhenius shift without a positive activation energy.
    #[error(
        "{}: shift.model = \"arrhenius\" needs a positive shift.E_a (J/mol){}",
        place(path, *line),
        value.map_or_else(String::new, |v| format!(", got {v}"))
    )]
    ArrheniusEnergy {
        path: PathBuf,
        /// Line of `shift.E_a`, or of `shift.model` when it is missing.
        line: Option<usize>,
        value: Option<f64>,
    },
    /// An Arrhenius shift with a WLF constant.
    #[error(
        "{}: shift.{key} does not belong to shift.model = \"arrhenius\" (it takes T_ref, E_a \
         and log_aT)",
        place(path, *line)
    )]
    ArrheniusWithWlfKey {
        path: PathBuf,
        line: Option<usize>,
        /// "C1" or "C2".
        key: &'static str,
    },
    /// A shift model other than "wlf", "arrhenius" and "free".
    #[error(
        "{}: shift.model = \"{model}\": unknown shift model; allowed: \"wlf\", \"arrhenius\", \
         \"free\"",
        place(path, *line)
    )]
    UnknownShiftModel {
        path: PathBuf,
        /// Line of `shift.model`, when found.
        line: Option<usize>,
        model: String,
    },
    /// A master curve other than a Prony series.
    #[error(
        "{}: model.kind = \"{kind}\": only \"prony\" master curves can be reported",
        path.display()
    )]
    NotProny { path: PathBuf, kind: String },
    /// The Prony series of fit.json is refused by the model crate.
    #[error("{}: model: {source}", path.display())]
    FitModel {
        path: PathBuf,
        /// What the model crate refused.
        source: rollfit_model::ModelError,
    },
    /// The window is not 0 < omega_min < omega_max.
    #[error(
        "{}: window: omega_min = {omega_min}, omega_max = {omega_max}: need 0 < omega_min < \
         omega_max",
        path.display()
    )]
    BadWindow {
        path: PathBuf,
        /// rad/s.
        omega_min: f64,
        /// rad/s.
        omega_max: f64,
    },
    /// A speed of mu.csv that is not positive.
    #[error("{}, line {line}: column {column}: {value} is not a positive speed", path.display())]
    SpeedNotPositive {
        /// The speed column's name.
        column: &'static str,
        path: PathBuf,
        line: usize,
        value: f64,
    },
    /// A frequency of modulus.csv that does not exceed the one above it.
    #[error(
        "{}, line {line}: column {column}: {value} does not increase (frequencies must be \
         positive and ascending)",
        path.display()
    )]
    OmegaNotIncreasing {
        /// The frequency column's name.
        column: &'static str,
        path: PathBuf,
        line: usize,
        value: f64,
    },
    /// A fit.json of a batch entry that cannot be read or parsed (both
    /// shown, not sources: the batch summary takes the text).
    #[error(
        "cannot read the result {}: {cause} (remove it or give --force to refit)",
        path.display()
    )]
    ResultUnreadable {
        path: PathBuf,
        /// What the system or serde_json said.
        cause: String,
    },

    // ------------------------------------------------------------ DMA files
    /// A Poisson's ratio, given with the DMA file, that cannot convert
    /// its shear moduli (`problem`: shown, not a source).
    #[error("{problem} (converting shear moduli of {} to Young's)", path.display())]
    DmaPoisson {
        path: PathBuf,
        problem: rollfit_model::PoissonOutOfRange,
    },
    /// ω ≤ 0.
    #[error("{}, {row}: {column}: frequency {value} is not positive", path.display())]
    FrequencyNotPositive {
        path: PathBuf,
        /// A text file's line, or a sheet's row.
        row: RowRef,
        column: ColumnRef,
        /// rad/s.
        value: f64,
    },
    /// E′ ≤ 0.
    #[error("{}, {row}: {column}: storage modulus {value} is not positive", path.display())]
    StorageNotPositive {
        path: PathBuf,
        /// A text file's line, or a sheet's row.
        row: RowRef,
        column: ColumnRef,
        /// As in the file, Pa.
        value: f64,
    },
    /// ω outside 1e-30 … 1e30 rad/s.
    #[error(
        "{}, {row}: {column}: frequency {value:e} rad/s is outside 1e-30 … 1e30 rad/s, \
         beyond any master curve",
        path.display()
    )]
    FrequencyOutOfRange {
        path: PathBuf,
        /// A text file's line, or a sheet's row.
        row: RowRef,
        column: ColumnRef,
        /// rad/s.
        value: f64,
    },
    /// A modulus above 1e13 Pa (after conversion to Young's).
    #[error(
        "{}, {row}: {column}: modulus {value:e} is above 1e13 Pa, stiffer than any solid \
         (diamond: about 1.2e12 Pa); is the column in Pa?",
        path.display()
    )]
    ModulusTooLarge {
        path: PathBuf,
        /// A text file's line, or a sheet's row.
        row: RowRef,
        column: ColumnRef,
        /// As in the file, Pa.
        value: f64,
    },
    /// E′ below 1e-3 Pa (after conversion to Young's).
    #[error(
        "{}, {row}: {column}: storage modulus {value:e} is below 1e-3 Pa, softer than any \
         solid; is the column in Pa?",
        path.display()
    )]
    StorageTooSmall {
        path: PathBuf,
        /// A text file's line, or a sheet's row.
        row: RowRef,
        column: ColumnRef,
        /// As in the file, Pa.
        value: f64,
    },
    /// A temperature outside (−273.15, 1000] °C.
    #[error(
        "{}, {row}: temperature {value} °C is outside (−273.15, 1000] °C",
        path.display()
    )]
    TemperatureOutOfRange {
        path: PathBuf,
        /// A text file's line, or a sheet's row.
        row: RowRef,
        /// °C.
        value: f64,
    },
    /// Every point had E″ ≤ 0 and was dropped.
    #[error("{}: no usable points: all {dropped} have a loss modulus ≤ 0", path.display())]
    NoUsablePoints {
        path: PathBuf,
        /// Points dropped.
        dropped: usize,
    },
    /// No point at all.
    #[error("{}: no data points", path.display())]
    NoDataPoints { path: PathBuf },
    /// A column whose unit contradicts its name (`omega_Hz`, `f_rad_s`).
    #[error(
        "{}, {line}: column {number} ({}): {contradiction}: name it f_Hz if it holds hertz \
         or omega_rad_s if it holds rad/s",
        path.display(),
        contradiction.column()
    )]
    ContradictoryUnit {
        path: PathBuf,
        /// The header's line or row.
        line: RowRef,
        /// The column, from 1.
        number: usize,
        contradiction: Contradiction,
    },
    /// Two columns for one quantity.
    #[error(transparent)]
    DuplicateQuantity(Box<DuplicateQuantity>),
    /// No `omega` or `f` column.
    #[error(
        "{}: no frequency column: need `omega` (rad/s) or `f` (Hz), optionally with a unit \
         suffix such as omega_rad_s or f_Hz (the header has: {}); stress-relaxation data (`t` \
         and `E_relax` or `G_relax`) are read by `rollfit master` and `rollfit compare`",
        path.display(),
        header.join(", ")
    )]
    NoFrequencyColumn { path: PathBuf, header: Vec<String> },
    /// Storage or loss columns absent.
    #[error(
        "{}: no {missing} column: need storage and loss moduli as E_storage, E_loss (Young's) or \
         G_storage, G_loss (shear), in Pa or with a unit suffix such as G_storage_Pa (the header \
         has: {})",
        path.display(),
        header.join(", ")
    )]
    NoModulusColumns {
        path: PathBuf,
        /// What is missing ("E_loss", "G_storage and G_loss", …).
        missing: String,
        header: Vec<String>,
    },
    /// A DMA column in a unit not known.
    #[error(transparent)]
    DmaUnknownUnit(Box<DmaUnknownUnit>),
    /// A workbook DMA file that cannot be read: see [`DmaSheetError`].
    #[error(transparent)]
    DmaSheet(Box<DmaSheetError>),
    /// A TRIOS export that cannot be read: see [`TriosError`].
    #[error(transparent)]
    Trios(Box<TriosError>),

    // ------------------------------------------------------------ data, tables
    /// An input file refused before it is read: see [`InputError`].
    #[error(transparent)]
    Input(Box<InputError>),
    /// A measured-data file that cannot be read: see [`DataError`].
    #[error(transparent)]
    Data(Box<DataError>),
    /// A modulus table that cannot be read: see [`TableError`].
    #[error(transparent)]
    Table(Box<TableError>),
    /// A scene file that cannot be read: see [`SceneError`].
    #[error(transparent)]
    Scene(Box<SceneError>),
    /// A batch manifest that cannot be read: see [`ManifestError`].
    #[error(transparent)]
    Manifest(Box<ManifestError>),
    /// A DMA file that gives no master curve: see [`DmaMasterError`].
    #[error(transparent)]
    Master(Box<DmaMasterError>),
    /// A stress-relaxation file that cannot be read: see
    /// [`RelaxationError`].
    #[error(transparent)]
    Relaxation(Box<RelaxationError>),

    // ------------------------------------------------------------ writing
    /// A number that is not finite in an output table.
    #[error(
        "the output's row {row} has {column} = {value}: not a finite number (refused rather than \
         written)"
    )]
    NonFiniteCell {
        /// Row, from 1 (below the header).
        row: usize,
        /// The column's name ("?" beyond the header).
        column: String,
        /// The cell ("NaN", "inf", "-inf").
        value: String,
    },
    /// An output file name that is a folder.
    #[error("output {} is a folder; give a file name for the output", path.display())]
    OutputIsFolder { path: PathBuf },
    /// A path that does not end in a file name (`..`).
    #[error("{} does not name a file", path.display())]
    NotAFileName { path: PathBuf },
    /// A folder could not be made.
    #[error("cannot create the folder {}", path.display())]
    CreateFolder {
        path: PathBuf,
        source: std::io::Error,
    },
    /// A file could not be written or renamed into place.
    #[error("cannot write {}", path.display())]
    Write {
        path: PathBuf,
        source: std::io::Error,
    },
    /// No temporary file or folder could be made beside the target.
    #[error("cannot create a temporary file in {} (is the folder writable?)", folder.display())]
    CreateTemporary {
        folder: PathBuf,
        source: std::io::Error,
    },
    /// An output folder that is a file.
    #[error(
        "output {} exists and is not a folder; give a folder for the results",
        dir.display()
    )]
    OutputNotFolder { dir: PathBuf },
    /// An output folder another run may not replace: see [`FolderError`].
    #[error(transparent)]
    Folder(#[from] FolderError),
    /// A result folder could not be filled or swapped in.
    #[error("cannot write the results to {}", dir.display())]
    WriteResults {
        /// The result folder.
        dir: PathBuf,
        source: std::io::Error,
    },
    /// A lock file could not be made.
    #[error("cannot create the lock file {} (is the folder writable?)", path.display())]
    CreateLock {
        path: PathBuf,
        source: std::io::Error,
    },
    /// The folder's lock is held by another run.
    #[error(
        "{} is being written by another rollfit run{}; wait for it to finish or give another \
         output folder",
        dir.display(),
        holders_note(holders)
    )]
    Locked {
        dir: PathBuf,
        /// Process ids of the running holders found.
        holders: Vec<u32>,
    },
    /// Locking failed for another reason than a holder.
    #[error("cannot lock {}", path.display())]
    Lock {
        path: PathBuf,
        source: std::io::Error,
    },

    // ------------------------------------------------------------ faults
    /// Not the user's doing: see [`Fault`].
    #[error(transparent)]
    Internal(#[from] Fault),
}
