//! The temperature a DMA file states outside a T column: in a title or
//! metadata line above its header (`Temperature: 20 °C`, `T=-10;Mw=…;`,
//! `Result: Frequency sweep 20C-cooling`) or in its file name
//! (`foam_dma_-25C.csv`, `sample_20c.csv`, `pmma_293K.txt`, `ps_130°C.csv`).
//! Instruments and labs that write one file per isotherm put it there.
//!
//! Two readings, the first that finds one wins:
//! 1. a key naming the temperature (`T`, `Temp`, `Temperature`, `Test
//!    temperature`, `Set temperature`, any case) followed by `:` or `=` and
//!    a number, with an optional unit (°C without one);
//! 2. a number directly followed by a temperature unit of [`crate::units`]
//!    (`°C`, `ºC`, `℃`, `C`, `c`, `degC`, `K`, `°F`; no lower-case `k`, `f`),
//!    the unit not followed by a letter or digit
//!    (`20C-cooling` is 20 °C, `20cm` is no temperature). A `-` before the
//!    number is its sign only at the start or after a separator (`_-25C`,
//!    ` -25C`), not after a word (`dma-25C` is 25 °C).
//!
//! A line (or name) holding two different temperatures by rule 2 states
//! none: which one is the isotherm's is a guess.

use crate::units::temperature_unit;

/// A temperature stated by a line or a name, °C.
pub fn in_text(text: &str) -> Option<f64> {
    keyed(text).or_else(|| unkeyed(text))
}

/// The first line of `lines` (number, text) that states a temperature:
/// (line number, °C).
pub fn in_lines<'a>(lines: impl IntoIterator<Item = (usize, &'a str)>) -> Option<(usize, f64)> {
    lines
        .into_iter()
        .find_map(|(number, line)| in_text(line).map(|t| (number, t)))
}

/// The temperature a file's name (without its extension) states, °C.
pub fn in_file_name(path: &std::path::Path) -> Option<f64> {
    path.file_stem().and_then(|s| s.to_str()).and_then(unkeyed)
}

/// The keys that name a temperature (lower case, spaces removed).
const KEYS: [&str; 6] = [
    "t",
    "temp",
    "temperature",
    "testtemperature",
    "settemperature",
    "temperatur",
];

/// Rule 1 of the module doc.
fn keyed(text: &str) -> Option<f64> {
    for part in text.split([';', ',', '\t']) {
        let Some(split) = part.find([':', '=']) else {
            continue;
        };
        let key: String = part[..split]
            .trim()
            .trim_start_matches('#')
            .chars()
            .filter(|c| !c.is_whitespace())
            .collect::<String>()
            .to_lowercase();
        if !KEYS.contains(&key.as_str()) {
            continue;
        }
        let value = part[split + 1..].trim();
        let Some((number, rest)) = leading_number(value) else {
            continue;
        };
        match unit(rest.trim_start()) {
            Some((to_celsius, _)) => return Some(to_celsius(number)),
            None if rest.trim().is_empty() => return Some(number),
            None => continue,
        }
    }
    None
}

/// Rule 2 of the module doc.
fn unkeyed(text: &str) -> Option<f64> {
    let mut found: Option<f64> = None;
    let chars: Vec<(usize, char)> = text.char_indices().collect();
    let mut k = 0;
    while k < chars.len() {
        let (at, c) = chars[k];
        let starts_number = c.is_ascii_digit()
            && (k == 0 || !(chars[k - 1].1.is_ascii_digit() || chars[k - 1].1 == '.'));
        if !starts_number {
            k += 1;
            continue;
        }
        let signed =
            k >= 1 && chars[k - 1].1 == '-' && (k == 1 || !chars[k - 2].1.is_alphanumeric());
        let start = if signed { chars[k - 1].0 } else { at };
        let Some((number, rest)) = leading_number(&text[start..]) else {
            k += 1;
            continue;
        };
        let consumed = text.len() - rest.len();
        if let Some((to_celsius, after)) = unit(rest.trim_start_matches(' '))
            && !after.starts_with(|c: char| c.is_alphanumeric())
        {
            let t = to_celsius(number);
            match found {
                Some(other) if other != t => return None,
                _ => found = Some(t),
            }
        }
        k = chars.partition_point(|&(i, _)| i < consumed);
    }
    found
}

