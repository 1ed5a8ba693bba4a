//! Several DMA files, or a folder of them, wherever rollfit reads DMA
//! frequency data: `compare`, `report --dma`, `fit --dma` and a scene's
//! `model = "dma"` read one file per temperature through the same
//! per-file temperature rule as `rollfit master`, and give what the one
//! file with a T column gives, to the last digit.

use crate::common;

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};

use common::{TempDir, assert_failure, committed_fit_as, rollfit, text};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The bundled isotherms: 9 × 13 points, −20 … 60 °C in 10 K steps.
fn bundled() -> String {
    fs::read_to_string(root().join("data/hn-rubber-dma-isotherms.csv")).unwrap()
}

/// The bundled isotherms as one file per temperature in a folder
/// `sweeps`: the first six state their temperature in the file name, the
/// last three nowhere (`--temperatures` or a scene's `temperatures`).
/// Returns the folder and the files in name order.
fn per_temperature(tmp: &TempDir) -> (PathBuf, Vec<PathBuf>) {
    let mut isotherms: Vec<(String, Vec<String>)> = Vec::new();
    for line in bundled().lines().filter(|l| !l.starts_with('#')).skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        let row = cells[..3].join(",");
        match isotherms.last_mut() {
            Some((t, rows)) if t == cells[3] => rows.push(row),
            _ => isotherms.push((cells[3].to_string(), vec![row])),
        }
    }
    assert_eq!(isotherms.len(), 9);
    let folder = tmp.path().join("sweeps");
    fs::create_dir(&folder).unwrap();
    let mut files = Vec::new();
    for (k, (t, rows)) in isotherms.iter().enumerate() {
        let name = match k < 6 {
            true => format!("{k}_sweep_{t}C.csv"),
            false => format!("{k}_sweep.csv"),
        };
        let path = folder.join(name);
        fs::write(&path, format!("f,G_storage,G_loss\n{}\n", rows.join("\n"))).unwrap();
        files.push(path);
    }
    (folder, files)
}

/// The temperatures of [`per_temperature`]'s files, in their order.
const GIVEN: &str = "-20,-10,0,10,20,30,40,50,60";

fn run(args: &[&OsStr]) -> String {
    let out = rollfit(args);
    assert!(
        out.status.success(),
        "rollfit failed:\n{}",
        text(&out.stderr)
    );
    text(&out.stdout)
}

/// A JSON document without the keys that name the DMA files or hold the
/// reader's notes (which name them too).
fn without_names(path: &Path) -> serde_json::Value {
    let mut json: serde_json::Value = serde_json::from_slice(&fs::read(path).unwrap()).unwrap();
    strip(&mut json);
    json
}

fn strip(value: &mut serde_json::Value) {
    match value {
        serde_json::Value::Object(map) => {
            // Names, and the run time of a fit.
            for key in [
                "dma_file",
                "notes",
                "warnings",
                "dma_source",
                "source",
                "wall_time_s",
            ] {
                map.remove(key);
            }
            map.values_mut().for_each(strip);
        }
        serde_json::Value::Array(items) => items.iter_mut().for_each(strip),
        _ => {}
    }
}

/// `compare` and `report --dma` with a folder, or the files listed, give
/// the one file's compare.json (the metrics to the last digit), and the
/// files without a temperature are refused without `--temperatures`.
#[test]
fn compare_and_report_read_one_file_per_temperature() {
    let tmp = TempDir::new("dma-files-compare");
    let plain = tmp.write("plain.csv", bundled());
    let (folder, files) = per_temperature(&tmp);
    let one = committed_fit_as(&tmp, "hn-rubber-tset", "one");
    run(&[OsStr::new("compare"), one.as_os_str(), plain.as_os_str()]);
    let expected = without_names(&one.join("compare.json"));

    let by_folder = committed_fit_as(&tmp, "hn-rubber-tset", "folder");
    let stdout = run(&[
        OsStr::new("compare"),
        by_folder.as_os_str(),
        folder.as_os_str(),
        OsStr::new("--temperatures"),
        OsStr::new(GIVEN),
    ]);
    assert!(stdout.contains("117 points"), "{stdout}");
    assert_eq!(without_names(&by_folder.join("compare.json")), expected);

    let listed = committed_fit_as(&tmp, "hn-rubber-tset", "listed");
    let mut args: Vec<&OsStr> = vec![OsStr::new("compare"), listed.as_os_str()];
    args.extend(files.iter().map(|p| p.as_os_str()));
    args.extend([OsStr::new("--temperatures"), OsStr::new(GIVEN)]);
    run(&args);
    assert_eq!(without_names(&listed.join("compare.json")), expected);

    let out = rollfit(&[
        OsStr::new("compare"),
        listed.as_os_str(),
        folder.as_os_str(),
    ]);
    assert_failure(&out, &["6_sweep.csv: no temperature", "--temperatures"]);

    let report = committed_fit_as(&tmp, "hn-rubber-tset", "report");
    run(&[
        OsStr::new("report"),
        report.as_os_str(),
        OsStr::new("--dma"),
        folder.as_os_str(),
        OsStr::new("--temperatures"),
        OsStr::new(GIVEN),
        OsStr::new("--scene"),
        root().join("data/hn-rubber-tset.toml").as_os_str(),
    ]);
    assert_eq!(without_names(&report.join("compare.json")), expected);
    let html = fs::read_to_string(report.join("report.html")).unwrap();
    assert!(html.contains("sweeps"), "the report names the DMA folder");
}

