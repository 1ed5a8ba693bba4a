//! What the CSV readers share: the line a record starts on (as an editor
//! counts), reading and checking a header row, naming its columns in
//! messages, and reading one finite number from a row. The tables
//! themselves are described in docs/ARCHITECTURE.md, "Contract" (measured
//! data, DMA files, the fit folder).

use crate::error::IoError;

/// A reader of rollfit's CSV tables: `#` starts a comment line and cells are
/// trimmed. `headed`: the first record is the header (false: the caller
/// finds it itself); `flexible`: rows may differ in length (the caller
/// checks them with line numbers of its own).
pub fn reader(text: &str, headed: bool, flexible: bool) -> csv::Reader<&[u8]> {
    reader_with(text, headed, flexible, ',')
}

/// [`reader`] with `delimiter` (an ASCII character) between the cells.
pub fn reader_with(
    text: &str,
    headed: bool,
    flexible: bool,
    delimiter: char,
) -> csv::Reader<&[u8]> {
    csv::ReaderBuilder::new()
        .delimiter(u8::try_from(delimiter).unwrap_or(b','))
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .has_headers(headed)
        .flexible(flexible)
        .from_reader(text.as_bytes())
}

/// Reads the header row of `reader` and checks it names at least one column
/// and none twice; `expected` lists the columns for the message about a
/// file without a header.
pub fn header<R: std::io::Read>(
    reader: &mut csv::Reader<R>,
    expected: &'static str,
) -> Result<csv::StringRecord, IoError> {
    let header = reader
        .headers()
        .map_err(|source| err!("cannot read the header row").caused_by(source))?
        .clone();
    if header.is_empty() {
        return Err(err!(
            "the table is empty: expected a header row ({expected}) and data rows"
        ));
    }
    if let Some(name) = duplicate(&header) {
        return Err(err!("the header names column `{name}` twice"));
    }
    Ok(header)
}

/// The value of column `name` (at `index`) on file line `line` of `record`:
/// a finite number, or an error naming the line and the column.
pub fn finite(
    record: &csv::StringRecord,
    index: usize,
    line: u64,
    name: &str,
) -> Result<f64, IoError> {
    let text = record.get(index).unwrap_or("");
    text.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .ok_or_else(|| {
            err!(
                "line {line}: column `{column}`: {text:?} is not a finite number",
                column = name,
            )
        })
}

/// The header's columns as a list for messages: `` `a`, `b` ``.
pub fn list(header: &csv::StringRecord) -> String {
    let names: Vec<String> = header.iter().map(|h| format!("`{h}`")).collect();
    names.join(", ")
}

/// The first column name the header repeats, if any.
fn duplicate(header: &csv::StringRecord) -> Option<&str> {
    header
        .iter()
        .enumerate()
        .find(|(i, h)| header.iter().skip(i + 1).any(|other| other == *h))
        .map(|(_, h)| h)
}

/// The line (from 1) where a CSV record read from `text` starts: one
/// question, answered by [`LineIndex::csv_line`] (a reader that asks for
/// every record builds the index once).
pub fn csv_line(text: &str, position: Option<&csv::Position>) -> usize {
    LineIndex::new(text).csv_line(position)
}

/// Where the lines of a text start, for the line of any byte by binary
/// search. Counting the line breaks before each record from the start of
/// the file would make every CSV reader quadratic in the file's size; the
/// index costs one pass and O(log n) per record.
pub struct LineIndex<'t> {
    text: &'t str,
    /// Byte offsets of the '\n' characters, ascending.
    breaks: Vec<usize>,
}

