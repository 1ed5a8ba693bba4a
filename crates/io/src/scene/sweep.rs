//! `[sweep]`: the speeds and temperatures `rollfit forward` evaluates μ at
//! (docs/ARCHITECTURE.md, "Contract", "Scene file").

use std::fmt;

use rollfit_fit::data::column_requirement;
use rollfit_model::modulus::FreeShift;
use serde::Deserialize;
use serde::de::{self, Deserializer, SeqAccess, Visitor};

use super::values::{Real, finite, reals, require_positive};
use crate::error::IoError;

/// Default number of log-spaced speeds of a `[sweep]` given by its range.
pub const DEFAULT_SWEEP_COUNT: i64 = 61;

/// Largest accepted `count`: far beyond any useful sweep, but small enough
/// that a typo cannot make the tool try to allocate exabytes.
pub const MAX_SWEEP_COUNT: i64 = 1_000_000;

/// The error of a `[sweep] temperature` without `[material.shift]`.
pub(crate) fn temperature_without_shift(temperature: &SweepTemperature) -> IoError {
    err!(
        "[sweep] {temperature} is set but [material] has no [material.shift]: without a \
         time-temperature shift the material is known only at its reference temperature",
        temperature = temperature.describe()
    )
}

/// `[sweep] temperature`, °C: one temperature, or a list of them (a
/// synthetic temperature set, one block of rows per temperature).
#[derive(Debug, Clone, PartialEq)]
pub enum SweepTemperature {
    /// `temperature = 20.0`.
    One(f64),
    /// `temperature = [-20.0, 0.0, ..]`, in the listed order.
    List(Vec<f64>),
}

impl SweepTemperature {
    /// The temperatures in order (one for [`SweepTemperature::One`]).
    pub fn values(&self) -> &[f64] {
        match self {
            SweepTemperature::One(t) => std::slice::from_ref(t),
            SweepTemperature::List(list) => list,
        }
    }

    /// How messages name the `i`-th temperature: `temperature = 20` or
    /// `temperature[i] = 20`.
    pub fn entry(&self, i: usize) -> String {
        match self {
            SweepTemperature::One(t) => format!("temperature = {t}"),
            SweepTemperature::List(list) => format!("temperature[{i}] = {}", list[i]),
        }
    }

    /// The key as written, for messages: `temperature = 20` or
    /// `temperature = [-20, 0, 20]`.
    fn describe(&self) -> String {
        match self {
            SweepTemperature::One(t) => format!("temperature = {t}"),
            SweepTemperature::List(list) => {
                let listed: Vec<String> = list.iter().map(f64::to_string).collect();
                format!("temperature = [{}]", listed.join(", "))
            }
        }
    }

    /// Checks what serde cannot see: each temperature inside the range a
    /// data file's T column accepts
    /// ([`rollfit_fit::data::column_requirement`]); a list names at least
    /// one temperature and none twice (within the model's
    /// [`FreeShift::TEMPERATURE_TOLERANCE`], the rule the fit uses to tell
    /// the temperatures of a set apart).
    pub(super) fn check(&self) -> Result<(), IoError> {
        for (i, &t) in self.values().iter().enumerate() {
            if let Some(requirement) = column_requirement("T", t) {
                let key = match self {
                    SweepTemperature::One(_) => "temperature".to_string(),
                    SweepTemperature::List(_) => format!("temperature[{i}]"),
                };
                // 1e300 in full is 301 digits.
                let shown = match t.abs() < 1e6 {
                    true => format!("{t}"),
                    false => format!("{t:e}"),
                };
                return Err(err!(
                    "{entry} °C {requirement}: a data file's T column is refused there, so `rollfit fit` \
         could not read these rows back",
                    entry = format!("{key} = {shown}")
                ));
            }
        }
        let SweepTemperature::List(list) = self else {
            return Ok(());
        };
        if list.is_empty() {
            return Err(err!(
                "`temperature = []` lists no temperatures: give at least one (°C), e.g. temperature = \
         [0.0, 20.0, 40.0], or leave the key out"
            ));
        }
        for (j, &t) in list.iter().enumerate() {
            if let Some(i) = list[..j]
                .iter()
                .position(|&s| (s - t).abs() <= FreeShift::TEMPERATURE_TOLERANCE)
            {
                return Err(err!(
                    "temperature[{index}] = {temperature} repeats temperature[{first}] = {first_temperature}: \
         list each temperature once",
                    first = i,
                    first_temperature = list[i],
                    index = j,
                    temperature = t
                ));
            }
        }
        Ok(())
    }
}

