//! End-to-end tests of `rollfit batch`: manifests of the bundled example
//! (data/hn-rubber.toml with data/hn-rubber*.csv, copied into a temporary
//! folder so that the manifest's relative paths are exercised) with fast
//! settings (λ fixed, one start); broken manifests are refused.
//!
//! Every bad-manifest test checks the same promise: a non-zero exit, an
//! error on stderr that names the manifest and the entry (and the line where
//! there is one), no panic, and no output folder.

use crate::common;

use std::collections::BTreeSet;
use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Output;

use common::{Table, TempDir, assert_failure, rollfit, rollfit_in, text};
use serde_json::Value;

// ---------------------------------------------------------------- helpers

/// The workspace root (this test is registered in crates/cli).
fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The columns of summary.csv, in order.
const COLUMNS: [&str; 11] = [
    "entry",
    "status",
    "objective",
    "misfit_per_point",
    "omega_min",
    "omega_max",
    "wall_time_s",
    "converged",
    "C1",
    "C2",
    "message",
];

/// Fast settings for every entry: a fixed λ (no λ search) and one start.
const DEFAULTS: &str = "[defaults]\nlambda = 1e2\nstarts = 1\n";

/// The same settings as flags of `rollfit fit`.
const FLAGS: [&str; 4] = ["--lambda", "1e2", "--starts", "1"];

/// Three entries: the bundled measurement and its two other noise seeds.
const THREE: &str = r#"
[[entry]]
name = "seed1"
scene = "hn-rubber.toml"
data = "hn-rubber.csv"

[[entry]]
name = "seed2"
scene = "hn-rubber.toml"
data = "hn-rubber-seed2.csv"

[[entry]]
name = "seed3"
scene = "hn-rubber.toml"
data = "hn-rubber-seed3.csv"
"#;

const NAMES: [&str; 3] = ["seed1", "seed2", "seed3"];

/// A temporary folder holding copies of the bundled scene and data.
fn bundled(name: &str) -> TempDir {
    let dir = TempDir::new(name);
    for file in [
        "hn-rubber.toml",
        "hn-rubber.csv",
        "hn-rubber-seed2.csv",
        "hn-rubber-seed3.csv",
    ] {
        fs::copy(workspace().join("data").join(file), dir.path().join(file)).unwrap();
    }
    dir
}

/// Runs `rollfit batch MANIFEST -o OUT extra..`.
fn batch(manifest: &Path, out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        OsStr::new("batch"),
        manifest.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ];
    args.extend(extra.iter().map(OsStr::new));
    rollfit(&args)
}

/// Runs a batch that must succeed; returns its stderr.
fn batch_ok(manifest: &Path, out: &Path, extra: &[&str]) -> String {
    let output = batch(manifest, out, extra);
    let stderr = text(&output.stderr);
    assert!(output.status.success(), "{extra:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr
}

/// One row of a summary, by column name.
struct Row(Vec<(String, String)>);

impl Row {
    fn get(&self, column: &str) -> &str {
        &self
            .0
            .iter()
            .find(|(c, _)| c == column)
            .unwrap_or_else(|| panic!("no column {column}"))
            .1
    }

    fn number(&self, column: &str) -> f64 {
        self.get(column)
            .parse()
            .unwrap_or_else(|_| panic!("{column} = {:?}", self.get(column)))
    }
}

/// Reads a summary CSV and checks its header.
fn summary(path: &Path) -> Vec<Row> {
    let mut reader = csv::Reader::from_path(path).unwrap();
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(header, COLUMNS);
    reader
        .records()
        .map(|r| {
            let r = r.unwrap();
            Row(header
                .iter()
                .cloned()
                .zip(r.iter().map(String::from))
                .collect())
        })
        .collect()
}

fn entries(rows: &[Row]) -> Vec<&str> {
    rows.iter().map(|r| r.get("entry")).collect()
}

fn statuses(rows: &[Row]) -> Vec<&str> {
    rows.iter().map(|r| r.get("status")).collect()
}

fn json(path: &Path) -> Value {
    serde_json::from_str(&fs::read_to_string(path).unwrap()).unwrap()
}

/// Removes every key named "wall_time_s", at any depth.
fn without_wall_times(value: &mut Value) {
    match value {
        Value::Object(map) => {
            map.remove("wall_time_s");
            map.values_mut().for_each(without_wall_times);
        }
        Value::Array(items) => items.iter_mut().for_each(without_wall_times),
        _ => {}
    }
}

/// The files of a folder, sorted.
fn files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    names
}

// ------------------------------------------------------------- good input

