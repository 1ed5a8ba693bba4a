//! Structured fuzzing of every input kind of the `rollfit` binary:
//! scenes (through `forward` and `fit`), data files, batch manifests,
//! DMA CSV files (`,`, or `;` with decimal commas) and TRIOS exports
//! (through `compare`), temperature ramps (through `master`), fit folders
//! (through `report` and `compare`), each mutated from a valid file by a
//! seeded sequence of structured edits (numbers replaced by extreme or
//! malformed values, lines deleted, duplicated, swapped or inserted,
//! delimiters changed, the file cut short, bytes flipped); inputs that are no ordinary file (a link to /dev/zero, a sparse 2 GiB
//! file) and workbooks of the data and DMA files with cells made Excel
//! errors, formulas without a saved result, text or empty; mutated scenes and data given through a pipe or the standard input,
//! and output folders shared between commands (a fit's or a master's
//! folder, holding a user's photo and, at times, a spoilt record, written
//! again by fit, master, batch, report or compare, with or without
//! `--force`): the photo is never touched, and another command's folder is
//! refused without `--force`; master curves asked for at a T_ref near the shift law's singular
//! temperature, workbooks with a stray cell far from the data (a sheet
//! extent of up to 1.7e10 cells) and relaxation files with extreme times.
//!
//! Every case must keep the promises of docs/ARCHITECTURE.md, "Contract",
//! which for bad input means:
//! - no panic, and no run longer than a minute;
//! - exit 0 only with finite outputs (every number in the written CSV and
//!   JSON files finite, fit.json readable);
//! - a non-zero exit leaves the output (file or folder) exactly as it was
//!   (for a batch, the entries' folders are each complete or untouched);
//! - every error message names a file: the input it blames or the output.
//!
//! `FUZZ_CASES=N` runs N cases (default 2100), `FUZZ_SEED=S` another seed
//! (default 14); a failure prints the case's seed and kind, and
//! `FUZZ_KEEP=1` keeps the cases' folders under the system's temporary
//! folder for a look.
//!
//! At the default seed and case count, every case's exit code and standard
//! error are compared with the message corpus
//! tests/data/messages/fuzz.tsv (`ROLLFIT_MESSAGE_CORPUS=write` records
//! it anew): what a user reads changes only where a change means it to.

use crate::{common, messages};
use rollfit_testkit::workbook;

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use common::{TempDir, copy_tree, small_scene, snapshot};

const MANIFEST: &str = r#"[defaults]
seed = 1

[[entry]]
name = "a"
scene = "scene.toml"
data = "data.csv"

[[entry]]
name = "b"
scene = "scene.toml"
data = "data.csv"
seed = 2
"#;

/// The input kinds and the command each is fed to.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    /// A scene through `forward -o out.csv`.
    SceneForward,
    /// A scene through `fit` into a folder holding a previous result.
    SceneFit,
    /// A data file through `fit` into a folder holding a previous result.
    Data,
    /// A manifest through `batch`.
    Manifest,
    /// A DMA CSV through `compare` of the previous result.
    DmaCsv,
    /// A TRIOS export through `compare`.
    Trios,
    /// A fit folder's file through `report`.
    FitFolderReport,
    /// A fit folder's file through `compare`.
    FitFolderCompare,
    /// A DMA CSV with `;` and decimal commas through `compare`.
    DmaSemicolon,
    /// A temperature ramp through `master`.
    DmaRamp,
    /// Data or DMA file without a size: a link to /dev/zero or
    /// a sparse 2 GiB file; refused before it is read.
    Unsized,
    /// A mutated scene or data file through a pipe (a FIFO with a writer)
    /// or the standard input (`-`), through `fit`.
    Piped,
    /// A fit's or a master's folder holding a user's photo, written again
    /// by another or the same command.
    SharedFolder,
    /// A workbook of the measured data (through `fit`) or of the DMA file
    /// (through `compare`) with some cells made Excel errors, formulas
    /// without a saved result, text or empty.
    Workbook,
    /// DMA isotherms through `master` with a T_ref near the singular
    /// temperature of WLF (−81.6 °C for these data) or Arrhenius (absolute
    /// zero), under a random shift law.
    TRefSingular,
    /// A workbook of the measured data (through `fit`) or of the DMA file
    /// (through `compare`) with one stray cell far below and right of the
    /// data.
    StrayCell,
    /// A relaxation file through `master` with times made extreme (1e±300
    /// s, just outside or inside the accepted range).
    ExtremeTimes,
}

