//! End-to-end tests of `rollfit fit`: a synthetic measurement is made with
//! `rollfit forward --noise` in a temporary folder and fitted back; broken
//! data files, scenes and flags are refused.
//!
//! Every bad-input test checks the same promise: a non-zero exit, an error
//! on stderr that names the file and the line or key (or the flag), no
//! panic, and no output folder.

use crate::common;

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Output;

use common::{Table, TempDir, assert_failure, rollfit, rollfit_in, text};

// ---------------------------------------------------------------- helpers

/// A steel ball on a broad Havriliak–Negami rubber (E1/E0 = 1000), 31
/// speeds over 6 decades, the static modulus known. The material is the
/// truth of the synthetic data; for the fit it is not a starting point
/// (only "sls" and "prony" materials are).
const SCENE: &str = r#"# fit_cli test scene
[geometry]
shape = "sphere"
radius = 0.005
load = 1.0

[substrate]
poisson = 0.5

[material]
model = "havriliak-negami"
E0 = 2.0e6
E1 = 2.0e9
tau = 1.0e-3
alpha = 0.55
beta = 0.4

[fit]
E0 = 2.0e6

[sweep]
v_min = 1e-6
v_max = 1.0
count = 31
"#;

/// Replaces exactly one occurrence of `from` in `scene`.
fn edit(scene: &str, from: &str, to: &str) -> String {
    assert_eq!(scene.matches(from).count(), 1, "{from:?} in the scene");
    scene.replacen(from, to, 1)
}

/// Writes `scene` and makes its synthetic measurement (1 % noise, seed 3)
/// with `rollfit forward`; returns (scene path, data path).
fn synthetic(dir: &TempDir, scene: &str) -> (PathBuf, PathBuf) {
    let scene_path = dir.write("scene.toml", scene);
    let data = dir.path().join("measured.csv");
    let out = rollfit(&[
        OsStr::new("forward"),
        scene_path.as_os_str(),
        OsStr::new("--noise"),
        OsStr::new("0.01"),
        OsStr::new("--seed"),
        OsStr::new("3"),
        OsStr::new("-o"),
        data.as_os_str(),
    ]);
    assert!(out.status.success(), "forward: {}", text(&out.stderr));
    (scene_path, data)
}

/// Runs `rollfit fit SCENE DATA -o OUT extra..`.
fn fit(scene: &Path, data: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        OsStr::new("fit"),
        scene.as_os_str(),
        data.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ];
    args.extend(extra.iter().map(OsStr::new));
    rollfit(&args)
}

/// Runs a fit that must succeed; returns its stderr.
fn fit_ok(scene: &Path, data: &Path, out: &Path, extra: &[&str]) -> String {
    let output = fit(scene, data, out, extra);
    let stderr = text(&output.stderr);
    assert!(output.status.success(), "{extra:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&fs::read_to_string(path).unwrap()).unwrap()
}

// ------------------------------------------------------------- good input

#[test]
fn fits_a_synthetic_measurement_with_a_static_modulus_anchor() {
    let dir = TempDir::new("good");
    let (scene, data) = synthetic(&dir, SCENE);
    let out = dir.path().join("result");
    let stderr = fit_ok(&scene, &data, &out, &[]);
    for fragment in [
        "method levenberg-marquardt",
        "converged",
        "misfit per point",
        "λ = ",
        "(discrepancy)",
        "window ω = ",
        "relaxation times",
        "determined by the data",
        "wall time",
        "scale anchor E0",
    ] {
        assert!(stderr.contains(fragment), "{fragment:?} in {stderr}");
    }
    assert!(!stderr.contains("no scale anchor"), "{stderr}");

    // fit.json: the contract's keys (docs/ARCHITECTURE.md, "Contract").
    let report = json(&out.join("fit.json"));
    for key in [
        "model",
        "poisson",
        "window",
        "method",
        "objective",
        "iterations",
        "converged",
        "wall_time_s",
        "stop_reason",
        "warnings",
        "lambda",
        "anchor",
    ] {
        assert!(report.get(key).is_some(), "fit.json has no {key}");
    }
    let model = &report["model"];
    assert_eq!(model["kind"], "prony");
    let tau = model["tau"].as_array().unwrap();
    let h = model["H"].as_array().unwrap();
    assert!(tau.len() >= 2 && tau.len() == h.len());
    assert!(h.iter().all(|h| h.as_f64().unwrap() >= 0.0));
    let e0 = model["E0"].as_f64().unwrap();
    assert!((e0 / 2.0e6 - 1.0).abs() < 1e-9, "anchored E0 = {e0}");
    assert!(model["E1"].as_f64().unwrap() > e0);
    assert_eq!(report["poisson"], 0.5);
    assert_eq!(report["method"], "levenberg-marquardt");
    assert_eq!(report["converged"], true);
    assert_eq!(report["anchor"]["source"], "E0");
    assert!(report["iterations"].as_u64().is_some());
    assert!(report["objective"].as_f64().unwrap() > 0.0);
    assert!(report["wall_time_s"].as_f64().unwrap() > 0.0);
    let (w_min, w_max) = (
        report["window"]["omega_min"].as_f64().unwrap(),
        report["window"]["omega_max"].as_f64().unwrap(),
    );
    assert!(0.0 < w_min && w_min < w_max, "window {w_min} … {w_max}");
    assert_eq!(report["input"]["points"], 31);

    // modulus.csv: the window only, increasing ω, positive moduli.
    let modulus = Table::read(&out.join("modulus.csv"));
    assert_eq!(
        modulus.header,
        [
            "omega",
            "E_storage",
            "E_loss",
            "tan_delta",
            "abs_E",
            "E_storage_sigma",
            "E_loss_sigma",
            "tan_delta_sigma",
            "abs_E_sigma"
        ]
    );
    let omega = modulus.column("omega");
    assert!(omega.len() > 10);
    assert!(omega.windows(2).all(|w| w[0] < w[1]));
    assert!(omega[0] >= w_min * (1.0 - 1e-12) && *omega.last().unwrap() <= w_max * (1.0 + 1e-12));
    for (i, row) in modulus.rows.iter().enumerate() {
        assert!(row.iter().all(|x| x.is_finite() && *x >= 0.0), "row {i}");
        assert!(
            (row[3] - row[2] / row[1]).abs() <= 1e-9 * row[3],
            "tan δ, row {i}"
        );
    }

    // mu.csv: the data's rows in order, the fit within a few per cent.
    let measured = Table::read(&data);
    let mu = Table::read(&out.join("mu.csv"));
    assert_eq!(
        mu.header,
        ["v", "mu_measured", "mu_fit", "sigma", "residual"]
    );
    assert_eq!(mu.column("v"), measured.column("v"));
    assert_eq!(mu.column("mu_measured"), measured.column("mu"));
    assert_eq!(mu.column("sigma"), measured.column("sigma"));
    let mut sum = 0.0;
    for row in &mu.rows {
        let relative = (row[2] - row[1]) / row[1];
        assert!((row[4] - relative).abs() < 1e-12, "residual column");
        assert!(relative.abs() < 0.05, "v = {}: μ misfit {relative}", row[0]);
        sum += relative * relative;
    }
    let rms = (sum / mu.rows.len() as f64).sqrt();
    assert!(rms < 0.02, "rms relative misfit {rms}");

    // Nothing but the three results and the folder's record of them (no
    // temporary files).
    let mut names: Vec<_> = fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [".rollfit-files.json", "fit.json", "modulus.csv", "mu.csv"]
    );
}

