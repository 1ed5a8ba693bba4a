//! The van Gurp–Palmen test of thermorheological simplicity, without any
//! shift: the phase angle δ = atan(E″/E′) against log10 |E*|.
//!
//! Where time–temperature superposition holds, E*(ω, T) = E*_ref(ω a_T)
//! (b_T = 1), so every isotherm traces a piece of the one curve
//! δ(log |E*|) of the material, whatever a_T: the isotherms collapse in
//! this plane before anything is shifted (van Gurp & Palmen 1998; Dealy &
//! Plazek 2009). Where they do not (a β relaxation with its own activation
//! energy, a phase change), no horizontal shift can superpose E′ and tan δ
//! together.
//!
//! Each pair of neighbouring isotherms is compared where their |E*| ranges
//! overlap: δ of each isotherm's points against the other's linear
//! interpolant in log |E*|, both ways, RMS in degrees (as a pair's shift is
//! measured, [`super::pairwise`], at s = 0). The pair collapses when that
//! RMS stays within
//!
//!   tolerance = [`VGP_TOLERANCE`] + 2 (σ_δ,i² + σ_δ,j²)^½,
//!
//! σ_δ the scatter of δ along each isotherm (second differences of
//! neighbouring points, var(δ_k − (δ_{k−1} + δ_{k+1})/2) = 1.5 σ² for
//! white noise; the curves' own curvature only widens it). The fixed part
//! is a modelling tolerance, not a statistical one, so that the test does
//! not fail every real material once its isotherms are dense enough: a
//! degree is what linear interpolation between sweep points 0.3 decade
//! apart and the density's few-per-cent change per isotherm leave on a
//! simple polymer. Pairs with fewer than two points of each inside the
//! other's |E*| range are not tested (the isotherms do not share a
//! modulus).
//!
//! # References
//! - M. van Gurp, J. Palmen, "Time–temperature superposition for polymeric
//!   blends", Rheology Bulletin 67 (1998) 5–8.
//! - J. Dealy, D. Plazek, "Time–temperature superposition — a users
//!   guide", Rheology Bulletin 78(2) (2009) 16–31.

use super::isotherm::Isotherm;
use crate::shift::overlap::{Curve, differences};

/// The modelling part of a pair's tolerance, degrees (module doc).
pub const VGP_TOLERANCE: f64 = 1.0;

/// One measured point in the van Gurp–Palmen plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VgpPoint {
    /// The isotherm's temperature, °C.
    pub temperature: f64,
    /// log10 |E*|, |E*| in Pa (unshifted).
    pub log_modulus: f64,
    /// The phase angle δ = atan(E″/E′), degrees.
    pub phase_angle: f64,
}

/// The test of one pair of neighbouring isotherms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VgpPair {
    /// The colder isotherm, °C.
    pub t_lower: f64,
    /// The warmer isotherm, °C.
    pub t_upper: f64,
    /// The common range of log10 |E*|, decades (0 where none).
    pub overlap: f64,
    /// RMS difference of δ over the common range, degrees (None where
    /// not tested).
    pub mismatch: Option<f64>,
    /// The pair's tolerance, degrees (module doc).
    pub tolerance: f64,
}

impl VgpPair {
    /// Whether the pair collapses (None where not tested).
    pub fn collapses(&self) -> Option<bool> {
        self.mismatch.map(|m| m <= self.tolerance)
    }
}

/// A run of neighbouring pairs with one outcome.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VgpRange {
    /// The coldest isotherm of the run, °C.
    pub t_from: f64,
    /// The warmest, °C.
    pub t_to: f64,
    /// Whether its pairs collapse (None: not tested).
    pub collapses: Option<bool>,
    /// The largest mismatch of its pairs, degrees (NaN where untested).
    pub worst: f64,
    /// The largest tolerance of its pairs, degrees.
    pub tolerance: f64,
}

/// The van Gurp–Palmen test of a set of isotherms: every point (for the
/// picture), every neighbour pair and the runs of equal outcome.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct VanGurpPalmen {
    /// Every measured point, by ascending temperature.
    pub points: Vec<VgpPoint>,
    /// Neighbour pairs, ascending.
    pub pairs: Vec<VgpPair>,
    /// Runs of pairs with one outcome, ascending.
    pub ranges: Vec<VgpRange>,
}

