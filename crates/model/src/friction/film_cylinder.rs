//! The quadrature of a cylinder on a film: its grid step and kernel window.
//!
//! Under a cylinder the film multiplies the loss compliance by g = 1/S(ωd/v)
//! (Persson 2010, S from [`crate::film`]), so the product integration of
//! [`crate::kernel::weights`] integrates Φ(σ)·g(σ) against the windowed
//! kernel instead of Φ alone. Both of its approximations were calibrated on
//! a half-space Φ, and g breaks both; each gets a film rule here.
//!
//! g is analytic except at the poles of 1/S(x), the zeros x* of
//!
//!   N(x) = (3 − 4ν) cosh 2x + 2x² + 5 − 4ν(3 − 2ν),   x = ωd/v = q d.
//!
//! The nearest to the real ln x axis is x* = 1.8094 + 2.4869i for ν = ½,
//! arg x* = δ_S = 0.9418; it is 0.949 at ν = 0.49, 1.056 at ν = 0.3, 1.179
//! at ν = 0 and ≥ 1.09 for −1 < ν < 0 (mpmath root scan, 110 starts per ν),
//! so ν = ½ is the worst case for every ν and one rule serves all.
//!
//! **The window.** The kernel's oscillatory part k_o ∝ Re e^{2iy} (y = qa)
//! is dropped beyond y ≈ X0 = 20 ([`crate::kernel::window`]), which is
//! exponentially accurate because the rest of the integrand can be continued
//! into Im ln y > 0 where e^{2iy} decays. The pole of g sits at
//! y_p = x*·a/d, and the Gaussian window grows like e^{(θ/w)²} (w = 0.25)
//! a distance θ off the axis: for a/d ≈ 2 … 10 (d ≈ 3e-5 … 3e-4 m under the
//! Fig. 2 roller) the pole's residue, ∝ e^{−2 Im y_p}, is multiplied by up
//! to e^{14} and the dropped part is no longer small. Measured (ν = ½,
//! d = 1e-4 m, dynamic size, v = 1.6e-4 m/s): −5.5e-7 at every grid step
//! down to h = 0.05 and every tolerance down to 1e-12 — an error the step
//! cannot cure. The film therefore uses a table whose window is centred at
//! [`crate::kernel::window::FILM_WINDOW_CENTRE`] = 40, where e^{−2 Im y_p}
//! outweighs the window's growth for every a/d: the same case is then
//! +5.8e-9 at h = 0.07 (the step's share) and +5.5e-10 at h = 0.05. The
//! window was also the one-signed floor of the static film at tolerance
//! 1e-8 (ν = ½, d = 1e-4 m, v = 1e-4 m/s: −1.19e-7 at every step, −3e-11
//! at X0 = 40). X0 must also stay below y ≈ π/h, where the oscillation
//! kept inside the window reaches the grid's own frequency and the
//! interpolation error resonates with it: X0 = 80 at h = 0.05 left
//! −1.3e-8 at d = 1e-5 m (ν = ½, v = 5e-6 m/s) at every tolerance, X0 = 40
//! leaves 3e-11. Hence the wide window only on steps h ≤ 0.07 (π/h ≥ 45,
//! tolerances ≤ 1e-6); the coarser steps that serve tolerances ≥ 1e-5 keep
//! X0 = 20, whose error for a film (≤ 6e-7 measured) is below those.
//! (The half-space keeps X0 = 20 and its floor of about 5e-9 … 1.4e-8, see
//! docs/validation.md, "Known gaps".)
//!
//! **The step.** The product integration's error is that of P-point
//! Lagrange interpolation of a function analytic in a strip of half-width δ
//! around the real σ axis, O((h/δ)^P). [`crate::kernel::step_for_tolerance`]
//! is calibrated on Φ of a Prony series, whose poles at ω = i/τ_k lie π/2
//! off the real axis of s = ln ω. In s the film's poles lie δ_S off it, and
//! both pass through the same map σ(s), so the product's strip is narrower
//! than the half-space's by δ_S/(π/2) = 0.600; keeping (h/δ)^P at the
//! calibrated value needs
//!
//!   h_film ≤ h_half-space(tolerance) · δ_S/(π/2),
//!
//! the largest of [`crate::kernel::STEPS`] that satisfies it: 0.14 → 0.07 at
//! tolerance 1e-6 and 1e-7, 0.2 → 0.1 at 1e-5, 0.1 → 0.05 at 1e-8 and 1e-9,
//! 0.07 → 0.035 below. Measured with a window at X0 = 80 (ν = ½,
//! d = 3e-4 m, dynamic size, v = 2.24e-4 m/s, the worst case of the
//! scan): 1.01e-5, 5.9e-7,
//! 2.0e-8 and 1.7e-9 at h = 0.14, 0.1, 0.07 and 0.05 — about h^9, and 1e-5
//! where the half-space's own error at h = 0.14 is 1e-8. The same rule for
//! every film thickness: g carries its poles wherever the film sits relative
//! to the contact size (for ν = ½ and d ≪ a the integral is even dominated
//! by ωd/v ≈ 1), and one step for all speeds keeps the grid shared across a
//! sweep.
//!
//! # References
//! - B.N.J. Persson, "Rolling friction for hard cylinder and sphere on
//!   viscoelastic solid", Eur. Phys. J. E 33 (2010) 327–333.
//! - L.N. Trefethen, *Approximation Theory and Approximation Practice*, SIAM
//!   2013, ch. 8 (interpolation error and the strip of analyticity).

