//! Standard linear solid, Persson (2010) Eq. (12):
//!
//! E*(ω) = E1 (1 + iωτ) / (E1/E0 + iωτ),
//!
//! rubbery modulus E0 at ω → 0, glassy modulus E1 at ω → ∞. It is the
//! one-term Prony series with strength E1 − E0 and relaxation time τ E0/E1.
//! Its loss tangent peaks at ωτ = (E0/E1)^½ and the low-frequency slope of the
//! loss compliance is L′(0) = τ (1/E0 − 1/E1) (before the factor 1 − ν²).

use num_complex::Complex64;

use super::{Prony, ViscoelasticModulus};
use crate::error::{ModelError, require_positive};

/// Standard linear solid: rubbery modulus `E0` (Pa), glassy modulus `E1` (Pa),
/// time constant `tau` (s) in the paper's parametrisation.
#[derive(Debug, Clone, PartialEq)]
pub struct StandardLinearSolid {
    rubbery_modulus: f64,
    glassy_modulus: f64,
    tau: f64,
    equivalent: Prony,
}

impl StandardLinearSolid {
    /// Builds a validated solid; requires 0 < E0 ≤ E1 and τ > 0.
    pub fn new(e0: f64, e1: f64, tau: f64) -> Result<Self, ModelError> {
        require_positive("E0", e0)?;
        require_positive("E1", e1)?;
        require_positive("tau", tau)?;
        if e1 < e0 {
            return Err(ModelError::parameter(
                "E1",
                e1,
                &format!("must be at least E0 = {e0} (the glassy modulus exceeds the rubbery one)"),
            ));
        }
        let equivalent = Prony::new(e1, vec![e1 - e0], vec![tau * e0 / e1])?;
        Ok(StandardLinearSolid {
            rubbery_modulus: e0,
            glassy_modulus: e1,
            tau,
            equivalent,
        })
    }

    /// Rubbery modulus E0, Pa.
    pub fn rubbery_modulus(&self) -> f64 {
        self.rubbery_modulus
    }

    /// Glassy modulus E1, Pa.
    pub fn glassy_modulus(&self) -> f64 {
        self.glassy_modulus
    }

    /// The paper's time constant τ, s.
    pub fn tau(&self) -> f64 {
        self.tau
    }

    /// The same solid as a one-term Prony series.
    pub fn to_prony(&self) -> Prony {
        self.equivalent.clone()
    }
}

impl ViscoelasticModulus for StandardLinearSolid {
    fn modulus(&self, omega: f64) -> Complex64 {
        self.equivalent.modulus(omega)
    }
    fn modulus_and_log_slope(&self, omega: f64) -> (Complex64, Complex64) {
        self.equivalent.modulus_and_log_slope(omega)
    }
    fn static_modulus(&self) -> f64 {
        self.rubbery_modulus
    }
    fn loss_slope_at_zero(&self) -> f64 {
        self.equivalent.loss_slope_at_zero()
    }
    fn structure_range(&self) -> (f64, f64) {
        self.equivalent.structure_range()
    }
    fn relaxation_bound(&self) -> Option<f64> {
        Some(self.glassy_modulus)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equals_equation_12() {
        let s = StandardLinearSolid::new(1e6, 1e7, 1.0).unwrap();
        for &w in &[1e-4, 0.1, 1.0, 3.0, 1e3] {
            let i = Complex64::new(0.0, 1.0);
            let direct = 1e7 * (1.0 + i * w) / (10.0 + i * w);
            assert!((s.modulus(w) - direct).norm() < 1e-8 * direct.norm());
        }
        assert!((s.loss_slope_at_zero() - 1e6 * 1.0 * 0.9).abs() < 1e-6);
    }
}
