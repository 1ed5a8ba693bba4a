//! The record a result folder keeps of its own files
//! (docs/ARCHITECTURE.md, "Contract", "Output folders"): the hidden file
//! [`RECORD_FILE`], JSON `{"written_by": "fit", "files": ["fit.json", …]}`,
//! naming the command that wrote the folder and every file rollfit put
//! there (the command's own and those added later, such as `rollfit
//! report`'s pictures).
//!
//! It is what decides who may replace what. A run of the same command
//! replaces the recorded files and keeps every other one (a user's
//! `sample-photo.png`); another command's folder is refused unless
//! `--force`. A folder without a record was written by an older rollfit or
//! by hand: its writer is read from the files it holds ([`Occupant::legacy`],
//! fixed names only, never a pattern such as `*.png`).

use std::fs;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::fit_dir::columns::{FIT_JSON, MODULUS_CSV, MU_CSV};

/// The record's file name in a result folder.
pub const RECORD_FILE: &str = ".rollfit-files.json";

/// The command that writes a result folder.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Writer {
    /// `rollfit fit` (and a batch entry's folder, `rollfit report` and
    /// `rollfit compare`, which add to a fit's folder).
    Fit,
    /// `rollfit master`, on frequency sweeps or relaxation data.
    Master,
    /// `rollfit batch`: the summary and one fit folder per entry.
    Batch,
}

impl Writer {
    /// The command, as a user types it.
    pub fn command(self) -> &'static str {
        match self {
            Writer::Fit => "rollfit fit",
            Writer::Master => "rollfit master",
            Writer::Batch => "rollfit batch",
        }
    }

    /// The files the command itself may write (a folder's other files
    /// that bear one of these names stop it).
    pub(super) fn own_files(self) -> &'static [&'static str] {
        match self {
            Writer::Fit => &self.legacy_files()[..3],
            _ => self.legacy_files(),
        }
    }

    /// The files an older rollfit, which kept no record, wrote as this
    /// command (and, for a fit, `report` and `compare` added): the
    /// command's own first.
    fn legacy_files(self) -> &'static [&'static str] {
        match self {
            Writer::Fit => &[
                FIT_JSON,
                MU_CSV,
                MODULUS_CSV,
                "report.html",
                "compare.json",
                "friction.png",
                "friction.svg",
                "master_curve.png",
                "master_curve.svg",
                "spectrum.png",
                "spectrum.svg",
                "convergence.png",
                "convergence.svg",
                "master_friction.png",
                "master_friction.svg",
                "shift.png",
                "shift.svg",
                "joint_master.png",
                "joint_master.svg",
                "joint_residuals.png",
                "joint_residuals.svg",
            ],
            Writer::Master => &[
                "master.json",
                "master.csv",
                "shift.csv",
                MODULUS_CSV,
                "material.toml",
                "relaxation.csv",
                "master.png",
                "master.svg",
            ],
            // A batch's names are read from its folder (`legacy`).
            Writer::Batch => &[],
        }
    }
}

/// The record as stored.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Record {
    written_by: Writer,
    files: Vec<String>,
}

/// Who wrote a result folder, and which of its entries are theirs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct Occupant {
    pub writer: Writer,
    /// The names rollfit wrote, as recorded (or, for an older folder, the
    /// fixed names of its writer that are present).
    pub files: Vec<String>,
}

impl Occupant {
    /// The writer of `dir` and its files: from the record, else from the
    /// files an older rollfit writes; `None` for a missing folder and for
    /// one rollfit did not write (empty, or a user's files only). A record
    /// that cannot be read counts as absent.
    pub fn of(dir: &Path) -> Option<Occupant> {
        if let Some(record) = fs::read(dir.join(RECORD_FILE))
            .ok()
            .and_then(|bytes| serde_json::from_slice::<Record>(&bytes).ok())
        {
            return Some(Occupant {
                writer: record.written_by,
                files: record.files,
            });
        }
        Occupant::legacy(dir)
    }

    /// An older rollfit's folder: the writer whose mark file is present,
    /// or a batch's when a sub-folder holds a fit.json, with the names it
    /// writes that are present (for a batch, its summaries and entries).
    fn legacy(dir: &Path) -> Option<Occupant> {
        let present = |name: &str| dir.join(name).is_file();
        let entries: Vec<(String, bool)> = fs::read_dir(dir)
            .ok()?
            .flatten()
            .map(|e| {
                let fit_folder = e.path().join(FIT_JSON).is_file();
                (e.file_name().to_string_lossy().into_owned(), fit_folder)
            })
            .collect();
        let writer = if present(FIT_JSON) {
            Writer::Fit
        } else if present("master.json") {
            Writer::Master
        } else if entries.iter().any(|e| e.1) {
            Writer::Batch
        } else {
            return None;
        };
        let mut files: Vec<String> = entries
            .into_iter()
            .filter(|(name, fit_folder)| match writer {
                Writer::Batch => {
                    *fit_folder || (name.starts_with("summary") && name.ends_with(".csv"))
                }
                _ => writer.legacy_files().contains(&name.as_str()) && present(name),
            })
            .map(|(name, _)| name)
            .collect();
        // Listed in a message: in a stable order.
        files.sort();
        Some(Occupant { writer, files })
    }

    /// Whether `name` is one of rollfit's files here.
    pub fn owns(&self, name: &str) -> bool {
        self.files.iter().any(|f| f == name)
    }
}

/// The record's bytes for `writer` and `names` (sorted, each once).
pub(super) fn encode(writer: Writer, names: impl IntoIterator<Item = String>) -> Vec<u8> {
    let mut files: Vec<String> = names.into_iter().collect();
    files.sort();
    files.dedup();
    let mut bytes = serde_json::to_vec_pretty(&Record {
        written_by: writer,
        files,
    })
    .unwrap_or_default();
    bytes.push(b'\n');
    bytes
}
