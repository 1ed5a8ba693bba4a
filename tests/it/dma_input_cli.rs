//! `rollfit master` on DMA files as labs write them: every
//! dialect the rolling-data reader accepts (`;` with decimal commas, tabs,
//! title lines; item 7) gives the comma file's master curve, and the
//! isotherms are grouped by a rule that cannot chain (item 6): a
//! temperature ramp is refused with its range, scattered isotherms keep
//! their count, a step column is honoured.

use crate::common;

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
        with_cells(&comma, |c| c.join(",").replace('.', ",")),
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
    let plain = tmp.write("plain.csv", bundled());
    succeed(master(&plain, &tmp.path().join("plain")));
    let path = tmp.write("stepped.csv", &stepped);
    succeed(master(&path, &tmp.path().join("stepped")));
    assert_eq!(
        outputs(&tmp.path().join("stepped")),
        outputs(&tmp.path().join("plain"))
    );
}

/// The bundled file's isotherms, each as its own file body (the header
/// `f,G_storage,G_loss`, no T column), in ascending temperature.
fn per_temperature() -> Vec<(String, Vec<String>)> {
    let mut out: Vec<(String, Vec<String>)> = Vec::new();
    for line in bundled().lines().filter(|l| !l.starts_with('#')).skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        let row = cells[..3].join(",");
        match out.last_mut() {
            Some((t, rows)) if t == cells[3] => rows.push(row),
            _ => out.push((cells[3].to_string(), vec![row])),
        }
    }
    out
}

/// `rollfit master` with `args` after the files.
fn master_files(files: &[&Path], dir: &Path, args: &[&str]) -> std::process::Output {
    let mut all: Vec<&OsStr> = vec![OsStr::new("master")];
    all.extend(files.iter().map(|p| p.as_os_str()));
    all.extend([OsStr::new("-o"), dir.as_os_str()]);
    all.extend(args.iter().map(OsStr::new));
    rollfit(&all)
}

/// One file per temperature, the temperature stated in the file name, in
/// a title line, in a key=value line or given on the command line: the
/// master curve of the one file with a T column, to the last digit, and
/// the summary says where each temperature came from.
#[test]
fn master_reads_one_file_per_temperature_from_every_source() {
    let tmp = TempDir::new("per-temperature");
    let plain = tmp.write("plain.csv", bundled());
    succeed(master(&plain, &tmp.path().join("plain")));
    let expected = outputs(&tmp.path().join("plain"));
    let folder = tmp.path().join("sweeps");
    fs::create_dir(&folder).unwrap();
    let isotherms = per_temperature();
    assert_eq!(isotherms.len(), 9);
    for (k, (t, rows)) in isotherms.iter().enumerate() {
        let (name, above) = match k {
            0 => (format!("a_{t}C.csv"), String::new()),
            1 => (format!("b_{t}c.csv"), String::new()),
            2 => (format!("c_{t}°C.csv"), String::new()),
            3 => ("d.csv".to_string(), format!("Temperature: {t} °C\n")),
            4 => ("e.csv".to_string(), format!("T={t};Mw=120000;\n")),
            5 => (
                "f.csv".to_string(),
                format!("Result: Frequency sweep {t}C-cooling\n"),
            ),
            _ => (format!("{}.csv", (b'a' + k as u8) as char), String::new()),
        };
        let body = format!("{above}f,G_storage,G_loss\n{}\n", rows.join("\n"));
        fs::write(folder.join(name), body).unwrap();
    }
    let given = "-20,-10,0,10,20,30,40,50,60";
    let out = master_files(
        &[&folder],
        &tmp.path().join("folder"),
        &["--temperatures", given],
    );
    let stdout = succeed(out);
    assert_eq!(outputs(&tmp.path().join("folder")), expected);
    for said in [
        "a_-20C.csv: 13 points, -20 °C, from the file name",
        "c_0°C.csv: 13 points, 0 °C, from the file name",
        "d.csv: 13 points, 10 °C, stated on line 1",
        "e.csv: 13 points, 20 °C, stated on line 1",
        "f.csv: 13 points, 30 °C, stated on line 1",
        "i.csv: 13 points, 60 °C, from --temperatures",
    ] {
        assert!(stdout.contains(said), "{said}\n{stdout}");
    }
    // Without the temperatures the last files state none: refused, named.
    let out = master_files(&[&folder], &tmp.path().join("none"), &[]);
    assert_failure(&out, &["g.csv: no temperature", "--temperatures"]);
    // The files one by one on the command line read alike; a count that
    // does not match the files is refused.
    let mut files: Vec<_> = fs::read_dir(&folder)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    let files: Vec<&Path> = files.iter().map(|p| p.as_path()).collect();
    succeed(master_files(
        &files,
        &tmp.path().join("listed"),
        &["--temperatures", given],
    ));
    assert_eq!(outputs(&tmp.path().join("listed")), expected);
    let out = master_files(
        &files,
        &tmp.path().join("count"),
        &["--temperatures", "1,2"],
    );
    assert_failure(&out, &["2 temperatures given for 9 DMA files"]);
}

