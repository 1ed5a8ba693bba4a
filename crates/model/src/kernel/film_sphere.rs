//! The film deficit of the sphere kernel: how much a film of thickness d on
//! a rigid base removes from the half-space kernel G of [`super::sphere`].
//!
//! With a film, L(ω) is divided by S(qd) ([`crate::film::film_factor`]);
//! S depends on the magnitude q of the wavevector, which in the reduced form
//! of Eq. (17) (ω = q v cos φ, cosh t = 1/cos φ) is q = (ω/v) cosh t. The
//! kernel becomes
//!
//!   G_film(x, z) = ∫₀^∞ f(x cosh t)/S(z cosh t) dt = G(x) − D(x, z),
//!   D(x, z) = ∫₀^∞ f(x cosh t) w(z cosh t) dt,   w(ζ) = 1 − 1/S(ζ),
//!
//! with x = ω r(ω)/v (contact radius × wavenumber along the rolling
//! direction, dimensionless), z = ω d/v and f the Hertz form factor.
//!
//! Why D and not G_film: 0 ≤ w ≤ 1 and S − 1 ≈ (4ζ² + 4ζ + 2k) e^{−2ζ}/(3−4ν)
//! for large ζ, so w(ζ) < 4·10⁻¹⁸ for ζ ≥ Z = 24 ([`FILM_CUTOFF`]) and every
//! 0 ≤ ν ≤ ½. D is therefore an integral over the bounded interval
//! z cosh t ≤ Z of a non-negative, smooth integrand, and vanishes for z ≥ Z:
//! none of the slowly decaying oscillation of G (which the half-space
//! product integration already treats) is left in it. Dropping ζ > Z changes
//! D by less than 4·10⁻¹⁸ G(x) (w ≤ w(Z) there and ∫f dt ≤ G).
//!
//! # Method
//!
//! Adaptive Gauss–Kronrod (7, 15) in t on [0, acosh(Z/z)] (the crate's
//! `kernel::gauss_kronrod`). The initial panels follow the integrand's
//! scales: in y = x cosh t, f oscillates with period π once y ≳ 1, and in
//! ζ = z cosh t the weight w falls like e^{−2ζ}; so a panel spans at most
//! [`SPAN`] in y and in ζ, and at most [`MAX_WIDTH`] in t (where both are
//! small the integrand is nearly constant). Since y/ζ = r/d, a film thin
//! compared with the contact (d ≪ r) needs about 2 r/d panels: f oscillates
//! about 8 r/d times (y up to Z r/d, period π) before w has decayed.
//!
//! # References
//! - B.N.J. Persson, "Rolling friction for hard cylinder and sphere on
//!   viscoelastic solid", Eur. Phys. J. E 33 (2010) 327–333, Eq. (17) and
//!   the film factor S.
//! - R. Piessens et al., *QUADPACK*, Springer 1983 (Gauss–Kronrod rules).

use super::gauss_kronrod::{Failure, Integral, Targets, integrate};
use super::sphere::hertz_form_factor;
use crate::film::film_factor;

/// Z: beyond ζ = qd = Z the film factor is 1 to within 4·10⁻¹⁸
/// (w(24) ≈ 3·10⁻¹⁸ for ν = ½, less for smaller ν).
pub const FILM_CUTOFF: f64 = 24.0;

/// Largest initial panel span in y = x cosh t and in ζ = z cosh t: about
/// four periods π of f's oscillation, or a factor e^{−24} of w's decay.
///
/// Adaptive bisection refines where needed, so a coarse start costs little
/// accuracy and saves the evaluations of needlessly fine panels (measured:
/// spans of 3, 6, 12, 24 need 1.3M, 490k, 300k, 230k evaluations per speed
/// at d = r0/10). Much wider panels are not used: a panel spanning many
/// periods samples the oscillation too sparsely for |K − G| to be a
/// reliable error estimate (both rules alias; at 8 periods and beyond the
/// measured errors start to grow, though still far inside the tolerance).
pub const SPAN: f64 = 12.0;

/// Largest initial panel width in t.
pub const MAX_WIDTH: f64 = 4.0;

