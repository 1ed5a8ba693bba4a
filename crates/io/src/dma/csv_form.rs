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
//! used (no ν needed). `omega`, `E_storage`, `E_loss` and `T` are the
//! names of a fit folder's tables too ([`crate::fit_dir::columns`]), so a
//! fit's modulus.csv reads here as it is.
//!
//! Refused, naming the columns: two columns for one quantity (`f` and
//! `omega`, or `E_storage` and `E_storage_MPa`), since which one is meant
//! is a guess and a factor 2π or 10⁶ rides on it; and the contradictory
//! `omega_Hz` or `f_rad_s` (ω is rad/s and f is Hz by name: the name or
//! the unit is wrong, and nothing says which).

use std::f64::consts::PI;
use std::path::Path;

use super::form::{FieldNames, FormRead, RawPoint};
use super::point::ModulusKind;
use crate::csv_columns::{csv_line, dma_number, not_csv};
use crate::error::{ColumnRef, Contradiction, DuplicateQuantity, IoError};
use crate::fit_dir::columns::{E_LOSS, E_STORAGE, OMEGA, T};

/// The columns only DMA files have, defined with the other shared names.
pub use crate::columns::{F, G_LOSS, G_STORAGE};

/// One recognised column: its index, header name and the factor to SI
/// (plus an offset, for kelvin).
#[derive(Debug, Clone)]
pub(super) struct Column {
    pub index: usize,
    pub name: String,
    pub factor: f64,
    pub offset: f64,
}

impl Column {
    /// `column N (name)` for messages.
    pub(super) fn reference(&self) -> ColumnRef {
        ColumnRef::numbered(self.index + 1, &self.name)
    }
}

/// The columns a file's header gives.
struct Header {
    names: Vec<String>,
    /// Both Young's and shear columns (the Young's are used).
    both: bool,
    kind: ModulusKind,
    omega: Column,
    storage: Column,
    loss: Column,
    temperature: Option<Column>,
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

/// The one column of `quantity` among `found`, or an error naming two.
fn one(
    path: &Path,
    header_line: usize,
    quantity: &'static str,
    found: Vec<Column>,
) -> Result<Option<Column>, IoError> {
    match found.as_slice() {
        [a, b, ..] => Err(IoError::DuplicateQuantity(Box::new(DuplicateQuantity {
            path: path.to_path_buf(),
            line: header_line,
            quantity,
            first: a.reference(),
            second: b.reference(),
        }))),
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
pub(crate) fn parse(path: &Path, text: &str) -> Result<FormRead, IoError> {
    let mut reader = crate::csv_columns::reader(text, false, true);
    let mut records = reader.records();
    let (header_line, names): (usize, Vec<String>) = loop {
        match records.next() {
            None => {
                return Err(IoError::NoHeader {
                    path: path.to_path_buf(),
                });
            }
            Some(Err(e)) => return Err(not_csv(path, text, e)),
            Some(Ok(r)) if r.iter().all(str::is_empty) => continue,
            Some(Ok(r)) => {
                let line = csv_line(text, r.position());
                break (line, r.iter().map(str::to_string).collect());
            }
        }
    };
    let header = columns(path, header_line, names)?;
    let mut warnings = Vec::new();
    if header.both {
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
        let record = record.map_err(|e| not_csv(path, text, e))?;
        let line = csv_line(text, record.position());
        if record.iter().all(str::is_empty) {
            continue;
        }
        let cut = unterminated == Some(line);
        points.push(row(path, line, cut, &header, &record, &mut warnings)?);
    }
    if points.is_empty() {
        return Err(IoError::NoRows {
            path: path.to_path_buf(),
        });
    }
    Ok(FormRead {
        points,
        kind: header.kind,
        names: FieldNames {
            omega: header.omega.reference(),
            storage: header.storage.reference(),
            loss: header.loss.reference(),
        },
        warnings,
    })
}

/// The columns of the header `names` on line `line` (see the module doc).
fn columns(path: &Path, line: usize, names: Vec<String>) -> Result<Header, IoError> {
    for (index, name) in names.iter().enumerate() {
        if let Some(contradiction) = Contradiction::of(name) {
            return Err(IoError::ContradictoryUnit {
                path: path.to_path_buf(),
                line,
                number: index + 1,
                contradiction,
            });
        }
    }
    let mut frequencies = find_all(&names, OMEGA, &[("rad_s", 1.0, 0.0)]);
    frequencies.extend(find_all(&names, F, &[("Hz", 2.0 * PI, 0.0)]));
    frequencies.sort_by_key(|c| c.index);
    let Some(omega) = one(path, line, "frequency", frequencies)? else {
        return Err(IoError::NoFrequencyColumn {
            path: path.to_path_buf(),
            header: names,
        });
    };
    let modulus =
        |base: &'static str| one(path, line, base, find_all(&names, base, &MODULUS_UNITS));
    let young = (modulus(E_STORAGE)?, modulus(E_LOSS)?);
    let shear = (modulus(G_STORAGE)?, modulus(G_LOSS)?);
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
                absent([(&s, E_STORAGE), (&l, E_LOSS)])
            } else if gs.is_some() || gl.is_some() {
                absent([(&gs, G_STORAGE), (&gl, G_LOSS)])
            } else {
                format!("{E_STORAGE} and {E_LOSS} (or {G_STORAGE} and {G_LOSS})")
            };
            return Err(IoError::NoModulusColumns {
                path: path.to_path_buf(),
                missing,
                header: names,
            });
        }
    };
    let temperature = one(
        path,
        line,
        "temperature",
        find_all(&names, T, &[("C", 1.0, 0.0), ("K", 1.0, -273.15)]),
    )?;
    Ok(Header {
        names,
        both,
        kind,
        omega,
        storage,
        loss,
        temperature,
    })
}

/// The point of the record on line `line`; `last_and_cut`: the record is
/// the file's last line and has no line break.
fn row(
    path: &Path,
    line: usize,
    last_and_cut: bool,
    header: &Header,
    record: &csv::StringRecord,
    warnings: &mut Vec<String>,
) -> Result<RawPoint, IoError> {
    let width = header.names.len();
    if record.len() != width {
        let missing = header.names[record.len().min(width)..]
            .iter()
            .enumerate()
            .map(|(i, n)| ColumnRef::numbered(record.len() + i + 1, n))
            .collect();
        return Err(IoError::FieldCount {
            path: path.to_path_buf(),
            line,
            found: record.len(),
            expected: width,
            missing,
            cut: last_and_cut,
        });
    }
    if last_and_cut {
        warnings.push(format!(
            "{}, line {line}: the file ends without a line break after this row: if the file was cut off, its last number may be incomplete",
            path.display()
        ));
    }
    let value = |c: &Column| -> Result<f64, IoError> {
        let v = dma_number(path, line, || c.reference(), &record[c.index])?;
        Ok(v * c.factor + c.offset)
    };
    Ok(RawPoint {
        line,
        omega: value(&header.omega)?,
        storage: value(&header.storage)?,
        loss: value(&header.loss)?,
        temperature: header.temperature.as_ref().map(&value).transpose()?,
    })
}
