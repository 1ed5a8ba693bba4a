//! The one table of units, for every reader (measured data, DMA CSV,
//! workbooks, TRIOS, relaxation and creep files, modulus tables;
//! docs/ARCHITECTURE.md, "Contract", "Measured data" and "DMA files"):
//! each quantity's spellings and their map to the unit rollfit computes in.
//!
//! | quantity             | spellings                                        | to |
//! |----------------------|--------------------------------------------------|----|
//! | speed                | a length (m, cm, mm, µm, nm, km) per a time: `mm/s`, `m s-1`, `mm·s⁻¹` | m/s |
//! | time                 | s, ms, min, h (and `sec`, `hour`, …)             | s |
//! | temperature          | °C, C, ℃, degC, celsius, K, kelvin, °F, F        | °C |
//! | frequency            | Hz, kHz, mHz, rad/s, 1/s (cycles for f, radians for ω) | rad/s |
//! | modulus              | Pa, kPa, MPa, GPa, N/mm², N/m²                   | Pa |
//! | creep compliance     | 1/MPa, MPa⁻¹, m²/N, µm²/N, cm²/dyn, …             | 1/Pa |
//! | phase angle          | °, deg, rad                                      | rad |
//! | viscosity            | Pa·s, mPa·s, kPa·s, MPa·s                         | Pa·s |
//! | friction coefficient | %                                                | 1 |
//!
//! Measured data apply powers of ten to the decimal text (0.0123 mm/s is
//! the f64 nearest 1.23e-5 m/s) and round temperatures to 1e-9 K (293.15 K
//! is 20 °C); DMA readers take a factor and an offset.

use std::f64::consts::PI;

/// How values in a unit become SI values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Conversion {
    /// × 10^pow10 / divisor (the power of ten is applied to the decimal
    /// text, so that e.g. 0.0123 mm/s is the f64 nearest 1.23e-5 m/s).
    Scale { pow10: i32, divisor: f64 },
    /// K → °C.
    Kelvin,
    /// °F → °C.
    Fahrenheit,
}

impl Conversion {
    pub const NONE: Conversion = Conversion::Scale {
        pow10: 0,
        divisor: 1.0,
    };

    pub fn is_identity(self) -> bool {
        self == Conversion::NONE
    }

    /// The conversion as a note says it: "×1e-3", "×1e-3/60", "−273.15".
    pub fn describe(self) -> String {
        match self {
            Conversion::Scale { pow10, divisor } => {
                let scale = if pow10 == 0 {
                    "1".to_string()
                } else {
                    format!("1e{pow10}")
                };
                if divisor == 1.0 {
                    format!("×{scale}")
                } else {
                    format!("×{scale}/{divisor}")
                }
            }
            Conversion::Kelvin => "−273.15".into(),
            Conversion::Fahrenheit => "(T − 32)·5/9".into(),
        }
    }

    /// The conversion as a factor and an offset, SI = value × factor +
    /// offset: for readers that convert a number, not its text.
    pub fn factor_offset(self) -> (f64, f64) {
        match self {
            Conversion::Scale { pow10, divisor } => (10f64.powi(pow10) / divisor, 0.0),
            Conversion::Kelvin => (1.0, -273.15),
            Conversion::Fahrenheit => (5.0 / 9.0, -32.0 * 5.0 / 9.0),
        }
    }

    /// Converts `value`, written as `text` (a decimal number with a point).
    pub fn apply(self, value: f64, text: &str) -> f64 {
        // Temperatures are rounded to 1e-9 K, so that 293.15 K is 20 °C and
        // not 19.999999999999977 (rows of one temperature stay equal).
        let round = |t: f64| (t * 1e9).round() / 1e9;
        match self {
            Conversion::Scale { pow10, divisor } => {
                shift_decimal(text, pow10).unwrap_or(value * 10f64.powi(pow10)) / divisor
            }
            Conversion::Kelvin => round(value - 273.15),
            Conversion::Fahrenheit => round((value - 32.0) * 5.0 / 9.0),
        }
    }
}

/// `text` × 10^pow10, rounded once: the exponent is shifted in the text.
fn shift_decimal(text: &str, pow10: i32) -> Option<f64> {
    if pow10 == 0 {
        return text.parse().ok();
    }
    let (mantissa, exponent) = match text.find(['e', 'E']) {
        Some(i) => (&text[..i], text[i + 1..].parse::<i32>().ok()?),
        None => (text, 0),
    };
    format!("{mantissa}e{}", exponent.checked_add(pow10)?)
        .parse()
        .ok()
}

/// A unit as understood.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Unit {
    /// As a note names it: "mm/s", "K".
    pub label: String,
    pub conversion: Conversion,
}

