//! End-to-end tests of the joint fit of DMA isotherms and rolling friction
//! through the command line: `rollfit fit --dma`, a scene's
//! `[fit] dma`, the joint settings' flags and a batch entry's `dma`. The
//! data are the bundled hn-rubber temperature set and the DMA isotherms of
//! the same truth (data/README.md); each joint fit takes about a second.
//!
//! Every bad-input test checks the same promise: a non-zero exit, an error
//! on stderr naming the file and line or the key, no panic, and no output
//! folder.

use crate::common;

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Output;

use common::{TempDir, assert_failure, rollfit_in, text};

/// The repository's data folder.
fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data")
}

/// The rolling temperature set's scene, the DMA file's line at `[fit]`
/// added when `dma` is given.
fn scene_text(dma: Option<&str>) -> String {
    let scene = fs::read_to_string(data().join("hn-rubber-tset.toml")).unwrap();
    match dma {
        Some(file) => format!("{scene}dma = \"{file}\"\n"),
        None => scene,
    }
}

/// Runs `rollfit ARGS` in `dir`.
fn run_in(dir: &Path, args: &[&str]) -> Output {
    let args: Vec<&OsStr> = args.iter().map(OsStr::new).collect();
    rollfit_in(Some(dir), &args)
}

/// Runs `rollfit fit SCENE tset.csv -o out EXTRA..` in `dir`.
fn fit_in(dir: &Path, scene: &str, extra: &[&str]) -> Output {
    let mut args = vec!["fit", scene, "tset.csv", "-o", "out"];
    args.extend(extra);
    run_in(dir, &args)
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&fs::read_to_string(path).unwrap()).unwrap()
}

/// A temporary folder holding the bundled rolling data (tset.csv) and DMA
/// isotherms (dma.csv).
fn folder(name: &str) -> TempDir {
    let dir = TempDir::new(name);
    for (from, to) in [
        ("hn-rubber-tset.csv", "tset.csv"),
        ("hn-rubber-dma-isotherms.csv", "dma.csv"),
    ] {
        fs::copy(data().join(from), dir.path().join(to)).unwrap();
    }
    dir
}

/// fit.json's `joint` record, checked for what every joint fit writes.
fn joint_record(out: &Path) -> serde_json::Value {
    let report = json(&out.join("fit.json"));
    let joint = report["joint"].clone();
    assert!(joint.is_object(), "fit.json has no joint record");
    assert_eq!(joint["dma_points"], 117);
    assert!(joint["rolling_points"].as_u64().unwrap() > 0);
    for key in ["rolling_joint", "dma_joint", "rolling_alone", "dma_alone"] {
        assert!(joint["chi2"][key].as_f64().unwrap() > 0.0, "chi2.{key}");
    }
    assert!(joint["compatibility"]["verdict"].is_string());
    assert_eq!(joint["dma"].as_array().unwrap().len(), 117);
    joint
}

