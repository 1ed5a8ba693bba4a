//! A result folder replaced as a whole (docs/ARCHITECTURE.md, "Data
//! flow"): the new files are written into a temporary sibling folder and
//! swapped in, so that a reader finds either the previous folder or the
//! new one. Who may replace what follows the folder's record of its own
//! files (`record.rs`).

use std::fs::{self, OpenOptions};
use std::io::{self, BufWriter};
use std::path::Path;

use super::atomic::write_atomically;
use super::content::FileContent;
use super::dirs::{create_folder, parent_of};
use super::record::{self, Occupant, RECORD_FILE, Writer};
use super::temporary::{TEMPORARY_PREFIX, loop_temporary, remove_stale, temporary_pid};
use crate::error::IoError;
use crate::error::files_list;

/// Checks, before a long computation, that `writer` may replace `dir` by
/// [`replace_folder`]: it is a folder or absent, not the current folder
/// (nor one holding it), not another command's results (unless `force`),
/// holds no file the command would write that rollfit did not write there,
/// no sub-folder, and its parent folder is writable (made if missing).
pub fn check_replaceable(dir: &Path, writer: Writer, force: bool) -> Result<(), IoError> {
    check_occupant(dir, writer, force, writer.own_files().iter().copied())?;
    let parent = parent_of(dir);
    create_folder(&parent)?;
    let (probe, ()) = loop_temporary(&parent, |p| fs::create_dir(p))?;
    let _ = fs::remove_dir(&probe);
    Ok(())
}

/// Who wrote `dir`, once it is known that `writer` may replace it (see
/// [`check_replaceable`]) with files named `names`.
fn check_occupant<'a>(
    dir: &Path,
    writer: Writer,
    force: bool,
    names: impl IntoIterator<Item = &'a str>,
) -> Result<Option<Occupant>, IoError> {
    if dir.exists() && !dir.is_dir() {
        return Err(err!(
            "output {} exists and is not a folder; give a folder for the results",
            dir.display()
        ));
    }
    if writer != Writer::Batch && holds_working_folder(dir) {
        return Err(err!(
            "output {} is the current folder (or holds it), which cannot be replaced while in use; \
         give a folder inside it, such as -o results",
            dir.display()
        ));
    }
    let occupant = Occupant::of(dir);
    if let Some(found) = occupant.as_ref().filter(|o| o.writer != writer && !force) {
        return Err(err!(
            "output {} holds the results of `{found}` ({}); `{ours}` does not replace them: give \
         another folder, or --force to replace them (files rollfit did not write there stay)",
            dir.display(),
            files_list(&found.files.clone()),
            found = found.writer.command(),
            ours = writer.command()
        ));
    }
    let owned = |name: &str| occupant.as_ref().is_some_and(|o| o.owns(name));
    for name in names {
        if dir.join(name).exists() && !owned(name) && !only_leftovers(&dir.join(name)) {
            return Err(err!(
                "output {} holds {name}, which rollfit did not write there; `{ours}` would overwrite \
         it: move it away or give another folder",
                dir.display(),
                ours = writer.command()
            ));
        }
    }
    if writer != Writer::Batch
        && let Ok(entries) = fs::read_dir(dir)
    {
        for entry in entries.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            if entry.path().is_dir() && temporary_pid(&name).is_none() && !owned(&name) {
                return Err(err!(
                    "output {} holds the folder {name}, which rollfit did not write; give an empty folder or \
         a previous fit's",
                    dir.display()
                ));
            }
        }
    }
    Ok(occupant)
}

/// Whether `path` is a folder that holds nothing but what killed runs of
/// rollfit leave (hidden `.tmp` names, removed before writing), or nothing
/// at all: no user's file is lost by writing there.
fn only_leftovers(path: &Path) -> bool {
    path.is_dir()
        && fs::read_dir(path).is_ok_and(|entries| {
            entries.flatten().all(|e| {
                let name = e.file_name();
                let name = name.to_string_lossy();
                name.starts_with('.') && name.ends_with(".tmp")
            })
        })
}