#[test]
fn three_entries_write_three_folders_and_a_summary() {
    let dir = bundled("three");
    let manifest = dir.write("three.toml", format!("{DEFAULTS}{THREE}"));
    let out = dir.path().join("results");
    let stderr = batch_ok(&manifest, &out, &["--jobs", "2"]);
    assert!(stderr.contains("3 of 3 entries"), "{stderr}");
    assert!(stderr.contains("2 thread(s)"), "{stderr}");
    for name in NAMES {
        assert!(stderr.contains(&format!("{name}: ok")), "{stderr}");
    }
    assert!(stderr.contains("[3/3]"), "one line per entry: {stderr}");
    assert!(stderr.contains("3 ok, 0 poor, 0 unconverged, 0 failed, 0 skipped"));

    // The lock file stays: removing it while another batch may be opening
    // it would let two batches lock two different files.
    // And the folder's record of its files.
    let mut expected = vec![
        ".rollfit-batch.lock".to_string(),
        ".rollfit-files.json".to_string(),
        "summary.csv".to_string(),
    ];
    expected.extend(NAMES.iter().map(|n| n.to_string()));
    expected.sort();
    assert_eq!(files(&out), expected);
    for name in NAMES {
        assert_eq!(
            files(&out.join(name)),
            [".rollfit-files.json", "fit.json", "modulus.csv", "mu.csv"],
            "{name}"
        );
        // The defaults reached the fit.
        let report = json(&out.join(name).join("fit.json"));
        assert_eq!(report["lambda"]["value"], 100.0, "{name}");
        assert_eq!(report["lambda"]["rule"], "fixed", "{name}");
    }

    let rows = summary(&out.join("summary.csv"));
    assert_eq!(entries(&rows), NAMES, "manifest order");
    assert_eq!(statuses(&rows), ["ok", "ok", "ok"]);
    for (row, name) in rows.iter().zip(NAMES) {
        let report = json(&out.join(name).join("fit.json"));
        assert_eq!(row.get("converged"), "true");
        for (column, value) in [
            ("objective", &report["objective"]),
            ("misfit_per_point", &report["misfit_per_point"]),
            ("omega_min", &report["window"]["omega_min"]),
            ("omega_max", &report["window"]["omega_max"]),
            ("wall_time_s", &report["wall_time_s"]),
        ] {
            assert_eq!(
                row.number(column),
                value.as_f64().unwrap(),
                "{name} {column}"
            );
        }
        let chi2 = row.number("misfit_per_point");
        assert!(0.5 < chi2 && chi2 < 2.0, "{name}: misfit per point {chi2}");
        assert_eq!(row.get("C1"), "", "single temperature: no WLF constants");
        assert_eq!(row.get("C2"), "");
    }
}

#[test]
fn entry_settings_override_flags_which_override_defaults() {
    let dir = bundled("precedence");
    let manifest = dir.write(
        "precedence.toml",
        r#"[defaults]
lambda = 1e2
starts = 1
seed = 7

[[entry]]
name = "flags"
scene = "hn-rubber.toml"
data = "hn-rubber.csv"

[[entry]]
name = "own"
scene = "hn-rubber.toml"
data = "hn-rubber-seed2.csv"
lambda = "20"
terms = "1.5/decade"
"#,
    );
    let out = dir.path().join("results");
    batch_ok(&manifest, &out, &["--lambda", "50", "--jobs", "1"]);
    let flags = json(&out.join("flags").join("fit.json"));
    assert_eq!(flags["lambda"]["value"], 50.0, "the flag over [defaults]");
    assert_eq!(flags["seed"], 7, "[defaults] over the scene");
    assert_eq!(flags["terms"]["rule"], "per_decade");
    let own = json(&out.join("own").join("fit.json"));
    assert_eq!(own["lambda"]["value"], 20.0, "the entry over the flag");
    assert_eq!(own["seed"], 7);
    let per_decade = own["terms"]["per_decade"].as_f64().unwrap();
    assert!((per_decade - 1.5).abs() < 0.1, "{per_decade}");
    for report in [&flags, &own] {
        let runs = report["runs"].as_array().unwrap();
        assert!(!runs.iter().any(|r| r["stage"] == "start 2"), "one start");
    }
}

#[test]
fn results_equal_fits_run_one_by_one() {
    let dir = bundled("same");
    let manifest = dir.write("same.toml", format!("{DEFAULTS}{THREE}"));
    let out = dir.path().join("batch");
    batch_ok(&manifest, &out, &[]);

    let data = [
        "hn-rubber.csv",
        "hn-rubber-seed2.csv",
        "hn-rubber-seed3.csv",
    ];
    for (name, data) in NAMES.iter().zip(data) {
        // The paths the batch resolved (relative to the manifest's folder),
        // so that fit.json's "input" is comparable as well.
        let single = dir.path().join("single").join(name);
        let (scene, data) = (dir.path().join("hn-rubber.toml"), dir.path().join(data));
        let mut args = vec![
            OsStr::new("fit"),
            scene.as_os_str(),
            data.as_os_str(),
            OsStr::new("-o"),
            single.as_os_str(),
        ];
        args.extend(FLAGS.iter().map(OsStr::new));
        let output = rollfit(&args);
        assert!(output.status.success(), "{}", text(&output.stderr));

        let mut from_batch = json(&out.join(name).join("fit.json"));
        let mut alone = json(&single.join("fit.json"));
        without_wall_times(&mut from_batch);
        without_wall_times(&mut alone);
        assert_eq!(from_batch, alone, "{name}: fit.json");
        for file in ["modulus.csv", "mu.csv"] {
            assert_eq!(
                fs::read(out.join(name).join(file)).unwrap(),
                fs::read(single.join(file)).unwrap(),
                "{name}: {file}"
            );
        }
    }
}

