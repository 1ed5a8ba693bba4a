//! CSV text as rollfit writes it (docs/ARCHITECTURE.md, "Data flow"):
//! numbers with the shortest digits that round-trip, a header row, and no
//! cell that is not a finite number.

use crate::error::IoError;

/// Formats a number so that parsing it back gives the same f64: `{:e}`
/// prints the shortest digits that round-trip, and the exponent form keeps
/// columns spanning many decades readable.
pub fn number(value: f64) -> String {
    format!("{value:e}")
}

/// CSV text (with a header row) from rows of numbers; refuses a number that
/// is not finite, naming its column and row, since no reader of the output
/// could use it.
pub fn csv_bytes(
    header: &[&str],
    rows: impl IntoIterator<Item = Vec<f64>>,
) -> Result<Vec<u8>, IoError> {
    csv_text_bytes(
        header,
        rows.into_iter()
            .map(|row| row.into_iter().map(number).collect()),
    )
}

/// CSV text (with a header row) from rows of cells already formatted
/// (numbers by [`number`]); refuses a cell that is NaN or ±∞.
pub fn csv_text_bytes(
    header: &[&str],
    rows: impl IntoIterator<Item = Vec<String>>,
) -> Result<Vec<u8>, IoError> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(header)?;
    for (i, row) in rows.into_iter().enumerate() {
        // [`number`] writes NaN and ±∞ so; no reader could use them.
        if let Some(k) = row
            .iter()
            .position(|cell| matches!(cell.as_str(), "NaN" | "inf" | "-inf"))
        {
            return Err(err!(
                "the output's row {row} has {column} = {value}: not a finite number (refused rather than \
         written)",
                column = header.get(k).copied().unwrap_or("?").to_string(),
                row = i + 1,
                value = row[k]
            ));
        }
        writer.write_record(row)?;
    }
    writer.into_inner().map_err(|e| {
        err!("cannot finish the CSV text")
            .caused_by(e.into_error())
            .internal()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_round_trip() {
        for v in [
            0.1,
            1e-8,
            10.0,
            1.0400419115259524e-3,
            123456789.123,
            f64::MIN_POSITIVE,
        ] {
            assert_eq!(number(v).parse::<f64>().unwrap(), v);
        }
        assert_eq!(number(1e-8), "1e-8");
    }

    #[test]
    fn csv_has_header_and_rows() {
        let bytes = csv_bytes(&["v", "mu"], vec![vec![1e-3, 0.5], vec![1.0, 0.25]]).unwrap();
        assert_eq!(
            String::from_utf8(bytes).unwrap(),
            "v,mu\n1e-3,5e-1\n1e0,2.5e-1\n"
        );
    }
}
