//! The header of a DMA table (docs/ARCHITECTURE.md, "Contract", "DMA
//! files"): which column holds which quantity, in which unit. One
//! vocabulary for every source of rows — CSV text ([`super::csv_form`])
//! and a workbook's sheet ([`super::sheet`]) — so that a column name means
//! the same wherever it is written.
//!
//! The names and units are [`super::vocabulary`]'s. The moduli come as
//! E′ and E″ (or G′, G″) or in a form converted exactly at each ω
//! ([`super::moduli::Moduli`]: |M*| with δ or tan δ, M′ with tan δ, η′ and
//! η″, |η*| with δ or tan δ).
//!
//! A unit is given in one of three ways: a suffix after an underscore
//! (`f_Hz`, `omega_rad_s`, `E_loss_MPa`, `T_K`; the CSV spellings, case as
//! written), in brackets after the name (`E' [MPa]`, `f (Hz)`), or in a
//! units row right below the header (`[Hz]`, `[°C]`, `[MPa]`, `[-]`, as the
//! Netzsch/GABO Eplexor "Excel Export" writes it) for the columns whose
//! names carry none. Without one a column is in the default unit. Primes
//! may be typed as `'`, `′`, `’`, `"` or `″`; names other than `T` compare
//! case-insensitively (a lone lowercase `t` is time). Other columns
//! (`t [s]`, `Normal force`) are ignored.
//!
//! Refused, naming the columns: two columns for one quantity, since which
//! one is meant is a guess and a factor 2π or 10⁶ rides on it; the
//! contradictory `omega_Hz` or `f_rad_s`; a unit not known.

use std::path::Path;

use super::form::{FieldNames, FormRead, Place, RawPoint};
use super::moduli::Moduli;
use super::point::ModulusKind::{self, Shear, Young};
use super::vocabulary::{Quantity, classify};
use crate::csv_columns::dma_number;
use crate::data::cell::{Cell, parse_number};
use crate::error::{ColumnRef, Contradiction, IoError};
use crate::fit_dir::columns::{E_LOSS, E_STORAGE};
pub use crate::units::modulus_unit;

use crate::columns::{G_LOSS, G_STORAGE};

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
    /// The number in `field` of this column on line `line`, with a decimal
    /// comma where `decimal_comma` allows one: the one reading of a DMA CSV
    /// cell, for frequency sweeps and relaxation runs alike.
    pub(crate) fn number(
        &self,
        path: &Path,
        line: usize,
        field: &str,
        decimal_comma: bool,
    ) -> Result<f64, IoError> {
        match parse_number(&Cell::text(field), decimal_comma) {
            Ok(Some(number)) => Ok(number.value),
            // The error as for any cell that is not a finite number.
            _ => dma_number(path, line, || self.reference.clone(), field),
        }
    }

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
    /// The first modulus column ([`Moduli`]: M′, |M*|, η′ or |η*|).
    pub storage: Column,
    /// The second (M″, δ, tan δ or η″).
    pub loss: Column,
    /// How the two become M′ and M″.
    pub moduli: Moduli,
    pub temperature: Option<Column>,
    /// A step (set, segment) column: which points form one isotherm.
    pub step: Option<Column>,
    /// What the reader should say of how the header was read: the unit
    /// assumed for moduli or δ without one, the conversion, columns
    /// named twice.
    pub notes: Vec<String>,
    /// What it assumed: the kind of moduli whose names do not say it.
    pub warnings: Vec<String>,
}

impl Header {
    /// What a form read under this header: `points` (at least one, the
    /// two modulus columns' values as read, made M′ and M″ here) and the
    /// `warnings` so far.
    pub fn form(
        &self,
        path: &Path,
        mut points: Vec<RawPoint>,
        mut warnings: Vec<String>,
    ) -> Result<FormRead, IoError> {
        if points.is_empty() {
            return Err(err!("{}: no data rows below the header", path.display()));
        }
        for p in &mut points {
            (p.storage, p.loss) = self.moduli.convert(p.omega, p.storage, p.loss);
        }
        warnings.extend(
            self.warnings
                .iter()
                .map(|w| format!("{}: {w}", path.display())),
        );
        Ok(FormRead {
            points,
            kind: self.kind,
            names: FieldNames {
                omega: self.omega.reference.clone(),
                storage: self.storage.reference.clone(),
                loss: self.loss.reference.clone(),
            },
            warnings,
            preamble: Vec::new(),
        })
    }

