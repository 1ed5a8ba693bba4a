//! Workbooks are written here, in the tests, with the zip crate
//! (rollfit-testkit's `workbook`, shared with the DMA and command-line
//! tests): the few XML parts calamine needs, no binary fixtures.

use std::path::PathBuf;

use super::*;
use crate::chain;
use crate::data::{read, read_sheet};
use crate::error::column_letter;

use rollfit_testkit::workbook::{X, ods, xlsx};

/// A fresh temporary folder for one test.
fn temp_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rollfit-data-file-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

fn two_runs() -> Vec<u8> {
    use X::*;
    xlsx(&[
        (
            "Run 1",
            vec![
                vec![S("Measurement 2024-03-01")],
                vec![],
                vec![S("velocity (mm/s)"), S("COF"), S("COF std"), S("T (°C)")],
                vec![N(0.5), N(0.05), N(0.001), N(20.0)],
                vec![S("1,5"), S("0.06"), N(0.001), N(20.0)],
                vec![N(2.5), Error, N(0.001), N(20.0)],
                vec![N(3.5), E, N(0.001), N(20.0)],
                vec![N(4.5), N(0.08), N(0.001), N(20.0)],
            ],
        ),
        (
            "Run 2",
            vec![
                vec![S("v"), S("mu"), S("T_K")],
                vec![N(1e-3), N(0.1), N(293.15)],
                vec![N(1e-2), N(0.2), N(313.15)],
            ],
        ),
    ])
}

