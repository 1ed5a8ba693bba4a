//! Output folders shared between commands (docs/ARCHITECTURE.md,
//! "Contract", "Output folders"): a command run again into a folder it
//! wrote replaces its own files and keeps the user's; another command's
//! folder is refused, naming what is there and `--force`, and left as it
//! was; `--force` replaces the other command's files and keeps the user's.
//! Every pair of run kinds (fit, master on frequency sweeps, master on
//! relaxation data, batch), plus `report` and `compare` adding to a fit's
//! folder, `forward` writing beside them, and `-o .`.

use crate::common;

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Output;

use common::{TempDir, assert_failure, rollfit_in, small_scene, snapshot, text};

/// The record each result folder keeps of its own files.
const RECORD: &str = ".rollfit-files.json";

/// A user's file that no command may touch.
const PHOTO: &str = "sample-photo.png";

/// What runs into the folder.
#[derive(Debug, Clone, Copy, PartialEq)]
enum RunKind {
    Fit,
    MasterFrequency,
    MasterRelaxation,
    Batch,
}

const KINDS: [RunKind; 4] = [
    RunKind::Fit,
    RunKind::MasterFrequency,
    RunKind::MasterRelaxation,
    RunKind::Batch,
];

impl RunKind {
    /// The command line, writing to `out` (relative to the case's folder).
    fn args(self, out: &str) -> Vec<String> {
        let args: &[&str] = match self {
            RunKind::Fit => &["fit", "scene.toml", "data.csv", "-o"],
            RunKind::MasterFrequency => &["master", "dma.csv", "-o"],
            RunKind::MasterRelaxation => &["master", "relax.csv", "-o"],
            RunKind::Batch => &["batch", "manifest.toml", "-o"],
        };
        let mut args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
        args.push(out.to_string());
        args
    }

    /// The command a refusal names as the folder's writer.
    fn command(self) -> &'static str {
        match self {
            RunKind::Fit => "rollfit fit",
            RunKind::MasterFrequency | RunKind::MasterRelaxation => "rollfit master",
            RunKind::Batch => "rollfit batch",
        }
    }

    /// The files (or entry folders) the run leaves, beside the record.
    fn files(self) -> &'static [&'static str] {
        match self {
            RunKind::Fit => &["fit.json", "modulus.csv", "mu.csv"],
            RunKind::MasterFrequency => &[
                "master.csv",
                "master.json",
                "master.png",
                "master.svg",
                "material.toml",
                "modulus.csv",
                "shift.csv",
                "vgp.png",
                "vgp.svg",
            ],
            RunKind::MasterRelaxation => &[
                "master.csv",
                "master.json",
                "master.png",
                "master.svg",
                "material.toml",
                "modulus.csv",
                "relaxation.csv",
                "shift.csv",
            ],
            RunKind::Batch => &["a", "summary.csv"],
        }
    }
}

/// A relaxation file: E(t) of a standard linear solid, shifted by WLF
/// (C1 = 8.86, C2 = 101.6 K, T_ref = 20 °C), at five temperatures, 21
/// times over 0.1 … 1000 s each.
fn relaxation_csv() -> String {
    let mut out = String::from("T,t,E_relax\n");
    for t in [0.0, 10.0, 20.0, 30.0, 40.0] {
        let log_a = -8.86 * (t - 20.0) / (101.6 + t - 20.0);
        for j in 0..=20 {
            let time = 10f64.powf(-1.0 + j as f64 / 5.0);
            let reduced = time / 10f64.powf(log_a);
            // A broad transition: a sum of relaxations a decade apart.
            let e = 1e6
                + (-4..=6)
                    .map(|k| 3e7 * (-reduced / 10f64.powi(k)).exp())
                    .sum::<f64>();
            out += &format!("{t},{time:e},{e:e}\n");
        }
    }
    out
}

