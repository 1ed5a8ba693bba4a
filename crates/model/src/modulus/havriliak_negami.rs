//! Havriliak–Negami modulus, a broad, asymmetric glass transition with
//! power-law wings:
//!
//! E*(ω) = E1 + (E0 − E1)/(1 + (iωτ)^α)^β,   0 < α ≤ 1, 0 < β ≤ 1,
//!
//! rubbery (static) modulus E0 at ω → 0, glassy modulus E1 at ω → ∞,
//! characteristic time τ. With z = (iωτ)^α = (ωτ)^α e^{iπα/2}:
//!
//! - low frequency: E* ≈ E0 + (E1 − E0) β z, so
//!   E″ ≈ (E1 − E0) β sin(πα/2) (ωτ)^α — the loss vanishes like ω^α, not
//!   like ω (a relaxation spectrum without a longest time when α < 1);
//! - high frequency: E* ≈ E1 − (E1 − E0) z^{−β}, E″ ∝ (ωτ)^{−αβ};
//! - α = β = 1 is the standard linear solid, Eq. (12), with the paper's time
//!   constant τ E1/E0 (one Prony term of strength E1 − E0 and time τ);
//!   β = 1 alone is the Cole–Cole form, α = 1 alone Cole–Davidson.
//!
//! Within these bounds the form has a positive relaxation spectrum, so
//! E″ ≥ 0 and |E*| rises monotonically from E0 to E1.
//!
//! It is written and evaluated as E* = E0 + (E1 − E0)·g with
//! g = 1 − (1 + z)^{−β} = −expm1(−β ln(1 + z)), so that E′ − E0 and E″ keep
//! full relative precision at low frequency, where E″ is many decades below
//! E1 − E0.
//!
//! # References
//! - S. Havriliak, S. Negami, "A complex plane representation of dielectric
//!   and mechanical relaxation processes in some polymers", Polymer 8 (1967)
//!   161–210.
//! - B.N.J. Persson, Eur. Phys. J. E 33 (2010), Eq. (12) (the limit α = β = 1).

use std::f64::consts::FRAC_PI_2;

use num_complex::Complex64;

use super::ViscoelasticModulus;
use crate::error::{ModelError, require_positive};

/// Relative accuracy to which E* follows its power-law limits outside
/// [`ViscoelasticModulus::structure_range`].
const STRUCTURE_TOLERANCE: f64 = 1e-6;

/// Bounds of the reported structure range, rad/s: wide enough for any real
/// material, narrow enough that the friction code's sampling a few decades
/// beyond it stays within normal floating-point numbers.
const OMEGA_FLOOR: f64 = 1e-290;
const OMEGA_CEILING: f64 = 1e290;

/// Havriliak–Negami modulus: rubbery modulus `E0` (Pa), glassy modulus `E1`
/// (Pa), time `tau` (s), shape exponents `alpha` (width) and `beta`
/// (asymmetry), both in (0, 1].
#[derive(Debug, Clone, PartialEq)]
pub struct HavriliakNegami {
    rubbery_modulus: f64,
    glassy_modulus: f64,
    tau: f64,
    alpha: f64,
    beta: f64,
    /// E1 − E0, Pa.
    strength: f64,
    /// (cos, sin) of πα/2: the direction of z = (iωτ)^α in the complex plane.
    direction: (f64, f64),
}

/// Checks 0 < `value` ≤ 1.
fn require_exponent(name: &str, value: f64) -> Result<f64, ModelError> {
    if value.is_finite() && value > 0.0 && value <= 1.0 {
        Ok(value)
    } else {
        Err(ModelError::parameter(
            name,
            value,
            "must be a number greater than 0 and at most 1",
        ))
    }
}

impl HavriliakNegami {
    /// Builds a validated modulus; requires 0 < E0 < E1, τ > 0 (all finite)
    /// and 0 < α, β ≤ 1.
    pub fn new(e0: f64, e1: f64, tau: f64, alpha: f64, beta: f64) -> Result<Self, ModelError> {
        require_positive("E0", e0)?;
        require_positive("E1", e1)?;
        require_positive("tau", tau)?;
        require_exponent("alpha", alpha)?;
        require_exponent("beta", beta)?;
        if e1 <= e0 {
            return Err(ModelError::parameter(
                "E1",
                e1,
                &format!(
                    "must exceed E0 = {e0} (the glassy modulus exceeds the rubbery one; \
                     for a purely elastic solid use a standard linear solid with E1 = E0)"
                ),
            ));
        }
        // cos(π/2) is 6e-17 in floating point; α = 1 must be exactly iωτ so
        // that the standard-linear-solid limit holds to rounding.
        let direction = if alpha == 1.0 {
            (0.0, 1.0)
        } else {
            let angle = FRAC_PI_2 * alpha;
            (angle.cos(), angle.sin())
        };
        Ok(HavriliakNegami {
            rubbery_modulus: e0,
            glassy_modulus: e1,
            tau,
            alpha,
            beta,
            strength: e1 - e0,
            direction,
        })
    }

