//! The surface displacement of a half-space under a uniform pressure on one
//! square cell: the elastic influence coefficient of the boundary elements.
//!
//! A unit pressure on the square |ξ|, |η| ≤ ½ (unit side) displaces the
//! surface point (x, y), in units of the effective compliance and the side,
//! by
//!
//!   C(x, y) = (1/π) ∫∫ dξ dη / √((x − ξ)² + (y − η)²)
//!
//! (Boussinesq: u = (1 − ν²)/(πE) ∫∫ p/r dA). With
//! F(s, t) = s ln(t + r) + t ln(s + r), r = √(s² + t²), ∂²F/∂s∂t = 1/r, so
//! C is the second difference of F over the corners (Love 1929; Johnson
//! §3.9). For |x| or |y| ≫ 1 the corner values cancel; there, and for the
//! field beyond the grid, the multipole expansion
//! C ≈ (1/π)(1/ρ + 1/(24 ρ³)) is used (the square's second moments are
//! equal, so the quadrupole has no angular part).
//!
//! # References
//! - A.E.H. Love, "The stress produced in a semi-infinite solid by pressure
//!   on part of the boundary", Phil. Trans. R. Soc. A 228 (1929) 377–420.
//! - K.L. Johnson, *Contact Mechanics*, Cambridge 1985, §3.9.

use std::f64::consts::PI;

/// ln(t + √(s² + t²)) without cancellation for t < 0.
fn log_sum(s: f64, t: f64) -> f64 {
    let r = s.hypot(t);
    if t >= 0.0 {
        (t + r).ln()
    } else {
        // t + r = s²/(r − t).
        2.0 * s.abs().ln() - (r - t).ln()
    }
}

/// s ln(t + r), zero where s = 0 (the limit).
fn corner_term(s: f64, t: f64) -> f64 {
    if s == 0.0 { 0.0 } else { s * log_sum(s, t) }
}

/// F(s, t) = s ln(t + r) + t ln(s + r).
pub(crate) fn corner(s: f64, t: f64) -> f64 {
    corner_term(s, t) + corner_term(t, s)
}

/// Distance beyond which the multipole form is used (in cells): there its
/// first neglected term, of relative size about (½/ρ)⁴/5, is below 5e-11,
/// while the corner form, which loses about ρ² ln ρ ulps, would lose more.
pub(crate) const MULTIPOLE_DISTANCE: f64 = 150.0;

/// C(x, y) of the unit cell, in cell sides (see the module documentation).
pub(crate) fn unit_cell_potential(x: f64, y: f64) -> f64 {
    let (x, y) = (x.abs(), y.abs());
    let rho = x.hypot(y);
    if rho > MULTIPOLE_DISTANCE {
        return far_field(rho);
    }
    let (s1, s2) = (-0.5 - x, 0.5 - x);
    let (t1, t2) = (-0.5 - y, 0.5 - y);
    (corner(s2, t2) - corner(s1, t2) - corner(s2, t1) + corner(s1, t1)) / PI
}

/// The multipole form (1/π)(1/ρ + 1/(24 ρ³)) at distance ρ (cells).
pub(crate) fn far_field(rho: f64) -> f64 {
    (1.0 / rho + 1.0 / (24.0 * rho * rho * rho)) / PI
}

/// Distance (cells) beyond which [`far_field_square`] is within the
/// corner form's own rounding (about 1e-12 relative here): its first
/// neglected term, of order ρ⁻⁷, is below 1e-12 of C from 40 cells on.
pub(crate) const FAR_SQUARE_DISTANCE: f64 = 40.0;

