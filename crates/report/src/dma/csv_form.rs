//! The CSV form of a DMA file (docs/ARCHITECTURE.md, "Contract", "DMA
//! files"): a header line, then one point per line; `#` lines are
//! comments, columns other than the ones below are ignored (they need not
//! even be numbers).
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
//! the default unit (ω in rad/s, f in Hz, moduli in Pa, T in °C). ω = 2π f.
//! When both Young's and shear columns are present the Young's ones are
//! used (no ν needed).
//!
//! Refused, naming the columns: two columns for one quantity (`f` and
//! `omega`, or `E_storage` and `E_storage_MPa`), since which one is meant
//! is a guess and a factor 2π or 10⁶ rides on it; and the contradictory
//! `omega_Hz` or `f_rad_s` (ω is rad/s and f is Hz by name: the name or
//! the unit is wrong, and nothing says which).

use std::f64::consts::PI;
use std::path::Path;

use super::{FieldNames, ModulusKind, RawPoint};
use crate::error::ReportError;
use crate::fit_dir::csv_line;

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

/// The columns among `header` named `base` or `base_UNIT` with UNIT one of
/// `units` ((suffix, factor, offset) to the SI unit), in header order.
fn find_all(header: &[String], base: &str, units: &[(&str, f64, f64)]) -> Vec<Column> {
    header
        .iter()
        .enumerate()
        .filter_map(|(index, name)| {
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
        .collect()
}

/// The one column of `what` among `found`, or an error naming two.
fn one(
    path: &Path,
    header_line: usize,
    what: &str,
    found: Vec<Column>,
    advice: &str,
) -> Result<Option<Column>, ReportError> {
    match found.as_slice() {
        [a, b, ..] => Err(ReportError::line(
            path,
            header_line,
            format!(
                "two {what} columns, column {} ({}) and column {} ({}): keep one{advice}",
                a.index + 1,
                a.name,
                b.index + 1,
                b.name
            ),
        )),
        _ => Ok(found.into_iter().next()),
    }
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
    let (header_line, header): (usize, Vec<String>) = loop {
        match records.next() {
            None => return Err(ReportError::format(path, "empty: no header line")),
            Some(Err(e)) => return Err(not_csv(path, text, &e)),
            Some(Ok(r)) if r.iter().all(str::is_empty) => continue,
            Some(Ok(r)) => {
                let line = csv_line(text, r.position());
                break (line, r.iter().map(str::to_string).collect());
            }
        }
    };
    let listed = header.join(", ");
    for (index, name) in header.iter().enumerate() {
        let contradiction = match name.as_str() {
            "omega_Hz" => Some("`omega` is an angular frequency, in rad/s, but the suffix says Hz"),
            "f_rad_s" => Some("`f` is a frequency, in Hz, but the suffix says rad/s"),
            _ => None,
        };
        if let Some(contradiction) = contradiction {
            return Err(ReportError::line(
                path,
                header_line,
                format!(
                    "column {} ({name}): {contradiction}: name it f_Hz if it holds hertz or omega_rad_s if it holds rad/s",
                    index + 1
                ),
            ));
        }
    }
    let mut frequencies = find_all(&header, "omega", &[("rad_s", 1.0, 0.0)]);
    frequencies.extend(find_all(&header, "f", &[("Hz", 2.0 * PI, 0.0)]));
    frequencies.sort_by_key(|c| c.index);
    let frequency = one(
        path,
        header_line,
        "frequency",
        frequencies,
        " (f in Hz or omega in rad/s)",
    )?;
    let Some(omega) = frequency else {
        return Err(ReportError::format(
            path,
            format!(
                "no frequency column: need `omega` (rad/s) or `f` (Hz), optionally with a unit suffix such as omega_rad_s or f_Hz (the header has: {listed})"
            ),
        ));
    };
    let modulus = |base: &str| {
        one(
            path,
            header_line,
            base,
            find_all(&header, base, &MODULUS_UNITS),
            "",
        )
    };
    let young = (modulus("E_storage")?, modulus("E_loss")?);
    let shear = (modulus("G_storage")?, modulus("G_loss")?);
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
    let temperature = one(
        path,
        header_line,
        "temperature",
        find_all(&header, "T", &[("C", 1.0, 0.0), ("K", 1.0, -273.15)]),
        "",
    )?;
    let mut warnings = Vec::new();
    if both {
        warnings.push(format!(
            "{}: both Young's (E_…) and shear (G_…) columns; the Young's ones are used",
            path.display()
        ));
    }

    // A file cut off inside its last row loses that row's tail: cells (a
    // count that no longer matches the header) or digits (which may still
    // parse). Only a missing final line break tells the second kind, and
    // CSV files written by hand lack one often enough that it is a warning.
    let unterminated = (!text.ends_with(['\n', '\r']))
        .then(|| text.lines().count())
        .filter(|&n| n > 0);
    let mut points = Vec::new();
    for record in records {
        let record = record.map_err(|e| not_csv(path, text, &e))?;
        let line = csv_line(text, record.position());
        if record.iter().all(str::is_empty) {
            continue;
        }
        let last_and_cut = unterminated == Some(line);
        if record.len() != header.len() {
            let missing = if record.len() < header.len() {
                let names: Vec<String> = header[record.len()..]
                    .iter()
                    .enumerate()
                    .map(|(i, n)| format!("column {} ({n})", record.len() + i + 1))
                    .collect();
                format!("; no value for {}", names.join(", "))
            } else {
                String::new()
            };
            let cut = if last_and_cut {
                "; the file ends in this line without a line break: it looks cut off"
            } else {
                ""
            };
            return Err(ReportError::line(
                path,
                line,
                format!(
                    "{} fields, but the header has {} columns{missing}{cut}",
                    record.len(),
                    header.len()
                ),
            ));
        }
        if last_and_cut {
            warnings.push(format!(
                "{}, line {line}: the file ends without a line break after this row: if the file was cut off, its last number may be incomplete",
                path.display()
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

fn not_csv(path: &Path, text: &str, e: &csv::Error) -> ReportError {
    ReportError::line(path, csv_line(text, e.position()), format!("not CSV: {e}"))
}