use std::f64::consts::FRAC_PI_2;

use crate::kernel::{STEPS, step_for_tolerance};

/// arg x* of the first-quadrant zero of N nearest the real axis at ν = ½,
/// the smallest over −1 < ν ≤ ½: the half-width of the strip of 1/S(e^u).
pub(crate) const FILM_STRIP: f64 = 0.941_811_442_640_294_5;

/// Half-width of the strip of a Prony modulus in ln ω, the poles at
/// ω = i/τ_k: what [`step_for_tolerance`] was calibrated on.
const MATERIAL_STRIP: f64 = FRAC_PI_2;

/// Index into [`STEPS`] of the grid step for a cylinder on a film at a
/// requested relative tolerance of μ.
pub(super) fn step_index(tolerance: f64) -> usize {
    let needed = STEPS[step_for_tolerance(tolerance)] * FILM_STRIP / MATERIAL_STRIP;
    STEPS
        .iter()
        .position(|&h| h <= needed)
        .unwrap_or(STEPS.len() - 1)
}

#[cfg(test)]
mod tests {
    use num_complex::Complex64;

    use super::*;

    /// The film's N(x) and N′(x).
    fn numerator(x: Complex64, nu: f64) -> (Complex64, Complex64) {
        let c = 3.0 - 4.0 * nu;
        let k = 5.0 - 4.0 * nu * (3.0 - 2.0 * nu);
        let two_x = 2.0 * x;
        (
            c * two_x.cosh() + 2.0 * x * x + k,
            2.0 * c * two_x.sinh() + 4.0 * x,
        )
    }

    /// Newton's method from a start near the first-quadrant zero.
    fn zero(nu: f64) -> Complex64 {
        let mut x = Complex64::new(1.4, 2.55);
        for _ in 0..50 {
            let (n, dn) = numerator(x, nu);
            let dx = n / dn;
            x -= dx;
            if dx.norm() < 1e-15 {
                break;
            }
        }
        x
    }

    #[test]
    fn the_film_strip_is_the_argument_of_the_zero_at_one_half() {
        let x = zero(0.5);
        assert!(numerator(x, 0.5).0.norm() < 1e-12, "{x}");
        assert!((x.arg() - FILM_STRIP).abs() < 1e-14, "{}", x.arg());
        // Wider for every compressible film met in practice.
        for nu in [0.0, 0.1, 0.2, 0.3, 0.4, 0.45, 0.49] {
            let x = zero(nu);
            assert!(numerator(x, nu).0.norm() < 1e-12, "{nu}: {x}");
            assert!(x.arg() > FILM_STRIP, "{nu}: {}", x.arg());
        }
    }

    #[test]
    fn the_film_step_is_the_largest_step_inside_the_narrower_strip() {
        let ratio = FILM_STRIP / MATERIAL_STRIP;
        for tolerance in [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-12] {
            let half_space = STEPS[step_for_tolerance(tolerance)];
            let i = step_index(tolerance);
            assert!(STEPS[i] <= half_space * ratio, "{tolerance}");
            assert!(i == 0 || STEPS[i - 1] > half_space * ratio, "{tolerance}");
        }
        assert_eq!(STEPS[step_index(1e-6)], 0.07);
        assert_eq!(STEPS[step_index(1e-8)], 0.05);
    }
}
