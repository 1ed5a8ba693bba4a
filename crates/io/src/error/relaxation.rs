//! The errors of reading a stress-relaxation or creep file ([`RelaxationError`],
//! reached as [`super::IoError::Relaxation`]; read by
//! [`crate::dma::relaxation`] for `rollfit master` and `rollfit compare`,
//! docs/ARCHITECTURE.md, "Contract", "DMA files"). Causes every CSV shares
//! (a cell that is not a number, a short row) are [`super::IoError`]'s own.

use std::path::PathBuf;

use thiserror::Error;

use rollfit_fit::master::relaxation::TimeQuantity;

use super::ColumnRef;

/// Why a relaxation or creep file cannot be read.
#[derive(Debug, Error)]
pub enum RelaxationError {
    /// A time column without a relaxation-modulus or creep-compliance
    /// column.
    #[error(
        "{}: a time column but no relaxation modulus: need E_relax (Young's) or G_relax \
         (shear), also spelled E(t), E_t, E, G(t), G_t, G, in Pa or with a unit such as \
         E_relax_MPa or \"E(t) (MPa)\"; or a creep compliance, J(t) or \"Creep Compliance\" \
         (shear), D(t) or \"Tensile Creep Compliance\" (tensile), in 1/Pa or with a unit \
         such as \"J (1/MPa)\" (the header has: {})",
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
        /// "time", "relaxation modulus", "creep compliance", "relaxation
        /// modulus or creep compliance" or "temperature".
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
    /// A creep compliance that is not positive or beyond any solid's.
    #[error(
        "{}, line {line}: {column}: D(t) = {value} 1/Pa (tensile) is not a creep compliance (it \
         must be positive and below 1 1/Pa)",
        path.display()
    )]
    ComplianceOutOfRange {
        path: PathBuf,
        line: usize,
        column: ColumnRef,
        value: f64,
    },
    /// A creep compliance that falls with time by more than scatter.
    #[error(
        "{}: column {column}: the creep isotherm at {temperature:.2} °C falls with time: line {} \
         (D = {:e} 1/Pa) is followed at a later time by line {} (D = {:e} 1/Pa), {:.0} % lower; \
         a creep compliance never decreases with time (it rises from the step of stress), so \
         this column is not a creep compliance (a modulus or a stress?)",
        path.display(),
        lines.0,
        values.0,
        lines.1,
        values.1,
        100.0 * (1.0 - values.1 / values.0)
    )]
    ComplianceFalls {
        path: PathBuf,
        column: ColumnRef,
        /// °C.
        temperature: f64,
        /// The line of the highest earlier value and the line below it.
        lines: (usize, usize),
        /// Their compliances, 1/Pa (tensile).
        values: (f64, f64),
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
        "{}: the {} isotherm at {temperature:.2} °C has times that do not increase: \
         line {} (t = {:e} s) is followed by line {} (t = {:e} s); a {} run's times \
         increase from the step of {}, and a repeated run is another isotherm",
        path.display(),
        quantity.name(),
        lines.0,
        times.0,
        lines.1,
        times.1,
        quantity.name(),
        if *quantity == TimeQuantity::Creep { "stress" } else { "strain" }
    )]
    NotIncreasing {
        path: PathBuf,
        /// What the isotherm measures.
        quantity: TimeQuantity,
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
        super::IoError::transparent(super::ErrorKind::Content, e)
    }
}
