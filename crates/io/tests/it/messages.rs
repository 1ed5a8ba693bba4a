//! The io crate's message corpus: every reader (scenes, manifests,
//! measured data as text and as a workbook, modulus tables, DMA CSV files,
//! TRIOS exports, relaxation files, fit folders) given a fixed family of
//! small bad inputs, each made from a valid file by one edit: a line
//! deleted, a number replaced by an odd value, a word replaced, the file
//! cut short, a byte that is not text, a workbook cell spoilt. What each
//! reader says, as the command line prints it ([`rollfit_io::chain`]), is
//! compared with tests/data/messages/io.tsv, so that a change of the error
//! layer that alters one character a user reads is seen, with the input
//! and both texts. `ROLLFIT_MESSAGE_CORPUS=write` records the file anew.
//!
//! The file stores each distinct text once, with the inputs that give it:
//! `ids \t text`, the text with `\`, tab and line breaks escaped, the
//! test's folder written `<dir>`.

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};

use rollfit_io::dma::relaxation::RelaxationData;
use rollfit_io::dma::{DmaData, DmaOptions};
use rollfit_io::{FitDir, chain, data, manifest, scene, table};

use rollfit_testkit::workbook::{self, X};

/// Values a number is replaced by.
const ODD_VALUES: &[&str] = &["nan", "-1", "0", "1e400", "x", "", "1e-320", "2e13"];

/// A reader: the file's name in the test's folder and what reading it
/// says (`None`: read).
type Reader = fn(&Path) -> Option<String>;

fn said<T, E: std::error::Error>(result: Result<T, E>) -> Option<String> {
    result.err().map(|e| chain(&e))
}

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Spans of number-like text holding a digit.
fn number_spans(text: &str) -> Vec<(usize, usize)> {
    let bytes = text.as_bytes();
    let numeric = |b: u8| b.is_ascii_digit() || matches!(b, b'.' | b'e' | b'E' | b'+' | b'-');
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if numeric(bytes[i]) && (i == 0 || !bytes[i - 1].is_ascii_alphabetic()) {
            let start = i;
            while i < bytes.len() && numeric(bytes[i]) {
                i += 1;
            }
            if bytes[start..i].iter().any(u8::is_ascii_digit) {
                spans.push((start, i));
            }
        } else {
            i += 1;
        }
    }
    spans
}

/// Spans of identifier-like words starting with a letter.
fn word_spans(text: &str) -> Vec<(usize, usize)> {
    let bytes = text.as_bytes();
    let mut spans = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i].is_ascii_alphabetic() {
            let start = i;
            while i < bytes.len() && (bytes[i].is_ascii_alphanumeric() || bytes[i] == b'_') {
                i += 1;
            }
            spans.push((start, i));
        } else {
            i += 1;
        }
    }
    spans
}

/// At most `n` items of `all`, spread evenly.
fn spread<T: Copy>(all: &[T], n: usize) -> Vec<(usize, T)> {
    if all.len() <= n {
        return all.iter().copied().enumerate().collect();
    }
    (0..n)
        .map(|k| {
            let i = k * all.len() / n;
            (i, all[i])
        })
        .collect()
}

/// The one-edit variants of `text`: (edit id, bytes).
fn variants(text: &str) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    let lines: Vec<&str> = text.split_inclusive('\n').collect();
    for (i, _) in spread(&lines, 40) {
        let mut kept = lines.clone();
        kept.remove(i);
        out.push((format!("line{}-deleted", i + 1), kept.concat().into_bytes()));
    }
    for (i, (a, b)) in spread(&number_spans(text), 30) {
        for (k, value) in ODD_VALUES.iter().enumerate() {
            let edited = format!("{}{value}{}", &text[..a], &text[b..]);
            out.push((format!("number{i}-odd{k}"), edited.into_bytes()));
        }
    }
    for (i, (a, b)) in spread(&word_spans(text), 30) {
        let edited = format!("{}foo{}", &text[..a], &text[b..]);
        out.push((format!("word{i}-foo"), edited.into_bytes()));
    }
    for k in 0..6 {
        let at = text.len() * k / 6;
        let cut = text.as_bytes()[..at].to_vec();
        out.push((format!("cut{k}"), cut));
        let mut bad = text.as_bytes().to_vec();
        bad.insert(at, 0xFF);
        out.push((format!("byte{k}"), bad));
    }
    out
}

