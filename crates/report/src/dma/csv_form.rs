//! The CSV form of a DMA file (DESIGN.md §4): a header line, then one point
//! per line; `#` lines are comments, columns other than the ones below are
//! ignored (they need not even be numbers).
//!
//! | quantity    | columns                         | unit suffixes (default first) |
//! |-------------|---------------------------------|-------------------------------|
//! | frequency   | `omega` or `f`                  | `rad_s` (omega), `Hz` (f)     |
//! | storage     | `E_storage` or `G_storage`      | `Pa`, `kPa`, `MPa`, `GPa`     |
//! | loss        | `E_loss` or `G_loss`            | `Pa`, `kPa`, `MPa`, `GPa`     |
//! | temperature | `T` (optional)                  | `C`, `K`                      |
//!
//! A suffix follows the name after an underscore: `omega_rad_s`, `f_Hz`,
//! `G_storage_Pa`, `E_loss_MPa`, `T_C`, `T_K`. Without one the column is in
//! the default unit (ω in rad/s, f in Hz, moduli in Pa, T in °C). When both
//! `omega` and `f` are present `omega` is used (no conversion); when both
//! Young's and shear columns are present the Young's ones are (no ν needed).
//! ω = 2π f.

use std::f64::consts::PI;
use std::path::Path;

use super::{FieldNames, ModulusKind, RawPoint};
use crate::error::ReportError;

/// What the CSV reader found.
pub(crate) struct CsvFile {
    pub points: Vec<RawPoint>,
    pub kind: ModulusKind,
    pub names: FieldNames,
    pub warnings: Vec<String>,
}

/// One recognised column: its index, header name and the factor to SI
/// (plus an offset, for kelvin).
#[derive(Debug, Clone)]
struct Column {
    index: usize,
    name: String,
    factor: f64,
    offset: f64,
}

/// The column among `header` named `base` or `base_UNIT` with UNIT one of
/// `units` ((suffix, factor, offset) to the SI unit), the first one found.
fn find(header: &[String], base: &str, units: &[(&str, f64, f64)]) -> Option<Column> {
    header.iter().enumerate().find_map(|(index, name)| {
        let (factor, offset) = if name == base {
            (units[0].1, units[0].2)
        } else {
            let suffix = name.strip_prefix(base)?.strip_prefix('_')?;
            let unit = units.iter().find(|u| u.0 == suffix)?;
            (unit.1, unit.2)
        };
        Some(Column {
            index,
            name: name.clone(),
            factor,
            offset,
        })
    })
}

const MODULUS_UNITS: [(&str, f64, f64); 4] = [
    ("Pa", 1.0, 0.0),
    ("kPa", 1e3, 0.0),
    ("MPa", 1e6, 0.0),
    ("GPa", 1e9, 0.0),
];

