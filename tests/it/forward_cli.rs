//! End-to-end tests of `rollfit forward`: the binary is run on the example
//! scenes in data/ and on broken scenes written to a temporary folder.
//!
//! Every bad-input test checks the same promise: a non-zero exit, an error
//! on stderr that names the file and the key or problem, and no panic.

use crate::common;

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Output;

use common::{Table, TempDir, assert_failure, parse_csv, rollfit, text};

// ---------------------------------------------------------------- helpers

/// The workspace root (this test is registered in crates/cli).
fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn data(name: &str) -> PathBuf {
    workspace().join("data").join(name)
}

fn forward(scene: &Path, out: Option<&Path>) -> Output {
    let mut args = vec![std::ffi::OsStr::new("forward"), scene.as_os_str()];
    if let Some(out) = out {
        args.push(std::ffi::OsStr::new("-o"));
        args.push(out.as_os_str());
    }
    rollfit(&args)
}

/// A small valid scene; bad-input tests break one line of it.
const SLS_SCENE: &str = r#"# test scene: paper sphere, few speeds
[geometry]
shape = "sphere"
radius = 0.01
load = 0.15

[substrate]
poisson = 0.0

[contact]
size = "dynamic"

[material]
model = "sls"
E0 = 1e6
E1 = 1e7
tau = 1.0

[sweep]
v_min = 1e-6
v_max = 1.0
count = 7
"#;

/// The same as a Prony series (E1 = 10 MPa, E0 = 1 MPa).
const PRONY_SCENE: &str = r#"[geometry]
shape = "sphere"
radius = 0.01
load = 0.15

[material]
model = "prony"
E1 = 1e7
H = [4e6, 5e6]
tau = [0.1, 1.0]

[sweep]
v_min = 1e-6
v_max = 1.0
count = 7
"#;

/// A table scene; the table file is written by each test.
const TABLE_SCENE: &str = r#"[geometry]
shape = "sphere"
radius = 0.01
load = 0.15

[material]
model = "table"
file = "modulus.csv"

[sweep]
v_min = 1e-6
v_max = 1.0
count = 7
"#;

const GOOD_TABLE: &str = "# omega in rad/s, moduli in Pa\nomega,E_storage,E_loss\n0.1,1.0e6,1.0e5\n1,2.0e6,8.0e5\n10,6.0e6,2.0e6\n";

/// `base` with `from` replaced by `to`; `from` must occur.
fn edit(base: &str, from: &str, to: &str) -> String {
    assert!(base.contains(from), "test scene has no {from:?}");
    base.replacen(from, to, 1)
}

/// Runs forward on `scene` (written as `bad.toml` in a fresh folder, with
/// optional extra files) and checks the failure report.
fn assert_rejected(scene: &str, extra: &[(&str, &str)], expected: &[&str]) -> String {
    let dir = TempDir::new("bad");
    for (name, content) in extra {
        dir.write(name, content);
    }
    let path = dir.write("bad.toml", scene);
    let out = forward(&path, None);
    assert_failure_names(&out, "bad.toml", expected)
}

fn assert_failure_names(out: &Output, file: &str, expected: &[&str]) -> String {
    let stderr = assert_failure(out, expected);
    assert_eq!(out.status.code(), Some(1), "exit code; stderr:\n{stderr}");
    assert!(
        stderr.contains(file),
        "stderr does not name {file}:\n{stderr}"
    );
    stderr
}

const HEADER: [&str; 7] = [
    "v",
    "mu",
    "mu_low_speed",
    "contact_size_static",
    "mean_pressure_static",
    "centroid_shift",
    "gt_alpha",
];

/// Runs forward on a scene that must succeed and returns its CSV, whose
/// columns must be `header`.
fn run_ok_with_header(scene: &Path, header: &[&str]) -> Table {
    let out = forward(scene, None);
    let stderr = text(&out.stderr);
    assert!(out.status.success(), "{}: {stderr}", scene.display());
    assert!(!stderr.contains("panicked"), "{stderr}");
    let table = parse_csv(&text(&out.stdout));
    assert_eq!(table.header, header, "{}", scene.display());
    table
}

/// Runs forward on a scene without a temperature: exactly [`HEADER`].
fn run_ok(scene: &Path) -> Table {
    run_ok_with_header(scene, &HEADER)
}

