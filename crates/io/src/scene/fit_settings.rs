//! Fit settings in a TOML table — the scene's `[fit]`, a manifest's
//! `[defaults]` and each `[[entry]]` — read through the fit library's one
//! parser, [`FitSettings::set`], and range-checked by
//! [`FitSettings::check`] as each value is read.
//!
//! This is serde glue, not a second parser: it turns a TOML value into a
//! [`SettingValue`] and hands it over with its key. Both steps run while
//! toml deserializes the table, so toml places every message at the
//! value's line and column, and an unknown key is serde's "unknown field"
//! error at the key's line, as derived tables report it.

use std::fmt;

use rollfit_fit::{FitSettings, SettingValue};
use serde::de::{self, DeserializeSeed, Deserializer, SeqAccess, Visitor};

use super::values::{Real, finite};

/// `first` followed by `second`, for the key lists of tables that hold
/// fit settings among keys of their own (`N` = the sum of the lengths).
pub(crate) const fn join<const A: usize, const B: usize, const N: usize>(
    first: [&'static str; A],
    second: [&'static str; B],
) -> [&'static str; N] {
    assert!(A + B == N, "N must be the sum of the lengths");
    let mut out = [""; N];
    let mut i = 0;
    while i < A {
        out[i] = first[i];
        i += 1;
    }
    while i < N {
        out[i] = second[i - A];
        i += 1;
    }
    out
}

/// A key of a table that knows the keys `.0`: the key as listed there, or
/// serde's "unknown field `…`, expected one of …" error, which toml places
/// at the key.
#[derive(Clone, Copy)]
pub(crate) struct Key(pub &'static [&'static str]);

impl<'de> DeserializeSeed<'de> for Key {
    type Value = &'static str;

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<Self::Value, D::Error> {
        deserializer.deserialize_identifier(self)
    }
}

impl Visitor<'_> for Key {
    type Value = &'static str;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a key")
    }

    fn visit_str<E: de::Error>(self, key: &str) -> Result<&'static str, E> {
        self.0
            .iter()
            .find(|known| **known == key)
            .copied()
            .ok_or_else(|| E::unknown_field(key, self.0))
    }
}

/// The fit settings of one table as it is read.
pub(crate) struct TableSettings {
    settings: FitSettings,
    /// Put before every message, e.g. "[fit]: ".
    prefix: &'static str,
}

impl TableSettings {
    /// No settings yet; `prefix` goes before every message.
    pub fn new(prefix: &'static str) -> Self {
        TableSettings {
            settings: FitSettings::default(),
            prefix,
        }
    }

    /// Reads the value of setting `key` (for `MapAccess::next_value_seed`).
    pub fn value_of(&mut self, key: &'static str) -> SettingSeed<'_> {
        SettingSeed { key, table: self }
    }

    /// The settings read.
    pub fn finish(self) -> FitSettings {
        self.settings
    }
}

/// Reads one setting's value: any TOML value becomes a [`SettingValue`],
/// [`FitSettings::set`] parses it under its key, and [`FitSettings::check`]
/// checks its range; errors become deserialization errors at the value.
pub(crate) struct SettingSeed<'t> {
    key: &'static str,
    table: &'t mut TableSettings,
}

impl<'de> DeserializeSeed<'de> for SettingSeed<'_> {
    type Value = ();

    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<(), D::Error> {
        let SettingSeed { key, table } = self;
        let prefix = table.prefix;
        let value = deserializer.deserialize_any(AnyValue).map_err(|e| {
            let message = e.to_string();
            de::Error::custom(format!(
                "{prefix}fit setting `{key}`: {}",
                message.trim_end()
            ))
        })?;
        table
            .settings
            .set(key, value.as_setting())
            .and_then(|()| table.settings.check())
            .map_err(|e| de::Error::custom(format!("{prefix}{e}")))
    }
}

/// A TOML value a setting can take.
enum TomlValue {
    Text(String),
    Integer(i64),
    Number(f64),
    Boolean(bool),
    Numbers(Vec<f64>),
}

impl TomlValue {
    fn as_setting(&self) -> SettingValue<'_> {
        match self {
            TomlValue::Text(text) => SettingValue::Text(text),
            TomlValue::Integer(n) => SettingValue::Integer(*n),
            TomlValue::Number(x) => SettingValue::Number(*x),
            TomlValue::Boolean(b) => SettingValue::Boolean(*b),
            TomlValue::Numbers(list) => SettingValue::Numbers(list.clone()),
        }
    }
}

/// Text, a whole or finite number, a boolean or a list of finite numbers
/// (nan and inf are refused here, as everywhere in a scene, so that toml
/// can place the message); which of them a key takes is
/// [`FitSettings::set`]'s to say.
struct AnyValue;

impl<'de> Visitor<'de> for AnyValue {
    type Value = TomlValue;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("text, a number, true or false, or a list of numbers")
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<TomlValue, E> {
        Ok(TomlValue::Text(v.to_owned()))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<TomlValue, E> {
        Ok(TomlValue::Integer(v))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<TomlValue, E> {
        Ok(i64::try_from(v).map_or(TomlValue::Number(v as f64), TomlValue::Integer))
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<TomlValue, E> {
        finite(v).map(|Real(x)| TomlValue::Number(x))
    }

    fn visit_bool<E: de::Error>(self, v: bool) -> Result<TomlValue, E> {
        Ok(TomlValue::Boolean(v))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<TomlValue, A::Error> {
        let mut values = Vec::new();
        while let Some(Real(v)) = seq.next_element::<Real>()? {
            values.push(v);
        }
        Ok(TomlValue::Numbers(values))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn join_lists_both_in_order() {
        const BOTH: [&str; 3] = join(["a"], ["b", "c"]);
        assert_eq!(BOTH, ["a", "b", "c"]);
    }
}
