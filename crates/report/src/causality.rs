//! The causality (Kramers–Kronig) check of DMA points as the io crate
//! reads them: the check itself is [`rollfit_fit::causality`] (a
//! non-negative Prony fit and its misfit); here io's points become its
//! samples.

use rollfit_io::dma::DmaPoint;

pub use rollfit_fit::causality::{
    CausalFit, KK_MAX_MISFIT_THRESHOLD, KK_MISFIT_THRESHOLD, ModulusSample, TAU_PER_DECADE, nnls,
    tau_grid,
};

use crate::error::ReportError;

/// [`rollfit_fit::causality::check`] of `points` (reduced to one reference
/// state, Young's moduli > 0).
pub fn check(points: &[DmaPoint]) -> Result<CausalFit, ReportError> {
    Ok(rollfit_fit::causality::check(&samples(points))?)
}

/// io's DMA points as the check's samples.
pub fn samples(points: &[DmaPoint]) -> Vec<ModulusSample> {
    points
        .iter()
        .map(|p| ModulusSample {
            omega: p.omega,
            storage: p.storage,
            loss: p.loss,
            temperature: p.temperature,
        })
        .collect()
}
