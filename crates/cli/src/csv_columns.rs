//! What the CSV readers (`data_file`, `table_file`) share: reading and
//! checking the header row, naming its columns in messages, and reading one
//! finite number from a row.

use anyhow::{Context, Result, bail, ensure};

/// Reads the header row of `reader` and checks it names at least one column
/// and none twice; `empty` is the message for a file without a header.
pub fn header<R: std::io::Read>(
    reader: &mut csv::Reader<R>,
    empty: &str,
) -> Result<csv::StringRecord> {
    let header = reader
        .headers()
        .context("cannot read the header row")?
        .clone();
    ensure!(!header.is_empty(), "{empty}");
    if let Some(name) = duplicate(&header) {
        bail!("the header names column `{name}` twice");
    }
    Ok(header)
}

/// The value of column `name` (at `index`) on file line `line` of `record`:
/// a finite number, or an error naming the line and the column.
pub fn finite(record: &csv::StringRecord, index: usize, line: u64, name: &str) -> Result<f64> {
    let text = record.get(index).unwrap_or("");
    text.parse::<f64>()
        .ok()
        .filter(|v| v.is_finite())
        .with_context(|| format!("line {line}: column `{name}`: {text:?} is not a finite number"))
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
