//! A result folder replaced as a whole (docs/ARCHITECTURE.md, "Data
//! flow"): the new files are written into a temporary sibling folder and
//! swapped in, so that a reader finds either the previous folder or the
//! new one.

use std::fs::{self, OpenOptions};
use std::io::{self, Write};
use std::path::Path;

use super::dirs::{create_folder, parent_of};
use super::temporary::{loop_temporary, remove_stale, temporary_pid};
use crate::error::IoError;
use crate::fit_dir::columns::{FIT_JSON, MODULUS_CSV, MU_CSV};

/// Files a result folder's writers own: the fit's three, the report's page,
/// pictures and comparison, and what `rollfit master` writes. A refit
/// replaces the folder without them (the report of an old fit would not
/// describe the new one); anything else found there is carried over.
fn owned_by_rollfit(name: &str) -> bool {
    [FIT_JSON, MODULUS_CSV, MU_CSV].contains(&name)
        || matches!(
            name,
            "report.html"
                | "compare.json"
                | "master.csv"
                | "shift.csv"
                | "material.toml"
                | "master.json"
        )
        || name.ends_with(".png")
        || name.ends_with(".svg")
}

/// Checks, before a long computation, that `dir` can be replaced by
/// [`replace_folder`]: it is a folder or absent, holds no sub-folder, and
/// its parent folder is writable (made if missing).
pub fn check_replaceable(dir: &Path) -> Result<(), IoError> {
    if dir.exists() && !dir.is_dir() {
        return Err(IoError::OutputNotFolder {
            dir: dir.to_path_buf(),
        });
    }
    if let Ok(entries) = fs::read_dir(dir) {
        for entry in entries.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            if entry.path().is_dir() && temporary_pid(&name).is_none() {
                return Err(IoError::ForeignFolder {
                    dir: dir.to_path_buf(),
                    name,
                });
            }
        }
    }
    let parent = parent_of(dir);
    create_folder(&parent)?;
    let (probe, ()) = loop_temporary(&parent, |p| fs::create_dir(p))?;
    let _ = fs::remove_dir(&probe);
    Ok(())
}

/// Replaces the folder `dir` by one holding `files` (name, content) as a
/// whole: a reader sees either the previous folder or the new one, never a
/// mixture, whenever the process is killed. The files are written into a
/// temporary sibling folder (with the previous folder's files that rollfit
/// does not own, linked or copied), flushed, and swapped in: on Linux by
/// one `renameat2(RENAME_EXCHANGE)`, elsewhere (or on a file system without
/// it) by two renames, between which `dir` is briefly absent. On an error
/// the temporary folder is removed and `dir` is as it was.
pub fn replace_folder(dir: &Path, files: &[(&str, &[u8])]) -> Result<(), IoError> {
    let parent = parent_of(dir);
    create_folder(&parent)?;
    remove_stale(&parent);
    let (stage, ()) = loop_temporary(&parent, |p| fs::create_dir(p))?;
    let result = fill_and_swap(dir, &stage, files);
    // After a swap the temporary name holds the previous folder.
    let _ = fs::remove_dir_all(&stage);
    result.map_err(|source| IoError::WriteResults {
        dir: dir.to_path_buf(),
        source,
    })
}

fn fill_and_swap(dir: &Path, stage: &Path, files: &[(&str, &[u8])]) -> io::Result<()> {
    if dir.is_dir() {
        for entry in fs::read_dir(dir)? {
            let entry = entry?;
            let name = entry.file_name();
            let text = name.to_string_lossy();
            let leftover = text.starts_with('.') && text.ends_with(".tmp");
            if owned_by_rollfit(&text) || leftover || !entry.path().is_file() {
                continue;
            }
            let target = stage.join(&name);
            if fs::hard_link(entry.path(), &target).is_err() {
                fs::copy(entry.path(), &target)?;
            }
        }
    }
    for (name, bytes) in files {
        let mut file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(stage.join(name))?;
        file.write_all(bytes)?;
        file.sync_all()?;
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
