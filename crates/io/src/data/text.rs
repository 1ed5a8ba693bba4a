//! Measured data as text (docs/ARCHITECTURE.md, "Contract", "Measured
//! data"): decoded as UTF-8 (a byte-order mark is ignored), UTF-16 with a
//! byte-order mark, or else Latin-1 (with a note naming the first line
//! that is not UTF-8); CR, CRLF and LF line ends; `#` comments and blank
//! lines left out; cells separated by `,`, `;` or tab — the delimiter that
//! gives a header, the widest one of several — and double quotes around a
//! cell removed (`""` inside is `"`).

use super::DataTable;
use super::cell::{Cell, Row, is_comment_or_blank};
use super::header_row::find_header;
use super::rows::table;
use super::source::Source;
use crate::error::DataError;

/// The delimiters tried, in order of preference on a tie.
const DELIMITERS: [char; 3] = ['\t', ';', ','];

/// Parses and checks a text measurement.
pub(super) fn parse_bytes(bytes: &[u8]) -> Result<DataTable, DataError> {
    let mut notes = Vec::new();
    let text = decode(bytes, &mut notes)?;
    let text = text.replace("\r\n", "\n").replace('\r', "\n");
    let lines: Vec<(u64, &str)> = text
        .split('\n')
        .enumerate()
        .filter(|(_, line)| !is_comment_or_blank(line))
        .map(|(i, line)| (i as u64 + 1, line))
        .collect();
    if lines.is_empty() {
        return Err(DataError::Empty);
    }
    let split = |delimiter: char| -> Vec<Row> {
        lines
            .iter()
            .map(|&(number, line)| Row {
                number,
                cells: split_line(line, delimiter),
            })
            .collect()
    };
    // The delimiter that gives a header; of several, the widest header.
    let mut best: Option<(char, Vec<Row>, usize, usize)> = None;
    for delimiter in DELIMITERS {
        let rows = split(delimiter);
        if let Some(header) = find_header(&rows) {
            let width = rows[header].cells.iter().filter(|c| !c.is_empty()).count();
            if best.as_ref().is_none_or(|b| width > b.3) {
                best = Some((delimiter, rows, header, width));
            }
        }
    }
    let (delimiter, rows, header) = match best {
        Some((delimiter, rows, header, _)) => (delimiter, rows, Some(header)),
        None => {
            let first = lines[0].1;
            let delimiter = DELIMITERS
                .into_iter()
                .max_by_key(|d| first.matches(*d).count())
                .unwrap_or(',');
            (delimiter, split(delimiter), None)
        }
    };
    table(&Source::Text { delimiter }, &rows, header, notes)
}

/// The text of `bytes`: UTF-8 (without a byte-order mark), UTF-16 with a
/// byte-order mark, else Latin-1 (with a note).
fn decode(bytes: &[u8], notes: &mut Vec<String>) -> Result<String, DataError> {
    let utf16 = |rest: &[u8], unit: fn([u8; 2]) -> u16| -> Result<String, DataError> {
        if !rest.len().is_multiple_of(2) {
            return Err(DataError::OddUtf16);
        }
        let units: Vec<u16> = rest.chunks(2).map(|c| unit([c[0], c[1]])).collect();
        String::from_utf16(&units).map_err(|source| DataError::NotUtf16 { source })
    };
    if let Some(rest) = bytes.strip_prefix(&[0xEF, 0xBB, 0xBF]) {
        return Ok(decode_8bit(rest, notes));
    }
    if let Some(rest) = bytes.strip_prefix(&[0xFF, 0xFE]) {
        notes.push("read as UTF-16 (little-endian byte-order mark)".into());
        return utf16(rest, u16::from_le_bytes);
    }
    if let Some(rest) = bytes.strip_prefix(&[0xFE, 0xFF]) {
        notes.push("read as UTF-16 (big-endian byte-order mark)".into());
        return utf16(rest, u16::from_be_bytes);
    }
    Ok(decode_8bit(bytes, notes))
}

fn decode_8bit(bytes: &[u8], notes: &mut Vec<String>) -> String {
    match std::str::from_utf8(bytes) {
        Ok(text) => text.to_string(),
        Err(e) => {
            let line = bytes[..e.valid_up_to()]
                .iter()
                .filter(|&&b| b == b'\n')
                .count()
                + 1;
            notes.push(format!(
                "not UTF-8 text (line {line} is not): read as Latin-1 (ISO 8859-1)"
            ));
            bytes.iter().map(|&b| char::from(b)).collect()
        }
    }
}

/// The cells of a text line: separated by `delimiter`, each trimmed, with
/// double quotes around a cell removed (`""` in a quoted cell is `"`).
fn split_line(line: &str, delimiter: char) -> Vec<Cell> {
    let mut cells = Vec::new();
    let mut current = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        if quoted {
            if c == '"' {
                if chars.peek() == Some(&'"') {
                    current.push('"');
                    chars.next();
                } else {
                    quoted = false;
                }
            } else {
                current.push(c);
            }
        } else if c == delimiter {
            cells.push(Cell::text(&current));
            current.clear();
        } else if c == '"' && current.trim().is_empty() {
            current.clear();
            quoted = true;
        } else {
            current.push(c);
        }
    }
    cells.push(Cell::text(&current));
    cells
}