impl<'t> LineIndex<'t> {
    /// The index of `text`.
    pub fn new(text: &'t str) -> LineIndex<'t> {
        let breaks = text
            .bytes()
            .enumerate()
            .filter(|(_, b)| *b == b'\n')
            .map(|(i, _)| i)
            .collect();
        LineIndex { text, breaks }
    }

    /// The line (from 1) of the byte at offset `i`: the breaks before it,
    /// plus one.
    fn line_of(&self, i: usize) -> usize {
        self.breaks.partition_point(|&b| b < i) + 1
    }

    /// The line (from 1) where a CSV record starts. The csv crate's
    /// position is where it began to read: before the comment and blank
    /// lines it skipped, and after a CRLF break at its '\n', which put rows
    /// of CRLF files and rows below a comment one or more lines early.
    pub fn csv_line(&self, position: Option<&csv::Position>) -> usize {
        let Some(position) = position else {
            return 0;
        };
        let bytes = self.text.as_bytes();
        let mut i = (position.byte() as usize).min(bytes.len());
        loop {
            while i < bytes.len() && (bytes[i] == b'\n' || bytes[i] == b'\r') {
                i += 1;
            }
            if i < bytes.len() && bytes[i] == b'#' {
                i = bytes[i..]
                    .iter()
                    .position(|&b| b == b'\n')
                    .map_or(bytes.len(), |n| i + n);
                continue;
            }
            break;
        }
        self.line_of(i)
    }

    /// [`LineIndex::csv_line`] of a record read from the text's tail
    /// from byte `start` (a reader started at a header below title lines).
    pub fn csv_line_after(&self, start: usize, position: Option<&csv::Position>) -> usize {
        let Some(position) = position else {
            return 0;
        };
        let mut shifted = position.clone();
        shifted.set_byte(position.byte() + start as u64);
        self.csv_line(Some(&shifted))
    }
}

/// A cell of a DMA file's CSV as a finite number, or the error naming its
/// line and its column (`column`, made only for the message).
pub(crate) fn dma_number(
    path: &std::path::Path,
    line: usize,
    column: impl Fn() -> crate::error::ColumnRef,
    field: &str,
) -> Result<f64, IoError> {
    let v: f64 = field.parse().map_err(|_| {
        err!(
            "{}, {cell}: {column}: \"{text}\" is not a number",
            path.display(),
            cell = crate::error::CellRef::line(line),
            column = column(),
            text = field
        )
    })?;
    if !v.is_finite() {
        return Err(err!(
            "{}, {cell}: {column}: {text} is not a finite number",
            path.display(),
            cell = crate::error::CellRef::line(line),
            column = column(),
            text = field
        ));
    }
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The line of a record the slow, obvious way: skip the breaks and
    /// comment lines after its position, then count the line breaks from
    /// the start of the text: the oracle the index is checked against.
    fn counted(text: &str, byte: usize) -> usize {
        let bytes = text.as_bytes();
        let mut i = byte.min(bytes.len());
        loop {
            while i < bytes.len() && (bytes[i] == b'\n' || bytes[i] == b'\r') {
                i += 1;
            }
            if i < bytes.len() && bytes[i] == b'#' {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
                continue;
            }
            break;
        }
        bytes[..i].iter().filter(|&&b| b == b'\n').count() + 1
    }

    /// The index against the count, at every record the csv crate reads
    /// and at every byte, on a text with comments, blank lines, CRLF and
    /// LF breaks, a comment at the end and no final break.
    #[test]
    fn the_index_gives_the_counted_line_everywhere() {
        let text = "# title\r\nf,E_storage,E_loss,T\r\n\r\n1,2,3,4\n# note\n\n5,6,7,8\r\n9,10,11,12\n# end\n13,14,15,16";
        let index = LineIndex::new(text);
        let mut reader = reader(text, false, true);
        let mut seen = Vec::new();
        for record in reader.records() {
            let record = record.unwrap();
            let position = record.position().unwrap();
            let line = index.csv_line(Some(position));
            assert_eq!(line, counted(text, position.byte() as usize));
            seen.push(line);
        }
        assert_eq!(seen, [2, 4, 7, 8, 10]);
        for byte in 0..=text.len() + 2 {
            let mut position = csv::Position::new();
            position.set_byte(byte as u64);
            assert_eq!(
                index.csv_line(Some(&position)),
                counted(text, byte),
                "byte {byte}"
            );
        }
        assert_eq!(index.csv_line(None), 0);
    }
}
