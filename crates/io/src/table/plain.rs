//! The plain modulus table (docs/ARCHITECTURE.md, "Contract", "Scene
//! file"): CSV with `,` between the columns and decimal points, `#`
//! comments, a header naming one frequency column, `omega` (rad/s) or `f`
//! (Hz), and `E_storage`, `E_loss` (Young's, Pa); other columns ignored.
//! Each number must be finite and positive, a modulus at most 1e13 Pa, ω
//! within 1e-30 … 1e30 rad/s, the rows in strictly increasing frequency,
//! and there must be two at least. Errors name the line and column but not
//! the file: [`super::read`] puts them behind `modulus table PATH`.

use std::f64::consts::PI;

use super::ModulusTable;
use crate::columns::F;
use crate::csv_columns::{self, LineIndex};
use crate::error::IoError;
use crate::fit_dir::columns::{E_LOSS, E_STORAGE, OMEGA};

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

/// Parses and checks a plain modulus table (the CSV text of a file).
pub fn parse(text: &str) -> Result<ModulusTable, IoError> {
    let mut reader = csv_columns::reader(text, true, false);
    let header = csv_columns::header(&mut reader, "omega or f, E_storage, E_loss")?;
    let (columns, frequency) = columns(&header)?;
    let names = [
        header[columns[0]].to_string(),
        E_STORAGE.to_string(),
        E_LOSS.to_string(),
    ];
    let mut table = ModulusTable {
        omega: Vec::new(),
        storage: Vec::new(),
        loss: Vec::new(),
        lines: Vec::new(),
        notes: Vec::new(),
    };
    let mut previous_line = 0;
    let lines = LineIndex::new(text);
    for record in reader.records() {
        let record = record.map_err(|source| err!("malformed row").caused_by(source))?;
        // Counted as the DMA reader counts (comments, blank lines, CRLF).
        let line = lines.csv_line(record.position()) as u64;
        let values = row(&record, line, &columns, &names)?;
        let omega = match frequency {
            Frequency::Angular => values[0],
            Frequency::Hertz => 2.0 * PI * values[0],
        };
        if !(OMEGA_RANGE.0..=OMEGA_RANGE.1).contains(&omega) {
            return Err(err!(
                "line {line}: frequency {column} = {value:e}: outside 1e-30 … 1e30 rad/s, beyond any \
         master curve",
                column = names[0].clone(),
                value = values[0]
            ));
        }
        if let Some(&last) = table.omega.last()
            && omega <= last
        {
            return Err(err!(
                "line {line}: frequency {column} = {value} does not exceed the one on line {previous}: \
         rows must be in strictly increasing frequency",
                column = names[0].clone(),
                previous = previous_line,
                value = values[0]
            ));
        }
        table.omega.push(omega);
        table.storage.push(values[1]);
        table.loss.push(values[2]);
        table.lines.push(line as usize);
        previous_line = line;
    }
    if table.omega.len() < 2 {
        return Err(err!(
            "the table has {rows} data row(s): at least two frequencies are needed to interpolate",
            rows = table.omega.len()
        ));
    }
    Ok(table)
}

/// The indices of the frequency, storage and loss columns of `header`, and
/// the kind of frequency.
fn columns(header: &csv::StringRecord) -> Result<([usize; 3], Frequency), IoError> {
    let position = |name: &str| header.iter().position(|h| h == name);
    let names = || header.iter().map(str::to_string).collect::<Vec<_>>();
    let (frequency_column, frequency) = match (position(OMEGA), position(F)) {
        (Some(i), None) => (i, Frequency::Angular),
        (None, Some(i)) => (i, Frequency::Hertz),
        (Some(_), Some(_)) => {
            return Err(err!(
                "the header has both `{OMEGA}` (rad/s) and `{F}` (Hz): keep one frequency column"
            ));
        }
        (None, None) => {
            return Err(err!(
                "the header has no frequency column: expected `{OMEGA}` (rad/s) or `{F}` (Hz), found {}",
                backquoted(&names())
            ));
        }
    };
    let mut columns = [frequency_column, 0, 0];
    for (slot, name) in columns.iter_mut().skip(1).zip([E_STORAGE, E_LOSS]) {
        *slot = position(name).ok_or_else(|| {
            let advice = if header.iter().any(|h| h.starts_with("G_")) {
                format!(
                    ": a material table holds Young's moduli {E_STORAGE}, {E_LOSS} (Pa); convert \
                     shear moduli with E = 2(1 + ν) G"
                )
            } else {
                format!(" (Pa); found {}", backquoted(&names()))
            };
            err!("the header has no `{name}` column{advice}")
        })?;
    }
    Ok((columns, frequency))
}

/// The frequency, storage and loss values of `record` on file line `line`:
/// finite and positive, the moduli at most [`MAX_MODULUS`].
fn row(
    record: &csv::StringRecord,
    line: u64,
    columns: &[usize; 3],
    names: &[String; 3],
) -> Result<[f64; 3], IoError> {
    let mut values = [0.0; 3];
    for ((value, &column), name) in values.iter_mut().zip(columns).zip(names) {
        *value = csv_columns::finite(record, column, line, name)?;
        if *value <= 0.0 {
            return Err(err!(
                "line {line}: column `{column}` = {value}: must be greater than zero (the table is \
         interpolated in log-log)",
                column = name,
                value = *value
            ));
        }
    }
    for (value, name) in values.iter().zip(names).skip(1) {
        if *value > MAX_MODULUS {
            return Err(err!(
                "line {line}: column `{column}` = {value:e}: above 1e13 Pa, stiffer than any solid \
         (diamond: about 1.2e12 Pa); is the column in Pa?",
                column = name,
                value = *value
            ));
        }
    }
    Ok(values)
}

/// `` `a`, `b` `` (as [`crate::csv_columns::list`]).
fn backquoted(header: &[String]) -> String {
    let names: Vec<String> = header.iter().map(|h| format!("`{h}`")).collect();
    names.join(", ")
}
