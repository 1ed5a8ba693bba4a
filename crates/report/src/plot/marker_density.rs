//! How many of an isotherm's points a picture marks.
//!
//! Loggers write thousands of frequencies per isotherm; marked one by one
//! they only overdraw each other, and an SVG of them runs to hundreds of
//! megabytes. A picture marks at most [`MARKERS_PER_ISOTHERM`]
//! of each isotherm, evenly spread through its points; the CSV files keep
//! every point.

use std::collections::HashMap;

/// The most markers an isotherm gets in a picture: one per 1/100 decade
/// of a three-decade sweep, denser than the picture can separate (an
/// isotherm spans a tenth of its width).
const MARKERS_PER_ISOTHERM: usize = 300;

/// The points a picture marks, of isotherms told apart by `temperature`
/// (°C): every point of an isotherm of at most [`MARKERS_PER_ISOTHERM`],
/// else every k-th in the given order, k the least stride that keeps it
/// within that number.
pub(crate) fn drawn_points<P>(points: &[P], temperature: impl Fn(&P) -> f64) -> Vec<&P> {
    let mut counts: HashMap<u64, usize> = HashMap::new();
    for p in points {
        *counts.entry(temperature(p).to_bits()).or_default() += 1;
    }
    let mut seen: HashMap<u64, usize> = HashMap::new();
    points
        .iter()
        .filter(|p| {
            let key = temperature(p).to_bits();
            let stride = counts[&key].div_ceil(MARKERS_PER_ISOTHERM);
            let index = seen.entry(key).or_default();
            *index += 1;
            (*index - 1).is_multiple_of(stride)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Short isotherms are marked whole; a long one is thinned to at most
    /// the cap, keeping its first point, whatever the interleaving.
    #[test]
    fn long_isotherms_are_thinned_short_ones_kept() {
        // (temperature, position in the sweep)
        let point = |temperature: f64, i: usize| (temperature, 1.0 + i as f64);
        let mut points = Vec::new();
        for i in 0..1000 {
            points.push(point(40.0, i));
            if i < 50 {
                points.push(point(20.0, i));
            }
        }
        let drawn = drawn_points(&points, |p| p.0);
        let at = |t: f64| drawn.iter().filter(|p| p.0 == t).count();
        assert_eq!(at(20.0), 50);
        assert!(at(40.0) <= MARKERS_PER_ISOTHERM && at(40.0) >= MARKERS_PER_ISOTHERM / 2);
        assert_eq!(drawn.iter().find(|p| p.0 == 40.0).unwrap().1, 1.0);
    }
}
