//! The advisory lock that keeps two runs from writing one folder
//! (docs/ARCHITECTURE.md, "Data flow", `batch`).

use std::fs::{self, OpenOptions};
use std::io::Write;
use std::path::Path;

use super::dirs::create_folder;
use super::temporary::{TEMPORARY_PREFIX, alive};
use crate::error::IoError;
use crate::error::holders_note;

/// An advisory lock on a folder, held until dropped: the lock file
/// `.rollfit-<what>.lock` in it, locked exclusively (or shared), holding
/// the holder's process id for the message of whoever finds it taken.
pub struct FolderLock {
    _file: fs::File,
}

impl FolderLock {
    /// Takes the lock `name` in `dir` (created if missing), exclusive or
    /// shared, or fails at once naming the folder and the holder.
    pub fn take(dir: &Path, name: &str, exclusive: bool) -> Result<FolderLock, IoError> {
        create_folder(dir)?;
        let path = dir.join(name);
        let file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .map_err(|source| {
                err!(
                    "cannot create the lock file {} (is the folder writable?)",
                    path.display()
                )
                .system(source)
            })?;
        let taken = if exclusive {
            file.try_lock()
        } else {
            file.try_lock_shared()
        };
        match taken {
            Ok(()) => {}
            Err(fs::TryLockError::WouldBlock) => {
                return Err(err!(
                    "{} is being written by another rollfit run{}; wait for it to finish or give another \
         output folder",
                    dir.display(),
                    holders_note(&holders(dir))
                ));
            }
            Err(fs::TryLockError::Error(source)) => {
                return Err(err!("cannot lock {}", path.display()).system(source));
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

/// The running processes named by the lock files of `dir`, ascending.
fn holders(dir: &Path) -> Vec<u32> {
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
    pids
}
