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
    csv::ReaderBuilder::new()
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
        .map_err(|source| IoError::CsvHeader { source })?
        .clone();
    if header.is_empty() {
        return Err(IoError::EmptyTable { expected });
    }
    if let Some(name) = duplicate(&header) {
        return Err(IoError::DuplicateColumn {
            name: name.to_string(),
        });
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
        .ok_or_else(|| IoError::CellNotFinite {
            line,
            column: name.to_string(),
            text: text.to_string(),
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

/// The line (from 1) where a CSV record read from `text` starts. The csv
/// crate's position is where it began to read: before the comment and
/// blank lines it skipped, and after a CRLF break at its '\n', which put
/// rows of CRLF files and rows below a comment one or more lines early.
pub fn csv_line(text: &str, position: Option<&csv::Position>) -> usize {
    let Some(position) = position else {
        return 0;
    };
    let bytes = text.as_bytes();
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
    bytes[..i].iter().filter(|&&b| b == b'\n').count() + 1
}

/// A cell of a DMA file's CSV as a finite number, or the error naming its
/// line and its column (`column`, made only for the message).
pub(crate) fn dma_number(
    path: &std::path::Path,
    line: usize,
    column: impl Fn() -> crate::error::ColumnRef,
    field: &str,
) -> Result<f64, IoError> {
    let v: f64 = field.parse().map_err(|_| IoError::NotANumber {
        path: path.to_path_buf(),
        cell: Box::new(crate::error::CellRef::line(line)),
        column: column(),
        text: field.to_string(),
    })?;
    if !v.is_finite() {
        return Err(IoError::NotFinite {
            path: path.to_path_buf(),
            cell: Box::new(crate::error::CellRef::line(line)),
            column: column(),
            text: field.to_string(),
        });
    }
    Ok(v)
}

/// The error of a CSV the csv crate cannot read, at its line.
pub(crate) fn not_csv(path: &std::path::Path, text: &str, error: csv::Error) -> IoError {
    IoError::NotCsv {
        path: path.to_path_buf(),
        line: csv_line(text, error.position()),
        error,
    }
}