/// The bundled measurement as a European spreadsheet exports it (a title
/// line, ';' between the columns, decimal commas, the speed in mm/s, the
/// friction as "COF", an extra row with an empty cell) gives the same fit as
/// the plain CSV, and stderr says how the file was read.
#[test]
fn a_semicolon_decimal_comma_file_with_units_fits_like_the_plain_csv() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let (scene, plain) = (
        root.join("data/hn-rubber.toml"),
        root.join("data/hn-rubber.csv"),
    );
    let dir = TempDir::new("fit-european");
    let table = fs::read_to_string(&plain).unwrap();
    let mut lines = table.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[..3], ["v", "mu", "sigma"]);
    // m/s → mm/s by the decimal exponent, so that the reader's ×1e-3 gives
    // back exactly the same numbers.
    let mm = |v: &str| {
        let (mantissa, exponent) = match v.split_once(['e', 'E']) {
            Some((m, e)) => (m, e.parse::<i32>().unwrap()),
            None => (v, 0),
        };
        format!("{mantissa}E{}", exponent + 3)
    };
    let mut european =
        String::from("Rollreibung 2024-03-01;Probe HN\n\nvelocity (mm/s);COF;COF std;\n");
    for (i, line) in lines.enumerate() {
        let cells: Vec<&str> = line.split(',').collect();
        let row = format!("{};{};{};\n", mm(cells[0]), cells[1], cells[2]);
        european += &row.replace('.', ",");
        if i == 10 {
            european += "0,5;;0,001;\n";
        }
    }
    let data = dir.write("european.csv", &european);

    let out_plain = dir.path().join("plain");
    fit_ok(&scene, &plain, &out_plain, &[]);
    let out = dir.path().join("european");
    let stderr = fit_ok(&scene, &data, &out, &[]);
    for fragment in [
        "note: data file ",
        "european.csv: header on line 3; the 1 line above it (titles) ignored",
        "european.csv: columns separated by ';', decimal commas read as decimal points",
        "european.csv: column \"velocity (mm/s)\" read as v in mm/s, converted to m/s (×1e-3)",
        "european.csv: column \"COF\" read as mu",
        "european.csv: column \"COF std\" read as sigma",
        "warning: data file ",
        "european.csv: skipped 1 row with empty or NaN cells in mu: line 15",
    ] {
        assert!(stderr.contains(fragment), "{fragment:?} in {stderr}");
    }
    let (a, b) = (
        json(&out_plain.join("fit.json")),
        json(&out.join("fit.json")),
    );
    assert_eq!(a["model"], b["model"]);
    assert_eq!(a["objective"], b["objective"]);
    assert_eq!(a["input"]["points"], b["input"]["points"]);
    assert_eq!(
        fs::read_to_string(out_plain.join("mu.csv")).unwrap(),
        fs::read_to_string(out.join("mu.csv")).unwrap()
    );
}

