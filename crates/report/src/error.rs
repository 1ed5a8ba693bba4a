//! The one error type of the report crate.

use std::path::{Path, PathBuf};

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

    /// Bytes that are not text in the file's encoding: the line, the byte
    /// offset in the file (from 0) and the byte of the line (from 1), so
    /// that a hex editor and a text editor both find it. `offset` indexes
    /// `bytes`, the whole file; `what` says what was expected there.
    pub(crate) fn encoding(path: &Path, bytes: &[u8], offset: usize, what: &str) -> Self {
        let before = &bytes[..offset.min(bytes.len())];
        let line_start = before
            .iter()
            .rposition(|&b| b == b'\n')
            .map_or(0, |i| i + 1);
        let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
        let found = bytes
            .get(offset)
            .map_or("the end of the file".to_string(), |b| {
                format!("byte 0x{b:02X}")
            });
        ReportError::line(
            path,
            line,
            format!(
                "{what}: {found} at byte offset {offset} (byte {} of the line)",
                offset - line_start + 1
            ),
        )
    }
}

/// The text of a file that must be UTF-8 (what rollfit writes), or an
/// error naming the line and byte offset of the first invalid byte rather
/// than the system's bare "stream did not contain valid UTF-8".
pub(crate) fn read_utf8(path: &Path) -> Result<String, ReportError> {
    let bytes = std::fs::read(path).map_err(|e| ReportError::io(path, e))?;
    String::from_utf8(bytes).map_err(|e| {
        let offset = e.utf8_error().valid_up_to();
        let what = if e.utf8_error().error_len().is_none() {
            "not UTF-8 (a character cut off by the end of the file)"
        } else {
            "not UTF-8"
        };
        ReportError::encoding(path, e.as_bytes(), offset, what)
    })
}
