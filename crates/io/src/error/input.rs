//! The errors of reading an input file at all ([`InputError`], reached as
//! [`super::IoError::Input`]): a file that is no regular file, one above the
//! size limit, and a malformed limit (crate::input_file).

use std::path::PathBuf;

use thiserror::Error;

use crate::input_file::{FileType, LIMIT_VARIABLE, size_text};

/// Why an input file is refused before its contents are looked at.
#[derive(Debug, Error)]
pub enum InputError {
    /// A FIFO, device, socket or folder: its size cannot be known (a FIFO
    /// would block, /dev/zero never ends), so it is not opened.
    #[error("{kind} {} {}", path.display(), found.refusal())]
    NotRegular {
        /// What the file is for ("data file", "DMA file").
        kind: &'static str,
        path: PathBuf,
        /// What was found instead of a regular file.
        found: FileType,
    },
    /// A file above the limit. `size` is `None` where the file grew while
    /// read, or its size as stated was wrong (/proc).
    #[error(
        "{kind} {} {}; set {LIMIT_VARIABLE} to raise it (e.g. {LIMIT_VARIABLE}=4G)",
        path.display(),
        match size {
            Some(size) => format!(
                "is {}, more than the limit of {} on an input file",
                size_text(*size),
                size_text(*limit)
            ),
            None => format!(
                "holds more than the limit of {} on an input file (more than its stated size: it \
                 grew while read, or is no ordinary file)",
                size_text(*limit)
            ),
        }
    )]
    TooLarge {
        kind: &'static str,
        path: PathBuf,
        size: Option<u64>,
        limit: u64,
    },
    /// The limit variable holds no size.
    #[error(
        "cannot read {kind} {}: {LIMIT_VARIABLE} = {value:?} is not a size: give bytes \
         (1000000) or a number with K, M, G or T (500M, 2G; powers of 1024), at least 1",
        path.display()
    )]
    BadLimit {
        kind: &'static str,
        path: PathBuf,
        /// The variable's value as found.
        value: String,
    },
}

impl From<InputError> for super::IoError {
    fn from(e: InputError) -> Self {
        super::IoError::Input(Box::new(e))
    }
}
