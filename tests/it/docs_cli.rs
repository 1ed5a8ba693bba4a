//! The README and docs/ as a newcomer follows them: every command
//! they show runs, every scene they show loads, every link resolves.
//!
//! - **Commands.** Each fenced `sh` block is read line by line (a trailing
//!   `\` joins lines, a `#` comment is dropped). A line that starts with
//!   `rollfit` or `cargo run --release -p rollfit-cli --` is run with the
//!   binary under test, in one scratch folder holding a copy of `data/` and
//!   `examples/`, in the order of [`DOCUMENTS`], so a later block may use
//!   what an earlier one wrote (`fits/hn-rubber` after the README's first
//!   command); it must exit 0. Other lines (`cargo test`, `pip install`)
//!   are not run. A block whose info string carries a marker of
//!   [`SKIP_MARKERS`] is not run; any other marker fails the test, so a
//!   typo does not hide a block.
//! - **TOML.** Every fenced `toml` block parses. A block with `[geometry]`
//!   is a whole scene and loads as `rollfit` loads a scene file (from
//!   `data/`, so its relative paths resolve); a block with `[[entry]]` is a
//!   batch manifest and parses as one.
//! - **Links.** Every relative link `](…)` and `src="…"` names a file of the
//!   repository, and a `#anchor` into a Markdown file names one of its
//!   headings (GitHub's slugs).

use crate::common;

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

use common::TempDir;

/// The documents, in the order their commands run.
const DOCUMENTS: [&str; 7] = [
    "README.md",
    "docs/user-guide.md",
    "docs/methods.md",
    "docs/validation.md",
    "docs/ARCHITECTURE.md",
    "docs/film-sphere-thin-limit.md",
    "data/README.md",
];

/// The markers that keep a block from running, and why.
const SKIP_MARKERS: [(&str, &str); 2] = [
    (
        "no-run",
        "needs what the test does not have: a Python venv, a browser, a cluster, the user's own files, or it is a synopsis with placeholders",
    ),
    ("slow", "runs for minutes (a full benchmark)"),
];

/// The prefix of the README's way of running the tool from the clone.
const CARGO_RUN: &str = "cargo run --release -p rollfit-cli --";

/// A fenced block: its document, first line (from 1), info string and text.
struct Block {
    document: &'static str,
    line: usize,
    language: String,
    markers: Vec<String>,
    text: String,
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The fenced blocks of a Markdown text; fences may be indented (inside a
/// list item), and the indentation is taken off the block's lines.
fn blocks(document: &'static str, text: &str) -> Vec<Block> {
    let mut found = Vec::new();
    let mut open: Option<(usize, usize, String, Vec<String>)> = None;
    let mut body = String::new();
    for (i, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        let indent = line.len() - trimmed.len();
        if let Some(info) = trimmed.strip_prefix("```") {
            match open.take() {
                None => {
                    let mut words = info.split_whitespace().map(str::to_string);
                    let language = words.next().unwrap_or_default();
                    open = Some((i + 1, indent, language, words.collect()));
                    body.clear();
                }
                Some((line, _, language, markers)) => found.push(Block {
                    document,
                    line,
                    language,
                    markers,
                    text: std::mem::take(&mut body),
                }),
            }
            continue;
        }
        if let Some((_, indent, _, _)) = &open {
            body.push_str(line.get(*indent..).unwrap_or(line.trim_start()));
            body.push('\n');
        }
    }
    assert!(open.is_none(), "{document}: a fenced block is not closed");
    found
}

fn read(document: &str) -> String {
    fs::read_to_string(root().join(document)).unwrap_or_else(|e| panic!("{document}: {e}"))
}

/// The command lines of a shell block: continuations joined, comments
/// dropped.
fn command_lines(text: &str) -> Vec<String> {
    let mut lines = Vec::new();
    let mut current = String::new();
    for raw in text.lines() {
        let line = raw.trim();
        if let Some(head) = line.strip_suffix('\\') {
            current.push_str(head.trim_end());
            current.push(' ');
            continue;
        }
        current.push_str(line);
        let command = match current.find(" #") {
            Some(at) => current[..at].trim().to_string(),
            None => current.trim().to_string(),
        };
        if !command.is_empty() && !command.starts_with('#') {
            lines.push(command);
        }
        current.clear();
    }
    lines
}

/// The arguments of a command line that runs the tool, or None for a line
/// that is not run.
fn tool_arguments(command: &str) -> Option<Vec<String>> {
    let rest = if let Some(rest) = command.strip_prefix(CARGO_RUN) {
        rest
    } else {
        command.strip_prefix("rollfit ")?
    };
    let words: Vec<String> = rest.split_whitespace().map(str::to_string).collect();
    for word in &words {
        // Shell syntax or a placeholder would make the line a template.
        assert!(
            !word.contains(['$', '|', '>', '<', '{', '[', '*']) && word != "&&",
            "`{command}`: `{word}` is shell syntax or a placeholder; make the command concrete or mark the block no-run"
        );
    }
    Some(words)
}

/// A copy of the folders the documents' commands read.
fn scratch() -> TempDir {
    let dir = TempDir::new("docs");
    for folder in ["data", "examples"] {
        copy_tree(&root().join(folder), &dir.path().join(folder));
    }
    dir
}

fn copy_tree(from: &Path, to: &Path) {
    fs::create_dir_all(to).unwrap();
    for entry in fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            copy_tree(&entry.path(), &target);
        } else {
            fs::copy(entry.path(), &target).unwrap();
        }
    }
}

