//! Column names and units of a measured-data header.
//!
//! A header cell is a name, optionally followed by a unit: in brackets or
//! parentheses (`velocity (mm/s)`, `speed [m/s]`, `v/(mm/s)`) or after the
//! name with a space, an underscore or "in" (`v_mm_s`, `speed um/s`,
//! `T_K`). Names are compared case-insensitively with spaces, underscores,
//! hyphens, dots and slashes alike (`Friction Coefficient`,
//! `friction_coefficient`); `µ` and `μ` (micro sign or Greek mu) read as
//! "mu" when alone and as the micro prefix before a unit (`µm/s`). One
//! exception to case-insensitivity: a lone lowercase `t` is time in most
//! lab files, so it is ignored unless it carries a temperature unit
//! (`t_C`, `t (°C)`); `T` is the temperature.

/// A quantity the data file gives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Quantity {
    Speed,
    Friction,
    Sigma,
    Temperature,
}

impl Quantity {
    /// In the order of the columns of a [`super::DataTable`].
    pub const ALL: [Quantity; 4] = [
        Quantity::Speed,
        Quantity::Friction,
        Quantity::Sigma,
        Quantity::Temperature,
    ];

    /// The canonical column name (docs/ARCHITECTURE.md, "Contract",
    /// "Measured data").
    pub fn key(self) -> &'static str {
        match self {
            Quantity::Speed => "v",
            Quantity::Friction => "mu",
            Quantity::Sigma => "sigma",
            Quantity::Temperature => "T",
        }
    }

    /// What the quantity is, for messages ("no speed column").
    pub fn what(self) -> &'static str {
        match self {
            Quantity::Speed => "speed",
            Quantity::Friction => "friction",
            Quantity::Sigma => "sigma (standard deviation of mu)",
            Quantity::Temperature => "temperature",
        }
    }

    /// The names understood, for messages.
    pub fn understood(self) -> &'static str {
        match self {
            Quantity::Speed => {
                "v, velocity, speed, rolling speed, with or without a unit: v, v_mm_s, \
                 velocity (mm/s), speed [m/s], …"
            }
            Quantity::Friction => "mu, µ, COF, friction coefficient, coefficient of friction, …",
            Quantity::Sigma => "sigma, std, sd, mu_std, sigma_mu, COF std, …",
            Quantity::Temperature => "T, temperature, T_C, T (°C), T_K, T [K], …",
        }
    }

    /// The SI unit of the values in a [`super::DataTable`].
    pub fn si_unit(self) -> &'static str {
        match self {
            Quantity::Speed => "m/s",
            Quantity::Temperature => "°C",
            Quantity::Friction | Quantity::Sigma => "",
        }
    }

    /// The units understood, for messages.
    pub fn units(self) -> &'static str {
        match self {
            Quantity::Speed => {
                "m/s, cm/s, mm/s, µm/s (um/s), nm/s, or any of these lengths per s, ms, min \
                 or h (mm/min, m/h); also written m s-1, mm·s⁻¹ or, after an underscore, v_mm_s"
            }
            Quantity::Temperature => "°C (C, degC, celsius), K (kelvin), °F (F, fahrenheit)",
            Quantity::Friction => "none (-, 1) or %",
            Quantity::Sigma => "none (-, 1)",
        }
    }

    fn aliases(self) -> &'static [&'static str] {
        match self {
            Quantity::Speed => &[
                "v",
                "vel",
                "velocity",
                "speed",
                "rolling_speed",
                "rolling_velocity",
            ],
            Quantity::Friction => &[
                "mu",
                "cof",
                "friction_coefficient",
                "friction_coeff",
                "coefficient_of_friction",
                "rolling_friction_coefficient",
                "coefficient_of_rolling_friction",
                "mu_measured",
                "mu_meas",
            ],
            Quantity::Sigma => &[
                "sigma",
                "std",
                "sd",
                "stdev",
                "std_dev",
                "standard_deviation",
                "mu_std",
                "mu_sd",
                "mu_stdev",
                "mu_sigma",
                "mu_err",
                "sigma_mu",
                "std_mu",
                "cof_std",
                "cof_sd",
                "cof_stdev",
                "cof_sigma",
                "std_cof",
                "friction_coefficient_std",
            ],
            Quantity::Temperature => &["t", "temp", "temperature"],
        }
    }
}

