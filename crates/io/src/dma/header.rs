//! The header of a DMA table (docs/ARCHITECTURE.md, "Contract", "DMA
//! files"): which column holds which quantity, in which unit. One
//! vocabulary for every source of rows — CSV text ([`super::csv_form`])
//! and a workbook's sheet ([`super::sheet`]) — so that a column name means
//! the same wherever it is written.
//!
//! | quantity    | names                                  | units (default first)        |
//! |-------------|----------------------------------------|------------------------------|
//! | frequency   | `f`, `freq`, `frequency`; `omega`, `ω` | Hz, kHz, mHz (f); rad/s (ω)  |
//! | storage     | `E_storage`, `E'`; shear `G_storage`, `G'` | Pa, kPa, MPa, GPa, N/mm² |
//! | loss        | `E_loss`, `E''`; shear `G_loss`, `G''` | as storage                   |
//! | temperature | `T`, `temp`, `temperature` (optional)  | °C, K                        |
//! | step        | `Step`, `Set`, `Segment` (optional)    | a label: which points form one isotherm |
//!
//! A unit is given in one of three ways: a suffix after an underscore
//! (`f_Hz`, `omega_rad_s`, `E_loss_MPa`, `T_K`; the CSV spellings, case as
//! written), in brackets after the name (`E' [MPa]`, `f (Hz)`), or in a
//! units row right below the header (`[Hz]`, `[°C]`, `[MPa]`, `[-]`, as the
//! Netzsch/GABO Eplexor "Excel Export" writes it) for the columns whose
//! names carry none. Without one a column is in the default unit. Primes
//! may be typed as `'`, `′`, `’`, `"` or `″`; names other than `T` compare
//! case-insensitively (a lone lowercase `t` is time). Columns named
//! otherwise (`tan delta`, `|E*|`, `t [s]`) are ignored.
//!
//! Refused, naming the columns: two columns for one quantity, since which
//! one is meant is a guess and a factor 2π or 10⁶ rides on it; the
//! contradictory `omega_Hz` or `f_rad_s`; a unit not known.

use std::f64::consts::PI;
use std::path::Path;

use super::form::{FieldNames, FormRead, Place, RawPoint};
use super::point::ModulusKind::{self, Shear, Young};
use crate::error::{ColumnRef, Contradiction, DmaUnknownUnit, DuplicateQuantity, IoError};
use crate::fit_dir::columns::{E_LOSS, E_STORAGE, OMEGA, T};

pub use crate::columns::{F, G_LOSS, G_STORAGE};

/// What a column holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Quantity {
    /// Angular frequency (default rad/s).
    Omega,
    /// Frequency (default Hz).
    Frequency,
    Storage(ModulusKind),
    Loss(ModulusKind),
    Temperature,
    /// The step, set or segment of a temperature programme: a label.
    Step,
}

impl Quantity {
    /// The kind of unit, for messages.
    fn unit_kind(self) -> &'static str {
        match self {
            Quantity::Omega | Quantity::Frequency => "a frequency",
            Quantity::Storage(_) | Quantity::Loss(_) => "a modulus",
            Quantity::Temperature => "a temperature",
            Quantity::Step => "a step",
        }
    }

    /// The units known, for messages.
    fn known(self) -> &'static str {
        match self {
            Quantity::Omega | Quantity::Frequency => "Hz, kHz, mHz, rad/s",
            Quantity::Storage(_) | Quantity::Loss(_) => "Pa, kPa, MPa, GPa, N/mm²",
            Quantity::Temperature => "°C, K",
            Quantity::Step => "none",
        }
    }

    /// The factor and offset to SI of the default unit.
    fn default_unit(self) -> (f64, f64) {
        match self {
            Quantity::Frequency => (2.0 * PI, 0.0),
            _ => (1.0, 0.0),
        }
    }

    /// The factor and offset to SI (rad/s, Pa, °C) of `unit` as written
    /// in brackets, a units row or (`rad_s`) a CSV suffix.
    fn unit(self, unit: &str) -> Option<(f64, f64)> {
        let unit = unit.trim();
        let hertz = |scale: f64| Some((2.0 * PI * scale, 0.0));
        match self {
            Quantity::Omega | Quantity::Frequency => match unit {
                "Hz" | "hz" => hertz(1.0),
                "kHz" | "khz" => hertz(1e3),
                "mHz" => hertz(1e-3),
                "rad/s" | "rad_s" | "rad s-1" | "rad·s⁻¹" | "rad s^-1" => Some((1.0, 0.0)),
                // Cycles per second for f, radians per second for ω.
                "1/s" | "s-1" | "s^-1" | "s⁻¹" => Some(self.default_unit()),
                _ => None,
            },
            Quantity::Storage(_) | Quantity::Loss(_) => match unit {
                "Pa" | "N/m²" | "N/m2" | "N/m^2" => Some((1.0, 0.0)),
                "kPa" => Some((1e3, 0.0)),
                "MPa" | "N/mm²" | "N/mm2" | "N/mm^2" => Some((1e6, 0.0)),
                "GPa" => Some((1e9, 0.0)),
                _ => None,
            },
            Quantity::Temperature => match unit {
                "°C" | "C" | "degC" | "deg C" | "℃" | "ºC" => Some((1.0, 0.0)),
                "K" => Some((1.0, -273.15)),
                _ => None,
            },
            // A label; whatever a units row writes above it.
            Quantity::Step => Some((1.0, 0.0)),
        }
    }
}

