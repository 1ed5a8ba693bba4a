//! Which measured temperatures are the same.

use crate::data::Measurements;

/// Temperatures closer than this (°C) are the same temperature.
pub(crate) const SAME_TEMPERATURE: f64 = 1e-9;

/// The distinct temperatures of a data set, ascending.
pub(crate) fn distinct_temperatures(data: &Measurements) -> Vec<f64> {
    let mut t: Vec<f64> = data.temperature().map(|t| t.to_vec()).unwrap_or_default();
    t.sort_by(f64::total_cmp);
    t.dedup_by(|a, b| (*a - *b).abs() <= SAME_TEMPERATURE);
    t
}

/// The index in `temps` of temperature `t`.
pub(crate) fn index_of(temps: &[f64], t: f64) -> Option<usize> {
    temps
        .iter()
        .position(|&x| (x - t).abs() <= SAME_TEMPERATURE)
}
