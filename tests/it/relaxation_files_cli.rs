//! Several relaxation files, or a folder of them, read by `rollfit master`
//! as one data set: one file per temperature, each file's temperature
//! from its file name or `--temperatures`, give the master curve of the
//! one file with a T column to the last digit; two files at one
//! temperature are refused.

use crate::common;

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};

use common::{TempDir, assert_failure, rollfit, text};

/// The isotherms' temperatures, °C.
const TEMPERATURES: [f64; 6] = [-10.0, 0.0, 10.0, 20.0, 30.0, 40.0];

/// A stretched-exponential E(t) (MPa) under WLF about 20 °C at `t` °C:
/// 16 times over three decades, as `t_s,E_relax_MPa` rows.
fn rows(t: f64) -> Vec<String> {
    let (e0, e1, tau, beta) = (2.0, 2000.0, 1e-2, 0.35);
    let log_a = -8.86 * (t - 20.0) / (101.6 + t - 20.0);
    (0..16)
        .map(|i| {
            let time = 10f64.powf(-1.0 + 3.0 * f64::from(i) / 15.0);
            let reduced = time / 10f64.powf(log_a);
            let e = e0 + (e1 - e0) * (-(reduced / tau).powf(beta)).exp();
            format!("{time:e},{e:e}")
        })
        .collect()
}

/// The one file with a T column.
fn plain() -> String {
    let mut text = String::from("T_C,t_s,E_relax_MPa\n");
    for t in TEMPERATURES {
        for row in rows(t) {
            text += &format!("{t},{row}\n");
        }
    }
    text
}

/// The same points as one file per temperature in `folder`: the first
/// four name their temperature, the last two nowhere (`--temperatures`).
fn per_temperature(tmp: &TempDir, folder: &str) -> PathBuf {
    let folder = tmp.path().join(folder);
    fs::create_dir(&folder).unwrap();
    for (k, t) in TEMPERATURES.iter().enumerate() {
        let name = match k < 4 {
            true => format!("{k}_relax_{t}C.csv"),
            false => format!("{k}_relax.csv"),
        };
        let text = format!("t_s,E_relax_MPa\n{}\n", rows(*t).join("\n"));
        fs::write(folder.join(name), text).unwrap();
    }
    folder
}

/// `rollfit master` of `inputs` into `out`, with `extra` arguments.
fn master(inputs: &[&Path], out: &Path, extra: &[&str]) -> String {
    let mut args: Vec<&OsStr> = vec![OsStr::new("master")];
    args.extend(inputs.iter().map(|p| p.as_os_str()));
    args.extend([OsStr::new("-o"), out.as_os_str()]);
    args.extend(extra.iter().map(OsStr::new));
    let run = rollfit(&args);
    assert!(
        run.status.success(),
        "rollfit failed:\n{}",
        text(&run.stderr)
    );
    text(&run.stdout)
}

/// A written file without its comment lines (which name the input).
fn body(path: &Path) -> String {
    let text = fs::read_to_string(path).unwrap();
    let lines: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).collect();
    lines.join("\n")
}

#[test]
fn relaxation_files_per_temperature_give_the_one_files_master_curve() {
    let tmp = TempDir::new("relaxation-files");
    let one = tmp.write("plain.csv", plain());
    let from_one = tmp.path().join("one");
    master(&[&one], &from_one, &[]);
    let folder = per_temperature(&tmp, "runs");
    let from_folder = tmp.path().join("folder");
    let summary = master(
        &[&folder],
        &from_folder,
        &["--temperatures", "-10,0,10,20,30,40"],
    );
    assert!(summary.contains("-10 °C, from the file name"), "{summary}");
    assert!(summary.contains("30 °C, from --temperatures"), "{summary}");
    for name in [
        "master.csv",
        "shift.csv",
        "relaxation.csv",
        "modulus.csv",
        "material.toml",
    ] {
        assert_eq!(
            body(&from_folder.join(name)),
            body(&from_one.join(name)),
            "{name}"
        );
    }

    // Without temperatures for the last two files: refused, naming one.
    let refused = rollfit(&[
        OsStr::new("master"),
        folder.as_os_str(),
        OsStr::new("-o"),
        tmp.path().join("refused").as_os_str(),
    ]);
    assert_failure(&refused, &["4_relax.csv: no temperature", "--temperatures"]);

    // Two runs at one temperature are no single isotherm.
    let twice = tmp.path().join("twice");
    fs::create_dir(&twice).unwrap();
    for name in ["a_20C.csv", "b_20C.csv"] {
        let text = format!("t_s,E_relax_MPa\n{}\n", rows(20.0).join("\n"));
        fs::write(twice.join(name), text).unwrap();
    }
    let refused = rollfit(&[
        OsStr::new("master"),
        twice.as_os_str(),
        OsStr::new("-o"),
        tmp.path().join("refused2").as_os_str(),
    ]);
    assert_failure(&refused, &["a_20C.csv", "b_20C.csv", "20.00 °C"]);
}
