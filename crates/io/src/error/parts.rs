//! The pieces of [`super::IoError`]'s messages that several variants
//! share: how a column, a TRIOS step and a place in a file are named.

use std::fmt;
use std::path::Path;

/// A column as a message names it: `column v` (a fit folder's table, by
/// name) or `column 3 (E_storage)` (a DMA file, by number from 1 and name).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ColumnRef {
    /// The column's number, from 1, when the message gives it.
    pub number: Option<usize>,
    /// The column's (or TRIOS variable's) name.
    pub name: String,
}

impl ColumnRef {
    /// `column N (name)`, N counting from 1.
    pub fn numbered(number: usize, name: impl Into<String>) -> ColumnRef {
        ColumnRef {
            number: Some(number),
            name: name.into(),
        }
    }

    /// `column name`.
    pub fn named(name: impl Into<String>) -> ColumnRef {
        ColumnRef {
            number: None,
            name: name.into(),
        }
    }
}

impl fmt::Display for ColumnRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.number {
            Some(n) => write!(f, "column {n} ({})", self.name),
            None => write!(f, "column {}", self.name),
        }
    }
}

/// A `[Step]` of a TRIOS export: `step "name" (line N)`, or `step at line
/// N` when it has no `Step name`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StepRef {
    /// Its `Step name`.
    pub name: Option<String>,
    /// The line of `[Step]`.
    pub line: usize,
}

impl fmt::Display for StepRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.name {
            Some(name) => write!(f, "step \"{name}\" (line {})", self.line),
            None => write!(f, "step at line {}", self.line),
        }
    }
}

/// A TRIOS step with data points but without the variables needed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SkippedStep {
    /// The step.
    pub step: StepRef,
    /// Its variables.
    pub variables: Vec<String>,
}

impl fmt::Display for SkippedStep {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} (its variables: {})",
            self.step,
            self.variables.join(", ")
        )
    }
}

/// What is wrong with bytes that are not text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum InvalidText {
    /// Not UTF-8 in a file that must be (what rollfit writes).
    NotUtf8,
    /// A UTF-8 character cut off by the end of the file.
    CutCharacter,
    /// Invalid UTF-8 after a UTF-8 byte-order mark.
    InvalidAfterMark,
    /// Invalid UTF-8 in a file that is UTF-8 elsewhere.
    MixedEncodings,
}

impl fmt::Display for InvalidText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            InvalidText::NotUtf8 => "not UTF-8",
            InvalidText::CutCharacter => "not UTF-8 (a character cut off by the end of the file)",
            InvalidText::InvalidAfterMark => {
                "invalid UTF-8 in a file marked UTF-8 (byte-order mark)"
            }
            InvalidText::MixedEncodings => {
                "invalid UTF-8 in a file that is UTF-8 elsewhere (damaged, or pieces in two \
                 encodings)"
            }
        })
    }
}

/// A DMA column whose unit contradicts its name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Contradiction {
    /// `omega_Hz`.
    OmegaInHertz,
    /// `f_rad_s`.
    FrequencyInRadians,
}

impl Contradiction {
    /// The column name that says it.
    pub fn column(self) -> &'static str {
        match self {
            Contradiction::OmegaInHertz => "omega_Hz",
            Contradiction::FrequencyInRadians => "f_rad_s",
        }
    }

    /// The contradiction of a header name, if it is one.
    pub fn of(name: &str) -> Option<Contradiction> {
        [
            Contradiction::OmegaInHertz,
            Contradiction::FrequencyInRadians,
        ]
        .into_iter()
        .find(|c| c.column() == name)
    }
}

impl fmt::Display for Contradiction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Contradiction::OmegaInHertz => {
                "`omega` is an angular frequency, in rad/s, but the suffix says Hz"
            }
            Contradiction::FrequencyInRadians => {
                "`f` is a frequency, in Hz, but the suffix says rad/s"
            }
        })
    }
}

/// `path` or `path, line N`.
pub(crate) fn place(path: &Path, line: Option<usize>) -> String {
    match line {
        Some(line) => format!("{}, line {line}", path.display()),
        None => path.display().to_string(),
    }
}

/// `byte 0xXX` or `the end of the file`.
pub(crate) fn found_byte(found: Option<u8>) -> String {
    found.map_or("the end of the file".to_string(), |b| {
        format!("byte 0x{b:02X}")
    })
}

/// What a null stands where serde expected `expected`.
pub(crate) fn null_expected(expected: &str) -> String {
    match expected {
        "f64" => "a number is required (a NaN or infinity written as null?)".to_string(),
        "usize" | "u64" => "a count is required".to_string(),
        other => format!("{other} is required"),
    }
}

/// The end of a field-count message: the columns without a value and
/// whether the row looks cut off.
pub(crate) fn field_count_tail(missing: &[ColumnRef], cut: bool) -> String {
    let mut tail = String::new();
    if !missing.is_empty() {
        let names: Vec<String> = missing.iter().map(ToString::to_string).collect();
        tail += &format!("; no value for {}", names.join(", "));
    }
    if cut {
        tail += "; the file ends in this line without a line break: it looks cut off";
    }
    tail
}

/// What a TRIOS step's rows are against its `Number of points`.
pub(crate) fn count_mismatch(
    declared: usize,
    found: usize,
    rows: Option<(usize, usize)>,
    last_line: usize,
) -> String {
    let rows = match rows {
        Some((first, last)) => format!("{found} data point rows follow (lines {first} to {last})"),
        None => "the step is without data points".to_string(),
    };
    let why = if found < declared {
        format!(
            "rows are missing: the file looks truncated (it ends at line {last_line}) or was edited"
        )
    } else {
        "the file was edited or steps were merged".to_string()
    };
    format!("{rows}; {why}")
}

/// ` (pid N, …)` for the running holders of a lock, or nothing.
pub(crate) fn holders_note(holders: &[u32]) -> String {
    match holders {
        [] => String::new(),
        pids => format!(
            " (pid {})",
            pids.iter()
                .map(u32::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// A folder's files for a message: "fit.json, mu.csv", the first six and
/// how many more.
pub(crate) fn files_list(files: &[String]) -> String {
    const SHOWN: usize = 6;
    let mut text = files
        .iter()
        .take(SHOWN)
        .cloned()
        .collect::<Vec<_>>()
        .join(", ");
    if files.len() > SHOWN {
        text += &format!(" and {} more", files.len() - SHOWN);
    }
    text
}
