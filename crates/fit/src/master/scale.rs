//! The modulus scale a master curve accepts: every E′, E″ (and E(t) of
//! relaxation data) inside [`DMA_MODULUS_RANGE`] = 1 Pa … 1e13 Pa, the
//! range the joint fit's DMA rows accept ([`crate::dma_rows`]).
//!
//! Why 1 Pa: the softest solids measured by DMA (gels, soft silicones)
//! have moduli of 10 Pa – 100 kPa, rubbers 1–10 MPa at rest and 1–3 GPa
//! glassy. A rubber's moduli written in MPa under a Pa header put E′ at
//! 1–3000 "Pa" and E″ of the rubbery plateau below 1 "Pa": the numbers are
//! the right shape but a factor 1e6 off, which superposition and the
//! Prony fit cannot notice (both work in logarithms). The upper bound,
//! 1e13 Pa, is stiffer than diamond.

use crate::dma_rows::DMA_MODULUS_RANGE;
use crate::error::FitError;

/// Refuses a modulus of the isotherm at `temperature` (°C) outside
/// [`DMA_MODULUS_RANGE`]; `moduli` are (point number from 1, name, Pa).
pub(crate) fn check_modulus_scale<'a>(
    temperature: f64,
    moduli: impl IntoIterator<Item = (usize, &'a str, f64)>,
) -> Result<(), FitError> {
    let (lo, hi) = DMA_MODULUS_RANGE;
    match moduli
        .into_iter()
        .find(|&(_, _, e)| !(e.is_finite() && (lo..=hi).contains(&e)))
    {
        None => Ok(()),
        Some((point, name, e)) => Err(FitError::InsufficientData(format!(
            "isotherm at {temperature} °C, point {point}: {name} = {e} Pa must lie in 1 … 1e13 \
             Pa (is the modulus in Pa? a rubber's moduli in MPa read as Pa lie a factor 1e6 \
             too low: give the column its unit, e.g. E_storage_MPa or \"E' [MPa]\")"
        ))),
    }
}
