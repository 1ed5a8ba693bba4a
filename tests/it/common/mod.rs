//! Helpers of the end-to-end tests that need the `rollfit` binary's path
//! (known only to this crate's tests, `CARGO_BIN_EXE_rollfit`), and the
//! scene most of them start from. The shared fixtures (temporary folders,
//! CSV tables, the promise of a refusal) are rollfit-testkit's, named here
//! once so that every module says `common::TempDir`.

use std::ffi::OsStr;
use std::path::Path;
use std::process::Output;

pub use rollfit_testkit::csv::{Table, parse_csv};
pub use rollfit_testkit::files::{TempDir, committed_fit_as, copy_tree, snapshot};
pub use rollfit_testkit::run::{assert_failure, text};

/// Runs the `rollfit` binary with `args`, in `dir` if given.
pub fn rollfit_in(dir: Option<&Path>, args: &[&OsStr]) -> Output {
    rollfit_testkit::run::run_in(env!("CARGO_BIN_EXE_rollfit"), dir, args)
}

/// Runs the `rollfit` binary with `args` in the current folder.
pub fn rollfit(args: &[&OsStr]) -> Output {
    rollfit_in(None, args)
}

/// Runs the `rollfit` binary with `args` and requires success; returns
/// stderr (summaries, notes and warnings).
pub fn succeed(args: &[&OsStr]) -> String {
    let out = rollfit(args);
    let stderr = text(&out.stderr);
    assert!(out.status.success(), "rollfit failed:\n{stderr}");
    stderr
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
