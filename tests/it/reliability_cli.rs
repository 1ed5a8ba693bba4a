//! Regression tests of the holes mutating the bundled inputs found: bad
//! input that once exited 0, result folders that could mix two
//! runs, errors without a place. Each test reproduces one hole; the fuzzing harness (fuzz_cli.rs) and the kill tests
//! (faults_cli.rs) cover the same promises broadly.

use crate::common;

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Output;

use common::{TempDir, assert_failure, rollfit, text};

/// The bundled example's file in data/.
fn bundled(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(name)
}

fn run(args: &[&dyn AsRef<OsStr>]) -> Output {
    let args: Vec<&OsStr> = args.iter().map(|a| a.as_ref()).collect();
    rollfit(&args)
}

/// The bundled example fitted into DIR/fit.
fn fitted_example(dir: &TempDir) -> PathBuf {
    let fit = dir.path().join("fit");
    let output = run(&[
        &"fit",
        &bundled("hn-rubber.toml"),
        &bundled("hn-rubber.csv"),
        &"-o",
        &fit,
    ]);
    assert!(output.status.success(), "{}", text(&output.stderr));
    fit
}

/// data/hn-rubber.csv with the cell (line, column) replaced by `value`.
fn edited_data(dir: &TempDir, line: usize, column: usize, value: &str) -> PathBuf {
    let text = fs::read_to_string(bundled("hn-rubber.csv")).unwrap();
    let edited: Vec<String> = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i + 1 == line {
                let mut cells: Vec<&str> = l.split(',').collect();
                cells[column] = value;
                cells.join(",")
            } else {
                l.to_string()
            }
        })
        .collect();
    dir.write("data.csv", &(edited.join("\n") + "\n"))
}

/// Item 1: one μ = 1e300 once gave an infinite objective, "converged" and a
/// fit.json with null in it; now the line is refused, and nothing written.
#[test]
fn a_friction_coefficient_of_1e300_is_refused_with_its_line() {
    let dir = TempDir::new("mu-1e300");
    let data = edited_data(&dir, 7, 1, "1e300");
    let out = dir.path().join("fit");
    let output = run(&[&"fit", &bundled("hn-rubber.toml"), &data, &"-o", &out]);
    assert_failure(&output, &["data.csv", "line 7", "`mu` = 1e300", "below 10"]);
    assert!(!out.exists());
}

/// Item 1, in a batch: the entry fails (it was once "ok").
#[test]
fn a_batch_entry_with_mu_1e300_fails() {
    let dir = TempDir::new("mu-1e300-batch");
    edited_data(&dir, 7, 1, "1e300");
    fs::copy(bundled("hn-rubber.toml"), dir.path().join("scene.toml")).unwrap();
    let manifest = dir.write(
        "m.toml",
        "[[entry]]\nname = \"bad\"\nscene = \"scene.toml\"\ndata = \"data.csv\"\n",
    );
    let out = dir.path().join("out");
    let output = run(&[&"batch", &manifest, &"-o", &out]);
    assert_failure(&output, &["1 of 1 entries failed (bad)"]);
    let summary = fs::read_to_string(out.join("summary.csv")).unwrap();
    assert!(
        summary.contains("bad,failed") && summary.contains("line 7"),
        "{summary}"
    );
    assert!(!out.join("bad").exists());
}

/// Item 2: σ = 1e-300 once gave NaN effective parameters and an unreadable
/// fit.json.
#[test]
fn a_sigma_of_1e_minus_300_is_refused_with_its_line() {
    let dir = TempDir::new("sigma-tiny");
    let data = edited_data(&dir, 7, 2, "1e-300");
    let output = run(&[
        &"fit",
        &bundled("hn-rubber.toml"),
        &data,
        &"-o",
        &dir.path().join("f"),
    ]);
    assert_failure(
        &output,
        &[
            "data.csv",
            "line 7",
            "`sigma` = 1e-300",
            "1e-9 of the row's mu",
        ],
    );
}

/// Item 3: every row at one speed.
#[test]
fn all_rows_at_one_speed_are_refused() {
    let dir = TempDir::new("one-speed");
    let rows: String = (0..10)
        .map(|i| format!("1e-3,{}\n", 0.01 + 1e-4 * i as f64))
        .collect();
    let data = dir.write("data.csv", format!("v,mu\n{rows}"));
    let output = run(&[
        &"fit",
        &bundled("hn-rubber.toml"),
        &data,
        &"-o",
        &dir.path().join("f"),
    ]);
    assert_failure(&output, &["data.csv", "1 distinct speed(s)", "at least 4"]);
}

