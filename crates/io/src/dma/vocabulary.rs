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
            Quantity::Omega | Quantity::Frequency => "Hz, kHz, mHz, rad/s",
            Quantity::Storage(_) | Quantity::Loss(_) | Quantity::Complex(_) => {
                "Pa, kPa, MPa, GPa, N/mm²"
            }
            Quantity::Phase => "°, deg, rad",
            Quantity::TanDelta => "-, 1",
            Quantity::ViscosityStorage | Quantity::ViscosityLoss | Quantity::ViscosityComplex => {
                "Pa·s, mPa·s, kPa·s, MPa·s"
            }
            Quantity::Temperature => "°C, K, °F",
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
    /// in brackets, a units row or (`rad_s`) a CSV suffix.
    pub(super) fn unit(self, unit: &str) -> Option<(f64, f64)> {
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
            Quantity::Storage(_) | Quantity::Loss(_) | Quantity::Complex(_) => {
                modulus_unit(unit).map(|(_, pascals)| (pascals, 0.0))
            }
            Quantity::Phase => match unit {
                "°" | "deg" | "degree" | "degrees" | "º" => Some((PI / 180.0, 0.0)),
                "rad" => Some((1.0, 0.0)),
                _ => None,
            },
            Quantity::TanDelta => matches!(unit, "-" | "1" | "").then_some((1.0, 0.0)),
            Quantity::ViscosityStorage | Quantity::ViscosityLoss | Quantity::ViscosityComplex => {
                let pascal_seconds = unit
                    .strip_suffix('s')?
                    .trim_end_matches(['·', ' ', '.', '*', '⋅']);
                modulus_unit(pascal_seconds).map(|(_, pascals)| (pascals, 0.0))
            }
            Quantity::Temperature => {
                crate::data::units::temperature_unit(unit).map(|u| u.conversion.factor_offset())
            }
            // A label; whatever a units row writes above it.
            Quantity::Step => Some((1.0, 0.0)),
        }
    }
}

/// Pascals per `unit` of a modulus (`Pa`, `kPa`, `MPa`, `GPa`, `N/mm²`):
/// the one table of modulus units, which `--units` reads too.
pub fn modulus_unit(unit: &str) -> Option<(&'static str, f64)> {
    match unit.trim() {
        "Pa" | "N/m²" | "N/m2" | "N/m^2" => Some(("Pa", 1.0)),
        "kPa" => Some(("kPa", 1e3)),
        "MPa" | "N/mm²" | "N/mm2" | "N/mm^2" => Some(("MPa", 1e6)),
        "GPa" => Some(("GPa", 1e9)),
        _ => None,
    }
}

/// 1/Pa per `unit` of a compliance: the reciprocal of a modulus unit
/// (`1/MPa`, `MPa^-1`, `MPa⁻¹`, `MPa-1`) or an area per force (`m²/N`,
/// `mm²/N`, `µm²/N`, and `cm²/dyn`, the CGS unit of the classic creep
/// literature: 1 dyn/cm² = 0.1 Pa). The table of creep-compliance units.
pub fn compliance_unit(unit: &str) -> Option<f64> {
    let unit = unit.trim();
    let per = |modulus: &str| modulus_unit(modulus).map(|(_, pascals)| 1.0 / pascals);
    if let Some(modulus) = unit.strip_prefix("1/") {
        return per(modulus);
    }
    for power in ["^-1", "⁻¹", "-1"] {
        if let Some(modulus) = unit.strip_suffix(power) {
            return per(modulus);
        }
    }
    let area = unit
        .strip_suffix("/N")
        .map(|a| (a, 1.0))
        .or_else(|| unit.strip_suffix("/dyn").map(|a| (a, 1e5)))?;
    let square = match area.0.trim_end_matches(['²', '2', '^']) {
        "m" => 1.0,
        "cm" => 1e-4,
        "mm" => 1e-6,
        "µm" | "μm" | "um" => 1e-12,
        _ => return None,
    };
    Some(square * area.1)
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

#[cfg(test)]
mod tests {
    use super::compliance_unit;

    /// Each spelling of a compliance unit against its value in 1/Pa worked
    /// out by hand; a modulus unit or nonsense is none.
    #[test]
    fn compliance_units_in_reciprocal_pascals() {
        for (unit, per_pascal) in [
            ("1/Pa", 1.0),
            ("1/kPa", 1e-3),
            ("1/MPa", 1e-6),
            ("MPa^-1", 1e-6),
            ("GPa⁻¹", 1e-9),
            ("Pa-1", 1.0),
            ("m²/N", 1.0),
            ("mm²/N", 1e-6),
            ("µm²/N", 1e-12),
            ("um2/N", 1e-12),
            // 1 dyn = 1e-5 N, 1 cm² = 1e-4 m².
            ("cm²/dyn", 10.0),
        ] {
            let found = compliance_unit(unit).unwrap_or_else(|| panic!("{unit}"));
            assert!((found / per_pascal - 1.0).abs() < 1e-15, "{unit}: {found}");
        }
        for unit in ["MPa", "Pa", "1/s", "km²/N", ""] {
            assert_eq!(compliance_unit(unit), None, "{unit}");
        }
    }
}