/// Whether `dir` is the current folder or one that holds it: a folder
/// cannot be swapped while it is a process's working folder ("Device or
/// resource busy"), and swapping a parent would move the user's shell into
/// the removed copy.
fn holds_working_folder(dir: &Path) -> bool {
    let here = std::env::current_dir().and_then(|d| d.canonicalize());
    match (here, dir.canonicalize()) {
        (Ok(here), Ok(target)) => here.starts_with(target),
        _ => false,
    }
}

/// Replaces the folder `dir` by one holding `files` (name, content) as a
/// whole: a reader sees either the previous folder or the new one, never a
/// mixture, whenever the process is killed. The files are written into a
/// temporary sibling folder (with the previous folder's files that rollfit
/// did not write, linked or copied, and the record of the new ones,
/// [`RECORD_FILE`]), flushed, and swapped in: on Linux by one
/// `renameat2(RENAME_EXCHANGE)`, elsewhere (or on a file system without
/// it) by two renames, between which `dir` is briefly absent. On an error
/// the temporary folder is removed and `dir` is as it was. Refused as
/// [`check_replaceable`] refuses, before anything is written.
pub fn replace_folder(
    dir: &Path,
    writer: Writer,
    force: bool,
    files: &[(&str, &[u8])],
) -> Result<(), IoError> {
    let contents: Vec<(&str, &dyn FileContent)> = files
        .iter()
        .map(|(name, bytes)| (*name, bytes as &dyn FileContent))
        .collect();
    replace_folder_with(dir, writer, force, &contents)
}

/// [`replace_folder`] with files whose content is written as it is
/// encoded ([`FileContent`]).
pub fn replace_folder_with(
    dir: &Path,
    writer: Writer,
    force: bool,
    files: &[(&str, &dyn FileContent)],
) -> Result<(), IoError> {
    let occupant = check_occupant(dir, writer, force, files.iter().map(|f| f.0))?;
    let parent = parent_of(dir);
    create_folder(&parent)?;
    remove_stale(&parent);
    let (stage, ()) = loop_temporary(&parent, |p| fs::create_dir(p))?;
    let result = fill_and_swap(dir, &stage, occupant.as_ref(), writer, files);
    // After a swap the temporary name holds the previous folder.
    let _ = fs::remove_dir_all(&stage);
    result.map_err(|source| err!("cannot write the results to {}", dir.display()).system(source))
}

/// Adds `files` to the result folder `dir` of `writer` (`rollfit report`'s
/// pictures in a fit's folder), each written atomically, and records them
/// as rollfit's: a later run of `writer` replaces them with the rest. A
/// file of that name that rollfit did not write there is refused, as is
/// another command's folder.
pub fn add_files(dir: &Path, writer: Writer, files: &[(&str, &[u8])]) -> Result<(), IoError> {
    let occupant = check_occupant(dir, writer, false, files.iter().map(|f| f.0))?;
    let mut names: Vec<String> = occupant.map(|o| o.files).unwrap_or_default();
    names.extend(files.iter().map(|f| f.0.to_string()));
    // The record first: killed before the files are in place, it names a
    // file that is not there, which harms nothing.
    write_atomically(&dir.join(RECORD_FILE), &record::encode(writer, names))?;
    for (name, bytes) in files {
        write_atomically(&dir.join(name), bytes)?;
    }
    Ok(())
}

/// Claims `dir` for `writer`, which fills it in its own time (a batch
/// writes its entries one by one and resumes): refused as
/// [`check_replaceable`] refuses; with `force`, another command's files are
/// removed; the record then names `writer` and `names` (with those of an
/// earlier run of `writer`).
pub fn claim_folder(
    dir: &Path,
    writer: Writer,
    force: bool,
    names: &[String],
) -> Result<(), IoError> {
    let occupant = check_occupant(dir, writer, force, names.iter().map(String::as_str))?;
    let mut recorded = Vec::new();
    match occupant {
        Some(o) if o.writer == writer => recorded = o.files,
        Some(o) => {
            for name in &o.files {
                let path = dir.join(name);
                let removed = if path.is_dir() {
                    fs::remove_dir_all(&path)
                } else {
                    fs::remove_file(&path)
                };
                if let Err(source) = removed.or_else(|e| match e.kind() {
                    io::ErrorKind::NotFound => Ok(()),
                    _ => Err(e),
                }) {
                    return Err(err!("cannot write {}", path.display()).system(source));
                }
            }
        }
        None => {}
    }
    recorded.extend(names.iter().cloned());
    write_atomically(&dir.join(RECORD_FILE), &record::encode(writer, recorded))
}