/// The number at the start of `text` (sign, digits, decimal point or
/// comma followed by digits) and what follows it.
fn leading_number(text: &str) -> Option<(f64, &str)> {
    let bytes = text.as_bytes();
    let mut end = usize::from(matches!(bytes.first(), Some(b'-' | b'+')));
    let digits = |from: usize| {
        bytes[from..]
            .iter()
            .take_while(|b| b.is_ascii_digit())
            .count()
    };
    let whole = digits(end);
    if whole == 0 {
        return None;
    }
    end += whole;
    if matches!(bytes.get(end), Some(b'.' | b',')) && digits(end + 1) > 0 {
        end += 1 + digits(end + 1);
    }
    let number: f64 = text[..end].replace(',', ".").parse().ok()?;
    Some((number, &text[end..]))
}

/// The temperature unit at the start of `text` (its longest spelling in the
/// one table, ending in a letter or `℃`; no `k` or `f`: `Mw=100k` is no
/// temperature) as the function to °C, and what follows it.
fn unit(text: &str) -> Option<(impl Fn(f64) -> f64, &str)> {
    if text.starts_with(['k', 'f']) {
        return None;
    }
    let (end, (factor, offset)) = text
        .char_indices()
        .take(12)
        .filter(|&(_, c)| c.is_alphabetic() || c == '℃')
        .filter_map(|(i, c)| {
            let end = i + c.len_utf8();
            let unit = temperature_unit(&text[..end])?;
            Some((end, unit.conversion.factor_offset()))
        })
        .last()?;
    Some((move |t: f64| t * factor + offset, &text[end..]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// The spellings the module doc lists, and what states no temperature.
    #[test]
    fn stated_temperatures() {
        assert_eq!(in_text("Temperature: 20 °C"), Some(20.0));
        assert_eq!(in_text("T=-10;Mw=120000;PDI=1.1"), Some(-10.0));
        assert_eq!(in_text("# temp = 35.5"), Some(35.5));
        assert_eq!(in_text("Result: Frequency sweep 20C-cooling"), Some(20.0));
        assert_eq!(in_text("Interval: 1"), None);
        assert_eq!(in_text("sample 20cm wide"), None);
        assert_eq!(in_text("from 20 °C to 80 °C"), None);
        assert_eq!(in_text("Test: Frequency sweep"), None);
        let name = |n: &str| in_file_name(Path::new(n));
        assert_eq!(name("foam_dma_-25C.csv"), Some(-25.0));
        assert_eq!(name("foam_dma_20c.csv"), Some(20.0));
        assert_eq!(name("ps_130°C.csv"), Some(130.0));
        assert_eq!(name("dma-25C.csv"), Some(25.0));
        assert!((name("pmma_293K.txt").unwrap() - 19.85).abs() < 1e-9);
        assert_eq!(name("oscillation_ps130_data.csv"), None);
        assert_eq!(name("sweep_2.5C.csv"), Some(2.5));
        assert_eq!(name("sweep_20C.v2.csv"), Some(20.0));
        // °F through the one units table; `k` of a molar mass is no kelvin.
        assert!((in_text("Temperature: 68 °F").unwrap() - 20.0).abs() < 1e-9);
        assert!((name("pmma_68degF.csv").unwrap() - 20.0).abs() < 1e-9);
        assert_eq!(in_text("Mw=100k;PDI=1.1"), None);
        assert_eq!(in_text("T = 20 °C (set)"), Some(20.0));
    }
}