/// The canonical (CSV) names, each with its unit suffixes: the name
/// alone, or `name_SUFFIX`.
const CANONICAL: [(&str, Quantity, &[&str]); 7] = [
    (OMEGA, Quantity::Omega, &["rad_s"]),
    (F, Quantity::Frequency, &["Hz"]),
    (E_STORAGE, Quantity::Storage(Young), &MODULUS_SUFFIXES),
    (E_LOSS, Quantity::Loss(Young), &MODULUS_SUFFIXES),
    (G_STORAGE, Quantity::Storage(Shear), &MODULUS_SUFFIXES),
    (G_LOSS, Quantity::Loss(Shear), &MODULUS_SUFFIXES),
    (T, Quantity::Temperature, &["C", "K"]),
];

const MODULUS_SUFFIXES: [&str; 4] = ["Pa", "kPa", "MPa", "GPa"];

/// The names instruments write (lower case, primes as `'`, no spaces).
const ALIASES: [(&str, Quantity); 21] = [
    ("step", Quantity::Step),
    ("stepnumber", Quantity::Step),
    ("stepno.", Quantity::Step),
    ("set", Quantity::Step),
    ("segment", Quantity::Step),
    ("seg", Quantity::Step),
    ("segmentnumber", Quantity::Step),
    ("freq", Quantity::Frequency),
    ("frequency", Quantity::Frequency),
    ("frequenz", Quantity::Frequency),
    ("ω", Quantity::Omega),
    ("angularfrequency", Quantity::Omega),
    ("e'", Quantity::Storage(Young)),
    ("e''", Quantity::Loss(Young)),
    ("g'", Quantity::Storage(Shear)),
    ("g''", Quantity::Loss(Shear)),
    ("temp", Quantity::Temperature),
    ("temperature", Quantity::Temperature),
    ("temperatur", Quantity::Temperature),
    ("e_storage", Quantity::Storage(Young)),
    ("e_loss", Quantity::Loss(Young)),
];

/// What a header cell names: the quantity and the unit its name gives
/// (`None`: none given; `Some(Err(unit))`: a unit not known).
type Named = (Quantity, Option<Result<(f64, f64), String>>);

/// What the header cell `raw` names, if anything.
fn classify(raw: &str) -> Option<Named> {
    let raw = raw.trim();
    for (base, quantity, suffixes) in CANONICAL {
        if raw == base {
            return Some((quantity, None));
        }
        if let Some(suffix) = raw.strip_prefix(base).and_then(|r| r.strip_prefix('_'))
            && suffixes.contains(&suffix)
        {
            let unit = quantity.unit(suffix).ok_or_else(|| suffix.to_string());
            return Some((quantity, Some(unit)));
        }
    }
    let (name, unit) = split_unit(raw);
    let quantity = alias(name)?;
    let unit = unit
        .filter(|u| !u.is_empty())
        .map(|u| quantity.unit(u).ok_or_else(|| u.to_string()));
    Some((quantity, unit))
}