/// The inputs of every run kind in `dir`: scene.toml and data.csv (a
/// noisy forward run), dma.csv (isotherms), sweep.csv (one DMA sweep, for
/// `compare`), relax.csv, manifest.toml.
fn inputs(dir: &Path) {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    fs::write(dir.join("scene.toml"), small_scene(8)).unwrap();
    fs::copy(
        repo.join("data/hn-rubber-dma-isotherms.csv"),
        dir.join("dma.csv"),
    )
    .unwrap();
    fs::copy(repo.join("data/hn-rubber-dma.csv"), dir.join("sweep.csv")).unwrap();
    fs::write(dir.join("relax.csv"), relaxation_csv()).unwrap();
    fs::write(
        dir.join("manifest.toml"),
        "[[entry]]\nname = \"a\"\nscene = \"scene.toml\"\ndata = \"data.csv\"\n",
    )
    .unwrap();
    let made = run(
        dir,
        &[
            "forward",
            "scene.toml",
            "--noise",
            "0.02",
            "--seed",
            "3",
            "-o",
            "data.csv",
        ],
    );
    assert!(made.status.success(), "{}", text(&made.stderr));
}

fn run<S: AsRef<OsStr>>(dir: &Path, args: &[S]) -> Output {
    let args: Vec<&OsStr> = args.iter().map(AsRef::as_ref).collect();
    rollfit_in(Some(dir), &args)
}

