//! Writing results: CSV text with full precision, written either to stdout or
//! atomically to a file; result folders replaced as a whole; the lock that
//! keeps two runs from writing one folder.
//!
//! Every temporary name is `.rollfit-<pid>-<n>.tmp` (short, so that a long
//! output name still fits the file system's 255-byte limit, and with the
//! writer's process id, so that a later run can tell a dead writer's
//! leftovers from a live one's: [`remove_stale`]).

use std::fs::{self, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use anyhow::{Context, Result, bail};

/// Formats a number so that parsing it back gives the same f64: `{:e}`
/// prints the shortest digits that round-trip, and the exponent form keeps
/// columns spanning many decades readable.
pub fn number(value: f64) -> String {
    format!("{value:e}")
}

/// CSV text (with a header row) from rows of numbers; refuses a number that
/// is not finite, naming its column and row, since no reader of the output
/// could use it.
pub fn csv_bytes(header: &[&str], rows: impl IntoIterator<Item = Vec<f64>>) -> Result<Vec<u8>> {
    csv_text_bytes(
        header,
        rows.into_iter()
            .map(|row| row.into_iter().map(number).collect()),
    )
}

/// CSV text (with a header row) from rows of cells already formatted
/// (numbers by [`number`]); refuses a cell that is NaN or ±∞.
pub fn csv_text_bytes(
    header: &[&str],
    rows: impl IntoIterator<Item = Vec<String>>,
) -> Result<Vec<u8>> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(header)?;
    for (i, row) in rows.into_iter().enumerate() {
        // [`number`] writes NaN and ±∞ so; no reader could use them.
        if let Some(k) = row
            .iter()
            .position(|cell| matches!(cell.as_str(), "NaN" | "inf" | "-inf"))
        {
            bail!(
                "the output's row {} has {} = {}: not a finite number (refused rather than \
                 written)",
                i + 1,
                header.get(k).copied().unwrap_or("?"),
                row[k]
            );
        }
        writer.write_record(row)?;
    }
    writer.into_inner().context("cannot finish the CSV text")
}

/// Writes `bytes` to stdout. A closed pipe (e.g. `rollfit forward s.toml |
/// head`) is the reader's choice, not an error.
pub fn write_stdout(bytes: &[u8]) -> Result<()> {
    let mut stdout = io::stdout().lock();
    match stdout.write_all(bytes).and_then(|()| stdout.flush()) {
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Ok(()),
        result => result.context("cannot write to stdout"),
    }
}

/// Checks that `path` can name an output file (it is not a folder).
pub fn check_target(path: &Path) -> Result<()> {
    if path.is_dir() {
        bail!(
            "output {} is a folder; give a file name for the output",
            path.display()
        );
    }
    Ok(())
}

/// Writes `bytes` to `path` so that the file is either the complete new
/// content or untouched: the text goes to a temporary file in the same
/// folder (a rename is atomic only within one file system), which is then
/// renamed into place. Creates missing parent folders.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    let parent = parent_of(path);
    fs::create_dir_all(&parent)
        .with_context(|| format!("cannot create the folder {}", parent.display()))?;
    check_target(path)?;
    if path.file_name().is_none() {
        bail!("{} does not name a file", path.display());
    }

    let (temporary, mut file) = create_temporary(&parent)?;
    let written = file
        .write_all(bytes)
        .and_then(|()| file.sync_all())
        .and_then(|()| {
            drop(file);
            fs::rename(&temporary, path)
        });
    if let Err(e) = written {
        let _ = fs::remove_file(&temporary);
        return Err(e).with_context(|| format!("cannot write {}", path.display()));
    }
    Ok(())
}

/// A new, exclusively created temporary file next to the target. The name
/// is hidden and ends in `.tmp` so that a crash leaves nothing that looks
/// like a result.
fn create_temporary(folder: &Path) -> Result<(PathBuf, fs::File)> {
    loop_temporary(folder, |candidate| {
        OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(candidate)
    })
}