/// Two sweeps at one temperature in two files are merged into one
/// isotherm ordered by frequency, and points at a repeated frequency are
/// averaged: the master curve of the file that holds each point once.
#[test]
fn master_merges_sweeps_at_one_temperature_and_repeated_frequencies() {
    let tmp = TempDir::new("merge");
    let plain = tmp.write("plain.csv", bundled());
    succeed(master(&plain, &tmp.path().join("plain")));
    let expected = outputs(&tmp.path().join("plain"));
    let folder = tmp.path().join("sweeps");
    fs::create_dir(&folder).unwrap();
    for (t, rows) in per_temperature() {
        let header = "f,G_storage,G_loss\n".to_string();
        if t == "20" {
            // Every other point in each of two files.
            for (part, name) in [(0, "20C_a.csv"), (1, "20C_b.csv")] {
                let mine: Vec<&String> = rows.iter().skip(part).step_by(2).collect();
                let body: Vec<&str> = mine.iter().map(|s| s.as_str()).collect();
                fs::write(folder.join(name), format!("{header}{}\n", body.join("\n"))).unwrap();
            }
        } else {
            fs::write(
                folder.join(format!("{t}C.csv")),
                format!("{header}{}\n", rows.join("\n")),
            )
            .unwrap();
        }
    }
    let out = master_files(&[&folder], &tmp.path().join("merged"), &[]);
    let stderr = text(&out.stderr);
    succeed(out);
    assert!(
        stderr.contains("2 sweeps at 20.00 °C (") && stderr.contains("merged into one isotherm"),
        "{stderr}"
    );
    assert_eq!(outputs(&tmp.path().join("merged")), expected);

    // The first point of the file written twice, E′ 1e6 Pa below and
    // above: their mean is the point.
    let first = "0.1,4.89321e+08,5.89546e+07,-20";
    let twice = bundled().replacen(
        first,
        "0.1,4.88321e+08,5.89546e+07,-20\n0.1,4.90321e+08,5.89546e+07,-20",
        1,
    );
    assert_ne!(twice, bundled());
    let path = tmp.write("twice.csv", &twice);
    let out = master(&path, &tmp.path().join("twice"));
    let stderr = text(&out.stderr);
    succeed(out);
    assert!(
        stderr.contains("isotherm at -20.00 °C: 2 points at repeated frequencies averaged into 1"),
        "{stderr}"
    );
    assert_eq!(outputs(&tmp.path().join("twice")), expected);
}

/// The numbers of master.csv, shift.csv and modulus.csv in `dir`, file by
/// file and row by row (empty cells as NaN).
fn numbers(dir: &Path) -> Vec<Vec<f64>> {
    ["master.csv", "shift.csv", "modulus.csv"]
        .iter()
        .map(|name| {
            let text = fs::read_to_string(dir.join(name)).unwrap();
            text.lines()
                .skip(1)
                .flat_map(|l| l.split(',').map(|c| c.parse().unwrap_or(f64::NAN)))
                .collect::<Vec<f64>>()
        })
        .collect()
}