    /// The notes, each behind the file's name.
    pub fn notes(&self, path: &Path) -> impl Iterator<Item = String> {
        self.notes
            .iter()
            .map(move |n| format!("{}: {n}", path.display()))
    }
}

/// The quantities `names` (a row's cells) name.
fn quantities(names: &[String]) -> Vec<Quantity> {
    names
        .iter()
        .filter_map(|n| classify(n))
        .map(|n| n.0)
        .collect()
}

/// Whether `names` (a row's cells) name a frequency and the moduli in one
/// of the forms [`Moduli`] lists: the header of a sheet, found among its
/// first rows.
pub(super) fn is_header(names: &[String]) -> bool {
    let found = quantities(names);
    let has = |q: Quantity| found.contains(&q);
    let any = |f: fn(Option<ModulusKind>) -> Quantity| {
        [Some(Young), Some(Shear), None]
            .into_iter()
            .any(|k| has(f(k)))
    };
    let frequency = has(Quantity::Omega) || has(Quantity::Frequency);
    let pair = |k: Option<ModulusKind>| has(Quantity::Storage(k)) && has(Quantity::Loss(k));
    let angle = has(Quantity::Phase) || has(Quantity::TanDelta);
    let moduli = pair(Some(Young))
        || pair(Some(Shear))
        || pair(None)
        || (any(Quantity::Complex) && angle)
        || (any(Quantity::Storage) && has(Quantity::TanDelta))
        || (has(Quantity::ViscosityStorage) && has(Quantity::ViscosityLoss))
        || (has(Quantity::ViscosityComplex) && angle);
    frequency && moduli
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

/// What the reader is told beyond the header: the modulus kind asked for
/// (`--dma-modulus`) and the unit of moduli the file gives none for
/// (`--units`: name, pascals).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Told {
    pub kind: Option<ModulusKind>,
    pub modulus_unit: Option<(&'static str, f64)>,
}

/// The columns of the header `names` on row `row` of `place`, with the
/// units of a units row `units` below it where the names give none (see
/// the module doc).
pub(super) fn columns(
    place: &Place,
    row: usize,
    names: Vec<String>,
    units: Option<(usize, &[String])>,
    told: Told,
) -> Result<Header, IoError> {
    let mut found: Vec<(Quantity, Column)> = Vec::new();
    let mut unitless: Vec<Quantity> = Vec::new();
    for (index, name) in names.iter().enumerate() {
        if let Some(contradiction) = Contradiction::of(name) {
            return Err(err!(
                "{}, {line}: column {number} ({}): {contradiction}: name it f_Hz if it holds hertz \
         or omega_rad_s if it holds rad/s",
                place.path.display(),
                contradiction.column(),
                line = place.row(row),
                number = index + 1
            ));
        }
        let Some((quantity, unit)) = classify(name) else {
            continue;
        };
        let from_row = units.and_then(|(units_row, cells)| {
            let written = unit_text(cells.get(index)?);
            (!written.is_empty() && written != "-").then_some((units_row, written))
        });
        let unknown = |cell, unit: &str| {
            err!(
                "{}, {cell}: column {column:?}: unit {unit:?} not known for {quantity}; known: {known}",
                place.path.display(),
                column = name,
                known = quantity.known(),
                quantity = quantity.unit_kind(),
            )
        };
        let (factor, offset) = match (unit, from_row) {
            (Some(Ok(unit)), _) => unit,
            (Some(Err(unit)), _) => return Err(unknown(place.cell(row, index), &unit)),
            (None, Some((units_row, written))) => quantity
                .unit(written)
                .ok_or_else(|| unknown(place.cell(units_row, index), written))?,
            (None, None) => {
                unitless.push(quantity);
                match told.modulus_unit {
                    Some((_, pascals)) if quantity.is_modulus() => (pascals, 0.0),
                    _ => quantity.default_unit(),
                }
            }
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
    let mut header = assemble(place, row, names, found, told.kind)?;
    let moduli_unitless = unitless.iter().any(|q| q.is_modulus())
        && header.moduli != Moduli::ViscosityParts
        && header.moduli != Moduli::ViscosityAbsPhase
        && header.moduli != Moduli::ViscosityAbsTan;
    match (moduli_unitless, told.modulus_unit) {
        (true, Some((name, _))) => header.notes.push(format!(
            "moduli without a unit in the file: read in {name}, as stated"
        )),
        (true, None) => header.notes.push(
            "moduli without a unit in the file: read in Pa (give --units to state another)"
                .to_string(),
        ),
        (false, Some((name, _))) => header.warnings.push(format!(
            "the file states the unit of its moduli: the unit given, {name}, is not used"
        )),
        (false, None) => {}
    }
    if unitless.contains(&Quantity::Phase)
        && matches!(header.moduli, Moduli::AbsPhase | Moduli::ViscosityAbsPhase)
    {
        header.notes.push(
            "phase angle δ without a unit: read in degrees (write `[rad]` for radians)".into(),
        );
    }
    Ok(header)
}

/// The header of the columns `found`: one of each quantity, the Young's
/// moduli before the shear ones, M′ and M″ before the forms converted
/// ([`Moduli`]); `requested` the kind of moduli whose names do not say.
fn assemble(
    place: &Place,
    row: usize,
    names: Vec<String>,
    found: Vec<(Quantity, Column)>,
    requested: Option<ModulusKind>,
) -> Result<Header, IoError> {
    let repeated = std::cell::RefCell::new(Vec::new());
    let one = |label: &'static str, wanted: &[Quantity]| {
        let all: Vec<&Column> = found
            .iter()
            .filter(|(q, _)| wanted.contains(q))
            .map(|(_, c)| c)
            .collect();
        // One name written twice (an export's two `Temp` columns) is one
        // quantity recorded twice: the first is read, and said.
        let same_name = |a: &Column, b: &Column| {
            names[a.index]
                .trim()
                .eq_ignore_ascii_case(names[b.index].trim())
        };
        match all.as_slice() {
            [a, rest @ ..] if !rest.is_empty() && rest.iter().all(|b| same_name(a, b)) => {
                repeated.borrow_mut().push(format!(
                    "{} and {} have one name: the first is read",
                    a.reference,
                    rest.iter()
                        .map(|b| b.reference.to_string())
                        .collect::<Vec<_>>()
                        .join(", ")
                ));
                Ok(Some((*a).clone()))
            }
            [a, b, ..] => Err(err!(
                "{}, {line}: two {quantity} columns, {first} and {second}: keep one{}",
                place.path.display(),
                if label == "frequency" {
                    " (f in Hz or omega in rad/s)"
                } else {
                    ""
                },
                first = a.reference,
                line = place.row(row),
                quantity = label,
                second = b.reference
            )),
            _ => Ok(all.first().map(|c| (*c).clone())),
        }
    };
    let Some(omega) = one("frequency", &[Quantity::Omega, Quantity::Frequency])? else {
        return Err(err!(
            "{}: no frequency column: need `omega` (rad/s) or `f` (Hz), optionally with a unit \
         suffix such as omega_rad_s or f_Hz (the header has: {}); stress-relaxation data (`t` \
         and `E_relax` or `G_relax`) are read by `rollfit master` and `rollfit compare`",
            place.path.display(),
            names.join(", ")
        ));
    };
    let young = (
        one(E_STORAGE, &[Quantity::Storage(Some(Young))])?,
        one(E_LOSS, &[Quantity::Loss(Some(Young))])?,
    );
    let shear = (
        one(G_STORAGE, &[Quantity::Storage(Some(Shear))])?,
        one(G_LOSS, &[Quantity::Loss(Some(Shear))])?,
    );
    let both = young.0.is_some() && young.1.is_some() && shear.0.is_some() && shear.1.is_some();
    let mut notes = Vec::new();
    let chosen = choose(&found, &young, &shear, &mut notes);
    let Some((kind, moduli, storage, loss)) = chosen else {
        return Err(no_moduli(place, names, &young, &shear));
    };
    let mut warnings = Vec::new();
    let kind = resolve_kind(kind, requested, &mut notes, &mut warnings);
    if let Some(said) = moduli.said() {
        let of = |c: &Column| c.reference.to_string();
        notes.push(format!(
            "{} moduli {said} ({} and {})",
            kind.name(),
            of(&storage),
            of(&loss)
        ));
    }
    let temperature = one("temperature", &[Quantity::Temperature])?;
    let step = one("step", &[Quantity::Step])?;
    notes.extend(repeated.into_inner());
    Ok(Header {
        names,
        both,
        kind,
        omega,
        storage,
        loss,
        moduli,
        temperature,
        step,
        notes,
        warnings,
    })
}

/// The kind of moduli: the names', else the one requested (noted), else
/// Young's (a warning: the names do not say).
fn resolve_kind(
    named: Option<ModulusKind>,
    requested: Option<ModulusKind>,
    notes: &mut Vec<String>,
    warnings: &mut Vec<String>,
) -> ModulusKind {
    match (named, requested) {
        (Some(k), _) => k,
        (None, Some(k)) => {
            notes.push(format!("moduli read as {} moduli, as stated", k.name()));
            k
        }
        (None, None) => {
            warnings.push(
                "the column names do not say whether the moduli are Young's (E) or shear (G): \
                 read as Young's (give --dma-modulus shear if they are shear moduli)"
                    .to_string(),
            );
            Young
        }
    }
}

/// The refusal of a header without moduli in any form, naming what is
/// missing of the kind the file started to give.
fn no_moduli(
    place: &Place,
    names: Vec<String>,
    young: &(Option<Column>, Option<Column>),
    shear: &(Option<Column>, Option<Column>),
) -> IoError {
    let (s, l) = young;
    let (gs, gl) = shear;
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
    err!(
        "{}: no {missing} column: need storage and loss moduli as E_storage, E_loss (Young's) or \
         G_storage, G_loss (shear), in Pa or with a unit suffix such as G_storage_Pa (the header \
         has: {})",
        place.path.display(),
        names.join(", ")
    )
}

/// A modulus pair the header gives: the kind its names say (None: they do
/// not), the form, and its two columns.
type Chosen = (Option<ModulusKind>, Moduli, Column, Column);

/// The moduli of the columns `found`: E′ and E″ (then G′, G″, then
/// unsaid), else the converted forms in the order of [`Moduli`]. Of a
/// quantity only a converted form reads, the first column is used (noted
/// in `notes` when there are more).
fn choose(
    found: &[(Quantity, Column)],
    young: &(Option<Column>, Option<Column>),
    shear: &(Option<Column>, Option<Column>),
    notes: &mut Vec<String>,
) -> Option<Chosen> {
    // The quantities only the converted forms read: the first column of
    // each (a rheometer writes δ in two columns now and then).
    let mut first = |wanted: &[Quantity]| -> Option<Column> {
        let all: Vec<&Column> = found
            .iter()
            .filter(|(q, _)| wanted.contains(q))
            .map(|(_, c)| c)
            .collect();
        if let [a, b, ..] = all.as_slice() {
            notes.push(format!(
                "{} and {} name one quantity: the first is read",
                a.reference, b.reference
            ));
        }
        all.first().map(|c| (*c).clone())
    };
    let plain = (
        first(&[Quantity::Storage(None)]),
        first(&[Quantity::Loss(None)]),
    );
    let complex = [Some(Young), Some(Shear), None]
        .into_iter()
        .find_map(|k| first(&[Quantity::Complex(k)]).map(|c| (k, c)));
    let phase = first(&[Quantity::Phase]);
    let tan = first(&[Quantity::TanDelta]);
    let eta = (
        first(&[Quantity::ViscosityStorage]),
        first(&[Quantity::ViscosityLoss]),
        first(&[Quantity::ViscosityComplex]),
    );
    let storage_any = young
        .0
        .clone()
        .map(|c| (Some(Young), c))
        .or_else(|| shear.0.clone().map(|c| (Some(Shear), c)))
        .or_else(|| plain.0.clone().map(|c| (None, c)));
    match (young, shear, &plain) {
        ((Some(s), Some(l)), _, _) => Some((Some(Young), Moduli::Parts, s.clone(), l.clone())),
        (_, (Some(s), Some(l)), _) => Some((Some(Shear), Moduli::Parts, s.clone(), l.clone())),
        (_, _, (Some(s), Some(l))) => Some((None, Moduli::Parts, s.clone(), l.clone())),
        _ => match (complex, phase, tan, storage_any, eta) {
            (Some((k, c)), Some(p), _, _, _) => Some((k, Moduli::AbsPhase, c, p)),
            (Some((k, c)), None, Some(t), _, _) => Some((k, Moduli::AbsTan, c, t)),
            (None, _, Some(t), Some((k, s)), _) => Some((k, Moduli::StorageTan, s, t)),
            (None, _, _, _, (Some(a), Some(b), _)) => {
                Some((Some(Shear), Moduli::ViscosityParts, a, b))
            }
            (None, Some(p), _, _, (_, _, Some(e))) => {
                Some((Some(Shear), Moduli::ViscosityAbsPhase, e, p))
            }
            (None, None, Some(t), None, (_, _, Some(e))) => {
                Some((Some(Shear), Moduli::ViscosityAbsTan, e, t))
            }
            _ => None,
        },
    }
}