/// `columns` followed by `T`, the column forward adds last whenever
/// [sweep] sets a temperature.
fn with_t(columns: &[&'static str]) -> Vec<&'static str> {
    columns.iter().copied().chain(["T"]).collect()
}

/// Runs forward on a scene whose [sweep] sets a temperature: [`HEADER`],
/// then `T`, and every row at temperature `t`.
fn run_ok_at(scene: &Path, t: f64) -> Table {
    let table = run_ok_with_header(scene, &with_t(&HEADER));
    assert!(table.column("T").iter().all(|&x| x == t), "T column ≠ {t}");
    table
}

fn assert_increasing(values: &[f64]) {
    assert!(
        values.windows(2).all(|w| w[0] < w[1]),
        "not strictly increasing: {values:?}"
    );
}

fn assert_close(actual: f64, expected: f64, rel: f64, what: &str) {
    assert!(
        (actual - expected).abs() <= rel * expected.abs(),
        "{what}: {actual} vs {expected} (relative {:.2e}, allowed {rel:.0e})",
        (actual - expected).abs() / expected.abs()
    );
}

// ------------------------------------------------- example scenes (need μ)

fn check_example(name: &str, count: usize, v_min: f64, v_max: f64, radius: f64) -> Table {
    let table = run_ok(&data(name));
    assert_eq!(table.rows.len(), count, "{name}");
    let v = table.column("v");
    assert_eq!((v[0], v[count - 1]), (v_min, v_max), "{name}");
    assert_increasing(&v);
    let mu = table.column("mu");
    let shift = table.column("centroid_shift");
    for (i, &m) in mu.iter().enumerate() {
        assert!(m.is_finite() && m > 0.0, "{name}: mu[{i}] = {m}");
        assert_close(shift[i], m * radius, 1e-12, "centroid shift = μR");
    }
    for column in [
        "mu_low_speed",
        "contact_size_static",
        "mean_pressure_static",
        "gt_alpha",
    ] {
        assert!(
            table
                .column(column)
                .iter()
                .all(|x| x.is_finite() && *x > 0.0),
            "{name}: {column} not finite and positive"
        );
    }
    table
}

#[test]
fn paper_fig2_sphere_scene_runs() {
    let t = check_example("paper-fig2-sphere.toml", 91, 1e-8, 10.0, 0.01);
    // Hertz with E_eff = E0 = 1 MPa (ν = 0): r0 = (3 F R / 4E)^(1/3).
    for r0 in t.column("contact_size_static") {
        assert_close(r0, 1.0400419115259524e-3, 1e-12, "r0");
    }
    // The paper's Fig. 2 has its maximum near v ≈ r0/τ ≈ 1 mm/s.
    let (v, mu) = (t.column("v"), t.column("mu"));
    let i = (0..mu.len())
        .max_by(|&a, &b| mu[a].total_cmp(&mu[b]))
        .unwrap();
    assert!((3e-4..3e-3).contains(&v[i]), "maximum at v = {}", v[i]);
}

#[test]
fn paper_fig2_cylinder_scene_runs() {
    let t = check_example("paper-fig2-cylinder.toml", 91, 1e-8, 10.0, 0.01);
    // a0 = (4 f R / (π E))^(1/2) with E = 1 MPa.
    for a0 in t.column("contact_size_static") {
        assert_close(a0, 1.1283791670955127e-3, 1e-12, "a0");
    }
}

#[test]
fn example_sphere_scene_runs() {
    let t = check_example("example-sphere.toml", 41, 1e-6, 1.0, 0.005);
    // E_eff(0) = 2 MPa / (1 − 0.25).
    let r0 = (3.0f64 * 1.0 * 0.005 / (4.0 * 2e6 / 0.75)).cbrt();
    assert_close(t.column("contact_size_static")[0], r0, 1e-9, "r0");
}

/// μ of the paper's sphere at three speeds from the independent reference
/// implementation (shared/reference/forward.json, accurate to about 1e-8).
#[test]
fn paper_sphere_matches_the_reference_implementation() {
    let dir = TempDir::new("reference");
    let points = [
        (1.0400419115259525e-6, 9.354466258556675e-05),
        (0.0010400419115259524, 0.0407284036469078),
        (0.10400419115259524, 0.0015776490033637064),
    ];
    let list: Vec<String> = points.iter().map(|(v, _)| format!("{v:e}")).collect();
    let scene = edit(
        SLS_SCENE,
        "v_min = 1e-6\nv_max = 1.0\ncount = 7\n",
        &format!("v = [{}]\ntolerance = 1e-8\n", list.join(", ")),
    );
    let t = run_ok(&dir.write("scene.toml", &scene));
    assert_eq!(t.column("v"), points.map(|p| p.0).to_vec());
    for (mu, (v, expected)) in t.column("mu").into_iter().zip(points) {
        assert_close(mu, expected, 1e-6, &format!("μ at v = {v}"));
    }
}

// ------------------------------------------ sanity warnings (need μ)

/// Runs forward on `scene`, which must succeed, and returns the `warning:`
/// lines of its stderr.
fn warning_lines(scene: &Path) -> Vec<String> {
    let out = forward(scene, None);
    let stderr = text(&out.stderr);
    assert!(out.status.success(), "{}: {stderr}", scene.display());
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr
        .lines()
        .filter(|l| l.starts_with("warning:"))
        .map(String::from)
        .collect()
}

/// The bundled example sphere with `from` replaced by `to` and 9 speeds.
fn example_sphere_with(from: &str, to: &str) -> String {
    let base = fs::read_to_string(data("example-sphere.toml")).unwrap();
    edit(&edit(&base, from, to), "count = 41", "count = 9")
}

#[test]
fn bundled_examples_print_no_sanity_warnings() {
    for name in [
        "example-sphere.toml",
        "hn-rubber.toml",
        "paper-fig2-cylinder.toml",
    ] {
        let lines = warning_lines(&data(name));
        assert!(lines.is_empty(), "{name}: {lines:#?}");
    }
}

#[test]
fn contact_beyond_the_small_contact_theory_is_warned_about() {
    // A load far beyond small contacts: 100 N on the example's 5 mm ball, r0 = 5.2 mm.
    let dir = TempDir::new("sanity-load");
    let scene = example_sphere_with("load = 1.0 ", "load = 100.0 ");
    let lines = warning_lines(&dir.write("heavy.toml", &scene));
    let contact: Vec<&String> = lines
        .iter()
        .filter(|l| l.contains("Hertz contact radius"))
        .collect();
    assert_eq!(contact.len(), 1, "{lines:#?}");
    for fragment in ["r = 0.0052 m", "R/3", "geometry.load = 100 N"] {
        assert!(contact[0].contains(fragment), "{fragment}: {}", contact[0]);
    }
}

#[test]
fn radius_in_millimetres_is_warned_about() {
    let dir = TempDir::new("sanity-radius");
    let scene = example_sphere_with("radius = 0.005 ", "radius = 5 ");
    let lines = warning_lines(&dir.write("mm.toml", &scene));
    assert!(
        lines.iter().any(|l| l.contains("geometry.radius = 5 m")
            && l.contains("was it given in mm? (5 mm = 5e-3 m)")),
        "{lines:#?}"
    );
}

// --------------------------------------------------- output file (need μ)

#[test]
fn output_file_is_written_atomically_into_new_folders() {
    let dir = TempDir::new("output");
    let out = dir.path().join("new").join("deeper").join("mu.csv");
    let scene = data("paper-fig2-cylinder.toml");
    let result = forward(&scene, Some(&out));
    let stderr = text(&result.stderr);
    assert!(result.status.success(), "{stderr}");
    assert!(result.stdout.is_empty(), "with -o nothing goes to stdout");
    // The one-line summary names the static contact.
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("a0 ="), "{stderr}");

    let written = fs::read_to_string(&out).unwrap();
    assert_eq!(
        written,
        text(&forward(&scene, None).stdout),
        "file = stdout"
    );
    let mut names: Vec<String> = fs::read_dir(out.parent().unwrap())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    // The CSV and its picture, nothing else.
    assert_eq!(names, ["mu.csv", "mu.png", "mu.svg"], "leftover files");
    let svg = fs::read_to_string(out.with_extension("svg")).unwrap();
    assert!(
        svg.contains("rolling speed v") && svg.contains("low-speed asymptote"),
        "the picture's axes and legend"
    );

    // Running again replaces the files, still without leftovers.
    fs::write(&out, "old").unwrap();
    assert!(forward(&scene, Some(&out)).status.success());
    assert_eq!(fs::read_to_string(&out).unwrap(), written);
    assert_eq!(fs::read_dir(out.parent().unwrap()).unwrap().count(), 3);
}

#[test]
fn failure_leaves_an_existing_output_untouched() {
    let dir = TempDir::new("keep");
    let out = dir.write("mu.csv", "previous result\n");
    let scene = dir.write(
        "bad.toml",
        edit(SLS_SCENE, "radius = 0.01", "radius = -0.01"),
    );
    let result = forward(&scene, Some(&out));
    assert_failure_names(&result, "bad.toml", &["radius"]);
    assert_eq!(fs::read_to_string(&out).unwrap(), "previous result\n");
    let mut names: Vec<String> = fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, vec!["bad.toml", "mu.csv"]);
}

#[test]
fn failure_creates_no_output_file() {
    let dir = TempDir::new("none");
    let out = dir.path().join("sub").join("mu.csv");
    let scene = dir.write("bad.toml", edit(SLS_SCENE, "count = 7", "count = 0"));
    assert_failure_names(&forward(&scene, Some(&out)), "bad.toml", &["count"]);
    assert!(!out.exists());
}

#[test]
fn output_path_that_is_a_folder_is_rejected() {
    let dir = TempDir::new("outdir");
    let scene = data("paper-fig2-sphere.toml");
    let result = forward(&scene, Some(dir.path()));
    let name = dir
        .path()
        .file_name()
        .unwrap()
        .to_string_lossy()
        .into_owned();
    assert_failure_names(&result, &name, &["is a folder"]);
}

// --------------------------------------------- materials and shifts (need μ)

#[test]
fn prony_scene_equals_the_equivalent_standard_linear_solid() {
    // SLS(E0, E1, τ) is the one-term Prony series H = E1 − E0, τ_P = τ E0/E1.
    let dir = TempDir::new("prony-sls");
    let sls = run_ok(&dir.write("sls.toml", SLS_SCENE));
    let prony = edit(
        SLS_SCENE,
        "model = \"sls\"\nE0 = 1e6\nE1 = 1e7\ntau = 1.0",
        "model = \"prony\"\nE1 = 1e7\nH = [9e6]\ntau = [0.1]",
    );
    let prony = run_ok(&dir.write("prony.toml", &prony));
    for (a, b) in sls.column("mu").into_iter().zip(prony.column("mu")) {
        assert_close(b, a, 1e-9, "μ prony vs sls");
    }
}

#[test]
fn wlf_temperature_equals_a_scaled_relaxation_time() {
    // E(ω, T) = E(ω a_T, T_ref): for a standard linear solid the same as τ → τ a_T.
    let dir = TempDir::new("wlf");
    let (t_ref, c1, c2, t) = (20.0, 8.86, 101.6, 35.0);
    let log_at: f64 = -c1 * (t - t_ref) / (c2 + t - t_ref);
    let shifted = edit(
        SLS_SCENE,
        "tau = 1.0\n",
        &format!(
            "tau = 1.0\n[material.shift]\nmodel = \"wlf\"\nT_ref = {t_ref:?}\nC1 = {c1}\nC2 = {c2}\n"
        ),
    ) + &format!("temperature = {t:?}\n");
    let scaled = edit(
        SLS_SCENE,
        "tau = 1.0",
        &format!("tau = {:e}", 10f64.powf(log_at)),
    );
    let a = run_ok_at(&dir.write("shifted.toml", &shifted), t);
    let b = run_ok(&dir.write("scaled.toml", &scaled));
    for (x, y) in a.column("mu").into_iter().zip(b.column("mu")) {
        assert_close(x, y, 1e-6, "μ shifted vs scaled");
    }
}

#[test]
fn free_shift_temperature_equals_a_scaled_relaxation_time() {
    let dir = TempDir::new("free");
    let shifted = edit(
        SLS_SCENE,
        "tau = 1.0\n",
        "tau = 1.0\n[material.shift]\nmodel = \"free\"\nT_ref = 20.0\n\
         log_aT = [{ T = 0.0, log_aT = 2.0 }, { T = 40.0, log_aT = -2.0 }]\n",
    ) + "temperature = 30.0\n";
    // Linear in T between 20 °C (0) and 40 °C (−2): log10 a_T(30 °C) = −1.
    let scaled = edit(SLS_SCENE, "tau = 1.0", "tau = 0.1");
    let a = run_ok_at(&dir.write("shifted.toml", &shifted), 30.0);
    let b = run_ok(&dir.write("scaled.toml", &scaled));
    for (x, y) in a.column("mu").into_iter().zip(b.column("mu")) {
        assert_close(x, y, 1e-6, "μ shifted vs scaled");
    }
}

