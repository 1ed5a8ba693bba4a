//! Where in fit.json a problem is: the key path of the value serde_json
//! stopped at, and the line of a key, so that errors name them
//! (docs/ARCHITECTURE.md, "Contract", "Fit folder"). "invalid type: null"
//! alone does not say which of forty numbers is null (serde_json writes a
//! NaN as null).

use std::path::Path;

use crate::error::IoError;
use crate::error::null_expected;

/// A serde error of fit.json with the key it is about: the line, the
/// column, the key's path (`model.H[3]`) and what is wrong, a null where a
/// number belongs said plainly.
pub(super) fn json_error(path: &Path, text: &str, e: &serde_json::Error) -> IoError {
    let (line, column) = (e.line(), e.column());
    let full = e.to_string();
    let message = full
        .strip_suffix(&format!(" at line {line} column {column}"))
        .unwrap_or(&full);
    // serde_json counts lines from 1 and columns from 1, in bytes.
    let line_start: usize = text
        .split_inclusive('\n')
        .take(line.saturating_sub(1))
        .map(str::len)
        .sum();
    let at = line_start + column.saturating_sub(1);
    let key = key_at(text, at + 1);
    let literal = |t: &str| {
        text.get(at..).is_some_and(|r| r.starts_with(t))
            || text
                .get(at.saturating_sub(1)..)
                .is_some_and(|r| r.starts_with(t))
    };
    let non_finite = message.starts_with("number out of range")
        || ["NaN", "Infinity", "-Infinity"].into_iter().any(literal);
    let path = path.to_path_buf();
    match (message.strip_prefix("invalid type: null, expected "), key) {
        (Some(expected), Some(key)) => err!(
            "{}, line {line}: column {column}: not a rollfit fit.json: `{key}` is null where {}",
            path.display(),
            null_expected(expected)
        ),
        (None, Some(key)) if non_finite => err!(
            "{}, line {line}: column {column}: not a rollfit fit.json: `{key}`: {message}: a number \
         must be finite (JSON has no NaN or infinity)",
            path.display(),
        ),
        (_, key) => {
            let path = &path;
            let line = &line;
            let column = &column;
            let key = &key;
            let message = &message.to_string();
            err!(
                "{}, line {line}: column {column}: not a rollfit fit.json: {}{message}",
                path.display(),
                key.as_ref().map_or(String::new(), |k| format!("`{k}`: "))
            )
        }
    }
}

/// The line (from 1) where the value of `key` (a path as [`path_of`]
/// writes it) starts in `text`.
pub(super) fn line_of_key(text: &str, key: &str) -> Option<usize> {
    let mut found = None;
    scan_json(text, text.len(), |stack, offset| {
        if path_of(stack) == key {
            found = Some(offset);
        }
        found.is_some()
    });
    found.map(|offset| text[..offset].matches('\n').count() + 1)
}

/// The path of the value serde_json stopped at, `end` bytes into `text`
/// (just past the character it reported), `None` at the top level.
fn key_at(text: &str, end: usize) -> Option<String> {
    let stack = scan_json(text, end, |_, _| false);
    Some(path_of(&stack)).filter(|p| !p.is_empty())
}

/// One open container while scanning JSON text.
enum Frame {
    /// The key being read, if any.
    Object(Option<String>),
    /// The index of the element being read.
    Array(usize),
}

/// `shift.log_aT[2].T` for a stack of frames.
fn path_of(stack: &[Frame]) -> String {
    let mut path = String::new();
    for frame in stack {
        match frame {
            Frame::Object(Some(key)) => {
                if !path.is_empty() {
                    path.push('.');
                }
                path.push_str(key);
            }
            Frame::Object(None) => {}
            Frame::Array(index) => path.push_str(&format!("[{index}]")),
        }
    }
    path
}

const OBJECT_START: u8 = 0x7B; // {
const OBJECT_END: u8 = 0x7D; // }
const ARRAY_START: u8 = b'[';
const ARRAY_END: u8 = b']';

/// Scans JSON `text` (assumed well-formed up to where it is stopped) and
/// calls `visit` with the path of every value as it starts and the byte
/// offset there; `visit` returns true to stop. Returns the open frames at
/// the stop (or at `end`).
fn scan_json(text: &str, end: usize, mut visit: impl FnMut(&[Frame], usize) -> bool) -> Vec<Frame> {
    let mut scanner = Scanner {
        text,
        end: end.min(text.len()),
        stack: Vec::new(),
        expect_key: false,
    };
    let mut i = 0;
    while i < scanner.end {
        match scanner.step(i, &mut visit) {
            Some(last) => i = last + 1,
            None => break,
        }
    }
    scanner.stack
}

/// The state of [`scan_json`].
struct Scanner<'a> {
    text: &'a str,
    /// Where to stop, in bytes.
    end: usize,
    stack: Vec<Frame>,
    /// The next string is a key.
    expect_key: bool,
}

impl Scanner<'_> {
    /// Reads the token at byte `i`; returns the offset of its last byte,
    /// or `None` when `visit` stops the scan.
    fn step(&mut self, i: usize, visit: &mut impl FnMut(&[Frame], usize) -> bool) -> Option<usize> {
        let bytes = self.text.as_bytes();
        match bytes[i] {
            b @ (OBJECT_START | ARRAY_START) => {
                if visit(&self.stack, i) {
                    return None;
                }
                self.stack.push(if b == OBJECT_START {
                    Frame::Object(None)
                } else {
                    Frame::Array(0)
                });
                self.expect_key = b == OBJECT_START;
            }
            OBJECT_END | ARRAY_END => {
                self.stack.pop();
                self.expect_key = false;
            }
            b',' => match self.stack.last_mut() {
                Some(Frame::Object(key)) => {
                    *key = None;
                    self.expect_key = true;
                }
                Some(Frame::Array(index)) => *index += 1,
                None => {}
            },
            b':' => self.expect_key = false,
            b'"' => return self.string(i, visit),
            b' ' | b'\t' | b'\n' | b'\r' => {}
            _ => {
                if visit(&self.stack, i) {
                    return None;
                }
                let mut last = i;
                let delimiters = [b',', OBJECT_END, ARRAY_END, b' ', b'\t', b'\n', b'\r'];
                while last + 1 < self.end && !delimiters.contains(&bytes[last + 1]) {
                    last += 1;
                }
                return Some(last);
            }
        }
        Some(i)
    }

    /// A string starting at byte `i`: a key, or a value to visit. Returns
    /// the offset of its closing quote.
    fn string(
        &mut self,
        i: usize,
        visit: &mut impl FnMut(&[Frame], usize) -> bool,
    ) -> Option<usize> {
        let bytes = self.text.as_bytes();
        let start = i + 1;
        let mut j = start;
        while j < bytes.len() && bytes[j] != b'"' {
            j += if bytes[j] == b'\\' { 2 } else { 1 };
        }
        let j = j.min(bytes.len());
        if self.expect_key {
            if let Some(Frame::Object(key)) = self.stack.last_mut() {
                *key = Some(self.text[start..j].to_string());
            }
        } else if visit(&self.stack, i) {
            return None;
        }
        Some(j)
    }
}
