//! The errors of building a master curve from a DMA file
//! ([`DmaMasterError`], reached as [`super::IoError::Master`]; built by
//! [`crate::dma_master`] for `rollfit master` and a scene's
//! `[material] model = "dma"`, docs/ARCHITECTURE.md, "Contract", "DMA
//! files"). What the fit library refuses is wrapped by a variant naming
//! the file ([`DmaMasterError::InFile`], [`DmaMasterError::MasterCurve`]),
//! whose source `{:#}` prints after it.

use std::fmt;
use std::path::PathBuf;

use thiserror::Error;

use super::{IoError, RowRef};

/// A point of an isotherm where its sweep turns, as a message names it:
/// `line 13: ω = 5.2e0 rad/s`, or `point 7: …` where the file has no line
/// for it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TurnPoint {
    /// The point's file line, if known.
    pub line: Option<usize>,
    /// Its index among the file's points, from 0.
    pub index: usize,
    /// Its frequency, rad/s.
    pub omega: f64,
}

impl fmt::Display for TurnPoint {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(l) => write!(f, "line {l}: ω = {:e} rad/s", self.omega),
            None => write!(f, "point {}: ω = {:e} rad/s", self.index + 1, self.omega),
        }
    }
}

/// Why no master curve could be built from a DMA file.
#[derive(Debug, Error)]
pub enum DmaMasterError {
    /// The DMA reader refused the file: its message, which names the file
    /// and line (shown, not a source, as the message always had it).
    #[error("{error}")]
    Read { error: Box<IoError> },
    /// Some points have a temperature and some do not.
    #[error(
        "DMA file {}: {missing} of {total} points have no temperature: cannot tell which \
         isotherm they belong to",
        path.display()
    )]
    TemperatureMissing {
        path: PathBuf,
        /// Points without a temperature.
        missing: usize,
        /// Points in all.
        total: usize,
    },
    /// A file without temperatures where no temperature stands in for them
    /// (a joint fit without `T_ref`).
    #[error(
        "DMA file {}: no point has a temperature: a joint fit places each DMA point at its \
         temperature; add a T column, or give `T_ref` (the temperature of this one curve)",
        path.display()
    )]
    NoTemperature { path: PathBuf },
    /// Temperatures that chain into no isotherm: a temperature sweep
    /// (crate::dma::isotherm).
    #[error(
        "DMA file {}: this looks like a temperature ramp, not isotherms: {count} points from \
         {low:.2} to {high:.2} °C with no gap over {gap} K between neighbouring temperatures \
         (the widest is {widest_gap:.2} K), where an isotherm spans at most {span} K. A \
         temperature sweep at fixed frequency is not a set of isotherms: rollfit master needs \
         frequency sweeps at several fixed temperatures (a column `Step`, `Set` or `Segment` \
         says which points form one)",
        path.display()
    )]
    Ramp {
        path: PathBuf,
        count: usize,
        low: f64,
        high: f64,
        widest_gap: f64,
        gap: f64,
        span: f64,
    },
    /// What the fit library refused about one point (the source), at its
    /// place in the file.
    #[error("DMA file {}, {row}", path.display())]
    AtPoint {
        path: PathBuf,
        row: RowRef,
        source: Box<DmaMasterError>,
    },
    /// What is wrong with the isotherms or the settings (the source).
    #[error("DMA file {}", path.display())]
    InFile {
        path: PathBuf,
        source: Box<DmaMasterError>,
    },
    /// The master-curve fit failed (the source says why).
    #[error("DMA file {}: master curve", path.display())]
    MasterCurve {
        path: PathBuf,
        source: Box<DmaMasterError>,
    },
    /// An isotherm whose frequencies neither rise nor fall throughout.
    #[error(
        "the isotherm at {temperature:.2} °C has frequencies that are not monotone ({}): a sweep \
         runs up or down once; split a repeated sweep into its own temperature or remove the \
         repeated points",
        list(turn)
    )]
    NotMonotone {
        /// °C.
        temperature: f64,
        /// The points about the turn, in file order.
        turn: Vec<TurnPoint>,
    },
    /// `--temperatures` (or a scene's `temperatures`) lists a number
    /// other than one per file.
    #[error(
        "{given} temperatures given for {files} DMA files: give one per file, in the order of \
         the files"
    )]
    TemperatureCount { given: usize, files: usize },
    /// A DMA file among several that states no temperature anywhere.
    #[error(
        "DMA file {}: no temperature: the file has no T column, no line above its header \
         states one (`Temperature: 20 °C`) and its name carries none (`…_20C.csv`); give \
         --temperatures T1,T2,… in the order of the files",
        path.display()
    )]
    FileWithoutTemperature { path: PathBuf },
    /// A folder given as DMA data without a data file in it.
    #[error(
        "DMA folder {}: no data file in it (read: {})",
        path.display(),
        crate::dma::files::DATA_EXTENSIONS.join(", ")
    )]
    EmptyFolder { path: PathBuf },
    /// The fit library refused the isotherms, the settings or the fit (its
    /// message, shown, not a source).
    #[error("{error}")]
    Fit { error: rollfit_fit::FitError },
}

impl From<DmaMasterError> for IoError {
    fn from(e: DmaMasterError) -> Self {
        IoError::transparent(super::ErrorKind::Content, e)
    }
}

/// `line 12: ω = …, line 13: ω = …`.
fn list(turn: &[TurnPoint]) -> String {
    let listed: Vec<String> = turn.iter().map(TurnPoint::to_string).collect();
    listed.join(", ")
}