/// A speed unit: `mm/s`, `µm/s`, `m s-1`, `mm·s⁻¹`, `m/min`, `mm per s`.
pub(crate) fn speed_unit(unit: &str) -> Option<Unit> {
    let unit = unit
        .trim()
        .to_lowercase()
        .replace(['µ', 'μ'], "u")
        .replace('⁻', "-")
        .replace('¹', "1")
        .replace(['·', '*', '_'], " ");
    let (length, time) = if let Some((l, t)) = unit.split_once('/') {
        (l.trim().to_string(), t.trim().to_string())
    } else if let Some((l, t)) = unit.split_once(" per ") {
        (l.trim().to_string(), t.trim().to_string())
    } else {
        let rest = unit
            .strip_suffix("^-1")
            .or_else(|| unit.strip_suffix("-1"))?
            .trim_end();
        let rest = rest.replace('.', " ");
        let (l, t) = rest.rsplit_once(' ')?;
        (l.trim().to_string(), t.trim().to_string())
    };
    speed_from_parts(&length, &time)
}

/// The speed unit `length`/`time` (lower case, micro as "u").
pub(crate) fn speed_from_parts(length: &str, time: &str) -> Option<Unit> {
    let (length_pow10, length_label) = match length {
        "m" => (0, "m"),
        "cm" => (-2, "cm"),
        "mm" => (-3, "mm"),
        "um" | "micron" | "microns" | "micrometre" | "micrometer" => (-6, "µm"),
        "nm" => (-9, "nm"),
        "km" => (3, "km"),
        _ => return None,
    };
    let (time_pow10, divisor, time_label) = time_unit(time)?;
    Some(Unit {
        label: format!("{length_label}/{time_label}"),
        conversion: Conversion::Scale {
            pow10: length_pow10 + time_pow10,
            divisor,
        },
    })
}

/// A time unit (lower case): (power of ten, divisor, label) of 1/unit in
/// 1/s.
pub(crate) fn time_unit(time: &str) -> Option<(i32, f64, &'static str)> {
    Some(match time {
        "s" | "sec" | "second" | "seconds" => (0, 1.0, "s"),
        "ms" => (3, 1.0, "ms"),
        "min" | "minute" | "minutes" => (0, 60.0, "min"),
        "h" | "hr" | "hour" | "hours" => (0, 3600.0, "h"),
        _ => return None,
    })
}

/// A temperature unit: °C, C, ℃, degC, celsius, K, kelvin, °F, F: the one
/// table of temperature units, for measured data and DMA files alike.
pub(crate) fn temperature_unit(unit: &str) -> Option<Unit> {
    let unit: String = unit
        .trim()
        .to_lowercase()
        .replace("deg", "")
        .chars()
        .filter(|c| !(c.is_whitespace() || "°º_.".contains(*c)))
        .collect();
    let (label, conversion) = match unit.as_str() {
        "c" | "celsius" | "℃" => ("°C", Conversion::NONE),
        "k" | "kelvin" => ("K", Conversion::Kelvin),
        "f" | "fahrenheit" => ("°F", Conversion::Fahrenheit),
        _ => return None,
    };
    Some(Unit {
        label: label.into(),
        conversion,
    })
}

/// The percent unit of a friction coefficient.
pub(crate) fn percent() -> Unit {
    Unit {
        label: "%".into(),
        conversion: Conversion::Scale {
            pow10: -2,
            divisor: 1.0,
        },
    }
}

/// Seconds per `unit` of a time (the spellings of [`time_unit`]).
pub(crate) fn seconds_per(unit: &str) -> Option<f64> {
    let (pow10, divisor, _) = time_unit(&unit.trim().to_lowercase())?;
    Some(10f64.powi(-pow10) * divisor)
}

/// The temperature units known, for messages.
pub(crate) const TEMPERATURE_UNITS: &str = "°C, K, °F";

/// Radians per second per `unit` of a frequency: Hz, kHz, mHz, rad/s;
/// `1/s` is cycles per second for a frequency f and radians per second
/// for an angular frequency ω (`angular`).
pub(crate) fn frequency_unit(unit: &str, angular: bool) -> Option<f64> {
    let hertz = |scale: f64| Some(2.0 * PI * scale);
    match unit.trim() {
        "Hz" | "hz" => hertz(1.0),
        "kHz" | "khz" => hertz(1e3),
        "mHz" => hertz(1e-3),
        "rad/s" | "rad_s" | "rad s-1" | "rad·s⁻¹" | "rad s^-1" => Some(1.0),
        "1/s" | "s-1" | "s^-1" | "s⁻¹" if angular => Some(1.0),
        "1/s" | "s-1" | "s^-1" | "s⁻¹" => hertz(1.0),
        _ => None,
    }
}