/// `--dma` relative to the current folder makes the fit a joint one:
/// fit.json's `joint` record, and the summary's block about the parts.
#[test]
fn dma_flag_makes_a_joint_fit() {
    let dir = folder("flag");
    dir.write("scene.toml", scene_text(None));
    let out = fit_in(dir.path(), "scene.toml", &["--dma", "dma.csv"]);
    let stderr = text(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    for fragment in [
        "joint fit with DMA file dma.csv (117 DMA points",
        "χ² rolling",
        "χ² DMA",
        "compatible",
        "shear moduli G′, G″ converted",
    ] {
        assert!(stderr.contains(fragment), "{fragment:?} in {stderr}");
    }
    let joint = joint_record(&dir.path().join("out"));
    assert_eq!(joint["dma_source"], "dma.csv");
    assert_eq!(joint["compatibility"]["compatible"], true);
    assert!(joint.get("friction_factor").is_none(), "κ = 1 by default");
}

/// `[fit] dma` is relative to the scene file's folder, wherever the command
/// runs; `--friction-factor free` fits κ and the summary prints it.
#[test]
fn scene_dma_is_relative_to_the_scene_and_kappa_is_fitted() {
    let dir = folder("scene");
    let sub = dir.path().join("scenes");
    fs::create_dir(&sub).unwrap();
    fs::rename(dir.path().join("dma.csv"), sub.join("dma.csv")).unwrap();
    fs::write(sub.join("scene.toml"), scene_text(Some("dma.csv"))).unwrap();
    let out = fit_in(
        dir.path(),
        "scenes/scene.toml",
        &["--friction-factor", "free"],
    );
    let stderr = text(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(stderr.contains("  friction factor: κ = "), "{stderr}");
    let joint = joint_record(&dir.path().join("out"));
    let source = joint["dma_source"].as_str().unwrap();
    assert_eq!(Path::new(source), Path::new("scenes").join("dma.csv"));
    let kappa = joint["friction_factor"]["value"].as_f64().unwrap();
    assert!((kappa - 1.0).abs() < 0.1, "κ = {kappa}");
}

/// A DMA file that does not exist: the error names it, nothing is written.
#[test]
fn a_missing_dma_file_is_named() {
    let dir = folder("missing");
    dir.write("scene.toml", scene_text(Some("absent.csv")));
    let out = fit_in(dir.path(), "scene.toml", &[]);
    assert_failure(&out, &["DMA file absent.csv does not exist", "scene file"]);
    let out = fit_in(dir.path(), "scene.toml", &["--dma", "gone.csv"]);
    let stderr = assert_failure(&out, &["DMA file gone.csv does not exist", "--dma"]);
    assert!(!stderr.contains("absent.csv"), "--dma overrides: {stderr}");
    assert!(!dir.path().join("out").exists());
}

/// A bad point is named by file and line: one the DMA reader refuses (a
/// negative modulus) and one the joint fit refuses (E′ below 1 Pa).
#[test]
fn a_bad_dma_point_names_file_and_line() {
    let dir = folder("bad-point");
    dir.write("scene.toml", scene_text(None));
    let good = fs::read_to_string(dir.path().join("dma.csv")).unwrap();
    let lines: Vec<&str> = good.lines().collect();
    // The 8th line is a data row: f,G_storage,G_loss,T.
    let header = lines.iter().position(|l| l.starts_with("f,")).unwrap();
    let at = header + 3;
    for (name, storage, fragments) in [
        ("negative.csv", "-5e5", &["negative.csv", "line"][..]),
        ("kilopascal.csv", "0.2", &["kilopascal.csv", "E′"][..]),
    ] {
        let mut fields: Vec<&str> = lines[at].split(',').collect();
        fields[1] = storage;
        let row = fields.join(",");
        let mut edited = lines.clone();
        edited[at] = &row;
        dir.write(name, &(edited.join("\n") + "\n"));
        let out = fit_in(dir.path(), "scene.toml", &["--dma", name]);
        let stderr = assert_failure(&out, fragments);
        assert!(stderr.contains(&format!("line {}", at + 1)), "{stderr}");
        assert!(!dir.path().join("out").exists());
    }
}

/// A DMA isotherm whose shift neither part determines (a flat isotherm at
/// 200 °C, far above the rolling temperatures, overlapping no other
/// isotherm) is the DMA file's problem: the message names that file and
/// the temperature, not the rolling data's file; nothing is written. The
/// isotherms without it are fitted, and the summary says what the DMA part
/// alone determines.
#[test]
fn a_shift_neither_part_determines_names_the_dma_file() {
    let dir = folder("undetermined");
    dir.write("scene.toml", scene_text(None));
    let mut far = fs::read_to_string(dir.path().join("dma.csv")).unwrap();
    for f in ["0.1", "0.316228", "1", "3.16228", "10", "31.6228", "100"] {
        far += &format!("{f},1e6,1e4,200\n");
    }
    dir.write("far.csv", &far);
    let out = fit_in(dir.path(), "scene.toml", &["--dma", "far.csv"]);
    let stderr = assert_failure(&out, &["DMA file far.csv", "200 °C", "neither part"]);
    assert!(!stderr.contains("data file tset.csv"), "{stderr}");
    assert!(!dir.path().join("out").exists());
    let out = fit_in(dir.path(), "scene.toml", &["--dma", "dma.csv"]);
    let stderr = text(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("DMA part alone: the DMA isotherms alone determine every shift"),
        "{stderr}"
    );
    let joint = joint_record(&dir.path().join("out"));
    let shifts = joint["dma_alone"]["shifts"].as_array().unwrap();
    assert_eq!(shifts.len(), 9);
    assert!(shifts.iter().all(|s| s["determined"] == true), "{shifts:?}");
}

/// The settings only a joint fit reads are refused without DMA data,
/// naming the flag.
#[test]
fn joint_settings_without_dma_name_the_key() {
    let dir = folder("no-dma");
    dir.write("scene.toml", scene_text(None));
    for (flag, value, key) in [
        ("--friction-factor", "free", "friction_factor"),
        ("--dma-sigma", "0.01", "dma_sigma"),
    ] {
        let out = fit_in(dir.path(), "scene.toml", &[flag, value]);
        assert_failure(
            &out,
            &[&format!("command line: {flag}"), &format!("`{key}`"), "DMA"],
        );
        assert!(!dir.path().join("out").exists());
    }
    let out = run_in(
        dir.path(),
        &[
            "fit",
            "scene.toml",
            "tset.csv",
            "--friction-factor",
            "kappa",
        ],
    );
    assert_failure(&out, &["--friction-factor", "\"kappa\""]);
}

/// A batch entry with `dma` (relative to the manifest) is a joint fit; an
/// entry without it is not, and a missing DMA file is refused before any
/// fit runs, naming the entry and the line.
#[test]
fn a_batch_entry_with_dma_is_a_joint_fit() {
    let dir = folder("batch");
    dir.write("scene.toml", scene_text(None));
    let manifest = "[defaults]\nstarts = 1\n\
                    [[entry]]\nname = \"joint\"\nscene = \"scene.toml\"\ndata = \"tset.csv\"\n\
                    dma = \"dma.csv\"\nfriction_factor = \"one\"\n";
    dir.write("batch.toml", manifest);
    let out = run_in(dir.path(), &["batch", "batch.toml", "-o", "out"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    joint_record(&dir.path().join("out").join("joint"));
    let summary = fs::read_to_string(dir.path().join("out").join("summary.csv")).unwrap();
    assert!(summary.contains("joint,ok"), "{summary}");

    let broken = manifest.replace("dma = \"dma.csv\"", "dma = \"absent.csv\"");
    dir.write("broken.toml", &broken);
    let out = run_in(dir.path(), &["batch", "broken.toml", "-o", "broken"]);
    assert_failure(
        &out,
        &["entry \"joint\"", "line 7", "dma file", "absent.csv"],
    );
    assert!(!dir.path().join("broken").join("joint").exists());
}

/// Rolling data of one temperature without a `T` column, `[fit] T_ref`
/// saying where they were measured, and DMA isotherms at several
/// temperatures (the user guide's "rolling data without a T column need
/// T_ref"): the joint fit is written, and mu.csv places every rolling row
/// at T_ref with log10 a_T = 0. The writer once stopped here on an
/// internal fault after the whole fit.
#[test]
fn single_temperature_rolling_data_with_t_ref_and_dma_are_fitted() {
    let dir = folder("single-temperature");
    let tset = fs::read_to_string(dir.path().join("tset.csv")).unwrap();
    let mut lines = tset.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|c| *c == name).unwrap();
    let (v, mu, sigma, t) = (column("v"), column("mu"), column("sigma"), column("T"));
    let mut single = String::from("v,mu,sigma\n");
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        if cells[t].parse::<f64>().unwrap() == 20.0 {
            single += &format!("{},{},{}\n", cells[v], cells[mu], cells[sigma]);
        }
    }
    dir.write("single.csv", &single);
    dir.write("scene.toml", scene_text(None));
    let out = run_in(
        dir.path(),
        &[
            "fit",
            "scene.toml",
            "single.csv",
            "-o",
            "out",
            "--dma",
            "dma.csv",
        ],
    );
    let stderr = text(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(!stderr.contains("internal"), "{stderr}");
    joint_record(&dir.path().join("out"));
    let mu = fs::read_to_string(dir.path().join("out/mu.csv")).unwrap();
    let mut rows = mu.lines();
    let header: Vec<&str> = rows.next().unwrap().split(',').collect();
    let (t, log_at) = (
        header.iter().position(|c| *c == "T").expect("a T column"),
        header.iter().position(|c| *c == "log_aT").unwrap(),
    );
    let mut count = 0;
    for row in rows {
        let cells: Vec<f64> = row.split(',').map(|c| c.parse().unwrap()).collect();
        assert_eq!(cells[t], 20.0, "{row}");
        assert_eq!(cells[log_at], 0.0, "{row}");
        count += 1;
    }
    assert_eq!(count, 41);
}
