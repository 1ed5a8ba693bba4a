//! The sphere kernel of Eq. (17) reduced to one frequency integral.
//!
//! Substituting ω = q v cos φ in Persson's Eq. (17) and u = 1/cos φ gives
//!
//!   μ = 18 F_N/(π² v²) ∫₀^∞ dω ω L(ω) G(ω r(ω)/v),
//!   G(x) = ∫₁^∞ f(xu) du/√(u² − 1),   f(y) = [(sin y − y cos y)/y³]²,
//!
//! and with s = ln ω, x = ω r/v, the integrand becomes (L/r²)·k(ln x) with the
//! universal kernel k(ln x) = x² G(x).
//!
//! G is evaluated to ~1e-14 by splitting f into a smooth and an oscillatory
//! part, f = f_n + f_o with
//!   f_n(y) = (1 + y²)/(2y⁶),   f_o(y) = −Re[e^{2iy}(1 − iy)²]/(2y⁶),
//! so that ∫₁^∞ f_n(xu) du/√(u²−1) = 1/(3x⁴) + 4/(15x⁶) =: G_n(x) exactly, and
//! the oscillatory integral is turned into an exponentially decaying one by
//! rotating the contour into the upper half plane (u = 1 + is). For small x the
//! split cancels badly, so there the integral runs along y = x cosh t up to
//! y = 4 directly and only the tail y > 4 is split and rotated.
//!
//! Asymptotes (tests): G(x) → 1/(3x⁴) for x → ∞; G(x) = (1/9) ln(2/x) + c_f
//! plus O(x² ln x) for x → 0; ∫₀^∞ x² G(x) dx = π²/24 (this fixes the
//! low-speed limit μ → (3π/4) p_a L′(0) v/r0).

use num_complex::Complex64;

use super::quadrature::{gauss_legendre_unit, integrate};

/// f(y) = [(sin y − y cos y)/y³]², the squared Fourier transform of the Hertz
/// pressure (up to constants), accurate also for small y.
pub fn hertz_form_factor(y: f64) -> f64 {
    let a = if y.abs() < 0.5 {
        // Series of (sin y − y cos y)/y³ = Σ (−1)^{n+1} 2n y^{2n−2}/(2n+1)!,
        // to avoid the cancellation of the closed form.
        let y2 = y * y;
        let mut term: f64 = 1.0 / 3.0;
        let mut sum = term;
        let mut n = 1.0;
        while term.abs() > 1e-18 {
            // ratio of consecutive terms: −y²·(2n+2)/((2n)(2n+2)(2n+3))
            let next = n + 1.0;
            term *= -y2 * (2.0 * next) / ((2.0 * n) * (2.0 * next) * (2.0 * next + 1.0));
            sum += term;
            n = next;
        }
        sum
    } else {
        (y.sin() - y * y.cos()) / (y * y * y)
    };
    a * a
}

/// Smooth part G_n(x) = 1/(3x⁴) + 4/(15x⁶) of G.
pub fn smooth_part(x: f64) -> f64 {
    let x2 = x * x;
    1.0 / (3.0 * x2 * x2) + 4.0 / (15.0 * x2 * x2 * x2)
}

struct Rules {
    g16: (Vec<f64>, Vec<f64>),
    g24: (Vec<f64>, Vec<f64>),
}

fn rules() -> &'static Rules {
    static RULES: std::sync::OnceLock<Rules> = std::sync::OnceLock::new();
    RULES.get_or_init(|| Rules {
        g16: gauss_legendre_unit(16),
        g24: gauss_legendre_unit(24),
    })
}

/// The oscillatory remainder of the tail ∫_Y^∞ f_o(y)/√(y² − x²) dy, along
/// y = Y + is (e^{2iy} decays there), for x < Y.
fn rotated_tail(x: f64, y0: f64) -> f64 {
    let r = rules();
    let i = Complex64::new(0.0, 1.0);
    let mut sum = Complex64::new(0.0, 0.0);
    // e^{−2s}: s up to 20 leaves e^{−40}.
    let panels = 10;
    let width = 2.0;
    for p in 0..panels {
        for (t, w) in r.g24.0.iter().zip(&r.g24.1) {
            let s = (p as f64 + t) * width;
            let y = Complex64::new(y0, s);
            let one_minus_iy = Complex64::new(1.0, 0.0) - i * y;
            let y2 = y * y;
            let y6 = y2 * y2 * y2;
            let value = (2.0 * i * y).exp() * one_minus_iy * one_minus_iy
                / (2.0 * y6 * (y2 - x * x).sqrt());
            sum += w * width * value * i;
        }
    }
    -sum.re
}

/// G(x) = ∫₁^∞ f(xu) du/√(u² − 1), x > 0, to about 1e-14 relative.
pub fn g(x: f64) -> f64 {
    assert!(x > 0.0, "G(x) needs x > 0");
    let r = rules();
    if x <= 2.0 {
        let y0 = 4.0;
        // Direct part along y = x cosh t, t ∈ [0, acosh(Y/x)]: f is smooth there.
        let t_max = (y0 / x).acosh();
        let panels = (t_max / 0.5).ceil().max(1.0) as usize;
        let direct = integrate(&r.g16, 0.0, t_max, panels, |t| {
            hertz_form_factor(x * t.cosh())
        });
        // Smooth tail with y = Y/z: ∫₀¹ (z⁵ + Y² z³)/(2Y⁵ √(Y² − x² z²)) dz.
        let smooth_tail = integrate(&r.g16, 0.0, 1.0, 2, |z| {
            let z3 = z * z * z;
            (z3 * z * z + y0 * y0 * z3) / (2.0 * y0.powi(5) * (y0 * y0 - x * x * z * z).sqrt())
        });
        direct + smooth_tail + rotated_tail(x, y0)
    } else {
        smooth_part(x) + oscillatory_part_large(x)
    }
}