/// How many of every 100 cases are of each kind: the fits are the slow
/// ones.
const MIX: [(Kind, usize); 17] = [
    (Kind::SceneForward, 11),
    (Kind::Unsized, 3),
    (Kind::Piped, 3),
    (Kind::SharedFolder, 3),
    (Kind::SceneFit, 7),
    (Kind::Data, 11),
    (Kind::TRefSingular, 2),
    (Kind::StrayCell, 2),
    (Kind::ExtremeTimes, 2),
    (Kind::Manifest, 4),
    (Kind::DmaCsv, 10),
    (Kind::Trios, 11),
    (Kind::FitFolderReport, 8),
    (Kind::FitFolderCompare, 11),
    (Kind::Workbook, 4),
    (Kind::DmaSemicolon, 5),
    (Kind::DmaRamp, 3),
];

fn kind_of(i: usize) -> Kind {
    let mut k = i % 100;
    for (kind, share) in MIX {
        if k < share {
            return kind;
        }
        k -= share;
    }
    unreachable!("MIX sums to 100")
}

/// Values a number is replaced by: extremes, non-numbers, malformed text.
const ODD_VALUES: &[&str] = &[
    "0",
    "-1",
    "-0",
    "1e308",
    "-1e308",
    "1e-308",
    "5e-324",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "1e300",
    "1e-300",
    "",
    "x",
    "1.2e",
    "1e",
    "99999999999999999999999",
    "0.5",
    "1e6",
    "1e-12",
    "\"s\"",
    "[1, 2]",
    "{}",
    "1,5",
    "0x10",
    "1_000",
    "true",
];

/// Lines inserted at random.
const ODD_LINES: &[&str] = &[
    "unknown = 1",
    "[unknown]",
    "x,y,z",
    "",
    "# a comment",
    "\u{feff}",
    "\"unterminated",
    "1e-3,0.01,0.001,20,5",
    ";;;",
    "\t\t",
    "Data point\t1\t2",
    "Number of points\t7",
    "[Step]",
    "}",
    "{",
    "[[entry]]",
    "name = \"a\"",
];

/// Words a key or name is replaced by.
const ODD_WORDS: &[&str] = &[
    "mu",
    "v",
    "sigma",
    "T",
    "omega",
    "f",
    "E_storage",
    "E_loss",
    "G_storage",
    "radius",
    "load",
    "sphere",
    "cylinder",
    "foo",
    "model",
    "wlf",
    "free",
    "prony",
    "table",
    "shape",
    "",
    "µ",
];

/// Spans of number-like text (digits with . e E + -) holding a digit.
fn number_spans(text: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    let numeric = |b: u8| b.is_ascii_digit() || matches!(b, b'.' | b'e' | b'E' | b'+' | b'-');
    while i < text.len() {
        if numeric(text[i]) {
            let start = i;
            while i < text.len() && numeric(text[i]) {
                i += 1;
            }
            if text[start..i].iter().any(u8::is_ascii_digit) {
                spans.push((start, i));
            }
        } else {
            i += 1;
        }
    }
    spans
}

/// Spans of identifier-like words (letters, digits, _), starting with a
/// letter.
fn word_spans(text: &[u8]) -> Vec<(usize, usize)> {
    let mut spans = Vec::new();
    let mut i = 0;
    while i < text.len() {
        if text[i].is_ascii_alphabetic() {
            let start = i;
            while i < text.len() && (text[i].is_ascii_alphanumeric() || text[i] == b'_') {
                i += 1;
            }
            spans.push((start, i));
        } else {
            i += 1;
        }
    }
    spans
}

fn splice(text: &mut Vec<u8>, (a, b): (usize, usize), with: &[u8]) {
    text.splice(a..b, with.iter().copied());
}

