//! The units of measured-data columns (docs/ARCHITECTURE.md, "Contract",
//! "Measured data") and their conversion to SI: speeds as a length per a
//! time (`mm/s`, `µm/s`, `m s-1`, `mm·s⁻¹`, `m/min`, `mm per s`; lengths m,
//! cm, mm, µm, nm, km; times s, ms, min, h), temperatures in °C, K or °F,
//! a friction coefficient in %. Powers of ten are applied to the decimal
//! text, so that 0.0123 mm/s becomes the f64 nearest 1.23e-5 m/s, rounded
//! once; temperatures are rounded to 1e-9 K, so that 293.15 K is 20 °C.

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
pub(super) fn speed_unit(unit: &str) -> Option<Unit> {
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
pub(super) fn speed_from_parts(length: &str, time: &str) -> Option<Unit> {
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
pub(super) fn time_unit(time: &str) -> Option<(i32, f64, &'static str)> {
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
pub(super) fn percent() -> Unit {
    Unit {
        label: "%".into(),
        conversion: Conversion::Scale {
            pow10: -2,
            divisor: 1.0,
        },
    }
}

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
}
