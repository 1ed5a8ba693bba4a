//! The column vocabulary of DMA tables, defined once for every source of
//! rows ([`super::header`] assembles a header from it): which quantity a
//! column name means and the factor and offset of each unit to SI (rad/s,
//! Pa, rad, Pa·s, °C).
//!
//! | quantity    | names (case-insensitive but `T`, `E`, `G`)          | units (default first) |
//! |-------------|------------------------------------------------------|-----------------------|
//! | frequency   | `f`, `freq`, `frequency`; `omega`, `ω`, `angular frequency` | Hz, kHz, mHz (f); rad/s (ω) |
//! | storage     | `E_storage`, `E_stor`, `E'`; `G_storage`, `G'`; `Storage Modulus` (kind unsaid) | Pa, kPa, MPa, GPa, N/mm² |
//! | loss        | `E_loss`, `E''`; `G_loss`, `G''`; `Loss Modulus`      | as storage |
//! | complex     | `|E*|`, `E*`, `|G*|`, `G*`, `Complex Modulus`         | as storage |
//! | phase δ     | `Phase angle`, `phase`, `delta`, `δ`                  | °, rad |
//! | tan δ       | `tan(delta)`, `tan delta`, `tan_delta`, `loss factor` | - |
//! | viscosity   | `η*′`, `η'`; `η*″`, `η''`; `|η*|`, `Complex Viscosity` | Pa·s, mPa·s, kPa·s, MPa·s |
//! | temperature | `T`, `temp`, `temperature`                            | °C, K, °F |
//! | step        | `Step`, `Set`, `Segment`                              | a label |
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, Ch. 1 (the complex modulus, phase angle and complex viscosity).

use std::f64::consts::PI;

use crate::units::{
    ANGLE_UNITS, FREQUENCY_UNITS, MODULUS_UNITS, TEMPERATURE_UNITS, VISCOSITY_UNITS, angle_unit,
    frequency_unit, modulus_unit, temperature_unit, viscosity_unit,
};

use super::point::ModulusKind::{self, Shear, Young};
use crate::fit_dir::columns::{E_LOSS, E_STORAGE, OMEGA, T};

use crate::columns::{F, G_LOSS, G_STORAGE};

/// What a column holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Quantity {
    /// Angular frequency (default rad/s).
    Omega,
    /// Frequency (default Hz).
    Frequency,
    /// E′ or G′; `None`: the name does not say which (`Storage Modulus`).
    Storage(Option<ModulusKind>),
    /// E″ or G″.
    Loss(Option<ModulusKind>),
    /// |E*| or |G*|.
    Complex(Option<ModulusKind>),
    /// The phase angle δ (default degrees).
    Phase,
    /// tan δ.
    TanDelta,
    /// η′ (shear, Pa·s).
    ViscosityStorage,
    /// η″.
    ViscosityLoss,
    /// |η*|.
    ViscosityComplex,
    Temperature,
    /// The step, set or segment of a temperature programme: a label.
    Step,
}

