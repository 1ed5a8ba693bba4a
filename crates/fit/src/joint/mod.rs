//! One master curve from DMA isotherms and rolling friction together
//! (issue 35).
//!
//! PLACEHOLDER DOC — replaced with the method below once the driver lands.

pub(crate) mod consistency;
mod record;
mod residuals;
mod rows;
pub(crate) mod start;

pub use record::{
    Compatibility, DmaFitPoint, FrictionFactorRecord, JointRecord, JointSigma, PartChi2,
    ResidualRange,
};
pub(crate) use residuals::DmaBlock;
pub(crate) use residuals::moduli_at;
pub use rows::{DMA_MODULUS_RANGE, DMA_OMEGA_RANGE, DMA_SIGMA_RANGE, DmaRows};

use crate::error::FitError;
use crate::params::{FrictionFactor, ValidFitParams};

/// The settings that only a joint fit reads are refused without DMA data,
/// naming the key: a κ or a DMA σ that silently did nothing would pass for
/// a result.
pub(crate) fn refuse_without_dma(params: &ValidFitParams) -> Result<(), FitError> {
    if params.friction_factor == FrictionFactor::Free {
        return Err(FitError::setting(
            "friction_factor",
            "\"free\" fits κ in μ_measured = κ μ_theory against DMA data; without DMA data \
             (`dma = FILE`, `--dma FILE`) κ and the modulus scale trade off undetermined",
        ));
    }
    if params.dma_sigma.is_some() {
        return Err(FitError::setting(
            "dma_sigma",
            "the σ of DMA moduli needs DMA data (`dma = FILE`, `--dma FILE`)",
        ));
    }
    Ok(())
}
