//! Running a binary and checking the promise of every bad-input test. The
//! binary's path is the caller's: only the crate that builds it knows it
//! (`env!("CARGO_BIN_EXE_rollfit")` in the cli crate's tests).

use std::ffi::OsStr;
use std::path::Path;
use std::process::{Command, Output};

/// Runs the binary `exe` with `args`, in `dir` if given.
pub fn run_in(exe: &str, dir: Option<&Path>, args: &[&OsStr]) -> Output {
    let mut command = Command::new(exe);
    command.args(args);
    if let Some(dir) = dir {
        command.current_dir(dir);
    }
    command.output().expect("cannot start the binary")
}

/// Bytes as text, invalid UTF-8 replaced.
pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
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

/// Fails naming the first of `fragments` not in `text`.
pub fn assert_contains(text: &str, fragments: &[&str]) {
    for f in fragments {
        assert!(text.contains(f), "{f:?} not in:\n{text}");
    }
}
