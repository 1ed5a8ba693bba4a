//! Reader for measured rolling friction (DESIGN.md §4): CSV with a header
//! row naming the columns `v` (m/s) and `mu`, optionally `sigma` (standard
//! deviation of μ) and `T` (°C); other columns are ignored, so the output of
//! `rollfit forward --noise` (v, mu, sigma, mu_exact, ...) is read directly.
//! Lines starting with `#` are comments.
//!
//! Every value must be a finite number; v, mu and sigma must be greater than
//! zero (the default weights are relative, 1/μ²). Repeated speeds and
//! unsorted rows are normal in real data and kept as they are, in file
//! order. Errors name the line of the file and the column; the caller adds
//! the file name.

use std::io::Read;
use std::path::Path;

use anyhow::{Context, Result, bail, ensure};
use rollfit_fit::Measurements;

use crate::csv_columns;

/// A measurement as read, in file order, with the file line of each row.
#[derive(Debug, Clone, PartialEq)]
pub struct DataTable {
    /// Speeds v, m/s.
    pub speeds: Vec<f64>,
    /// Friction coefficients μ.
    pub friction: Vec<f64>,
    /// Standard deviations of μ, when the file has a `sigma` column.
    pub sigma: Option<Vec<f64>>,
    /// Temperatures, °C, when the file has a `T` column.
    pub temperature: Option<Vec<f64>>,
    /// The file line of each row (for messages).
    pub lines: Vec<u64>,
}

impl DataTable {
    /// The validated measurements of the fit library.
    pub fn measurements(&self) -> Result<Measurements> {
        Measurements::new(
            self.speeds.clone(),
            self.friction.clone(),
            self.sigma.clone(),
            self.temperature.clone(),
        )
        .map_err(|e| anyhow::anyhow!("{e}"))
    }

    /// The distinct temperatures of a `T` column, in order of appearance.
    pub fn temperatures(&self) -> Vec<f64> {
        let mut distinct: Vec<f64> = Vec::new();
        for &t in self.temperature.iter().flatten() {
            if !distinct.contains(&t) {
                distinct.push(t);
            }
        }
        distinct
    }
}

/// Reads and checks the measurement at `path`; errors name the file.
pub fn read(path: &Path) -> Result<DataTable> {
    let file = std::fs::File::open(path)
        .with_context(|| format!("cannot open data file {}", path.display()))?;
    parse(file).with_context(|| format!("data file {}", path.display()))
}

/// A column the reader looks for: its name, whether it must be there, and
/// what its values must satisfy.
struct Column {
    name: &'static str,
    required: bool,
    positive: bool,
    meaning: &'static str,
}

const COLUMNS: [Column; 4] = [
    Column {
        name: "v",
        required: true,
        positive: true,
        meaning: "rolling speed, m/s",
    },
    Column {
        name: "mu",
        required: true,
        positive: true,
        meaning: "friction coefficient",
    },
    Column {
        name: "sigma",
        required: false,
        positive: true,
        meaning: "standard deviation of mu",
    },
    Column {
        name: "T",
        required: false,
        positive: false,
        meaning: "temperature, °C",
    },
];