/// Parses the CSV text of `path`.
pub(crate) fn parse(path: &Path, text: &str) -> Result<CsvFile, ReportError> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .has_headers(false)
        .flexible(true)
        .from_reader(text.as_bytes());
    let mut records = reader.records();
    let header: Vec<String> = loop {
        match records.next() {
            None => return Err(ReportError::format(path, "empty: no header line")),
            Some(Err(e)) => return Err(not_csv(path, &e)),
            Some(Ok(r)) if r.iter().all(str::is_empty) => continue,
            Some(Ok(r)) => break r.iter().map(str::to_string).collect(),
        }
    };
    let listed = header.join(", ");
    let omega = find(&header, "omega", &[("rad_s", 1.0, 0.0), ("Hz", 2.0 * PI, 0.0)])
        .or_else(|| find(&header, "f", &[("Hz", 2.0 * PI, 0.0), ("rad_s", 1.0, 0.0)]))
        .ok_or_else(|| {
            ReportError::format(
                path,
                format!(
                    "no frequency column: need `omega` (rad/s) or `f` (Hz), optionally with a unit suffix such as omega_rad_s or f_Hz (the header has: {listed})"
                ),
            )
        })?;
    let young = (
        find(&header, "E_storage", &MODULUS_UNITS),
        find(&header, "E_loss", &MODULUS_UNITS),
    );
    let shear = (
        find(&header, "G_storage", &MODULUS_UNITS),
        find(&header, "G_loss", &MODULUS_UNITS),
    );
    let both = young.0.is_some() && young.1.is_some() && shear.0.is_some() && shear.1.is_some();
    let (kind, storage, loss) = match (young, shear) {
        ((Some(s), Some(l)), _) => (ModulusKind::Young, s, l),
        (_, (Some(s), Some(l))) => (ModulusKind::Shear, s, l),
        ((s, l), (gs, gl)) => {
            // Name what is missing of the kind the file started to give.
            let absent = |pair: [(&Option<Column>, &'static str); 2]| {
                pair.iter()
                    .filter(|(c, _)| c.is_none())
                    .map(|(_, n)| *n)
                    .collect::<Vec<_>>()
                    .join(" and ")
            };
            let missing = if s.is_some() || l.is_some() {
                absent([(&s, "E_storage"), (&l, "E_loss")])
            } else if gs.is_some() || gl.is_some() {
                absent([(&gs, "G_storage"), (&gl, "G_loss")])
            } else {
                "E_storage and E_loss (or G_storage and G_loss)".to_string()
            };
            return Err(ReportError::format(
                path,
                format!(
                    "no {missing} column: need storage and loss moduli as E_storage, E_loss (Young's) or G_storage, G_loss (shear), in Pa or with a unit suffix such as G_storage_Pa (the header has: {listed})"
                ),
            ));
        }
    };
    let temperature = find(&header, "T", &[("C", 1.0, 0.0), ("K", 1.0, -273.15)]);
    let mut warnings = Vec::new();
    if both {
        warnings.push(format!(
            "{}: both Young's (E_…) and shear (G_…) columns; the Young's ones are used",
            path.display()
        ));
    }

    let mut points = Vec::new();
    for record in records {
        let record = record.map_err(|e| not_csv(path, &e))?;
        let line = record.position().map_or(0, |p| p.line() as usize);
        if record.iter().all(str::is_empty) {
            continue;
        }
        if record.len() != header.len() {
            return Err(ReportError::line(
                path,
                line,
                format!(
                    "{} fields, but the header has {} columns",
                    record.len(),
                    header.len()
                ),
            ));
        }
        let value = |c: &Column| -> Result<f64, ReportError> {
            let field = &record[c.index];
            let v: f64 = field.parse().map_err(|_| {
                ReportError::line(
                    path,
                    line,
                    format!(
                        "column {} ({}): \"{field}\" is not a number",
                        c.index + 1,
                        c.name
                    ),
                )
            })?;
            if !v.is_finite() {
                return Err(ReportError::line(
                    path,
                    line,
                    format!(
                        "column {} ({}): {field} is not a finite number",
                        c.index + 1,
                        c.name
                    ),
                ));
            }
            Ok(v * c.factor + c.offset)
        };
        points.push(RawPoint {
            line,
            omega: value(&omega)?,
            storage: value(&storage)?,
            loss: value(&loss)?,
            temperature: temperature.as_ref().map(&value).transpose()?,
        });
    }
    if points.is_empty() {
        return Err(ReportError::format(path, "no data rows below the header"));
    }
    let label = |c: &Column| format!("column {} ({})", c.index + 1, c.name);
    Ok(CsvFile {
        points,
        kind,
        names: FieldNames {
            omega: label(&omega),
            storage: label(&storage),
            loss: label(&loss),
        },
        warnings,
    })
}

fn not_csv(path: &Path, e: &csv::Error) -> ReportError {
    let line = e.position().map_or(0, |p| p.line() as usize);
    ReportError::line(path, line, format!("not CSV: {e}"))
}
