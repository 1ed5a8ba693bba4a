//! Output folders another run may not replace (docs/ARCHITECTURE.md,
//! "Contract", "Output folders and their record").

use std::path::PathBuf;

use super::parts::files_list;

/// Why a command may not write its results where it was told to.
#[derive(Debug, thiserror::Error)]
pub enum FolderError {
    /// An output folder that is the current folder or holds it.
    #[error(
        "output {} is the current folder (or holds it), which cannot be replaced while in use; \
         give a folder inside it, such as -o results",
        dir.display()
    )]
    OutputHoldsWorkingFolder { dir: PathBuf },
    /// An output folder holding another command's results.
    #[error(
        "output {} holds the results of `{found}` ({}); `{ours}` does not replace them: give \
         another folder, or --force to replace them (files rollfit did not write there stay)",
        dir.display(),
        files_list(files)
    )]
    OtherCommandsFolder {
        dir: PathBuf,
        /// The command that wrote the folder.
        found: &'static str,
        /// Its files there.
        files: Vec<String>,
        /// The command refused.
        ours: &'static str,
    },
    /// A file in an output folder, not written there by rollfit, that a
    /// command would overwrite.
    #[error(
        "output {} holds {name}, which rollfit did not write there; `{ours}` would overwrite \
         it: move it away or give another folder",
        dir.display()
    )]
    NotOurFile {
        dir: PathBuf,
        /// The file's name.
        name: String,
        /// The command refused.
        ours: &'static str,
    },
    /// An output file that another command recorded as its own.
    #[error(
        "{} is a file `{found}` wrote (its folder's record says so); give another output file",
        path.display()
    )]
    WrittenByAnother {
        path: PathBuf,
        /// The command that wrote it.
        found: &'static str,
    },
    /// An output folder holding a folder rollfit did not write.
    #[error(
        "output {} holds the folder {name}, which rollfit did not write; give an empty folder or \
         a previous fit's",
        dir.display()
    )]
    ForeignFolder {
        /// The output folder.
        dir: PathBuf,
        /// The sub-folder's name.
        name: String,
    },
}