fn all_blocks() -> Vec<Block> {
    DOCUMENTS
        .iter()
        .flat_map(|document| blocks(document, &read(document)))
        .collect()
}

fn skipped(block: &Block) -> bool {
    for marker in &block.markers {
        assert!(
            SKIP_MARKERS.iter().any(|(known, _)| known == marker),
            "{}:{}: unknown marker `{marker}` (known: {:?})",
            block.document,
            block.line,
            SKIP_MARKERS.map(|(m, _)| m)
        );
    }
    !block.markers.is_empty()
}

#[test]
fn every_command_of_the_readme_and_docs_runs() {
    let dir = scratch();
    let mut ran = 0;
    for block in all_blocks() {
        if !matches!(block.language.as_str(), "sh" | "bash" | "shell") || skipped(&block) {
            continue;
        }
        for command in command_lines(&block.text) {
            let Some(arguments) = tool_arguments(&command) else {
                continue;
            };
            let out = Command::new(env!("CARGO_BIN_EXE_rollfit"))
                .args(&arguments)
                .current_dir(dir.path())
                .output()
                .expect("cannot start the rollfit binary");
            assert!(
                out.status.success(),
                "{}:{}: `{command}` exited with {}:\n{}",
                block.document,
                block.line,
                out.status,
                String::from_utf8_lossy(&out.stderr)
            );
            ran += 1;
        }
    }
    // The README alone shows ten; fewer means the reader lost its way.
    assert!(ran >= 10, "only {ran} commands found in the documents");
}

#[test]
fn every_toml_block_parses_and_every_scene_loads() {
    let dir = scratch();
    let data = dir.path().join("data");
    let mut scenes = 0;
    for (n, block) in all_blocks().into_iter().enumerate() {
        if block.language != "toml" {
            continue;
        }
        let place = format!("{}:{}", block.document, block.line);
        if let Err(error) = block.text.parse::<toml::Table>() {
            panic!("{place}: not TOML: {error}");
        }
        if block.text.contains("[[entry]]") {
            if let Err(error) = rollfit_io::manifest::parse(&block.text, &data) {
                panic!("{place}: not a batch manifest: {error}");
            }
        } else if block.text.contains("[geometry]") {
            let path = data.join(format!("docs-scene-{n}.toml"));
            fs::write(&path, &block.text).unwrap();
            if let Err(error) = rollfit_io::scene::load(&path) {
                panic!("{place}: the scene does not load: {error}");
            }
            scenes += 1;
        }
    }
    assert!(scenes >= 2, "only {scenes} scenes found in the documents");
}

