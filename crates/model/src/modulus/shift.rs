//! Time–temperature superposition. PLACEHOLDER: being written (helper task); API fixed.

use num_complex::Complex64;

use super::ViscoelasticModulus;
use crate::error::ModelError;

/// WLF shift: log10 a_T = −C1 (T − T_ref)/(C2 + T − T_ref); temperatures in °C.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wlf {
    /// Reference temperature, °C.
    pub t_ref: f64,
    /// C1 (dimensionless).
    pub c1: f64,
    /// C2, K.
    pub c2: f64,
}

impl Wlf {
    /// Validated WLF constants.
    pub fn new(t_ref: f64, c1: f64, c2: f64) -> Result<Self, ModelError> {
        Ok(Wlf { t_ref, c1, c2 })
    }

    /// log10 a_T at temperature `t` (°C).
    pub fn log10_shift(&self, t: f64) -> Result<f64, ModelError> {
        Ok(-self.c1 * (t - self.t_ref) / (self.c2 + t - self.t_ref))
    }
}

/// E(ω, T) = E_ref(ω a_T): a modulus at reference temperature, shifted.
#[derive(Debug, Clone, PartialEq)]
pub struct Shifted<M> {
    inner: M,
    shift_factor: f64,
}

impl<M: ViscoelasticModulus> Shifted<M> {
    /// Wraps `inner` (the modulus at T_ref) with shift factor 10^`log10_a_t`.
    pub fn new(inner: M, log10_a_t: f64) -> Result<Self, ModelError> {
        Ok(Shifted {
            inner,
            shift_factor: 10f64.powf(log10_a_t),
        })
    }
}

impl<M: ViscoelasticModulus> ViscoelasticModulus for Shifted<M> {
    fn modulus(&self, omega: f64) -> Complex64 {
        self.inner.modulus(omega * self.shift_factor)
    }
    fn modulus_and_log_slope(&self, omega: f64) -> (Complex64, Complex64) {
        self.inner.modulus_and_log_slope(omega * self.shift_factor)
    }
    fn static_modulus(&self) -> f64 {
        self.inner.static_modulus()
    }
    fn loss_slope_at_zero(&self) -> f64 {
        self.inner.loss_slope_at_zero() * self.shift_factor
    }
    fn structure_range(&self) -> (f64, f64) {
        let (a, b) = self.inner.structure_range();
        (a / self.shift_factor, b / self.shift_factor)
    }
}