/// The test (module doc) of `isotherms` (any order).
pub fn van_gurp_palmen(isotherms: &[Isotherm]) -> VanGurpPalmen {
    let mut sorted: Vec<&Isotherm> = isotherms.iter().collect();
    sorted.sort_by(|a, b| a.temperature.total_cmp(&b.temperature));
    let plane = |iso: &Isotherm| -> Vec<(f64, f64)> {
        (0..iso.omega.len())
            .map(|i| {
                let (s, l) = (iso.storage[i], iso.loss[i]);
                (s.hypot(l).log10(), l.atan2(s).to_degrees())
            })
            .collect()
    };
    let mut out = VanGurpPalmen::default();
    let curves: Vec<(Curve, f64)> = sorted
        .iter()
        .map(|iso| {
            let p = plane(iso);
            let delta: Vec<f64> = p.iter().map(|q| q.1).collect();
            out.points.extend(p.iter().map(|&(m, d)| VgpPoint {
                temperature: iso.temperature,
                log_modulus: m,
                phase_angle: d,
            }));
            (Curve::new(p), scatter(&delta))
        })
        .collect();
    for k in 1..curves.len() {
        let ((lower, s_l), (upper, s_u)) = (&curves[k - 1], &curves[k]);
        let one = differences(lower, upper, 0.0);
        let other = differences(upper, lower, 0.0);
        let common = |c: &Curve| (c.x[0], c.x[c.x.len() - 1]);
        let ((l0, l1), (u0, u1)) = (common(lower), common(upper));
        let overlap = (l1.min(u1) - l0.max(u0)).max(0.0);
        let mismatch = (one.2 >= 2 && other.2 >= 2)
            .then(|| (0.5 * (one.1 / one.2 as f64 + other.1 / other.2 as f64)).sqrt());
        out.pairs.push(VgpPair {
            t_lower: sorted[k - 1].temperature,
            t_upper: sorted[k].temperature,
            overlap,
            mismatch,
            tolerance: VGP_TOLERANCE + 2.0 * s_l.hypot(*s_u),
        });
    }
    for p in &out.pairs {
        let worst = p.mismatch.unwrap_or(f64::NAN);
        match out.ranges.last_mut() {
            Some(r) if r.collapses == p.collapses() => {
                r.t_to = p.t_upper;
                r.worst = r.worst.max(worst);
                r.tolerance = r.tolerance.max(p.tolerance);
            }
            _ => out.ranges.push(VgpRange {
                t_from: p.t_lower,
                t_to: p.t_upper,
                collapses: p.collapses(),
                worst,
                tolerance: p.tolerance,
            }),
        }
    }
    out
}

/// The scatter of δ along an isotherm from second differences (module
/// doc); 0 with fewer than three points.
fn scatter(delta: &[f64]) -> f64 {
    if delta.len() < 3 {
        return 0.0;
    }
    let sum: f64 = delta
        .windows(3)
        .map(|w| (w[1] - 0.5 * (w[0] + w[2])).powi(2))
        .sum();
    (sum / (delta.len() - 2) as f64 / 1.5).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rollfit_model::{HavriliakNegami, ViscoelasticModulus};

    fn isotherms(log_a: fn(f64) -> f64, beta_shift: Option<fn(f64) -> f64>) -> Vec<Isotherm> {
        let master = HavriliakNegami::new(2e6, 2e9, 1e-3, 0.55, 0.4).unwrap();
        (0..6)
            .map(|k| {
                let t = 10.0 * k as f64;
                let omega: Vec<f64> = (0..10).map(|i| 0.1 * 10f64.powf(i as f64 / 3.0)).collect();
                let e: Vec<_> = omega
                    .iter()
                    .map(|w| {
                        let mut e = master.modulus(w * 10f64.powf(log_a(t)));
                        if let Some(b) = beta_shift {
                            // A loss process of its own, shifting by its own law.
                            let x = w * 10f64.powf(b(t));
                            e.im += 5e7 * x / (1.0 + x * x);
                        }
                        e
                    })
                    .collect();
                Isotherm {
                    temperature: t,
                    storage: e.iter().map(|e| e.re).collect(),
                    loss: e.iter().map(|e| e.im).collect(),
                    omega,
                }
            })
            .collect()
    }

    /// Isotherms of one master curve collapse whatever their shifts; a
    /// loss process with a shift of its own makes them fail, with the
    /// mismatch above the tolerance.
    #[test]
    fn simple_isotherms_collapse_and_complex_ones_do_not() {
        let simple = van_gurp_palmen(&isotherms(|t| -0.15 * (t - 20.0), None));
        assert_eq!(simple.points.len(), 60);
        assert!(
            simple.pairs.iter().all(|p| p.collapses() == Some(true)),
            "{simple:?}"
        );
        let complex = van_gurp_palmen(&isotherms(|t| -0.15 * (t - 20.0), Some(|t| 0.5 - 0.1 * t)));
        let failing = complex
            .pairs
            .iter()
            .filter(|p| p.collapses() == Some(false))
            .count();
        assert!(failing >= 3, "{complex:?}");
    }
}