/// Item 4: a DMA CSV with both f and omega once silently used omega.
#[test]
fn a_dma_file_with_two_frequency_columns_is_refused() {
    let dir = TempDir::new("two-frequencies");
    let fit = fitted_example(&dir);
    let dma = dir.write(
        "dma.csv",
        "f,omega,G_storage,G_loss\n1,6.283185307179586,1e6,1e5\n10,62.83185307179586,2e6,3e5\n",
    );
    let output = run(&[&"compare", &fit, &dma]);
    assert_failure(&output, &["dma.csv", "two frequency columns", "keep one"]);
    let dma = dir.write(
        "dma2.csv",
        "omega_Hz,G_storage,G_loss\n1,1e6,1e5\n10,2e6,3e5\n",
    );
    let output = run(&[&"compare", &fit, &dma]);
    assert_failure(&output, &["dma2.csv", "omega_Hz", "suffix says Hz"]);
}

/// Item 5: extreme loads and radii gave μ = inf and NaN in the output.
#[test]
fn loads_and_radii_no_float_can_hold_are_refused_naming_the_key() {
    let dir = TempDir::new("extreme-geometry");
    let scene = fs::read_to_string(bundled("hn-rubber.toml")).unwrap();
    for (from, to, key) in [
        ("load = 1.0 ", "load = 1e308 ", "load = 1e308"),
        ("radius = 0.005 ", "radius = 1e308 ", "radius = 1e308"),
        ("radius = 0.005 ", "radius = 5e-324 ", "radius = 5e-324"),
        ("v_max = 1.0 ", "v_max = 1e6 ", "v_max = 1e6"),
    ] {
        assert!(scene.contains(from));
        let path = dir.write("scene.toml", scene.replace(from, to));
        let out = dir.path().join("mu.csv");
        let output = run(&[&"forward", &path, &"-o", &out]);
        assert_failure(&output, &["scene.toml", key]);
        assert!(!out.exists());
    }
}

/// Item 6: a hand-edited fit.json with an unknown shift model once read as
/// WLF, and ν = 1 was blamed on the DMA file.
#[test]
fn a_hand_edited_fit_json_is_refused_naming_fit_json_and_the_key() {
    let dir = TempDir::new("edited-fit-json");
    let fit = fitted_example(&dir);
    let json = fs::read_to_string(fit.join("fit.json")).unwrap();
    let poisson = json.replace("\"poisson\": 0.5", "\"poisson\": 1.0");
    assert_ne!(poisson, json);
    fs::write(fit.join("fit.json"), poisson).unwrap();
    let output = run(&[&"compare", &fit, &bundled("hn-rubber-dma.csv")]);
    let stderr = assert_failure(&output, &["fit.json", "poisson"]);
    assert!(!stderr.contains("hn-rubber-dma.csv"), "{stderr}");
}

/// Item 7: `forward --noise 0` wrote σ = 0, which `fit` refuses.
#[test]
fn zero_noise_is_refused_by_forward() {
    let output = run(&[&"forward", &bundled("hn-rubber.toml"), &"--noise", &"0"]);
    assert_failure(&output, &["--noise", "greater than zero"]);
}

/// Item 8: a refit whose fit is rejected leaves the previous result as it
/// was (it once replaced the files one by one, or wrote a rejected fit).
#[test]
fn a_rejected_refit_leaves_the_previous_result() {
    let dir = TempDir::new("rejected-refit");
    let fit = fitted_example(&dir);
    let before: Vec<Vec<u8>> = ["fit.json", "modulus.csv", "mu.csv"]
        .iter()
        .map(|f| fs::read(fit.join(f)).unwrap())
        .collect();
    let scene = fs::read_to_string(bundled("hn-rubber.toml")).unwrap();
    let budget = dir.write(
        "budget.toml",
        scene.replace("[fit]\n", "[fit]\nmax_evaluations = 1\n"),
    );
    let output = run(&[&"fit", &budget, &bundled("hn-rubber.csv"), &"-o", &fit]);
    assert_failure(&output, &["did not converge", "nothing was written"]);
    let after: Vec<Vec<u8>> = ["fit.json", "modulus.csv", "mu.csv"]
        .iter()
        .map(|f| fs::read(fit.join(f)).unwrap())
        .collect();
    assert!(before == after);
}

