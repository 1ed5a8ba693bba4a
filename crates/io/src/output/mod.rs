//! Writing results to disk (docs/ARCHITECTURE.md, "Data flow"): a single
//! file atomically (write to a temporary, then rename), a result folder
//! replaced as a whole (and the record of its own files that decides
//! which files a later run replaces), and the lock that keeps two runs from writing one
//! folder.
//!
//! Every temporary name is `.rollfit-<pid>-<n>.tmp` (short, so that a long
//! output name still fits the file system's 255-byte limit, and with the
//! writer's process id, so that a later run can tell a dead writer's
//! leftovers from a live one's: [`remove_stale`]).

mod atomic;
mod content;
mod dirs;
mod folder;
mod lock;
mod record;
mod temporary;

pub use atomic::{check_target, write_atomically};
pub use content::FileContent;
pub use folder::{
    add_files, check_free_file, check_replaceable, claim_folder, replace_folder,
    replace_folder_with,
};
pub use lock::FolderLock;
pub use record::{RECORD_FILE, Writer};
pub use temporary::remove_stale;

#[cfg(test)]
mod tests;