#[test]
fn a_second_run_skips_finished_entries_and_force_refits() {
    let dir = bundled("skip");
    let manifest = dir.write("skip.toml", format!("{DEFAULTS}{THREE}"));
    let out = dir.path().join("results");
    batch_ok(&manifest, &out, &[]);
    let first = summary(&out.join("summary.csv"));
    let json_before: Vec<String> = NAMES
        .iter()
        .map(|n| fs::read_to_string(out.join(n).join("fit.json")).unwrap())
        .collect();

    // Mark seed2's result so that its row can only come from its fit.json.
    let seed2 = out.join("seed2").join("fit.json");
    let mut marked = json(&seed2);
    marked["objective"] = Value::from(12345.0);
    fs::write(&seed2, serde_json::to_string_pretty(&marked).unwrap()).unwrap();

    let stderr = batch_ok(&manifest, &out, &[]);
    assert!(
        stderr.contains("0 ok, 0 poor, 0 unconverged, 0 failed, 3 skipped"),
        "{stderr}"
    );
    let second = summary(&out.join("summary.csv"));
    assert_eq!(entries(&second), NAMES);
    assert_eq!(statuses(&second), ["skipped", "skipped", "skipped"]);
    for (a, b) in first.iter().zip(&second) {
        for column in [
            "misfit_per_point",
            "omega_min",
            "omega_max",
            "wall_time_s",
            "converged",
        ] {
            assert_eq!(a.get(column), b.get(column), "{} {column}", a.get("entry"));
        }
    }
    assert_eq!(first[0].get("objective"), second[0].get("objective"));
    assert_eq!(second[1].number("objective"), 12345.0);
    assert_eq!(
        fs::read_to_string(out.join("seed1").join("fit.json")).unwrap(),
        json_before[0],
        "a skipped entry is not rewritten"
    );

    // An interrupted batch: seed3's fit.json is missing, so it runs again.
    fs::remove_file(out.join("seed3").join("fit.json")).unwrap();
    batch_ok(&manifest, &out, &[]);
    let resumed = summary(&out.join("summary.csv"));
    assert_eq!(statuses(&resumed), ["skipped", "skipped", "ok"]);
    assert_eq!(resumed[2].get("objective"), first[2].get("objective"));

    // --force refits every entry, the marked one too.
    let stderr = batch_ok(&manifest, &out, &["--force"]);
    assert!(
        stderr.contains("3 ok, 0 poor, 0 unconverged, 0 failed, 0 skipped"),
        "{stderr}"
    );
    let forced = summary(&out.join("summary.csv"));
    assert_eq!(statuses(&forced), ["ok", "ok", "ok"]);
    assert_eq!(forced[1].get("objective"), first[1].get("objective"));
    assert_eq!(
        json(&seed2)["objective"].as_f64(),
        first[1].number("objective").into()
    );
}