    /// Rubbery (static) modulus E0, Pa.
    pub fn rubbery_modulus(&self) -> f64 {
        self.rubbery_modulus
    }

    /// Glassy modulus E1, Pa.
    pub fn glassy_modulus(&self) -> f64 {
        self.glassy_modulus
    }

    /// Characteristic time τ, s.
    pub fn tau(&self) -> f64 {
        self.tau
    }

    /// Width exponent α (dimensionless, 0 < α ≤ 1).
    pub fn alpha(&self) -> f64 {
        self.alpha
    }

    /// Asymmetry exponent β (dimensionless, 0 < β ≤ 1).
    pub fn beta(&self) -> f64 {
        self.beta
    }

    /// z = (iωτ)^α, ln(1 + z), and z/(1 + z), for ω ≥ 0.
    fn parts(&self, omega: f64) -> (Complex64, Complex64, Complex64) {
        // Clamped so that ω = ∞ gives the glassy limit instead of ∞·0.
        let r = (omega * self.tau).powf(self.alpha).min(f64::MAX);
        let (c, s) = self.direction;
        let z = Complex64::new(r * c, r * s);
        // ln|1 + z| = ½ ln(1 + 2Re z + |z|²): log1p keeps it accurate for
        // small z; hypot avoids overflow of |z|² for huge z.
        let ln_abs = if r < 1.0 {
            0.5 * (2.0 * z.re + r * r).ln_1p()
        } else {
            (1.0 + z.re).hypot(z.im).ln()
        };
        let ln_1p = Complex64::new(ln_abs, z.im.atan2(1.0 + z.re));
        // z/(1 + z) = 1/(1 + 1/z) for large z keeps ω → ∞ finite.
        let ratio = if r < 1.0 {
            z / (1.0 + z)
        } else {
            1.0 / (1.0 + 1.0 / z)
        };
        (z, ln_1p, ratio)
    }
}

/// expm1 of a complex number, accurate for small arguments:
/// e^{a+ib} − 1 = (expm1(a) cos b − 2 sin²(b/2)) + i e^a sin b.
fn expm1(w: Complex64) -> Complex64 {
    let half = (0.5 * w.im).sin();
    Complex64::new(
        w.re.exp_m1() * w.im.cos() - 2.0 * half * half,
        w.re.exp() * w.im.sin(),
    )
}

impl ViscoelasticModulus for HavriliakNegami {
    fn modulus(&self, omega: f64) -> Complex64 {
        let (_, ln_1p, _) = self.parts(omega);
        let g = -expm1(-self.beta * ln_1p);
        self.rubbery_modulus + self.strength * g
    }

    fn modulus_and_log_slope(&self, omega: f64) -> (Complex64, Complex64) {
        let (_, ln_1p, ratio) = self.parts(omega);
        let scaled = -self.beta * ln_1p;
        let g = -expm1(scaled);
        // dz/d ln ω = αz, so dE*/d ln ω = (E1 − E0) αβ z (1 + z)^{−β−1}
        // = (E1 − E0) αβ · z/(1 + z) · (1 + z)^{−β}.
        let power = scaled.exp();
        let slope = self.strength * self.alpha * self.beta * ratio * power;
        (self.rubbery_modulus + self.strength * g, slope)
    }

    fn static_modulus(&self) -> f64 {
        self.rubbery_modulus
    }

    /// (E1 − E0) β τ for α = 1; infinite for α < 1, where E″ ∝ ω^α.
    fn loss_slope_at_zero(&self) -> f64 {
        if self.alpha == 1.0 {
            self.strength * self.beta * self.tau
        } else {
            f64::INFINITY
        }
    }

    /// p = α: E″ ≈ (E1 − E0) β sin(πα/2) (ωτ)^α.
    fn loss_exponent_at_zero(&self) -> f64 {
        self.alpha
    }

    /// ℓ = lim E″/ω^α = (E1 − E0) β sin(πα/2) τ^α, Pa·s^α.
    fn low_frequency_loss_coefficient(&self) -> f64 {
        self.strength * self.beta * self.direction.1 * self.tau.powf(self.alpha)
    }

