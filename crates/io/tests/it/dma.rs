//! DMA files read: the CSV forms, the TRIOS LIMS export, shear converted
//! to Young's, and every refusal naming the file, line and column
//! (docs/ARCHITECTURE.md, "Contract", "DMA files").
//!
//! Every expected value is computed here independently: the Prony and WLF
//! formulas written out in the test, unit conversions by hand. Fixtures in
//! tests/fixtures/ are the project's own (synthetic numbers from the model
//! named in each file's comment).

use std::f64::consts::PI;
use std::fs;
use std::path::{Path, PathBuf};

use rollfit_fit::master::pipeline;
use rollfit_fit::master::{MasterCurve, MasterSettings, ValidMasterSettings};
use rollfit_io::dma::{
    DmaData, DmaInput, DmaOptions, ModulusKind, group_isotherms, master_refused,
};
use rollfit_io::{IoError, chain, material_file};

use rollfit_testkit::eplexor::{eplexor_csv, eplexor_points, eplexor_rows};
use rollfit_testkit::files::TempDir;
use rollfit_testkit::materials::hn_rubber;
use rollfit_testkit::run::assert_contains;
use rollfit_testkit::series::{Series, wlf};
use rollfit_testkit::workbook::{X, ods, texts, xlsx};

// ---------------------------------------------------------------- helpers

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
}