/// The start of every line (after each '\n').
fn line_starts(text: &[u8]) -> Vec<usize> {
    let mut starts = vec![0];
    starts.extend(
        text.iter()
            .enumerate()
            .filter(|(i, b)| **b == b'\n' && i + 1 < text.len())
            .map(|(i, _)| i + 1),
    );
    starts
}

fn line_span(text: &[u8], k: usize) -> (usize, usize) {
    let starts = line_starts(text);
    let k = k % starts.len();
    let end = starts.get(k + 1).copied().unwrap_or(text.len());
    (starts[k], end)
}

/// One to three structured edits of `text`.
fn mutate(text: &[u8], rng: &mut ChaCha8Rng) -> Vec<u8> {
    let mut out = text.to_vec();
    let edits = rng.random_range(1..=3);
    for _ in 0..edits {
        if out.is_empty() {
            out.extend_from_slice(b"x");
        }
        match rng.random_range(0..100) {
            // The most telling edit: one number becomes something odd.
            0..40 => {
                let spans = number_spans(&out);
                if !spans.is_empty() {
                    let span = spans[rng.random_range(0..spans.len())];
                    let value = ODD_VALUES[rng.random_range(0..ODD_VALUES.len())];
                    splice(&mut out, span, value.as_bytes());
                }
            }
            40..50 => {
                let spans = word_spans(&out);
                if !spans.is_empty() {
                    let span = spans[rng.random_range(0..spans.len())];
                    let word = ODD_WORDS[rng.random_range(0..ODD_WORDS.len())];
                    splice(&mut out, span, word.as_bytes());
                }
            }
            50..60 => {
                let k = rng.random_range(0..64);
                let span = line_span(&out, k);
                splice(&mut out, span, b"");
            }
            60..66 => {
                let span = line_span(&out, rng.random_range(0..64));
                let line = out[span.0..span.1].to_vec();
                splice(&mut out, (span.0, span.0), &line);
            }
            66..72 => {
                let a = line_span(&out, rng.random_range(0..64));
                let line = out[a.0..a.1].to_vec();
                splice(&mut out, a, b"");
                let b = line_span(&out, rng.random_range(0..64));
                splice(&mut out, (b.1, b.1), &line);
            }
            72..80 => {
                let at = line_span(&out, rng.random_range(0..64)).0;
                let line = ODD_LINES[rng.random_range(0..ODD_LINES.len())];
                splice(&mut out, (at, at), format!("{line}\n").as_bytes());
            }
            80..86 => {
                let (a, b) = line_span(&out, rng.random_range(0..64));
                let to = [b';', b'\t', b',', b' '][rng.random_range(0..4)];
                for byte in &mut out[a..b] {
                    if matches!(*byte, b',' | b';' | b'\t') {
                        *byte = to;
                    }
                }
            }
            86..93 => {
                let at = rng.random_range(0..out.len());
                out.truncate(at);
            }
            _ => {
                let at = rng.random_range(0..out.len());
                out[at] = rng.random();
            }
        }
    }
    out
}

/// What a run returned.
struct Run {
    code: Option<i32>,
    stderr: String,
    timed_out: bool,
}

/// Runs rollfit with `args` in `dir`, killing it after a minute.
fn run(dir: &Path, args: &[&str]) -> Run {
    run_fed(dir, args, None)
}