/// Creates `.rollfit-<pid>-<n>.tmp` in `folder` with `make`, trying the next
/// n while the name is taken.
fn loop_temporary<T>(folder: &Path, make: impl Fn(&Path) -> io::Result<T>) -> Result<(PathBuf, T)> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let pid = std::process::id();
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let candidate = folder.join(format!("{TEMPORARY_PREFIX}{pid}-{n}.tmp"));
        match make(&candidate) {
            Ok(made) => return Ok((candidate, made)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists && n < 1000 => continue,
            Err(e) => {
                return Err(e).with_context(|| {
                    format!(
                        "cannot create a temporary file in {} (is the folder writable?)",
                        folder.display()
                    )
                });
            }
        }
    }
}

/// How every temporary name starts.
const TEMPORARY_PREFIX: &str = ".rollfit-";

/// The process id in a temporary name: `.rollfit-<pid>-<n>.tmp` (or
/// `….old.tmp`, a folder moved aside), or `.<file>.<pid>-<n>.tmp` as
/// written by rollfit 0.1.
fn temporary_pid(name: &str) -> Option<u32> {
    let rest = name.strip_prefix('.')?.strip_suffix(".tmp")?;
    let rest = rest.strip_suffix(".old").unwrap_or(rest);
    let tail = match rest.strip_prefix(&TEMPORARY_PREFIX[1..]) {
        Some(tail) => tail,
        None => rest.rsplit_once('.')?.1,
    };
    let (pid, n) = tail.split_once('-')?;
    n.parse::<u64>().ok()?;
    pid.parse().ok()
}

/// Whether process `pid` is running. Only Linux answers (from /proc);
/// elsewhere every writer counts as alive and its leftovers stay.
fn alive(pid: u32) -> bool {
    if pid == std::process::id() {
        return true;
    }
    if cfg!(target_os = "linux") {
        Path::new("/proc").join(pid.to_string()).exists()
    } else {
        true
    }
}

/// Removes the temporary files and folders that writers killed before they
/// finished left in `folder`; returns how many. A live writer's are kept.
pub fn remove_stale(folder: &Path) -> usize {
    let Ok(entries) = fs::read_dir(folder) else {
        return 0;
    };
    let mut removed = 0;
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = temporary_pid(&name.to_string_lossy()) else {
            continue;
        };
        if alive(pid) {
            continue;
        }
        let path = entry.path();
        let gone = if path.is_dir() {
            fs::remove_dir_all(&path)
        } else {
            fs::remove_file(&path)
        };
        if gone.is_ok() {
            removed += 1;
        }
    }
    removed
}

/// Files a result folder's writers own: the fit's three, the report's page,
/// pictures and comparison, and what `rollfit master` writes. A refit replaces the folder without them (the
/// report of an old fit would not describe the new one); anything else
/// found there is carried over.
fn owned_by_rollfit(name: &str) -> bool {
    matches!(
        name,
        "fit.json"
            | "modulus.csv"
            | "mu.csv"
            | "report.html"
            | "compare.json"
            | "master.csv"
            | "shift.csv"
            | "material.toml"
            | "master.json"
    ) || name.ends_with(".png")
        || name.ends_with(".svg")
}

/// Checks, before a long computation, that `dir` can be replaced by
/// [`replace_folder`]: it is a folder or absent, holds no sub-folder, and
/// its parent folder is writable (made if missing).
pub fn check_replaceable(dir: &Path) -> Result<()> {
    if dir.exists() && !dir.is_dir() {
        bail!(
            "output {} exists and is not a folder; give a folder for the results",
            dir.display()
        );
    }
    if let Ok(entries) = fs::read_dir(dir) {
        for entry in entries.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            if entry.path().is_dir() && temporary_pid(&name).is_none() {
                bail!(
                    "output {} holds the folder {name}, which rollfit did not write; give an \
                     empty folder or a previous fit's",
                    dir.display()
                );
            }
        }
    }
    let parent = parent_of(dir);
    fs::create_dir_all(&parent)
        .with_context(|| format!("cannot create the folder {}", parent.display()))?;
    let (probe, ()) = loop_temporary(&parent, |p| fs::create_dir(p))?;
    let _ = fs::remove_dir(&probe);
    Ok(())
}