    /// The next terms of both expansions, E0 + (E1 − E0)βz and
    /// E1 − (E1 − E0)z^{−β}, are smaller than the power-law term they
    /// correct (in particular E″ ∝ ω^α and ∝ ω^{−αβ}) by a factor of order
    /// |z| below and 1/|z| above, so |z| = (ωτ)^α = 1e-6 and 1e6 bound the
    /// structure: ω ∈ [1e-6^{1/α}, 1e6^{1/α}]/τ (clamped to finite numbers
    /// for tiny α or extreme τ).
    fn structure_range(&self) -> (f64, f64) {
        let half_width = -STRUCTURE_TOLERANCE.ln() / self.alpha;
        let ln_tau = self.tau.ln();
        let lo = (-half_width - ln_tau).max(OMEGA_FLOOR.ln()).exp();
        let hi = (half_width - ln_tau).min(OMEGA_CEILING.ln()).exp();
        (lo.min(hi), hi.max(lo))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modulus::StandardLinearSolid;

    /// A small deterministic generator (SplitMix64) for test frequencies.
    struct SplitMix(u64);

    impl SplitMix {
        fn next_unit(&mut self) -> f64 {
            self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^= z >> 31;
            (z >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    fn rubber() -> HavriliakNegami {
        HavriliakNegami::new(2e6, 2e9, 1e-4, 0.55, 0.4).unwrap()
    }

    /// Direct evaluation of the defining formula.
    fn direct(m: &HavriliakNegami, omega: f64) -> Complex64 {
        let i = Complex64::new(0.0, 1.0);
        let z = (i * omega * m.tau()).powf(m.alpha());
        m.glassy_modulus() + (m.rubbery_modulus() - m.glassy_modulus()) / (1.0 + z).powf(m.beta())
    }

    #[test]
    fn equals_the_defining_formula() {
        let m = rubber();
        for k in -10..=16 {
            let w = 10f64.powi(k);
            let e = m.modulus(w);
            let d = direct(&m, w);
            assert!((e - d).norm() < 1e-12 * d.norm(), "ω = {w}: {e} vs {d}");
        }
    }

    #[test]
    fn log_slope_matches_central_differences() {
        let mut rng = SplitMix(20240611);
        for (alpha, beta) in [(0.55, 0.4), (1.0, 1.0), (0.2, 0.9), (1.0, 0.3), (0.7, 1.0)] {
            let m = HavriliakNegami::new(1e6, 3e8, 0.01, alpha, beta).unwrap();
            for _ in 0..50 {
                let w = 10f64.powf(-8.0 + 16.0 * rng.next_unit());
                let (e, slope) = m.modulus_and_log_slope(w);
                assert_eq!(e, m.modulus(w));
                let h: f64 = 1e-5;
                let fd = (m.modulus(w * h.exp()) - m.modulus(w * (-h).exp())) / (2.0 * h);
                // Central differences are accurate to O(h²) plus the
                // rounding of E, a few ulp of |E| divided by h.
                let tolerance = 1e-6 * slope.norm() + 4.0 * f64::EPSILON * e.norm() / h;
                assert!(
                    (slope - fd).norm() < tolerance,
                    "α = {alpha}, β = {beta}, ω = {w}: {slope} vs {fd}"
                );
            }
        }
    }

    #[test]
    fn limits_are_rubbery_and_glassy_with_power_law_wings() {
        let m = rubber();
        assert_eq!(m.modulus(0.0), Complex64::new(2e6, 0.0));
        assert_eq!(m.static_modulus(), 2e6);
        let (lo, hi) = m.structure_range();
        assert!(lo > 0.0 && hi > lo && hi.is_finite());
        // Below the structure: E″ = ℓ ω^α, E′ = E0, to the structure tolerance.
        let p = m.loss_exponent_at_zero();
        assert_eq!(p, 0.55);
        let ell = m.low_frequency_loss_coefficient();
        for w in [lo, lo * 1e-3] {
            let e = m.modulus(w);
            assert!((e.im / (ell * w.powf(p)) - 1.0).abs() < 3e-6, "ω = {w}");
            assert!((e.re / 2e6 - 1.0).abs() < 1e-6 * 1e3, "ω = {w}");
        }
        // Above the structure: E* = E1 − (E1 − E0) z^{−β}.
        for w in [hi, hi * 1e3] {
            let e = m.modulus(w);
            let i = Complex64::new(0.0, 1.0);
            let wing = 2e9 - (2e9 - 2e6) * (i * w * 1e-4).powf(-0.55 * 0.4);
            assert!((e.im / wing.im - 1.0).abs() < 3e-6, "ω = {w}");
            assert!((e.re / wing.re - 1.0).abs() < 1e-9, "ω = {w}");
        }
        let top = m.modulus(1e300);
        assert!(top.re.is_finite() && top.re <= 2e9 && top.re > 1.9e9);
        let (_, slope) = m.modulus_and_log_slope(f64::INFINITY);
        assert!(slope.re.is_finite() && slope.im.is_finite());
        assert!(m.loss_slope_at_zero().is_infinite());
    }

    #[test]
    fn alpha_and_beta_one_is_the_standard_linear_solid() {
        // E1 − (E1 − E0)/(1 + iωτ) is Eq. (12) with the paper's τ_sls = τ E1/E0.
        let (e0, e1, tau) = (1e6, 1e7, 0.1);
        let hn = HavriliakNegami::new(e0, e1, tau, 1.0, 1.0).unwrap();
        let sls = StandardLinearSolid::new(e0, e1, tau * e1 / e0).unwrap();
        for k in -40..=40 {
            let w = 10f64.powf(k as f64 / 5.0);
            let (a, da) = hn.modulus_and_log_slope(w);
            let (b, db) = sls.modulus_and_log_slope(w);
            assert!((a - b).norm() < 1e-13 * b.norm(), "ω = {w}");
            assert!((da - db).norm() < 1e-12 * (db.norm() + 1.0), "ω = {w}");
        }
        let slope = sls.loss_slope_at_zero();
        assert!((hn.loss_slope_at_zero() / slope - 1.0).abs() < 1e-14);
        assert!((hn.low_frequency_loss_coefficient() / slope - 1.0).abs() < 1e-14);
        assert_eq!(hn.loss_exponent_at_zero(), 1.0);
    }

    #[test]
    fn loss_is_never_negative_and_storage_rises() {
        let mut rng = SplitMix(7);
        for _ in 0..40 {
            let alpha = 0.05 + 0.95 * rng.next_unit();
            let beta = 0.05 + 0.95 * rng.next_unit();
            let m = HavriliakNegami::new(1e6, 1e9, 1.0, alpha, beta).unwrap();
            let mut last = 0.0;
            for k in -300..=300 {
                let w = 10f64.powf(k as f64 / 10.0);
                let e = m.modulus(w);
                assert!(e.im >= 0.0, "α = {alpha}, β = {beta}, ω = {w}: {e}");
                // A positive relaxation spectrum makes E′ non-decreasing.
                assert!(e.re >= last * (1.0 - 1e-14), "E′ falls at ω = {w}");
                last = e.re;
            }
        }
    }

    #[test]
    fn bad_parameters_are_refused() {
        let ok = |e0, e1, tau, a, b| HavriliakNegami::new(e0, e1, tau, a, b).is_ok();
        assert!(ok(1e6, 1e9, 1.0, 1.0, 1.0));
        assert!(!ok(0.0, 1e9, 1.0, 0.5, 0.5));
        assert!(!ok(1e6, 1e6, 1.0, 0.5, 0.5));
        assert!(!ok(1e6, 1e5, 1.0, 0.5, 0.5));
        assert!(!ok(1e6, f64::INFINITY, 1.0, 0.5, 0.5));
        assert!(!ok(1e6, 1e9, 0.0, 0.5, 0.5));
        assert!(!ok(1e6, 1e9, f64::NAN, 0.5, 0.5));
        assert!(!ok(1e6, 1e9, 1.0, 0.0, 0.5));
        assert!(!ok(1e6, 1e9, 1.0, 1.5, 0.5));
        assert!(!ok(1e6, 1e9, 1.0, 0.5, -0.1));
        assert!(!ok(1e6, 1e9, 1.0, 0.5, f64::NAN));
        match HavriliakNegami::new(1e6, 1e9, 1.0, 0.5, 2.0) {
            Err(ModelError::InvalidParameter { name, .. }) => assert_eq!(name, "beta"),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn structure_range_stays_finite_for_extreme_parameters() {
        for (tau, alpha) in [(1e-200, 0.01), (1e200, 0.01), (1.0, 1e-6), (1e-300, 1.0)] {
            let m = HavriliakNegami::new(1.0, 2.0, tau, alpha, 0.5).unwrap();
            let (lo, hi) = m.structure_range();
            assert!(lo > 0.0 && hi >= lo && hi.is_finite(), "{lo} {hi}");
        }
    }
}
