//! How a batch manifest's messages name an entry ([`EntryRef`]), where a
//! TOML error lies ([`TomlPlace`]) and what is wrong with an entry
//! ([`EntryProblem`]).

use std::fmt;
use std::path::PathBuf;

/// An `[[entry]]` as messages name it: `entry "NAME" (K of N, line L)`,
/// `entry K of N (line L)` without a name.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EntryRef {
    /// Position in the manifest, from 0.
    pub index: usize,
    /// Entries in the manifest.
    pub total: usize,
    /// Its name, if it has one.
    pub name: Option<String>,
    /// The line of its `[[entry]]` header.
    pub line: usize,
}

impl fmt::Display for EntryRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (k, total, line) = (self.index + 1, self.total, self.line);
        match &self.name {
            Some(name) => write!(f, "entry {name:?} ({k} of {total}, line {line})"),
            None => write!(f, "entry {k} of {total} (line {line})"),
        }
    }
}

/// Where in a manifest a TOML error lies, as its message names it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum TomlPlace {
    /// `[defaults]`.
    Defaults,
    /// An entry of a manifest that parses as an outline.
    Entry(EntryRef),
    /// The K-th `[[entry]]` header above a syntax error, and its line.
    EntryHeader { number: usize, line: usize },
}

impl fmt::Display for TomlPlace {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TomlPlace::Defaults => f.write_str("[defaults]"),
            TomlPlace::Entry(entry) => entry.fmt(f),
            TomlPlace::EntryHeader { number, line } => write!(f, "entry {number} (line {line})"),
        }
    }
}

/// What is wrong with one entry.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum EntryProblem {
    /// No `name`.
    MissingName { entry: EntryRef },
    /// A name that cannot be a result folder (`why` says what is wrong).
    BadName {
        entry: EntryRef,
        name: String,
        why: String,
    },
    /// A name an earlier entry has (`same`: exactly; else up to case).
    DuplicateName {
        entry: EntryRef,
        first: EntryRef,
        same: bool,
    },
    /// No `scene` or `data`.
    MissingFile { entry: EntryRef, key: &'static str },
    /// A `scene` or `data` file that does not exist or is not a file.
    NoSuchFile {
        entry: EntryRef,
        /// The line of the key.
        line: usize,
        key: &'static str,
        path: PathBuf,
        /// The path exists (as a folder or another non-file).
        exists: bool,
    },
}

impl fmt::Display for EntryProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            EntryProblem::MissingName { entry } => write!(
                f,
                "{entry}: missing `name` (the result folder, e.g. name = \"sample-1\")"
            ),
            EntryProblem::BadName { entry, name, why } => write!(f, "{entry}: name {name:?} {why}"),
            EntryProblem::DuplicateName { entry, first, same } => write!(
                f,
                "{entry}: duplicate name: {first} has {}; names must be unique, each names a \
                 result folder",
                if *same {
                    "the same name"
                } else {
                    "a name that differs only in case (one folder on many file systems)"
                }
            ),
            EntryProblem::MissingFile { entry, key } => {
                write!(f, "{entry}: missing `{key}` (path of the {key} file)")
            }
            EntryProblem::NoSuchFile {
                entry,
                line,
                key,
                path,
                exists,
            } => write!(
                f,
                "{entry}: line {line}: {key} file {} {} (paths are relative to the manifest's \
                 folder)",
                path.display(),
                if *exists {
                    "is not a file"
                } else {
                    "does not exist"
                }
            ),
        }
    }
}

/// One problem a line.
pub(crate) fn problem_list(problems: &[EntryProblem]) -> String {
    let lines: Vec<String> = problems.iter().map(EntryProblem::to_string).collect();
    lines.join("\n")
}
