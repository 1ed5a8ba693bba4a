//! Fault tests: `rollfit fit` and `rollfit batch` killed with
//! SIGKILL at random moments (fixed seeds), 50 kills in all. After each
//! kill, every result folder must be either the previous complete result or
//! the new complete one, never a mixture; a resumed batch must equal an
//! uninterrupted one bit for bit (up to the wall times that fit.json
//! records); and what the killed runs left behind must be gone after the
//! next run.

use crate::common;

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde_json::Value;

use common::{TempDir, copy_tree, small_scene, snapshot};

fn rollfit(dir: &Path) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_rollfit"));
    command
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    command
}

/// Runs rollfit to the end; panics with its stderr unless it succeeds.
fn run_ok(dir: &Path, args: &[&str]) -> Duration {
    let start = Instant::now();
    let out = rollfit(dir).args(args).output().unwrap();
    assert!(
        out.status.success(),
        "rollfit {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    start.elapsed()
}

/// Starts rollfit and kills it (SIGKILL) after `after`, or lets it end.
fn run_killed(dir: &Path, args: &[&str], after: Duration) -> bool {
    let mut child = rollfit(dir).args(args).spawn().unwrap();
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            return false;
        }
        if start.elapsed() >= after {
            child.kill().unwrap();
            child.wait().unwrap();
            return true;
        }
        std::thread::sleep(Duration::from_micros(200));
    }
}

/// fit.json without the wall times (of the fit and of each run), which no
/// two runs share.
fn without_times(bytes: &[u8]) -> Value {
    fn strip(value: &mut Value) {
        match value {
            Value::Object(map) => {
                map.remove("wall_time_s");
                map.values_mut().for_each(strip);
            }
            Value::Array(items) => items.iter_mut().for_each(strip),
            _ => {}
        }
    }
    let mut value: Value = serde_json::from_slice(bytes).expect("fit.json is JSON");
    strip(&mut value);
    value
}

/// Whether two result folders hold the same result: the same files, equal
/// byte for byte but for fit.json's wall times.
fn same_result(a: &BTreeMap<PathBuf, Vec<u8>>, b: &BTreeMap<PathBuf, Vec<u8>>) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|((na, ca), (nb, cb))| {
            na == nb
                && if na.as_os_str() == "fit.json" {
                    without_times(ca) == without_times(cb)
                } else {
                    ca == cb
                }
        })
}

/// Temporary files and folders rollfit left in `dir` (not the lock).
fn leftovers(dir: &Path) -> Vec<String> {
    fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.') && n.ends_with(".tmp"))
        .collect()
}

fn write_inputs(dir: &Path, entries: usize) {
    fs::write(dir.join("scene.toml"), small_scene(12)).unwrap();
    for seed in 1..=3 {
        run_ok(
            dir,
            &[
                "forward",
                "scene.toml",
                "--noise",
                "0.02",
                "--seed",
                &seed.to_string(),
                "-o",
                &format!("data{seed}.csv"),
            ],
        );
    }
    let mut manifest = String::new();
    for i in 0..entries {
        manifest += &format!(
            "[[entry]]\nname = \"e{i}\"\nscene = \"scene.toml\"\ndata = \"data{}.csv\"\n\n",
            1 + i % 3
        );
    }
    fs::write(dir.join("manifest.toml"), manifest).unwrap();
}

/// 30 kills of a refit: the folder holds the previous fit (of data1.csv)
/// and the killed run fits data2.csv into it.
#[test]
fn a_killed_fit_leaves_the_previous_or_the_new_result() {
    let temp = TempDir::new("kill-fit");
    let dir = temp.path();
    write_inputs(dir, 0);
    run_ok(dir, &["fit", "scene.toml", "data1.csv", "-o", "previous"]);
    let duration = run_ok(dir, &["fit", "scene.toml", "data2.csv", "-o", "new"]);
    let previous = snapshot(&dir.join("previous"));
    let new = snapshot(&dir.join("new"));
    assert!(!same_result(&previous, &new));
    // Deterministic: the same fit again gives the same files.
    run_ok(dir, &["fit", "scene.toml", "data2.csv", "-o", "again"]);
    assert!(same_result(&snapshot(&dir.join("again")), &new));

    let mut rng = ChaCha8Rng::seed_from_u64(14);
    let (mut kept_previous, mut got_new) = (0, 0);
    for kill in 0..30 {
        copy_tree(&dir.join("previous"), &dir.join("out"));
        // Up to 10 % past the usual end, so that some kills land in the
        // writing.
        let after = duration.mul_f64(rng.random_range(0.0..1.1));
        let killed = run_killed(dir, &["fit", "scene.toml", "data2.csv", "-o", "out"], after);
        let now = snapshot(&dir.join("out"));
        if same_result(&now, &previous) {
            kept_previous += 1;
        } else if same_result(&now, &new) {
            got_new += 1;
        } else {
            panic!(
                "kill {kill} after {after:?} (killed: {killed}): out holds neither result: {:?}",
                now.keys().collect::<Vec<_>>()
            );
        }
    }
    eprintln!("30 kills: {kept_previous} left the previous result, {got_new} the new one");
    // The next run removes what the killed ones left.
    run_ok(dir, &["fit", "scene.toml", "data2.csv", "-o", "out"]);
    assert_eq!(leftovers(dir), Vec::<String>::new());
    assert!(same_result(&snapshot(&dir.join("out")), &new));
}

/// 20 kills of a batch of six entries, each followed by a resume: every
/// entry folder is complete or absent after the kill, and the resumed batch
/// equals an uninterrupted one.
#[test]
fn a_killed_batch_resumes_to_the_uninterrupted_result() {
    let temp = TempDir::new("kill-batch");
    let dir = temp.path();
    write_inputs(dir, 6);
    let duration = run_ok(
        dir,
        &["batch", "manifest.toml", "-o", "reference", "--jobs", "2"],
    );
    let entries: Vec<String> = (0..6).map(|i| format!("e{i}")).collect();
    let reference: Vec<_> = entries
        .iter()
        .map(|e| snapshot(&dir.join("reference").join(e)))
        .collect();

    let mut rng = ChaCha8Rng::seed_from_u64(15);
    let mut finished_before_resume = 0;
    for kill in 0..20 {
        let out = dir.join("out");
        let _ = fs::remove_dir_all(&out);
        let after = duration.mul_f64(rng.random_range(0.0..1.0));
        run_killed(
            dir,
            &["batch", "manifest.toml", "-o", "out", "--jobs", "2"],
            after,
        );
        for (entry, expected) in entries.iter().zip(&reference) {
            let folder = out.join(entry);
            if folder.exists() {
                let now = snapshot(&folder);
                assert!(
                    same_result(&now, expected),
                    "kill {kill} after {after:?}: entry {entry} is not its complete result: {:?}",
                    now.keys().collect::<Vec<_>>()
                );
                finished_before_resume += 1;
            }
        }
        run_ok(dir, &["batch", "manifest.toml", "-o", "out", "--jobs", "2"]);
        for (entry, expected) in entries.iter().zip(&reference) {
            assert!(
                same_result(&snapshot(&out.join(entry)), expected),
                "kill {kill}: the resumed entry {entry} differs from the uninterrupted batch's"
            );
            assert_eq!(leftovers(&out.join(entry)), Vec::<String>::new());
        }
        assert_eq!(leftovers(&out), Vec::<String>::new(), "kill {kill}");
    }
    eprintln!(
        "20 kills: {finished_before_resume} of {} entries were complete at the kill",
        20 * entries.len()
    );
}