fn ok(dir: &Path, args: &[String]) {
    let out = run(dir, args);
    assert!(
        out.status.success(),
        "{args:?} failed:\n{}",
        text(&out.stderr)
    );
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// What `kind` leaves in a folder that also holds the user's photo.
fn expected(kind: RunKind) -> Vec<String> {
    let mut names: Vec<String> = kind.files().iter().map(|s| s.to_string()).collect();
    names.extend([RECORD.to_string(), PHOTO.to_string()]);
    if kind == RunKind::Batch {
        // The batch's lock, kept for the next run to take.
        names.push(".rollfit-batch.lock".into());
    }
    names.sort();
    names
}

/// Every pair of run kinds into one folder that also holds the user's
/// photo: the same command replaces its own files (master on relaxation
/// data then frequency sweeps, or twice on relaxation data, with no stale
/// relaxation.csv and no "File exists"); another command is refused with
/// the folder unchanged, then `--force` replaces it. The photo stays.
#[test]
fn a_rerun_into_the_same_folder_for_every_pair_of_run_kinds() {
    let tmp = TempDir::new("pairs");
    inputs(tmp.path());
    for first in KINDS {
        for second in KINDS {
            let out = format!("out-{first:?}-{second:?}");
            let dir = tmp.path().join(&out);
            fs::create_dir_all(&dir).unwrap();
            fs::write(dir.join(PHOTO), b"the user's photo").unwrap();
            ok(tmp.path(), &first.args(&out));
            assert_eq!(names(&dir), expected(first), "{first:?}");
            let same = first.command() == second.command();
            let output = run(tmp.path(), &second.args(&out));
            if same {
                assert!(
                    output.status.success(),
                    "{first:?} then {second:?}:\n{}",
                    text(&output.stderr)
                );
            } else {
                let before = snapshot(&dir);
                let stderr = assert_failure(
                    &output,
                    &[
                        &format!("holds the results of `{}`", first.command()),
                        first.files()[0],
                        "--force to replace them",
                    ],
                );
                assert_eq!(
                    snapshot(&dir),
                    before,
                    "{first:?} then {second:?}: {stderr}"
                );
                let mut forced = second.args(&out);
                forced.push("--force".into());
                ok(tmp.path(), &forced);
            }
            assert_eq!(names(&dir), expected(second), "{first:?} then {second:?}");
            assert_eq!(fs::read(dir.join(PHOTO)).unwrap(), b"the user's photo");
        }
    }
}

/// `report` and `compare` add their files to a fit's folder and the
/// record; a refit removes them (they described the old fit) and keeps the
/// user's photo. A user's own file under a name the report writes is never
/// overwritten.
#[test]
fn a_refit_removes_the_report_and_keeps_the_user_s_files() {
    let tmp = TempDir::new("report");
    inputs(tmp.path());
    let dir = tmp.path().join("out");
    ok(tmp.path(), &RunKind::Fit.args("out"));
    fs::write(dir.join(PHOTO), b"photo").unwrap();
    ok(tmp.path(), &["report".into(), "out".into()]);
    ok(
        tmp.path(),
        &["compare".into(), "out".into(), "sweep.csv".into()],
    );
    let record = fs::read_to_string(dir.join(RECORD)).unwrap();
    for name in ["report.html", "friction.png", "compare.json", "fit.json"] {
        assert!(record.contains(&format!("\"{name}\"")), "{record}");
    }
    assert!(!record.contains(PHOTO), "{record}");
    ok(tmp.path(), &RunKind::Fit.args("out"));
    assert_eq!(names(&dir), expected(RunKind::Fit));

    // A picture of the user's named as the report's: refused, kept.
    fs::write(dir.join("friction.png"), b"mine").unwrap();
    let output = run(tmp.path(), &["report", "out"]);
    assert_failure(
        &output,
        &[
            "holds friction.png, which rollfit did not write there",
            "move it away",
        ],
    );
    assert_eq!(fs::read(dir.join("friction.png")).unwrap(), b"mine");
}

/// A folder an older rollfit wrote (no record) is judged by its fixed
/// names: a refit replaces them and keeps a user's `*.png`; `master` is
/// refused naming the fit.
#[test]
fn a_folder_without_a_record_is_judged_by_its_fixed_names() {
    let tmp = TempDir::new("legacy");
    inputs(tmp.path());
    let dir = tmp.path().join("out");
    ok(tmp.path(), &RunKind::Fit.args("out"));
    ok(tmp.path(), &["report".into(), "out".into()]);
    ok(
        tmp.path(),
        &["compare".into(), "out".into(), "sweep.csv".into()],
    );
    fs::remove_file(dir.join(RECORD)).unwrap();
    fs::write(dir.join(PHOTO), b"photo").unwrap();
    let output = run(tmp.path(), &RunKind::MasterFrequency.args("out"));
    assert_failure(
        &output,
        &[
            "holds the results of `rollfit fit` (compare.json",
            "fit.json",
        ],
    );
    ok(tmp.path(), &RunKind::Fit.args("out"));
    assert_eq!(names(&dir), expected(RunKind::Fit));
}

/// `forward -o` naming a file another command recorded is refused before
/// the computation; beside it, a new name is fine.
#[test]
fn forward_never_overwrites_a_result_folder_s_file() {
    let tmp = TempDir::new("forward");
    inputs(tmp.path());
    ok(tmp.path(), &RunKind::Fit.args("out"));
    let before = snapshot(&tmp.path().join("out"));
    let output = run(tmp.path(), &["forward", "scene.toml", "-o", "out/mu.csv"]);
    assert_failure(
        &output,
        &[
            "out/mu.csv is a file `rollfit fit` wrote",
            "give another output file",
        ],
    );
    assert_eq!(snapshot(&tmp.path().join("out")), before);
    ok(
        tmp.path(),
        &[
            "forward".into(),
            "scene.toml".into(),
            "-o".into(),
            "out/curve.csv".into(),
        ],
    );
}

/// `-o .` (the current folder) and a folder holding it are refused with
/// what to do, not "Device or resource busy".
#[test]
fn the_current_folder_as_output_is_refused_with_what_to_do() {
    let tmp = TempDir::new("dot");
    inputs(tmp.path());
    let sub: PathBuf = tmp.path().join("work");
    fs::create_dir_all(&sub).unwrap();
    for name in ["scene.toml", "data.csv", "dma.csv"] {
        fs::copy(tmp.path().join(name), sub.join(name)).unwrap();
    }
    for args in [
        RunKind::Fit.args("."),
        RunKind::MasterFrequency.args("."),
        RunKind::Fit.args(".."),
    ] {
        let output = run(&sub, &args);
        let stderr = assert_failure(
            &output,
            &["is the current folder (or holds it)", "such as -o results"],
        );
        assert!(!stderr.contains("resource busy"), "{stderr}");
    }
    assert_eq!(names(&sub), ["data.csv", "dma.csv", "scene.toml"]);
}