/// Whether `a` and `b` agree within `tolerance`, NaN with NaN: relative
/// for numbers above 1 (moduli, frequencies), absolute below (log10 a_T
/// near T_ref is near 0 decades, where a relative test is meaningless).
fn agree(a: &[Vec<f64>], b: &[Vec<f64>], tolerance: f64) -> Result<(), String> {
    for (file, (x, y)) in a.iter().zip(b).enumerate() {
        if x.len() != y.len() {
            return Err(format!(
                "file {file}: {} against {} numbers",
                x.len(),
                y.len()
            ));
        }
        for (k, (p, q)) in x.iter().zip(y).enumerate() {
            let same = (p.is_nan() && q.is_nan()) || (p - q).abs() <= tolerance * p.abs().max(1.0);
            if !same {
                return Err(format!("file {file}, number {k}: {p} against {q}"));
            }
        }
    }
    Ok(())
}

/// The bundled isotherms written as rheometers export them — |G*| with δ
/// in degrees, |G*| with tan δ, η*′ and η*″, |η*| with δ in radians,
/// `Storage Modulus` and `Loss Modulus` in MPa on a units row — give the
/// plain file's master curve within 1e-6: each conversion is exact.
#[test]
fn master_reads_complex_moduli_phase_angles_and_viscosities() {
    let tmp = TempDir::new("forms");
    let plain = tmp.write("plain.csv", bundled());
    succeed(master(&plain, &tmp.path().join("plain")));
    let expected = numbers(&tmp.path().join("plain"));
    let rows: Vec<[f64; 4]> = bundled()
        .lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(|l| {
            let c: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            [c[0], c[1], c[2], c[3]]
        })
        .collect();
    type Row = fn(&[f64; 4]) -> String;
    let forms: [(&str, &str, Row, &[&str]); 5] = [
        (
            "abs-phase.csv",
            "Frequency [Hz],|G*| [Pa],Phase angle [°],Temperature [°C]",
            |[f, s, l, t]| format!("{f},{:e},{:e},{t}", s.hypot(*l), l.atan2(*s).to_degrees()),
            &[],
        ),
        (
            "abs-tan.csv",
            "f (Hz);Complex Modulus (Pa);tan(delta);T",
            |[f, s, l, t]| format!("{f};{:e};{:e};{t}", s.hypot(*l), l / s),
            &["--dma-modulus", "shear"],
        ),
        (
            "viscosity.csv",
            "Angular Frequency [rad/s],η*′ [Pa·s],η*″ [Pa·s],Temperature",
            |[f, s, l, t]| {
                let w = 2.0 * std::f64::consts::PI * f;
                format!("{w:e},{:e},{:e},{t}", l / w, s / w)
            },
            &[],
        ),
        (
            "complex-viscosity.csv",
            "Angular Frequency,Complex Viscosity,delta,Temperature\nrad/s,Pa·s,rad,°C",
            |[f, s, l, t]| {
                let w = 2.0 * std::f64::consts::PI * f;
                format!("{w:e},{:e},{:e},{t}", s.hypot(*l) / w, l.atan2(*s))
            },
            &[],
        ),
        (
            "storage-loss.csv",
            "Frequency,Storage Modulus,Loss Modulus,Temperature\n[Hz],[MPa],[MPa],[°C]",
            |[f, s, l, t]| format!("{f},{:e},{:e},{t}", s / 1e6, l / 1e6),
            &["--dma-modulus", "shear"],
        ),
    ];
    for (name, header, row, args) in forms {
        let body: Vec<String> = rows.iter().map(row).collect();
        let path = tmp.write(name, format!("{header}\n{}\n", body.join("\n")));
        let dir = tmp.path().join(name.replace('.', "_"));
        let mut all: Vec<&str> = vec![];
        all.extend(args);
        let out = master_files(&[&path], &dir, &all);
        let stderr = text(&out.stderr);
        succeed(out);
        agree(&numbers(&dir), &expected, 1e-6).unwrap_or_else(|e| panic!("{name}: {e}\n{stderr}"));
        if name == "abs-phase.csv" {
            assert!(stderr.contains("shear moduli from |M*| and δ"), "{stderr}");
        }
    }
    // Unitless moduli whose names do not say shear or Young's: read as
    // Young's in Pa, and both said.
    let body: Vec<String> = rows
        .iter()
        .map(|[f, s, l, t]| format!("{f},{s:e},{l:e},{t}"))
        .collect();
    let path = tmp.write(
        "unsaid.csv",
        format!(
            "Frequency,Storage Modulus,Loss Modulus,T\n{}\n",
            body.join("\n")
        ),
    );
    let out = master_files(&[&path], &tmp.path().join("unsaid"), &[]);
    let stderr = text(&out.stderr);
    succeed(out);
    for said in [
        "moduli without a unit in the file: read in Pa (give --units to state another)",
        "the column names do not say whether the moduli are Young's (E) or shear (G): read as \
         Young's (give --dma-modulus shear if they are shear moduli)",
    ] {
        assert!(stderr.contains(said), "{said}\n{stderr}");
    }
}