impl<'de> Deserialize<'de> for SweepTemperature {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct TemperatureVisitor;
        impl<'de> Visitor<'de> for TemperatureVisitor {
            type Value = SweepTemperature;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a temperature in °C or an array of temperatures")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<SweepTemperature, E> {
                finite(v).map(|r| SweepTemperature::One(r.0))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<SweepTemperature, E> {
                Ok(SweepTemperature::One(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<SweepTemperature, E> {
                Ok(SweepTemperature::One(v as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<SweepTemperature, A::Error> {
                let mut values = Vec::new();
                // Real rejects nan and inf; the entry's index is added here,
                // toml adds the line and column.
                while let Some(Real(t)) = seq.next_element::<Real>().map_err(|e| {
                    de::Error::custom(format!("[sweep] temperature[{}]: {e}", values.len()))
                })? {
                    values.push(t);
                }
                Ok(SweepTemperature::List(values))
            }
        }
        deserializer.deserialize_any(TemperatureVisitor)
    }
}

/// `[sweep]`: the speeds forward evaluates μ at.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSection {
    /// Lowest speed, m/s.
    pub v_min: Option<Real>,
    /// Highest speed, m/s.
    pub v_max: Option<Real>,
    /// Number of log-spaced speeds (default 61).
    pub count: Option<i64>,
    /// Explicit speeds, m/s, instead of a range.
    pub v: Option<Vec<Real>>,
    /// Temperature, °C, or a list of them (a temperature set); needs
    /// `[material.shift]`.
    pub temperature: Option<SweepTemperature>,
    /// Relative quadrature tolerance of μ (default 1e-6).
    pub tolerance: Option<Real>,
}

/// The speeds `rollfit fit` accepts ([`rollfit_fit::data::SPEED_RANGE`]),
/// so that a synthetic measurement can be fitted back.
fn in_speed_range(key: impl FnOnce() -> String, v: f64) -> Result<(), IoError> {
    let (low, high) = rollfit_fit::data::SPEED_RANGE;
    if (low..=high).contains(&v) {
        return Ok(());
    }
    Err(err!(
        "{key} = {value:e}: speeds must lie between {low:e} and {high:e} m/s (the range of a \
         rolling measurement that `rollfit fit` accepts)",
        key = key(),
        value = v
    ))
}

impl SweepSection {
    /// The speeds (m/s), strictly increasing: log-spaced from the range or
    /// the explicit list.
    pub fn speeds(&self) -> Result<Vec<f64>, IoError> {
        self.check_speeds()
    }

    /// [`Self::speeds`], with the scene's own error.
    pub(super) fn check_speeds(&self) -> Result<Vec<f64>, IoError> {
        if let Some(list) = &self.v {
            if self.v_min.is_some() || self.v_max.is_some() || self.count.is_some() {
                return Err(err!(
                    "give either `v = [..]` or `v_min`, `v_max` (and `count`), not both"
                ));
            }
            if list.is_empty() {
                return Err(err!("`v` is empty: list at least one speed"));
            }
            let speeds = reals(list);
            for (i, &v) in speeds.iter().enumerate() {
                if v <= 0.0 {
                    return Err(err!(
                        "v[{index}] = {value}: speeds must be greater than zero",
                        index = i,
                        value = v
                    ));
                }
                in_speed_range(|| format!("v[{i}]"), v)?;
            }
            if let Some(i) = speeds.windows(2).position(|w| w[1] <= w[0]) {
                return Err(err!(
                    "v[{index}] = {value} does not exceed v[{}] = {previous}: list the speeds in increasing \
         order",
                    &(i + 1) - 1,
                    index = i + 1,
                    previous = speeds[i],
                    value = speeds[i + 1]
                ));
            }
            return Ok(speeds);
        }
        let v_min = self
            .v_min
            .ok_or(err!(
                "needs `v_min` and `v_max` (m/s), or a list `v = [..]`"
            ))?
            .0;
        let v_max = self
            .v_max
            .ok_or(err!(
                "needs `v_min` and `v_max` (m/s), or a list `v = [..]`"
            ))?
            .0;
        require_positive("v_min", v_min)?;
        require_positive("v_max", v_max)?;
        in_speed_range(|| "v_min".into(), v_min)?;
        in_speed_range(|| "v_max".into(), v_max)?;
        if v_min >= v_max {
            return Err(err!("v_min = {v_min} must be less than v_max = {v_max}"));
        }
        let count = self.count.unwrap_or(DEFAULT_SWEEP_COUNT);
        if count < 1 {
            return Err(err!("count = {count}: must be at least 1"));
        }
        if count > MAX_SWEEP_COUNT {
            return Err(err!(
                "count = {count}: at most {max} speeds",
                max = MAX_SWEEP_COUNT
            ));
        }
        let speeds = log_spaced(v_min, v_max, count as usize);
        if !speeds.windows(2).all(|w| w[0] < w[1]) {
            return Err(err!(
                "count = {count} is too many distinct speeds between v_min = {v_min} and v_max = {v_max}"
            ));
        }
        Ok(speeds)
    }
}

/// `count` speeds log-spaced from `v_min` to `v_max`, both ends exact; a
/// single speed is `v_min`.
pub fn log_spaced(v_min: f64, v_max: f64, count: usize) -> Vec<f64> {
    if count == 1 {
        return vec![v_min];
    }
    let (a, b) = (v_min.log10(), v_max.log10());
    let last = (count - 1) as f64;
    (0..count)
        .map(|i| match i {
            0 => v_min,
            i if i == count - 1 => v_max,
            i => 10f64.powf(a + (b - a) * i as f64 / last),
        })
        .collect()
}