/// Item 9: a second batch into a folder another batch is writing is
/// refused at once, naming the holder.
#[test]
fn a_second_batch_into_a_busy_folder_is_refused() {
    let dir = TempDir::new("busy");
    fs::copy(bundled("hn-rubber.toml"), dir.path().join("scene.toml")).unwrap();
    fs::copy(bundled("hn-rubber.csv"), dir.path().join("data.csv")).unwrap();
    let entries: String = (0..4)
        .map(|i| {
            format!("[[entry]]\nname = \"e{i}\"\nscene = \"scene.toml\"\ndata = \"data.csv\"\n")
        })
        .collect();
    let manifest = dir.write("m.toml", &entries);
    let out = dir.path().join("out");
    let mut first = std::process::Command::new(env!("CARGO_BIN_EXE_rollfit"))
        .args([
            OsStr::new("batch"),
            manifest.as_os_str(),
            OsStr::new("-o"),
            out.as_os_str(),
        ])
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // Wait for the first batch to take the lock.
    let lock = out.join(".rollfit-batch.lock");
    while fs::read_to_string(&lock).map_or(true, |s| s.is_empty()) {
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let output = run(&[&"batch", &manifest, &"-o", &out, &"--force"]);
    let stderr = assert_failure(&output, &["is being written by another rollfit run"]);
    assert!(stderr.contains(&format!("pid {}", first.id())), "{stderr}");
    assert!(first.wait().unwrap().success());
}

/// Item 10: a batch into a folder it cannot write is refused before any fit
/// runs; leftovers of a killed writer are removed when the batch resumes.
#[test]
fn a_batch_checks_its_folder_first_and_cleans_up_after_killed_runs() {
    let dir = TempDir::new("batch-folder");
    fs::copy(bundled("hn-rubber.toml"), dir.path().join("scene.toml")).unwrap();
    fs::copy(bundled("hn-rubber.csv"), dir.path().join("data.csv")).unwrap();
    let manifest = dir.write(
        "m.toml",
        "[[entry]]\nname = \"e\"\nscene = \"scene.toml\"\ndata = \"data.csv\"\n",
    );
    // A file where the folder should be: refused before fitting.
    let blocked = dir.write("blocked", "");
    let output = run(&[&"batch", &manifest, &"-o", &blocked.join("out")]);
    assert_failure(&output, &["blocked"]);

    let out = dir.path().join("out");
    fs::create_dir_all(out.join("e")).unwrap();
    // What killed runs of rollfit 0.1 and of this version leave; pid
    // 4194304 is above Linux's pid_max, so never alive.
    fs::write(out.join("e").join(".mu.csv.4194304-0.tmp"), "x").unwrap();
    fs::create_dir(out.join(".rollfit-4194304-0.tmp")).unwrap();
    let output = run(&[&"batch", &manifest, &"-o", &out]);
    assert!(output.status.success(), "{}", text(&output.stderr));
    if cfg!(target_os = "linux") {
        assert!(!out.join(".rollfit-4194304-0.tmp").exists());
        let mut names: Vec<String> = fs::read_dir(out.join("e"))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(
            names,
            [".rollfit-files.json", "fit.json", "modulus.csv", "mu.csv"]
        );
    }
}

/// Item 11: errors that named no place.
#[test]
fn errors_name_the_line_byte_key_or_table_line() {
    let dir = TempDir::new("places");
    // Invalid UTF-8 in a scene: line and byte.
    let mut bytes = fs::read(bundled("hn-rubber.toml")).unwrap();
    let at = bytes.iter().position(|&b| b == b'[').unwrap();
    bytes.insert(at + 1, 0xff);
    let scene = dir.path().join("scene.toml");
    fs::write(&scene, bytes).unwrap();
    let output = run(&[&"forward", &scene]);
    assert_failure(&output, &["scene.toml", "not UTF-8", "byte 0xFF", "line "]);

    // A data speed of 1e300: the line.
    let data = edited_data(&dir, 5, 0, "1e300");
    let output = run(&[
        &"fit",
        &bundled("hn-rubber.toml"),
        &data,
        &"-o",
        &dir.path().join("f"),
    ]);
    assert_failure(&output, &["data.csv", "line 5", "`v` = 1e300"]);

    // A table value of 1e300: the table's line.
    let table = dir.write(
        "modulus.csv",
        "omega,E_storage,E_loss\n0.1,2e6,1e5\n1,3e6,1e300\n10,5e6,1e6\n",
    );
    let scene = dir.write(
        "table.toml",
        format!(
            "[geometry]\nshape = \"sphere\"\nradius = 0.005\nload = 1.0\n[substrate]\npoisson = \
             0.5\n[contact]\nsize = \"dynamic\"\n[material]\nmodel = \"table\"\nfile = \"{}\"\n\
             [sweep]\nv_min = 1e-6\nv_max = 1e-3\ncount = 4\n",
            table.file_name().unwrap().to_string_lossy()
        ),
    );
    let output = run(&[&"forward", &scene]);
    assert_failure(&output, &["modulus.csv", "line 3", "E_loss", "1e300"]);

    // An output name of 244 characters: the temporary names still fit.
    let long = dir.path().join("r".repeat(244));
    let output = run(&[
        &"fit",
        &bundled("hn-rubber.toml"),
        &bundled("hn-rubber.csv"),
        &"-o",
        &long,
    ]);
    assert!(output.status.success(), "{}", text(&output.stderr));
    assert!(long.join("fit.json").is_file());
}

/// Absurd loads, film thicknesses and E1_max are refused
/// when the scene is read, naming the file, the section and key, the value
/// and the range, by `forward` and by `fit` alike (each rule is defined
/// once: `model::scene` for the set-up, `fit::params` for the fit's moduli).
#[test]
fn absurd_scene_values_are_refused_naming_their_key() {
    let tmp = TempDir::new("absurd-scene");
    let data = bundled("hn-rubber.csv");
    let cases: [(&str, &str, &str, &[&str]); 4] = [
        (
            "load = 1.0",
            "load = 1e300",
            "load",
            &["[geometry]", "load = 1e300", "1e-9 and 1e8 N"],
        ),
        (
            "load = 1.0",
            "load = 1e-300",
            "load",
            &["[geometry]", "load = 1e-300", "1e-9 and 1e8 N"],
        ),
        (
            "poisson = 0.5",
            "poisson = 0.5\nthickness = 1e-300",
            "thickness",
            &["[substrate]", "thickness = 1e-300", "1e-9 m and 1000 m"],
        ),
        (
            "[fit]",
            "[fit]\nE1_max = 1e-300",
            "E1_max",
            &["E1_max", "1e-300", "between 1e3 and 1e12 Pa"],
        ),
    ];
    for (from, to, name, expected) in cases {
        let text = common::small_scene(11).replacen(from, to, 1);
        assert!(text.contains(to), "{name}: {from:?} not in the scene");
        let scene = tmp.write(&format!("{name}.toml"), &text);
        let out = tmp.path().join(format!("{name}-out"));
        let csv = tmp.path().join(format!("{name}.csv"));
        let forward = run(&[&"forward", &scene, &"-o", &csv]);
        let stderr = assert_failure(&forward, expected);
        assert!(stderr.contains(&format!("{name}.toml")), "{stderr}");
        let fit = run(&[&"fit", &scene, &data, &"-o", &out]);
        assert_failure(&fit, expected);
        assert!(!out.exists() && !csv.exists(), "{name}: an output written");
    }
}

/// The bundled data's v and μ copied six times over
/// without a sigma column (dense enough to be condensed) once failed on a
/// σ of 1e-17 the file never held; now the message says what the file
/// holds and what to give. The Python module meets it through the same
/// code (`fit::condense`).
#[test]
fn copied_rows_without_sigma_say_what_the_file_holds() {
    let tmp = TempDir::new("copied-rows");
    let text = fs::read_to_string(bundled("hn-rubber.csv")).unwrap();
    let rows: Vec<String> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').take(2).collect::<Vec<_>>().join(","))
        .collect();
    let mut csv = String::from("v,mu\n");
    for _ in 0..6 {
        csv += &(rows.join("\n") + "\n");
    }
    let data = tmp.write("copies.csv", &csv);
    let out = tmp.path().join("fit");
    let fit = run(&[&"fit", &bundled("hn-rubber.toml"), &data, &"-o", &out]);
    assert_failure(
        &fit,
        &[
            "the 246 rows repeat 41 speeds",
            "the noise cannot be estimated from the scatter of repeated rows",
            "give a sigma column",
        ],
    );
    assert!(!out.exists());
}
