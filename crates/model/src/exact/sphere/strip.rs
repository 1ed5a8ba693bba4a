//! The surface displacement of a half-space in plane strain under a uniform
//! pressure on one strip: the elastic influence coefficient of the boundary
//! elements when the sphere's code solves a cylinder.
//!
//! In plane strain a pressure p(s) displaces the surface by
//! u(x) = −(2/π)(1 − ν²)/E ∫ p(s) ln|x − s| ds + const (Johnson §2.2), so a
//! unit pressure on the strip |ξ| ≤ ½ (unit width) displaces the point x,
//! in units of the effective compliance and the width, by
//!
//!   C(x) = −(2/π) ∫_{−½}^{½} ln|x − ξ| dξ = −(2/π) [G(x + ½) − G(x − ½)],
//!   G(s) = s ln|s| − s.
//!
//! The kernel does not decay: C ≈ −(2/π) ln|x| far away, and the constant
//! of u is fixed only by a reference point. Every additive constant c in
//! the kernel adds c ∫p = c W to u at every point of the surface, which
//! the approach δ absorbs at fixed load, so measuring lengths in strip
//! widths (the physical kernel less (2/π) ln h) and the reference shifts
//! of [`super::memory::CellTable`] change δ only, not the pressure. For
//! |x| ≫ 1 the two G cancel; there the expansion
//! C ≈ −(2/π)(ln|x| − 1/(24x²) − 1/(320x⁴)) (the strip's even moments
//! 1/12, 1/80) is used.
//!
//! # References
//! - K.L. Johnson, *Contact Mechanics*, Cambridge 1985, §2.2 (the line
//!   load in plane strain), §2.8.

use std::f64::consts::PI;

use super::cell::MULTIPOLE_DISTANCE;

/// G(s) = s ln|s| − s, zero at s = 0 (the limit).
fn antiderivative(s: f64) -> f64 {
    if s == 0.0 { 0.0 } else { s * s.abs().ln() - s }
}

/// C(x) of the unit strip, in strip widths (see the module documentation).
pub(crate) fn unit_strip_potential(x: f64) -> f64 {
    let x = x.abs();
    if x > MULTIPOLE_DISTANCE {
        return strip_far_field(x);
    }
    -(2.0 / PI) * (antiderivative(x + 0.5) - antiderivative(x - 0.5))
}

/// The far form −(2/π)(ln x − 1/(24x²) − 1/(320x⁴)) at distance x (widths):
/// its first neglected term, (2/π)/(1792 x⁶), is below 1e-16 beyond the
/// switch at [`MULTIPOLE_DISTANCE`].
pub(crate) fn strip_far_field(x: f64) -> f64 {
    let x2 = x * x;
    -(2.0 / PI) * (x.ln() - 1.0 / (24.0 * x2) - 1.0 / (320.0 * x2 * x2))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::quadrature::gauss_legendre_unit;

    /// The closed form against Gauss–Legendre quadrature of the logarithm
    /// off the strip, its known centre value, and the far form where the
    /// two meet.
    #[test]
    fn closed_form_matches_quadrature() {
        let rule = gauss_legendre_unit(40);
        let integral = |x: f64, a: f64, b: f64| -> f64 {
            rule.0
                .iter()
                .zip(&rule.1)
                .map(|(t, w)| w * (b - a) * (x - (a + t * (b - a))).abs().ln())
                .sum()
        };
        for x in [1.0, 2.5, -3.0, 17.0, 0.75] {
            let direct = -(2.0 / PI) * integral(x, -0.5, 0.5);
            let c = unit_strip_potential(x);
            assert!((c - direct).abs() < 1e-10, "{x}: {c} vs {direct}");
        }
        // Centre: −(2/π)(ln ½ − 1).
        let centre = -(2.0 / PI) * (0.5f64.ln() - 1.0);
        assert!((unit_strip_potential(0.0) - centre).abs() < 1e-15);
        let rho = MULTIPOLE_DISTANCE * 0.999;
        let near = -(2.0 / PI) * (antiderivative(rho + 0.5) - antiderivative(rho - 0.5));
        assert!((strip_far_field(rho) - near).abs() < 1e-12);
    }
}
