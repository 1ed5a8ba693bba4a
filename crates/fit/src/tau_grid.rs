//! The relaxation-time grid of a fit.
//!
//! A speed v probes frequencies ω ≈ v/r … 20 v/r, r the contact size at
//! that frequency (Persson 2010, Section 3; the kernel x²G(x) of Eq. 17 and
//! J1²(y)/y of Eq. 11 carry most of their weight there). Over a data set the
//! probed band is therefore
//!
//!   ω_lo = v_min/r_soft,   ω_hi = 20 v_max/r_stiff,
//!
//! with r_soft the contact size of the softest plausible solid (the anchored
//! or starting E0, else 0.1 MPa) and r_stiff that of the stiffest (E1_max).
//! The grid extends beyond the band on both sides because terms just outside
//! it still shape E* inside it, and asymmetrically: the glassy side of a
//! rubber relaxes slowly (its spectrum falls like a power law), so terms up to
//! [`EXTEND_HIGH`] decades above ω_hi matter, while the rubbery side ends
//! abruptly and [`EXTEND_LOW`] decades suffice. The τ_k are log-spaced,
//! τ_k = 1/ω_k, at the requested density (two per decade by default: one per
//! decade, the paper's choice, leaves a ripple of a few per cent in tan δ).
//!
//! Where the grid ends selects among near-equivalent fits; the rule above is
//! tested (`tests/grid_rule.rs`) by moving both ends outward and checking that
//! the recovered tan δ inside the window does not move.

use std::f64::consts::PI;

use rollfit_model::Shape;

use crate::params::{RollingSetup, TermRule};

/// Decades added below the probed band.
pub const EXTEND_LOW: f64 = 1.5;
/// Decades added above the probed band (slow glassy tail).
pub const EXTEND_HIGH: f64 = 3.0;
/// Softest static Young's modulus assumed when nothing better is known, Pa.
pub const SOFTEST_MODULUS: f64 = 1e5;

/// Contact size (m) of the set-up on a solid of Young's modulus `modulus`.
pub fn contact_size(setup: &RollingSetup, modulus: f64) -> f64 {
    let nu = setup.substrate.poisson;
    let e_eff = modulus / (1.0 - nu * nu);
    let g = setup.geometry;
    match g.shape {
        Shape::Sphere => (0.75 * g.load * g.radius / e_eff).cbrt(),
        Shape::Cylinder => (4.0 * g.load * g.radius / (PI * e_eff)).sqrt(),
    }
}

/// The probed band [ω_lo, ω_hi] (rad/s) for speeds in [v_min, v_max] and a
/// modulus between `soft` and `stiff` Pa.
pub fn probed_band(setup: &RollingSetup, speeds: (f64, f64), soft: f64, stiff: f64) -> (f64, f64) {
    let r_soft = contact_size(setup, soft);
    let r_stiff = contact_size(setup, stiff);
    (speeds.0 / r_soft, 20.0 * speeds.1 / r_stiff)
}

/// Relaxation times (s, increasing) for the band `band` under `rule`
/// (`TermRule::Auto` is resolved by the caller; it is treated as two per
/// decade here).
pub fn relaxation_times(band: (f64, f64), rule: &TermRule) -> Vec<f64> {
    let omega_top = band.1 * 10f64.powf(EXTEND_HIGH);
    let omega_bottom = band.0 / 10f64.powf(EXTEND_LOW);
    let (tau_min, tau_max) = (1.0 / omega_top, 1.0 / omega_bottom);
    let decades = (tau_max / tau_min).log10();
    let count = match rule {
        TermRule::Explicit(tau) => return tau.clone(),
        TermRule::Count(n) => *n,
        TermRule::PerDecade(d) => (decades * d).round() as usize + 1,
        TermRule::Auto => (decades * 2.0).round() as usize + 1,
    }
    .max(2);
    (0..count)
        .map(|k| tau_min * (tau_max / tau_min).powf(k as f64 / (count - 1) as f64))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setup() -> RollingSetup {
        crate::params::example_setup()
    }

    #[test]
    fn grid_covers_the_band_with_margins() {
        let band = probed_band(&setup(), (1e-6, 1.0), 2e6, 1e10);
        assert!(band.0 < band.1);
        let tau = relaxation_times(band, &TermRule::PerDecade(2.0));
        assert!(1.0 / tau[0] >= band.1 * 999.0);
        assert!(1.0 / tau[tau.len() - 1] <= band.0 / 30.0);
        // Two per decade.
        let ratio = tau[1] / tau[0];
        assert!((ratio.log10() - 0.5).abs() < 0.05, "{ratio}");
        assert!(tau.windows(2).all(|w| w[1] > w[0]));
    }
}
