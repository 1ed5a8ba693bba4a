//! The message corpus: every case's exit code and standard error, kept in
//! a committed file so that a change of the error layer that alters one
//! character a user reads is seen, with the case and both texts.
//!
//! The file stores each distinct (exit code, text) once, with the ids of
//! the cases that give it: `exit \t ids \t text`, the text with `\`, tab
//! and line breaks escaped. The temporary folder of a run is written
//! `<root>` (and a case's own folder `<case>`), so the texts do not depend
//! on where the run happened; what depends on the machine's load is
//! hidden: a duration (`wall time 0.52 s`, `in 0.28 s`, `0.9714, 0.74 s`)
//! is written `<t>`, and the entries of a batch, which finish in any
//! order, are sorted with their counters written `[·/N]`. A case stopped
//! by the time limit is not compared (under load any case may be), nor is
//! one whose input is a fit folder's file ([`INCOMPARABLE`]).

/// Why the cases of a fit folder are not compared: their fit.json holds
/// the fixture fit's wall times, so its bytes, and with them where a
/// mutation falls and the offsets a message names, differ from run to
/// run. The io crate's corpus (crates/io/tests/it/messages.rs) reads a fixed
/// fit folder instead.
pub const INCOMPARABLE: &str = "varies";

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

/// What a case ended with: the exit code (`None`: killed by a signal or
/// the time limit) and the standard error, or that it timed out.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Outcome {
    Ended {
        code: Option<i32>,
        stderr: String,
    },
    TimedOut,
    /// Not compared: see [`INCOMPARABLE`].
    Varies {
        code: Option<i32>,
    },
}

/// `stderr` with the run's folders replaced by `<case>` and `<root>` and
/// its durations by `<t>`.
pub fn normalised(stderr: &str, root: &Path, case_dir: &Path) -> String {
    let text = stderr
        .replace(&case_dir.display().to_string(), "<case>")
        .replace(&root.display().to_string(), "<root>");
    batch_order_hidden(&durations_hidden(&text))
}

/// `text` with each run of batch entry lines (`[2/3] name: …`) sorted and
/// their counters written `[·/3]`.
fn batch_order_hidden(text: &str) -> String {
    let mut lines: Vec<String> = Vec::new();
    let mut run: Vec<String> = Vec::new();
    for line in text.split('\n') {
        let entry = line.strip_prefix('[').and_then(|rest| {
            let (counter, tail) = rest.split_once("] ")?;
            let (k, n) = counter.split_once('/')?;
            let numbers = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
            (numbers(k) && numbers(n)).then(|| format!("[·/{n}] {tail}"))
        });
        match entry {
            Some(entry) => run.push(entry),
            None => {
                run.sort();
                lines.append(&mut run);
                lines.push(line.to_string());
            }
        }
    }
    run.sort();
    lines.append(&mut run);
    lines.join("\n")
}

/// `text` with every duration in seconds after "wall time ", " in " or
/// ", " (a decimal number followed by " s") written `<t>`.
fn durations_hidden(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = ["wall time ", " in ", ", "]
        .iter()
        .filter_map(|lead| rest.find(lead).map(|i| i + lead.len()))
        .min()
    {
        out.push_str(&rest[..at]);
        rest = &rest[at..];
        let number = rest
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(rest.len());
        if number > 0 && rest[..number].contains('.') && rest[number..].starts_with(" s") {
            out.push_str("<t>");
            rest = &rest[number..];
        }
    }
    out.push_str(rest);
    out
}

fn escape(text: &str) -> String {
    text.replace('\\', "\\\\")
        .replace('\t', "\\t")
        .replace('\n', "\\n")
        .replace('\r', "\\r")
}

fn unescape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars();
    while let Some(c) = chars.next() {
        if c != '\\' {
            out.push(c);
            continue;
        }
        match chars.next() {
            Some('t') => out.push('\t'),
            Some('n') => out.push('\n'),
            Some('r') => out.push('\r'),
            Some(other) => out.push(other),
            None => out.push('\\'),
        }
    }
    out
}

