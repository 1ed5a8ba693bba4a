//! Measured data as text (docs/ARCHITECTURE.md, "Contract", "Measured
//! data"): decoded by the one decoder ([`crate::text_file`]: UTF-8,
//! UTF-16 with a byte-order mark, or Latin-1, each noted); CR, CRLF and LF
//! line ends; `#` comments and blank
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
use crate::text_file::{Encodings, Text, Undecodable, decode};

/// Parses and checks a text measurement.
///
/// The file's bytes are taken, not borrowed, and the lines are walked
/// twice rather than collected, the second time split into cells one row
/// at a time as the rows are read: a logger's file of a million rows then
/// lives once as text beside its values.
pub(super) fn parse_bytes(bytes: Vec<u8>) -> Result<DataTable, IoError> {
    let Text { text, notes } = decode(bytes, Encodings::Any).map_err(Undecodable::in_lines)?;
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