fn relative(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

fn error_text(result: Result<DmaData, IoError>) -> String {
    match result {
        Ok(data) => panic!("expected an error, read {} points", data.points.len()),
        Err(e) => e.to_string(),
    }
}

// ---------------------------------------------------------------- CSV forms

/// Five points of the broad rubber (Young's, Pa) at 20 °C.
fn reference_points() -> Vec<(f64, f64, f64)> {
    let series = Series::broad_rubber();
    [0.5, 3.0, 20.0, 150.0, 900.0]
        .iter()
        .map(|&omega| {
            let (s, l) = series.at(omega);
            (omega, s, l)
        })
        .collect()
}

fn assert_points(data: &DmaData, expected: &[(f64, f64, f64)], temperature: Option<f64>) {
    assert_eq!(data.points.len(), expected.len());
    for (p, &(omega, storage, loss)) in data.points.iter().zip(expected) {
        assert!(relative(p.omega, omega) < 1e-13, "{p:?} vs ω {omega}");
        assert!(
            relative(p.storage, storage) < 1e-13,
            "{p:?} vs E′ {storage}"
        );
        assert!(relative(p.loss, loss) < 1e-13, "{p:?} vs E″ {loss}");
        match (p.temperature, temperature) {
            (Some(t), Some(e)) => assert!((t - e).abs() < 1e-12, "T {t} vs {e}"),
            (None, None) => {}
            other => panic!("temperature {other:?}"),
        }
    }
}

#[test]
fn every_csv_form_reads_the_same_points() {
    let dir = TempDir::new("forms");
    let points = reference_points();
    let nu = 0.5;
    // (file name, header, row maker, expected temperature)
    type Row = fn(f64, f64, f64) -> String;
    let forms: Vec<(&str, &str, Row, Option<f64>)> = vec![
        (
            "plain.csv",
            "omega,E_storage,E_loss",
            |w, s, l| format!("{w:e},{s:e},{l:e}"),
            None,
        ),
        (
            "hz.csv",
            "f,E_storage,E_loss,T",
            |w, s, l| format!("{:e},{s:e},{l:e},20", w / (2.0 * PI)),
            Some(20.0),
        ),
        (
            "suffixed.csv",
            "T_C,omega_rad_s,G_storage_Pa,G_loss_Pa,tan_delta",
            |w, s, l| format!("20,{w:e},{:e},{:e},{:e}", s / 3.0, l / 3.0, l / s),
            Some(20.0),
        ),
        (
            "hz_mpa.csv",
            "sample,f_Hz,E_loss_MPa,E_storage_MPa,T_K",
            |w, s, l| {
                format!(
                    "A-1,{:e},{:e},{:e},293.15",
                    w / (2.0 * PI),
                    l / 1e6,
                    s / 1e6
                )
            },
            Some(20.0),
        ),
        (
            "shear_kpa.csv",
            "omega,G_storage_kPa,G_loss_GPa",
            |w, s, l| format!("{w:e},{:e},{:e}", s / 3e3, l / 3e9),
            None,
        ),
    ];
    for (name, header, row, temperature) in forms {
        let mut text = format!("# {name}: made for the test\n{header}\n");
        for &(w, s, l) in &points {
            text.push_str(&row(w, s, l));
            text.push('\n');
        }
        text.push_str("\n# trailing comment\n");
        let path = dir.write(name, &text);
        let data = DmaData::read(&path, nu, &DmaOptions::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(data.format, "csv");
        let shear = name.contains("shear") || name.contains("suffixed");
        assert_eq!(
            data.kind,
            if shear {
                ModulusKind::Shear
            } else {
                ModulusKind::Young
            },
            "{name}"
        );
        // T_K: 293.15 − 273.15 is 20 only up to the rounding of the
        // subtraction (5.7e-14), hence the tolerance of assert_points.
        assert_points(&data, &points, temperature);
    }
}

#[test]
fn shear_becomes_young_with_the_fits_poisson_ratio() {
    let dir = TempDir::new("nu");
    let path = dir.write("g.csv", "omega,G_storage,G_loss\n1,1e6,2e5\n10,2e6,5e5\n");
    for nu in [0.5, 0.3, 0.0] {
        let data = DmaData::read(&path, nu, &DmaOptions::default()).unwrap();
        let factor = 2.0 + 2.0 * nu;
        assert_eq!(data.kind, ModulusKind::Shear);
        assert!(relative(data.points[0].storage, factor * 1e6) < 1e-15);
        assert!(relative(data.points[1].loss, factor * 5e5) < 1e-15);
        // The CSV's columns say shear: the conversion is a note, not a
        // warning.
        assert!(
            data.notes.iter().any(|w| w.contains(&format!("ν = {nu}"))),
            "{:?}",
            data.notes
        );
        assert!(data.warnings.is_empty(), "{:?}", data.warnings);
    }
    // A CSV says shear with its column names; a contrary request is
    // ignored, with a warning.
    let young = DmaOptions {
        kind: Some(ModulusKind::Young),
        wlf: None,
        ..Default::default()
    };
    let data = DmaData::read(&path, 0.5, &young).unwrap();
    assert_eq!(data.kind, ModulusKind::Shear);
    assert!(
        data.warnings.iter().any(|w| w.contains("ignored")),
        "{:?}",
        data.warnings
    );
    let e = DmaData::read(&path, 0.7, &DmaOptions::default()).unwrap_err();
    assert_contains(&e.to_string(), &["0.7"]);
}

// ---------------------------------------------------------------- TRIOS

/// The fixtures' model (their Notes line): shear Prony with WLF.
fn fixture_model(omega: f64, t: f64) -> (f64, f64) {
    let series = Series {
        e1: 1e8,
        h: vec![3e7, 4e7, 2.5e7],
        tau: vec![1e-3, 1e-2, 1e-1],
    };
    series.at(omega * 10f64.powf(wlf(t, 20.0, 8.86, 101.6)))
}

#[test]
fn trios_lims_shear_export_with_its_units() {
    let path = fixture("trios_shear_two_steps.txt");
    let data = DmaData::read(&path, 0.5, &DmaOptions::default()).unwrap();
    assert_eq!(data.format, "trios-lims");
    assert_eq!(data.kind, ModulusKind::Shear);
    assert_eq!(data.points.len(), 10);
    assert!(
        data.warnings.iter().any(|w| w.contains("shear")
            && w.contains("Oscillation torque")
            && w.contains("AresG2")),
        "{:?}",
        data.warnings
    );
    // Step 1: rad/s, °C, MPa and kPa; step 2: Hz, K, GPa and Pa.
    let omegas = [1.0, 3.16227766017, 10.0, 31.6227766017, 100.0]
        .into_iter()
        .chain([0.1, 0.5, 1.0, 5.0, 10.0].into_iter().map(|f| 2.0 * PI * f));
    let temperatures = [
        20.01, 19.99, 20.02, 20.0, 19.98, 40.01, 39.99, 40.0, 40.02, 40.0,
    ];
    for ((p, omega), t) in data.points.iter().zip(omegas).zip(temperatures) {
        let (g_storage, g_loss) = fixture_model(omega, t);
        assert!(relative(p.omega, omega) < 1e-11, "{p:?}");
        assert!((p.temperature.unwrap() - t).abs() < 1e-9, "{p:?}");
        // ν = 0.5: E = 3 G; the file has 12 significant digits.
        assert!(relative(p.storage, 3.0 * g_storage) < 1e-10, "{p:?}");
        assert!(relative(p.loss, 3.0 * g_loss) < 1e-10, "{p:?}");
    }
    assert_eq!(data.temperatures().len(), 2);

    // The user's word wins over the file's torque.
    let young = DmaOptions {
        kind: Some(ModulusKind::Young),
        wlf: None,
        ..Default::default()
    };
    let data = DmaData::read(&path, 0.5, &young).unwrap();
    assert_eq!(data.kind, ModulusKind::Young);
    let (g_storage, _) = fixture_model(1.0, 20.01);
    assert!(relative(data.points[0].storage, g_storage) < 1e-10);
}

#[test]
fn trios_lims_tensile_export_and_utf16() {
    let path = fixture("trios_tensile.txt");
    let data = DmaData::read(&path, 0.5, &DmaOptions::default()).unwrap();
    assert_eq!(data.kind, ModulusKind::Young);
    assert!(
        data.warnings
            .iter()
            .any(|w| w.contains("Oscillation force"))
    );
    for (p, omega) in data.points.iter().zip([1.0, 10.0, 100.0]) {
        let (s, l) = fixture_model(omega, 20.0);
        assert!(
            relative(p.storage, s) < 1e-10 && relative(p.loss, l) < 1e-10,
            "{p:?}"
        );
    }
    // The same text as UTF-16 with a byte-order mark, as Windows tools
    // write it, and with a .csv name: the content decides.
    let dir = TempDir::new("utf16");
    let text = fs::read_to_string(&path).unwrap();
    let mut bytes = vec![0xFF, 0xFE];
    bytes.extend(text.encode_utf16().flat_map(u16::to_le_bytes));
    let copy = dir.path().join("export.csv");
    fs::write(&copy, bytes).unwrap();
    let again = DmaData::read(&copy, 0.5, &DmaOptions::default()).unwrap();
    assert_eq!(again.format, "trios-lims");
    assert_eq!(again.points, data.points);
}

// ---------------------------------------------------------------- bad input

#[test]
fn bad_csv_files_are_refused_with_file_line_and_column() {
    let dir = TempDir::new("bad");
    let options = DmaOptions::default();
    let read = |name: &str, text: &str| DmaData::read(&dir.write(name, text), 0.5, &options);

    let missing = dir.path().join("absent.csv");
    let e = error_text(DmaData::read(&missing, 0.5, &options));
    assert_contains(&e, &["absent.csv"]);

    let e = error_text(read("noloss.csv", "omega,E_storage,T\n1,1e6,20\n"));
    assert_contains(
        &e,
        &[
            "noloss.csv",
            "no E_loss column",
            "the header has: omega, E_storage, T",
        ],
    );
    let e = error_text(read("nofreq.csv", "w,E_storage,E_loss\n1,1e6,1e5\n"));
    assert_contains(
        &e,
        &[
            "nofreq.csv",
            "no frequency column",
            "the header has: w, E_storage, E_loss",
        ],
    );
    let e = error_text(read("nomod.csv", "omega,storage,loss\n1,1e6,1e5\n"));
    assert_contains(&e, &["E_storage and E_loss (or G_storage and G_loss)"]);
    let e = error_text(read("half.csv", "omega,G_storage\n1,1e6\n"));
    assert_contains(&e, &["no G_loss column"]);

    let e = error_text(read(
        "text.csv",
        "# c\nomega,E_storage,E_loss\n1,1e6,1e5\n2,abc,1e5\n",
    ));
    assert_contains(
        &e,
        &[
            "text.csv, line 4",
            "column 2 (E_storage)",
            "\"abc\" is not a number",
        ],
    );
    let e = error_text(read("nan.csv", "omega,E_storage,E_loss\n1,1e6,NaN\n"));
    assert_contains(
        &e,
        &[
            "nan.csv, line 2",
            "column 3 (E_loss)",
            "not a finite number",
        ],
    );
    let e = error_text(read("inf.csv", "omega,E_storage,E_loss\ninf,1e6,1e5\n"));
    assert_contains(
        &e,
        &["inf.csv, line 2", "column 1 (omega)", "not a finite number"],
    );
    let e = error_text(read(
        "zero.csv",
        "f,E_storage,E_loss\n1,1e6,1e5\n0,1e6,1e5\n",
    ));
    assert_contains(&e, &["zero.csv, line 3", "column 1 (f)", "not positive"]);
    let e = error_text(read("soft.csv", "omega,E_storage,E_loss\n1,-1e6,1e5\n"));
    assert_contains(
        &e,
        &["soft.csv, line 2", "column 2 (E_storage)", "not positive"],
    );
    let e = error_text(read("short.csv", "omega,E_storage,E_loss\n1,1e6\n"));
    assert_contains(&e, &["short.csv, line 2", "2 fields", "3 columns"]);
    let e = error_text(read("empty.csv", "# nothing\nomega,E_storage,E_loss\n"));
    assert_contains(&e, &["empty.csv", "no data rows"]);
    let e = error_text(read("blank.csv", "# nothing at all\n"));
    assert_contains(&e, &["blank.csv", "no header"]);

    // A negative loss modulus is dropped with a warning naming it; a file
    // with nothing else is refused.
    let data = read("neg.csv", "omega,E_storage,E_loss\n1,1e6,1e5\n2,1e6,-3e4\n").unwrap();
    assert_eq!(data.points.len(), 1);
    assert!(
        data.warnings.iter().any(|w| w.contains("neg.csv, line 3")
            && w.contains("column 3 (E_loss)")
            && w.contains("dropped")),
        "{:?}",
        data.warnings
    );
    let e = error_text(read("allneg.csv", "omega,E_storage,E_loss\n1,1e6,-1e5\n"));
    assert_contains(&e, &["allneg.csv", "no usable points"]);
}

#[test]
fn bad_trios_files_are_refused_with_line_and_variable() {
    let dir = TempDir::new("badtrios");
    let good = fs::read_to_string(fixture("trios_tensile.txt")).unwrap();
    let options = DmaOptions::default();
    let read = |name: &str, text: &str| DmaData::read(&dir.write(name, text), 0.5, &options);

    let e = error_text(read("unit.txt", &good.replacen("MPa\tMPa", "MPa\tpsi", 1)));
    assert_contains(
        &e,
        &[
            "unit.txt, line 21",
            "Loss modulus",
            "column 6",
            "\"psi\"",
            "Pa, kPa, MPa, GPa",
        ],
    );
    let e = error_text(read("hz.txt", &good.replacen("\trad/s\t", "\trpm\t", 1)));
    assert_contains(&e, &["hz.txt, line 21", "Angular frequency", "\"rpm\""]);
    let e = error_text(read(
        "novar.txt",
        &good.replace("\tLoss modulus", "\tComplex modulus"),
    ));
    assert_contains(
        &e,
        &[
            "novar.txt",
            "no step has the variables needed",
            "Complex modulus",
        ],
    );
    let e = error_text(read(
        "num.txt",
        &good.replacen("Data point\t20\t1\t", "Data point\t20\tx\t", 1),
    ));
    assert_contains(
        &e,
        &["num.txt, line 22", "column 3 (Angular frequency)", "\"x\""],
    );
    let undecided = good
        .replace("Oscillation force", "Amplitude")
        .replace("RSA-G2", "Mystery 3000");
    let e = error_text(read("kind.txt", &undecided));
    assert_contains(
        &e,
        &[
            "kind.txt",
            "shear (G) or tensile (E)",
            "Mystery 3000",
            "--dma-modulus",
        ],
    );
    let told = DmaOptions {
        kind: Some(ModulusKind::Shear),
        wlf: None,
        ..Default::default()
    };
    let data = DmaData::read(&dir.path().join("kind.txt"), 0.5, &told).unwrap();
    assert_eq!(data.kind, ModulusKind::Shear);
    let e = error_text(read("nodata.txt", good.split("Data point").next().unwrap()));
    assert_contains(&e, &["nodata.txt", "without data points"]);
}

/// A hole fuzzing found: `f` and `omega` together, or a frequency whose
/// name and unit disagree, was read as one of them without a word.
#[test]
fn csv_with_two_frequency_columns_or_contradictory_units_is_refused() {
    let dir = TempDir::new("freq");
    let options = DmaOptions::default();
    let read = |name: &str, text: &str| DmaData::read(&dir.write(name, text), 0.5, &options);

    let e = error_text(read(
        "both.csv",
        "# f and omega\nf,omega,E_storage,E_loss\n1,6.283185307179586,1e6,1e5\n",
    ));
    assert_contains(
        &e,
        &[
            "both.csv, line 2",
            "two frequency columns, column 1 (f) and column 2 (omega)",
            "keep one",
        ],
    );
    let e = error_text(read(
        "suffixed.csv",
        "omega_rad_s,E_storage,E_loss,f_Hz\n6.283185307179586,1e6,1e5,1\n",
    ));
    assert_contains(
        &e,
        &[
            "suffixed.csv, line 1",
            "column 1 (omega_rad_s) and column 4 (f_Hz)",
        ],
    );
    let e = error_text(read(
        "omega_hz.csv",
        "T,omega_Hz,E_storage,E_loss\n20,1,1e6,1e5\n",
    ));
    assert_contains(
        &e,
        &[
            "omega_hz.csv, line 1",
            "column 2 (omega_Hz)",
            "`omega` is an angular frequency, in rad/s, but the suffix says Hz",
        ],
    );
    let e = error_text(read("f_rad.csv", "f_rad_s,E_storage,E_loss\n1,1e6,1e5\n"));
    assert_contains(
        &e,
        &[
            "f_rad.csv, line 1",
            "column 1 (f_rad_s)",
            "`f` is a frequency, in Hz, but the suffix says rad/s",
        ],
    );
    // The same for the moduli and the temperature: which of two is meant
    // is a guess with a factor 10⁶ or 273.15 K on it.
    let e = error_text(read(
        "two_storage.csv",
        "omega,E_storage,E_loss,E_storage_MPa\n1,1e6,1e5,1\n",
    ));
    assert_contains(
        &e,
        &[
            "two_storage.csv, line 1",
            "two E_storage columns, column 2 (E_storage) and column 4 (E_storage_MPa)",
        ],
    );
    let e = error_text(read(
        "two_t.csv",
        "omega,E_storage,E_loss,T_C,T_K\n1,1e6,1e5,20,293.15\n",
    ));
    assert_contains(
        &e,
        &["two_t.csv, line 1", "column 4 (T_C) and column 5 (T_K)"],
    );
}

/// A hole fuzzing found: a TRIOS export cut off was read in part; its
/// `Number of points` was never checked.
#[test]
fn truncated_trios_export_is_refused() {
    let dir = TempDir::new("trios-cut");
    let good = fs::read_to_string(fixture("trios_shear_two_steps.txt")).unwrap();
    let options = DmaOptions::default();
    let read = |name: &str, text: &str| DmaData::read(&dir.write(name, text), 0.5, &options);
    let lines: Vec<&str> = good.lines().collect();
    // The first `n` lines, each with its line break.
    let head = |n: usize| {
        lines[..n]
            .iter()
            .map(|l| format!("{l}\n"))
            .collect::<String>()
    };

    // Cut inside the second step's Variables line (line 30): the first
    // isotherm alone used to be read.
    let cut = format!("{}Variables\tTemperature\tFreq", head(29));
    let e = error_text(read("variables.txt", &cut));
    assert_contains(
        &e,
        &[
            "variables.txt, line 29",
            "step \"Frequency sweep (40.0 °C)\" (line 27)",
            "Number of points says 5",
            "without data points",
            "truncated",
        ],
    );
    // Cut between rows: two of five rows left.
    let e = error_text(read("rows.txt", &head(33)));
    assert_contains(
        &e,
        &[
            "rows.txt, line 29",
            "step \"Frequency sweep (40.0 °C)\" (line 27)",
            "Number of points says 5, but 2 data point rows follow (lines 32 to 33)",
            "it ends at line 33",
        ],
    );
    // Cut in the last row's last number (5000121.77315 → 5000121.7):
    // the row count matches and the number parses.
    let mid_number = format!(
        "{}Data point\t313.15\t10\t50\t0.00617224643619\t6166024.9",
        head(35)
    );
    let e = error_text(read("number.txt", &mid_number));
    assert_contains(
        &e,
        &[
            "number.txt, line 36",
            "step \"Frequency sweep (40.0 °C)\" (line 27)",
            "without a line break",
            "cut off",
        ],
    );
    // Cut mid-row, before the used columns end.
    let mid_row = format!("{}Data point\t313.15\t10\t50\t0.006", head(35));
    let e = error_text(read("row.txt", &mid_row));
    assert_contains(&e, &["row.txt, line 36", "without a line break"]);
    // More rows than declared, and a count that is not one.
    let extra = good.replacen("Number of points\t5", "Number of points\t4", 1);
    let e = error_text(read("extra.txt", &extra));
    assert_contains(
        &e,
        &[
            "extra.txt, line 19",
            "step \"Frequency sweep (20.0 °C)\" (line 17)",
            "Number of points says 4, but 5 data point rows follow (lines 22 to 26)",
        ],
    );
    let e = error_text(read(
        "count.txt",
        &good.replacen("Number of points\t5", "Number of points\tfive", 1),
    ));
    assert_contains(
        &e,
        &[
            "count.txt, line 19",
            "Number of points \"five\" is not a count",
        ],
    );
    // The whole file, with and without CRLF line breaks, still reads.
    assert_eq!(read("whole.txt", &good).unwrap().points.len(), 10);
    let crlf = good.replace('\n', "\r\n");
    assert_eq!(read("crlf.txt", &crlf).unwrap().points.len(), 10);
}

/// A hole fuzzing found: a CSV cut inside its last row.
#[test]
fn csv_cut_in_its_last_row_is_refused_or_flagged() {
    let dir = TempDir::new("csv-cut");
    let options = DmaOptions::default();
    let read = |name: &str, text: &str| DmaData::read(&dir.write(name, text), 0.5, &options);
    let head = "omega,E_storage,E_loss\n1,1e6,1e5\n";

    let e = error_text(read("cells.csv", &format!("{head}2,1.2e")));
    assert_contains(
        &e,
        &[
            "cells.csv, line 3",
            "2 fields, but the header has 3 columns",
            "no value for column 3 (E_loss)",
            "cut off",
        ],
    );
    let e = error_text(read("exponent.csv", &format!("{head}2,1e6,1.2e")));
    assert_contains(
        &e,
        &[
            "exponent.csv, line 3",
            "column 3 (E_loss)",
            "\"1.2e\" is not a number",
        ],
    );
    let e = error_text(read("dot.csv", &format!("{head}2,1e6,1.2e+")));
    assert_contains(&e, &["dot.csv, line 3", "column 3 (E_loss)", "\"1.2e+\""]);
    // A number cut to one that still parses: only the missing line break
    // tells, and CSV files without one are common: read, with a warning.
    let data = read("digits.csv", &format!("{head}2,1e6,1.2")).unwrap();
    assert_eq!(data.points.len(), 2);
    assert!(
        data.warnings
            .iter()
            .any(|w| w.contains("digits.csv, line 3") && w.contains("without a line break")),
        "{:?}",
        data.warnings
    );
    let data = read("whole.csv", &format!("{head}2,1e6,1.2e5\n")).unwrap();
    assert!(data.warnings.is_empty(), "{:?}", data.warnings);
}

/// A hole fuzzing found: invalid bytes were "stream did not contain valid
/// UTF-8" (fit folder) or quietly read as Latin-1 (DMA); now the file, the
/// line and the byte offset.
#[test]
fn invalid_bytes_in_dma_files_are_located_by_line_and_offset() {
    let dir = TempDir::new("bytes");
    let options = DmaOptions::default();
    let write = |name: &str, bytes: &[u8]| {
        let path = dir.path().join(name);
        fs::write(&path, bytes).unwrap();
        path
    };

    // UTF-8 (the ° of line 1) with a stray 0xFF in line 3, byte 3.
    let mut bytes = "# 20 °C\nomega,E_storage,E_loss\n1,".as_bytes().to_vec();
    let offset = bytes.len();
    bytes.extend(b"\xFF,1e5\n");
    let e = error_text(DmaData::read(&write("mixed.csv", &bytes), 0.5, &options));
    assert_contains(
        &e,
        &[
            "mixed.csv, line 3",
            "invalid UTF-8",
            &format!("byte 0xFF at byte offset {offset} (byte 3 of the line)"),
        ],
    );
    // A UTF-8 mark says UTF-8 for the whole file.
    let mut marked = vec![0xEF, 0xBB, 0xBF];
    marked.extend(b"omega,E_storage,E_loss\n1,1e6,1e5\n2,1e6,");
    let offset = marked.len();
    marked.extend(b"\xB05\n");
    let e = error_text(DmaData::read(&write("bom.csv", &marked), 0.5, &options));
    assert_contains(
        &e,
        &[
            "bom.csv, line 3",
            "byte-order mark",
            &format!("byte 0xB0 at byte offset {offset} (byte 7 of the line)"),
        ],
    );
    // Latin-1 throughout is still read (° as 0xB0 in a comment).
    let latin1 = b"# 20 \xB0C\nomega,E_storage,E_loss\n1,1e6,1e5\n";
    let data = DmaData::read(&write("latin1.csv", latin1), 0.5, &options).unwrap();
    assert_eq!(data.points.len(), 1);

    // UTF-16: an unpaired surrogate in line 2, and an odd byte count.
    let text = fs::read_to_string(fixture("trios_tensile.txt")).unwrap();
    let units: Vec<u16> = text.encode_utf16().collect();
    let second_line = units.iter().position(|&u| u == u16::from(b'\n')).unwrap() + 1;
    let mut bad = units.clone();
    bad[second_line + 3] = 0xD800;
    let utf16 = |units: &[u16]| {
        let mut bytes = vec![0xFF, 0xFE];
        bytes.extend(units.iter().flat_map(|u| u.to_le_bytes()));
        bytes
    };
    let e = error_text(DmaData::read(
        &write("surrogate.txt", &utf16(&bad)),
        0.5,
        &options,
    ));
    assert_contains(
        &e,
        &[
            "surrogate.txt, line 2",
            "unpaired surrogate 0xD800",
            &format!("byte offset {}", 2 + 2 * (second_line + 3)),
        ],
    );
    let mut odd = utf16(&units);
    odd.pop();
    let e = error_text(DmaData::read(&write("odd.txt", &odd), 0.5, &options));
    assert_contains(
        &e,
        &["odd.txt, line 24", "odd number of bytes", "truncated"],
    );
}

/// data/hn-rubber-dma.csv (the bundled example's DMA sweep, made with the
/// command in data/README.md) is the hn-rubber truth at six significant
/// digits: the Havriliak–Negami modulus of rollfit-model, G = E/3.
#[test]
fn the_bundled_dma_sweep_is_the_truth_of_the_example() {
    use rollfit_model::ViscoelasticModulus;
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/hn-rubber-dma.csv");
    let data = DmaData::read(&path, 0.5, &DmaOptions::default()).unwrap();
    assert_eq!(data.points.len(), 21);
    let truth = hn_rubber();
    for p in &data.points {
        let e = truth.modulus(p.omega);
        assert!(relative(p.storage, e.re) < 1e-5, "E′ at {}", p.omega);
        assert!(relative(p.loss, e.im) < 1e-5, "E″ at {}", p.omega);
    }
}

/// Found by fuzzing: the csv crate's record position is where
/// it began to read, before skipped comment and blank lines and, in CRLF
/// files (the 468MP CSV is one), a line early; messages named the wrong
/// line.
#[test]
fn csv_errors_name_the_right_line_below_comments_blank_lines_and_in_crlf_files() {
    let dir = TempDir::new("lines");
    let cases = [
        (
            "comment.csv",
            "omega,E_storage,E_loss\n1,1e6,1e5\n# mid\n2,abc,1e5\n",
            4,
        ),
        (
            "blank.csv",
            "omega,E_storage,E_loss\n1,1e6,1e5\n\n\n2,abc,1e5\n",
            5,
        ),
        (
            "crlf.csv",
            "omega,E_storage,E_loss\r\n1,1e6,1e5\r\n2,abc,1e5\r\n",
            3,
        ),
        (
            "crlf_comment.csv",
            "\r\n# x\r\n\r\nomega,E_storage,E_loss\r\n1,1e6,1e5\r\n# y\r\n2,abc,1e5\r\n",
            7,
        ),
    ];
    for (name, text, line) in cases {
        let e = error_text(DmaData::read(
            &dir.write(name, text),
            0.5,
            &DmaOptions::default(),
        ));
        assert_contains(&e, &[&format!("{name}, line {line}:"), "\"abc\""]);
    }
}

// ---------------------------------------------------------------- workbooks

/// A DMA file read, grouped and made a master curve by the fit library's
/// pipeline, as `rollfit master` does.
struct Mastered {
    data: DmaData,
    settings: ValidMasterSettings,
    master: MasterCurve,
}

fn master_of(path: &Path, settings: &MasterSettings) -> Result<Mastered, IoError> {
    let data = DmaInput::file(path).read(0.5, None)?;
    let untimed = settings.t_ref.unwrap_or(rollfit_fit::master::DEFAULT_T_REF);
    let read = group_isotherms(data, Some(untimed))?;
    let built = pipeline::build(&read.isotherms, (), settings)
        .map_err(|error| master_refused(&read.data.path, error))?;
    Ok(Mastered {
        data: read.data,
        settings: built.settings,
        master: built.master,
    })
}

/// material.toml without its comment header (which names the file).
fn material_body(built: &Mastered) -> String {
    let encoded = material_file::encode(&built.data.path, &built.master, &built.settings);
    let text = String::from_utf8(encoded.unwrap()).unwrap();
    text.lines()
        .filter(|l| !l.starts_with('#'))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn eplexor_workbook_gives_the_csv_master_curve_to_the_last_digit() {
    let dir = TempDir::new("eplexor");
    let points = eplexor_points(&[0.0, 20.0, 40.0, 60.0]);
    let csv = dir.write("sweep.csv", eplexor_csv(&points));
    let book = xlsx(&[
        ("Sheet1", eplexor_rows(&points, false)),
        ("Info", vec![vec![X::S("Operator"), X::S("A. N. Other")]]),
    ]);
    let xlsx_path = dir.write("sweep.xlsx", &book);
    let ods_path = dir.write("sweep.ods", ods("Messung", eplexor_rows(&points, false)));
    let settings = MasterSettings::default();
    let from_csv = master_of(&csv, &settings).unwrap();
    assert_eq!(from_csv.data.format, "csv");
    for path in [&xlsx_path, &ods_path] {
        let built = master_of(path, &settings)
            .unwrap_or_else(|e| panic!("{}: {}", path.display(), chain(&e)));
        assert_eq!(built.data.format, "workbook");
        // Bit for bit: the points, every shifted point, the series, the
        // shift, and the material a scene reads.
        assert_eq!(built.data.points, from_csv.data.points);
        assert_eq!(built.data.kind, ModulusKind::Young);
        assert_eq!(
            format!("{:?}", built.master),
            format!("{:?}", from_csv.master)
        );
        assert_eq!(material_body(&built), material_body(&from_csv));
        // Rows of the sheet: the data start below the units row (row 5).
        assert_eq!(built.data.lines[0], 6);
        assert!(built.data.warnings.is_empty(), "{:?}", built.data.warnings);
        assert!(
            built
                .data
                .notes
                .iter()
                .any(|n| n.contains("header on sheet")
                    && n.contains("row 4; the 2 rows above it (titles) ignored")),
            "{:?}",
            built.data.notes
        );
        assert!(
            built
                .data
                .notes
                .iter()
                .any(|n| n.contains("row 5, below the header")),
            "{:?}",
            built.data.notes
        );
    }
    // Independently of the CSV reader: E′ in MPa × 1e6, f in Hz × 2π.
    let data = DmaData::read(&xlsx_path, 0.5, &DmaOptions::default()).unwrap();
    assert_eq!(data.sheet.as_deref(), Some("Sheet1"));
    let (t, f, s, l) = points[3];
    let p = data.points[3];
    assert_eq!(p.temperature, Some(t));
    assert!(relative(p.omega, 2.0 * PI * f) < 1e-15);
    assert!(relative(p.storage, s * 1e6) < 1e-15);
    assert!(relative(p.loss, l * 1e6) < 1e-15);
    // A workbook saved under another name is one by its content.
    let renamed = dir.write("sweep.txt", &book);
    let data = DmaData::read(&renamed, 0.5, &DmaOptions::default()).unwrap();
    assert_eq!(data.points.len(), points.len());
    assert!(
        data.notes.iter().any(|n| n.contains("by its content")),
        "{:?}",
        data.notes
    );
}

#[test]
fn shear_eplexor_workbook_is_converted_with_poisson() {
    let dir = TempDir::new("eplexor-shear");
    let points = eplexor_points(&[20.0]);
    let path = dir.write(
        "shear.xlsx",
        xlsx(&[("Sheet1", eplexor_rows(&points, true))]),
    );
    let nu = 0.4;
    let data = DmaData::read(&path, nu, &DmaOptions::default()).unwrap();
    assert_eq!(data.kind, ModulusKind::Shear);
    for (p, &(_, f, s, l)) in data.points.iter().zip(&points) {
        assert!(relative(p.omega, 2.0 * PI * f) < 1e-15);
        assert!(relative(p.storage, 2.0 * (1.0 + nu) * s * 1e6) < 1e-15);
        assert!(relative(p.loss, 2.0 * (1.0 + nu) * l * 1e6) < 1e-15);
    }
    assert!(
        data.notes
            .iter()
            .any(|n| n.contains("shear moduli G′, G″ converted") && n.contains("ν = 0.4")),
        "{:?}",
        data.notes
    );
}

#[test]
fn workbook_sheet_by_name_and_plain_column_names() {
    use X::*;
    let dir = TempDir::new("sheets");
    let book = xlsx(&[
        ("Notes", vec![vec![S("measured 2026-03-01")]]),
        (
            "Run 2",
            vec![
                vec![
                    S("omega_rad_s"),
                    S("G_storage_kPa"),
                    S("G_loss_kPa"),
                    S("T_K"),
                ],
                vec![N(1.0), N(1e3), N(2e2), N(293.15)],
                vec![N(10.0), S("2,5E+03"), N(5e2), N(293.15)],
            ],
        ),
    ]);
    let path = dir.write("runs.xlsx", &book);
    let options = DmaOptions::default();
    for name in ["Run 2", "run 2"] {
        let data = DmaData::read_sheet(&path, 0.5, &options, Some(name)).unwrap();
        assert_eq!(data.sheet.as_deref(), Some("Run 2"));
        assert_eq!(data.kind, ModulusKind::Shear);
        assert_eq!(data.lines, [2, 3]);
        assert_eq!(data.points[1].omega, 10.0);
        assert_eq!(data.points[1].storage, 3.0 * 2.5e6);
        assert!((data.points[0].temperature.unwrap() - 20.0).abs() < 1e-12);
    }
    let e = chain(&DmaData::read_sheet(&path, 0.5, &options, Some("Run 3")).unwrap_err());
    assert_contains(
        &e,
        &["runs.xlsx", "no sheet \"Run 3\"", "\"Notes\", \"Run 2\""],
    );
    // The first sheet has no DMA columns: every sheet's header cells listed.
    let e = chain(&DmaData::read(&path, 0.5, &options).unwrap_err());
    assert_contains(
        &e,
        &[
            "runs.xlsx: sheet \"Notes\": no header row naming a frequency",
            "sheet \"Notes\" has \"measured 2026-03-01\"",
            "sheet \"Run 2\" has \"omega_rad_s\", \"G_storage_kPa\", \"G_loss_kPa\", \"T_K\"",
        ],
    );
    // A sheet named for a text file.
    let csv = dir.write("plain.csv", "omega,E_storage,E_loss\n1,1e6,1e5\n");
    let e = chain(&DmaData::read_sheet(&csv, 0.5, &options, Some("Run 2")).unwrap_err());
    assert_contains(
        &e,
        &["plain.csv: a sheet (\"Run 2\") was given", "not a workbook"],
    );
}

#[test]
fn bad_workbook_cells_name_the_sheet_and_cell() {
    use X::*;
    let dir = TempDir::new("bad-cells");
    let points = eplexor_points(&[20.0]);
    let options = DmaOptions::default();
    // Text in a number column: row 7 is the second point (rows 6 on).
    let mut rows = eplexor_rows(&points, false);
    rows[6][5] = S("n. m.");
    let path = dir.write("text.xlsx", xlsx(&[("Sheet1", rows)]));
    let e = chain(&DmaData::read(&path, 0.5, &options).unwrap_err());
    assert_contains(
        &e,
        &[
            "text.xlsx, sheet \"Sheet1\", cell F7: column F (E'')",
            "\"n. m.\" is not a number",
        ],
    );
    // An error cell (#DIV/0!) or an empty cell: the row is skipped with a
    // warning naming it, as the measured-data reader does.
    let mut rows = eplexor_rows(&points, false);
    rows[6][4] = Error;
    rows[8][3] = E;
    let path = dir.write("error.xlsx", xlsx(&[("Sheet1", rows)]));
    let data = DmaData::read(&path, 0.5, &options).unwrap();
    assert_eq!(data.points.len(), points.len() - 2);
    assert!(!data.lines.contains(&7) && !data.lines.contains(&9));
    assert!(
        data.warnings
            .iter()
            .any(|w| w.contains("skipped sheet \"Sheet1\", rows 7, 9 with an empty cell")),
        "{:?}",
        data.warnings
    );
    // A non-positive value names the row and the column.
    let mut rows = eplexor_rows(&points, false);
    rows[7][4] = N(-1.0);
    let path = dir.write("negative.xlsx", xlsx(&[("Sheet1", rows)]));
    let e = chain(&DmaData::read(&path, 0.5, &options).unwrap_err());
    assert_contains(
        &e,
        &[
            "negative.xlsx, sheet \"Sheet1\", row 8: column E (E'): storage modulus -1000000 is not positive",
        ],
    );
    // A unit not known in the units row names its cell.
    let mut rows = eplexor_rows(&points, false);
    rows[4][4] = S("[psi]");
    let path = dir.write("psi.xlsx", xlsx(&[("Sheet1", rows)]));
    let e = chain(&DmaData::read(&path, 0.5, &options).unwrap_err());
    assert_contains(
        &e,
        &["psi.xlsx, sheet \"Sheet1\", cell E5: column \"E'\": unit \"psi\" not known"],
    );
    // Not a workbook after all.
    let path = dir.write("broken.xlsx", b"PK\x03\x04 not really a zip");
    let e = chain(&DmaData::read(&path, 0.5, &options).unwrap_err());
    assert_contains(&e, &["broken.xlsx: cannot read the file as a workbook"]);
}

#[test]
fn one_isotherm_workbook_is_a_modulus_table() {
    let dir = TempDir::new("table");
    let points = eplexor_points(&[25.0]);
    let path = dir.write(
        "curve.xlsx",
        xlsx(&[("Sheet1", eplexor_rows(&points, false))]),
    );
    let table = rollfit_io::table::read_sheet(&path, 0.5, None, Some("sheet1")).unwrap();
    // Sorted up in frequency (the sweep ran down), rows of the sheet kept.
    assert_eq!(table.omega.len(), points.len());
    assert_eq!(table.lines.first(), Some(&(5 + points.len())));
    for (k, &(_, f, s, l)) in points.iter().rev().enumerate() {
        assert!(relative(table.omega[k], 2.0 * PI * f) < 1e-15);
        assert!(relative(table.storage[k], s * 1e6) < 1e-15);
        assert!(relative(table.loss[k], l * 1e6) < 1e-15);
    }
    assert!(
        table
            .notes
            .iter()
            .any(|n| n.contains("all points at 25 °C")),
        "{:?}",
        table.notes
    );
}

// ---------------------------------------------------------------- dialects

/// The comma file of two isotherms and the same points as a lab's
/// spreadsheet writes them: `;` with decimal commas, tabs, a title line
/// above the header, a units row below it, CRLF line ends. Each reads to the comma file's points; lines stay the file's own.
#[test]
fn dma_csv_in_every_dialect_reads_the_same_points() {
    let dir = TempDir::new("dialects");
    let points = reference_points();
    let rows = |sep: &str, comma: bool| -> String {
        let mut text = String::new();
        for t in [20.0, 30.0] {
            for &(w, s, l) in &points {
                let cells = [w / (2.0 * PI), s, l, t].map(|v| {
                    let v = format!("{v:e}");
                    if comma { v.replace('.', ",") } else { v }
                });
                text.push_str(&cells.join(sep));
                text.push('\n');
            }
        }
        text
    };
    let comma = format!("f,E_storage,E_loss,T\n{}", rows(",", false));
    let reference =
        DmaData::read(&dir.write("comma.csv", &comma), 0.5, &DmaOptions::default()).unwrap();
    let variants = [
        (
            "semicolon.csv",
            format!("f;E_storage;E_loss;T\n{}", rows(";", true)),
            0,
            "`;`",
        ),
        (
            "tab.txt",
            format!("f\tE_storage\tE_loss\tT\n{}", rows("\t", false)),
            0,
            "tabs",
        ),
        (
            "title.csv",
            format!(
                "DMA export, sample A-1\nf;E_storage;E_loss;T\n{}",
                rows(";", true)
            ),
            1,
            "header on line 2; the 1 line above it (titles) ignored",
        ),
        (
            "units.csv",
            format!(
                "Eplexor export\n\nf;E';E'';T\n[Hz];[Pa];[Pa];[°C]\n{}",
                rows(";", true)
            ),
            3,
            "header on line 3",
        ),
        ("crlf.csv", comma.replace('\n', "\r\n"), 0, ""),
    ];
    for (name, text, shift, note) in variants {
        let path = dir.write(name, &text);
        let data = DmaData::read(&path, 0.5, &DmaOptions::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(data.points.len(), reference.points.len(), "{name}");
        for (p, q) in data.points.iter().zip(&reference.points) {
            assert!(relative(p.omega, q.omega) < 1e-15, "{name}: {p:?} vs {q:?}");
            assert!(relative(p.storage, q.storage) < 1e-15, "{name}: {p:?}");
            assert!(relative(p.loss, q.loss) < 1e-15, "{name}: {p:?}");
            assert_eq!(p.temperature, q.temperature, "{name}");
        }
        let lines: Vec<usize> = reference.lines.iter().map(|l| l + shift).collect();
        assert_eq!(data.lines, lines, "{name}");
        assert_eq!(data.temperatures(), [20.0, 30.0], "{name}");
        assert!(
            data.notes.iter().any(|n| n.contains(note)) || note.is_empty() && data.notes.is_empty(),
            "{name}: {:?}",
            data.notes
        );
    }
}

/// What the dialect cannot decide is refused at its line: decimal commas
/// in a comma-separated file (a field count off), a thousands separator.
#[test]
fn dma_csv_dialects_it_cannot_decide_are_refused_at_their_line() {
    let dir = TempDir::new("undecided");
    let path = dir.write("commas.csv", "f,E_storage,E_loss,T\n1,5,2,3e6,1e5,20\n");
    let text = error_text(DmaData::read(&path, 0.5, &DmaOptions::default()));
    assert_contains(
        &text,
        &["commas.csv, line 2: 6 fields, but the header has 4 columns"],
    );
    let path = dir.write(
        "thousands.csv",
        "# export\nf;E_storage;E_loss;T\n1;2,3e6;1e5;20\n1,5;1.234,5;1e5;20\n",
    );
    let text = error_text(DmaData::read(&path, 0.5, &DmaOptions::default()));
    assert_contains(
        &text,
        &["thousands.csv, line 4: column 2 (E_storage): \"1.234,5\" is not a number"],
    );
}

/// A step column groups what the temperatures alone would join: two
/// sweeps at 20.0 and 20.6 °C, one isotherm by their 0.6 K gap, two by
/// their `Segment`; a workbook's `Set` alike.
#[test]
fn a_step_column_groups_the_isotherms() {
    let dir = TempDir::new("steps");
    let rows = "1,2e6,2e5,20.0,A\n10,3e6,3e5,20.1,A\n1,2.1e6,2e5,20.6,B\n10,3.1e6,3e5,20.5,B\n";
    let plain = dir.write("plain.csv", format!("f,E_storage,E_loss,T,label\n{rows}"));
    let data = DmaData::read(&plain, 0.5, &DmaOptions::default()).unwrap();
    assert_eq!(data.steps, None);
    assert_eq!(data.temperatures().len(), 1);
    let stepped = dir.write(
        "stepped.csv",
        format!("f,E_storage,E_loss,T,Segment\n{rows}"),
    );
    let data = DmaData::read(&stepped, 0.5, &DmaOptions::default()).unwrap();
    assert_eq!(data.steps.as_deref(), Some(&[0, 0, 1, 1][..]));
    let grouping = data.grouping();
    assert_eq!(grouping.isotherms.len(), 2);
    assert_eq!(grouping.isotherms[1].points, [2, 3]);
    assert!((grouping.isotherms[1].temperature - 20.55).abs() < 1e-12);
    let book = xlsx(&[(
        "Data",
        vec![
            texts(&["Set", "f", "E'", "E''", "T"]),
            vec![X::N(1.0), X::N(1.0), X::N(2e6), X::N(2e5), X::N(20.0)],
            vec![X::N(2.0), X::N(1.0), X::N(2e6), X::N(2e5), X::N(20.6)],
        ],
    )]);
    let path = dir.write("sets.xlsx", book);
    let data = DmaData::read(&path, 0.5, &DmaOptions::default()).unwrap();
    assert_eq!(data.temperatures().len(), 2);
}

/// A stress-relaxation CSV in the shared dialect: `;` with decimal commas
/// under a title line reads to the comma file's points, at its own lines.
#[test]
fn relaxation_csv_in_the_semicolon_dialect_reads_the_same_points() {
    use rollfit_io::dma::relaxation::{RelaxationData, is_relaxation};
    let dir = TempDir::new("relaxation-dialect");
    let comma = "t_s,E_relax_MPa,T\n0.1,12.5,20\n1,10.25,20\n10,8.5,20\n";
    let semicolon = format!(
        "Relaxation test, sample B\n{}",
        comma.replace(',', ";").replace('.', ",")
    );
    assert!(is_relaxation(&semicolon));
    let a = RelaxationData::read(&dir.write("comma.csv", comma), 0.5).unwrap();
    let b = RelaxationData::read(&dir.write("semicolon.csv", &semicolon), 0.5).unwrap();
    assert_eq!(a.points, b.points);
    assert_eq!(b.lines, [3, 4, 5]);
}

/// a DMA workbook's spreadsheet error is skipped with a
/// warning naming the cell and the error; a formula the file saved no
/// result for is refused, naming the cell and the formula.
#[test]
fn workbook_error_cells_are_named_and_formulas_without_results_refused() {
    use X::*;
    let dir = TempDir::new("error-cells");
    let header = || texts(&["f [Hz]", "E' [MPa]", "E'' [MPa]"]);
    let book = xlsx(&[(
        "DMA",
        vec![
            header(),
            vec![N(1.0), N(2.0), N(0.2)],
            vec![N(2.0), Error, N(0.3)],
            vec![N(5.0), N(2.5), N(0.4)],
        ],
    )]);
    let path = dir.write("errors.xlsx", &book);
    let data = DmaData::read(&path, 0.5, &DmaOptions::default()).unwrap();
    assert_eq!(data.points.len(), 2);
    let warnings = data.warnings.join("\n");
    assert!(
        warnings.contains(
            "; the first error: sheet \"DMA\", cell B3: column B (E' [MPa]): the cell holds the \
             Excel error #DIV/0!"
        ),
        "{warnings}"
    );
    let book = xlsx(&[(
        "DMA",
        vec![
            header(),
            vec![N(1.0), N(2.0), N(0.2)],
            vec![N(2.0), N(2.2), F("B2*1.1")],
        ],
    )]);
    let path = dir.write("formula.xlsx", &book);
    let m = error_text(DmaData::read(&path, 0.5, &DmaOptions::default()));
    assert!(
        m.contains(
            "formula.xlsx, sheet \"DMA\", cell C3: column C (E'' [MPa]): the cell holds a formula (=B2*1.1) \
             the file saved no result for; open it in Excel or LibreOffice and save, so its value \
             is stored"
        ),
        "{m}"
    );
}

/// One units table for every reader: the same temperatures written in °F
/// read as in °C, in a TRIOS export and in a relaxation file (whose own
/// table, before the one table, had no °F).
#[test]
fn fahrenheit_reads_the_same_in_trios_and_relaxation_files() {
    let dir = TempDir::new("fahrenheit");
    let fahrenheit = |c: f64| format!("{}", c * 9.0 / 5.0 + 32.0);

    // TRIOS: the Temperature variable of every step in °F.
    let celsius = fs::read_to_string(fixture("trios_tensile.txt")).unwrap();
    let mut in_data = false;
    let lines: Vec<String> = celsius
        .lines()
        .map(|line| {
            if line.starts_with("Units\t°C") {
                in_data = true;
                return line.replacen("°C", "°F", 1);
            }
            let mut cells: Vec<String> = line.split('\t').map(str::to_string).collect();
            match cells.get(1).map(|t| t.parse::<f64>()) {
                Some(Ok(t)) if in_data && cells[0] == "Data point" => {
                    cells[1] = fahrenheit(t);
                    cells.join("\t")
                }
                _ => line.to_string(),
            }
        })
        .collect();
    let path = dir.path().join("trios_F.txt");
    fs::write(&path, lines.join("\n") + "\n").unwrap();
    let options = DmaOptions::default();
    let expected = DmaData::read(&fixture("trios_tensile.txt"), 0.5, &options).unwrap();
    let read = DmaData::read(&path, 0.5, &options).unwrap();
    assert_eq!(read.points.len(), expected.points.len());
    for (p, q) in read.points.iter().zip(&expected.points) {
        assert!((p.temperature.unwrap() - q.temperature.unwrap()).abs() < 1e-9);
        assert_eq!((p.omega, p.storage, p.loss), (q.omega, q.storage, q.loss));
    }

    // A relaxation file with `T [°F]`.
    let rows = [(1.0, 2e7, 20.0), (10.0, 1e7, 20.0), (1.0, 5e6, 40.0)];
    let write = |name: &str, header: &str, t: &dyn Fn(f64) -> String| {
        let body: Vec<String> = rows
            .iter()
            .map(|(time, e, c)| format!("{time},{e},{}", t(*c)))
            .collect();
        let path = dir.path().join(name);
        fs::write(&path, format!("{header}\n{}\n", body.join("\n"))).unwrap();
        rollfit_io::dma::relaxation::RelaxationData::read(&path, 0.5).unwrap()
    };
    let celsius = write("relax_C.csv", "t,E_relax,T", &|c| c.to_string());
    let read = write("relax_F.csv", "t,E_relax,T [°F]", &fahrenheit);
    for (p, q) in read.points.iter().zip(&celsius.points) {
        assert!((p.temperature.unwrap() - q.temperature.unwrap()).abs() < 1e-9);
        assert_eq!((p.time, p.value), (q.time, q.value));
    }
}
