//! `rollfit master` on DMA files as labs write them (issue 36): every
//! dialect the rolling-data reader accepts (`;` with decimal commas, tabs,
//! title lines; item 7) gives the comma file's master curve, and the
//! isotherms are grouped by a rule that cannot chain (item 6): a
//! temperature ramp is refused with its range, scattered isotherms keep
//! their count, a step column is honoured.

mod common;

use std::ffi::OsStr;
use std::fs;
use std::path::Path;

use common::{TempDir, assert_failure, rollfit, text};

/// The bundled isotherms: 9 × 13 points, −20 … 60 °C in 10 K steps.
fn bundled() -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/hn-rubber-dma-isotherms.csv");
    fs::read_to_string(path).unwrap()
}

/// `rollfit master DMA -o DIR`: its stdout on success, else a panic with
/// stderr.
fn master(dma: &Path, dir: &Path) -> std::process::Output {
    rollfit(&[
        OsStr::new("master"),
        dma.as_os_str(),
        OsStr::new("-o"),
        dir.as_os_str(),
    ])
}

fn succeed(out: std::process::Output) -> String {
    assert!(
        out.status.success(),
        "rollfit failed:\n{}",
        text(&out.stderr)
    );
    text(&out.stdout)
}

/// What master writes that does not name the input file.
fn outputs(dir: &Path) -> Vec<String> {
    ["master.csv", "shift.csv", "modulus.csv", "material.toml"]
        .iter()
        .map(|name| {
            let text = fs::read_to_string(dir.join(name)).unwrap();
            let body: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).collect();
            body.join("\n")
        })
        .collect()
}

/// The data lines of the bundled file, split into cells (comments kept
/// as they are).
fn with_cells(text: &str, mut f: impl FnMut(Vec<&str>) -> String) -> String {
    text.lines()
        .map(|l| match l.starts_with('#') {
            true => l.to_string(),
            false => f(l.split(',').collect()),
        })
        .collect::<Vec<_>>()
        .join("\n")
        + "\n"
}

#[test]
fn master_reads_every_dma_dialect_to_the_same_master_curve() {
    let tmp = TempDir::new("dialects");
    let comma = bundled();
    let reference = tmp.write("comma.csv", &comma);
    let stdout = succeed(master(&reference, &tmp.path().join("comma")));
    assert!(
        stdout.contains("9 isotherms: -20.0 … 60.0 °C (each within ±0.0 K)"),
        "{stdout}"
    );
    let expected = outputs(&tmp.path().join("comma"));
    let semicolon = with_cells(&comma, |c| c.join(";").replace('.', ","));
    let variants = [
        ("semicolon.csv", semicolon.clone()),
        ("tab.txt", with_cells(&comma, |c| c.join("\t"))),
        ("title.csv", format!("DMA export; sample HN-1\n{semicolon}")),
    ];
    for (name, content) in variants {
        let path = tmp.write(name, &content);
        let dir = tmp.path().join(name.replace('.', "_"));
        let out = master(&path, &dir);
        let stderr = text(&out.stderr);
        succeed(out);
        assert_eq!(outputs(&dir), expected, "{name}");
        if name == "title.csv" {
            assert!(
                stderr.contains("header on line 6; the 1 line above it (titles) ignored"),
                "{stderr}"
            );
        }
    }
    // Decimal commas between commas: refused at the line, nothing written.
    let path = tmp.write(
        "commas.csv",
        &with_cells(&comma, |c| c.join(",").replace('.', ",")),
    );
    let out = master(&path, &tmp.path().join("commas"));
    assert_failure(
        &out,
        &["commas.csv, line 6: 7 fields, but the header has 4 columns"],
    );
    assert!(!tmp.path().join("commas").exists());
}

#[test]
fn master_refuses_a_temperature_ramp_and_groups_by_gaps_or_steps() {
    let tmp = TempDir::new("ramp");
    // −50 … 150 °C in 0.02 K steps at three frequencies: a temperature
    // sweep, which once chained into one "isotherm at 49.99 °C".
    let mut ramp = String::from("f,E_storage,E_loss,T\n");
    for k in 0..=10_000 {
        let t = -50.0 + 0.02 * k as f64;
        for (f, s) in [(1.0, 2e6), (10.0, 3e6), (100.0, 5e6)] {
            ramp += &format!("{f},{s:e},{:e},{t:.2}\n", 0.2 * s);
        }
    }
    let path = tmp.write("ramp.csv", &ramp);
    let out = master(&path, &tmp.path().join("ramp"));
    assert_failure(
        &out,
        &[
            "DMA file",
            "ramp.csv: this looks like a temperature ramp, not isotherms: 30003 points from -50.00 \
             to 150.00 °C with no gap over 1 K between neighbouring temperatures (the widest is \
             0.02 K)",
            "rollfit master needs frequency sweeps at several fixed temperatures",
        ],
    );
    assert!(!tmp.path().join("ramp").exists());

    // The bundled isotherms with ±0.3 K scatter on T: still 9, each named
    // by its spread.
    let scatter = [0.3, -0.3, 0.1, -0.2, 0.0, 0.25, -0.1];
    let mut row = 0;
    let scattered = with_cells(&bundled(), |c| match c[3].parse::<f64>() {
        Ok(t) => {
            row += 1;
            let t = t + scatter[row % scatter.len()];
            format!("{},{},{},{t}", c[0], c[1], c[2])
        }
        Err(_) => c.join(","),
    });
    let path = tmp.write("scattered.csv", &scattered);
    let stdout = succeed(master(&path, &tmp.path().join("scattered")));
    assert!(
        stdout.contains(
            "9 isotherms: -20.0 … 60.0 °C (each within ±0.3 K); spread over 0.5 K: -20.3 … -19.7 °C"
        ),
        "{stdout}"
    );

    // A step column: the bundled file with a `Set` per isotherm gives
    // its master curve; the ramp cut into steps stays a ramp per step.
    let mut set = 0;
    let mut last = String::new();
    let stepped = with_cells(&bundled(), |c| {
        if c[3] != last {
            last = c[3].to_string();
            set += 1;
        }
        match c[3] {
            "T" => format!("Set,{}", c.join(",")),
            _ => format!("{set},{}", c.join(",")),
        }
    });
    let plain = tmp.write("plain.csv", &bundled());
    succeed(master(&plain, &tmp.path().join("plain")));
    let path = tmp.write("stepped.csv", &stepped);
    succeed(master(&path, &tmp.path().join("stepped")));
    assert_eq!(
        outputs(&tmp.path().join("stepped")),
        outputs(&tmp.path().join("plain"))
    );
}