fn parent_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Replaces the folder `dir` by one holding `files` (name, content) as a
/// whole: a reader sees either the previous folder or the new one, never a
/// mixture, whenever the process is killed. The files are written into a
/// temporary sibling folder (with the previous folder's files that rollfit
/// does not own, linked or copied), flushed, and swapped in: on Linux by
/// one `renameat2(RENAME_EXCHANGE)`, elsewhere (or on a file system without
/// it) by two renames, between which `dir` is briefly absent. On an error
/// the temporary folder is removed and `dir` is as it was.
pub fn replace_folder(dir: &Path, files: &[(&str, &[u8])]) -> Result<()> {
    let parent = parent_of(dir);
    fs::create_dir_all(&parent)
        .with_context(|| format!("cannot create the folder {}", parent.display()))?;
    remove_stale(&parent);
    let (stage, ()) = loop_temporary(&parent, |p| fs::create_dir(p))?;
    let result = fill_and_swap(dir, &stage, files);
    // After a swap the temporary name holds the previous folder.
    let _ = fs::remove_dir_all(&stage);
    result.with_context(|| format!("cannot write the results to {}", dir.display()))
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

/// An advisory lock on a folder, held until dropped: the lock file
/// `.rollfit-<what>.lock` in it, locked exclusively (or shared), holding
/// the holder's process id for the message of whoever finds it taken.
pub struct FolderLock {
    _file: fs::File,
}

impl FolderLock {
    /// Takes the lock `name` in `dir` (created if missing), exclusive or
    /// shared, or fails at once naming the folder and the holder.
    pub fn take(dir: &Path, name: &str, exclusive: bool) -> Result<FolderLock> {
        fs::create_dir_all(dir)
            .with_context(|| format!("cannot create the folder {}", dir.display()))?;
        let path = dir.join(name);
        let file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .with_context(|| {
                format!(
                    "cannot create the lock file {} (is the folder writable?)",
                    path.display()
                )
            })?;
        let taken = if exclusive {
            file.try_lock()
        } else {
            file.try_lock_shared()
        };
        match taken {
            Ok(()) => {}
            Err(fs::TryLockError::WouldBlock) => {
                let holder = holders(dir);
                bail!(
                    "{} is being written by another rollfit run{holder}; wait for it to finish \
                     or give another output folder",
                    dir.display()
                );
            }
            Err(fs::TryLockError::Error(e)) => {
                return Err(e).with_context(|| format!("cannot lock {}", path.display()));
            }
        }
        if exclusive {
            // The holder's pid, for the message above; a shared lock's file
            // is not ours alone to write.
            let mut handle = &file;
            let _ = handle
                .set_len(0)
                .and_then(|()| handle.write_all(std::process::id().to_string().as_bytes()));
        }
        Ok(FolderLock { _file: file })
    }
}

/// " (pid N, …)" from the lock files of `dir` that name a running process.
fn holders(dir: &Path) -> String {
    let mut pids: Vec<u32> = fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .filter(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            name.starts_with(TEMPORARY_PREFIX) && name.ends_with(".lock")
        })
        .filter_map(|e| fs::read_to_string(e.path()).ok())
        .filter_map(|text| text.trim().parse().ok())
        .filter(|&pid| pid != std::process::id() && alive(pid))
        .collect();
    pids.sort_unstable();
    pids.dedup();
    match pids.as_slice() {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_round_trip() {
        for v in [
            0.1,
            1e-8,
            10.0,
            1.0400419115259524e-3,
            123456789.123,
            f64::MIN_POSITIVE,
        ] {
            assert_eq!(number(v).parse::<f64>().unwrap(), v);
        }
        assert_eq!(number(1e-8), "1e-8");
    }

    #[test]
    fn csv_has_header_and_rows() {
        let bytes = csv_bytes(&["v", "mu"], vec![vec![1e-3, 0.5], vec![1.0, 0.25]]).unwrap();
        assert_eq!(
            String::from_utf8(bytes).unwrap(),
            "v,mu\n1e-3,5e-1\n1e0,2.5e-1\n"
        );
    }

    #[test]
    fn atomic_write_replaces_and_cleans_up() {
        let dir = std::env::temp_dir().join(format!("rollfit-output-unit-{}", std::process::id()));
        let path = dir.join("sub").join("out.csv");
        write_atomically(&path, b"first").unwrap();
        write_atomically(&path, b"second").unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"second");
        let names: Vec<_> = fs::read_dir(dir.join("sub"))
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("out.csv")]);
        assert!(write_atomically(&dir, b"x").is_err());
        fs::remove_dir_all(&dir).unwrap();
    }

    fn folder(tag: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("rollfit-output-{tag}-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_folder_is_replaced_as_a_whole() {
        let root = folder("replace");
        let dir = root.join("fit");
        replace_folder(&dir, &[("fit.json", b"1"), ("mu.csv", b"a")]).unwrap();
        fs::write(dir.join("friction.png"), b"old picture").unwrap();
        fs::write(dir.join("notes.txt"), b"mine").unwrap();
        fs::write(dir.join(".mu.csv.4194304-0.tmp"), b"left by a killed 0.1").unwrap();
        replace_folder(&dir, &[("fit.json", b"2"), ("modulus.csv", b"b")]).unwrap();
        // The report's pictures of the old fit go, the user's notes stay.
        assert_eq!(names(&dir), ["fit.json", "modulus.csv", "notes.txt"]);
        assert_eq!(fs::read(dir.join("fit.json")).unwrap(), b"2");
        assert_eq!(names(&root), ["fit"]);
        // A name near the file system's limit still leaves room for the
        // temporary one.
        let long = root.join("x".repeat(250));
        replace_folder(&long, &[("fit.json", b"3")]).unwrap();
        write_atomically(&long.join("y".repeat(250)), b"4").unwrap();
        fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn only_a_dead_writer_s_leftovers_are_removed() {
        let dir = folder("stale");
        // pid 0 is never a process of ours; 4194304 is above Linux's pid_max.
        let own = format!(".rollfit-{}-7.tmp", std::process::id());
        for name in [
            ".rollfit-4194304-0.tmp",
            ".rollfit-4194304-1.old.tmp",
            own.as_str(),
        ] {
            fs::create_dir(dir.join(name)).unwrap();
        }
        fs::write(dir.join(".mu.csv.4194304-3.tmp"), b"x").unwrap();
        fs::write(dir.join("keep.tmp"), b"x").unwrap();
        let removed = remove_stale(&dir);
        if cfg!(target_os = "linux") {
            assert_eq!(removed, 3);
            assert_eq!(names(&dir), [own.as_str(), "keep.tmp"]);
        }
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_taken_lock_is_refused_naming_the_holder() {
        let dir = folder("lock");
        let held = FolderLock::take(&dir, ".rollfit-batch.lock", true).unwrap();
        // A second open file description conflicts even within one process.
        let m = format!(
            "{:#}",
            FolderLock::take(&dir, ".rollfit-batch.lock", true)
                .err()
                .unwrap()
        );
        assert!(m.contains("is being written by another rollfit run"), "{m}");
        assert!(FolderLock::take(&dir, ".rollfit-batch.lock", false).is_err());
        drop(held);
        let a = FolderLock::take(&dir, ".rollfit-batch.lock", false).unwrap();
        let b = FolderLock::take(&dir, ".rollfit-batch.lock", false).unwrap();
        assert!(FolderLock::take(&dir, ".rollfit-batch.lock", true).is_err());
        drop((a, b));
        fs::remove_dir_all(&dir).unwrap();
    }
}