/// Parses and checks a measurement from any reader.
///
/// Comment and blank lines are removed here rather than by the csv reader,
/// whose record positions count them with the record after them; the
/// remaining lines keep their original numbers for messages.
pub fn parse<R: Read>(mut input: R) -> Result<DataTable> {
    let mut text = String::new();
    input
        .read_to_string(&mut text)
        .context("cannot read the file as UTF-8 text")?;
    let mut kept = String::with_capacity(text.len());
    let mut line_numbers = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        if !(trimmed.is_empty() || trimmed.starts_with('#')) {
            kept.push_str(line);
            kept.push('\n');
            line_numbers.push(i as u64 + 1);
        }
    }
    // The file line of the csv reader's line `n` (counting kept lines from 1).
    let file_line = |n: u64| {
        usize::try_from(n)
            .ok()
            .and_then(|n| n.checked_sub(1))
            .and_then(|i| line_numbers.get(i).copied())
            .unwrap_or(n)
    };
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(kept.as_bytes());
    let header = csv_columns::header(
        &mut reader,
        "the file is empty: expected a header row (v, mu, optionally sigma and T) and data rows",
    )?;
    let mut positions = [None; 4];
    for (slot, column) in positions.iter_mut().zip(&COLUMNS) {
        *slot = header.iter().position(|h| h == column.name);
        if column.required && slot.is_none() {
            bail!(
                "line {} (header): no column `{}` ({}); found {}",
                file_line(1),
                column.name,
                column.meaning,
                csv_columns::list(&header)
            );
        }
    }

    let mut values: [Vec<f64>; 4] = Default::default();
    let mut lines = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| match e.position() {
            Some(p) => anyhow::anyhow!("line {}: malformed row: {e}", file_line(p.line())),
            None => anyhow::anyhow!("malformed row: {e}"),
        })?;
        let line = record.position().map_or(0, |p| file_line(p.line()));
        for ((column, position), target) in COLUMNS.iter().zip(positions).zip(values.iter_mut()) {
            let Some(index) = position else { continue };
            let value = csv_columns::finite(&record, index, line, column.name)?;
            if column.positive && value <= 0.0 {
                let why = match column.name {
                    "mu" => " (the fit weighs residuals relative to μ and needs μ > 0)",
                    "sigma" => {
                        " (a standard deviation of zero would give the point infinite weight)"
                    }
                    _ => "",
                };
                bail!(
                    "line {line}: column `{}` = {value}: must be greater than zero{why}",
                    column.name
                );
            }
            target.push(value);
        }
        lines.push(line);
    }
    ensure!(
        !lines.is_empty(),
        "the file has a header but no data rows: nothing to fit"
    );
    let [speeds, friction, sigma, temperature] = values;
    Ok(DataTable {
        speeds,
        friction,
        sigma: positions[2].map(|_| sigma),
        temperature: positions[3].map(|_| temperature),
        lines,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_str(text: &str) -> Result<DataTable> {
        parse(text.as_bytes())
    }

    fn message(text: &str) -> String {
        format!("{:#}", parse_str(text).unwrap_err())
    }

    #[test]
    fn reads_comments_extra_columns_repeats_and_unsorted_rows() {
        let t = parse_str(
            "# measured 2024\nv,mu,sigma,mu_exact\n1e-3,0.05,5e-4,0.051\n# again\n1e-4, 0.02, 2e-4, 0.02\n1e-3,0.052,5e-4,0.051\n",
        )
        .unwrap();
        assert_eq!(t.speeds, vec![1e-3, 1e-4, 1e-3]);
        assert_eq!(t.friction, vec![0.05, 0.02, 0.052]);
        assert_eq!(t.sigma, Some(vec![5e-4, 2e-4, 5e-4]));
        assert_eq!(t.temperature, None);
        assert_eq!(t.lines, vec![3, 5, 6]);
        let m = t.measurements().unwrap();
        assert_eq!(m.len(), 3);
        let t = parse_str("\n# a\n#b\nv,mu\n\n1,0.1\n  # c\n\n2,0.2\n").unwrap();
        assert_eq!(t.lines, vec![6, 9]);
        let m = message("#\nv,mu\n# c\n\n1,0.1\n# d\n2,x\n");
        assert!(m.contains("line 7") && m.contains("\"x\""), "{m}");
        let t = parse_str("mu,T,v\n0.1,-20,1\n0.2,40,2\n").unwrap();
        assert_eq!(t.speeds, vec![1.0, 2.0]);
        assert_eq!(t.temperature, Some(vec![-20.0, 40.0]));
        assert_eq!(t.sigma, None);
        assert_eq!(t.temperatures(), vec![-20.0, 40.0]);
    }

    #[test]
    fn errors_name_the_line_and_column() {
        let m = message("v,mu\n1e-3,0.05\nnan,0.1\n");
        assert!(
            m.contains("line 3") && m.contains("`v`") && m.contains("finite"),
            "{m}"
        );
        let m = message("# c\nv,mu\n1e-3,0.05\n1e-2,-0.1\n");
        assert!(
            m.contains("line 4") && m.contains("`mu`") && m.contains("greater than zero"),
            "{m}"
        );
        let m = message("v,mu,sigma\n1e-3,0.05,0\n");
        assert!(m.contains("line 2") && m.contains("`sigma`"), "{m}");
        let m = message("v,mu\n0,0.05\n");
        assert!(m.contains("line 2") && m.contains("`v` = 0"), "{m}");
        let m = message("v,mu\n1,inf\n");
        assert!(m.contains("line 2") && m.contains("`mu`"), "{m}");
        let m = message("v,mu,T\n1,0.1,\n");
        assert!(m.contains("line 2") && m.contains("`T`"), "{m}");
    }

    #[test]
    fn rejects_missing_columns_and_empty_data() {
        let m = message("# c\nv,friction\n1,0.1\n");
        assert!(
            m.contains("line 2 (header): no column `mu`") && m.contains("`friction`"),
            "{m}"
        );
        assert!(message("").contains("empty"));
        assert!(message("# only a comment\n").contains("empty"));
        assert!(message("v,mu\n").contains("no data rows"));
        assert!(message("v,mu\n# c\n").contains("no data rows"));
        assert!(message("v,mu,v\n1,2,3\n").contains("twice"));
        let m = message("v,mu\n# c\n1,0.1\n2\n");
        assert!(m.contains("line 4: malformed row"), "{m}");
    }
}