#[test]
fn free_shift_is_exact_at_listed_temperatures_and_knows_t_ref() {
    // T_ref = 20 °C is not listed but counts as log10 a_T = 0: 30 °C lies
    // between it and 40 °C (−2), so log10 a_T = −1; 40 °C itself gives −2.
    let dir = TempDir::new("free-listed");
    let base = edit(
        SLS_SCENE,
        "tau = 1.0\n",
        "tau = 1.0\n[material.shift]\nmodel = \"free\"\nT_ref = 20.0\n\
         log_aT = [{ T = 40.0, log_aT = -2.0 }]\n",
    );
    for (t, tau) in [(30.0, "0.1"), (40.0, "0.01")] {
        let shifted = format!("{base}temperature = {t:?}\n");
        let scaled = edit(SLS_SCENE, "tau = 1.0", &format!("tau = {tau}"));
        let a = run_ok_at(&dir.write("shifted.toml", &shifted), t);
        let b = run_ok(&dir.write("scaled.toml", &scaled));
        for (x, y) in a.column("mu").into_iter().zip(b.column("mu")) {
            assert_close(x, y, 1e-6, "μ shifted vs scaled");
        }
    }
}

#[test]
fn table_scene_follows_the_tabulated_solid() {
    // A dense table of the standard linear solid (20 points per decade, Hz
    // column) must give nearly the μ(v) of the solid itself.
    let dir = TempDir::new("table");
    let (e0, e1, tau) = (1e6f64, 1e7f64, 1.0f64);
    let mut csv = String::from("# SLS E0 = 1 MPa, E1 = 10 MPa, tau = 1 s\nf,E_storage,E_loss\n");
    for k in 0..=320 {
        let omega = 10f64.powf(-8.0 + k as f64 / 20.0);
        // E = E1 (1 + iωτ)/(E1/E0 + iωτ)
        let (a, b) = (e1 / e0, omega * tau);
        let den = a * a + b * b;
        let storage = e1 * (a + b * b) / den;
        let loss = e1 * b * (a - 1.0) / den;
        csv += &format!(
            "{:e},{storage:e},{loss:e}\n",
            omega / (2.0 * std::f64::consts::PI)
        );
    }
    dir.write("modulus.csv", &csv);
    let table_scene = edit(
        TABLE_SCENE,
        "load = 0.15\n",
        "load = 0.15\n[substrate]\npoisson = 0.0\n",
    );
    let table_path = dir.write("table.toml", &table_scene);
    let header: Vec<&str> = HEADER
        .iter()
        .copied()
        .chain(["table_error_estimate"])
        .collect();
    let t = run_ok_with_header(&table_path, &header);
    let s = run_ok(&dir.write("sls.toml", SLS_SCENE));
    for (x, y) in t.column("mu").into_iter().zip(s.column("mu")) {
        assert_close(x, y, 2e-2, "μ table vs sls");
    }
    // The table's own interpolation error: 20 rows a decade of a smooth
    // solid err by about 1e-6 of μ (crates/model/tests/table_friction.rs);
    // the estimate is stated per row and in the notes and summary.
    let estimate = t.column("table_error_estimate");
    assert!(
        estimate.iter().all(|&e| (0.0..1e-4).contains(&e)),
        "{estimate:?}"
    );
    assert!(estimate.iter().any(|&e| e > 0.0), "{estimate:?}");
    let stderr = text(&forward(&table_path, None).stderr);
    assert!(
        stderr.contains("between the rows the interpolation is estimated to err by up to")
            && stderr.contains("μ estimated to err by up to")
            && stderr.contains("(column table_error_estimate)"),
        "{stderr}"
    );
}

#[test]
fn explicit_speed_list_is_kept() {
    let dir = TempDir::new("list");
    let scene = edit(
        PRONY_SCENE,
        "v_min = 1e-6\nv_max = 1.0\ncount = 7",
        "v = [1e-5, 3e-4, 2e-3]",
    );
    let t = run_ok(&dir.write("list.toml", &scene));
    assert_eq!(t.column("v"), vec![1e-5, 3e-4, 2e-3]);
}

// ------------------------------------------- bad input: files and syntax

#[test]
fn missing_scene_file() {
    let dir = TempDir::new("missing");
    let out = forward(&dir.path().join("nothere.toml"), None);
    assert_failure_names(&out, "nothere.toml", &["cannot read scene file"]);
}

#[test]
fn malformed_toml_shows_line_and_column() {
    let scene = edit(SLS_SCENE, "load = 0.15", "load = = 0.15");
    assert_rejected(&scene, &[], &["line 5, column", "load = = 0.15"]);
}

#[test]
fn unknown_key_is_named() {
    let scene = edit(SLS_SCENE, "radius = 0.01", "radus = 0.01");
    assert_rejected(&scene, &[], &["unknown field `radus`", "line 4"]);
}

#[test]
fn unknown_section_is_named() {
    let scene = edit(SLS_SCENE, "[sweep]", "[sweeps]");
    assert_rejected(&scene, &[], &["unknown field `sweeps`"]);
}

#[test]
fn unknown_key_in_fit_section_is_named() {
    let scene = format!("{SLS_SCENE}[fit]\nE0 = 2e6\nsmoothness = 3\n");
    assert_rejected(&scene, &[], &["unknown field `smoothness`"]);
}

#[test]
fn unknown_key_in_shift_section_is_named() {
    let scene = edit(
        SLS_SCENE,
        "tau = 1.0\n",
        "tau = 1.0\n[material.shift]\nmodel = \"wlf\"\nT_ref = 20.0\nC1 = 8.86\nC2 = 101.6\nC3 = 1\n",
    );
    assert_rejected(&scene, &[], &["unknown field `C3`"]);
}

#[test]
fn key_of_another_material_model_is_named() {
    let scene = edit(SLS_SCENE, "tau = 1.0", "tau = 1.0\nH = [1e6]");
    assert_rejected(&scene, &[], &["key `H`", "\"sls\""]);
}

#[test]
fn missing_material_key_is_named() {
    let scene = edit(SLS_SCENE, "E1 = 1e7\n", "");
    assert_rejected(&scene, &[], &["needs the key `E1`"]);
}

#[test]
fn wrong_type_is_reported() {
    let scene = edit(SLS_SCENE, "radius = 0.01", "radius = \"1 cm\"");
    assert_rejected(&scene, &[], &["radius = \"1 cm\"", "invalid type: string"]);
}

#[test]
fn wrong_type_of_count_is_reported() {
    let scene = edit(SLS_SCENE, "count = 7", "count = 7.5");
    assert_rejected(&scene, &[], &["count = 7.5", "invalid type"]);
}

#[test]
fn unknown_shape_is_reported() {
    let scene = edit(SLS_SCENE, "shape = \"sphere\"", "shape = \"cube\"");
    assert_rejected(
        &scene,
        &[],
        &["unknown variant `cube`", "sphere", "cylinder"],
    );
}

#[test]
fn nan_is_rejected_with_its_key() {
    let scene = edit(SLS_SCENE, "radius = 0.01", "radius = nan");
    assert_rejected(&scene, &[], &["radius = nan", "finite"]);
}

#[test]
fn infinity_is_rejected_with_its_key() {
    let scene = edit(SLS_SCENE, "load = 0.15", "load = +inf");
    assert_rejected(&scene, &[], &["load = +inf", "finite"]);
}

#[test]
fn nan_inside_an_array_is_rejected() {
    let scene = edit(PRONY_SCENE, "H = [4e6, 5e6]", "H = [4e6, nan]");
    assert_rejected(&scene, &[], &["H = [4e6, nan]", "finite"]);
}

// ------------------------------------------------ bad input: value ranges

#[test]
fn zero_radius_is_rejected() {
    let scene = edit(SLS_SCENE, "radius = 0.01", "radius = 0.0");
    assert_rejected(
        &scene,
        &[],
        &["[geometry]", "radius = 0", "greater than zero"],
    );
}

#[test]
fn negative_radius_is_rejected() {
    let scene = edit(SLS_SCENE, "radius = 0.01", "radius = -0.01");
    assert_rejected(
        &scene,
        &[],
        &["[geometry]", "radius = -0.01", "greater than zero"],
    );
}