/// G_o(x) = G(x) − G_n(x) for x > 2, by u = 1 + i w² (which also removes the
/// inverse-square-root endpoint singularity):
/// G_o = −Re[e^{2ix} ∫₀^∞ e^{−2xw²} (1 − ix(1 + iw²))² · 2i
///        / (2x⁶ (1 + iw²)⁶ √(2i − w²)) dw].
fn oscillatory_part_large(x: f64) -> f64 {
    -(Complex64::new(0.0, 2.0 * x).exp() * oscillatory_amplitude(x)).re
}

/// The non-oscillating amplitude I(x) of G_o(x) = −Re[e^{2ix} I(x)] for
/// x > 2 (the integral in [`oscillatory_part_large`]): smooth in ln x, so a
/// quadrature that follows the oscillation can tabulate it.
pub fn oscillatory_amplitude(x: f64) -> Complex64 {
    let r = rules();
    let i = Complex64::new(0.0, 1.0);
    let w_max = (40.0 / (2.0 * x)).sqrt();
    let panels = ((w_max / 0.25).ceil() as usize).max(2);
    let width = w_max / panels as f64;
    let mut sum = Complex64::new(0.0, 0.0);
    for p in 0..panels {
        for (t, wt) in r.g24.0.iter().zip(&r.g24.1) {
            let w = (p as f64 + t) * width;
            let u = Complex64::new(1.0, w * w);
            let a = Complex64::new(1.0, 0.0) - i * x * u;
            let u2 = u * u;
            let u6 = u2 * u2 * u2;
            let value = (-2.0 * x * w * w).exp() * a * a * 2.0 * i
                / (2.0 * x.powi(6) * u6 * (Complex64::new(-w * w, 2.0)).sqrt());
            sum += wt * width * value;
        }
    }
    sum
}

/// G_o(x) = G(x) − G_n(x), the oscillatory part, for any x > 0 (cancels
/// badly for x ≲ 0.5; used only where the window is active).
pub fn oscillatory_part(x: f64) -> f64 {
    if x > 2.0 {
        oscillatory_part_large(x)
    } else {
        g(x) - smooth_part(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Slow oracle: G(x) = ∫₀^∞ f(x cosh t) dt by a fine trapezoid-free
    /// composite Gauss rule to large t, plus the averaged 1/(3x⁴)-type tail.
    fn slow_g(x: f64) -> f64 {
        let rule = gauss_legendre_unit(8);
        // up to y = x cosh T = 4000: tail beyond is below 1e-13 relative.
        let t_max = (4000.0 / x).acosh();
        let panels = 400_000;
        let body = integrate(&rule, 0.0, t_max, panels, |t| {
            hertz_form_factor(x * t.cosh())
        });
        // Tail: f averages to (1 + y²)/(2y⁶) ≈ 1/(2y⁴); ∫_T^∞ dt/(2x⁴cosh⁴t).
        let tail = integrate(&rule, t_max, t_max + 20.0, 200, |t| {
            let y = x * t.cosh();
            (1.0 + y * y) / (2.0 * y.powi(6))
        });
        body + tail
    }

    #[test]
    fn matches_slow_integration() {
        for &x in &[1e-4, 0.01, 0.3, 1.0, 1.9, 2.1, 5.0, 20.0, 80.0] {
            let fast = g(x);
            let slow = slow_g(x);
            assert!(
                ((fast - slow) / slow).abs() < 2e-9,
                "x={x}: {fast} vs {slow}"
            );
        }
    }

    /// G(x) from an independent 30-digit mpmath evaluation
    /// (quad on y = x cosh t up to y = 4, quadosc beyond).
    #[test]
    fn matches_extended_precision() {
        for (x, reference) in [
            (1e-4, 1.153_680_521_846_280_6),
            (1e-3, 0.897_837_644_280_744_1),
            (0.5, 0.202_030_650_264_137_14),
        ] {
            assert!((g(x) / reference - 1.0).abs() < 1e-14, "{x}");
        }
    }

    #[test]
    fn continuous_across_the_regime_switch() {
        let below = g(2.0);
        let above = smooth_part(2.0 + 1e-12) + oscillatory_part_large(2.0 + 1e-12);
        assert!(((below - above) / below).abs() < 1e-11, "{below} {above}");
    }

    #[test]
    fn asymptotes() {
        // Large x: 1/(3x⁴) up to an oscillation of relative size ~ x^(−1/2).
        for &x in &[1e2f64, 1e3, 1e4] {
            assert!((g(x) * 3.0 * x.powi(4) - 1.0).abs() < 1.5 / x.sqrt(), "{x}");
        }
        // Small x: G(x) − (1/9) ln(1/x) tends to a constant.
        let c1 = g(1e-6) - (1e6f64).ln() / 9.0;
        let c2 = g(1e-7) - (1e7f64).ln() / 9.0;
        assert!((c1 - c2).abs() < 1e-10, "{c1} {c2}");
    }

    #[test]
    fn form_factor_series_matches_closed_form() {
        for &y in &[0.3f64, 0.45, 0.49999] {
            let closed = ((y.sin() - y * y.cos()) / (y * y * y)).powi(2);
            assert!((hertz_form_factor(y) - closed).abs() < 1e-12);
        }
        assert!((hertz_form_factor(1e-9) - 1.0 / 9.0).abs() < 1e-16);
    }
}