/// [`run`] with `stdin` written to the standard input (else none).
fn run_fed(dir: &Path, args: &[&str], stdin: Option<Vec<u8>>) -> Run {
    let mut child = Command::new(env!("CARGO_BIN_EXE_rollfit"))
        .args(args)
        .current_dir(dir)
        .stdin(if stdin.is_some() {
            Stdio::piped()
        } else {
            Stdio::null()
        })
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("cannot start the rollfit binary");
    if let (Some(bytes), Some(mut pipe)) = (stdin, child.stdin.take()) {
        // A run that stops reading early closes the pipe: not our concern.
        std::thread::spawn(move || {
            let _ = std::io::Write::write_all(&mut pipe, &bytes);
        });
    }
    let stderr = child.stderr.take().unwrap();
    let reader = std::thread::spawn(move || {
        let mut text = Vec::new();
        let mut stderr = stderr;
        let _ = std::io::Read::read_to_end(&mut stderr, &mut text);
        String::from_utf8_lossy(&text).into_owned()
    });
    let start = Instant::now();
    let mut timed_out = false;
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > Duration::from_secs(60) {
            timed_out = true;
            let _ = child.kill();
            break child.wait().unwrap();
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    Run {
        code: status.code(),
        stderr: reader.join().unwrap(),
        timed_out,
    }
}

/// The problems with the finite-output promise in the files under `path`:
/// every CSV cell that is not a number must be a header or a text column,
/// and no cell may be NaN or ±∞; every JSON file must parse.
fn non_finite_outputs(path: &Path) -> Vec<String> {
    let mut problems = Vec::new();
    for (name, bytes) in snapshot(path) {
        let shown = name.display().to_string();
        let text = String::from_utf8_lossy(&bytes);
        match name.extension().and_then(|e| e.to_str()) {
            Some("csv") => {
                for (i, line) in text.lines().enumerate() {
                    for cell in line.split(',') {
                        let lower = cell.trim().to_ascii_lowercase();
                        if matches!(lower.as_str(), "nan" | "inf" | "-inf" | "+inf" | "infinity") {
                            problems.push(format!("{shown} line {}: {cell}", i + 1));
                        }
                    }
                }
            }
            Some("json") => {
                if let Err(e) = serde_json::from_slice::<serde_json::Value>(&bytes) {
                    problems.push(format!("{shown}: not JSON: {e}"));
                }
                // A non-finite f64 is written as null by serde_json.
                for key in ["objective", "misfit", "misfit_per_point", "noise"] {
                    if text.contains(&format!("\"{key}\": null")) {
                        problems.push(format!("{shown}: {key} is null"));
                    }
                }
            }
            _ => {}
        }
    }
    problems
}

/// The fixtures every case starts from, in `root`: scene.toml, data.csv
/// (a noisy forward run), dma.csv, trios.txt, manifest.toml and base/ (a
/// complete fit of data.csv).
fn fixtures(root: &Path) {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    fs::write(root.join("scene.toml"), small_scene(8)).unwrap();
    fs::write(root.join("manifest.toml"), MANIFEST).unwrap();
    fs::copy(repo.join("data/hn-rubber-dma.csv"), root.join("dma.csv")).unwrap();
    // The same sweep as a German spreadsheet writes it, and a temperature
    // ramp at two frequencies.
    let dma = fs::read_to_string(root.join("dma.csv")).unwrap();
    let semicolon: String = dma
        .lines()
        .map(|l| match l.starts_with('#') {
            true => format!("{l}\n"),
            false => format!("{}\n", l.replace(',', ";").replace('.', ",")),
        })
        .collect();
    fs::write(root.join("dma-semicolon.csv"), semicolon).unwrap();
    let mut ramp = String::from("f,E_storage,E_loss,T\n");
    for k in 0..=2000 {
        for (f, s) in [(1.0, 2e6), (10.0, 3e6)] {
            ramp += &format!("{f},{s:e},{:e},{:.1}\n", 0.2 * s, -50.0 + 0.1 * k as f64);
        }
    }
    fs::write(root.join("ramp.csv"), ramp).unwrap();
    fs::copy(
        repo.join("data/hn-rubber-dma-isotherms.csv"),
        root.join("iso.csv"),
    )
    .unwrap();
    // Three isotherms of a relaxation modulus falling 0.35 decades per
    // decade of time, shifted 1.5 decades per 10 K.
    let mut relax = String::from("t_s,E_relax,T\n");
    for (j, t) in [0.0, 10.0, 20.0].iter().enumerate() {
        for k in 0..=20 {
            let time = 10f64.powf(k as f64 / 5.0);
            let reduced = time * 10f64.powf(1.5 * j as f64);
            relax += &format!("{time:e},{:e},{t}\n", 1e8 * reduced.powf(-0.35) + 1e6);
        }
    }
    fs::write(root.join("relax.csv"), relax).unwrap();
    fs::copy(
        repo.join("crates/io/tests/fixtures/trios_tensile.txt"),
        root.join("trios.txt"),
    )
    .unwrap();
    let forward = run(
        root,
        &[
            "forward",
            "scene.toml",
            "--noise",
            "0.02",
            "--seed",
            "3",
            "-o",
            "data.csv",
        ],
    );
    assert_eq!(forward.code, Some(0), "{}", forward.stderr);
    let fit = run(root, &["fit", "scene.toml", "data.csv", "-o", "base"]);
    assert_eq!(fit.code, Some(0), "{}", fit.stderr);
    let master = run(root, &["master", "dma.csv", "-o", "master-base"]);
    assert_eq!(master.code, Some(0), "{}", master.stderr);
}

/// The CSV file `csv` as a one-sheet workbook (comment lines dropped),
/// each cell below the header, with probability 1/20, made an Excel error,
/// a formula without a saved result, text or empty.
fn spoilt_workbook(csv: &Path, rng: &mut ChaCha8Rng) -> Vec<u8> {
    use workbook::X;
    let mut rows = workbook_rows(csv);
    for row in rows.iter_mut().skip(1) {
        for cell in row.iter_mut() {
            match rng.random_range(0..80) {
                0 => *cell = X::Error,
                1 => *cell = X::F("A2*2"),
                2 => *cell = X::S("n/a"),
                3 => *cell = X::E,
                _ => {}
            }
        }
    }
    workbook::xlsx(&[("Data", rows)])
}

/// The CSV file `csv` as the rows of a sheet (comment lines dropped).
fn workbook_rows(csv: &Path) -> Vec<Vec<workbook::X<'static>>> {
    use workbook::X;
    let text: &'static str = Box::leak(fs::read_to_string(csv).unwrap().into_boxed_str());
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let mut rows = vec![workbook::texts(&header)];
    for line in lines {
        rows.push(
            line.split(',')
                .map(|cell| cell.trim().parse::<f64>().map_or(X::S("?"), X::N))
                .collect(),
        );
    }
    rows
}

