//! The errors of reading a stress-relaxation file ([`RelaxationError`],
//! reached as [`super::IoError::Relaxation`]; read by
//! [`crate::dma::relaxation`] for `rollfit master` and `rollfit compare`,
//! docs/ARCHITECTURE.md, "Contract", "DMA files"). Causes every CSV shares
//! (a cell that is not a number, a short row) are [`super::IoError`]'s own.

use std::path::PathBuf;

use thiserror::Error;

use super::ColumnRef;

/// Why a relaxation file cannot be read.
#[derive(Debug, Error)]
pub enum RelaxationError {
    /// A time column without a relaxation-modulus column.
    #[error(
        "{}: a time column but no relaxation modulus: need E_relax (Young's) or G_relax \
         (shear), also spelled E(t), E_t, E, G(t), G_t, G, in Pa or with a unit such as \
         E_relax_MPa or \"E(t) (MPa)\" (the header has: {})",
        path.display(),
        header.join(", ")
    )]
    NoModulusColumn { path: PathBuf, header: Vec<String> },
    /// Two columns for one quantity.
    #[error(
        "{}, line {line}: two {quantity} columns, {} and {}: keep one",
        path.display(),
        columns.0,
        columns.1
    )]
    TwoColumns {
        path: PathBuf,
        line: usize,
        /// "time", "relaxation modulus" or "temperature".
        quantity: &'static str,
        /// The first two, in header order (boxed: they are large).
        columns: Box<(ColumnRef, ColumnRef)>,
    },
    /// A time that is not positive (t is counted from the step of strain).
    #[error(
        "{}, line {line}: {column}: t = {value} s: times are counted from the step of strain \
         and must be positive",
        path.display()
    )]
    TimeNotPositive {
        path: PathBuf,
        line: usize,
        column: ColumnRef,
        value: f64,
    },
    /// A time outside 1e-30 … 1e30 s (the reciprocal of the frequency
    /// form's range).
    #[error(
        "{}, line {line}: {column}: t = {value:e} s is outside 1e-30 … 1e30 s, beyond any \
         relaxation measurement (is the time in s, or is the column a time at all?)",
        path.display()
    )]
    TimeOutOfRange {
        path: PathBuf,
        line: usize,
        column: ColumnRef,
        value: f64,
    },
    /// A relaxation modulus that is not positive or beyond any solid's.
    #[error(
        "{}, line {line}: {column}: E(t) = {value} Pa is not a modulus (it must be positive and \
         below 1e13 Pa)",
        path.display()
    )]
    ModulusOutOfRange {
        path: PathBuf,
        line: usize,
        column: ColumnRef,
        value: f64,
    },
    /// A temperature outside (−273.15, 1000] °C.
    #[error("{}, line {line}: temperature {value} °C is out of range", path.display())]
    TemperatureOutOfRange {
        path: PathBuf,
        line: usize,
        value: f64,
    },
    /// Some rows have a temperature and some not.
    #[error(
        "{}: {missing} of {total} rows have no temperature: cannot tell which isotherm they \
         belong to",
        path.display()
    )]
    TemperatureMissing {
        path: PathBuf,
        missing: usize,
        total: usize,
    },
    /// Times that do not increase within an isotherm.
    #[error(
        "{}: the relaxation isotherm at {temperature:.2} °C has times that do not increase: \
         line {} (t = {:e} s) is followed by line {} (t = {:e} s); a relaxation run's times \
         increase from the step of strain, and a repeated run is another isotherm",
        path.display(),
        lines.0,
        times.0,
        lines.1,
        times.1
    )]
    NotIncreasing {
        path: PathBuf,
        /// °C.
        temperature: f64,
        /// The two lines, in file order.
        lines: (usize, usize),
        /// Their times, s.
        times: (f64, f64),
    },
}

impl From<RelaxationError> for super::IoError {
    fn from(e: RelaxationError) -> Self {
        super::IoError::Relaxation(Box::new(e))
    }
}
