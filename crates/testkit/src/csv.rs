//! The numbers of a CSV file the tool wrote, read without the tool's own
//! reader so that a test does not check the reader against itself.

use std::fs;
use std::path::Path;

/// A CSV of numbers: its header and rows.
pub struct Table {
    pub header: Vec<String>,
    pub rows: Vec<Vec<f64>>,
}

impl Table {
    /// Reads the CSV file at `path`, leaving out lines starting with `#`.
    pub fn read(path: &Path) -> Table {
        let content = fs::read_to_string(path).unwrap();
        let kept: Vec<&str> = content.lines().filter(|l| !l.starts_with('#')).collect();
        parse_csv(&kept.join("\n"))
    }

    pub fn column(&self, name: &str) -> Vec<f64> {
        let i = self
            .header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no column {name} in {:?}", self.header));
        self.rows.iter().map(|r| r[i]).collect()
    }
}

/// Parses CSV text: a header row, then rows of as many numbers (an empty
/// cell, a number not determined, reads as NaN; true/false as 1/0).
pub fn parse_csv(csv: &str) -> Table {
    let mut lines = csv.lines();
    let header: Vec<String> = lines
        .next()
        .expect("empty CSV")
        .split(',')
        .map(str::to_string)
        .collect();
    let rows: Vec<Vec<f64>> = lines
        .map(|l| {
            l.split(',')
                .map(|x| match x {
                    "" => f64::NAN,
                    "true" => 1.0,
                    "false" => 0.0,
                    _ => x
                        .parse::<f64>()
                        .unwrap_or_else(|_| panic!("bad number {x:?}")),
                })
                .collect()
        })
        .collect();
    for row in &rows {
        assert_eq!(row.len(), header.len());
    }
    Table { header, rows }
}