#[test]
fn negative_load_is_rejected() {
    let scene = edit(SLS_SCENE, "load = 0.15", "load = -0.15");
    assert_rejected(
        &scene,
        &[],
        &["[geometry]", "load = -0.15", "greater than zero"],
    );
}

#[test]
fn zero_e0_is_rejected() {
    let scene = edit(SLS_SCENE, "E0 = 1e6", "E0 = 0");
    assert_rejected(&scene, &[], &["[material]", "E0 = 0", "greater than zero"]);
}

#[test]
fn negative_e1_is_rejected() {
    let scene = edit(PRONY_SCENE, "E1 = 1e7", "E1 = -1e7");
    assert_rejected(
        &scene,
        &[],
        &["[material]", "E1 = -10000000", "greater than zero"],
    );
}

#[test]
fn zero_tau_is_rejected() {
    let scene = edit(SLS_SCENE, "tau = 1.0", "tau = 0.0");
    assert_rejected(&scene, &[], &["[material]", "tau = 0", "greater than zero"]);
}

#[test]
fn negative_prony_tau_is_rejected() {
    let scene = edit(PRONY_SCENE, "tau = [0.1, 1.0]", "tau = [0.1, -1.0]");
    assert_rejected(
        &scene,
        &[],
        &["[material]", "tau[1] = -1", "greater than zero"],
    );
}

#[test]
fn negative_thickness_is_rejected() {
    let scene = edit(
        SLS_SCENE,
        "poisson = 0.0",
        "poisson = 0.0\nthickness = -1e-3",
    );
    assert_rejected(
        &scene,
        &[],
        &["[substrate]", "thickness = -0.001", "greater than zero"],
    );
}

#[test]
fn zero_thickness_is_rejected() {
    let scene = edit(SLS_SCENE, "poisson = 0.0", "poisson = 0.0\nthickness = 0.0");
    assert_rejected(
        &scene,
        &[],
        &["[substrate]", "thickness = 0", "greater than zero"],
    );
}

#[test]
fn poisson_above_one_half_is_rejected() {
    let scene = edit(SLS_SCENE, "poisson = 0.0", "poisson = 0.6");
    assert_rejected(
        &scene,
        &[],
        &["[substrate]: poisson = 0.6 outside [0, 0.5]: Poisson's ratio of rubber is 0.5"],
    );
}

#[test]
fn negative_poisson_is_rejected() {
    let scene = edit(SLS_SCENE, "poisson = 0.0", "poisson = -0.1");
    assert_rejected(
        &scene,
        &[],
        &["[substrate]: poisson = -0.1 outside [0, 0.5]: Poisson's ratio of rubber is 0.5"],
    );
}

#[test]
fn prony_length_mismatch_is_rejected() {
    let scene = edit(PRONY_SCENE, "H = [4e6, 5e6]", "H = [4e6, 5e6, 1e5]");
    assert_rejected(&scene, &[], &["[material]", "H has 3", "tau has 2"]);
}

#[test]
fn prony_without_static_modulus_is_rejected() {
    let scene = edit(PRONY_SCENE, "H = [4e6, 5e6]", "H = [5e6, 5e6]");
    assert_rejected(
        &scene,
        &[],
        &["[material]", "E0 = E1 - sum(H)", "greater than zero"],
    );
}

#[test]
fn sls_tau_array_is_rejected() {
    let scene = edit(SLS_SCENE, "tau = 1.0", "tau = [1.0]");
    assert_rejected(&scene, &[], &["[material]", "`tau` must be a number"]);
}

// --------------------------------------------------- bad input: the sweep

#[test]
fn v_min_not_below_v_max_is_rejected() {
    let scene = edit(SLS_SCENE, "v_min = 1e-6", "v_min = 1.0");
    assert_rejected(&scene, &[], &["[sweep]", "v_min = 1", "v_max = 1"]);
}

#[test]
fn count_below_one_is_rejected() {
    let scene = edit(SLS_SCENE, "count = 7", "count = 0");
    assert_rejected(&scene, &[], &["[sweep]", "count = 0", "at least 1"]);
}

#[test]
fn negative_count_is_rejected() {
    let scene = edit(SLS_SCENE, "count = 7", "count = -5");
    assert_rejected(&scene, &[], &["[sweep]", "count = -5"]);
}

#[test]
fn non_positive_v_min_is_rejected() {
    let scene = edit(SLS_SCENE, "v_min = 1e-6", "v_min = -1e-6");
    assert_rejected(
        &scene,
        &[],
        &["[sweep]", "v_min = -0.000001", "greater than zero"],
    );
}

#[test]
fn non_positive_listed_speed_is_rejected() {
    let scene = edit(
        SLS_SCENE,
        "v_min = 1e-6\nv_max = 1.0\ncount = 7",
        "v = [1e-3, 0.0, 1.0]",
    );
    assert_rejected(&scene, &[], &["[sweep]", "v[1] = 0", "greater than zero"]);
}

#[test]
fn unordered_speed_list_is_rejected() {
    let scene = edit(
        SLS_SCENE,
        "v_min = 1e-6\nv_max = 1.0\ncount = 7",
        "v = [1e-3, 1e-4]",
    );
    assert_rejected(&scene, &[], &["[sweep]", "increasing"]);
}

#[test]
fn range_and_list_together_are_rejected() {
    let scene = edit(SLS_SCENE, "count = 7", "count = 7\nv = [1e-3]");
    assert_rejected(&scene, &[], &["[sweep]", "not both"]);
}

#[test]
fn missing_sweep_is_rejected() {
    let scene = SLS_SCENE.split("[sweep]").next().unwrap().to_string();
    assert_rejected(&scene, &[], &["[sweep]"]);
}

#[test]
fn missing_material_is_rejected() {
    let scene = edit(
        SLS_SCENE,
        "[material]\nmodel = \"sls\"\nE0 = 1e6\nE1 = 1e7\ntau = 1.0\n",
        "",
    );
    assert_rejected(&scene, &[], &["[material]"]);
}

#[test]
fn tolerance_out_of_range_is_rejected() {
    let scene = edit(SLS_SCENE, "count = 7", "count = 7\ntolerance = 0.5");
    assert_rejected(&scene, &[], &["[sweep]", "tolerance = 0.5"]);
}

#[test]
fn temperature_without_shift_is_rejected() {
    let scene = edit(SLS_SCENE, "count = 7", "count = 7\ntemperature = 40.0");
    assert_rejected(&scene, &[], &["temperature", "[material.shift]"]);
}

#[test]
fn temperature_outside_a_free_shift_is_rejected() {
    let scene = edit(
        SLS_SCENE,
        "tau = 1.0\n",
        "tau = 1.0\n[material.shift]\nmodel = \"free\"\nT_ref = 20.0\n\
         log_aT = [{ T = 0.0, log_aT = 2.0 }, { T = 40.0, log_aT = -2.0 }]\n",
    ) + "temperature = 80.0\n";
    // The model's rule and message (temperature, listed range), with the
    // section, key and file from the CLI.
    assert_rejected(
        &scene,
        &[],
        &[
            "[material.shift] at [sweep] temperature = 80",
            "T = 80 °C",
            "outside",
            "0 to 40 °C",
            "`log_aT`",
        ],
    );
    let below = edit(&scene, "temperature = 80.0", "temperature = -0.5");
    assert_rejected(&below, &[], &["T = -0.5 °C", "outside", "0 to 40 °C"]);
}

#[test]
fn free_shift_entries_are_checked_and_named() {
    let with_entries = |entries: &str| {
        edit(
            SLS_SCENE,
            "tau = 1.0\n",
            &format!(
                "tau = 1.0\n[material.shift]\nmodel = \"free\"\nT_ref = 20.0\nlog_aT = {entries}\n"
            ),
        )
    };
    assert_rejected(
        &with_entries("[{ T = 0.0, log_aT = 2.0 }, { T = 0.0, log_aT = 2.5 }]"),
        &[],
        &[
            "[material.shift]",
            "`log_aT`",
            "entry 1",
            "listed before as entry 0",
        ],
    );
    assert_rejected(
        &with_entries("[{ T = 20.0, log_aT = 1.0 }]"),
        &[],
        &["[material.shift]", "`log_aT`", "reference temperature"],
    );
    assert_rejected(
        &with_entries("[]"),
        &[],
        &["[material.shift]", "`log_aT`", "no temperatures"],
    );
}