/// The bundled file as a UTF-16 export with a stray byte after its last
/// line (as RheoCompass writes one): its master curve, with notes.
#[test]
fn master_reads_utf16_with_a_stray_trailing_byte() {
    let tmp = TempDir::new("utf16");
    let plain = tmp.write("plain.csv", bundled());
    succeed(master(&plain, &tmp.path().join("plain")));
    let mut bytes = vec![0xFF, 0xFE];
    bytes.extend(bundled().encode_utf16().flat_map(u16::to_le_bytes));
    bytes.push(0x00);
    let path = tmp.path().join("utf16.csv");
    fs::write(&path, bytes).unwrap();
    let out = master(&path, &tmp.path().join("utf16"));
    let stderr = text(&out.stderr);
    succeed(out);
    for said in [
        "read as UTF-16 (little-endian byte-order mark)",
        "one stray byte after the last line",
    ] {
        assert!(stderr.contains(said), "{said}\n{stderr}");
    }
    assert_eq!(
        outputs(&tmp.path().join("utf16")),
        outputs(&tmp.path().join("plain"))
    );
}

/// The bundled isotherms as an Anton Paar RheoCompass export: a `Test:`
/// line, then one `Result:` block per temperature with its `Interval`
/// lines, a header row, units in brackets on a row of their own,
/// tab-separated cells with decimal commas and a point number and status
/// the reader does not know. `in_column`: each block's temperature in a T
/// column, else only in its Result line (`20C-cooling`). `split`: the
/// 20 °C sweep written as two blocks (every other point).
fn rheocompass(in_column: bool, split: bool) -> String {
    let mut out = vec!["Project:\tHN rubber".to_string(), "Test:\tFS".to_string()];
    let mut blocks: Vec<(String, Vec<String>)> = Vec::new();
    for (t, rows) in per_temperature() {
        match split && t == "20" {
            true => {
                for part in 0..2 {
                    let mine = rows.iter().skip(part).step_by(2).cloned().collect();
                    blocks.push((t.clone(), mine));
                }
            }
            false => blocks.push((t, rows)),
        }
    }
    for (t, rows) in blocks {
        let (title, t_name, t_unit) = match in_column {
            true => ("Frequency sweep".to_string(), "\tTemperature", "\t[°C]"),
            false => (format!("Frequency sweep {t}C-cooling"), "", ""),
        };
        out.push(format!("Result:\t{title}"));
        out.push(format!("Interval and data points:\t1\t{}", rows.len()));
        out.push(format!(
            "Interval data:\tPoint No.\tFrequency\tStorage Modulus\tLoss Modulus{t_name}\tStatus"
        ));
        out.push(format!("\t\t[Hz]\t[Pa]\t[Pa]{t_unit}\t[]"));
        for (k, row) in rows.iter().enumerate() {
            let cells = row.replace(',', "\t").replace('.', ",");
            let t_cell = if in_column {
                format!("\t{t}")
            } else {
                String::new()
            };
            out.push(format!("\t{}\t{cells}{t_cell}\tDy_auto", k + 1));
        }
        out.push(String::new());
    }
    out.join("\r\n") + "\r\n"
}

