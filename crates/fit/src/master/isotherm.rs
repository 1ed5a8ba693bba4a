//! The measurement the master curve is built from: isotherms of any kind
//! (a frequency sweep here, a relaxation or creep run in
//! [`super::relaxation`]) share [`Sweep`], what grouping and merging need.

use super::repeats::Averaged;

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

/// An isotherm over an abscissa (ω in rad/s, or t in s) with its measured
/// quantities at each: what the steps before the kind-specific numerics
/// (grouping, averaging of repeated abscissae) treat alike.
pub trait Sweep: Sized {
    /// The isotherm at `temperature` of the averaged points, whose
    /// `quantities` are its measured quantities in order (E′ and E″; or
    /// E(t); or D(t)).
    fn from_averaged(temperature: f64, averaged: Averaged) -> Self;
}

impl Sweep for Isotherm {
    fn from_averaged(temperature: f64, averaged: Averaged) -> Self {
        let mut quantities = averaged.quantities.into_iter();
        Isotherm {
            temperature,
            omega: averaged.abscissa,
            storage: quantities.next().unwrap_or_default(),
            loss: quantities.next().unwrap_or_default(),
        }
    }
}