#[test]
fn a_failing_entry_is_reported_and_the_others_finish() {
    let dir = bundled("failing");
    let scene = fs::read_to_string(dir.path().join("hn-rubber.toml")).unwrap();
    assert_eq!(scene.matches("radius = 0.005").count(), 1);
    dir.write(
        "broken.toml",
        scene.replacen("radius = 0.005", "radius = -0.005", 1),
    );
    let manifest = dir.write(
        "failing.toml",
        format!(
            "{DEFAULTS}{}",
            THREE.replacen(
                "name = \"seed2\"\nscene = \"hn-rubber.toml\"",
                "name = \"seed2\"\nscene = \"broken.toml\"",
                1
            )
        ),
    );
    let out = dir.path().join("results");
    let output = batch(&manifest, &out, &[]);
    let stderr = text(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(stderr.contains("seed2: failed"), "{stderr}");
    assert!(stderr.contains("1 of 3 entries failed (seed2)"), "{stderr}");

    let rows = summary(&out.join("summary.csv"));
    assert_eq!(entries(&rows), NAMES);
    assert_eq!(statuses(&rows), ["ok", "failed", "ok"]);
    let message = rows[1].get("message");
    assert!(
        message.contains("broken.toml") && message.contains("radius"),
        "{message}"
    );
    for column in ["objective", "misfit_per_point", "converged", "C1"] {
        assert_eq!(rows[1].get(column), "", "{column} of a failed entry");
    }
    assert!(!out.join("seed2").join("fit.json").exists());
    for name in ["seed1", "seed3"] {
        assert!(out.join(name).join("fit.json").is_file(), "{name}");
    }

    // Run again: the finished entries are skipped, the failed one fails again.
    let again = batch(&manifest, &out, &[]);
    assert_eq!(again.status.code(), Some(1));
    let rows = summary(&out.join("summary.csv"));
    assert_eq!(statuses(&rows), ["skipped", "failed", "skipped"]);
}

#[test]
fn an_unconverged_entry_fails_the_batch_unless_allowed() {
    let dir = bundled("unconverged");
    let scene = fs::read_to_string(dir.path().join("hn-rubber.toml")).unwrap();
    dir.write(
        "budget.toml",
        scene.replacen("[fit]\n", "[fit]\nmax_evaluations = 3\n", 1),
    );
    let manifest = dir.write(
        "budget-batch.toml",
        format!(
            "{DEFAULTS}{}",
            THREE.replacen(
                "name = \"seed3\"\nscene = \"hn-rubber.toml\"",
                "name = \"seed3\"\nscene = \"budget.toml\"",
                1
            )
        ),
    );
    let out = dir.path().join("results");
    let output = batch(&manifest, &out, &[]);
    let stderr = text(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("did not converge (seed3)") && stderr.contains("--allow-unconverged"),
        "{stderr}"
    );
    let rows = summary(&out.join("summary.csv"));
    assert_eq!(statuses(&rows), ["ok", "ok", "unconverged"]);
    assert_eq!(rows[2].get("converged"), "false");
    assert!(
        rows[2].get("message").contains("budget"),
        "{}",
        rows[2].get("message")
    );
    assert!(out.join("seed3").join("fit.json").is_file(), "results kept");
    // Three evaluations leave it poor as well, but an unconverged fit is
    // judged by the convergence gate alone (--allow-unconverged accepts it
    // below without --allow-poor-fit).
    let report = json(&out.join("seed3").join("fit.json"));
    assert_eq!(report["fit_quality"]["verdict"], "poor");
    assert!(!stderr.contains("do not describe their data"), "{stderr}");

    // The kept result still counts when it is skipped, unless allowed.
    let again = batch(&manifest, &out, &[]);
    assert_eq!(again.status.code(), Some(1), "{}", text(&again.stderr));
    let stderr = batch_ok(&manifest, &out, &["--allow-unconverged"]);
    assert!(
        stderr.contains("warning: 1 fit(s) did not converge"),
        "{stderr}"
    );
    let rows = summary(&out.join("summary.csv"));
    assert_eq!(statuses(&rows), ["skipped", "skipped", "skipped"]);
    assert_eq!(rows[2].get("converged"), "false");
}

/// Two entries: seed2 as usual, and the bundled measurement with 15 terms
/// (0.9 per decade cannot follow the 1 % data: judged poor, as in
/// report_cli.rs).
const POOR: &str = r#"
[[entry]]
name = "seed2"
scene = "hn-rubber.toml"
data = "hn-rubber-seed2.csv"

[[entry]]
name = "fifteen"
scene = "hn-rubber.toml"
data = "hn-rubber.csv"
terms = 15
"#;

#[test]
fn a_poor_entry_fails_the_batch_unless_allowed() {
    let dir = bundled("poor");
    let manifest = dir.write("poor.toml", format!("{DEFAULTS}{POOR}"));
    let out = dir.path().join("results");
    let output = batch(&manifest, &out, &[]);
    let stderr = text(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(stderr.contains("fifteen: poor"), "{stderr}");
    assert!(
        stderr.contains("1 ok, 1 poor, 0 unconverged, 0 failed, 0 skipped"),
        "{stderr}"
    );
    assert!(
        stderr.contains("do not describe their data (fifteen)")
            && stderr.contains("--allow-poor-fit"),
        "{stderr}"
    );
    let rows = summary(&out.join("summary.csv"));
    assert_eq!(entries(&rows), ["seed2", "fifteen"]);
    assert_eq!(statuses(&rows), ["ok", "poor"]);
    assert_eq!(rows[1].get("converged"), "true");
    let message = rows[1].get("message");
    assert!(
        message.contains("does not describe the data") && message.contains("fit quality: "),
        "the reasons: {message}"
    );
    // The results are written all the same.
    assert_eq!(
        files(&out.join("fifteen")),
        [".rollfit-files.json", "fit.json", "modulus.csv", "mu.csv"]
    );
    let report = json(&out.join("fifteen").join("fit.json"));
    assert_eq!(report["fit_quality"]["verdict"], "poor");
    assert_eq!(report["terms"]["count"], 15);
    assert_eq!(report["converged"], true);

    // The kept result still counts when it is skipped, unless allowed.
    let again = batch(&manifest, &out, &[]);
    let stderr = text(&again.stderr);
    assert_eq!(again.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("do not describe their data (fifteen)"),
        "{stderr}"
    );
    let rows = summary(&out.join("summary.csv"));
    assert_eq!(statuses(&rows), ["skipped", "skipped"]);
    assert!(
        rows[1].get("message").contains("fit quality: "),
        "{}",
        rows[1].get("message")
    );
    let stderr = batch_ok(&manifest, &out, &["--allow-poor-fit"]);
    assert!(
        stderr.contains("warning: 1 fit(s) do not describe their data (fifteen)"),
        "{stderr}"
    );

    // A fresh run with --allow-poor-fit: exit 0, still marked poor.
    let stderr = batch_ok(&manifest, &out, &["--force", "--allow-poor-fit"]);
    assert!(
        stderr.contains("1 ok, 1 poor, 0 unconverged, 0 failed, 0 skipped"),
        "{stderr}"
    );
    let rows = summary(&out.join("summary.csv"));
    assert_eq!(statuses(&rows), ["ok", "poor"]);
    assert!(out.join("fifteen").join("fit.json").is_file());
    // --allow-unconverged does not accept a poor fit.
    let output = batch(&manifest, &out, &["--allow-unconverged"]);
    assert_eq!(output.status.code(), Some(1), "{}", text(&output.stderr));
}

/// An entry without an anchor whose data leave the modulus scale
/// undetermined (a 0.01 N ball: the contact stays small down to 10 kPa, and
/// the profile is flat there) is written, marked "unanchored", and fails the
/// batch unless --allow-unanchored, which --allow-poor-fit does not replace.
#[test]
fn an_unanchored_entry_fails_the_batch_unless_allowed() {
    let dir = bundled("unanchored");
    let scene = fs::read_to_string(dir.path().join("hn-rubber.toml")).unwrap();
    let light: String = scene
        .lines()
        .filter(|l| !l.starts_with("E_at"))
        .map(|l| {
            if l.starts_with("load") {
                "load = 0.01"
            } else {
                l
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    let light_scene = dir.write("light.toml", &light);
    let data = dir.path().join("light.csv");
    let made = rollfit(&[
        OsStr::new("forward"),
        light_scene.as_os_str(),
        OsStr::new("--noise"),
        OsStr::new("0.01"),
        OsStr::new("--seed"),
        OsStr::new("2"),
        OsStr::new("-o"),
        data.as_os_str(),
    ]);
    assert!(made.status.success(), "{}", text(&made.stderr));
    let manifest = dir.write(
        "light-batch.toml",
        "[[entry]]\nname = \"light\"\nscene = \"light.toml\"\ndata = \"light.csv\"\n",
    );
    let out = dir.path().join("results");
    let output = batch(&manifest, &out, &["--allow-poor-fit"]);
    let stderr = text(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("leave the modulus scale undetermined (light)")
            && stderr.contains("--allow-unanchored")
            && stderr.contains("1 unanchored"),
        "{stderr}"
    );
    let rows = summary(&out.join("summary.csv"));
    assert_eq!(statuses(&rows), ["unanchored"]);
    assert!(rows[0].get("message").contains("contact_radius"));
    let report = json(&out.join("light").join("fit.json"));
    assert_eq!(report["scale"]["status"], "undetermined");
    // Kept and skipped, it still counts, unless allowed.
    let again = batch(&manifest, &out, &[]);
    assert_eq!(again.status.code(), Some(1), "{}", text(&again.stderr));
    let stderr = batch_ok(&manifest, &out, &["--allow-unanchored"]);
    assert!(
        stderr.contains("warning: 1 fit(s) leave the modulus scale undetermined (light)"),
        "{stderr}"
    );
}

#[test]
fn data_file_notes_and_warnings_reach_the_message() {
    // The bundled measurement with the speed in mm/s, the friction named
    // COF and one row without a μ: a unit conversion and a column name
    // (notes) and a skipped row (a warning), as `rollfit fit` prints them.
    let dir = bundled("notes");
    let table = Table::read(&dir.path().join("hn-rubber.csv"));
    let mut csv = String::from("v (mm/s),COF,sigma\n");
    for (i, ((v, mu), sigma)) in table
        .column("v")
        .into_iter()
        .zip(table.column("mu"))
        .zip(table.column("sigma"))
        .enumerate()
    {
        let mu = if i == 3 {
            "NaN".to_string()
        } else {
            mu.to_string()
        };
        csv += &format!("{},{mu},{sigma}\n", v * 1e3);
    }
    dir.write("mm.csv", &csv);
    let manifest = dir.write(
        "notes.toml",
        format!(
            "{DEFAULTS}[[entry]]\nname = \"mm\"\nscene = \"hn-rubber.toml\"\ndata = \"mm.csv\"\n"
        ),
    );
    let out = dir.path().join("results");
    let stderr = batch_ok(&manifest, &out, &[]);
    let rows = summary(&out.join("summary.csv"));
    assert_eq!(statuses(&rows), ["ok"]);
    let message = rows[0].get("message");
    for fragment in [
        "note: data file",
        "mm.csv: column \"v (mm/s)\" read as v in mm/s, converted to m/s",
        "column \"COF\" read as mu",
        "warning: data file",
        "skipped 1 row with empty or NaN cells in mu",
    ] {
        assert!(message.contains(fragment), "{fragment:?} in {message}");
        assert!(stderr.contains(fragment), "{fragment:?} in {stderr}");
    }
    assert!(!message.contains("fitting "), "{message}");
    let report = json(&out.join("mm").join("fit.json"));
    assert_eq!(report["input"]["points"], 40);
}

#[test]
fn shards_split_the_entries_and_an_unsharded_run_merges_them() {
    let dir = bundled("shards");
    let manifest = dir.write("sharded.toml", format!("{DEFAULTS}{THREE}"));
    let out = dir.path().join("results");

    batch_ok(&manifest, &out, &["--shard", "0/2"]);
    let shard0 = summary(&out.join("summary-0-of-2.csv"));
    assert_eq!(entries(&shard0), ["seed1", "seed3"], "indices 0 and 2");
    assert_eq!(statuses(&shard0), ["ok", "ok"]);
    assert!(!out.join("seed2").exists(), "shard 0 ran only its entries");
    assert!(!out.join("summary.csv").exists());

    batch_ok(&manifest, &out, &["--shard", "1/2"]);
    let shard1 = summary(&out.join("summary-1-of-2.csv"));
    assert_eq!(entries(&shard1), ["seed2"]);
    assert_eq!(statuses(&shard1), ["ok"]);

    let all: BTreeSet<&str> = entries(&shard0)
        .into_iter()
        .chain(entries(&shard1))
        .collect();
    assert_eq!(all.len(), shard0.len() + shard1.len(), "disjoint");
    assert_eq!(all, NAMES.into_iter().collect(), "complete");

    let stderr = batch_ok(&manifest, &out, &[]);
    assert!(stderr.contains("3 skipped"), "{stderr}");
    let merged = summary(&out.join("summary.csv"));
    assert_eq!(entries(&merged), NAMES);
    assert_eq!(statuses(&merged), ["skipped", "skipped", "skipped"]);
    let shard_rows = [&shard0[0], &shard1[0], &shard0[1]];
    for (row, from_shard) in merged.iter().zip(shard_rows) {
        assert_eq!(row.get("objective"), from_shard.get("objective"));
        assert_eq!(row.get("converged"), "true");
    }

    // A shard beyond the entries has nothing to do and says so.
    let stderr = batch_ok(&manifest, &out, &["--shard", "5/7"]);
    assert!(stderr.contains("0 of 3 entries"), "{stderr}");
    assert!(summary(&out.join("summary-5-of-7.csv")).is_empty());
}

#[test]
fn the_bundled_batch_example_is_valid() {
    // Checks the manifest and its files, not the fits: an impossible
    // --starts makes the command stop right after reading the manifest.
    let dir = TempDir::new("example");
    let manifest = workspace().join("data").join("example-batch.toml");
    let out = rollfit_in(
        Some(dir.path()),
        &[
            OsStr::new("batch"),
            manifest.as_os_str(),
            OsStr::new("--starts"),
            OsStr::new("0"),
        ],
    );
    assert_failure(&out, &["command line: --starts"]);
    let text = fs::read_to_string(&manifest).unwrap();
    for file in [
        "hn-rubber.toml",
        "hn-rubber.csv",
        "hn-rubber-seed2.csv",
        "hn-rubber-seed3.csv",
    ] {
        assert!(text.contains(&format!("\"{file}\"")), "{file}");
        assert!(workspace().join("data").join(file).is_file(), "{file}");
    }
}

#[test]
fn bundled_seeds_are_what_their_documented_commands_make() {
    // data/README.md: `rollfit forward data/hn-rubber.toml --noise 0.01
    // --seed N -o data/hn-rubber-seedN.csv`, N = 2, 3.
    let dir = TempDir::new("seeds");
    for seed in ["2", "3"] {
        let made = dir.path().join(format!("seed{seed}.csv"));
        let scene = workspace().join("data").join("hn-rubber.toml");
        let out = rollfit(&[
            OsStr::new("forward"),
            scene.as_os_str(),
            OsStr::new("--noise"),
            OsStr::new("0.01"),
            OsStr::new("--seed"),
            OsStr::new(seed),
            OsStr::new("-o"),
            made.as_os_str(),
        ]);
        assert!(out.status.success(), "{}", text(&out.stderr));
        let made = Table::read(&made);
        let stored = Table::read(
            &workspace()
                .join("data")
                .join(format!("hn-rubber-seed{seed}.csv")),
        );
        assert_eq!(made.header, stored.header);
        assert_eq!(made.column("v"), stored.column("v"));
        // Equal up to the quadrature tolerance, as for hn-rubber.csv.
        for name in ["mu", "sigma", "mu_exact"] {
            for (a, b) in made.column(name).into_iter().zip(stored.column(name)) {
                assert!(
                    (a - b).abs() <= 1e-5 * b.abs(),
                    "seed {seed}, {name}: {a} vs {b}"
                );
            }
        }
    }
}

// ------------------------------------------------------------ bad manifests

/// Writes `manifest` as bad.toml next to the bundled files, runs `rollfit
/// batch bad.toml extra..` there (default output folder fits/bad) and checks
/// the promise of every bad-input test. Returns stderr.
fn assert_refused(manifest: &str, extra: &[&str], expected: &[&str]) -> String {
    let dir = bundled("bad");
    dir.write("bad.toml", manifest);
    let mut args = vec!["batch", "bad.toml"];
    args.extend(extra);
    let args: Vec<&OsStr> = args.iter().map(OsStr::new).collect();
    let out = rollfit_in(Some(dir.path()), &args);
    let stderr = assert_failure(&out, expected);
    assert!(
        !dir.path().join("fits").exists(),
        "an output folder was created"
    );
    stderr
}

/// A valid manifest of two entries, "a" (lines 5-8) and "b" (lines 10-13),
/// that the tests break.
const TWO: &str = r#"[defaults]
lambda = 1e2
starts = 1

[[entry]]
name = "a"
scene = "hn-rubber.toml"
data = "hn-rubber.csv"

[[entry]]
name = "b"
scene = "hn-rubber.toml"
data = "hn-rubber-seed2.csv"
"#;

/// Replaces exactly one occurrence of `from` in `text`.
fn edit(text: &str, from: &str, to: &str) -> String {
    assert_eq!(text.matches(from).count(), 1, "{from:?}");
    text.replacen(from, to, 1)
}

#[test]
fn the_valid_two_entry_manifest_is_accepted() {
    // The base of the tests below is itself fine (checked without fitting:
    // an impossible --terms stops the command after the manifest).
    let stderr = assert_refused(TWO, &["--terms", "1"], &["command line: --terms"]);
    assert!(!stderr.contains("bad.toml"), "{stderr}");
}

#[test]
fn missing_manifest() {
    let dir = TempDir::new("missing");
    let out = rollfit_in(
        Some(dir.path()),
        &[OsStr::new("batch"), OsStr::new("nothing-here.toml")],
    );
    assert_failure(&out, &["cannot read manifest nothing-here.toml"]);
    assert!(!dir.path().join("fits").exists());
}

#[test]
fn toml_syntax_error_in_an_entry() {
    let manifest = edit(
        TWO,
        "data = \"hn-rubber-seed2.csv\"",
        "data = \"hn-rubber-seed2.csv",
    );
    assert_refused(
        &manifest,
        &[],
        &["manifest bad.toml", "entry 2 (line 10)", "line 13"],
    );
}

#[test]
fn unknown_key_in_an_entry() {
    let manifest = edit(TWO, "name = \"b\"\n", "name = \"b\"\nlamda = 1\n");
    assert_refused(
        &manifest,
        &[],
        &[
            "manifest bad.toml",
            "entry \"b\" (2 of 2, line 10)",
            "line 12",
            "unknown field `lamda`",
        ],
    );
}

#[test]
fn unknown_table() {
    let manifest = edit(TWO, "[defaults]", "[default]");
    assert_refused(
        &manifest,
        &[],
        &["manifest bad.toml", "line 1", "unknown field `default`"],
    );
}

#[test]
fn missing_name_scene_or_data() {
    let manifest = edit(TWO, "name = \"b\"\n", "");
    assert_refused(
        &manifest,
        &[],
        &[
            "manifest bad.toml",
            "entry 2 of 2 (line 10)",
            "missing `name`",
        ],
    );
    // Entry "b" without the key.
    let (a, b) = TWO.split_at(TWO.find("name = \"b\"").unwrap());
    for key in ["scene", "data"] {
        let line = b.lines().find(|l| l.starts_with(key)).unwrap();
        let manifest = format!("{a}{}", edit(b, &format!("{line}\n"), ""));
        assert_refused(
            &manifest,
            &[],
            &[
                "manifest bad.toml",
                "entry \"b\" (2 of 2, line 10)",
                &format!("missing `{key}`"),
            ],
        );
    }
}

#[test]
fn duplicate_names() {
    let manifest = edit(TWO, "name = \"b\"", "name = \"a\"");
    assert_refused(
        &manifest,
        &[],
        &[
            "manifest bad.toml",
            "entry \"a\" (2 of 2, line 10)",
            "duplicate name",
            "entry \"a\" (1 of 2, line 5)",
        ],
    );
    // Names that differ only in case would share a folder on many systems.
    let manifest = edit(TWO, "name = \"b\"", "name = \"A\"");
    assert_refused(
        &manifest,
        &[],
        &[
            "entry \"A\" (2 of 2, line 10)",
            "duplicate name",
            "only in case",
        ],
    );
}

#[test]
fn invalid_names() {
    for (name, why) in [
        ("a b", "contains ' '"),
        ("../up", "contains '/'"),
        ("", "is empty"),
        (".hidden", "starts with '.'"),
        ("..", "starts with '.'"),
        ("summary.csv", "reserved"),
    ] {
        let manifest = edit(TWO, "name = \"b\"", &format!("name = {name:?}"));
        assert_refused(
            &manifest,
            &[],
            &[
                "manifest bad.toml",
                &format!("entry {name:?} (2 of 2, line 10)"),
                why,
            ],
        );
    }
}

#[test]
fn scene_or_data_file_that_does_not_exist() {
    let manifest = edit(TWO, "data = \"hn-rubber-seed2.csv\"", "data = \"nope.csv\"");
    assert_refused(
        &manifest,
        &[],
        &[
            "manifest bad.toml",
            "entry \"b\" (2 of 2, line 10)",
            "line 13",
            "data file nope.csv does not exist",
        ],
    );
    // Both entries' problems are reported at once.
    let manifest = TWO.replace("scene = \"hn-rubber.toml\"", "scene = \"nope.toml\"");
    assert_refused(
        &manifest,
        &[],
        &[
            "entry \"a\" (1 of 2, line 5): line 7: scene file nope.toml does not exist",
            "entry \"b\" (2 of 2, line 10): line 12: scene file nope.toml does not exist",
        ],
    );
}

#[test]
fn no_entries() {
    assert_refused(
        "# nothing yet\n[defaults]\nstarts = 1\n",
        &[],
        &["manifest bad.toml", "no entries", "[[entry]]"],
    );
    assert_refused("", &[], &["manifest bad.toml", "no entries"]);
}

#[test]
fn bad_setting_values() {
    for (from, to, expected) in [
        (
            "name = \"b\"\n",
            "name = \"b\"\nstarts = 0\n",
            "use 1 to 100",
        ),
        (
            "name = \"b\"\n",
            "name = \"b\"\nmethod = \"newton\"\n",
            "unknown method",
        ),
        (
            "name = \"b\"\n",
            "name = \"b\"\nterms = 1\n",
            "use 2 to 200",
        ),
        (
            "name = \"b\"\n",
            "name = \"b\"\nterms = \"x/decade\"\n",
            "terms per decade",
        ),
        ("name = \"b\"\n", "name = \"b\"\nlambda = -1\n", "lambda"),
        ("name = \"b\"\n", "name = \"b\"\nseed = -3\n", "seed"),
    ] {
        let manifest = edit(TWO, from, to);
        assert_refused(
            &manifest,
            &[],
            &[
                "manifest bad.toml",
                "entry \"b\" (2 of 2, line 10)",
                "line 12",
                expected,
            ],
        );
    }
    // In [defaults]: named by its table.
    let manifest = edit(TWO, "lambda = 1e2", "lambda = \"often\"");
    assert_refused(
        &manifest,
        &[],
        &["manifest bad.toml", "[defaults]", "line 2", "lambda"],
    );
}

#[test]
fn malformed_shard_jobs_and_flags() {
    for shard in ["4/4", "a/2", "1/0", "1", "-1/2"] {
        assert_refused(TWO, &["--shard", shard], &["--shard", shard]);
    }
    assert_refused(TWO, &["--jobs", "0"], &["--jobs"]);
    assert_refused(
        TWO,
        &["--starts", "0"],
        &["command line: --starts", "use 1 to 100"],
    );
    assert_refused(TWO, &["--method", "newton"], &["--method", "newton"]);
}

/// `physics` in a manifest: `[defaults]` asks for the exact contact, one
/// entry for the approximate one; the entries run in parallel and each
/// fit.json says which it got (a cylinder on the bundled rubber, 11 speeds
/// made by `rollfit forward --noise`).
#[test]
fn physics_is_a_setting_of_defaults_and_entries() {
    let dir = TempDir::new("physics");
    let scene = dir.write(
        "cylinder.toml",
        "[geometry]\nshape = \"cylinder\"\nradius = 0.005\nload = 1000.0\n\n\
         [material]\nmodel = \"havriliak-negami\"\nE0 = 2.0e6\nE1 = 2.0e9\ntau = 1.0e-3\n\
         alpha = 0.55\nbeta = 0.4\n\n[fit]\nE0 = 2.0e6\n\n\
         [sweep]\nv_min = 1e-8\nv_max = 1e-3\ncount = 11\n",
    );
    let data = dir.path().join("cylinder.csv");
    let made = rollfit(&[
        OsStr::new("forward"),
        scene.as_os_str(),
        OsStr::new("--noise"),
        OsStr::new("0.01"),
        OsStr::new("-o"),
        data.as_os_str(),
    ]);
    assert!(made.status.success(), "{}", text(&made.stderr));
    let manifest = dir.write(
        "physics.toml",
        "[defaults]\nphysics = \"exact\"\n\n\
         [[entry]]\nname = \"exact\"\nscene = \"cylinder.toml\"\ndata = \"cylinder.csv\"\n\n\
         [[entry]]\nname = \"approximate\"\nscene = \"cylinder.toml\"\ndata = \"cylinder.csv\"\n\
         physics = \"approximate\"\n",
    );
    let out = dir.path().join("results");
    batch_ok(&manifest, &out, &["--jobs", "2"]);
    let exact = json(&out.join("exact").join("fit.json"));
    assert_eq!(exact["physics"]["kind"], "exact", "{}", exact["physics"]);
    assert!(
        json(&out.join("approximate").join("fit.json"))
            .get("physics")
            .is_none()
    );
    let header = |name: &str| Table::read(&out.join(name).join("mu.csv")).header;
    assert_eq!(
        header("exact").last().map(String::as_str),
        Some("exact_correction")
    );
    assert!(!header("approximate").contains(&"exact_correction".to_string()));
}

/// An entry whose inputs changed since its result was written is refitted,
/// the message saying which input changed; unchanged entries are kept.
#[test]
fn an_entry_whose_inputs_changed_is_refitted_saying_which() {
    let dir = bundled("changed");
    let manifest = dir.write("changed.toml", format!("{DEFAULTS}{THREE}"));
    let out = dir.path().join("results");
    batch_ok(&manifest, &out, &[]);
    // seed1 now names another data file; seed3's data are rewritten.
    let edited = edit(
        &format!("{DEFAULTS}{THREE}"),
        "data = \"hn-rubber.csv\"",
        "data = \"hn-rubber-seed2.csv\"",
    );
    fs::write(&manifest, edited).unwrap();
    let seed3 = dir.path().join("hn-rubber-seed3.csv");
    fs::write(&seed3, fs::read(&seed3).unwrap()).unwrap();
    batch_ok(&manifest, &out, &[]);
    let rows = summary(&out.join("summary.csv"));
    assert_eq!(statuses(&rows), ["ok", "skipped", "ok"]);
    let message = rows[0].get("message");
    assert!(
        message.contains("refitted: the existing result no longer answers the entry (data was ")
            && message.contains("hn-rubber.csv, is now ")
            && message.contains("hn-rubber-seed2.csv"),
        "{message}"
    );
    assert!(
        rows[2]
            .get("message")
            .contains("hn-rubber-seed3.csv was modified after the result was written"),
        "{}",
        rows[2].get("message")
    );
    // seed1's result is now the one of its new data.
    assert_eq!(rows[0].get("objective"), rows[1].get("objective"));
    batch_ok(&manifest, &out, &[]);
    let rows = summary(&out.join("summary.csv"));
    assert_eq!(statuses(&rows), ["skipped", "skipped", "skipped"]);
}

/// A joint fit's key in an entry without DMA data names the manifest, the
/// entry and the key's line, not the command line.
#[test]
fn a_joint_key_without_dma_names_the_manifest_entry_and_line() {
    let dir = bundled("joint-key");
    for (key, value) in [("friction_factor", "\"free\""), ("dma_sigma", "0.02")] {
        let manifest = dir.write(
            "joint.toml",
            format!(
                "{DEFAULTS}\n[[entry]]\nname = \"seed1\"\nscene = \"hn-rubber.toml\"\n\
                 data = \"hn-rubber.csv\"\n{key} = {value}\n"
            ),
        );
        let out = dir.path().join("results");
        let output = batch(&manifest, &out, &[]);
        let rows = summary(&out.join("summary.csv"));
        assert!(!output.status.success());
        let message = rows[0].get("message");
        assert!(
            message.contains(&format!(
                "joint.toml: entry \"seed1\" (1 of 1, line 5), line 9: `{key}`"
            )) && !message.contains("command line"),
            "{message}"
        );
        fs::remove_dir_all(&out).unwrap();
    }
}