/// What each input of a family says: input id → text.
fn family(
    dir: &Path,
    name: &str,
    file: &str,
    base: &str,
    read: Reader,
    said_by: &mut BTreeMap<String, String>,
) {
    let path = dir.join(file);
    for (edit, bytes) in variants(base) {
        fs::write(&path, &bytes).unwrap();
        if let Some(text) = read(&path) {
            said_by.insert(format!("{name}:{edit}"), text);
        }
    }
}

fn read_scene(path: &Path) -> Option<String> {
    said(scene::load(path))
}

fn read_manifest(path: &Path) -> Option<String> {
    said(manifest::load(path))
}

fn read_data(path: &Path) -> Option<String> {
    said(data::read(path).and_then(|table| table.measurements()))
}

fn read_table(path: &Path) -> Option<String> {
    said(table::read(path, 0.5, None))
}

fn read_dma(path: &Path) -> Option<String> {
    said(DmaData::read(path, 0.5, &DmaOptions::default()))
}

fn read_relaxation(path: &Path) -> Option<String> {
    said(RelaxationData::read(path, 0.5))
}

fn read_fit_dir(path: &Path) -> Option<String> {
    said(FitDir::read(path.parent().unwrap()))
}

/// A relaxation file: three isotherms of a modulus falling 0.35 decades
/// per decade of time.
fn relaxation_text() -> String {
    let mut text = String::from("t_s,E_relax,T\n");
    for (j, t) in [0.0, 10.0, 20.0].iter().enumerate() {
        for k in 0..=6 {
            let time = 10f64.powf(k as f64 / 2.0);
            let reduced = time * 10f64.powf(1.5 * j as f64);
            text += &format!("{time:e},{:e},{t}\n", 1e8 * reduced.powf(-0.35) + 1e6);
        }
    }
    text
}

/// A plain modulus table: a Zener solid at eight frequencies.
fn table_text() -> String {
    let mut text = String::from("omega,E_storage,E_loss\n");
    for k in 0..8 {
        let omega = 10f64.powi(k - 3);
        let x = omega * 1e-2;
        let storage = 2e6 + 2e9 * x * x / (1.0 + x * x);
        let loss = 2e9 * x / (1.0 + x * x);
        text += &format!("{omega:e},{storage:e},{loss:e}\n");
    }
    text
}

/// The CSV text as a one-sheet workbook's rows (comment lines dropped).
fn sheet_rows(csv: &str) -> Vec<Vec<X<'_>>> {
    let mut lines = csv.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let mut rows = vec![workbook::texts(&header)];
    for line in lines {
        rows.push(
            line.split(',')
                .map(|cell| cell.trim().parse::<f64>().map_or(X::S(cell), X::N))
                .collect(),
        );
    }
    rows
}

/// Workbooks of `csv` with one cell of the first rows spoilt, read by
/// `read`.
fn workbook_family(
    dir: &Path,
    name: &str,
    csv: &str,
    read: Reader,
    said_by: &mut BTreeMap<String, String>,
) {
    let path = dir.join(format!("{name}.xlsx"));
    let rows = sheet_rows(csv);
    let spoilt = [X::Error, X::F("A2*2"), X::S("n/a"), X::E, X::N(-1.0)];
    for r in 0..rows.len().min(4) {
        for c in 0..rows[r].len() {
            for (k, cell) in spoilt.iter().enumerate() {
                let mut edited = rows.clone();
                edited[r][c] = *cell;
                fs::write(&path, workbook::xlsx(&[("Data", edited)])).unwrap();
                if let Some(text) = read(&path) {
                    said_by.insert(format!("{name}:row{r}-col{c}-cell{k}"), text);
                }
            }
        }
    }
}

fn escape(text: &str) -> String {
    text.replace('\\', "\\\\")
        .replace('\t', "\\t")
        .replace('\n', "\\n")
        .replace('\r', "\\r")
}

