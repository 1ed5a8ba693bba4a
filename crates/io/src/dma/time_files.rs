//! Several relaxation or creep files read as one data set: one file per
//! isotherm, or a folder of such files, as frequency sweeps are read
//! ([`super::files`]). Each file is read alone
//! ([`RelaxationData::read_as`]), and each file's temperature comes from,
//! in order:
//! 1. its T column;
//! 2. its file name (`…_-25C.csv`, `…_293K.txt`);
//! 3. the temperatures given (`--temperatures`), one per file in the order
//!    of the files.
//!
//! Where each came from is kept ([`TemperatureOrigin`]) for the summary.
//! The points are concatenated in file order. Every file must measure the
//! same quantity (all relaxation or all creep), and no two files may lie
//! at one temperature: a run's times start again at the step, so two runs
//! are never one isotherm.

use std::path::{Path, PathBuf};

use super::files::{DmaFile, TemperatureOrigin, check_given, common_folder, expand};
use super::point::ModulusKind;
use super::relaxation::{RelaxationData, groups, is_relaxation_file};
use super::stated_temperature::in_file_name;
use crate::error::IoError;

/// A relaxation or creep data set and where each file's temperature came
/// from.
#[derive(Debug, Clone)]
pub struct TimeFiles {
    /// The points of every file, in file order (path: the one file, or
    /// the folder holding several).
    pub data: RelaxationData,
    /// Each file, its points' range in `data.points` and its
    /// temperature's origin.
    pub files: Vec<DmaFile>,
}

/// Reads `inputs` (files, or folders of files) as one relaxation or creep
/// data set: `poisson` converts shear, `kind` states a creep compliance's
/// ([`RelaxationData::read_as`]), `given` one temperature per file (°C)
/// for the files that state none.
pub fn read_time_files(
    inputs: &[PathBuf],
    poisson: f64,
    kind: Option<ModulusKind>,
    given: Option<&[f64]>,
) -> Result<TimeFiles, IoError> {
    let paths = expand(inputs)?;
    check_given(given, paths.len())?;
    let mut all: Option<TimeFiles> = None;
    for (k, path) in paths.iter().enumerate() {
        let mut data = RelaxationData::read_as(path, poisson, kind).map_err(|error| {
            // A frequency sweep among time-domain files is a mix-up, not a
            // relaxation file without its time column (looked at again
            // only on this error path).
            if k > 0 && !is_relaxation_file(path) {
                err!(
                    "{}: not relaxation or creep data (no time column), unlike {}: give \
                     frequency sweeps and time-domain files to separate runs",
                    path.display(),
                    paths[0].display()
                )
            } else {
                error
            }
        })?;
        let origin = temperature_of(&mut data, given.map(|g| g[k]));
        if paths.len() > 1 && origin == TemperatureOrigin::None {
            return Err(err!(
                "relaxation file {}: no temperature: the file has no T column and its name \
         carries none (`…_20C.csv`); give --temperatures T1,T2,… in the order of the files",
                path.display()
            ));
        }
        let file = DmaFile {
            path: path.clone(),
            points: 0..data.points.len(),
            temperature: origin,
            block: None,
        };
        all = Some(match all {
            None => TimeFiles {
                data,
                files: vec![file],
            },
            Some(so_far) => join(so_far, data, file)?,
        });
    }
    let mut read = all.ok_or_else(|| err!("no relaxation file given"))?;
    if paths.len() > 1 {
        read.data.path = common_folder(&paths);
        refuse_shared_temperatures(&read)?;
    }
    Ok(read)
}

/// Where the temperature of the file `data` comes from (module doc),
/// given to its points when it is not its T column; a temperature given
/// for a file that states its own is noted and not used.
fn temperature_of(data: &mut RelaxationData, given: Option<f64>) -> TemperatureOrigin {
    let origin = if data.points.iter().any(|p| p.temperature.is_some()) {
        TemperatureOrigin::Column
    } else if let Some(t) = in_file_name(&data.path) {
        TemperatureOrigin::FileName(t)
    } else if let Some(t) = given {
        TemperatureOrigin::Given(t)
    } else {
        return TemperatureOrigin::None;
    };
    if let Some(t) = origin.stated() {
        for p in &mut data.points {
            p.temperature = Some(t);
        }
    }
    match (given, &origin) {
        (Some(t), TemperatureOrigin::FileName(own)) if *own != t => data.notes.push(format!(
            "{}: the temperature given, {t} °C, differs from the file's own ({origin}): the \
             file's is used",
            data.path.display()
        )),
        (Some(t), TemperatureOrigin::Column) => data.notes.push(format!(
            "{}: the file has a T column: the temperature given, {t} °C, is not used",
            data.path.display()
        )),
        _ => {}
    }
    origin
}

/// `so_far` followed by the file `data`: points, lines and notes
/// concatenated; refused when the two measure different quantities.
fn join(
    mut so_far: TimeFiles,
    data: RelaxationData,
    mut file: DmaFile,
) -> Result<TimeFiles, IoError> {
    let first = &so_far.files[0].path;
    if data.quantity != so_far.data.quantity {
        return Err(err!(
            "relaxation file {}: it holds a {} run, but {} holds a {} run: read relaxation and \
             creep files apart",
            data.path.display(),
            data.quantity.name(),
            first.display(),
            so_far.data.quantity.name()
        ));
    }
    let offset = so_far.data.points.len();
    file.points = offset..offset + data.points.len();
    if data.kind != so_far.data.kind {
        so_far.data.notes.push(format!(
            "the files hold both Young's and shear data ({} is {}): each converted as its column \
             names say",
            data.path.display(),
            data.kind.name()
        ));
    }
    so_far.data.points.extend(data.points);
    so_far.data.lines.extend(data.lines);
    for note in data.notes {
        if !so_far.data.notes.contains(&note) {
            so_far.data.notes.push(note);
        }
    }
    so_far.files.push(file);
    Ok(so_far)
}

/// Refuses two files whose points form one isotherm: each run's times
/// start at its own step, so together they are no single run.
fn refuse_shared_temperatures(read: &TimeFiles) -> Result<(), IoError> {
    let file_of = |i: usize| read.files.iter().find(|f| f.points.contains(&i));
    for (temperature, indices) in groups(&read.data.points) {
        let mut from: Vec<&Path> = indices
            .iter()
            .filter_map(|&i| file_of(i).map(|f| f.path.as_path()))
            .collect();
        from.dedup();
        if let [a, b, ..] = from[..] {
            return Err(err!(
                "relaxation files {} and {}: both hold an isotherm at {temperature:.2} °C: each \
                 run's times start at its own step, so two runs at one temperature are no single \
                 isotherm; give each file its own temperature, or leave one out",
                a.display(),
                b.display()
            ));
        }
    }
    Ok(())
}