/// GitHub's anchor of a heading: lower case, letters, digits, `-` and `_`
/// kept, spaces to `-`, everything else dropped.
fn slug(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

fn anchors(text: &str) -> BTreeSet<String> {
    let mut inside_fence = false;
    let mut found = BTreeSet::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            inside_fence = !inside_fence;
        } else if !inside_fence && line.starts_with('#') {
            found.insert(slug(line.trim_start_matches('#')));
        }
    }
    found
}

/// The relative link targets of a Markdown text: `](target)` and
/// `src="target"`.
fn links(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    for (open, close) in [("](", ')'), ("src=\"", '"')] {
        let mut rest = text;
        while let Some(at) = rest.find(open) {
            rest = &rest[at + open.len()..];
            if let Some(end) = rest.find(close) {
                found.push(rest[..end].to_string());
            }
        }
    }
    found
        .into_iter()
        .filter(|l| !l.contains("://") && !l.starts_with("mailto:"))
        .collect()
}

#[test]
fn every_link_of_the_readme_and_docs_resolves() {
    let mut checked = 0;
    for document in DOCUMENTS {
        let text = read(document);
        let folder = root().join(document).parent().unwrap().to_path_buf();
        for link in links(&text) {
            let (path, anchor) = match link.split_once('#') {
                Some((path, anchor)) => (path, Some(anchor)),
                None => (link.as_str(), None),
            };
            let target = if path.is_empty() {
                root().join(document)
            } else {
                folder.join(path)
            };
            assert!(
                target.exists(),
                "{document}: the link `{link}` names no file"
            );
            if let Some(anchor) = anchor.filter(|_| path.is_empty() || path.ends_with(".md")) {
                let headings = anchors(&fs::read_to_string(&target).unwrap());
                assert!(
                    headings.contains(anchor),
                    "{document}: the link `{link}` names no heading of {}",
                    target.display()
                );
            }
            checked += 1;
        }
    }
    assert!(checked >= 20, "only {checked} links found");
}

#[test]
fn the_readme_leads() {
    let readme = read("README.md");
    let lines = readme.lines().count();
    assert!(lines <= 300, "README.md has {lines} lines (at most 300)");
    // The two set-up commands open it.
    let first = &blocks("README.md", &readme)[0];
    assert_eq!(
        command_lines(&first.text),
        [
            "cargo run --release -p rollfit-cli -- fit data/hn-rubber.toml data/hn-rubber.csv",
            "cargo test --release --workspace"
        ]
    );
}

#[test]
fn the_reader_finds_fenced_blocks_and_commands() {
    // The parts of the reader, on a text whose answer is known.
    let text = "a\n  ```sh slow\n  rollfit fit a.toml \\\n    b.csv   # c\n  cargo test\n  ```\n```toml\nx = 1\n```\n";
    let found = blocks("x.md", text);
    assert_eq!(found.len(), 2);
    assert_eq!((found[0].line, found[0].language.as_str()), (2, "sh"));
    assert_eq!(found[0].markers, ["slow"]);
    let lines = command_lines(&found[0].text);
    assert_eq!(lines, ["rollfit fit a.toml b.csv", "cargo test"]);
    assert_eq!(
        tool_arguments(&lines[0]).unwrap(),
        ["fit", "a.toml", "b.csv"]
    );
    assert_eq!(tool_arguments(&lines[1]), None);
    assert_eq!(
        slug("From DMA isotherms to a master curve and μ(v)"),
        "from-dma-isotherms-to-a-master-curve-and-μv"
    );
    assert_eq!(
        links("[a](b.md#c) <img src=\"d.png\">"),
        ["b.md#c", "d.png"]
    );
}
