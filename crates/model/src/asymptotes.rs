//! Derived quantities. PLACEHOLDER while written; API fixed.

use crate::error::ModelError;
use crate::modulus::ViscoelasticModulus;
use crate::scene::Scene;

/// The friction maximum of μ(v).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionPeak {
    /// Speed of the maximum, m/s.
    pub speed: f64,
    /// μ at the maximum.
    pub mu: f64,
}

impl<M: ViscoelasticModulus> Scene<M> {
    /// Low-speed asymptote μ ≈ c p_a L′(0) v / a0 (Eqs. 18/19), c = 3π/4
    /// for a sphere, 8/π for a cylinder.
    pub fn low_speed_asymptote(&self, v: f64) -> f64 {
        let _ = v;
        f64::NAN
    }

    /// The Greenwood–Tabor hysteresis-loss fraction α that reproduces `mu`.
    pub fn greenwood_tabor_alpha(&self, mu: f64) -> f64 {
        let _ = mu;
        f64::NAN
    }

    /// Pressure-centroid shift x̄ = μR (m).
    pub fn centroid_shift(&self, mu: f64) -> f64 {
        mu * self.geometry().radius
    }

    /// The global maximum of μ(v) for v in [v_min, v_max] (m/s).
    pub fn friction_maximum(&self, v_min: f64, v_max: f64) -> Result<FrictionPeak, ModelError> {
        let _ = (v_min, v_max);
        Err(ModelError::Evaluation("not yet available".into()))
    }
}
