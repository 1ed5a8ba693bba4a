//! Several DMA files read as one data set: one file per isotherm, as many
//! instruments and labs write them, or a folder of such files.
//!
//! Each file is read alone ([`super::DmaData::read_sheet`]), and each
//! file's temperature comes from, in order:
//! 1. its T column;
//! 2. a title or metadata line above its header that states one
//!    ([`super::stated_temperature`]);
//! 3. its file name (`…_-25C.csv`, `…_293K.txt`);
//! 4. the temperatures given (`--temperatures`), one per file in the order
//!    of the files.
//!
//! Where each came from is kept ([`TemperatureOrigin`]) for the summary.
//! The points are then concatenated in file order; a file's own steps are
//! kept (numbered apart from the other files') when every file has a step
//! column, else the isotherms are found from the temperatures as in one
//! file ([`super::isotherms`]).

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

use super::{DmaData, DmaOptions, DmaWlf, ModulusKind};
use crate::error::IoError;

/// The file extensions read from a folder of DMA files.
pub const DATA_EXTENSIONS: [&str; 9] = [
    "csv", "txt", "tsv", "dat", "xlsx", "xlsm", "xlsb", "xls", "ods",
];

/// Where a file's temperature came from.
#[derive(Debug, Clone, PartialEq)]
pub enum TemperatureOrigin {
    /// Its T column (one or several isotherms).
    Column,
    /// A title or metadata line above its header: (line, °C).
    Line(usize, f64),
    /// Its file name, °C.
    FileName(f64),
    /// The temperatures given for the files, °C.
    Given(f64),
    /// Nowhere: the file is one curve without a temperature.
    None,
}

impl TemperatureOrigin {
    /// The temperature stated outside a T column, °C.
    pub fn stated(&self) -> Option<f64> {
        match *self {
            TemperatureOrigin::Line(_, t)
            | TemperatureOrigin::FileName(t)
            | TemperatureOrigin::Given(t) => Some(t),
            TemperatureOrigin::Column | TemperatureOrigin::None => None,
        }
    }
}

impl fmt::Display for TemperatureOrigin {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TemperatureOrigin::Column => write!(f, "from its T column"),
            TemperatureOrigin::Line(line, t) => write!(f, "{t} °C, stated on line {line}"),
            TemperatureOrigin::FileName(t) => write!(f, "{t} °C, from the file name"),
            TemperatureOrigin::Given(t) => write!(f, "{t} °C, as given"),
            TemperatureOrigin::None => write!(f, "no temperature"),
        }
    }
}

/// One file of a data set: its points' range in [`DmaData::points`] and
/// where their temperature came from.
#[derive(Debug, Clone, PartialEq)]
pub struct DmaFile {
    pub path: PathBuf,
    pub points: Range<usize>,
    pub temperature: TemperatureOrigin,
    /// The line a result block starts on, for a file of several
    /// (RheoCompass); None: the whole file.
    pub block: Option<usize>,
}

impl DmaFile {
    /// The file, or its block, as messages name it.
    pub fn name(&self) -> String {
        match self.block {
            Some(line) => format!("{} (block on line {line})", self.path.display()),
            None => self.path.display().to_string(),
        }
    }
}

/// The DMA data of a command: files or folders, and what the command line
/// (or a scene) says about them. Every reader of DMA frequency data takes
/// its files through [`DmaInput::read`], so that each file's temperature
/// comes from the same places in the same order.
#[derive(Debug, Clone, Default)]
pub struct DmaInput {
    /// The files, or folders of files ([`expand`]).
    pub files: Vec<PathBuf>,
    /// The sheet of a workbook (default: the first).
    pub sheet: Option<String>,
    /// Overrides the shear/tensile decision where the file's names do not
    /// state it.
    pub kind: Option<ModulusKind>,
    /// One temperature per file (°C), for files that state none.
    pub temperatures: Option<Vec<f64>>,
    /// The unit of moduli the files give none for (name, pascals).
    pub modulus_unit: Option<(&'static str, f64)>,
}

impl DmaInput {
    /// One file, read as it says.
    pub fn file(path: &Path) -> DmaInput {
        DmaInput {
            files: vec![path.to_path_buf()],
            ..DmaInput::default()
        }
    }

    /// Reads the files (folders expanded) as one data set, shear moduli
    /// converted with `poisson`; `wlf`, the DMA's own shift where a
    /// comparison uses it.
    pub fn read(&self, poisson: f64, wlf: Option<DmaWlf>) -> Result<DmaData, IoError> {
        let options = DmaOptions {
            kind: self.kind,
            wlf,
            modulus_unit: self.modulus_unit,
        };
        let paths = expand(&self.files)?;
        let given = self.temperatures.as_deref();
        read_files(&paths, poisson, &options, self.sheet.as_deref(), given)
    }

