//! Column names of a measured-data header (docs/ARCHITECTURE.md,
//! "Contract", "Measured data"): which of the four quantities
//! ([`Quantity`]) a header cell names, and in which unit ([`super::units`]).
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
//! (`t_C`, `t (°C)`); `T` is the temperature. The canonical names and
//! mu.csv's `mu_measured` come from [`crate::columns`] and
//! [`crate::fit_dir::columns`], where their writers take them.

use super::quantity::Quantity;
use crate::columns::MU;
use crate::fit_dir::columns::{MU_MEASURED, SIGMA, V};
use crate::units::{Unit, percent, speed_from_parts, speed_unit, temperature_unit, time_unit};

/// The names of a quantity, as [`tokens`] joins them (lower case, words
/// joined by `_`).
fn aliases(quantity: Quantity) -> &'static [&'static str] {
    match quantity {
        Quantity::Speed => &[
            V,
            "vel",
            "velocity",
            "speed",
            "rolling_speed",
            "rolling_velocity",
        ],
        Quantity::Friction => &[
            MU,
            "cof",
            "friction_coefficient",
            "friction_coeff",
            "coefficient_of_friction",
            "rolling_friction_coefficient",
            "coefficient_of_rolling_friction",
            MU_MEASURED,
            "mu_meas",
        ],
        Quantity::Sigma => &[
            SIGMA,
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
        // "T" in lower case, as tokens compare.
        Quantity::Temperature => &["t", "temp", "temperature"],
    }
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
        .find(|q| aliases(*q).contains(&joined.as_str()))
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
        for alias in aliases(quantity) {
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
            "%" if quantity == Quantity::Friction => column(Some(percent())),
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

#[cfg(test)]
mod tests;