/// How values in a unit become SI values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Conversion {
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
pub(super) struct Unit {
    /// As a note names it: "mm/s", "K".
    pub label: String,
    pub conversion: Conversion,
}

/// What a header cell names.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum Header {
    /// A column of `quantity`; `unit` None when no unit is given (the SI
    /// unit, or dimensionless).
    Column {
        quantity: Quantity,
        unit: Option<Unit>,
    },
    /// A column of `quantity` in a unit not understood (as written).
    BadUnit { quantity: Quantity, unit: String },
    /// Anything else (ignored).
    Other,
}

impl Header {
    /// The quantity named, understood or not.
    pub fn quantity(&self) -> Option<Quantity> {
        match self {
            Header::Column { quantity, .. } | Header::BadUnit { quantity, .. } => Some(*quantity),
            Header::Other => None,
        }
    }
}

/// What the header cell `raw` names.
pub(super) fn classify(raw: &str) -> Header {
    let raw = raw.trim();
    let (name, bracketed) = split_bracket(raw);
    let tokens = tokens(name);
    if tokens.is_empty() {
        return Header::Other;
    }
    let joined = tokens.join("_");
    // The name alone.
    if let Some(quantity) = Quantity::ALL
        .into_iter()
        .find(|q| q.aliases().contains(&joined.as_str()))
    {
        if quantity == Quantity::Temperature && name.trim() == "t" && bracketed.is_none() {
            return Header::Other; // time, most likely
        }
        return match bracketed {
            None => Header::Column {
                quantity,
                unit: None,
            },
            Some(unit) => bracket_unit(quantity, unit),
        };
    }
    if bracketed.is_some() {
        return Header::Other;
    }
    // A name followed by a unit: v_mm_s, speed um/s, T_K, velocity in mm/s.
    for quantity in [Quantity::Speed, Quantity::Temperature] {
        for alias in quantity.aliases() {
            let alias: Vec<&str> = alias.split('_').collect();
            if tokens.len() <= alias.len() || tokens[..alias.len()] != alias[..] {
                continue;
            }
            let mut rest = &tokens[alias.len()..];
            if rest.len() > 1 && rest[0] == "in" {
                rest = &rest[1..];
            }
            match quantity {
                Quantity::Speed => {
                    // A unit is a length per a time (the last token).
                    let per = rest.iter().position(|t| t == "per");
                    let (length, time) = match per {
                        Some(i) if i + 2 == rest.len() => (rest[..i].join(" "), &rest[i + 1]),
                        Some(_) => continue,
                        None if rest.len() >= 2 && time_unit(rest.last().unwrap()).is_some() => {
                            (rest[..rest.len() - 1].join(" "), rest.last().unwrap())
                        }
                        None => continue,
                    };
                    let written = format!("{length}/{time}");
                    return match speed_from_parts(&length, time) {
                        Some(unit) => Header::Column {
                            quantity,
                            unit: Some(unit),
                        },
                        None => Header::BadUnit {
                            quantity,
                            unit: written,
                        },
                    };
                }
                _ => {
                    if let Some(unit) = temperature_unit(&rest.join(" ")) {
                        return Header::Column {
                            quantity,
                            unit: Some(unit),
                        };
                    }
                }
            }
        }
    }
    Header::Other
}

/// (name, unit in brackets) of a header cell: `speed (mm/s)`, `T [°C]`,
/// `v/(mm/s)`.
fn split_bracket(raw: &str) -> (&str, Option<&str>) {
    let open = match raw.chars().last() {
        Some(')') => '(',
        Some(']') => '[',
        Some('}') => '{',
        _ => return (raw, None),
    };
    let Some(start) = raw.rfind(open) else {
        return (raw, None);
    };
    let name = raw[..start].trim_end();
    let name = name.strip_suffix('/').unwrap_or(name).trim_end();
    if name.is_empty() {
        return (raw, None);
    }
    (name, Some(raw[start + 1..raw.len() - 1].trim()))
}

/// The lower-case words of a name; `µ`/`μ` alone is "mu", before a unit
/// the micro prefix "u".
fn tokens(name: &str) -> Vec<String> {
    name.split(|c: char| c.is_whitespace() || "_-./\\,:;".contains(c))
        .filter(|t| !t.is_empty())
        .map(|t| {
            let lower = t.to_lowercase();
            match lower.strip_prefix(['µ', 'μ']) {
                Some("") => "mu".to_string(),
                Some(rest) => format!("u{rest}"),
                None => lower,
            }
        })
        .collect()
}