#[test]
fn wlf_shift_without_constants_is_rejected() {
    let scene = edit(
        SLS_SCENE,
        "tau = 1.0\n",
        "tau = 1.0\n[material.shift]\nmodel = \"wlf\"\nT_ref = 20.0\nC1 = 8.86\n",
    );
    assert_rejected(&scene, &[], &["[material.shift]", "`C2`"]);
}

// ------------------------------------------------------ bad input: [fit]

#[test]
fn fit_terms_must_be_positive() {
    let scene = format!("{SLS_SCENE}[fit]\nterms = 0\n");
    assert_rejected(&scene, &[], &["[fit]", "terms = 0"]);
}

#[test]
fn fit_terms_must_be_a_number_or_auto() {
    let scene = format!("{SLS_SCENE}[fit]\nterms = \"many\"\n");
    assert_rejected(&scene, &[], &["terms = \"many\"", "auto"]);
}

#[test]
fn fit_anchor_must_be_positive() {
    let scene = format!("{SLS_SCENE}[fit]\nE_at = {{ omega = 1.0, E = -1e8 }}\n");
    assert_rejected(&scene, &[], &["[fit]", "E_at.E"]);
}

#[test]
fn fit_method_must_be_a_string() {
    let scene = format!("{SLS_SCENE}[fit]\nmethod = 3\n");
    assert_rejected(&scene, &[], &["method = 3", "invalid type"]);
}

// ----------------------------------------------- bad input: modulus tables

#[test]
fn missing_table_file() {
    let stderr = assert_rejected(
        TABLE_SCENE,
        &[],
        &["modulus.csv", "cannot read modulus table"],
    );
    assert!(stderr.contains("[material]"), "{stderr}");
}

#[test]
fn malformed_table_value() {
    let table = "omega,E_storage,E_loss\n0.1,1e6,1e5\n1,two,8e5\n";
    assert_rejected(
        TABLE_SCENE,
        &[("modulus.csv", table)],
        &["modulus.csv", "line 3", "E_storage", "\"two\""],
    );
}

#[test]
fn malformed_table_row() {
    let table = "omega,E_storage,E_loss\n0.1,1e6,1e5\n1,2e6\n";
    assert_rejected(
        TABLE_SCENE,
        &[("modulus.csv", table)],
        &["modulus.csv", "line: 3"],
    );
}

#[test]
fn table_without_frequency_column() {
    let table = "w,E_storage,E_loss\n0.1,1e6,1e5\n1,2e6,8e5\n";
    assert_rejected(
        TABLE_SCENE,
        &[("modulus.csv", table)],
        &["modulus.csv", "`omega`", "`f`"],
    );
}

#[test]
fn table_without_loss_column() {
    let table = "omega,E_storage\n0.1,1e6\n1,2e6\n";
    assert_rejected(
        TABLE_SCENE,
        &[("modulus.csv", table)],
        &["modulus.csv", "`E_loss`"],
    );
}

#[test]
fn table_with_non_increasing_frequencies() {
    let table = "omega,E_storage,E_loss\n0.1,1e6,1e5\n1,2e6,8e5\n1,3e6,9e5\n";
    assert_rejected(
        TABLE_SCENE,
        &[("modulus.csv", table)],
        &["modulus.csv", "line 4", "increasing"],
    );
}

#[test]
fn empty_table() {
    assert_rejected(
        TABLE_SCENE,
        &[("modulus.csv", "")],
        &["modulus.csv", "empty"],
    );
}

#[test]
fn table_with_header_only() {
    let table = "# nothing measured yet\nomega,E_storage,E_loss\n";
    assert_rejected(
        TABLE_SCENE,
        &[("modulus.csv", table)],
        &["modulus.csv", "0 data row"],
    );
}

#[test]
fn table_with_non_positive_modulus() {
    let table = "omega,E_storage,E_loss\n0.1,1e6,1e5\n1,2e6,-8e5\n";
    assert_rejected(
        TABLE_SCENE,
        &[("modulus.csv", table)],
        &["modulus.csv", "line 3", "E_loss", "greater than zero"],
    );
}

#[test]
fn table_with_nan_modulus() {
    let table = "omega,E_storage,E_loss\n0.1,1e6,1e5\n1,NaN,8e5\n";
    assert_rejected(
        TABLE_SCENE,
        &[("modulus.csv", table)],
        &["modulus.csv", "line 3", "finite"],
    );
}