/// One case: mutate, run, check; the problems found, the kind and how it
/// ended.
fn case(root: &Path, index: usize, seed: u64) -> (Vec<String>, Kind, messages::Outcome) {
    let kind = kind_of(index);
    let mut rng =
        ChaCha8Rng::seed_from_u64(seed ^ (index as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
    let dir = root.join(format!("case-{index}"));
    fs::create_dir_all(&dir).unwrap();
    for name in [
        "scene.toml",
        "data.csv",
        "dma.csv",
        "trios.txt",
        "manifest.toml",
    ] {
        fs::copy(root.join(name), dir.join(name)).unwrap();
    }
    let mutated = |name: &str, rng: &mut ChaCha8Rng| {
        let original = fs::read(dir.join(name)).unwrap();
        fs::write(dir.join(name), mutate(&original, rng)).unwrap();
    };
    // The previous result an output must keep on a failure.
    let with_base = |dir: &Path| copy_tree(&root.join("base"), &dir.join("out"));
    // What a piped case feeds, and a shared folder's expectations.
    let mut stdin = None;
    let mut feeder = None;
    let mut refusal_expected = false;
    let (args, output, input): (Vec<&str>, &str, &str) = match kind {
        Kind::Piped => {
            let name = ["scene.toml", "data.csv"][rng.random_range(0..2)];
            mutated(name, &mut rng);
            with_base(&dir);
            let bytes = fs::read(dir.join(name)).unwrap();
            let pipe = if name == "data.csv" {
                "pipe.csv"
            } else {
                "pipe.toml"
            };
            let made = rng.random_bool(0.5)
                && Command::new("mkfifo")
                    .arg(dir.join(pipe))
                    .status()
                    .is_ok_and(|s| s.success());
            let given = if made {
                feeder = Some(
                    Command::new("sh")
                        .arg("-c")
                        .arg("cat \"$0\" > \"$1\"")
                        .arg(dir.join(name))
                        .arg(dir.join(pipe))
                        .spawn()
                        .unwrap(),
                );
                pipe
            } else {
                stdin = Some(bytes);
                "-"
            };
            let args = if name == "data.csv" {
                vec!["fit", "scene.toml", given, "-o", "out"]
            } else {
                vec!["fit", given, "data.csv", "-o", "out"]
            };
            (args, "out", if made { pipe } else { "file -" })
        }
        Kind::SharedFolder => {
            let first_fit = rng.random_bool(0.5);
            let first = if first_fit { "base" } else { "master-base" };
            copy_tree(&root.join(first), &dir.join("out"));
            fs::write(dir.join("out/photo.png"), b"the user's photo").unwrap();
            let record = dir.join("out/.rollfit-files.json");
            let spoilt = rng.random_range(0..4) == 0;
            if spoilt {
                let original = fs::read(&record).unwrap();
                fs::write(&record, mutate(&original, &mut rng)).unwrap();
            }
            let force = rng.random_bool(0.3);
            let (mut args, fit_writer, master_writer) = match rng.random_range(0..5) {
                0 => (
                    vec!["fit", "scene.toml", "data.csv", "-o", "out"],
                    true,
                    false,
                ),
                1 => (vec!["master", "dma.csv", "-o", "out"], false, true),
                2 => (vec!["batch", "manifest.toml", "-o", "out"], false, false),
                3 => (vec!["report", "out"], true, false),
                _ => (vec!["compare", "out", "dma.csv"], true, false),
            };
            let writes_folder = args[0] != "report" && args[0] != "compare";
            if force && writes_folder {
                args.push("--force");
            }
            let same = if first_fit { fit_writer } else { master_writer };
            refusal_expected = !(spoilt || same || (force && writes_folder));
            (args, "out", ".rollfit-files.json")
        }
        Kind::SceneForward => {
            mutated("scene.toml", &mut rng);
            fs::write(dir.join("out.csv"), b"previous output\n").unwrap();
            (
                vec!["forward", "scene.toml", "-o", "out.csv"],
                "out.csv",
                "scene.toml",
            )
        }
        Kind::SceneFit | Kind::Data => {
            let name = if kind == Kind::Data {
                "data.csv"
            } else {
                "scene.toml"
            };
            mutated(name, &mut rng);
            with_base(&dir);
            (
                vec!["fit", "scene.toml", "data.csv", "-o", "out"],
                "out",
                name,
            )
        }
        Kind::Manifest => {
            mutated("manifest.toml", &mut rng);
            (
                vec!["batch", "manifest.toml", "-o", "out"],
                "out",
                "manifest.toml",
            )
        }
        Kind::DmaCsv | Kind::Trios => {
            let name = if kind == Kind::Trios {
                "trios.txt"
            } else {
                "dma.csv"
            };
            mutated(name, &mut rng);
            with_base(&dir);
            (vec!["compare", "out", name], "out", name)
        }
        Kind::DmaSemicolon | Kind::DmaRamp => {
            let name = match kind {
                Kind::DmaRamp => "ramp.csv",
                _ => "dma-semicolon.csv",
            };
            fs::copy(root.join(name), dir.join(name)).unwrap();
            mutated(name, &mut rng);
            match kind {
                Kind::DmaRamp => (vec!["master", name, "-o", "master"], "master", name),
                _ => {
                    with_base(&dir);
                    (vec!["compare", "out", name], "out", name)
                }
            }
        }
        Kind::Workbook => {
            with_base(&dir);
            let (source, name) =
                [("data.csv", "data.xlsx"), ("dma.csv", "dma.xlsx")][rng.random_range(0..2)];
            fs::write(dir.join(name), spoilt_workbook(&dir.join(source), &mut rng)).unwrap();
            let args = if name == "data.xlsx" {
                vec!["fit", "scene.toml", "data.xlsx", "-o", "out"]
            } else {
                vec!["compare", "out", "dma.xlsx"]
            };
            (args, "out", name)
        }
        Kind::TRefSingular => {
            fs::copy(root.join("iso.csv"), dir.join("iso.csv")).unwrap();
            let near = [-81.6, -81.0, -80.0, -82.0, -100.0, -250.0, -273.14, -260.0];
            let t_ref = near[rng.random_range(0..near.len())] + rng.random_range(-0.5..0.5);
            let law = ["wlf", "arrhenius", "wlf-arrhenius", "auto", "free"][rng.random_range(0..5)];
            let mut args = vec!["master", "iso.csv", "-o", "master", "--shift", law];
            args.push("--T-ref");
            args.push(Box::leak(format!("{t_ref:.3}").into_boxed_str()));
            (args, "master", "iso.csv")
        }
        Kind::StrayCell => {
            with_base(&dir);
            let (source, name) =
                [("data.csv", "data.xlsx"), ("dma.csv", "dma.xlsx")][rng.random_range(0..2)];
            let column = ["XFD", "CZ", "A", "D", "AAA"][rng.random_range(0..5)];
            let row = [1048576, 1000000, 1, 2, 70000][rng.random_range(0..5)];
            let at = format!("{column}{row}");
            let rows = workbook_rows(&dir.join(source));
            fs::write(
                dir.join(name),
                workbook::xlsx_with_stray(&[("Data", rows)], Some(&at)),
            )
            .unwrap();
            let args = if name == "data.xlsx" {
                vec!["fit", "scene.toml", "data.xlsx", "-o", "out"]
            } else {
                vec!["compare", "out", "dma.xlsx"]
            };
            (args, "out", name)
        }
        Kind::ExtremeTimes => {
            let text = fs::read_to_string(root.join("relax.csv")).unwrap();
            let extremes = [
                "1e300", "1e-300", "1e30", "1e-30", "1.1e30", "9e-31", "0", "-1",
            ];
            let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
            for _ in 0..rng.random_range(1..4) {
                let k = rng.random_range(1..lines.len());
                let rest = lines[k][lines[k].find(',').unwrap()..].to_string();
                lines[k] = format!("{}{rest}", extremes[rng.random_range(0..extremes.len())]);
            }
            fs::write(dir.join("relax.csv"), lines.join("\n") + "\n").unwrap();
            (
                vec!["master", "relax.csv", "-o", "master"],
                "master",
                "relax.csv",
            )
        }
        Kind::Unsized => {
            with_base(&dir);
            let name = ["data.csv", "dma.csv"][rng.random_range(0..2)];
            let path = dir.join(name);
            fs::remove_file(&path).unwrap();
            match rng.random_range(0..2) {
                0 => std::os::unix::fs::symlink("/dev/zero", &path).unwrap(),
                _ => fs::File::create(&path).unwrap().set_len(2 << 30).unwrap(),
            }
            let args = if name == "data.csv" {
                vec!["fit", "scene.toml", "data.csv", "-o", "out"]
            } else {
                vec!["compare", "out", "dma.csv"]
            };
            (args, "out", name)
        }
        Kind::FitFolderReport | Kind::FitFolderCompare => {
            with_base(&dir);
            let file = ["fit.json", "mu.csv", "modulus.csv"][rng.random_range(0..3)];
            let path = dir.join("out").join(file);
            let original = fs::read(&path).unwrap();
            fs::write(&path, mutate(&original, &mut rng)).unwrap();
            let args = if kind == Kind::FitFolderReport {
                vec!["report", "out"]
            } else {
                vec!["compare", "out", "dma.csv"]
            };
            (args, "out", file)
        }
    };
    let before = snapshot(&dir.join(output));
    let result = run_fed(&dir, &args, stdin);
    if let Some(mut feeder) = feeder {
        let _ = feeder.kill();
        let _ = feeder.wait();
    }
    let mut problems = Vec::new();
    let what = format!("case {index} ({kind:?}, {input} mutated, {args:?})");
    if kind == Kind::SharedFolder {
        if fs::read(dir.join("out/photo.png")).ok().as_deref() != Some(b"the user's photo") {
            problems.push(format!("{what}: the user's photo was touched"));
        }
        if refusal_expected && result.code == Some(0) {
            problems.push(format!(
                "{what}: another command's folder was written without --force"
            ));
        }
    }
    if result.timed_out {
        problems.push(format!("{what}: still running after 60 s"));
    }
    if result.code == Some(101) || result.stderr.contains("panicked") {
        problems.push(format!("{what}: panic: {}", result.stderr));
    }
    match result.code {
        Some(0) => {
            if kind == Kind::Unsized {
                problems.push(format!("{what}: a file without a size was read"));
            }
            for p in non_finite_outputs(&dir.join(output)) {
                problems.push(format!("{what}: exit 0 with a non-finite output: {p}"));
            }
        }
        _ => {
            let error = result
                .stderr
                .lines()
                .find(|l| l.starts_with("error:"))
                .unwrap_or("");
            let names = [
                "scene.toml",
                "data.csv",
                "dma.csv",
                "trios.txt",
                "manifest.toml",
            ];
            let named = names.iter().any(|n| error.contains(n))
                || error.contains("out")
                || error.contains(input);
            if !named {
                problems.push(format!(
                    "{what}: the error names no file: {}",
                    result.stderr
                ));
            }
            if kind == Kind::Manifest {
                // A failed batch may have finished some entries; each entry
                // folder must be complete (or absent).
                for entry in ["a", "b"] {
                    let folder = dir.join("out").join(entry);
                    if folder.exists() {
                        let files: Vec<_> = snapshot(&folder).into_keys().collect();
                        let complete = ["fit.json", "modulus.csv", "mu.csv"]
                            .iter()
                            .all(|f| files.contains(&PathBuf::from(f)));
                        if !complete {
                            problems
                                .push(format!("{what}: entry {entry} is incomplete: {files:?}"));
                        }
                    }
                }
                for p in non_finite_outputs(&dir.join("out")) {
                    problems.push(format!("{what}: a non-finite output: {p}"));
                }
            } else if snapshot(&dir.join(output)) != before {
                problems.push(format!(
                    "{what}: exit {:?} but the output changed: {}",
                    result.code, result.stderr
                ));
            }
        }
    }
    let fit_folder = matches!(kind, Kind::FitFolderReport | Kind::FitFolderCompare);
    let outcome = match result.timed_out {
        true => messages::Outcome::TimedOut,
        false if fit_folder => messages::Outcome::Varies { code: result.code },
        false => messages::Outcome::Ended {
            code: result.code,
            stderr: messages::normalised(&result.stderr, root, &dir),
        },
    };
    if std::env::var_os("FUZZ_KEEP").is_none() && problems.is_empty() {
        let _ = fs::remove_dir_all(&dir);
    }
    (problems, kind, outcome)
}

/// The fuzzing target: at least 2 000 structured cases, none of
/// which panics, exits 0 with a non-finite output, changes the output on a
/// failure, or fails without naming a file.
#[test]
fn mutated_inputs_keep_every_promise() {
    const DEFAULT_CASES: usize = 2100;
    const DEFAULT_SEED: u64 = 14;
    let cases: usize = std::env::var("FUZZ_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(DEFAULT_CASES);
    let seed: u64 = std::env::var("FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(DEFAULT_SEED);
    let temp = TempDir::new("fuzz");
    let root = temp.path().to_path_buf();
    if std::env::var_os("FUZZ_KEEP").is_some() {
        eprintln!("cases kept in {}", root.display());
        std::mem::forget(temp);
    }
    fixtures(&root);
    let next = AtomicUsize::new(0);
    let problems = Mutex::new(Vec::new());
    let exits = Mutex::new(BTreeMap::<(String, Option<i32>), usize>::new());
    let outcomes = Mutex::new(BTreeMap::new());
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get());
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    if i >= cases {
                        break;
                    }
                    let (found, kind, outcome) = case(&root, i, seed);
                    problems.lock().unwrap().extend(found);
                    let code = match &outcome {
                        messages::Outcome::Ended { code, .. } => *code,
                        messages::Outcome::Varies { code } => *code,
                        messages::Outcome::TimedOut => None,
                    };
                    outcomes.lock().unwrap().insert(i, outcome);
                    *exits
                        .lock()
                        .unwrap()
                        .entry((format!("{kind:?}"), code))
                        .or_default() += 1;
                }
            });
        }
    });
    // How the cases ended, for a look at how deep the mutations reach.
    for ((kind, code), count) in exits.into_inner().unwrap() {
        eprintln!("{kind}: exit {code:?} × {count}");
    }
    let mut problems = problems.into_inner().unwrap();
    if cases == DEFAULT_CASES && seed == DEFAULT_SEED {
        let corpus =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/messages/fuzz.tsv");
        let outcomes = outcomes.into_inner().unwrap();
        for difference in messages::check(&corpus, &outcomes) {
            problems.push(format!("a message changed: {difference}"));
        }
    }
    assert!(
        problems.is_empty(),
        "{} of {cases} cases (seed {seed}) broke a promise:\n{}",
        problems.len(),
        problems.join("\n")
    );
}