impl Quantity {
    /// The kind of unit, for messages.
    pub(super) fn unit_kind(self) -> &'static str {
        match self {
            Quantity::Omega | Quantity::Frequency => "a frequency",
            Quantity::Storage(_) | Quantity::Loss(_) | Quantity::Complex(_) => "a modulus",
            Quantity::Phase => "an angle",
            Quantity::TanDelta => "a ratio",
            Quantity::ViscosityStorage | Quantity::ViscosityLoss | Quantity::ViscosityComplex => {
                "a viscosity"
            }
            Quantity::Temperature => "a temperature",
            Quantity::Step => "a step",
        }
    }

    /// A modulus (storage, loss or complex), whose unit `--units` states
    /// where the file gives none.
    pub(super) fn is_modulus(self) -> bool {
        matches!(
            self,
            Quantity::Storage(_) | Quantity::Loss(_) | Quantity::Complex(_)
        )
    }

    /// The units known, for messages.
    pub(super) fn known(self) -> &'static str {
        match self {
            Quantity::Omega | Quantity::Frequency => FREQUENCY_UNITS,
            Quantity::Storage(_) | Quantity::Loss(_) | Quantity::Complex(_) => MODULUS_UNITS,
            Quantity::Phase => ANGLE_UNITS,
            Quantity::TanDelta => "-, 1",
            Quantity::ViscosityStorage | Quantity::ViscosityLoss | Quantity::ViscosityComplex => {
                VISCOSITY_UNITS
            }
            Quantity::Temperature => TEMPERATURE_UNITS,
            Quantity::Step => "none",
        }
    }

    /// The factor and offset to SI of the default unit.
    pub(super) fn default_unit(self) -> (f64, f64) {
        match self {
            Quantity::Frequency => (2.0 * PI, 0.0),
            Quantity::Phase => (PI / 180.0, 0.0),
            _ => (1.0, 0.0),
        }
    }

    /// The factor and offset to SI (rad/s, Pa, °C) of `unit` as written
    /// in brackets, a units row or (`rad_s`) a CSV suffix, from the one
    /// table of units ([`crate::units`]).
    pub(super) fn unit(self, unit: &str) -> Option<(f64, f64)> {
        let factor = |f: Option<f64>| f.map(|f| (f, 0.0));
        match self {
            Quantity::Omega => factor(frequency_unit(unit, true)),
            Quantity::Frequency => factor(frequency_unit(unit, false)),
            Quantity::Storage(_) | Quantity::Loss(_) | Quantity::Complex(_) => {
                factor(modulus_unit(unit).map(|(_, pascals)| pascals))
            }
            Quantity::Phase => factor(angle_unit(unit)),
            Quantity::TanDelta => matches!(unit.trim(), "-" | "1" | "").then_some((1.0, 0.0)),
            Quantity::ViscosityStorage | Quantity::ViscosityLoss | Quantity::ViscosityComplex => {
                factor(viscosity_unit(unit))
            }
            Quantity::Temperature => temperature_unit(unit).map(|u| u.conversion.factor_offset()),
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
    (E_STORAGE, Quantity::Storage(Some(Young)), &MODULUS_SUFFIXES),
    (E_LOSS, Quantity::Loss(Some(Young)), &MODULUS_SUFFIXES),
    (G_STORAGE, Quantity::Storage(Some(Shear)), &MODULUS_SUFFIXES),
    (G_LOSS, Quantity::Loss(Some(Shear)), &MODULUS_SUFFIXES),
    (T, Quantity::Temperature, &["C", "K", "F"]),
];

const MODULUS_SUFFIXES: [&str; 4] = ["Pa", "kPa", "MPa", "GPa"];

/// The names instruments and tools write (lower case, primes as `'`, no
/// spaces).
const ALIASES: [(&str, Quantity); 59] = [
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
    ("angularfreq", Quantity::Omega),
    ("e'", Quantity::Storage(Some(Young))),
    ("e''", Quantity::Loss(Some(Young))),
    ("g'", Quantity::Storage(Some(Shear))),
    ("g''", Quantity::Loss(Some(Shear))),
    ("temp", Quantity::Temperature),
    ("temperature", Quantity::Temperature),
    ("temperatur", Quantity::Temperature),
    ("e_storage", Quantity::Storage(Some(Young))),
    ("e_loss", Quantity::Loss(Some(Young))),
    ("e_stor", Quantity::Storage(Some(Young))),
    ("g_stor", Quantity::Storage(Some(Shear))),
    ("storagemodulus", Quantity::Storage(None)),
    ("lossmodulus", Quantity::Loss(None)),
    ("tensilestoragemodulus", Quantity::Storage(Some(Young))),
    ("tensilelossmodulus", Quantity::Loss(Some(Young))),
    ("shearstoragemodulus", Quantity::Storage(Some(Shear))),
    ("shearlossmodulus", Quantity::Loss(Some(Shear))),
    ("complexmodulus", Quantity::Complex(None)),
    ("|e*|", Quantity::Complex(Some(Young))),
    ("e*", Quantity::Complex(Some(Young))),
    ("|g*|", Quantity::Complex(Some(Shear))),
    ("g*", Quantity::Complex(Some(Shear))),
    ("complexshearmodulus", Quantity::Complex(Some(Shear))),
    ("phaseangle", Quantity::Phase),
    ("phase", Quantity::Phase),
    ("phaseshift", Quantity::Phase),
    ("delta", Quantity::Phase),
    ("δ", Quantity::Phase),
    ("tan(delta)", Quantity::TanDelta),
    ("tandelta", Quantity::TanDelta),
    ("tan_delta", Quantity::TanDelta),
    ("tanδ", Quantity::TanDelta),
    ("tan(δ)", Quantity::TanDelta),
    ("lossfactor", Quantity::TanDelta),
    ("losstangent", Quantity::TanDelta),
    ("complexviscosity", Quantity::ViscosityComplex),
    ("|η*|", Quantity::ViscosityComplex),
    ("η*", Quantity::ViscosityComplex),
    ("|eta*|", Quantity::ViscosityComplex),
    ("η'", Quantity::ViscosityStorage),
    ("η*'", Quantity::ViscosityStorage),
    ("eta'", Quantity::ViscosityStorage),
    ("dynamicviscosity", Quantity::ViscosityStorage),
    ("η''", Quantity::ViscosityLoss),
    ("η*''", Quantity::ViscosityLoss),
    ("eta''", Quantity::ViscosityLoss),
];

/// What a header cell names: the quantity and the unit its name gives
/// (`None`: none given; `Some(Err(unit))`: a unit not known).
pub(super) type Named = (Quantity, Option<Result<(f64, f64), String>>);

/// What the header cell `raw` names, if anything.
pub(super) fn classify(raw: &str) -> Option<Named> {
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
    // A name with brackets of its own (`tan(delta)`) before a unit in
    // brackets (`f (Hz)`).
    if let Some(quantity) = alias(raw) {
        return Some((quantity, None));
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
