//! Measured data as text (docs/ARCHITECTURE.md, "Contract", "Measured
//! data"): decoded as UTF-8 (a byte-order mark is ignored), UTF-16 with a
//! byte-order mark, or else Latin-1 (with a note naming the first line
//! that is not UTF-8); CR, CRLF and LF line ends; `#` comments and blank
//! lines left out; cells separated by `,`, `;` or tab, with title lines
//! above the header, as [`super::dialect`] detects them (shared with DMA
//! CSV); double quotes around a cell removed (`""` inside is `"`).

use super::DataTable;
use super::cell::Row;
use super::dialect::{self, Line, split_line};
use super::header_row::is_header;
use super::rows::table;
use super::source::Source;
use crate::error::IoError;

/// Parses and checks a text measurement.
///
/// The file's bytes are taken, not borrowed, and the lines are walked
/// twice rather than collected, the second time split into cells one row
/// at a time as the rows are read: a logger's file of a million rows then
/// lives once as text beside its values.
pub(super) fn parse_bytes(bytes: Vec<u8>) -> Result<DataTable, IoError> {
    let mut notes = Vec::new();
    let text = decode(bytes, &mut notes)?;
    let Some(first) = dialect::lines(&text).next() else {
        return Err(err!(
            "the file is empty: expected a header row (v, mu, optionally sigma and T) and data rows"
        ));
    };
    let (delimiter, header) = match dialect::detect(dialect::lines(&text), is_header) {
        Some(found) => (found.delimiter, Some(found.index)),
        None => (dialect::likeliest(first.text), None),
    };
    // Split as the rows are read, never all at once.
    let rows = dialect::lines(&text).map(|line: Line| Row {
        number: line.number,
        cells: split_line(line.text, delimiter),
    });
    table(&Source::Text { delimiter }, rows, header, notes)
}

/// The text of `bytes`: UTF-8 (without a byte-order mark), UTF-16 with a
/// byte-order mark, else Latin-1 (with a note).
fn decode(bytes: Vec<u8>, notes: &mut Vec<String>) -> Result<String, IoError> {
    let utf16 = |rest: &[u8], unit: fn([u8; 2]) -> u16| -> Result<String, IoError> {
        if !rest.len().is_multiple_of(2) {
            return Err(err!(
                "the file starts with a UTF-16 byte-order mark but has an odd number of bytes"
            ));
        }
        let units: Vec<u16> = rest.chunks(2).map(|c| unit([c[0], c[1]])).collect();
        String::from_utf16(&units)
            .map_err(|source| err!("the file is not valid UTF-16 text").caused_by(source))
    };
    if let Some(rest) = bytes.strip_prefix(&[0xEF, 0xBB, 0xBF]) {
        return Ok(decode_8bit(rest.to_vec(), notes));
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

fn decode_8bit(bytes: Vec<u8>, notes: &mut Vec<String>) -> String {
    match String::from_utf8(bytes) {
        Ok(text) => text,
        Err(e) => {
            let valid_up_to = e.utf8_error().valid_up_to();
            let bytes = e.into_bytes();
            let line = bytes[..valid_up_to].iter().filter(|&&b| b == b'\n').count() + 1;
            notes.push(format!(
                "not UTF-8 text (line {line} is not): read as Latin-1 (ISO 8859-1)"
            ));
            bytes.iter().map(|&b| char::from(b)).collect()
        }
    }
}