/// The quantity of a name without its unit.
fn alias(name: &str) -> Option<Quantity> {
    if name == T {
        return Some(Quantity::Temperature);
    }
    if name == "t" {
        return None; // time
    }
    if let Some((_, quantity, _)) = CANONICAL.iter().find(|(base, _, _)| *base == name) {
        return Some(*quantity);
    }
    let folded: String = name
        .to_lowercase()
        .replace(['′', '’', '´', '`'], "'")
        .replace(['″', '"'], "''")
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect();
    match folded.as_str() {
        "f" => Some(Quantity::Frequency),
        "omega" => Some(Quantity::Omega),
        _ => ALIASES.iter().find(|(a, _)| *a == folded).map(|(_, q)| *q),
    }
}

/// (name, unit) of `E' [MPa]`, `f (Hz)`; the unit `None` without brackets.
fn split_unit(raw: &str) -> (&str, Option<&str>) {
    let open = match raw.chars().last() {
        Some(')') => '(',
        Some(']') => '[',
        _ => return (raw, None),
    };
    match raw.rfind(open) {
        Some(start) if !raw[..start].trim().is_empty() => (
            raw[..start].trim_end(),
            Some(raw[start + 1..raw.len() - 1].trim()),
        ),
        _ => (raw, None),
    }
}

/// A units-row cell without its brackets.
fn unit_text(cell: &str) -> &str {
    cell.trim()
        .trim_start_matches(['[', '('])
        .trim_end_matches([']', ')'])
        .trim()
}

/// One recognised column: its index (from 0), header name, how messages
/// name it, and the factor and offset to SI.
#[derive(Debug, Clone)]
pub(super) struct Column {
    pub index: usize,
    pub reference: ColumnRef,
    pub factor: f64,
    pub offset: f64,
}

impl Column {
    /// `value` in SI.
    pub fn convert(&self, value: f64) -> f64 {
        value * self.factor + self.offset
    }
}

/// The columns a header gives.
pub(super) struct Header {
    /// The header's cells as written.
    pub names: Vec<String>,
    /// Both Young's and shear columns (the Young's are used).
    pub both: bool,
    pub kind: ModulusKind,
    pub omega: Column,
    pub storage: Column,
    pub loss: Column,
    pub temperature: Option<Column>,
    /// A step (set, segment) column: which points form one isotherm.
    pub step: Option<Column>,
}

impl Header {
    /// What a form read under this header: `points` (at least one) and
    /// the `warnings` so far.
    pub fn form(
        &self,
        path: &Path,
        points: Vec<RawPoint>,
        warnings: Vec<String>,
    ) -> Result<FormRead, IoError> {
        if points.is_empty() {
            return Err(IoError::NoRows {
                path: path.to_path_buf(),
            });
        }
        Ok(FormRead {
            points,
            kind: self.kind,
            names: FieldNames {
                omega: self.omega.reference.clone(),
                storage: self.storage.reference.clone(),
                loss: self.loss.reference.clone(),
            },
            warnings,
        })
    }
}

/// Whether `names` (a row's cells) name a frequency, a storage and a loss
/// column of one kind: the header of a sheet, found among its first rows.
pub(super) fn is_header(names: &[String]) -> bool {
    let found: Vec<Quantity> = names
        .iter()
        .filter_map(|n| classify(n))
        .map(|n| n.0)
        .collect();
    let has = |q: Quantity| found.contains(&q);
    let frequency = has(Quantity::Omega) || has(Quantity::Frequency);
    let pair = |k: ModulusKind| has(Quantity::Storage(k)) && has(Quantity::Loss(k));
    frequency && (pair(Young) || pair(ModulusKind::Shear))
}

/// Whether `cells`, the row below the header `names`, is a units row: no
/// number in it, and a unit known for its column under a column read.
pub(super) fn is_units_row(names: &[String], cells: &[String]) -> bool {
    if cells
        .iter()
        .any(|c| c.trim().replace(',', ".").parse::<f64>().is_ok())
    {
        return false;
    }
    names
        .iter()
        .zip(cells)
        .any(|(name, cell)| classify(name).is_some_and(|(q, _)| q.unit(unit_text(cell)).is_some()))
}

