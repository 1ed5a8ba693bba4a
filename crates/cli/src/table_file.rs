//! Reader for modulus tables: a measured master curve of Young's modulus in
//! CSV, the material of `model = "table"`.
//!
//! Format: a header row, then one row per frequency. Columns: a frequency,
//! either `omega` (rad/s) or `f` (Hz), and `E_storage`, `E_loss` (Pa). Other
//! columns (e.g. `tan_delta` in a `modulus.csv` written by `rollfit fit`) are
//! ignored. Lines starting with `#` are comments. Frequencies must be
//! positive and strictly increasing, moduli positive: the model interpolates
//! in log–log, where zero and negative values have no place.
//!
//! The model checks the same things again; checking here as well is what
//! lets an error name the line of the file.

use std::f64::consts::PI;
use std::io::Read;
use std::path::Path;

use anyhow::{Context, Result, bail, ensure};

use crate::csv_columns;

/// A master curve as read: angular frequency (rad/s), storage and loss
/// Young's moduli (Pa), in increasing frequency.
#[derive(Debug, Clone, PartialEq)]
pub struct ModulusTable {
    /// Angular frequencies ω, rad/s, strictly increasing.
    pub omega: Vec<f64>,
    /// Storage modulus E′(ω), Pa.
    pub storage: Vec<f64>,
    /// Loss modulus E″(ω), Pa.
    pub loss: Vec<f64>,
}

/// Reads and checks the modulus table at `path`; errors name the file.
pub fn read(path: &Path) -> Result<ModulusTable> {
    let text = crate::text_file::read_utf8(path, "modulus table")?;
    parse(text.as_bytes()).with_context(|| format!("modulus table {}", path.display()))
}

/// The largest accepted E′ or E″, Pa: above any solid's modulus, and small
/// enough that the contact map ω·a(ω) built from the table stays finite.
const MAX_MODULUS: f64 = 1e13;

/// Accepted angular frequencies, rad/s: wider than any master curve, far
/// inside the floating-point range the contact map needs.
const OMEGA_RANGE: (f64, f64) = (1e-30, 1e30);

/// Which kind of frequency the table gives.
#[derive(Clone, Copy)]
enum Frequency {
    /// `omega`, rad/s.
    Angular,
    /// `f`, Hz.
    Hertz,
}