/// w(ζ) = 1 − 1/S(ζ), the fraction of the half-space loss a film removes at
/// wavenumber × thickness ζ = qd (0 ≤ w ≤ 1, w → 1 for ζ → 0), accurate to
/// a few ulp relative also where w is tiny.
///
/// For 2ζ < 2 it is 1 − 1/S with S from [`film_factor`] (w ≳ 0.5 there, no
/// cancellation). Above, 1 − 1/S would keep only the absolute accuracy
/// 1e-16, which is no relative accuracy at all once w ≲ 1e-13 (ζ ≳ 17), and
/// the inner quadrature needs relative accuracy there; with y = 2ζ,
/// t = e^{−y}, c = 3 − 4ν, k = 5 − 4ν(3 − 2ν) the exponential form of S
/// gives, free of cancellation,
///
///   w = (S − 1)/S = [2c t² + (y² + 2y + 2k) t] / [c(1 + t²) + (y² + 2k) t].
#[inline]
pub fn film_deficit_weight(zeta: f64, poisson: f64) -> f64 {
    let y = 2.0 * zeta;
    if y < 2.0 {
        return 1.0 - 1.0 / film_factor(zeta, poisson);
    }
    let nu = poisson;
    let c = 3.0 - 4.0 * nu;
    let k2 = 2.0 * (5.0 - 4.0 * nu * (3.0 - 2.0 * nu));
    let t = (-y).exp();
    (2.0 * c * t * t + (y * y + 2.0 * y + k2) * t) / (c * (1.0 + t * t) + (y * y + k2) * t)
}

/// Initial panel boundaries in t for D(x, z), written to `out` (empty for
/// z ≥ Z, where D = 0); `None` if more than `max_panels` would be needed (a
/// film very thin compared with the contact: y reaches Z x/z = Z r/d) or an
/// argument is NaN.
pub(crate) fn panel_breaks(x: f64, z: f64, max_panels: usize, out: &mut Vec<f64>) -> Option<()> {
    out.clear();
    if x.is_nan() || z.is_nan() {
        return None;
    }
    if z >= FILM_CUTOFF {
        return Some(());
    }
    let t_end = (FILM_CUTOFF / z).acosh();
    let scale = x.max(z);
    let mut t = 0.0f64;
    out.push(t);
    while t < t_end {
        let next = (t.cosh() + SPAN / scale)
            .acosh()
            .min(t + MAX_WIDTH)
            .min(t_end);
        // cosh t + SPAN/scale rounds to cosh t only for y ≳ 1e16 SPAN, far
        // past any panel budget; the check keeps the loop finite regardless.
        if next.is_nan() || next <= t || out.len() > max_panels {
            return None;
        }
        out.push(next);
        t = next;
    }
    Some(())
}

/// D(x, z) = ∫₀^∞ f(x cosh t) w(z cosh t) dt for x, z > 0, to the accuracy
/// max(`relative`·D, `absolute`) (the integrand is non-negative, so a
/// relative bound carries over to every positively weighted sum of D
/// values). `breaks` is scratch space.
pub(crate) fn deficit(
    x: f64,
    z: f64,
    poisson: f64,
    relative: f64,
    absolute: f64,
    max_panels: usize,
    breaks: &mut Vec<f64>,
) -> Result<Integral<1>, Failure> {
    integrate_in_t(x, z, relative, absolute, max_panels, breaks, |y, zeta| {
        [hertz_form_factor(y) * film_deficit_weight(zeta, poisson)]
    })
}

/// D(x, z) and x ∂D/∂x = ∫₀^∞ y f′(y) w(z cosh t) dt (y = x cosh t), each to
/// max(`relative`·|value|, `absolute`): what the derivatives of μ with
/// respect to the contact radius need.
pub(crate) fn deficit_and_slope(
    x: f64,
    z: f64,
    poisson: f64,
    relative: f64,
    absolute: f64,
    max_panels: usize,
    breaks: &mut Vec<f64>,
) -> Result<Integral<2>, Failure> {
    integrate_in_t(x, z, relative, absolute, max_panels, breaks, |y, zeta| {
        let w = film_deficit_weight(zeta, poisson);
        let (f, slope) = hertz_form_factor_and_log_slope(y);
        [f * w, slope * w]
    })
}