/// The columns of the header `names` on row `row` of `place`, with the
/// units of a units row `units` below it where the names give none (see
/// the module doc).
pub(super) fn columns(
    place: &Place,
    row: usize,
    names: Vec<String>,
    units: Option<(usize, &[String])>,
) -> Result<Header, IoError> {
    let mut found: Vec<(Quantity, Column)> = Vec::new();
    for (index, name) in names.iter().enumerate() {
        if let Some(contradiction) = Contradiction::of(name) {
            return Err(IoError::ContradictoryUnit {
                path: place.path.to_path_buf(),
                line: place.row(row),
                number: index + 1,
                contradiction,
            });
        }
        let Some((quantity, unit)) = classify(name) else {
            continue;
        };
        let from_row = units.and_then(|(units_row, cells)| {
            let written = unit_text(cells.get(index)?);
            (!written.is_empty() && written != "-").then_some((units_row, written))
        });
        let unknown = |cell, unit: &str| {
            IoError::DmaUnknownUnit(Box::new(DmaUnknownUnit {
                path: place.path.to_path_buf(),
                cell,
                column: name.clone(),
                quantity: quantity.unit_kind(),
                unit: unit.to_string(),
                known: quantity.known(),
            }))
        };
        let (factor, offset) = match (unit, from_row) {
            (Some(Ok(unit)), _) => unit,
            (Some(Err(unit)), _) => return Err(unknown(place.cell(row, index), &unit)),
            (None, Some((units_row, written))) => quantity
                .unit(written)
                .ok_or_else(|| unknown(place.cell(units_row, index), written))?,
            (None, None) => quantity.default_unit(),
        };
        let reference = place.column(index, name);
        found.push((
            quantity,
            Column {
                index,
                reference,
                factor,
                offset,
            },
        ));
    }
    assemble(place, row, names, found)
}

/// The header of the columns `found`: one of each quantity, the Young's
/// moduli before the shear ones.
fn assemble(
    place: &Place,
    row: usize,
    names: Vec<String>,
    found: Vec<(Quantity, Column)>,
) -> Result<Header, IoError> {
    let one = |label: &'static str, wanted: &[Quantity]| {
        let all: Vec<&Column> = found
            .iter()
            .filter(|(q, _)| wanted.contains(q))
            .map(|(_, c)| c)
            .collect();
        match all.as_slice() {
            [a, b, ..] => Err(IoError::DuplicateQuantity(Box::new(DuplicateQuantity {
                path: place.path.to_path_buf(),
                line: place.row(row),
                quantity: label,
                first: a.reference.clone(),
                second: b.reference.clone(),
            }))),
            _ => Ok(all.first().map(|c| (*c).clone())),
        }
    };
    let Some(omega) = one("frequency", &[Quantity::Omega, Quantity::Frequency])? else {
        return Err(IoError::NoFrequencyColumn {
            path: place.path.to_path_buf(),
            header: names,
        });
    };
    let young = (
        one(E_STORAGE, &[Quantity::Storage(Young)])?,
        one(E_LOSS, &[Quantity::Loss(Young)])?,
    );
    let shear = (
        one(G_STORAGE, &[Quantity::Storage(Shear)])?,
        one(G_LOSS, &[Quantity::Loss(Shear)])?,
    );
    let both = young.0.is_some() && young.1.is_some() && shear.0.is_some() && shear.1.is_some();
    let (kind, storage, loss) = match (young, shear) {
        ((Some(s), Some(l)), _) => (Young, s, l),
        (_, (Some(s), Some(l))) => (Shear, s, l),
        ((s, l), (gs, gl)) => {
            // Name what is missing of the kind the file started to give.
            let absent = |pair: [(bool, &'static str); 2]| {
                pair.iter()
                    .filter(|(present, _)| !present)
                    .map(|(_, n)| *n)
                    .collect::<Vec<_>>()
                    .join(" and ")
            };
            let missing = if s.is_some() || l.is_some() {
                absent([(s.is_some(), E_STORAGE), (l.is_some(), E_LOSS)])
            } else if gs.is_some() || gl.is_some() {
                absent([(gs.is_some(), G_STORAGE), (gl.is_some(), G_LOSS)])
            } else {
                format!("{E_STORAGE} and {E_LOSS} (or {G_STORAGE} and {G_LOSS})")
            };
            return Err(IoError::NoModulusColumns {
                path: place.path.to_path_buf(),
                missing,
                header: names,
            });
        }
    };
    let temperature = one("temperature", &[Quantity::Temperature])?;
    let step = one("step", &[Quantity::Step])?;
    Ok(Header {
        names,
        both,
        kind,
        omega,
        storage,
        loss,
        temperature,
        step,
    })
}
