//! The one error type of the report crate.

use std::path::PathBuf;

use thiserror::Error;

/// Everything that can stop a report or a comparison. Every variant names
/// the file it is about; bad rows name their line (counting from 1, as an
/// editor does).
#[derive(Debug, Error)]
pub enum ReportError {
    /// A file could not be read.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// A file is readable but its content is not what it must be.
    #[error("{}: {message}", path.display())]
    Format {
        /// The file.
        path: PathBuf,
        /// What is wrong, with the key or column.
        message: String,
    },
    /// One line of a table is wrong.
    #[error("{}, line {line}: {message}", path.display())]
    Line {
        /// The file.
        path: PathBuf,
        /// Line number, counting from 1.
        line: usize,
        /// What is wrong, with the column.
        message: String,
    },
    /// The fit's model cannot be rebuilt (a fit.json edited by hand).
    #[error("{}: model: {source}", path.display())]
    Model {
        /// The fit.json.
        path: PathBuf,
        /// What the model crate refused.
        source: rollfit_model::ModelError,
    },
    /// The data cannot answer the question asked (e.g. a DMA file whose
    /// temperatures cannot be shifted with the fit's shift).
    #[error("{0}")]
    Unanswerable(String),
    /// Drawing a picture failed.
    #[error("picture {name}: {message}")]
    Plot {
        /// The picture's file stem.
        name: String,
        /// What plotters or the encoder said.
        message: String,
    },
}

impl ReportError {
    pub(crate) fn format(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        ReportError::Format {
            path: path.into(),
            message: message.into(),
        }
    }

    pub(crate) fn line(path: impl Into<PathBuf>, line: usize, message: impl Into<String>) -> Self {
        ReportError::Line {
            path: path.into(),
            line,
            message: message.into(),
        }
    }

    pub(crate) fn io(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        ReportError::Io {
            path: path.into(),
            source,
        }
    }
}