fn integrate_in_t<const N: usize>(
    x: f64,
    z: f64,
    relative: f64,
    absolute: f64,
    max_panels: usize,
    breaks: &mut Vec<f64>,
    integrand: impl Fn(f64, f64) -> [f64; N],
) -> Result<Integral<N>, Failure> {
    if panel_breaks(x, z, max_panels, breaks).is_none() {
        return Err(Failure::PanelLimit {
            error: f64::INFINITY,
            target: 0.0,
        });
    }
    if breaks.len() < 2 {
        return Ok(Integral {
            value: [0.0; N],
            error: [0.0; N],
            evaluations: 0,
        });
    }
    integrate(
        |t| {
            let c = t.cosh();
            integrand(x * c, z * c)
        },
        breaks,
        Targets {
            absolute: [absolute.max(f64::MIN_POSITIVE); N],
            relative,
        },
        max_panels,
    )
}

/// f(y) and y f′(y) for the Hertz form factor f = a², a = (sin y − y cos y)/y³:
/// y a′ = sin y / y − 3a, so y f′ = 2a (sin y/y − 3a). Below y = ½ both come
/// from the series a = Σ_{n≥1} (−1)^{n+1} 2n y^{2n−2}/(2n+1)! (the closed
/// forms cancel there); y a′ multiplies each term by 2n − 2.
pub fn hertz_form_factor_and_log_slope(y: f64) -> (f64, f64) {
    let (a, ya) = if y.abs() < 0.5 {
        let y2 = y * y;
        // term_n for n = 1: 2/3! = 1/3.
        let mut term = 1.0 / 3.0;
        let (mut a, mut ya) = (term, 0.0);
        // y² ≤ ¼: the n-th term is below 4^{1−n}·2n/(2n+1)!, under 1e-18
        // relative by n = 9.
        for n in 1..10 {
            let nf = n as f64;
            // term_{n+1}/term_n = −y² (2n+2)/((2n)(2n+2)(2n+3)) = −y²/(2n(2n+3)).
            term *= -y2 / (2.0 * nf * (2.0 * nf + 3.0));
            a += term;
            ya += 2.0 * nf * term;
        }
        (a, ya)
    } else {
        let (sin, cos) = y.sin_cos();
        let a = (sin - y * cos) / (y * y * y);
        (a, sin / y - 3.0 * a)
    };
    (a * a, 2.0 * a * ya)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::quadrature::{gauss_legendre_unit, integrate as fixed};
    use crate::kernel::sphere;

    /// Brute force: composite 8-point Gauss in t with tiny panels.
    fn slow_deficit(x: f64, z: f64, nu: f64) -> f64 {
        let rule = gauss_legendre_unit(8);
        let t_end = (FILM_CUTOFF / z).acosh();
        let y_end = x * FILM_CUTOFF / z;
        let panels = ((y_end * 4.0) as usize).max(2000);
        fixed(&rule, 0.0, t_end, panels, |t| {
            let c = t.cosh();
            hertz_form_factor(x * c) * film_deficit_weight(z * c, nu)
        })
    }

    #[test]
    fn matches_brute_force() {
        let mut scratch = Vec::new();
        for &(x, z) in &[
            (1e-3, 1e-3),
            (0.5, 0.8),
            (2.0, 0.2),
            (30.0, 3.0),
            (5.0, 20.0),
            (1e-6, 1e-4),
            (0.3, 23.9),
        ] {
            for nu in [0.0, 0.3, 0.5] {
                let fast = deficit(x, z, nu, 1e-12, 0.0, 10_000, &mut scratch).unwrap();
                let slow = slow_deficit(x, z, nu);
                assert!(
                    (fast.value[0] / slow - 1.0).abs() < 1e-11,
                    "x={x} z={z} nu={nu}: {} vs {slow}",
                    fast.value[0]
                );
                assert!(fast.error[0] <= 1e-12 * fast.value[0]);
            }
        }
    }

    #[test]
    fn vanishes_beyond_the_cutoff_and_tends_to_g_for_a_very_thin_film() {
        let mut scratch = Vec::new();
        let d = deficit(1.0, FILM_CUTOFF, 0.5, 1e-10, 0.0, 100, &mut scratch).unwrap();
        assert_eq!(d.value[0], 0.0);
        // z ≪ x ≪ 1: w ≈ 1 wherever f matters, so D → G(x); the remainder
        // ∫f/S dt ≈ ∫f (z cosh t)³/1.5 dt is about (z/x)³/3 ≈ 3e-10.
        for &x in &[1e-4, 1e-3] {
            let d = deficit(x, 1e-3 * x, 0.5, 1e-12, 0.0, 20_000, &mut scratch).unwrap();
            let g = sphere::g(x);
            assert!(
                (d.value[0] / g - 1.0).abs() < 1e-9,
                "{x}: {} {g}",
                d.value[0]
            );
            assert!(d.value[0] < g);
        }
    }

    #[test]
    fn deficit_weight_is_relatively_accurate() {
        for nu in [0.0, 0.25, 0.5] {
            // Continuous at the switch, and equal to 1 − 1/S where that has
            // relative accuracy.
            let a = film_deficit_weight(1.0 - 1e-12, nu);
            let b = film_deficit_weight(1.0, nu);
            assert!((a / b - 1.0).abs() < 1e-12, "{nu}: {a} {b}");
            for &zeta in &[1.5, 3.0, 6.0] {
                let direct = 1.0 - 1.0 / film_factor(zeta, nu);
                let w = film_deficit_weight(zeta, nu);
                assert!(
                    (w / direct - 1.0).abs() < 1e-16 / direct * 8.0,
                    "{nu} {zeta}"
                );
            }
            // Large ζ: w ≈ (4ζ² + 4ζ + 2k) e^{−2ζ}/c.
            let zeta: f64 = 20.0;
            let (c, k) = (3.0 - 4.0 * nu, 5.0 - 4.0 * nu * (3.0 - 2.0 * nu));
            let lead = (4.0 * zeta * zeta + 4.0 * zeta + 2.0 * k) * (-2.0 * zeta).exp() / c;
            assert!((film_deficit_weight(zeta, nu) / lead - 1.0).abs() < 1e-12);
            assert!(film_deficit_weight(FILM_CUTOFF, nu) < 4e-18);
        }
    }

    #[test]
    fn form_factor_slope_matches_differences() {
        for &y in &[1e-3, 0.2, 0.4999, 0.5, 0.7, 3.0, 17.3] {
            let (f, slope) = hertz_form_factor_and_log_slope(y);
            assert!((f - hertz_form_factor(y)).abs() <= 1e-15 * f.max(1e-300) + 1e-300);
            // Fourth-order central differences.
            let h = 1e-3 * y.min(1.0);
            let g = |k: f64| hertz_form_factor(y + k * h);
            let fd = y * (8.0 * (g(1.0) - g(-1.0)) - (g(2.0) - g(-2.0))) / (12.0 * h);
            assert!(
                (slope - fd).abs() < 1e-10 * f + 1e-9 * slope.abs(),
                "{y}: {slope} {fd}"
            );
        }
        // Small y: a ≈ 1/3 − y²/30, so y f′ = 2a·y a′ ≈ −(2/45) y².
        let (_, s) = hertz_form_factor_and_log_slope(1e-4);
        assert!((s / (-2.0 / 45.0 * 1e-8) - 1.0).abs() < 1e-7, "{s}");
    }

    #[test]
    fn slope_of_deficit_matches_differences() {
        let mut scratch = Vec::new();
        for &(x, z) in &[(0.3, 0.4), (4.0, 1.0), (0.01, 0.2)] {
            let both = deficit_and_slope(x, z, 0.5, 1e-12, 0.0, 10_000, &mut scratch).unwrap();
            let plain = deficit(x, z, 0.5, 1e-12, 0.0, 10_000, &mut scratch).unwrap();
            assert!((both.value[0] / plain.value[0] - 1.0).abs() < 1e-12);
            // x ∂D/∂x at fixed z, fourth-order differences in ln x.
            let h = 1e-3;
            let mut at = |k: f64| {
                deficit(x * (k * h).exp(), z, 0.5, 1e-14, 0.0, 10_000, &mut scratch)
                    .unwrap()
                    .value[0]
            };
            let fd = (8.0 * (at(1.0) - at(-1.0)) - (at(2.0) - at(-2.0))) / (12.0 * h);
            assert!(
                (both.value[1] - fd).abs() < 1e-9 * (plain.value[0] + fd.abs()),
                "{x} {z}: {} {fd}",
                both.value[1]
            );
        }
    }

    #[test]
    fn panel_budget_is_reported() {
        let mut scratch = Vec::new();
        // y reaches Z·x/z = 2.4e9: far beyond any budget, refused up front.
        assert!(deficit(1.0, 1e-8, 0.5, 1e-8, 0.0, 1000, &mut scratch).is_err());
        assert!(panel_breaks(1e300, 1e-300, 10, &mut scratch).is_none());
    }
}