/// The bundled temperature set (data/hn-rubber-tset.*, five temperatures,
/// WLF truth C1 = 8.86, C2 = 101.6 K at 20 °C): fit.json carries the shift
/// and its cross-check, mu.csv the reduced speeds.
#[test]
fn fits_the_bundled_temperature_set() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = TempDir::new("fit-tset");
    let out = dir.path().join("out");
    let stderr = fit_ok(
        &root.join("data/hn-rubber-tset.toml"),
        &root.join("data/hn-rubber-tset.csv"),
        &out,
        &[],
    );
    assert!(stderr.contains("shift WLF at T_ref = 20 °C"), "{stderr}");
    assert!(stderr.contains("cross-check"), "{stderr}");
    let report = json(&out.join("fit.json"));
    let shift = &report["shift"];
    assert_eq!(shift["model"], "wlf");
    assert_eq!(shift["T_ref"], 20.0);
    let c1 = shift["C1"].as_f64().unwrap();
    let c2 = shift["C2"].as_f64().unwrap();
    assert!((c1 / 8.86 - 1.0).abs() < 0.05, "C1 {c1}");
    assert!((c2 / 101.6 - 1.0).abs() < 0.05, "C2 {c2}");
    assert_eq!(shift["log_aT"].as_array().unwrap().len(), 5);
    let check = &report["shift_cross_check"];
    assert_eq!(check["temperatures"].as_array().unwrap().len(), 5);
    assert!(check["max_difference"].as_f64().unwrap() < 0.1);
    let mu = Table::read(&out.join("mu.csv"));
    let (v, t, log_a, reduced) = (
        mu.column("v"),
        mu.column("T"),
        mu.column("log_aT"),
        mu.column("v_reduced"),
    );
    assert_eq!(v.len(), 205);
    for i in 0..v.len() {
        assert!((reduced[i] / (v[i] * 10f64.powf(log_a[i])) - 1.0).abs() < 1e-12);
        let truth = -8.86 * (t[i] - 20.0) / (101.6 + t[i] - 20.0);
        assert!((log_a[i] - truth).abs() < 0.1);
    }
    // The window covers the combined, shifted range (~16 decades).
    let w = &report["window"];
    let span = (w["omega_max"].as_f64().unwrap() / w["omega_min"].as_f64().unwrap()).log10();
    assert!(span > 15.0, "{span}");
}

