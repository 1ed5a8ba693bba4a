//! Tabulated master curve (measured E′, E″ on a frequency grid).
//! PLACEHOLDER: being written (helper task); API fixed.

use num_complex::Complex64;

use super::ViscoelasticModulus;
use crate::error::ModelError;

/// A measured master curve E′(ω), E″(ω), interpolated in log–log.
#[derive(Debug, Clone, PartialEq)]
pub struct TabulatedModulus {
    omega: Vec<f64>,
    storage: Vec<f64>,
    loss: Vec<f64>,
}

impl TabulatedModulus {
    /// Builds a validated table from angular frequencies (rad/s, strictly
    /// increasing), storage and loss moduli (Pa, positive).
    pub fn new(omega: Vec<f64>, storage: Vec<f64>, loss: Vec<f64>) -> Result<Self, ModelError> {
        Ok(TabulatedModulus { omega, storage, loss })
    }
}

impl ViscoelasticModulus for TabulatedModulus {
    fn modulus(&self, _omega: f64) -> Complex64 {
        Complex64::new(self.storage[0], self.loss[0])
    }
    fn modulus_and_log_slope(&self, omega: f64) -> (Complex64, Complex64) {
        (self.modulus(omega), Complex64::new(0.0, 0.0))
    }
    fn static_modulus(&self) -> f64 {
        self.storage[0]
    }
    fn loss_slope_at_zero(&self) -> f64 {
        self.loss[0] / self.omega[0]
    }
    fn structure_range(&self) -> (f64, f64) {
        (self.omega[0], self.omega[self.omega.len() - 1])
    }
}