/// The meaning of a unit in brackets for `quantity`.
fn bracket_unit(quantity: Quantity, unit: &str) -> Header {
    let bad = || Header::BadUnit {
        quantity,
        unit: unit.to_string(),
    };
    let column = |unit: Option<Unit>| Header::Column { quantity, unit };
    match quantity {
        Quantity::Speed => speed_unit(unit).map_or_else(bad, |u| column(Some(u))),
        Quantity::Temperature => {
            if time_unit(&unit.trim().to_lowercase()).is_some() {
                return Header::Other; // t (s): time
            }
            temperature_unit(unit).map_or_else(bad, |u| column(Some(u)))
        }
        Quantity::Friction | Quantity::Sigma => match unit.trim() {
            "" | "-" | "–" | "—" | "1" => column(None),
            "%" if quantity == Quantity::Friction => column(Some(Unit {
                label: "%".into(),
                conversion: Conversion::Scale {
                    pow10: -2,
                    divisor: 1.0,
                },
            })),
            _ => bad(),
        },
    }
}

/// The unit in a units row below the header (`mm/s`, `-`, `°C`, or
/// nothing) for a column of `quantity`; Err if not understood.
pub(super) fn unit_cell(quantity: Quantity, text: &str) -> Result<Option<Unit>, ()> {
    if text.trim().is_empty() {
        return Ok(None);
    }
    match bracket_unit(quantity, text) {
        Header::Column { unit, .. } => Ok(unit),
        Header::BadUnit { .. } | Header::Other => Err(()),
    }
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
fn speed_from_parts(length: &str, time: &str) -> Option<Unit> {
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
fn time_unit(time: &str) -> Option<(i32, f64, &'static str)> {
    Some(match time {
        "s" | "sec" | "second" | "seconds" => (0, 1.0, "s"),
        "ms" => (3, 1.0, "ms"),
        "min" | "minute" | "minutes" => (0, 60.0, "min"),
        "h" | "hr" | "hour" | "hours" => (0, 3600.0, "h"),
        _ => return None,
    })
}

/// A temperature unit: °C, C, degC, celsius, K, kelvin, °F, F.
pub(super) fn temperature_unit(unit: &str) -> Option<Unit> {
    let unit: String = unit
        .trim()
        .to_lowercase()
        .replace("deg", "")
        .chars()
        .filter(|c| !(c.is_whitespace() || "°º_.".contains(*c)))
        .collect();
    let (label, conversion) = match unit.as_str() {
        "c" | "celsius" => ("°C", Conversion::NONE),
        "k" | "kelvin" => ("K", Conversion::Kelvin),
        "f" | "fahrenheit" => ("°F", Conversion::Fahrenheit),
        _ => return None,
    };
    Some(Unit {
        label: label.into(),
        conversion,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn column(raw: &str) -> (Quantity, Option<(String, Conversion)>) {
        match classify(raw) {
            Header::Column { quantity, unit } => (quantity, unit.map(|u| (u.label, u.conversion))),
            other => panic!("{raw:?}: {other:?}"),
        }
    }

    fn scale(pow10: i32, divisor: f64) -> Conversion {
        Conversion::Scale { pow10, divisor }
    }

    #[test]
    fn speed_names_and_units() {
        for raw in [
            "v",
            "V",
            "velocity",
            "Speed",
            "rolling speed",
            "Rolling_Speed",
            "vel",
        ] {
            assert_eq!(column(raw), (Quantity::Speed, None), "{raw}");
        }
        let cases = [
            ("v_m_s", "m/s", 0, 1.0),
            ("v_mm_s", "mm/s", -3, 1.0),
            ("v_um_s", "µm/s", -6, 1.0),
            ("v_µm_s", "µm/s", -6, 1.0),
            ("velocity (mm/s)", "mm/s", -3, 1.0),
            ("speed_um_s", "µm/s", -6, 1.0),
            ("speed [m/s]", "m/s", 0, 1.0),
            ("Speed (m/s)", "m/s", 0, 1.0),
            ("rolling speed (mm/s)", "mm/s", -3, 1.0),
            ("Velocity [µm/s]", "µm/s", -6, 1.0),
            ("v (μm/s)", "µm/s", -6, 1.0),
            ("v [cm/s]", "cm/s", -2, 1.0),
            ("v (nm/s)", "nm/s", -9, 1.0),
            ("v (mm/min)", "mm/min", -3, 60.0),
            ("speed (m/min)", "m/min", 0, 60.0),
            ("v (m/h)", "m/h", 0, 3600.0),
            ("v (mm/ms)", "mm/ms", 0, 1.0),
            ("v [m s-1]", "m/s", 0, 1.0),
            ("v [mm s^-1]", "mm/s", -3, 1.0),
            ("v (mm·s⁻¹)", "mm/s", -3, 1.0),
            ("v/(mm/s)", "mm/s", -3, 1.0),
            ("speed mm/s", "mm/s", -3, 1.0),
            ("speed in mm/s", "mm/s", -3, 1.0),
            ("v_mm_per_s", "mm/s", -3, 1.0),
            ("Speed(mm/s)", "mm/s", -3, 1.0),
        ];
        for (raw, label, pow10, divisor) in cases {
            assert_eq!(
                column(raw),
                (
                    Quantity::Speed,
                    Some((label.to_string(), scale(pow10, divisor)))
                ),
                "{raw}"
            );
        }
        for (raw, unit) in [
            ("v_furlong_s", "furlong/s"),
            ("speed (furlong/fortnight)", "furlong/fortnight"),
            ("v (V)", "V"),
        ] {
            assert_eq!(
                classify(raw),
                Header::BadUnit {
                    quantity: Quantity::Speed,
                    unit: unit.into()
                },
                "{raw}"
            );
        }
        for raw in [
            "v_reduced",
            "velocity profile",
            "v2",
            "vx (mm/s)",
            "(mm/s)",
            "",
        ] {
            assert_eq!(classify(raw), Header::Other, "{raw}");
        }
    }

    #[test]
    fn friction_sigma_and_temperature_names() {
        for raw in [
            "mu",
            "MU",
            "µ",
            "μ",
            "COF",
            "cof",
            "friction coefficient",
            "friction_coefficient",
            "Friction Coefficient (-)",
            "Coefficient of friction",
            "µ [-]",
            "mu_measured",
        ] {
            assert_eq!(column(raw), (Quantity::Friction, None), "{raw}");
        }
        assert_eq!(
            column("COF (%)"),
            (Quantity::Friction, Some(("%".into(), scale(-2, 1.0))))
        );
        for raw in [
            "sigma",
            "std",
            "sd",
            "mu_std",
            "sigma_mu",
            "COF std",
            "µ std",
            "Std. Dev.",
            "SD (-)",
        ] {
            assert_eq!(column(raw), (Quantity::Sigma, None), "{raw}");
        }
        for raw in ["T", "temperature", "Temp"] {
            assert_eq!(column(raw), (Quantity::Temperature, None), "{raw}");
        }
        let celsius = Some(("°C".to_string(), Conversion::NONE));
        let kelvin = Some(("K".to_string(), Conversion::Kelvin));
        let fahrenheit = Some(("°F".to_string(), Conversion::Fahrenheit));
        for (raw, unit) in [
            ("T_C", &celsius),
            ("T (°C)", &celsius),
            ("T [°C]", &celsius),
            ("temperature (C)", &celsius),
            ("Temperature [degC]", &celsius),
            ("t_C", &celsius),
            ("T_K", &kelvin),
            ("T (K)", &kelvin),
            ("temperature [kelvin]", &kelvin),
            ("T_F", &fahrenheit),
            ("T (°F)", &fahrenheit),
        ] {
            assert_eq!(column(raw), (Quantity::Temperature, unit.clone()), "{raw}");
        }
        for raw in [
            "t",
            "t (s)",
            "T [min]",
            "time",
            "mu_exact",
            "mu_low_speed",
            "T_ref",
        ] {
            assert_eq!(classify(raw), Header::Other, "{raw}");
        }
        for (raw, quantity) in [
            ("mu (N)", Quantity::Friction),
            ("sigma (%)", Quantity::Sigma),
            ("T (R)", Quantity::Temperature),
        ] {
            assert!(
                matches!(classify(raw), Header::BadUnit { quantity: q, .. } if q == quantity),
                "{raw}"
            );
        }
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
