//! DMA points grouped into isotherms: temperatures within
//! [`ISOTHERM_TOLERANCE`] of a neighbour belong to one, whose temperature
//! is their mean (docs/ARCHITECTURE.md, "Data flow", `master`). A
//! controller's ±0.02 K scatter should not split an isotherm, and "the
//! 150 °C isotherm" is what a user names.

use super::point::DmaPoint;

/// Temperatures closer than this (K) belong to one isotherm; also how far a
/// DMA isotherm may lie from a temperature a free shift lists and still
/// take its shift. Controllers hold a set point to ±0.1 K; steps of a
/// temperature programme are ≥ 2 K apart.
pub const ISOTHERM_TOLERANCE: f64 = 0.5;

/// One isotherm of a DMA file.
#[derive(Debug, Clone, PartialEq)]
pub struct Isotherm {
    /// Mean temperature, °C.
    pub temperature: f64,
    /// Indices of its points in `DmaData::points`.
    pub points: Vec<usize>,
}

/// The isotherms of `points` (those with a temperature), ascending.
pub fn isotherms(points: &[DmaPoint]) -> Vec<Isotherm> {
    group_temperatures(points.iter().map(|p| p.temperature))
}

/// The isotherms of points with these temperatures (those with one),
/// ascending; `points` of each index the sequence.
pub fn group_temperatures(temperatures: impl Iterator<Item = Option<f64>>) -> Vec<Isotherm> {
    let mut order: Vec<(usize, f64)> = temperatures
        .enumerate()
        .filter_map(|(i, t)| t.map(|t| (i, t)))
        .collect();
    order.sort_by(|a, b| a.1.total_cmp(&b.1));
    let mut groups: Vec<(Vec<usize>, Vec<f64>)> = Vec::new();
    let mut last = f64::NEG_INFINITY;
    for (i, t) in order {
        match groups.last_mut() {
            Some((indices, temps)) if t - last <= ISOTHERM_TOLERANCE => {
                indices.push(i);
                temps.push(t);
            }
            _ => groups.push((vec![i], vec![t])),
        }
        last = t;
    }
    groups
        .into_iter()
        .map(|(points, temps)| Isotherm {
            temperature: temps.iter().sum::<f64>() / temps.len() as f64,
            points,
        })
        .collect()
}
