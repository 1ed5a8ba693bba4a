//! One output file written atomically: the complete new content or the
//! file untouched (docs/ARCHITECTURE.md, "Data flow").

use std::fs;
use std::io::Write;
use std::path::Path;

use super::dirs::{create_folder, parent_of};
use super::temporary::create_temporary;
use crate::error::IoError;

/// Checks that `path` can name an output file (it is not a folder).
pub fn check_target(path: &Path) -> Result<(), IoError> {
    if path.is_dir() {
        return Err(err!(
            "output {} is a folder; give a file name for the output",
            path.display()
        ));
    }
    Ok(())
}

/// Writes `bytes` to `path` so that the file is either the complete new
/// content or untouched: the text goes to a temporary file in the same
/// folder (a rename is atomic only within one file system), which is then
/// renamed into place. Creates missing parent folders.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), IoError> {
    let parent = parent_of(path);
    create_folder(&parent)?;
    check_target(path)?;
    if path.file_name().is_none() {
        return Err(err!("{} does not name a file", path.display()));
    }

    let (temporary, mut file) = create_temporary(&parent)?;
    let written = file
        .write_all(bytes)
        .and_then(|()| file.sync_all())
        .and_then(|()| {
            drop(file);
            fs::rename(&temporary, path)
        });
    if let Err(source) = written {
        let _ = fs::remove_file(&temporary);
        return Err(err!("cannot write {}", path.display()).system(source));
    }
    Ok(())
}
