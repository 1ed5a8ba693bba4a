//! μ(v). PLACEHOLDER while the quadrature is written; API fixed.

use crate::error::ModelError;
use crate::modulus::{Prony, ViscoelasticModulus};
use crate::scene::Scene;

/// μ at several speeds and its derivatives with respect to the Prony
/// parameters p = (E1, H_1, …, H_n).
#[derive(Debug, Clone, PartialEq)]
pub struct FrictionJacobian {
    /// μ(v_i).
    pub mu: Vec<f64>,
    /// ∂μ(v_i)/∂p_j, row-major: `jacobian[i * parameter_count + j]`, 1/Pa.
    pub jacobian: Vec<f64>,
    /// Number of parameters n + 1.
    pub parameter_count: usize,
}

impl<M: ViscoelasticModulus> Scene<M> {
    /// The friction coefficient μ at rolling speed `v` (m/s).
    pub fn friction(&self, v: f64) -> Result<f64, ModelError> {
        Err(ModelError::Evaluation(format!("not yet available at v = {v}")))
    }

    /// μ at each of `speeds` (m/s), sharing the modulus evaluations.
    pub fn friction_sweep(&self, speeds: &[f64]) -> Result<Vec<f64>, ModelError> {
        speeds.iter().map(|&v| self.friction(v)).collect()
    }
}

impl Scene<Prony> {
    /// μ at each of `speeds` and ∂μ/∂(E1, H_1..H_n), computed in one pass.
    pub fn friction_with_gradient(&self, speeds: &[f64]) -> Result<FrictionJacobian, ModelError> {
        Err(ModelError::Evaluation(format!(
            "not yet available for {} speeds",
            speeds.len()
        )))
    }
}