/// data/hn-rubber-tset.csv is what its documented command makes
/// (data/README.md).
#[test]
fn bundled_temperature_set_is_what_its_command_makes() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = TempDir::new("tset-made");
    let made = dir.path().join("made.csv");
    let out = rollfit(&[
        OsStr::new("forward"),
        root.join("data/hn-rubber-tset-truth.toml").as_os_str(),
        OsStr::new("--noise"),
        OsStr::new("0.01"),
        OsStr::new("--seed"),
        OsStr::new("4"),
        OsStr::new("-o"),
        made.as_os_str(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert_eq!(
        fs::read_to_string(&made).unwrap(),
        fs::read_to_string(root.join("data/hn-rubber-tset.csv")).unwrap()
    );
}

/// A free shift must be tied to a measured temperature.
#[test]
fn free_shift_at_an_unmeasured_reference_is_refused() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let scene = fs::read_to_string(root.join("data/hn-rubber-tset.toml")).unwrap();
    let scene = edit(&scene, "shift = \"wlf\"", "shift = \"free\"");
    let scene = edit(&scene, "T_ref = 20.0", "T_ref = 25.0");
    let dir = TempDir::new("fit-tset-free");
    let scene_path = dir.write("bad-scene.toml", &scene);
    let out = dir.path().join("out");
    let output = fit(
        &scene_path,
        &root.join("data/hn-rubber-tset.csv"),
        &out,
        &[],
    );
    assert_failure(
        &output,
        &[
            "bad-scene.toml",
            "T_ref",
            "25 °C is not one of the measured temperatures",
        ],
    );
    assert!(!out.exists());
}

#[test]
fn default_output_folder_is_fits_and_the_data_stem() {
    let dir = TempDir::new("default-out");
    synthetic(&dir, SCENE);
    let out = rollfit_in(
        Some(dir.path()),
        &[
            OsStr::new("fit"),
            OsStr::new("scene.toml"),
            OsStr::new("measured.csv"),
        ],
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let folder = dir.path().join("fits").join("measured");
    for name in ["fit.json", "modulus.csv", "mu.csv"] {
        assert!(folder.join(name).is_file(), "{name}");
    }
}

/// Without an anchor, the scale profile says what the data
/// determine. Under 1 N the test scene's 31 speeds bound E0 from above near
/// the truth and the R/3 limit of the model bounds it from below within a
/// factor 9: the fit is written with its interval. Under 0.01 N the contact
/// is small down to 10 kPa and the profile stays flat there: the fit is
/// refused, writes nothing and names the three anchors; with
/// --allow-unanchored it is written, marked, with the interval.
#[test]
fn without_an_anchor_the_scale_interval_decides() {
    let dir = TempDir::new("no-anchor");
    let unanchored = edit(SCENE, "[fit]\nE0 = 2.0e6\n", "");
    let (scene, data) = synthetic(&dir, &unanchored);
    let out = dir.path().join("result");
    let stderr = fit_ok(&scene, &data, &out, &[]);
    assert!(stderr.contains("determined by the data"), "{stderr}");
    let report = json(&out.join("fit.json"));
    assert!(report["anchor"].is_null());
    assert_eq!(report["scale"]["status"], "data", "{}", report["scale"]);
    assert_interval_holds(&report, 2.0e6);

    let light = TempDir::new("no-anchor-light");
    let (scene, data) = synthetic(&light, &edit(&unanchored, "load = 1.0", "load = 0.01"));
    let out = light.path().join("result");
    let refused = fit(&scene, &data, &out, &[]);
    let stderr = text(&refused.stderr);
    assert!(!refused.status.success(), "{stderr}");
    for needle in [
        "do not determine the modulus scale",
        "E0 = …",
        "E_at",
        "contact_radius",
        "--allow-unanchored",
    ] {
        assert!(stderr.contains(needle), "{needle}: {stderr}");
    }
    assert!(!out.exists(), "a refused fit wrote {}", out.display());
    let stderr = fit_ok(&scene, &data, &out, &["--allow-unanchored"]);
    assert!(stderr.contains("warning: no scale anchor"), "{stderr}");
    let report = json(&out.join("fit.json"));
    assert_eq!(
        report["scale"]["status"], "undetermined",
        "{}",
        report["scale"]
    );
    assert_interval_holds(&report, 2.0e6);
}

/// The fit's E0 and the true `e0` lie inside fit.json's 2σ interval.
fn assert_interval_holds(report: &serde_json::Value, e0: f64) {
    let scale = &report["scale"];
    let low = scale["E0_low"].as_f64().unwrap_or(0.0);
    let high = scale["E0_high"].as_f64().unwrap_or(f64::INFINITY);
    let fitted = report["model"]["E0"].as_f64().unwrap();
    assert!(
        low <= fitted && fitted <= high,
        "E0 {fitted} outside {scale}"
    );
    assert!(low <= e0 && e0 <= high, "the truth {e0} outside {scale}");
}

#[test]
fn repeated_speeds_unsorted_rows_and_comments_are_accepted() {
    let dir = TempDir::new("unsorted");
    let (scene, data) = synthetic(&dir, SCENE);
    // Reverse the rows, repeat two of them (rescaled a little), add
    // comments and drop the sigma column (relative weights).
    let measured = Table::read(&data);
    let (v, mu) = (measured.column("v"), measured.column("mu"));
    let mut content = String::from("# measured in reverse\nmu,v,note\n");
    let mut expected_v = Vec::new();
    for i in (0..v.len()).rev() {
        content += &format!("{:e},{:e},0\n", mu[i], v[i]);
        expected_v.push(v[i]);
        if i == 10 || i == 20 {
            content += &format!("# repeat\n{:e},{:e},1\n", mu[i] * 1.01, v[i]);
            expected_v.push(v[i]);
        }
    }
    let shuffled = dir.write("shuffled.csv", &content);
    let out = dir.path().join("result");
    fit_ok(&scene, &shuffled, &out, &[]);
    let result = Table::read(&out.join("mu.csv"));
    assert_eq!(result.header, ["v", "mu_measured", "mu_fit", "residual"]);
    assert_eq!(result.column("v"), expected_v);
    let report = json(&out.join("fit.json"));
    assert_eq!(report["sigma_weights"], false);
    assert_eq!(report["input"]["points"], 33);
}

#[test]
fn an_unconverged_fit_writes_nothing_and_fails_unless_allowed() {
    let dir = TempDir::new("unconverged");
    let (_, data) = synthetic(&dir, SCENE);
    let scene = dir.write(
        "budget.toml",
        edit(SCENE, "[fit]\n", "[fit]\nmax_evaluations = 1\n"),
    );
    let out = dir.path().join("result");
    let output = fit(&scene, &data, &out, &[]);
    let stderr = text(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(
        stderr.contains("did not converge")
            && stderr.contains("nothing was written")
            && stderr.contains("--allow-unconverged"),
        "{stderr}"
    );
    // A non-zero exit leaves the output as it was.
    assert!(!out.exists());

    let stderr = fit_ok(&scene, &data, &out, &["--allow-unconverged"]);
    assert!(
        stderr.contains("warning: the fit did not converge"),
        "{stderr}"
    );
    let report = json(&out.join("fit.json"));
    assert_eq!(report["converged"], false);
    assert!(
        report["stop_reason"].as_str().unwrap().contains("budget"),
        "{}",
        report["stop_reason"]
    );
    assert!(out.join("modulus.csv").is_file() && out.join("mu.csv").is_file());
}

#[test]
fn command_line_flags_override_the_scene() {
    let dir = TempDir::new("flags");
    let (_, data) = synthetic(&dir, SCENE);
    let scene = dir.write(
        "settings.toml",
        edit(
            SCENE,
            "[fit]\n",
            "[fit]\nmethod = \"nelder-mead\"\nlambda = 5.0\nseed = 1\nstarts = 4\nterms = \"auto\"\n",
        ),
    );
    let out = dir.path().join("result");
    fit_ok(
        &scene,
        &data,
        &out,
        &[
            "--method",
            "auto",
            "--lambda",
            "10",
            "--seed",
            "5",
            "--starts",
            "1",
            "--terms",
            "1.5/decade",
            "--allow-unconverged",
        ],
    );
    let report = json(&out.join("fit.json"));
    assert_eq!(report["method"], "levenberg-marquardt");
    assert_eq!(report["lambda"]["value"], 10.0);
    assert_eq!(report["lambda"]["rule"], "fixed");
    assert_eq!(report["seed"], 5);
    assert_eq!(report["terms"]["rule"], "per_decade");
    let per_decade = report["terms"]["per_decade"].as_f64().unwrap();
    assert!((per_decade - 1.5).abs() < 0.1, "{per_decade}");
    let runs = report["runs"].as_array().unwrap();
    assert!(!runs.iter().any(|r| r["stage"] == "start 2"), "one start");
}

// -------------------------------------------------------------- bad input

/// A small valid data set for tests whose error lies elsewhere.
const SMALL_DATA: &str = "v,mu\n1e-6,0.02\n1e-5,0.05\n1e-4,0.06\n1e-3,0.04\n1e-2,0.02\n";

/// Runs `rollfit fit` on `scene` and `data` (None: a data file that does
/// not exist) written to a temporary folder, and checks the promise of
/// every bad-input test. Returns stderr.
fn assert_refused(scene: &str, data: Option<&str>, extra: &[&str], expected: &[&str]) -> String {
    let dir = TempDir::new("bad");
    let scene = dir.write("bad-scene.toml", scene);
    let data = match data {
        Some(content) => dir.write("bad-data.csv", content),
        None => dir.path().join("missing.csv"),
    };
    let out = dir.path().join("result");
    let stderr = assert_failure(&fit(&scene, &data, &out, extra), expected);
    assert!(!out.exists(), "an output folder was created");
    stderr
}

#[test]
fn missing_data_file() {
    assert_refused(SCENE, None, &[], &["missing.csv", "cannot open data file"]);
}

#[test]
fn data_without_a_mu_column() {
    assert_refused(
        SCENE,
        Some("# speeds only\nv,friction\n1e-3,0.1\n"),
        &[],
        &[
            "bad-data.csv",
            "line 2 (header)",
            "no friction column (mu, µ, COF",
            "found \"v\", \"friction\" (delimiter ',')",
        ],
    );
}

#[test]
fn speed_that_is_not_a_number() {
    assert_refused(
        SCENE,
        Some("v,mu\n1e-3,0.1\n# next\nabc,0.2\n"),
        &[],
        &[
            "bad-data.csv",
            "line 4",
            "column `v`",
            "\"abc\" is not a number",
        ],
    );
}

#[test]
fn sheet_flag_with_a_text_file() {
    assert_refused(
        SCENE,
        Some("v,mu\n1e-3,0.1\n"),
        &["--sheet", "Run 1"],
        &[
            "bad-data.csv",
            "a sheet (\"Run 1\") was given",
            "not a workbook",
        ],
    );
}

#[test]
fn infinite_speed() {
    assert_refused(
        SCENE,
        Some("v,mu\n1e-3,0.1\n# next\ninf,0.2\n"),
        &[],
        &["bad-data.csv", "line 4", "column `v`", "\"inf\"", "finite"],
    );
}

#[test]
fn negative_mu() {
    assert_refused(
        SCENE,
        Some("v,mu\n1e-3,0.1\n1e-2,-0.02\n"),
        &[],
        &[
            "bad-data.csv",
            "line 3",
            "column `mu` = -0.02",
            "greater than zero",
        ],
    );
}

#[test]
fn zero_sigma() {
    assert_refused(
        SCENE,
        Some("v,mu,sigma\n1e-3,0.1,1e-3\n1e-2,0.2,0\n"),
        &[],
        &[
            "bad-data.csv",
            "line 3",
            "column `sigma` = 0",
            "greater than zero",
        ],
    );
}

#[test]
fn empty_data() {
    assert_refused(
        SCENE,
        Some("# nothing measured yet\nv,mu,sigma\n"),
        &[],
        &["bad-data.csv", "no data rows"],
    );
    assert_refused(SCENE, Some(""), &[], &["bad-data.csv", "empty"]);
}

/// Several temperatures form a temperature set, which needs a sweep at
/// each temperature.
#[test]
fn temperature_set_with_one_point_per_temperature() {
    assert_refused(
        SCENE,
        Some("v,mu,T\n1e-3,0.1,20\n1e-2,0.2,20\n1e-1,0.3,20\n1e-2,0.2,40\n"),
        &[],
        &[
            "bad-data.csv",
            "T = 40 °C has 1 measurement",
            "temperature set needs at least two speeds",
        ],
    );
}

#[test]
fn unknown_fit_key() {
    let scene = edit(SCENE, "[fit]\n", "[fit]\nlamda = 1\n");
    assert_refused(
        &scene,
        Some(SMALL_DATA),
        &[],
        &["bad-scene.toml", "unknown field `lamda`", "line 19"],
    );
}

#[test]
fn two_anchors() {
    let scene = edit(SCENE, "[fit]\n", "[fit]\nE_at = { omega = 1.0, E = 1e8 }\n");
    assert_refused(
        &scene,
        Some(SMALL_DATA),
        &[],
        &["bad-scene.toml", "[fit]", "`E0`, `E_at`", "at most one"],
    );
}

#[test]
fn negative_static_modulus_anchor() {
    let scene = edit(SCENE, "[fit]\nE0 = 2.0e6\n", "[fit]\nE0 = -1\n");
    assert_refused(
        &scene,
        Some(SMALL_DATA),
        &[],
        &["bad-scene.toml", "[fit]", "E0 = -1", "greater than zero"],
    );
}

#[test]
fn anchor_above_the_glassy_bound() {
    let scene = edit(
        SCENE,
        "[fit]\nE0 = 2.0e6\n",
        "[fit]\nE_at = { omega = 1.0, E = 2e10 }\n",
    );
    assert_refused(
        &scene,
        Some(SMALL_DATA),
        &[],
        &["bad-scene.toml", "`E_at`", "E1_max"],
    );
}

#[test]
fn fewer_than_four_distinct_speeds() {
    assert_refused(
        SCENE,
        Some("v,mu\n1e-5,0.05\n1e-3,0.04\n1e-1,0.01\n1e-3,0.041\n"),
        &[],
        &["bad-data.csv", "3 distinct speed", "4 row", "at least 4"],
    );
    assert_refused(
        SCENE,
        Some("v,mu\n1e-3,0.05\n1e-3,0.04\n1e-3,0.045\n1e-3,0.041\n1e-3,0.05\n"),
        &[],
        &["bad-data.csv", "1 distinct speed", "5 row"],
    );
}

#[test]
fn unknown_method_flag() {
    assert_refused(
        SCENE,
        Some(SMALL_DATA),
        &["--method", "newton"],
        &["--method", "unknown method \"newton\"", "nelder-mead"],
    );
}

#[test]
fn unknown_method_in_the_scene() {
    let scene = edit(SCENE, "[fit]\n", "[fit]\nmethod = \"newton\"\n");
    assert_refused(
        &scene,
        Some(SMALL_DATA),
        &[],
        &["bad-scene.toml", "[fit]", "unknown method \"newton\""],
    );
}

#[test]
fn out_of_range_flags_are_named() {
    assert_refused(
        SCENE,
        Some(SMALL_DATA),
        &["--starts", "0"],
        &["--starts", "use 1 to 100"],
    );
    assert_refused(
        SCENE,
        Some(SMALL_DATA),
        &["--terms", "many"],
        &["--terms", "\"many\""],
    );
    assert_refused(
        SCENE,
        Some(SMALL_DATA),
        &["--lambda", "-1"],
        &["--lambda", "≥ 0"],
    );
}

#[test]
fn bad_geometry_is_named_with_its_section() {
    let scene = edit(SCENE, "radius = 0.005", "radius = -0.005");
    assert_refused(
        &scene,
        Some(SMALL_DATA),
        &[],
        &["bad-scene.toml", "[geometry]", "radius"],
    );
}

#[test]
fn output_that_is_a_file_is_refused() {
    let dir = TempDir::new("out-file");
    let scene = dir.write("scene.toml", SCENE);
    let data = dir.write("data.csv", SMALL_DATA);
    let out = dir.write("taken", "not a folder");
    let output = fit(&scene, &data, &out, &[]);
    let stderr = text(&output.stderr);
    assert!(!output.status.success());
    assert!(
        stderr.contains("taken") && stderr.contains("not a folder"),
        "{stderr}"
    );
    assert_eq!(fs::read_to_string(&out).unwrap(), "not a folder");
}

#[test]
fn the_exact_contact_is_forward_only() {
    let scene = edit(
        SCENE,
        "[substrate]",
        "[contact]\nsize = \"exact\"\n\n[substrate]",
    );
    assert_refused(
        &scene,
        Some(SMALL_DATA),
        &[],
        &["bad-scene.toml", "[contact]", "exact", "forward-only"],
    );
    for rung in ["auto", "low-speed"] {
        let scene = edit(
            SCENE,
            "[substrate]",
            &format!("[contact]\nsize = \"{rung}\"\n\n[substrate]"),
        );
        assert_refused(
            &scene,
            Some(SMALL_DATA),
            &[],
            &["bad-scene.toml", "[contact]", rung, "forward only"],
        );
    }
}

// ------------------------------------------------------ physics = "exact"

/// A 5 mm cylinder at 1000 N/m on the broad rubber of [`SCENE`], 11
/// speeds over 5 decades up to its friction maximum, E0 known.
const CYLINDER: &str = r#"# fit_cli exact-physics scene
[geometry]
shape = "cylinder"
radius = 0.005
load = 1000.0

[material]
model = "havriliak-negami"
E0 = 2.0e6
E1 = 2.0e9
tau = 1.0e-3
alpha = 0.55
beta = 0.4

[fit]
E0 = 2.0e6

[sweep]
v_min = 1e-8
v_max = 1e-3
count = 11
"#;

/// `--physics exact` on a cylinder: fit.json says how the exact contact
/// was reached, mu.csv gets `exact_correction` after its other columns,
/// the summary says so, and `rollfit report` draws the folder; without the
/// flag neither key nor column is written.
#[test]
fn physics_exact_writes_its_record_and_correction() {
    let dir = TempDir::new("exact-physics");
    let (scene, data) = synthetic(&dir, CYLINDER);
    let out = dir.path().join("exact");
    let stderr = fit_ok(&scene, &data, &out, &["--physics", "exact"]);
    assert!(
        stderr.contains("physics exact (defect correction)"),
        "{stderr}"
    );
    let report = json(&out.join("fit.json"));
    let physics = &report["physics"];
    assert_eq!(physics["kind"], "exact", "{physics}");
    assert!(physics["exact_solves"].as_u64().unwrap() >= 22, "{physics}");
    assert!(physics["converged"].as_bool().unwrap(), "{physics}");
    let mu = Table::read(&out.join("mu.csv"));
    assert_eq!(
        mu.header,
        [
            "v",
            "mu_measured",
            "mu_fit",
            "sigma",
            "residual",
            "exact_correction"
        ]
    );
    for row in &mu.rows {
        let r = row[5];
        assert!(r > 0.5 && r < 1.5, "{row:?}");
    }
    let drawn = rollfit(&[OsStr::new("report"), out.as_os_str()]);
    assert!(drawn.status.success(), "{}", text(&drawn.stderr));

    let plain = dir.path().join("approximate");
    fit_ok(&scene, &data, &plain, &[]);
    assert!(json(&plain.join("fit.json")).get("physics").is_none());
    assert_eq!(
        Table::read(&plain.join("mu.csv")).header,
        ["v", "mu_measured", "mu_fit", "sigma", "residual"]
    );
}

/// `--physics exact` on a ball (the exact sphere behind
/// `exact_body`): 8 speeds of Eq. (17) data at 1 % over four decades up to
/// the friction maximum of a 5 mm ball at 1 N. The fit converges, every
/// speed got an exact solve per sweep (fewer than 12 speeds: the first
/// sweep is not thinned), and the correction r = μ_exact/μ_17
/// is the few per cent Eq. (17) is off for this rubber (docs/validation.md, "Eq. (17)
/// against the exact rolling sphere"), not 1 and not far from it.
#[test]
fn physics_exact_fits_a_sphere() {
    let dir = TempDir::new("exact-physics-sphere");
    let ball = CYLINDER
        .replace("shape = \"cylinder\"", "shape = \"sphere\"")
        .replace("load = 1000.0", "load = 1.0")
        .replace("count = 11", "count = 8")
        .replace("v_min = 1e-8", "v_min = 1e-7");
    let (scene, data) = synthetic(&dir, &ball);
    let out = dir.path().join("exact");
    let stderr = fit_ok(&scene, &data, &out, &["--physics", "exact"]);
    assert!(
        stderr.contains("physics exact (defect correction)"),
        "{stderr}"
    );
    let physics = &json(&out.join("fit.json"))["physics"];
    assert!(physics["converged"].as_bool().unwrap(), "{physics}");
    let iterations = physics["iterations"].as_u64().unwrap();
    assert_eq!(
        physics["exact_solves"].as_u64().unwrap(),
        8 * (1 + iterations),
        "{physics}"
    );
    let mu = Table::read(&out.join("mu.csv"));
    let corrections: Vec<f64> = mu.rows.iter().map(|row| row[5]).collect();
    assert!(
        corrections.iter().all(|r| (0.9..1.1).contains(r)),
        "{corrections:?}"
    );
    assert!(
        corrections.iter().any(|r| (r - 1.0).abs() > 1e-3),
        "{corrections:?}"
    );
}

#[test]
fn physics_exact_is_refused_on_a_film_naming_the_key() {
    let scene = edit(
        CYLINDER,
        "[fit]\n",
        "[substrate]\nthickness = 1e-3\n\n[fit]\nphysics = \"exact\"\n",
    );
    assert_refused(
        &scene,
        Some(SMALL_DATA),
        &[],
        &["bad-scene.toml", "`physics`", "film", "\"approximate\""],
    );
    assert_refused(
        &edit(
            CYLINDER,
            "[fit]\n",
            "[substrate]\nthickness = 1e-3\n\n[fit]\n",
        ),
        Some(SMALL_DATA),
        &["--physics", "exact"],
        &["--physics", "`physics`", "film"],
    );
}

#[test]
fn unknown_physics_is_named_in_the_scene_and_the_flag() {
    let scene = edit(CYLINDER, "[fit]\n", "[fit]\nphysics = \"exakt\"\n");
    assert_refused(
        &scene,
        Some(SMALL_DATA),
        &[],
        &[
            "bad-scene.toml",
            "[fit]",
            "`physics`",
            "line 16",
            "\"exakt\"",
        ],
    );
    assert_refused(
        CYLINDER,
        Some(SMALL_DATA),
        &["--physics", "exakt"],
        &["--physics", "\"exakt\"", "\"approximate\" or \"exact\""],
    );
}

/// A temperature set whose shifts are not WLF (WLF about 20 °C
/// above T_g = −10 °C, Arrhenius with 120 kJ/mol below), made by `forward`
/// from a free `[material.shift]`, 7 temperatures × 21 speeds, 1 % noise.
/// The default `shift = "auto"` fits it and says which law it chose and
/// why (stderr and fit.json's `shift_choice`); `shift = "wlf"` is refused
/// as poor, naming `shift = "free"` and `--shift free`, and writes nothing;
/// `--shift free` overrides the scene's law.
#[test]
fn shifts_that_are_not_wlf_are_chosen_free_and_a_poor_wlf_fit_names_free() {
    let wlf = |t: f64| -8.86 * (t - 20.0) / (101.6 + t - 20.0);
    let kinked = |t: f64| {
        let x = |t: f64| 1.0 / (t + 273.15);
        if t >= -10.0 {
            wlf(t)
        } else {
            wlf(-10.0) + 1.2e5 / (8.314462618 * 10f64.ln()) * (x(t) - x(-10.0))
        }
    };
    let temperatures = [-40.0, -25.0, -10.0, 5.0, 20.0, 35.0, 50.0];
    let table: Vec<String> = temperatures
        .iter()
        .map(|&t| format!("{{ T = {t:?}, log_aT = {:?} }}", kinked(t)))
        .collect();
    let truth = edit(SCENE, "[fit]\nE0 = 2.0e6\n", "")
        .replace(
            "beta = 0.4\n",
            "beta = 0.4\n[material.shift]\nmodel = \"free\"\nT_ref = 20.0\n",
        )
        .replace("v_max = 1.0\ncount = 31\n", "v_max = 0.1\ncount = 21\n");
    let truth = format!(
        "{}log_aT = [{}]\n{}temperature = {temperatures:?}\n",
        &truth[..truth.find("[sweep]").unwrap()],
        table.join(", "),
        &truth[truth.find("[sweep]").unwrap()..]
    );
    let dir = TempDir::new("fit-kinked");
    let (_, data) = synthetic(&dir, &truth);
    let geometry = &SCENE[..SCENE.find("[material]").unwrap()];
    let scene = dir.write(
        "fit.toml",
        format!("{geometry}[fit]\nT_ref = 20.0\nE_at = {{ omega = 10.0, E = 6.26e7 }}\n"),
    );
    let out = dir.path().join("auto");
    let stderr = fit_ok(&scene, &data, &out, &[]);
    assert!(
        stderr.contains("shift law free: the data reject WLF"),
        "{stderr}"
    );
    let report = json(&out.join("fit.json"));
    assert_eq!(report["shift"]["model"], "free");
    assert_eq!(report["shift_choice"]["chosen_by"], "auto");
    assert_eq!(report["shift_choice"]["candidates"][0]["rejected"], true);
    for s in report["shift"]["log_aT"].as_array().unwrap() {
        let t = s["T"].as_f64().unwrap();
        let error = s["log_aT"].as_f64().unwrap() - kinked(t);
        assert!(error.abs() <= 0.05, "T {t}: off by {error}");
        assert!(s["log_aT_sigma"].as_f64().is_some(), "{s}");
    }
    let wlf_scene = dir.write(
        "wlf.toml",
        format!(
            "{geometry}[fit]\nshift = \"wlf\"\nT_ref = 20.0\nE_at = {{ omega = 10.0, E = 6.26e7 }}\n"
        ),
    );
    let refused = dir.path().join("wlf");
    let output = fit(&wlf_scene, &data, &refused, &[]);
    assert_failure(
        &output,
        &[
            "does not describe the data",
            "shift = \"free\"",
            "--shift free",
        ],
    );
    assert!(!refused.exists());
    // The flag overrides the scene's law.
    let flagged = dir.path().join("flag");
    fit_ok(&wlf_scene, &data, &flagged, &["--shift", "free"]);
    assert_eq!(json(&flagged.join("fit.json"))["shift"]["model"], "free");
    // A two-branch law in the scene, which the fit does not have: free
    // shifts in its place, and said on stderr and in fit.json.
    let material = &SCENE[..SCENE.find("[fit]").unwrap()];
    let two_branch = dir.write(
        "two-branch.toml",
        format!(
            "{material}[material.shift]\nmodel = \"wlf-arrhenius\"\nT_ref = 20.0\nC1 = 8.86\n\
             C2 = 101.6\nT_g = -10.0\nE_a = 1.2e5\n\n[fit]\nE_at = {{ omega = 10.0, E = 6.26e7 }}\n"
        ),
    );
    let substituted = dir.path().join("two-branch");
    let stderr = fit_ok(&two_branch, &data, &substituted, &[]);
    assert!(
        stderr.contains(
            "shift law free: [material.shift] model = \"wlf-arrhenius\" asks for a law the fit \
             does not have; fitted instead: free shifts"
        ),
        "{stderr}"
    );
    let report = json(&substituted.join("fit.json"));
    assert_eq!(report["shift"]["model"], "free");
    assert_eq!(report["shift_choice"]["chosen_by"], "substitute");
    assert_eq!(report["shift_choice"]["requested"], "wlf-arrhenius");
    assert!(report["shift_choice"]["test"].is_null(), "{report}");
}