/// Refuses `path` as an output file of a command that keeps no folder
/// (`rollfit forward`) when it is a file another command recorded as its
/// own in its folder.
pub fn check_free_file(path: &Path) -> Result<(), IoError> {
    let Some(name) = path.file_name().map(|n| n.to_string_lossy().into_owned()) else {
        return Ok(());
    };
    match Occupant::of(&parent_of(path)) {
        Some(o) if o.owns(&name) || name == RECORD_FILE => Err(err!(
            "{} is a file `{found}` wrote (its folder's record says so); give another output file",
            path.display(),
            found = o.writer.command()
        )),
        _ => Ok(()),
    }
}

fn fill_and_swap(
    dir: &Path,
    stage: &Path,
    occupant: Option<&Occupant>,
    writer: Writer,
    files: &[(&str, &dyn FileContent)],
) -> io::Result<()> {
    if dir.is_dir() {
        for entry in fs::read_dir(dir)? {
            let entry = entry?;
            let name = entry.file_name();
            let text = name.to_string_lossy();
            let leftover = text.starts_with('.') && text.ends_with(".tmp");
            // A batch's lock belongs to the batch's folder, not to this one.
            let lock = text.starts_with(TEMPORARY_PREFIX) && text.ends_with(".lock");
            let ours = occupant.is_some_and(|o| o.owns(&text)) || text == RECORD_FILE || lock;
            if ours || leftover || !entry.path().is_file() {
                continue;
            }
            let target = stage.join(&name);
            if fs::hard_link(entry.path(), &target).is_err() {
                fs::copy(entry.path(), &target)?;
            }
        }
    }
    let record = record::encode(writer, files.iter().map(|f| f.0.to_string()));
    let record: (&str, &dyn FileContent) = (RECORD_FILE, &record);
    for (name, content) in files.iter().chain([&record]) {
        let file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(stage.join(name))?;
        let mut out = BufWriter::new(file);
        content.write_to(&mut out)?;
        out.into_inner().map_err(|e| e.into_error())?.sync_all()?;
    }
    sync_folder(stage);
    if !dir.exists() {
        match fs::rename(stage, dir) {
            Ok(()) => {
                sync_folder(&parent_of(dir));
                return Ok(());
            }
            // Made by someone else meanwhile: swap with it instead.
            Err(_) if dir.is_dir() => {}
            Err(e) => return Err(e),
        }
    }
    swap(stage, dir)?;
    sync_folder(&parent_of(dir));
    Ok(())
}

/// Exchanges the folders `a` and `b` atomically.
#[cfg(target_os = "linux")]
fn swap(a: &Path, b: &Path) -> io::Result<()> {
    use rustix::fs::{CWD, RenameFlags, renameat_with};
    match renameat_with(CWD, a, CWD, b, RenameFlags::EXCHANGE) {
        Ok(()) => Ok(()),
        // File systems without RENAME_EXCHANGE (some network ones).
        Err(rustix::io::Errno::INVAL | rustix::io::Errno::NOSYS | rustix::io::Errno::OPNOTSUPP) => {
            swap_by_renames(a, b)
        }
        Err(e) => Err(e.into()),
    }
}

#[cfg(not(target_os = "linux"))]
fn swap(a: &Path, b: &Path) -> io::Result<()> {
    swap_by_renames(a, b)
}

/// Moves `b` aside, `a` to `b`, and the old `b` to `a` (so that the caller
/// removes it under the name it made); `b` is absent between the first two
/// renames.
fn swap_by_renames(a: &Path, b: &Path) -> io::Result<()> {
    let aside = a.with_extension("old.tmp");
    fs::rename(b, &aside)?;
    if let Err(e) = fs::rename(a, b) {
        let _ = fs::rename(&aside, b);
        return Err(e);
    }
    fs::rename(&aside, a)
}

/// Flushes a folder's entries to disk (best effort: not every platform
/// opens folders as files).
fn sync_folder(dir: &Path) {
    if let Ok(handle) = fs::File::open(dir) {
        let _ = handle.sync_all();
    }
}