#[test]
fn good_table_is_read() {
    // Reading and checking the table must not be what fails: any error left
    // is the model's, never the table's.
    let dir = TempDir::new("good-table");
    dir.write("modulus.csv", GOOD_TABLE);
    let out = forward(&dir.write("scene.toml", TABLE_SCENE), None);
    let stderr = text(&out.stderr);
    assert!(!stderr.contains("modulus table"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn command_line_errors_exit_non_zero() {
    let out = rollfit(&[std::ffi::OsStr::new("forward")]);
    assert!(!out.status.success());
    assert!(text(&out.stderr).contains("SCENE"));
    let out = rollfit(&[std::ffi::OsStr::new("frobnicate")]);
    assert!(!out.status.success());
}

// ------------------------------- Havriliak–Negami and synthetic noise

/// A Havriliak–Negami scene with α = β = 1, i.e. the standard linear solid
/// of `SLS_SCENE` (paper τ = 1 s = τ_HN E1/E0).
const HN_SCENE: &str = r#"[geometry]
shape = "sphere"
radius = 0.01
load = 0.15

[substrate]
poisson = 0.0

[material]
model = "havriliak-negami"
E0 = 1e6
E1 = 1e7
tau = 0.1
alpha = 1.0
beta = 1.0

[sweep]
v_min = 1e-6
v_max = 1.0
count = 7
"#;

const NOISY_HEADER: [&str; 9] = [
    "v",
    "mu",
    "sigma",
    "mu_exact",
    "mu_low_speed",
    "contact_size_static",
    "mean_pressure_static",
    "centroid_shift",
    "gt_alpha",
];

/// Runs `rollfit forward SCENE extra..` and returns (stdout, stderr) after
/// checking success.
fn forward_with(scene: &Path, extra: &[&str]) -> (String, String) {
    let mut args = vec![std::ffi::OsStr::new("forward"), scene.as_os_str()];
    args.extend(extra.iter().map(std::ffi::OsStr::new));
    let out = rollfit(&args);
    let stderr = text(&out.stderr);
    assert!(out.status.success(), "{extra:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    (text(&out.stdout), stderr)
}

#[test]
fn havriliak_negami_with_alpha_beta_one_is_the_standard_linear_solid() {
    let dir = TempDir::new("hn-sls");
    let sls = run_ok(&dir.write("sls.toml", SLS_SCENE));
    for model in ["\"havriliak-negami\"", "\"hn\""] {
        let scene = edit(HN_SCENE, "\"havriliak-negami\"", model);
        let hn = run_ok(&dir.write("hn.toml", &scene));
        for column in ["mu", "mu_low_speed", "gt_alpha"] {
            for (a, b) in sls.column(column).into_iter().zip(hn.column(column)) {
                // Different tail bounds (sampled for HN, exact for the
                // solid) stop the sums at slightly different nodes.
                assert_close(b, a, 1e-7, &format!("{model} {column} vs sls"));
            }
        }
    }
}

#[test]
fn hn_rubber_example_shows_rise_and_peak() {
    let t = check_example("hn-rubber.toml", 41, 1e-8, 1.0, 0.005);
    let (v, mu) = (t.column("v"), t.column("mu"));
    assert!(v[40] / v[0] >= 1e6, "at least 6 decades");
    let i = (0..mu.len())
        .max_by(|&a, &b| mu[a].total_cmp(&mu[b]))
        .unwrap();
    assert!((5..36).contains(&i), "peak at index {i}, v = {}", v[i]);
    // At the lowest speed μ follows the power-law asymptote μ ∝ v^0.55
    // (E″ ∝ ω^α) to within its slowly vanishing correction.
    let low = t.column("mu_low_speed");
    assert_close(mu[0], low[0], 3e-2, "μ vs asymptote at the lowest speed");
    assert_close(low[5] / low[0], (v[5] / v[0]).powf(0.55), 1e-9, "v^α");
}

#[test]
fn hn_rubber_data_is_what_its_documented_command_makes() {
    let dir = TempDir::new("hn-data");
    let out = dir.path().join("hn-rubber.csv");
    let scene = data("hn-rubber.toml");
    let (_, _) = forward_with(
        &scene,
        &[
            "--noise",
            "0.01",
            "--seed",
            "1",
            "-o",
            out.to_str().unwrap(),
        ],
    );
    let made = parse_csv(&fs::read_to_string(&out).unwrap());
    let stored = parse_csv(&fs::read_to_string(data("hn-rubber.csv")).unwrap());
    assert_eq!(stored.header, NOISY_HEADER);
    assert_eq!(made.header, stored.header);
    assert_eq!(made.column("v"), stored.column("v"));
    assert_eq!(stored.rows.len(), 41);
    // Equal up to the quadrature tolerance (1e-6), so that a more accurate
    // μ in a later version does not break the data set's provenance.
    for name in ["mu", "sigma", "mu_exact"] {
        for (a, b) in made.column(name).into_iter().zip(stored.column(name)) {
            assert_close(a, b, 1e-5, name);
        }
    }
    for (s, m) in stored
        .column("sigma")
        .into_iter()
        .zip(stored.column("mu_exact"))
    {
        assert_close(s, 0.01 * m, 1e-12, "sigma = 1 % of μ");
    }
}

#[test]
fn noise_is_deterministic_for_a_seed() {
    let dir = TempDir::new("noise-seed");
    let scene = dir.write("scene.toml", SLS_SCENE);
    let (a, _) = forward_with(&scene, &["--noise", "0.02", "--seed", "42"]);
    let (b, _) = forward_with(&scene, &["--noise", "0.02", "--seed", "42"]);
    assert_eq!(a, b, "same seed, same file");
    let (c, _) = forward_with(&scene, &["--noise", "0.02", "--seed", "43"]);
    assert_ne!(a, c, "another seed, other noise");
    // --seed defaults to 0.
    let (d, _) = forward_with(&scene, &["--noise", "0.02"]);
    let (e, _) = forward_with(&scene, &["--noise", "0.02", "--seed", "0"]);
    assert_eq!(d, e);
    let (a, c) = (parse_csv(&a), parse_csv(&c));
    assert_eq!(a.header, NOISY_HEADER);
    assert_eq!(a.column("mu_exact"), c.column("mu_exact"));
    assert!(
        a.column("mu")
            .iter()
            .zip(c.column("mu"))
            .all(|(x, y)| *x != y)
    );
}

#[test]
fn noise_columns_and_statistics_are_sane() {
    let dir = TempDir::new("noise-stats");
    let scene = dir.write("scene.toml", edit(SLS_SCENE, "count = 7", "count = 400"));
    let rel = 0.05;
    let exact = run_ok(&scene);
    let (noisy, _) = forward_with(&scene, &["--noise", "0.05", "--seed", "7"]);
    let noisy = parse_csv(&noisy);
    assert_eq!(noisy.header, NOISY_HEADER);
    assert_eq!(noisy.column("v"), exact.column("v"));
    assert_eq!(noisy.column("mu_exact"), exact.column("mu"));
    // The model columns are the noiseless run's.
    for name in &HEADER[2..] {
        assert_eq!(noisy.column(name), exact.column(name), "{name}");
    }
    let (mu, sigma, mu_exact) = (
        noisy.column("mu"),
        noisy.column("sigma"),
        noisy.column("mu_exact"),
    );
    let z: Vec<f64> = (0..mu.len())
        .map(|i| {
            assert_eq!(sigma[i], rel * mu_exact[i]);
            (mu[i] - mu_exact[i]) / sigma[i]
        })
        .collect();
    let n = z.len() as f64;
    let mean = z.iter().sum::<f64>() / n;
    let sd = (z.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    // 400 standard normal deviates: the mean is within 4 standard errors
    // (0.2) of 0, the standard deviation within 15 % of 1, none beyond 6.
    assert!(mean.abs() < 0.2, "mean of z = {mean}");
    assert!((sd - 1.0).abs() < 0.15, "standard deviation of z = {sd}");
    assert!(z.iter().all(|x| x.abs() < 6.0));
    // No noise at all would write σ = 0, which `fit` refuses: the
    // noiseless curve is `forward` without --noise.
    let out = rollfit(&[
        std::ffi::OsStr::new("forward"),
        scene.as_os_str(),
        std::ffi::OsStr::new("--noise"),
        std::ffi::OsStr::new("0"),
    ]);
    assert_failure(&out, &["--noise", "greater than zero", "leave --noise out"]);
}

#[test]
fn noise_file_output_equals_stdout() {
    let dir = TempDir::new("noise-file");
    let scene = dir.write("scene.toml", SLS_SCENE);
    let out = dir.path().join("noisy.csv");
    let (stdout, _) = forward_with(&scene, &["--noise", "0.01", "--seed", "3"]);
    let (nothing, _) = forward_with(
        &scene,
        &[
            "--noise",
            "0.01",
            "--seed",
            "3",
            "-o",
            out.to_str().unwrap(),
        ],
    );
    assert!(nothing.is_empty());
    assert_eq!(fs::read_to_string(&out).unwrap(), stdout);
}

#[test]
fn bad_noise_level_is_refused() {
    let dir = TempDir::new("noise-bad");
    let scene = dir.write("scene.toml", SLS_SCENE);
    for bad in ["-0.01", "nan", "inf", "-inf", "1%", "lots"] {
        let out = rollfit(&[
            std::ffi::OsStr::new("forward"),
            scene.as_os_str(),
            std::ffi::OsStr::new("--noise"),
            std::ffi::OsStr::new(bad),
        ]);
        let stderr = text(&out.stderr);
        assert!(!out.status.success(), "--noise {bad} accepted");
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert!(out.stdout.is_empty());
        assert!(
            stderr.contains("--noise") && stderr.contains(bad),
            "--noise {bad}: {stderr}"
        );
    }
}

#[test]
fn seed_without_noise_is_refused() {
    let dir = TempDir::new("seed-alone");
    let scene = dir.write("scene.toml", SLS_SCENE);
    let out = rollfit(&[
        std::ffi::OsStr::new("forward"),
        scene.as_os_str(),
        std::ffi::OsStr::new("--seed"),
        std::ffi::OsStr::new("1"),
    ]);
    let stderr = text(&out.stderr);
    assert!(!out.status.success());
    assert!(out.stdout.is_empty());
    assert!(stderr.contains("--noise"), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn havriliak_negami_missing_key_is_named() {
    let scene = edit(HN_SCENE, "beta = 1.0\n", "");
    assert_rejected(
        &scene,
        &[],
        &["[material]", "\"havriliak-negami\"", "needs the key `beta`"],
    );
}

#[test]
fn havriliak_negami_exponent_out_of_range_is_rejected() {
    let scene = edit(HN_SCENE, "alpha = 1.0", "alpha = 1.5");
    assert_rejected(&scene, &[], &["[material]", "alpha = 1.5", "at most 1"]);
    let scene = edit(HN_SCENE, "beta = 1.0", "beta = 0");
    assert_rejected(&scene, &[], &["[material]", "beta = 0", "greater than 0"]);
}

#[test]
fn havriliak_negami_glassy_below_rubbery_is_rejected() {
    let scene = edit(HN_SCENE, "E1 = 1e7", "E1 = 1e5");
    assert_rejected(&scene, &[], &["[material]", "E1 = 100000", "exceed E0"]);
}

#[test]
fn havriliak_negami_foreign_and_array_keys_are_named() {
    let scene = edit(HN_SCENE, "beta = 1.0", "beta = 1.0\nH = [1e6]");
    assert_rejected(&scene, &[], &["key `H`", "\"havriliak-negami\""]);
    let scene = edit(HN_SCENE, "tau = 0.1", "tau = [0.1]");
    assert_rejected(&scene, &[], &["[material]", "`tau` must be a number"]);
    let scene = edit(SLS_SCENE, "tau = 1.0", "tau = 1.0\nalpha = 0.5");
    assert_rejected(&scene, &[], &["key `alpha`", "\"sls\""]);
    let scene = edit(HN_SCENE, "alpha = 1.0", "alpha = \"wide\"");
    assert_rejected(&scene, &[], &["alpha", "invalid type: string"]);
}

// ------------------------------------------------------ temperature sets

/// `SLS_SCENE` with a WLF shift (T_ref = 20 °C); add `temperature = ..`.
fn wlf_scene() -> String {
    edit(
        SLS_SCENE,
        "tau = 1.0\n",
        "tau = 1.0\n[material.shift]\nmodel = \"wlf\"\nT_ref = 20.0\nC1 = 8.86\nC2 = 101.6\n",
    )
}

/// `SLS_SCENE` with a free shift listing 0 °C (2.0) and 40 °C (−2.0)
/// around T_ref = 20 °C; add `temperature = ..`.
fn free_scene() -> String {
    edit(
        SLS_SCENE,
        "tau = 1.0\n",
        "tau = 1.0\n[material.shift]\nmodel = \"free\"\nT_ref = 20.0\n\
         log_aT = [{ T = 0.0, log_aT = 2.0 }, { T = 40.0, log_aT = -2.0 }]\n",
    )
}

/// Listed out of order on purpose (the blocks keep the listed order), with
/// an integer entry (TOML arrays may mix integers and floats).
const SET: [f64; 5] = [20.0, -20.0, 60.0, 0.0, 40.0];
const SET_TOML: &str = "temperature = [20.0, -20.0, 60.0, 0, 40.0]\n";
/// Speeds per block (`count` of `SLS_SCENE`).
const COUNT: usize = 7;

/// The data lines of a CSV (without its header).
fn data_lines(csv: &str) -> Vec<&str> {
    csv.lines().skip(1).collect()
}

#[test]
fn temperature_list_writes_one_block_per_temperature() {
    let dir = TempDir::new("tset");
    let scene = dir.write("set.toml", &(wlf_scene() + SET_TOML));
    let (csv, stderr) = forward_with(&scene, &[]);
    let set = parse_csv(&csv);
    assert_eq!(set.header, with_t(&HEADER), "T is the last column");
    assert_eq!(set.rows.len(), COUNT * SET.len());
    let expected_t: Vec<f64> = SET
        .iter()
        .flat_map(|&t| std::iter::repeat_n(t, COUNT))
        .collect();
    assert_eq!(set.column("T"), expected_t);
    let v = set.column("v");
    for block in v.chunks(COUNT) {
        assert_eq!(block, &v[..COUNT], "every block is the full sweep");
    }
    assert_eq!((v[0], v[COUNT - 1]), (1e-6, 1.0));

    // Each block is, number for number, the single-temperature file.
    let lines = data_lines(&csv);
    for (k, &t) in SET.iter().enumerate() {
        let single = dir.write(
            "single.toml",
            &(wlf_scene() + &format!("temperature = {t:?}\n")),
        );
        let (single_csv, _) = forward_with(&single, &[]);
        let single_table = parse_csv(&single_csv);
        assert_eq!(single_table.header, set.header);
        assert_eq!(
            set.rows[k * COUNT..(k + 1) * COUNT],
            single_table.rows[..],
            "block {k} (T = {t} °C)"
        );
        assert_eq!(
            lines[k * COUNT..(k + 1) * COUNT],
            data_lines(&single_csv)[..],
            "block {k} (T = {t} °C) as text"
        );
    }
    // The shift matters: 20 °C and 60 °C give other curves.
    let mu = set.column("mu");
    assert!(
        mu[..COUNT]
            .iter()
            .zip(&mu[2 * COUNT..3 * COUNT])
            .all(|(a, b)| a != b)
    );

    // The summary is one line and names the temperatures in order.
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("T = 20, -20, 60, 0, 40 °C"), "{stderr}");
    assert!(stderr.contains("5 temperatures"), "{stderr}");
}

#[test]
fn free_shift_temperature_list_equals_scaled_relaxation_times() {
    // log10 a_T: 40 °C → −2, 0 °C → 2, 30 °C → −1 (between T_ref and 40 °C).
    let dir = TempDir::new("tset-free");
    let set = run_ok_with_header(
        &dir.write(
            "set.toml",
            &(free_scene() + "temperature = [40.0, 0.0, 30.0]\n"),
        ),
        &with_t(&HEADER),
    );
    assert_eq!(set.rows.len(), 3 * COUNT);
    let (mu, t) = (set.column("mu"), set.column("T"));
    for (k, (temperature, tau)) in [(40.0, "0.01"), (0.0, "100.0"), (30.0, "0.1")]
        .into_iter()
        .enumerate()
    {
        let scaled = edit(SLS_SCENE, "tau = 1.0", &format!("tau = {tau}"));
        let b = run_ok(&dir.write("scaled.toml", &scaled));
        let block = k * COUNT..(k + 1) * COUNT;
        assert!(t[block.clone()].iter().all(|&x| x == temperature));
        for (x, y) in mu[block].iter().zip(b.column("mu")) {
            assert_close(*x, y, 1e-6, &format!("μ at {temperature} °C vs τ = {tau}"));
        }
    }
}

/// z = (mu − mu_exact)/sigma of every row of a noisy CSV.
fn deviates(table: &Table) -> Vec<f64> {
    let (mu, sigma, exact) = (
        table.column("mu"),
        table.column("sigma"),
        table.column("mu_exact"),
    );
    (0..mu.len())
        .map(|i| (mu[i] - exact[i]) / sigma[i])
        .collect()
}

#[test]
fn temperature_set_noise_is_one_stream_reproducible_by_seed() {
    let dir = TempDir::new("tset-noise");
    let scene = dir.write("set.toml", &(wlf_scene() + SET_TOML));
    let noise = |seed: &str| forward_with(&scene, &["--noise", "0.02", "--seed", seed]).0;
    let (a, b, c) = (noise("11"), noise("11"), noise("12"));
    assert_eq!(a, b, "same seed, same file");
    assert_ne!(a, c, "another seed, other noise");

    let a = parse_csv(&a);
    assert_eq!(a.header, with_t(&NOISY_HEADER), "T is the last column");
    let exact = run_ok_with_header(&scene, &with_t(&HEADER));
    assert_eq!(a.column("mu_exact"), exact.column("mu"));
    assert_eq!(a.column("T"), exact.column("T"));
    for name in &HEADER[2..] {
        assert_eq!(a.column(name), exact.column(name), "{name}");
    }
    for (s, m) in a.column("sigma").into_iter().zip(a.column("mu_exact")) {
        assert_eq!(s, 0.02 * m);
    }

    // One stream in row order over the whole file: the deviates are those
    // of a single sweep of as many rows with the same seed...
    let rows = COUNT * SET.len();
    let long = dir.write(
        "long.toml",
        edit(SLS_SCENE, "count = 7", &format!("count = {rows}")),
    );
    let (long, _) = forward_with(&long, &["--noise", "0.02", "--seed", "11"]);
    let (z, z_long) = (deviates(&a), deviates(&parse_csv(&long)));
    assert_eq!(z.len(), z_long.len());
    for (i, (x, y)) in z.iter().zip(&z_long).enumerate() {
        assert!((x - y).abs() < 1e-9, "deviate {i}: {x} vs {y}");
    }
    // ... so the first block is the single-temperature file with that seed,
    // and the blocks do not repeat one another's noise.
    let first = dir.write(
        "first.toml",
        &(wlf_scene() + &format!("temperature = {:?}\n", SET[0])),
    );
    let (first, _) = forward_with(&first, &["--noise", "0.02", "--seed", "11"]);
    assert_eq!(a.rows[..COUNT], parse_csv(&first).rows[..]);
    assert!(
        z[..COUNT]
            .iter()
            .zip(&z[COUNT..2 * COUNT])
            .all(|(x, y)| x != y)
    );
}

#[test]
fn empty_temperature_list_is_rejected() {
    assert_rejected(
        &(wlf_scene() + "temperature = []\n"),
        &[],
        &["[sweep]", "`temperature = []`", "no temperatures"],
    );
}

#[test]
fn non_finite_temperature_entry_is_rejected() {
    let scene = wlf_scene() + "temperature = [0.0, nan, 40.0]\n";
    let line = scene.lines().count();
    assert_rejected(
        &scene,
        &[],
        &[
            "[sweep] temperature[1]",
            "NaN",
            "finite",
            &format!("line {line}"),
        ],
    );
    assert_rejected(
        &(wlf_scene() + "temperature = [0.0, 20.0, -inf]\n"),
        &[],
        &["[sweep] temperature[2]", "inf", "finite"],
    );
    assert_rejected(
        &(wlf_scene() + "temperature = [0.0, \"warm\"]\n"),
        &[],
        &["[sweep] temperature[1]", "invalid type: string"],
    );
}

#[test]
fn duplicate_temperatures_are_rejected() {
    assert_rejected(
        &(wlf_scene() + "temperature = [0.0, 20.0, 40.0, 20]\n"),
        &[],
        &[
            "[sweep]",
            "temperature[3] = 20",
            "repeats temperature[1] = 20",
        ],
    );
}

#[test]
fn temperature_list_without_shift_is_rejected() {
    assert_rejected(
        &(SLS_SCENE.to_string() + "temperature = [0.0, 20.0]\n"),
        &[],
        &["[sweep]", "temperature = [0, 20]", "[material.shift]"],
    );
}

#[test]
fn temperature_list_outside_a_free_shift_names_the_entry() {
    assert_rejected(
        &(free_scene() + "temperature = [0.0, 40.0, 80.0, 20.0]\n"),
        &[],
        &[
            "[material.shift] at [sweep] temperature[2] = 80 °C",
            "T = 80 °C",
            "outside",
            "0 to 40 °C",
            "`log_aT`",
        ],
    );
    assert_rejected(
        &(free_scene() + "temperature = [-0.5, 20.0]\n"),
        &[],
        &["temperature[0] = -0.5 °C", "outside", "0 to 40 °C"],
    );
}

// ------------------------------------------------- the exact cylinder

/// The columns of `[contact] size = "exact"`: [`HEADER`], the contact edges
/// and the solution's error estimate.
fn exact_header() -> Vec<&'static str> {
    HEADER
        .iter()
        .copied()
        .chain([
            "contact_trailing_edge",
            "contact_leading_edge",
            "error_estimate",
        ])
        .collect()
}

/// `[contact] size = "exact"`: the paper's Fig. 2 cylinder (standard linear
/// solid, E1/E0 = 10) by the exact rolling-contact solution. Its friction
/// maximum is a little above Eq. (11)'s (about 0.7 %, Persson 2010 Fig. 2
/// and the error map in crates/model/tests/eq11_error_map.rs); both limits
/// agree with Eq. (11); the contact edges straddle the axis, shifted to the
/// leading side.
#[test]
fn exact_cylinder_scene_runs_and_sits_just_above_eq11_at_the_maximum() {
    let dir = TempDir::new("exact");
    let base = std::fs::read_to_string(data("paper-fig2-cylinder.toml")).unwrap();
    let exact_scene = dir.write(
        "exact.toml",
        edit(&base, "size = \"dynamic\"", "size = \"exact\""),
    );
    let exact = run_ok_with_header(&exact_scene, &exact_header());
    let paper = run_ok(&data("paper-fig2-cylinder.toml"));
    let (mu_exact, mu_paper) = (exact.column("mu"), paper.column("mu"));
    let max = |m: &[f64]| m.iter().copied().fold(0.0, f64::max);
    let ratio = max(&mu_exact) / max(&mu_paper);
    assert!(
        (1.002..1.012).contains(&ratio),
        "exact/Eq. (11) maximum: {ratio}"
    );
    let n = mu_exact.len();
    for i in [0, n - 1] {
        assert_close(mu_exact[i], mu_paper[i], 1e-3, "a speed limit");
    }
    let (trailing, leading) = (
        exact.column("contact_trailing_edge"),
        exact.column("contact_leading_edge"),
    );
    for i in 0..n {
        assert!(trailing[i] < 0.0 && leading[i] > 0.0);
        assert!(
            leading[i] + trailing[i] > 0.0,
            "centre on the leading side at row {i}"
        );
    }
}

#[test]
fn exact_contact_is_refused_where_it_does_not_apply() {
    let cylinder = edit(
        &edit(SLS_SCENE, "shape = \"sphere\"", "shape = \"cylinder\""),
        "size = \"dynamic\"",
        "size = \"exact\"",
    );
    // A sphere has an exact solution
    // (crates/model/tests/it/exact_sphere.rs); films and other moduli still
    // have none.
    assert_rejected(
        &edit(
            &cylinder,
            "poisson = 0.0",
            "poisson = 0.0\nthickness = 1e-3",
        ),
        &[],
        &["[contact]", "exact", "half-space"],
    );
    assert_rejected(
        &edit(
            &cylinder,
            "model = \"sls\"",
            "model = \"havriliak-negami\"\nalpha = 0.5\nbeta = 0.5",
        ),
        &[],
        &["[contact]", "exact", "\"sls\" or \"prony\""],
    );
}

// ------------------------------------------- the model ladder and auto

/// Runs forward on `scene`, whose CSV ends with the text column `rung`:
/// the numeric table without it, and the rungs.
fn run_auto(scene: &Path) -> (Table, Vec<String>, String) {
    let out = forward(scene, None);
    let stderr = text(&out.stderr);
    assert!(out.status.success(), "{}: {stderr}", scene.display());
    let csv = text(&out.stdout);
    let mut numbers = Vec::new();
    let mut rungs = Vec::new();
    for (i, line) in csv.lines().enumerate() {
        let (rest, last) = line.rsplit_once(',').unwrap();
        if i == 0 {
            assert_eq!(last, "rung");
        } else {
            rungs.push(last.to_string());
        }
        numbers.push(rest.to_string());
    }
    (parse_csv(&numbers.join("\n")), rungs, stderr)
}

/// `[contact] size = "auto"` on the paper's cylinder: every μ within the
/// requested accuracy of the exact rolling cylinder, each row saying which
/// rung gave it and its estimated error, cheaper rungs at low speed, and
/// the summary saying what was chosen.
#[test]
fn auto_scene_meets_its_accuracy_against_the_exact_rung() {
    let dir = TempDir::new("auto");
    let base = std::fs::read_to_string(data("paper-fig2-cylinder.toml")).unwrap();
    let auto_scene = dir.write(
        "auto.toml",
        edit(
            &base,
            "size = \"dynamic\"",
            "size = \"auto\"\naccuracy = 1e-2",
        ),
    );
    let exact_scene = dir.write(
        "exact.toml",
        edit(&base, "size = \"dynamic\"", "size = \"exact\""),
    );
    let (auto, rungs, stderr) = run_auto(&auto_scene);
    let header: Vec<&str> = HEADER.iter().copied().chain(["error_estimate"]).collect();
    assert_eq!(auto.header, header);
    assert!(stderr.contains("auto, accuracy 1e-2 against the exact rolling cylinder"));
    assert!(stderr.contains("estimated error"), "{stderr}");
    let exact = run_ok_with_header(&exact_scene, &exact_header());
    let (mu, estimate, reference, reference_error) = (
        auto.column("mu"),
        auto.column("error_estimate"),
        exact.column("mu"),
        exact.column("error_estimate"),
    );
    for i in 0..mu.len() {
        assert!(
            ["low-speed", "dynamic", "exact"].contains(&rungs[i].as_str()),
            "{}",
            rungs[i]
        );
        assert!(estimate[i] <= 1e-2, "row {i}: estimate {}", estimate[i]);
        let error = (mu[i] / reference[i] - 1.0).abs();
        assert!(
            error <= 1e-2 + reference_error[i],
            "row {i} ({}): off the exact rung by {error:.2e}",
            rungs[i]
        );
    }
    assert_eq!(rungs[0], "low-speed");
    assert!(rungs.iter().any(|r| r == "exact"));
}

/// `size = "low-speed"`: μ is the asymptote column.
#[test]
fn low_speed_rung_is_the_asymptote() {
    let dir = TempDir::new("low");
    let base = std::fs::read_to_string(data("paper-fig2-cylinder.toml")).unwrap();
    let scene = dir.write(
        "low.toml",
        edit(&base, "size = \"dynamic\"", "size = \"low-speed\""),
    );
    let out = forward(&scene, None);
    assert!(out.status.success());
    assert!(text(&out.stderr).contains("low-speed asymptote (Eqs. 18/19) at every speed"));
    let table = parse_csv(&text(&out.stdout));
    assert_eq!(table.column("mu"), table.column("mu_low_speed"));
}

#[test]
fn auto_settings_are_checked() {
    let auto = edit(SLS_SCENE, "size = \"dynamic\"", "size = \"auto\"");
    assert_rejected(
        &edit(
            SLS_SCENE,
            "size = \"dynamic\"",
            "size = \"dynamic\"\naccuracy = 1e-3",
        ),
        &[],
        &["[contact]", "accuracy", "size = \"auto\""],
    );
    for bad in ["0.0", "2.0", "1e-9"] {
        assert_rejected(
            &edit(
                &auto,
                "size = \"auto\"",
                &format!("size = \"auto\"\naccuracy = {bad}"),
            ),
            &[],
            &["[contact]", "accuracy", "between 1e-8 and 0.5"],
        );
    }
    assert_rejected(
        &edit(&auto, "[sweep]", "[sweep]\ntolerance = 1e-6"),
        &[],
        &["[sweep]", "tolerance", "auto"],
    );
    assert_rejected(
        &edit(SLS_SCENE, "size = \"dynamic\"", "size = \"fastest\""),
        &[],
        &["size", "fastest"],
    );
}