/// The frequency units known, for messages.
pub(crate) const FREQUENCY_UNITS: &str = "Hz, kHz, mHz, rad/s";

/// Pascals per `unit` of a modulus (`Pa`, `kPa`, `MPa`, `GPa`, `N/mm²`),
/// with the unit's name; `--units` reads this table too.
pub fn modulus_unit(unit: &str) -> Option<(&'static str, f64)> {
    match unit.trim() {
        "Pa" | "N/m²" | "N/m2" | "N/m^2" => Some(("Pa", 1.0)),
        "kPa" => Some(("kPa", 1e3)),
        "MPa" | "N/mm²" | "N/mm2" | "N/mm^2" => Some(("MPa", 1e6)),
        "GPa" => Some(("GPa", 1e9)),
        _ => None,
    }
}

/// The modulus units known, for messages.
pub(crate) const MODULUS_UNITS: &str = "Pa, kPa, MPa, GPa, N/mm²";

/// 1/Pa per `unit` of a compliance: the reciprocal of a modulus unit
/// (`1/MPa`, `MPa^-1`, `MPa⁻¹`, `MPa-1`) or an area per force (`m²/N`,
/// `mm²/N`, `µm²/N`, and `cm²/dyn`, the CGS unit of the classic creep
/// literature: 1 dyn/cm² = 0.1 Pa).
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

/// Radians per `unit` of an angle: °, deg, rad.
pub(crate) fn angle_unit(unit: &str) -> Option<f64> {
    match unit.trim() {
        "°" | "deg" | "degree" | "degrees" | "º" => Some(PI / 180.0),
        "rad" => Some(1.0),
        _ => None,
    }
}

/// The angle units known, for messages.
pub(crate) const ANGLE_UNITS: &str = "°, deg, rad";

/// Pa·s per `unit` of a viscosity: a modulus unit or mPa, times seconds
/// (`Pa·s`, `mPa·s`, `kPa s`, `MPa.s`).
pub(crate) fn viscosity_unit(unit: &str) -> Option<f64> {
    let pressure = unit
        .trim()
        .strip_suffix('s')?
        .trim_end_matches(['·', ' ', '.', '*', '⋅']);
    match pressure {
        "mPa" => Some(1e-3),
        _ => modulus_unit(pressure).map(|(_, pascals)| pascals),
    }
}

/// The viscosity units known, for messages.
pub(crate) const VISCOSITY_UNITS: &str = "Pa·s, mPa·s, kPa·s, MPa·s";

#[cfg(test)]
mod tests {
    use super::*;

    fn scale(pow10: i32, divisor: f64) -> Conversion {
        Conversion::Scale { pow10, divisor }
    }

    #[test]
    fn conversions_are_rounded_once() {
        let mm = scale(-3, 1.0);
        assert_eq!(mm.apply(0.0123, "0.0123"), 1.23e-5);
        assert_eq!(mm.apply(1.5e-5, "1.5E-05"), 1.5e-8);
        assert_eq!(mm.apply(12.0, "+12"), 0.012);
        assert_eq!(scale(-3, 60.0).apply(6.0, "6"), 1e-4);
        assert_eq!(Conversion::Kelvin.apply(293.15, "293.15"), 20.0);
        assert_eq!(Conversion::Fahrenheit.apply(68.0, "68"), 20.0);
        assert_eq!(mm.describe(), "×1e-3");
        assert_eq!(scale(-3, 60.0).describe(), "×1e-3/60");
        assert_eq!(scale(0, 60.0).describe(), "×1/60");
        assert!(Conversion::NONE.is_identity());
    }

    #[test]
    fn every_quantity_has_its_factor() {
        assert_eq!(seconds_per("ms"), Some(1e-3));
        assert_eq!(seconds_per("min"), Some(60.0));
        assert_eq!(frequency_unit("kHz", false), Some(2e3 * PI));
        assert_eq!(frequency_unit("1/s", true), Some(1.0));
        assert_eq!(frequency_unit("1/s", false), Some(2.0 * PI));
        assert_eq!(viscosity_unit("mPa·s"), Some(1e-3));
        assert_eq!(viscosity_unit("kPa s"), Some(1e3));
        assert_eq!(angle_unit("deg"), Some(PI / 180.0));
        let fahrenheit = temperature_unit("°F").unwrap().conversion.factor_offset();
        assert_eq!(68.0 * fahrenheit.0 + fahrenheit.1, 20.0);
    }

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
