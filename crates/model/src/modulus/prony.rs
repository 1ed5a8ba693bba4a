//! Prony series (generalised Maxwell model), Persson (2010) Eq. (B2):
//!
//! E*(ω) = E1 − Σ_k H_k / (1 + i ω τ_k),   H_k ≥ 0, τ_k > 0,
//!
//! with E1 the glassy (high-frequency) modulus and E0 = E1 − Σ_k H_k > 0 the
//! rubbery (static) one. The series is linear in its parameters
//! p = (E1, H_1, …, H_n): ∂E*/∂E1 = 1 and ∂E*/∂H_k = −1/(1 + iωτ_k), which is
//! what makes the exact gradient of the friction coefficient cheap.

use num_complex::Complex64;

use super::ViscoelasticModulus;
use crate::error::{ModelError, require_non_negative, require_positive};

/// A Prony series E*(ω) = E1 − Σ H_k/(1 + iωτ_k); moduli in Pa, times in s.
#[derive(Debug, Clone, PartialEq)]
pub struct Prony {
    glassy_modulus: f64,
    strengths: Vec<f64>,
    relaxation_times: Vec<f64>,
}

impl Prony {
    /// Builds a validated series from the glassy modulus `e1` (Pa), the
    /// strengths `h` (Pa, each ≥ 0) and the relaxation times `tau` (s, each
    /// > 0). The static modulus E0 = E1 − ΣH must be positive.
    pub fn new(e1: f64, h: Vec<f64>, tau: Vec<f64>) -> Result<Self, ModelError> {
        require_positive("E1", e1)?;
        if h.len() != tau.len() {
            return Err(ModelError::table(
                "prony",
                format!(
                    "H has {} entries but tau has {}: they must have the same length",
                    h.len(),
                    tau.len()
                ),
            ));
        }
        for (k, &hk) in h.iter().enumerate() {
            require_non_negative(&format!("H[{k}]"), hk)?;
        }
        for (k, &tk) in tau.iter().enumerate() {
            require_positive(&format!("tau[{k}]"), tk)?;
        }
        let e0 = e1 - h.iter().sum::<f64>();
        if e0.is_nan() || e0 <= 0.0 {
            return Err(ModelError::parameter(
                "E0 = E1 - sum(H)",
                e0,
                "must be greater than zero (the static modulus of a solid)",
            ));
        }
        Ok(Prony {
            glassy_modulus: e1,
            strengths: h,
            relaxation_times: tau,
        })
    }

    /// The series at another temperature, E*(ω, T) = E*_ref(ω a_T) with
    /// log10 a_T = `log10_a_t` (the convention of `modulus::shift`): a
    /// Prony series again, with every τ_k multiplied by a_T, since
    /// iω a_T τ_k/(1 + iω a_T τ_k) is the term of relaxation time a_T τ_k.
    /// The exact rolling cylinder needs the series itself, not a wrapper.
    pub fn shifted(&self, log10_a_t: f64) -> Result<Prony, ModelError> {
        let factor = 10f64.powf(log10_a_t);
        Prony::new(
            self.glassy_modulus,
            self.strengths.clone(),
            self.relaxation_times.iter().map(|t| t * factor).collect(),
        )
    }

    /// The series times the vertical factor b = 10^`log10_b_t`
    /// (`modulus::shift`): b E*(ω) is a Prony series again, with E1 and
    /// every H_k multiplied by b. The exact rolling contact needs the
    /// series itself, not a wrapper.
    pub fn scaled(&self, log10_b_t: f64) -> Result<Prony, ModelError> {
        let factor = 10f64.powf(log10_b_t);
        Prony::new(
            self.glassy_modulus * factor,
            self.strengths.iter().map(|h| h * factor).collect(),
            self.relaxation_times.clone(),
        )
    }

    /// The glassy modulus E1, Pa.
    pub fn glassy_modulus(&self) -> f64 {
        self.glassy_modulus
    }

    /// The strengths H_k, Pa.
    pub fn strengths(&self) -> &[f64] {
        &self.strengths
    }

    /// The relaxation times τ_k, s.
    pub fn relaxation_times(&self) -> &[f64] {
        &self.relaxation_times
    }

    /// The relaxation modulus E(t) = E0 + Σ H_k e^(−t/τ_k), Pa, at time
    /// t ≥ 0 (s): the response to a unit step of strain, whose Fourier
    /// transform is E*(ω) (Ferry 1980, ch. 3). E(0) = E1, E(∞) = E0.
    pub fn relaxation_modulus(&self, t: f64) -> f64 {
        self.static_modulus()
            + self
                .strengths
                .iter()
                .zip(&self.relaxation_times)
                .map(|(h, tau)| h * (-t / tau).exp())
                .sum::<f64>()
    }

    /// Number of terms n.
    pub fn len(&self) -> usize {
        self.strengths.len()
    }

    /// True for a purely elastic series (no terms).
    pub fn is_empty(&self) -> bool {
        self.strengths.is_empty()
    }

    /// Number of parameters (E1, H_1..H_n) = n + 1.
    pub fn parameter_count(&self) -> usize {
        self.strengths.len() + 1
    }

