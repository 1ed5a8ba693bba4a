//! The one error type of the io crate, [`IoError`]: where (the file, when
//! one is to blame), what (the message a user reads after `error: `, which
//! names the file and, where one is at fault, the line, cell, column or
//! key), a small [`ErrorKind`] for the few callers that branch (a system
//! failure, bad content, a fault of rollfit itself) and the cause (the
//! [`std::error::Error::source`], which the command line's `{:#}` and
//! [`crate::chain`] print after a colon: `scene file s.toml: [sweep]:
//! count = 0: must be at least 1`).
//!
//! One type, not an enum of causes: no caller matches a cause (the command
//! line and the Python module print the text, the batch keeps it), so the
//! messages are the contract (docs/ARCHITECTURE.md, "Contract",
//! "Commands"), checked character by character by the message corpus
//! (tests/data/messages/). A message is written where its cause is found,
//! with `err!` (`err!("{}, line {line}: …", path.display())`), the cause
//! added with [`IoError::caused_by`] or [`IoError::system`]. The pieces
//! several messages share are here: how a byte, a column, a TRIOS step and
//! a place in a file are named ([`parts`]), a place and a column of
//! measured data ([`data`]), an entry of a manifest ([`manifest`]).

use std::path::PathBuf;

pub(crate) mod data;
pub(crate) mod manifest;
pub mod parts;

pub use data::{CellRef, ColumnName, RowRef, RowsRef, column_letter};
pub use manifest::{EntryProblem, EntryRef, TomlPlace};
pub use parts::{ColumnRef, Contradiction, InvalidText, SkippedStep, StepRef};
pub(crate) use parts::{
    field_count_tail, files_list, found_byte, holders_note, null_expected, place,
};

/// What kind of failure an [`IoError`] is: the distinctions a caller acts
/// on (the Python module raises `OSError` for a system failure and
/// `ValueError` for the rest; the batch keeps going after either).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorKind {
    /// The file's content, or what was asked of it, is wrong: the user
    /// mends the file or the command.
    Content,
    /// The operating system refused (a file absent, unreadable, a folder
    /// not writable); the cause is its [`std::io::Error`].
    System,
    /// A fault of rollfit itself, which no input can cause (an encoder
    /// failing on a memory buffer, a fit result inconsistent with its
    /// data).
    Internal,
}

/// Everything that can stop reading or writing a rollfit file: the file
/// blamed (where known), the message, its [`ErrorKind`] and its cause.
#[derive(Debug)]
pub struct IoError {
    kind: ErrorKind,
    file: Option<PathBuf>,
    message: String,
    source: Option<Box<dyn std::error::Error + Send + Sync + 'static>>,
    /// The message is the cause's own: `Display` and `source` are the
    /// cause's (an error of another crate passed on as it is).
    transparent: bool,
}

impl IoError {
    /// Bad content, with its message.
    pub fn content(message: impl Into<String>) -> IoError {
        IoError {
            kind: ErrorKind::Content,
            file: None,
            message: message.into(),
            source: None,
            transparent: false,
        }
    }

    /// An error of another crate shown as it is, its own message and
    /// cause: a model's refusal, an encoder's fault.
    pub fn transparent(
        kind: ErrorKind,
        error: impl std::error::Error + Send + Sync + 'static,
    ) -> IoError {
        IoError {
            kind,
            file: None,
            message: String::new(),
            source: Some(Box::new(error)),
            transparent: true,
        }
    }

    /// The system's refusal as the cause: kind [`ErrorKind::System`].
    pub fn system(mut self, cause: std::io::Error) -> IoError {
        self.kind = ErrorKind::System;
        self.source = Some(Box::new(cause));
        self
    }

    /// `cause` as the cause; an [`IoError`] cause lends its kind, so a
    /// file that cannot be read stays a system failure behind the scene
    /// naming it.
    pub fn caused_by(
        mut self,
        cause: impl Into<Box<dyn std::error::Error + Send + Sync + 'static>>,
    ) -> IoError {
        let cause = cause.into();
        if let Some(inner) = cause.downcast_ref::<IoError>() {
            self.kind = inner.kind;
        }
        self.source = Some(cause);
        self
    }

    /// A fault of rollfit itself: kind [`ErrorKind::Internal`].
    pub fn internal(mut self) -> IoError {
        self.kind = ErrorKind::Internal;
        self
    }

    /// The file blamed as a whole: one that cannot be read, or the scene,
    /// data, manifest or table file a cause found inside it is put behind.
    pub fn in_file(mut self, path: impl Into<PathBuf>) -> IoError {
        self.file = Some(path.into());
        self
    }

    /// What kind of failure this is.
    pub fn kind(&self) -> ErrorKind {
        self.kind
    }

    /// The file blamed, where a reader names one as a whole
    /// ([`IoError::in_file`]); the message names it too, with the line,
    /// cell or key at fault.
    pub fn file(&self) -> Option<&std::path::Path> {
        self.file.as_deref()
    }

    /// The error of another crate this one passes on as it is, if it is a
    /// `T`; else the error itself.
    pub fn into_transparent<T: std::error::Error + 'static>(self) -> Result<T, IoError> {
        match self.source {
            Some(source) if self.transparent && source.is::<T>() => {
                Ok(*source.downcast::<T>().expect("checked by is"))
            }
            source => Err(IoError { source, ..self }),
        }
    }
}

impl std::fmt::Display for IoError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match (&self.source, self.transparent) {
            (Some(source), true) => source.fmt(f),
            _ => f.write_str(&self.message),
        }
    }
}

impl std::error::Error for IoError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        let source = self.source.as_deref()?;
        match self.transparent {
            true => source.source(),
            false => Some(source),
        }
    }
}

/// An encoder's failure on a memory buffer: a fault, shown as the csv
/// crate says it.
impl From<csv::Error> for IoError {
    fn from(error: csv::Error) -> IoError {
        IoError::transparent(ErrorKind::Internal, error)
    }
}

/// `err!("fmt", args…)`: an [`IoError`] of bad content whose message is
/// `format!("fmt", args…)`; `.system(cause)`, `.caused_by(cause)`,
/// `.internal()` and `.in_file(path)` add the rest.
macro_rules! err {
    ($($arg:tt)*) => {
        $crate::error::IoError::content(format!($($arg)*))
    };
}
