//! Helpers shared by the end-to-end tests of the `rollfit` binary
//! (forward_cli.rs, fit_cli.rs): running it, temporary folders, reading its
//! CSV output and checking the promise of every bad-input test.
//!
//! Each test file is its own crate and uses only some of these helpers; the
//! rest would be reported as dead code in that crate.
#![allow(dead_code)]

use std::collections::BTreeMap;
use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

/// Runs the `rollfit` binary with `args`, in `dir` if given.
pub fn rollfit_in(dir: Option<&Path>, args: &[&OsStr]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_rollfit"));
    command.args(args);
    if let Some(dir) = dir {
        command.current_dir(dir);
    }
    command.output().expect("cannot start the rollfit binary")
}

/// Runs the `rollfit` binary with `args` in the current folder.
pub fn rollfit(args: &[&OsStr]) -> Output {
    rollfit_in(None, args)
}

pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Runs the `rollfit` binary with `args` and requires success; returns
/// stderr (summaries, notes and warnings).
pub fn succeed(args: &[&OsStr]) -> String {
    let out = rollfit(args);
    let stderr = text(&out.stderr);
    assert!(out.status.success(), "rollfit failed:\n{stderr}");
    stderr
}

/// Checks the promise of every bad-input test: a non-zero exit, no panic,
/// every `expected` fragment on stderr and nothing on stdout. Returns
/// stderr.
pub fn assert_failure(out: &Output, expected: &[&str]) -> String {
    let stderr = text(&out.stderr);
    assert!(
        !out.status.success(),
        "expected a failure, got success; stderr:\n{stderr}"
    );
    assert!(!stderr.contains("panicked"), "panic:\n{stderr}");
    for fragment in expected {
        assert!(
            stderr.contains(fragment),
            "stderr does not contain {fragment:?}:\n{stderr}"
        );
    }
    assert!(out.stdout.is_empty(), "stdout not empty on failure");
    stderr
}

/// A folder of its own under the system's temporary folder, removed on drop.
pub struct TempDir(PathBuf);

impl TempDir {
    /// `rollfit-<test crate>-<process>-<name>-<n>`: the test crate's name
    /// (fit-cli, forward-cli) keeps the test binaries apart.
    pub fn new(name: &str) -> TempDir {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let path = std::env::temp_dir().join(format!(
            "rollfit-{}-{}-{name}-{n}",
            env!("CARGO_CRATE_NAME").replace('_', "-"),
            std::process::id()
        ));
        let _ = fs::remove_dir_all(&path);
        fs::create_dir_all(&path).unwrap();
        TempDir(path)
    }

    pub fn write(&self, name: &str, content: &str) -> PathBuf {
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

/// A CSV of numbers: its header and rows.
pub struct Table {
    pub header: Vec<String>,
    pub rows: Vec<Vec<f64>>,
}

impl Table {
    /// Reads the CSV file at `path`, leaving out lines starting with `#`.
    pub fn read(path: &Path) -> Table {
        let content = fs::read_to_string(path).unwrap();
        let kept: Vec<&str> = content.lines().filter(|l| !l.starts_with('#')).collect();
        parse_csv(&kept.join("\n"))
    }

    pub fn column(&self, name: &str) -> Vec<f64> {
        let i = self
            .header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no column {name} in {:?}", self.header));
        self.rows.iter().map(|r| r[i]).collect()
    }
}

/// Parses CSV text: a header row, then rows of as many numbers (an empty
/// cell, a number not determined, reads as NaN; true/false as 1/0).
pub fn parse_csv(csv: &str) -> Table {
    let mut lines = csv.lines();
    let header: Vec<String> = lines
        .next()
        .expect("empty CSV")
        .split(',')
        .map(str::to_string)
        .collect();
    let rows: Vec<Vec<f64>> = lines
        .map(|l| {
            l.split(',')
                .map(|x| match x {
                    "" => f64::NAN,
                    "true" => 1.0,
                    "false" => 0.0,
                    _ => x
                        .parse::<f64>()
                        .unwrap_or_else(|_| panic!("bad number {x:?}")),
                })
                .collect()
        })
        .collect();
    for row in &rows {
        assert_eq!(row.len(), header.len());
    }
    Table { header, rows }
}

/// A small laboratory-shaped scene: the bundled example's ball and rubber
/// (data/hn-rubber.toml) at `count` speeds from 1 µm/s to 1 cm/s, anchored
/// at |E(10 rad/s)|; its fits take a fraction of a second.
pub fn small_scene(count: usize) -> String {
    format!(
        r#"[geometry]
shape = "sphere"
radius = 0.005      # m
load = 1.0          # N

[substrate]
poisson = 0.5

[contact]
size = "dynamic"

[material]
model = "havriliak-negami"
E0 = 2.0e6
E1 = 2.0e9
tau = 1.0e-3
alpha = 0.55
beta = 0.4

[sweep]
v_min = 1e-6
v_max = 1e-2
count = {count}

[fit]
E_at = {{ omega = 10.0, E = 6.26e7 }}
"#
    )
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
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
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