    /// E*(ω) and dE*/d ln ω, and the relaxation factors D_k = 1/(1 + iωτ_k)
    /// written into `factors` (length n): ∂E*/∂H_k = −D_k, ∂E*/∂E1 = 1.
    pub fn evaluate_with_factors(
        &self,
        omega: f64,
        factors: &mut [Complex64],
    ) -> (Complex64, Complex64) {
        let mut e = Complex64::new(self.glassy_modulus, 0.0);
        let mut slope = Complex64::new(0.0, 0.0);
        for ((&h, &tau), d_out) in self
            .strengths
            .iter()
            .zip(&self.relaxation_times)
            .zip(factors.iter_mut())
        {
            let w = omega * tau;
            let inv = 1.0 / (1.0 + w * w);
            let d = Complex64::new(inv, -w * inv);
            *d_out = d;
            e -= h * d;
            // dD/d ln ω = −iw D², so dE/d ln ω = Σ H i w D².
            slope += Complex64::new(0.0, h * w) * d * d;
        }
        (e, slope)
    }
}

impl ViscoelasticModulus for Prony {
    fn modulus(&self, omega: f64) -> Complex64 {
        let mut e = Complex64::new(self.glassy_modulus, 0.0);
        for (&h, &tau) in self.strengths.iter().zip(&self.relaxation_times) {
            let w = omega * tau;
            let inv = h / (1.0 + w * w);
            e.re -= inv;
            e.im += w * inv;
        }
        e
    }

    fn modulus_and_log_slope(&self, omega: f64) -> (Complex64, Complex64) {
        // Per term, with w = ωτ and D = 1/(1 + iw): E −= H D, and
        // dE/d ln ω = Σ H i w D² = Σ H w/(1 + w²)² (2w + i(1 − w²)),
        // written out in reals because this loop is the friction code's
        // innermost one.
        let (mut e_re, mut e_im) = (self.glassy_modulus, 0.0);
        let (mut slope_re, mut slope_im) = (0.0, 0.0);
        for (&h, &tau) in self.strengths.iter().zip(&self.relaxation_times) {
            let w = omega * tau;
            let w2 = w * w;
            let inv = 1.0 / (1.0 + w2);
            let hinv = h * inv;
            e_re -= hinv;
            e_im += w * hinv;
            let hwinv2 = w * hinv * inv;
            slope_re += 2.0 * w * hwinv2;
            slope_im += (1.0 - w2) * hwinv2;
        }
        (
            Complex64::new(e_re, e_im),
            Complex64::new(slope_re, slope_im),
        )
    }

    fn static_modulus(&self) -> f64 {
        self.glassy_modulus - self.strengths.iter().sum::<f64>()
    }

    fn loss_slope_at_zero(&self) -> f64 {
        self.strengths
            .iter()
            .zip(&self.relaxation_times)
            .map(|(h, t)| h * t)
            .sum()
    }

    fn structure_range(&self) -> (f64, f64) {
        let (lo, hi) = self
            .relaxation_times
            .iter()
            .zip(&self.strengths)
            .filter(|(_, h)| **h > 0.0)
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), (&t, _)| {
                (lo.min(t), hi.max(t))
            });
        if hi == 0.0 {
            return (1.0, 1.0);
        }
        (1e-3 / hi, 1e3 / lo)
    }

    fn relaxation_bound(&self) -> Option<f64> {
        Some(self.glassy_modulus)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shifted series is the reference one at ω a_T, as the model's
    /// generic [`super::super::Shifted`] wrapper computes it.
    #[test]
    fn shifted_series_equals_the_shift_wrapper() {
        let p = Prony::new(1e8, vec![5e7, 3e7, 1.5e7], vec![1e-4, 1e-2, 1.0]).unwrap();
        for (log_a, log_b) in [
            (-2.5, 0.0),
            (0.0, 0.0),
            (1.3, 0.0),
            (1.3, -0.07),
            (-0.4, 0.2),
        ] {
            let series = p.shifted(log_a).unwrap().scaled(log_b).unwrap();
            let wrapper = super::super::Shifted::new(p.clone(), log_a)
                .unwrap()
                .with_vertical(log_b)
                .unwrap();
            for &w in &[1e-3, 0.3, 20.0, 4e3] {
                let (a, b) = (series.modulus(w), wrapper.modulus(w));
                assert!(
                    (a - b).norm() <= 1e-12 * b.norm(),
                    "{log_a} {w}: {a} vs {b}"
                );
            }
        }
    }

    #[test]
    fn limits_are_glassy_and_rubbery() {
        let p = Prony::new(1e8, vec![5e7, 3e7, 1.5e7], vec![1e-4, 1e-2, 1.0]).unwrap();
        assert!((p.modulus(0.0).re - 5e6).abs() < 1e-6);
        let hi = p.modulus(1e12);
        assert!((hi.re - 1e8).abs() / 1e8 < 1e-7);
        assert!(hi.im > 0.0);
    }

    #[test]
    fn log_slope_matches_finite_difference() {
        let p = Prony::new(1e8, vec![5e7, 3e7, 1.5e7], vec![1e-4, 1e-2, 1.0]).unwrap();
        for &w in &[1e-3, 0.3, 20.0, 4e3, 1e6] {
            let (_, slope) = p.modulus_and_log_slope(w);
            let eps = 1e-6;
            let fd = (p.modulus(w * f64::exp(eps)) - p.modulus(w * f64::exp(-eps))) / (2.0 * eps);
            assert!((slope - fd).norm() < 1e-6 * p.glassy_modulus(), "{w}");
        }
    }

    #[test]
    fn rejects_non_solid_series() {
        assert!(Prony::new(1e6, vec![2e6], vec![1.0]).is_err());
        assert!(Prony::new(1e6, vec![-1.0], vec![1.0]).is_err());
        assert!(Prony::new(1e6, vec![1.0], vec![0.0]).is_err());
        assert!(Prony::new(1e6, vec![1.0, 2.0], vec![1.0]).is_err());
        assert!(Prony::new(f64::NAN, vec![], vec![]).is_err());
    }
}
