//! Temporary names beside a target, `.rollfit-<pid>-<n>.tmp`, and the
//! removal of those a killed writer left behind (docs/ARCHITECTURE.md,
//! "Data flow").

use std::fs::{self, OpenOptions};
use std::io;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::IoError;

/// How every temporary name starts.
pub(super) const TEMPORARY_PREFIX: &str = ".rollfit-";

/// A new, exclusively created temporary file next to the target. The name
/// is hidden and ends in `.tmp` so that a crash leaves nothing that looks
/// like a result.
pub(super) fn create_temporary(folder: &Path) -> Result<(PathBuf, fs::File), IoError> {
    loop_temporary(folder, |candidate| {
        OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(candidate)
    })
}

/// Creates `.rollfit-<pid>-<n>.tmp` in `folder` with `make`, trying the next
/// n while the name is taken.
pub(super) fn loop_temporary<T>(
    folder: &Path,
    make: impl Fn(&Path) -> io::Result<T>,
) -> Result<(PathBuf, T), IoError> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let pid = std::process::id();
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let candidate = folder.join(format!("{TEMPORARY_PREFIX}{pid}-{n}.tmp"));
        match make(&candidate) {
            Ok(made) => return Ok((candidate, made)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists && n < 1000 => continue,
            Err(source) => {
                return Err(err!(
                    "cannot create a temporary file in {} (is the folder writable?)",
                    folder.display()
                )
                .system(source));
            }
        }
    }
}

/// The process id in a temporary name: `.rollfit-<pid>-<n>.tmp` (or
/// `….old.tmp`, a folder moved aside), or `.<file>.<pid>-<n>.tmp` as
/// written by rollfit 0.1.
pub(super) fn temporary_pid(name: &str) -> Option<u32> {
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
pub(super) fn alive(pid: u32) -> bool {
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