#[test]
fn xlsx_first_sheet_by_default() {
    let dir = temp_dir("first-sheet");
    let path = write(&dir, "runs.xlsx", &two_runs());
    let t = read(&path).unwrap();
    assert_eq!(t.speeds, [0.5e-3, 1.5e-3, 4.5e-3]);
    assert_eq!(t.friction, [0.05, 0.06, 0.08]);
    assert_eq!(t.sigma, Some(vec![0.001; 3]));
    assert_eq!(t.temperature, Some(vec![20.0; 3]));
    assert_eq!(t.lines, [4, 5, 8]);
    assert_eq!(
        t.notes,
        [
            "sheet \"Run 1\", the first of 2 (\"Run 1\", \"Run 2\"); choose another with --sheet",
            "header on sheet \"Run 1\", row 3; the 1 row above it (titles) ignored",
            "decimal commas read as decimal points",
            "column \"velocity (mm/s)\" read as v in mm/s, converted to m/s (×1e-3)",
            "column \"COF\" read as mu",
            "column \"COF std\" read as sigma",
            "column \"T (°C)\" read as T in °C",
        ]
    );
    assert_eq!(
        t.warnings,
        [
            "skipped 2 rows with empty or NaN cells in mu: sheet \"Run 1\", rows 6, 7; the first \
             error: sheet \"Run 1\", cell B6: column `COF` (mu): the cell holds the Excel error #DIV/0!"
        ]
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn xlsx_sheet_by_name_and_unknown_sheet() {
    let dir = temp_dir("by-name");
    let path = write(&dir, "runs.XLSX", &two_runs());
    for name in ["Run 2", "run 2"] {
        let t = read_sheet(&path, Some(name)).unwrap();
        assert_eq!(t.speeds, [1e-3, 1e-2]);
        assert_eq!(t.temperature, Some(vec![20.0, 40.0]));
        assert_eq!(t.lines, [2, 3]);
    }
    let m = chain(&read_sheet(&path, Some("Run 3")).unwrap_err());
    assert!(
        m.contains("runs.XLSX: no sheet \"Run 3\": the workbook has \"Run 1\", \"Run 2\""),
        "{m}"
    );
    // --sheet with a text file.
    let csv = write(&dir, "plain.csv", b"v,mu\n1,0.1\n");
    let m = chain(&read_sheet(&csv, Some("Run 1")).unwrap_err());
    assert!(
        m.contains("plain.csv") && m.contains("not a workbook"),
        "{m}"
    );
    // A workbook saved under a .csv name is read by its content.
    let disguised = write(&dir, "runs.csv", &two_runs());
    let t = read(&disguised).unwrap();
    assert_eq!(t.speeds.len(), 3);
    assert!(t.notes[0].contains("by its content"), "{:?}", t.notes);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn xlsx_errors_name_the_sheet_and_the_cell() {
    use X::*;
    let dir = temp_dir("errors");
    let bad = xlsx(&[(
        "Run 1",
        vec![
            vec![S("Speed (m/s)"), S("COF")],
            vec![N(1.0), N(0.1)],
            vec![N(2.0), N(0.1)],
            vec![N(3.0), N(0.1)],
            vec![N(4.0), N(0.1)],
            vec![N(5.0), N(0.1)],
            vec![N(6.0), S("abc")],
        ],
    )]);
    let path = write(&dir, "bad.xlsx", &bad);
    let m = chain(&read(&path).unwrap_err());
    assert!(
        m.contains("data file ")
            && m.contains(
                "bad.xlsx: sheet \"Run 1\", cell B7: column `COF` (mu): \"abc\" is not a number"
            ),
        "{m}"
    );
    let negative = xlsx(&[("S", vec![vec![S("v"), S("mu")], vec![N(-1.0), N(0.1)]])]);
    let path = write(&dir, "negative.xlsx", &negative);
    let m = chain(&read(&path).unwrap_err());
    assert!(
        m.contains("sheet \"S\", cell A2: column `v` = -1: must be greater than zero"),
        "{m}"
    );
    let missing = xlsx(&[(
        "Run 1",
        vec![vec![S("Speed"), S("Force (N)")], vec![N(1.0), N(2.0)]],
    )]);
    let path = write(&dir, "missing.xlsx", &missing);
    let m = chain(&read(&path).unwrap_err());
    assert!(
        m.contains(
            "sheet \"Run 1\", row 1 (header): no friction column (mu, µ, COF, friction \
             coefficient, coefficient of friction, …); found \"Speed\", \"Force (N)\""
        ),
        "{m}"
    );
    let dates = xlsx(&[("S", vec![vec![S("v"), S("mu"), S("v_mm_s")]])]);
    let path = write(&dir, "two.xlsx", &dates);
    let m = chain(&read(&path).unwrap_err());
    assert!(
        m.contains("two speed columns, \"v\" (column A) and \"v_mm_s\" (column C)"),
        "{m}"
    );
    let path = write(&dir, "empty.xlsx", &xlsx(&[("Empty", vec![])]));
    let m = chain(&read(&path).unwrap_err());
    assert!(m.contains("sheet \"Empty\" is empty"), "{m}");
    let path = write(&dir, "broken.xlsx", b"PK\x03\x04 not really a zip");
    let m = chain(&read(&path).unwrap_err());
    assert!(
        m.contains("broken.xlsx: cannot read the file as a workbook"),
        "{m}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn ods_workbook() {
    use X::*;
    let dir = temp_dir("ods");
    let book = ods(
        "Messung",
        vec![
            vec![S("Geschwindigkeit"), S("speed_um_s"), S("µ")],
            vec![S("x"), N(250.0), N(0.125)],
            vec![S("y"), S("2,5E+02"), S("0,25")],
        ],
    );
    let path = write(&dir, "messung.ods", &book);
    let t = read(&path).unwrap();
    assert_eq!(t.speeds, [2.5e-4, 2.5e-4]);
    assert_eq!(t.friction, [0.125, 0.25]);
    assert!(
        t.notes
            .iter()
            .any(|n| n == "column \"speed_um_s\" read as v in µm/s, converted to m/s (×1e-6)"),
        "{:?}",
        t.notes
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn column_letters() {
    let letters: Vec<String> = [0, 1, 25, 26, 27, 51, 52, 701, 702]
        .into_iter()
        .map(column_letter)
        .collect();
    assert_eq!(
        letters,
        ["A", "B", "Z", "AA", "AB", "AZ", "BA", "ZZ", "AAA"]
    );
}

/// A formula whose result the file does not hold is a
/// value the user means: refused, naming the cell and the formula, not
/// skipped as an empty cell.
#[test]
fn a_formula_without_a_saved_result_is_refused_naming_it() {
    use X::*;
    let dir = temp_dir("formula");
    let book = xlsx(&[(
        "Data",
        vec![
            vec![S("v"), S("mu")],
            vec![N(1e-3), N(0.05)],
            vec![N(2e-3), F("A2/B2")],
        ],
    )]);
    let path = write(&dir, "formula.xlsx", &book);
    let m = chain(&read(&path).unwrap_err());
    assert!(
        m.contains(
            "sheet \"Data\", cell B3: column `mu`: the cell holds a formula (=A2/B2) the file saved \
             no result for; open it in Excel or LibreOffice and save, so its value is stored"
        ),
        "{m}"
    );
    std::fs::remove_dir_all(dir).unwrap();
}