/// Parses and checks a modulus table from any reader.
pub fn parse<R: Read>(input: R) -> Result<ModulusTable> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_reader(input);
    let header = csv_columns::header(
        &mut reader,
        "the table is empty: expected a header row (omega or f, E_storage, E_loss) and data rows",
    )?;
    let position = |name: &str| header.iter().position(|h| h == name);
    let (frequency_column, frequency) = match (position("omega"), position("f")) {
        (Some(i), None) => (i, Frequency::Angular),
        (None, Some(i)) => (i, Frequency::Hertz),
        (Some(_), Some(_)) => {
            bail!("the header has both `omega` (rad/s) and `f` (Hz): keep one frequency column")
        }
        (None, None) => bail!(
            "the header has no frequency column: expected `omega` (rad/s) or `f` (Hz), found {}",
            csv_columns::list(&header)
        ),
    };
    let mut columns = [frequency_column, 0, 0];
    for (slot, name) in columns.iter_mut().skip(1).zip(["E_storage", "E_loss"]) {
        *slot = match position(name) {
            Some(i) => i,
            None if header.iter().any(|h| h.starts_with("G_")) => bail!(
                "the header has no `{name}` column: a material table holds Young's moduli \
                 E_storage, E_loss (Pa); convert shear moduli with E = 2(1 + ν) G"
            ),
            None => bail!(
                "the header has no `{name}` column (Pa); found {}",
                csv_columns::list(&header)
            ),
        };
    }
    let names = [
        header[frequency_column].to_string(),
        "E_storage".into(),
        "E_loss".into(),
    ];

    let mut table = ModulusTable {
        omega: Vec::new(),
        storage: Vec::new(),
        loss: Vec::new(),
    };
    let mut previous_line = 0;
    for record in reader.records() {
        let record = record.context("malformed row")?;
        let line = record.position().map_or(0, |p| p.line());
        let mut values = [0.0; 3];
        for ((value, &column), name) in values.iter_mut().zip(&columns).zip(&names) {
            *value = csv_columns::finite(&record, column, line, name)?;
            ensure!(
                *value > 0.0,
                "line {line}: column `{name}` = {value}: must be greater than zero \
                 (the table is interpolated in log-log)"
            );
        }
        for (value, name) in values.iter().zip(&names).skip(1) {
            ensure!(
                *value <= MAX_MODULUS,
                "line {line}: column `{name}` = {value:e}: above 1e13 Pa, stiffer than any solid \
                 (diamond: about 1.2e12 Pa); is the column in Pa?"
            );
        }
        let omega = match frequency {
            Frequency::Angular => values[0],
            Frequency::Hertz => 2.0 * PI * values[0],
        };
        ensure!(
            (OMEGA_RANGE.0..=OMEGA_RANGE.1).contains(&omega),
            "line {line}: frequency {} = {:e}: outside 1e-30 … 1e30 rad/s, beyond any master \
             curve",
            names[0],
            values[0]
        );
        if let Some(&last) = table.omega.last() {
            ensure!(
                omega > last,
                "line {line}: frequency {} = {} does not exceed the one on line {previous_line}: \
                 rows must be in strictly increasing frequency",
                names[0],
                values[0]
            );
        }
        table.omega.push(omega);
        table.storage.push(values[1]);
        table.loss.push(values[2]);
        previous_line = line;
    }
    ensure!(
        table.omega.len() >= 2,
        "the table has {} data row(s): at least two frequencies are needed to interpolate",
        table.omega.len()
    );
    Ok(table)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_str(text: &str) -> Result<ModulusTable> {
        parse(text.as_bytes())
    }

    fn message(text: &str) -> String {
        format!("{:#}", parse_str(text).unwrap_err())
    }

    #[test]
    fn reads_omega_and_hertz_with_comments_and_extra_columns() {
        let t = parse_str("# master curve\nomega,E_storage,E_loss,tan_delta\n1,2e6,1e5,0.05\n# mid\n10, 3e6, 2e5, 0.07\n").unwrap();
        assert_eq!(t.omega, vec![1.0, 10.0]);
        assert_eq!(t.storage, vec![2e6, 3e6]);
        assert_eq!(t.loss, vec![1e5, 2e5]);
        let t = parse_str("f,E_loss,E_storage\n1,1e5,2e6\n2,1e5,2e6\n").unwrap();
        assert!((t.omega[0] - 2.0 * PI).abs() < 1e-15);
        assert_eq!(t.storage[1], 2e6);
    }

    #[test]
    fn errors_name_the_line_and_column() {
        let m = message("omega,E_storage,E_loss\n1,2e6,1e5\n10,abc,2e5\n");
        assert!(
            m.contains("line 3") && m.contains("E_storage") && m.contains("abc"),
            "{m}"
        );
        let m = message("omega,E_storage,E_loss\n1,2e6,1e5\n1,2e6,2e5\n");
        assert!(m.contains("line 3") && m.contains("increasing"), "{m}");
        let m = message("omega,E_storage,E_loss\n1,2e6,1e5\n2,2e6,0\n");
        assert!(
            m.contains("line 3") && m.contains("E_loss") && m.contains("greater than zero"),
            "{m}"
        );
        let m = message("omega,E_storage,E_loss\n1,2e6,nan\n2,2e6,1\n");
        assert!(m.contains("line 2") && m.contains("finite"), "{m}");
    }

    #[test]
    fn rejects_empty_and_incomplete_tables() {
        assert!(message("").contains("empty"));
        assert!(message("# nothing\n").contains("empty"));
        assert!(message("omega,E_storage,E_loss\n").contains("0 data row"));
        assert!(message("omega,E_storage\n1,2\n").contains("E_loss"));
        assert!(message("w,E_storage,E_loss\n1,2,3\n").contains("frequency column"));
        assert!(message("omega,f,E_storage,E_loss\n1,2,3,4\n").contains("both"));
        assert!(message("f,G_storage,G_loss\n1,2,3\n").contains("2(1 + ν) G"));
        assert!(message("omega,E_storage,E_loss\n1,2,3\n2,3\n").contains("malformed row"));
    }
}