/// RheoCompass exports, UTF-8 and UTF-16, with the temperature in each
/// block's T column or only in its Result line: the master curve of the
/// plain CSV to the last digit, the summary naming each block's source;
/// two blocks at one temperature are merged into one isotherm and the
/// summary says so.
#[test]
fn master_reads_rheocompass_result_blocks() {
    let tmp = TempDir::new("rheocompass");
    let plain = tmp.write("plain.csv", bundled());
    succeed(master(&plain, &tmp.path().join("plain")));
    let expected = outputs(&tmp.path().join("plain"));
    let shear = ["--dma-modulus", "shear"];
    let utf8 = tmp.write("rc8.txt", rheocompass(false, false));
    let out = master_files(&[&utf8], &tmp.path().join("rc8"), &shear);
    let stderr = text(&out.stderr);
    let stdout = succeed(out);
    assert_eq!(outputs(&tmp.path().join("rc8")), expected);
    assert!(
        stderr.contains("rc8.txt: an Anton Paar RheoCompass export of 9 result block(s)"),
        "{stderr}"
    );
    assert!(
        stdout.contains("rc8.txt: 13 points, -20 °C, stated on line 3"),
        "{stdout}"
    );

    let mut bytes = vec![0xFF, 0xFE];
    bytes.extend(
        rheocompass(true, false)
            .encode_utf16()
            .flat_map(u16::to_le_bytes),
    );
    let utf16 = tmp.path().join("rc16.txt");
    fs::write(&utf16, bytes).unwrap();
    let out = master_files(&[&utf16], &tmp.path().join("rc16"), &shear);
    let stdout = succeed(out);
    assert_eq!(outputs(&tmp.path().join("rc16")), expected);
    assert!(
        stdout.contains("rc16.txt: 13 points, from its T column"),
        "{stdout}"
    );

    let split = tmp.write("split.txt", rheocompass(false, true));
    let out = master_files(&[&split], &tmp.path().join("split"), &shear);
    let stdout = succeed(out);
    assert_eq!(outputs(&tmp.path().join("split")), expected);
    assert!(
        stdout.contains("2 sweeps at 20.00 °C (")
            && stdout.contains("(block on line 75)")
            && stdout.contains("merged into one isotherm"),
        "{stdout}"
    );
}

