//! Temporary folders, folder snapshots and the workspace's root.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// The workspace's root (this crate sits at crates/testkit).
pub fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A folder of its own under the system's temporary folder, removed on
/// drop: `rollfit-test-<process>-<name>-<n>`. The process id keeps test
/// binaries apart and the counter keeps apart the tests of one binary,
/// which run as threads of one process and may ask for the same name.
pub struct TempDir(PathBuf);

impl TempDir {
    pub fn new(name: &str) -> TempDir {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let path =
            std::env::temp_dir().join(format!("rollfit-test-{}-{name}-{n}", std::process::id()));
        let _ = fs::remove_dir_all(&path);
        fs::create_dir_all(&path).unwrap();
        TempDir(path)
    }

    /// Writes `content` to the file `name` in the folder; its path.
    pub fn write(&self, name: &str, content: impl AsRef<[u8]>) -> PathBuf {
        let path = self.0.join(name);
        fs::write(&path, content).unwrap();
        path
    }

    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

/// Every file under `path` (a file or a folder tree): relative name →
/// content; empty when absent.
pub fn snapshot(path: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    fn walk(root: &Path, at: &Path, files: &mut BTreeMap<PathBuf, Vec<u8>>) {
        if at.is_dir() {
            for entry in fs::read_dir(at).unwrap().flatten() {
                walk(root, &entry.path(), files);
            }
        } else if let Ok(bytes) = fs::read(at) {
            files.insert(at.strip_prefix(root).unwrap().to_path_buf(), bytes);
        }
    }
    let mut files = BTreeMap::new();
    walk(path, path, &mut files);
    files
}

/// Replaces the folder `to` by a copy of the folder `from`.
pub fn copy_tree(from: &Path, to: &Path) {
    let _ = fs::remove_dir_all(to);
    fs::create_dir_all(to).unwrap();
    for (name, bytes) in snapshot(from) {
        let target = to.join(name);
        fs::create_dir_all(target.parent().unwrap()).unwrap();
        fs::write(target, bytes).unwrap();
    }
}

/// A copy of the committed fit `examples/fits/<name>`'s three result
/// files in the folder `to` of `tmp`.
pub fn committed_fit_as(tmp: &TempDir, name: &str, to: &str) -> PathBuf {
    let root = workspace();
    let target = tmp.path().join(to);
    fs::create_dir_all(&target).unwrap();
    for file in ["fit.json", "mu.csv", "modulus.csv"] {
        fs::copy(
            root.join("examples/fits").join(name).join(file),
            target.join(file),
        )
        .unwrap();
    }
    target
}
