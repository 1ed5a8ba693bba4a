//! The errors of a TA Instruments TRIOS "LIMS" text export
//! ([`TriosError`], reached as [`super::IoError::Trios`]; read by
//! [`crate::dma::trios`], docs/ARCHITECTURE.md, "Contract", "DMA files"):
//! its steps, their point counts, variables and units, and whether the
//! moduli are shear or tensile. Each names the file and, where one is at
//! fault, the line and step.

use std::path::PathBuf;

use thiserror::Error;

use super::IoError;
use super::parts::{SkippedStep, StepRef, count_mismatch};

/// Why a TRIOS export cannot be read.
#[derive(Debug, Error)]
pub enum TriosError {
    /// A TRIOS `Number of points` that is not a count.
    #[error(
        "{}, line {line}: {step}: Number of points \"{text}\" is not a count",
        path.display()
    )]
    StepCountNotANumber {
        path: PathBuf,
        line: usize,
        step: StepRef,
        text: String,
    },
    /// A TRIOS step whose `Data point` rows are not as many as it says.
    #[error(
        "{}, line {line}: {step}: Number of points says {declared}, but {}",
        path.display(),
        count_mismatch(*declared, *found, *rows, *last_line)
    )]
    StepCountMismatch {
        path: PathBuf,
        /// Line of `Number of points`.
        line: usize,
        step: StepRef,
        declared: usize,
        found: usize,
        /// First and last line of the rows found.
        rows: Option<(usize, usize)>,
        /// The file's last line.
        last_line: usize,
    },
    /// A TRIOS file cut inside a step.
    #[error(
        "{}, line {line}: the file ends inside {step} without a line break after this line: the \
         export looks cut off in the middle of it (a row or a number may be incomplete); if the \
         file is complete, end it with a line break",
        path.display()
    )]
    CutInStep {
        path: PathBuf,
        /// The last line.
        line: usize,
        step: StepRef,
    },
    /// A TRIOS step with data but without `Variables` and `Units`.
    #[error(
        "{}, line {line}: {step} has data points but no Variables and Units lines",
        path.display()
    )]
    StepWithoutVariables {
        path: PathBuf,
        /// Line of `[Step]`.
        line: usize,
        step: StepRef,
    },
    /// A TRIOS variable in a unit rollfit does not know.
    #[error(transparent)]
    UnknownUnit(Box<IoError>),
    /// A TRIOS file without any `Data point` row.
    #[error("{}: TRIOS export without data points", path.display())]
    TriosWithoutPoints { path: PathBuf },
    /// No TRIOS step has frequency, storage and loss.
    #[error(
        "{}: no step has the variables needed (Angular frequency or Frequency, Storage modulus, \
         Loss modulus): {}",
        path.display(),
        skipped.iter().map(ToString::to_string).collect::<Vec<_>>().join("; ")
    )]
    NoUsableStep {
        path: PathBuf,
        /// The steps with data, each with its variables.
        skipped: Vec<SkippedStep>,
    },
    /// Neither the variables nor the instrument say shear or tensile.
    #[error(
        "{}: cannot tell whether Storage and Loss modulus are shear (G) or tensile (E): no torque \
         or Oscillation force variable{}; give --dma-modulus shear or --dma-modulus young",
        path.display(),
        instrument.as_ref().map_or(String::new(), |i| format!("; instrument type {i}"))
    )]
    ModulusKindUnknown {
        path: PathBuf,
        /// `Instrument type`, when the file gives it.
        instrument: Option<String>,
    },
}

impl From<TriosError> for super::IoError {
    fn from(e: TriosError) -> Self {
        super::IoError::transparent(super::ErrorKind::Content, e)
    }
}