/// Rheometer exports as they come, each the plain CSV's master curve to
/// the last digit with a note: a column name repeated, a header naming
/// more columns than its rows fill, rows ending in empty cells, numbers
/// aligned with runs of spaces, a Latin-1 `°` in a units row, CR-only
/// line ends and a UTF-8 byte-order mark.
#[test]
fn master_reads_messy_exports_with_a_note_each() {
    let tmp = TempDir::new("messy");
    let plain = tmp.write("plain.csv", bundled());
    succeed(master(&plain, &tmp.path().join("plain")));
    let expected = outputs(&tmp.path().join("plain"));
    let body: Vec<String> = bundled()
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(str::to_string)
        .collect();
    let rows = &body[1..];
    let each = |f: &dyn Fn(&str) -> String| rows.iter().map(|r| f(r)).collect::<Vec<_>>();
    let t_of = |r: &str| r.rsplit(',').next().unwrap().to_string();
    let aligned = |r: &str| {
        let cells: Vec<String> = r.split(',').map(|c| format!("{c:>14}")).collect();
        cells.join("  ")
    };
    let variants: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "twotemp.csv",
            format!(
                "f,G_storage,G_loss,Temp,Temp\n{}\n",
                each(&|r| format!("{r},{}", t_of(r))).join("\n")
            )
            .into_bytes(),
            "column 4 (Temp) and column 5 (Temp) have one name: the first is read",
        ),
        (
            "short.csv",
            format!("{},Comment,Operator\n{}\n", body[0], rows.join("\n")).into_bytes(),
            "117 row(s) hold fewer cells than the header's 6 columns (the first on line 2)",
        ),
        (
            "trailing.csv",
            format!("{}\n{}\n", body[0], each(&|r| format!("{r},,")).join("\n")).into_bytes(),
            "117 row(s) end with empty cells beyond the header's 4 columns",
        ),
        (
            "aligned.txt",
            format!(
                "  f   G_storage   G_loss   T\n{}\n",
                each(&aligned).join("\n")
            )
            .into_bytes(),
            "columns aligned with runs of spaces",
        ),
        (
            "latin1.csv",
            [
                format!("{}\nHz,Pa,Pa,", body[0]).as_bytes(),
                &[0xB0, b'C', b'\n'],
                rows.join("\n").as_bytes(),
                b"\n",
            ]
            .concat(),
            "not UTF-8 text (line 2 is not): read as Latin-1",
        ),
        (
            "cr.csv",
            (body.join("\r") + "\r").into_bytes(),
            "lines end with CR only",
        ),
        (
            "bom.csv",
            [&[0xEF, 0xBB, 0xBF], (body.join("\n") + "\n").as_bytes()].concat(),
            "UTF-8 byte-order mark ignored",
        ),
    ];
    for (name, bytes, said) in variants {
        let path = tmp.path().join(name);
        fs::write(&path, bytes).unwrap();
        let dir = tmp.path().join(name.replace('.', "_"));
        let out = master(&path, &dir);
        let stderr = text(&out.stderr);
        succeed(out);
        assert_eq!(outputs(&dir), expected, "{name}");
        assert!(stderr.contains(said), "{name}: {said}\n{stderr}");
    }
    // A second temperature column of another name is still refused, and a
    // short row that misses a column read is refused at its line.
    let two = format!(
        "f,G_storage,G_loss,T,Temp\n{}\n",
        each(&|r| format!("{r},{}", t_of(r))).join("\n")
    );
    let out = master(&tmp.write("two.csv", &two), &tmp.path().join("two"));
    assert_failure(&out, &["two temperature columns"]);
    let cut = format!("{}\n{}\n0.1,2e6\n", body[0], rows.join("\n"));
    let out = master(&tmp.write("cut.csv", &cut), &tmp.path().join("cut"));
    assert_failure(
        &out,
        &["cut.csv, line 119: 2 fields, but the header has 4 columns"],
    );
}

/// Temperatures in °F, as a `T_F` column or a units row, read by the one
/// table of temperature units the measured-data reader uses: the plain
/// file's master curve within 1e-6 (the conversion intervenes).
#[test]
fn master_reads_temperatures_in_fahrenheit() {
    let tmp = TempDir::new("fahrenheit");
    let plain = tmp.write("plain.csv", bundled());
    succeed(master(&plain, &tmp.path().join("plain")));
    let expected = numbers(&tmp.path().join("plain"));
    let fahrenheit = |c: Vec<&str>| match c[3].parse::<f64>() {
        Ok(t) => format!("{},{},{},{}", c[0], c[1], c[2], t * 9.0 / 5.0 + 32.0),
        Err(_) => c.join(","),
    };
    let body = with_cells(&bundled(), fahrenheit);
    for (name, text) in [
        (
            "suffix.csv",
            body.replace("f,G_storage,G_loss,T\n", "f,G_storage,G_loss,T_F\n"),
        ),
        (
            "row.csv",
            body.replace("G_loss,T\n", "G_loss,T\nHz,Pa,Pa,°F\n"),
        ),
    ] {
        let path = tmp.write(name, &text);
        assert!(text.contains(",-4\n"), "-20 °C is -4 °F");
        let dir = tmp.path().join(name.replace('.', "_"));
        succeed(master(&path, &dir));
        agree(&numbers(&dir), &expected, 1e-6).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}
