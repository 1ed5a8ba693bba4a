//! Faults of rollfit itself, kept apart from what a user can mend
//! ([`super::IoError::Internal`]).

use thiserror::Error;

/// Faults of rollfit itself, which no input can cause: encoders failing on
/// memory buffers, a fit result inconsistent with its data.
#[derive(Debug, Error)]
pub enum Fault {
    /// The CSV encoder failed.
    #[error(transparent)]
    CsvEncode(#[from] csv::Error),
    /// The CSV encoder could not be finished.
    #[error("cannot finish the CSV text")]
    CsvFinish {
        /// What the encoder said.
        source: std::io::Error,
    },
    /// A JSON encoding failed.
    #[error("cannot encode the {what}")]
    JsonEncode {
        /// What was encoded ("fit report").
        what: &'static str,
        /// What serde_json said.
        source: serde_json::Error,
    },
    /// A TOML encoding failed.
    #[error("cannot format {file}")]
    TomlEncode {
        /// The file encoded ("material.toml").
        file: &'static str,
        /// What toml said.
        source: toml::ser::Error,
    },
    /// A master curve without the constants of its own shift law.
    #[error("{law} fit missing")]
    LawMissing {
        /// "WLF" or "Arrhenius".
        law: &'static str,
    },
    /// The fit returned another number of values than there are points.
    #[error("the fit returned {fitted} fitted values for {points} data points")]
    FittedCount {
        /// Values returned.
        fitted: usize,
        /// Data points.
        points: usize,
    },
}