#[test]
fn every_reader_says_what_it_said() {
    let dir = std::env::temp_dir().join(format!("rollfit-io-messages-{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    let read = |name: &str| fs::read_to_string(repo().join(name)).unwrap();
    let mut said_by = BTreeMap::new();
    for name in [
        "example-sphere",
        "hn-rubber",
        "hn-rubber-tset",
        "lab-ball",
        "paper-fig2-cylinder",
        "hn-rubber-joint",
    ] {
        let text = read(&format!("data/{name}.toml"));
        let label = format!("scene-{name}");
        family(&dir, &label, "scene.toml", &text, read_scene, &mut said_by);
    }
    let batch = read("data/example-batch.toml");
    family(
        &dir,
        "manifest",
        "manifest.toml",
        &batch,
        read_manifest,
        &mut said_by,
    );
    let measured = read("data/hn-rubber.csv");
    family(&dir, "data", "data.csv", &measured, read_data, &mut said_by);
    let tset = read("data/hn-rubber-tset.csv");
    family(
        &dir,
        "data-tset",
        "data.csv",
        &tset,
        read_data,
        &mut said_by,
    );
    family(
        &dir,
        "table",
        "table.csv",
        &table_text(),
        read_table,
        &mut said_by,
    );
    let dma = read("data/hn-rubber-dma.csv");
    family(&dir, "dma", "dma.csv", &dma, read_dma, &mut said_by);
    let isotherms = read("data/hn-rubber-dma-isotherms.csv");
    family(
        &dir,
        "dma-iso",
        "dma.csv",
        &isotherms,
        read_dma,
        &mut said_by,
    );
    for name in ["trios_tensile", "trios_shear_two_steps"] {
        let text = read(&format!("crates/io/tests/fixtures/{name}.txt"));
        family(&dir, name, "trios.txt", &text, read_dma, &mut said_by);
    }
    let relaxation = relaxation_text();
    family(
        &dir,
        "relaxation",
        "relax.csv",
        &relaxation,
        read_relaxation,
        &mut said_by,
    );
    workbook_family(&dir, "data-xlsx", &measured, read_data, &mut said_by);
    workbook_family(&dir, "dma-xlsx", &dma, read_dma, &mut said_by);
    let fit = dir.join("fit");
    fs::create_dir_all(&fit).unwrap();
    for file in ["fit.json", "mu.csv", "modulus.csv"] {
        for other in ["fit.json", "mu.csv", "modulus.csv"] {
            let original = repo().join("examples/fits/hn-rubber").join(other);
            fs::copy(original, fit.join(other)).unwrap();
        }
        let text = read(&format!("examples/fits/hn-rubber/{file}"));
        let label = format!("fit-{file}");
        family(&fit, &label, file, &text, read_fit_dir, &mut said_by);
    }
    let _ = fs::remove_dir_all(&dir);

    let shown = dir.display().to_string();
    let mut by_text: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for (id, text) in &said_by {
        let text = escape(&text.replace(&shown, "<dir>"));
        by_text.entry(text).or_default().push(id.clone());
    }
    let corpus: String = by_text
        .iter()
        .map(|(text, ids)| format!("{}\t{text}\n", ids.join(",")))
        .collect();
    let path = repo().join("tests/data/messages/io.tsv");
    if std::env::var("ROLLFIT_MESSAGE_CORPUS").as_deref() == Ok("write") {
        fs::write(&path, &corpus).unwrap();
        return;
    }
    let recorded = fs::read_to_string(&path).unwrap_or_else(|e| {
        panic!(
            "cannot read the message corpus {}: {e} (ROLLFIT_MESSAGE_CORPUS=write records it)",
            path.display()
        )
    });
    let mut was: BTreeMap<&str, &str> = BTreeMap::new();
    for line in recorded.lines() {
        let (ids, text) = line.split_once('\t').expect("ids, a tab and the text");
        for id in ids.split(',') {
            was.insert(id, text);
        }
    }
    let mut now: BTreeMap<&str, &str> = BTreeMap::new();
    for line in corpus.lines() {
        let (ids, text) = line.split_once('\t').unwrap();
        for id in ids.split(',') {
            now.insert(id, text);
        }
    }
    let mut differences = Vec::new();
    for (id, text) in &now {
        match was.get(id) {
            Some(old) if old == text => {}
            Some(old) => differences.push(format!("{id}: recorded\n  {old}\nnow\n  {text}")),
            None => differences.push(format!("{id}: not in the corpus; now\n  {text}")),
        }
    }
    for (id, old) in &was {
        if !now.contains_key(id) {
            differences.push(format!(
                "{id}: recorded\n  {old}\nnow read without an error"
            ));
        }
    }
    assert!(
        differences.is_empty(),
        "{} of {} inputs say something else than recorded in {}:\n{}",
        differences.len(),
        was.len().max(now.len()),
        path.display(),
        differences.join("\n")
    );
}