    /// The files as messages name them: the one file, or every one.
    pub fn names(&self) -> String {
        names(&self.files)
    }
}

/// Paths as messages name them: `a.csv, b.csv`.
pub fn names(paths: &[PathBuf]) -> String {
    let names: Vec<String> = paths.iter().map(|p| p.display().to_string()).collect();
    names.join(", ")
}

/// The files `inputs` name: each file as given, each folder as its data
/// files ([`DATA_EXTENSIONS`], not hidden) in the order of their names.
pub fn expand(inputs: &[PathBuf]) -> Result<Vec<PathBuf>, IoError> {
    let mut files = Vec::new();
    for input in inputs {
        if !input.is_dir() {
            files.push(input.clone());
            continue;
        }
        let read = std::fs::read_dir(input)
            .map_err(|source| err!("{}: {source}", input.display()).system(source))?;
        let mut found: Vec<PathBuf> = read
            .filter_map(Result::ok)
            .map(|entry| entry.path())
            .filter(|p| p.is_file() && is_data_file(p))
            .collect();
        if found.is_empty() {
            return Err(err!(
                "DMA folder {}: no data file in it (read: {})",
                input.display(),
                crate::dma::files::DATA_EXTENSIONS.join(", ")
            ));
        }
        found.sort();
        files.extend(found);
    }
    Ok(files)
}

/// A visible file with one of [`DATA_EXTENSIONS`].
fn is_data_file(path: &Path) -> bool {
    let hidden = path
        .file_name()
        .and_then(|n| n.to_str())
        .is_none_or(|n| n.starts_with('.'));
    let extension = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    !hidden && extension.is_some_and(|e| DATA_EXTENSIONS.contains(&e.as_str()))
}

/// Reads `paths` (files; folders expanded by [`expand`] first) as one data
/// set, a workbook's sheet `sheet`; `given`, one temperature per file (°C),
/// for the files that state none. One file is read as
/// [`DmaData::read_sheet`] reads it, with the temperature given.
pub fn read_files(
    paths: &[PathBuf],
    poisson: f64,
    options: &DmaOptions,
    sheet: Option<&str>,
    given: Option<&[f64]>,
) -> Result<DmaData, IoError> {
    check_given(given, paths.len())?;
    let mut all: Option<DmaData> = None;
    for (k, path) in paths.iter().enumerate() {
        let mut data = DmaData::read_sheet(path, poisson, options, sheet)?;
        if let Some(t) = given.map(|g| g[k]) {
            give_temperature(&mut data, t);
        }
        let untold = |f: &DmaFile| f.temperature == TemperatureOrigin::None;
        if paths.len() > 1 && data.files.iter().any(untold) {
            return Err(err!(
                "DMA file {}: no temperature: the file has no T column, no line above its header \
         states one (`Temperature: 20 °C`) and its name carries none (`…_20C.csv`); give \
         --temperatures T1,T2,… in the order of the files",
                path.display()
            ));
        }
        all = Some(match all {
            None => data,
            Some(so_far) => join(so_far, data),
        });
    }
    let mut data = all.ok_or_else(|| err!("{}: no data points", (PathBuf::new()).display()))?;
    if paths.len() > 1 {
        data.path = common_folder(paths);
    }
    Ok(data)
}

/// Refuses temperatures given (`--temperatures`) that are not one per
/// file.
pub(super) fn check_given(given: Option<&[f64]>, files: usize) -> Result<(), IoError> {
    if let Some(given) = given
        && given.len() != files
    {
        return Err(err!(
            "{given} temperatures given for {files} DMA files: give one per file, in the order of \
         the files",
            given = given.len()
        ));
    }
    Ok(())
}

/// Gives the file `data` the temperature `t` (°C) when it states none;
/// where it states one that differs, says so and keeps its own.
fn give_temperature(data: &mut DmaData, t: f64) {
    let file = &mut data.files[0];
    match file.temperature.stated() {
        _ if file.temperature == TemperatureOrigin::None => {
            for p in &mut data.points {
                p.temperature = Some(t);
            }
            file.temperature = TemperatureOrigin::Given(t);
        }
        Some(own) if own != t => data.warnings.push(format!(
            "{}: the temperature given, {t} °C, differs from the file's own ({}): the file's is used",
            file.path.display(),
            file.temperature
        )),
        _ if file.temperature == TemperatureOrigin::Column => data.warnings.push(format!(
            "{}: the file has a T column: the temperature given, {t} °C, is not used",
            file.path.display()
        )),
        _ => {}
    }
}

/// `a` followed by `b`: points, lines and files concatenated; steps kept
/// apart when both have them; a note both have said once.
pub(super) fn join(mut a: DmaData, b: DmaData) -> DmaData {
    let offset = a.points.len();
    a.steps = match (a.steps.take(), b.steps) {
        (Some(mut first), Some(second)) => {
            let next = first.iter().max().map_or(0, |m| m + 1);
            first.extend(second.iter().map(|s| s + next));
            Some(first)
        }
        _ => None,
    };
    a.points.extend(b.points);
    a.lines.extend(b.lines);
    a.files.extend(b.files.into_iter().map(|mut f| {
        f.points = f.points.start + offset..f.points.end + offset;
        f
    }));
    if a.kind != b.kind {
        a.warnings.push(format!(
            "the files hold both Young's and shear moduli ({} is {}): each converted as its \
             column names say",
            b.path.display(),
            b.kind.name()
        ));
    }
    if a.format != b.format {
        a.format = "mixed";
    }
    a.warnings.extend(b.warnings);
    for note in b.notes {
        if !a.notes.contains(&note) {
            a.notes.push(note);
        }
    }
    a
}

/// The folder holding all of `paths` (their first's parent when they
/// share none).
pub(super) fn common_folder(paths: &[PathBuf]) -> PathBuf {
    let parent = |p: &PathBuf| p.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut common = parent(&paths[0]);
    for p in &paths[1..] {
        while !p.starts_with(&common) {
            match common.parent() {
                Some(up) => common = up.to_path_buf(),
                None => return parent(&paths[0]),
            }
        }
    }
    common
}