/// The multipole form of the square cell through order ρ⁻⁵ at the offset
/// (x, y) (cells): (1/π)(1/ρ + 1/(24ρ³) + (7c²s²/96 − 7/1920)/ρ⁵),
/// c = x/ρ, s = y/ρ, the Legendre terms P_2 and P_4 averaged over the
/// unit square (⟨ξ²⟩ = 1/12, ⟨ξ⁴⟩ = 1/80, ⟨ξ²η²⟩ = 1/144). The tail
/// integrals of the memory tables ([`super::memory`]) evaluate C hundreds
/// of times per row and retardation term beyond the grid, where this form
/// costs one square root against the corner form's eight logarithms.
pub(crate) fn far_field_square(x: f64, y: f64) -> f64 {
    let r2 = x * x + y * y;
    let rho = r2.sqrt();
    let angular = 7.0 * x * x * y * y / (96.0 * r2 * r2) - 7.0 / 1920.0;
    (1.0 / rho) * (1.0 + (1.0 / 24.0 + angular / r2) / r2) / PI
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::quadrature::gauss_legendre_unit;

    /// The closed form against a direct 2-D Gauss–Legendre quadrature of
    /// 1/r (away from the cell, where the integrand is smooth), and the
    /// centre value 4 asinh(1)/π·… against its known closed form.
    #[test]
    fn closed_form_matches_quadrature() {
        let rule = gauss_legendre_unit(24);
        let direct = |x: f64, y: f64| {
            let mut sum = 0.0;
            for (a, wa) in rule.0.iter().zip(&rule.1) {
                for (b, wb) in rule.0.iter().zip(&rule.1) {
                    sum += wa * wb / (x - (a - 0.5)).hypot(y - (b - 0.5));
                }
            }
            sum / PI
        };
        for (x, y) in [(1.0, 0.0), (2.0, 3.0), (-1.5, 0.5), (0.0, -2.0), (7.0, 5.0)] {
            let (c, d) = (unit_cell_potential(x, y), direct(x, y));
            assert!((c / d - 1.0).abs() < 1e-10, "({x}, {y}): {c} vs {d}");
        }
        // Centre of the square: ∫∫ 1/r = 4 ln(1 + √2).
        let centre = 4.0 * (1.0 + 2f64.sqrt()).ln() / PI;
        assert!((unit_cell_potential(0.0, 0.0) / centre - 1.0).abs() < 1e-14);
    }

    /// The multipole form through ρ⁻⁵ against C evaluated in 50-digit
    /// decimal arithmetic (the corner form, Python's `decimal`): within
    /// 2e-13 from 40 cells on; against the corner form in f64, within that
    /// form's rounding (a few ρ² ln ρ ulps: 4e-12 at 60 cells, 2.6e-11 at
    /// 149 on the axis), which the two-term form (error 1e-9 at 60 cells)
    /// would miss.
    #[test]
    fn square_multipole_matches_the_closed_form() {
        for (x, y, precise) in [
            (60.0, 0.0, 0.0053052261706073986),
            (40.0, 0.0, 0.007957954376259718),
            (87.0, 0.0, 0.003658754464723335),
        ] {
            let far = far_field_square(x, y);
            assert!(
                (far / precise - 1.0).abs() < 2e-13,
                "({x}, {y}): {far} vs {precise}"
            );
        }
        for rho in [40.0, 60.0, 100.0, 149.0] {
            for angle in [0.0f64, 0.3, 0.785, 1.2, 1.57] {
                let (x, y) = (rho * angle.cos(), rho * angle.sin());
                let (far, exact) = (far_field_square(x, y), unit_cell_potential(x, y));
                assert!(
                    (far / exact - 1.0).abs() < 6e-11,
                    "{rho}, {angle}: {far} vs {exact}"
                );
            }
        }
        let error = |rho: f64| {
            (far_field_square(rho, 0.3 * rho) / unit_cell_potential(rho, 0.3 * rho) - 1.0).abs()
        };
        assert!(
            error(5.0) > 1e-8 && error(10.0) < error(5.0) / 40.0,
            "{} {}",
            error(5.0),
            error(10.0)
        );
    }

    /// The two forms agree where they meet.
    #[test]
    fn multipole_joins_the_closed_form() {
        for angle in [0.0f64, 0.3, 0.785, 1.2] {
            let rho = MULTIPOLE_DISTANCE * 0.999;
            let (x, y) = (rho * angle.cos(), rho * angle.sin());
            let exact = unit_cell_potential(x, y);
            assert!(
                (far_field(rho) / exact - 1.0).abs() < 1e-10,
                "{angle}: {} vs {exact}",
                far_field(rho)
            );
        }
    }
}