fn code_text(outcome: &Outcome) -> String {
    match outcome {
        Outcome::Ended { code: Some(c), .. } => c.to_string(),
        Outcome::Ended { code: None, .. } => "signal".to_string(),
        Outcome::TimedOut => "timeout".to_string(),
        Outcome::Varies { .. } => INCOMPARABLE.to_string(),
    }
}

/// The corpus file's text for `outcomes` (case id → outcome).
pub fn corpus(outcomes: &BTreeMap<usize, Outcome>) -> String {
    let mut groups: BTreeMap<(String, String), Vec<usize>> = BTreeMap::new();
    for (id, outcome) in outcomes {
        let text = match outcome {
            Outcome::Ended { stderr, .. } => escape(stderr),
            Outcome::TimedOut | Outcome::Varies { .. } => String::new(),
        };
        groups
            .entry((code_text(outcome), text))
            .or_default()
            .push(*id);
    }
    let mut lines: Vec<(usize, String)> = groups
        .into_iter()
        .map(|((code, text), ids)| {
            let list: Vec<String> = ids.iter().map(usize::to_string).collect();
            (ids[0], format!("{code}\t{}\t{text}\n", list.join(",")))
        })
        .collect();
    lines.sort();
    lines.into_iter().map(|(_, line)| line).collect()
}

/// The corpus file's text read back: case id → (exit, text).
pub fn parse(corpus: &str) -> BTreeMap<usize, (String, String)> {
    let mut cases = BTreeMap::new();
    for line in corpus.lines() {
        let mut fields = line.splitn(3, '\t');
        let (Some(code), Some(ids), Some(text)) = (fields.next(), fields.next(), fields.next())
        else {
            panic!("corpus line without three tab-separated fields: {line:?}");
        };
        for id in ids.split(',') {
            let id: usize = id.parse().expect("a case id");
            cases.insert(id, (code.to_string(), unescape(text)));
        }
    }
    cases
}

/// The differences between the recorded corpus and `outcomes`, one per
/// case, each naming the case and both texts. Cases timed out in either
/// are skipped.
pub fn differences(recorded: &str, outcomes: &BTreeMap<usize, Outcome>) -> Vec<String> {
    let recorded = parse(recorded);
    let mut found = Vec::new();
    for (id, outcome) in outcomes {
        if matches!(outcome, Outcome::TimedOut | Outcome::Varies { .. }) {
            continue;
        }
        let now_code = code_text(outcome);
        let Outcome::Ended { stderr, .. } = outcome else {
            continue;
        };
        match recorded.get(id) {
            None => found.push(format!(
                "case {id}: not in the corpus; now exit {now_code}:\n{stderr}"
            )),
            Some((code, _)) if code == "timeout" || code == INCOMPARABLE => {}
            Some((code, text)) if *code != now_code || text != stderr => found.push(format!(
                "case {id}: recorded exit {code}:\n{text}\nnow exit {now_code}:\n{stderr}"
            )),
            Some(_) => {}
        }
    }
    found
}

/// Compares `outcomes` with the corpus at `path`, or writes it there when
/// `ROLLFIT_MESSAGE_CORPUS=write`; the differences found.
pub fn check(path: &Path, outcomes: &BTreeMap<usize, Outcome>) -> Vec<String> {
    if std::env::var("ROLLFIT_MESSAGE_CORPUS").as_deref() == Ok("write") {
        fs::create_dir_all(path.parent().unwrap()).unwrap();
        fs::write(path, corpus(outcomes)).unwrap();
        eprintln!("message corpus written to {}", path.display());
        return Vec::new();
    }
    let recorded = fs::read_to_string(path).unwrap_or_else(|e| {
        panic!(
            "cannot read the message corpus {}: {e} (ROLLFIT_MESSAGE_CORPUS=write records it)",
            path.display()
        )
    });
    differences(&recorded, outcomes)
}