/// `fit --dma FOLDER` fits what `fit --dma FILE` fits: fit.json equal but
/// for the names of the DMA source; the folder with files that state no
/// temperature is refused, and read with `--temperatures` as `master`
/// reads it.
#[test]
fn a_joint_fit_reads_a_folder_of_isotherms() {
    let tmp = TempDir::new("dma-files-fit");
    let plain = tmp.write("plain.csv", bundled());
    let (folder, files) = per_temperature(&tmp);
    // Only the six whose names state their temperature: a joint fit takes
    // no --temperatures.
    let named = tmp.path().join("named");
    fs::create_dir(&named).unwrap();
    for f in &files[..6] {
        fs::copy(f, named.join(f.file_name().unwrap())).unwrap();
    }
    let mut six = String::from("f,G_storage,G_loss,T\n");
    for line in bundled().lines().filter(|l| !l.starts_with('#')).skip(1) {
        let t: f64 = line.split(',').nth(3).unwrap().parse().unwrap();
        if t <= 30.0 {
            six += &format!("{line}\n");
        }
    }
    let six = tmp.write("six.csv", &six);
    let scene = root().join("data/hn-rubber-tset.toml");
    let data = root().join("data/hn-rubber-tset.csv");
    let fit_output = |dma: &Path, out: &str, flags: &[&str]| {
        let dir = tmp.path().join(out);
        let mut args = vec![
            OsStr::new("fit"),
            scene.as_os_str(),
            data.as_os_str(),
            OsStr::new("--dma"),
            dma.as_os_str(),
            OsStr::new("-o"),
            dir.as_os_str(),
        ];
        args.extend(flags.iter().map(OsStr::new));
        (rollfit(&args), dir.join("fit.json"))
    };
    let fit = |dma: &Path, out: &str| {
        let (output, json) = fit_output(dma, out, &[]);
        assert!(output.status.success(), "{}", text(&output.stderr));
        without_names(&json)
    };
    let (by_folder, by_file) = (fit(&named, "by-folder"), fit(&six, "by-file"));
    assert!(by_folder["joint"]["dma"].as_array().unwrap().len() == 78);
    assert!(by_folder == by_file, "fit.json differs");
    // The folder with files that state no temperature: refused, named.
    let (out, _) = fit_output(&folder, "refused", &[]);
    assert_failure(&out, &["6_sweep.csv: no temperature"]);
    assert!(!plain.with_file_name("refused").exists());
    // With --temperatures (and --units stating the files' Pa), as
    // `master` reads them: the nine files give the one file's fit.
    let flags = ["--temperatures", GIVEN, "--units", "Pa"];
    let (out, given) = fit_output(&folder, "given", &flags);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stderr = text(&out.stderr);
    assert!(stderr.contains("read in Pa, as stated"), "{stderr}");
    assert!(
        without_names(&given) == fit(&plain, "all"),
        "fit.json differs"
    );
}

/// A scene's `model = "dma"` with `file` a list or a folder (and
/// `temperatures` for the files that state none) predicts μ(v) to the
/// last digit as with the one file; a list for `model = "table"` is
/// refused.
#[test]
fn a_scene_dma_material_reads_a_list_or_a_folder() {
    let tmp = TempDir::new("dma-files-scene");
    tmp.write("plain.csv", bundled());
    let (_, files) = per_temperature(&tmp);
    let scene = |material: &str| {
        format!(
            "[geometry]\nshape = \"sphere\"\nradius = 0.01\nload = 0.05\n[material]\n\
             model = \"dma\"\n{material}\n[sweep]\nv_min = 1e-6\nv_max = 1.0\ncount = 11\n\
             temperature = [0.0, 20.0, 45.0]\n"
        )
    };
    let forward = |name: &str, material: &str| {
        let path = tmp.write(name, scene(material));
        let out = tmp.path().join(format!("{name}.csv"));
        run(&[
            OsStr::new("forward"),
            path.as_os_str(),
            OsStr::new("-o"),
            out.as_os_str(),
        ]);
        fs::read_to_string(out).unwrap()
    };
    let expected = forward("one.toml", "file = \"plain.csv\"");
    let list: Vec<String> = files
        .iter()
        .map(|f| {
            format!(
                "{:?}",
                format!("sweeps/{}", f.file_name().unwrap().to_str().unwrap())
            )
        })
        .collect();
    let temperatures = format!("temperatures = [{GIVEN}]");
    let listed = format!("file = [{}]\n{temperatures}", list.join(", "));
    assert_eq!(forward("list.toml", &listed), expected);
    let folder = format!("file = \"sweeps\"\n{temperatures}");
    assert_eq!(forward("folder.toml", &folder), expected);

    let table = tmp.write(
        "table.toml",
        "[geometry]\nshape = \"sphere\"\nradius = 0.01\nload = 0.05\n[material]\n\
         model = \"table\"\nfile = [\"a.csv\", \"b.csv\"]\n[sweep]\nv_min = 1e-6\n\
         v_max = 1.0\ncount = 11\n",
    );
    let out = rollfit(&[
        OsStr::new("forward"),
        table.as_os_str(),
        OsStr::new("-o"),
        tmp.path().join("table.csv").as_os_str(),
    ]);
    assert_failure(&out, &["model \"table\" reads one file: `file` is a list"]);
}
