//! Hertz contact of a rigid sphere or cylinder on a (visco)elastic half-space.
//!
//! With the effective modulus E_eff = E/(1 − ν²):
//! - cylinder, load per length f_N: a = (4 f_N R / (π E_eff))^½, mean pressure
//!   p_a = f_N / (2a);
//! - sphere, load F_N: r = (3 F_N R / (4 E_eff))^⅓, p_a = F_N / (π r²).
//!
//! In the viscoelastic problem the paper's "dynamic" choice uses |E_eff(ω)| at
//! the frequency ω each Fourier component of the deformation is excited at;
//! "static" uses E_eff(0) throughout.
//!
//! # References
//! - K.L. Johnson, *Contact Mechanics*, Cambridge 1985, §4.2 and §5.8.
//! - B.N.J. Persson, Eur. Phys. J. E 33 (2010), Eqs. (9), (14).

use std::f64::consts::PI;

/// Shape of the rolling body.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    /// Sphere of radius R; load is a force F_N (N).
    Sphere,
    /// Cylinder of radius R; load is a force per length f_N (N/m).
    Cylinder,
}

impl Shape {
    /// Exponent n in the contact law a ∝ E^(−1/n): 3 for a sphere, 2 for a cylinder.
    pub(crate) fn contact_exponent(self) -> f64 {
        match self {
            Shape::Sphere => 3.0,
            Shape::Cylinder => 2.0,
        }
    }
}

/// Which modulus sets the contact size.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ContactSize {
    /// |E_eff(ω)| at the local frequency (Persson's choice).
    #[default]
    Dynamic,
    /// E_eff(0) for every frequency.
    Static,
}

/// Hertz contact size (m): radius r for a sphere, half-width a for a cylinder,
/// for effective modulus `e_eff` (Pa), body radius `radius` (m) and `load`
/// (N or N/m).
pub fn hertz_contact_size(shape: Shape, radius: f64, load: f64, e_eff: f64) -> f64 {
    match shape {
        Shape::Sphere => (3.0 * load * radius / (4.0 * e_eff)).cbrt(),
        Shape::Cylinder => (4.0 * load * radius / (PI * e_eff)).sqrt(),
    }
}

/// Mean contact pressure p_a (Pa) for contact size `size` (m).
pub fn mean_pressure(shape: Shape, load: f64, size: f64) -> f64 {
    match shape {
        Shape::Sphere => load / (PI * size * size),
        Shape::Cylinder => load / (2.0 * size),
    }
}

/// ln of [`hertz_contact_size`] (m) for ln E_eff = `ln_e_eff` (ln Pa),
/// evaluated in logarithms: finite for every positive finite radius and
/// load, where the product F R overflows (a load of 1e308 N typed by
/// mistake must still give a plausibility warning with numbers, not NaN).
pub fn ln_hertz_contact_size(shape: Shape, radius: f64, load: f64, ln_e_eff: f64) -> f64 {
    match shape {
        Shape::Sphere => (0.75f64.ln() + load.ln() + radius.ln() - ln_e_eff) / 3.0,
        Shape::Cylinder => ((4.0 / PI).ln() + load.ln() + radius.ln() - ln_e_eff) / 2.0,
    }
}

/// ln of [`mean_pressure`] (ln Pa) for a contact of size exp(`ln_size`) (m),
/// in logarithms as [`ln_hertz_contact_size`].
pub fn ln_mean_pressure(shape: Shape, load: f64, ln_size: f64) -> f64 {
    match shape {
        Shape::Sphere => load.ln() - PI.ln() - 2.0 * ln_size,
        Shape::Cylinder => load.ln() - 2f64.ln() - ln_size,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_fig2_contact_sizes() {
        // Persson (2010) text: r0 ≈ 0.10 cm, a0 ≈ 0.11 cm, E0 = 1 MPa as E_eff.
        let r0 = hertz_contact_size(Shape::Sphere, 0.01, 0.15, 1e6);
        let a0 = hertz_contact_size(Shape::Cylinder, 0.01, 100.0, 1e6);
        assert!((r0 - 1.04004e-3).abs() < 1e-8, "{r0}");
        assert!((a0 - 1.12838e-3).abs() < 1e-8, "{a0}");
        let p = mean_pressure(Shape::Sphere, 0.15, r0);
        assert!((p - 44.14e3).abs() < 50.0, "{p}");
    }

    /// The logarithmic forms are the linear ones where those are finite,
    /// and stay finite where the product F R overflows.
    #[test]
    fn logarithmic_forms_match_and_stay_finite() {
        for shape in [Shape::Sphere, Shape::Cylinder] {
            for (radius, load, e_eff) in
                [(0.01, 0.15, 1e6), (0.005, 1000.0, 2.7e6), (2e-5, 1e4, 1e10)]
            {
                let size = hertz_contact_size(shape, radius, load, e_eff);
                let ln_size = ln_hertz_contact_size(shape, radius, load, e_eff.ln());
                assert!(
                    (ln_size.exp() / size - 1.0).abs() < 1e-13,
                    "{shape:?} {radius} {load}"
                );
                let p = mean_pressure(shape, load, size);
                let ln_p = ln_mean_pressure(shape, load, ln_size);
                assert!(
                    (ln_p.exp() / p - 1.0).abs() < 1e-13,
                    "{shape:?} {radius} {load}"
                );
            }
            let huge = ln_hertz_contact_size(shape, 1e308, 1e308, 1e6f64.ln());
            assert!(huge.is_finite() && hertz_contact_size(shape, 1e308, 1e308, 1e6).is_infinite());
        }
    }
}
