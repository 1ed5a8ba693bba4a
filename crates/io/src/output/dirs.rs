//! The folders outputs go into: the folder a path is in, made when missing.

use std::path::{Path, PathBuf};

use crate::error::IoError;

/// The folder `path` is in (`.` for a bare name).
pub(super) fn parent_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Makes `folder` and its missing parents.
pub(super) fn create_folder(folder: &Path) -> Result<(), IoError> {
    std::fs::create_dir_all(folder)
        .map_err(|source| err!("cannot create the folder {}", folder.display()).system(source))
}
