//! The measurement the master curve is built from.

/// One DMA isotherm: E*(ω) at one temperature.
#[derive(Debug, Clone, PartialEq)]
pub struct Isotherm {
    /// Temperature, °C.
    pub temperature: f64,
    /// Angular frequencies, rad/s, monotone (a sweep up or down).
    pub omega: Vec<f64>,
    /// E′ at each frequency, Pa.
    pub storage: Vec<f64>,
    /// E″ at each frequency, Pa.
    pub loss: Vec<f64>,
}
