//! One master curve from DMA isotherms and rolling friction together
//!.
//!
//! A DMA sweep measures E*(ω) at a few temperatures over 0.1–100 Hz; rolling
//! over 1e-6 … 1 m/s reaches reduced frequencies the isotherms reach only
//! through long shift chains, or not at all. The DMA data fix the modulus
//! scale and the shift law, which μ(v) determines only weakly; μ(v), in
//! turn, tests whether the friction is the bulk hysteresis Persson's theory
//! assumes. The joint fit fits one Prony series at T_ref and one shift law
//! to both:
//!
//!   V(θ) = Σ_i [(κ μ_th(v_i a_{T_i}; θ) − μ_i)/σ_i]²
//!        + Σ_j {[ln(b_T E′(ω_j a_{T_j})) − ln E′_j]² + [ln(b_T E″(ω_j a_{T_j})) − ln E″_j]²}/σ_D²
//!        + λ Σ_k (Δ² ln H_k)² + P(θ),
//!
//! the rolling rows of Eq. (B3) ([`crate::objective`]) and two rows per DMA
//! point ([`residuals`]), κ = 1 or fitted (`friction_factor = "free"`).
//! No anchor is needed: the DMA rows fix the scale.
//!
//! Weights. Each part is weighted by its own σ, given (a rolling σ column,
//! `dma_sigma`) or estimated from that part fitted alone: the rolling
//! rows' relative σ from the rolling fit alone (its noise estimate), the
//! DMA moduli's from the master curve of the isotherms alone
//! ([`start`]). λ and a common noise level are chosen by the marginal
//! likelihood, whatever σ is given: the compatibility test compares the
//! parts' minima, which the discrepancy principle (χ² = N by construction)
//! does not give.
//!
//! Steps (`crate::driver`'s `joint.rs`):
//! 1. The DMA part alone ([`alone`]): `rollfit master`'s master curve, or
//!    each isotherm its own curve where the isotherms determine no shift
//!    between them; its χ² and effective parameters, its σ when not
//!    given, and which shifts it determines. It never refuses the joint
//!    fit by itself.
//! 2. The rolling part alone: the usual fit (no scale profile, λ by the
//!    marginal likelihood) under the law asked for; with `shift = "auto"`
//!    first with free shifts, whose pairs join the DMA's determined pairs
//!    to choose the law on both parts together ([`law`]), then again
//!    under that law when it is not free. Its χ², effective parameters
//!    and σ when not given.
//! 3. The start ([`start`]): at every temperature of either part the DMA
//!    part's shift where it determines it, else the rolling fit's; a
//!    temperature neither determines is refused, named, as the DMA file's
//!    problem. The spectrum of the DMA master curve (or of a series on the
//!    DMA points at those shifts) on the joint τ grid, which covers the
//!    band the rolling speeds probe and the DMA's reduced frequencies.
//! 4. Both together: the λ path of [`crate::driver`] on the joint objective
//!    from that start, one start (the DMA master is the exploration), the
//!    usual analysis: bands, shift σ, window (the DMA points widen the
//!    probed window).
//! 5. The account ([`JointRecord`], [`consistency`]): each part's χ² at the
//!    joint optimum and alone, the compatibility test, κ with its σ, the
//!    residuals of each part per decade of reduced frequency, and the DMA
//!    points with the joint curve. Incompatible parts make the verdict
//!    "poor".
//!
//! Rolling data without a `T` column are taken at the given T_ref. The
//! exact physics is not available in a joint fit (its defect correction
//! acts on the rolling rows alone).

pub(crate) mod alone;
pub(crate) mod consistency;
pub(crate) mod law;
mod record;
mod residuals;
pub(crate) mod start;

pub use crate::dma_rows::{DMA_MODULUS_RANGE, DMA_OMEGA_RANGE, DmaRows};
pub use crate::params::DMA_SIGMA_RANGE;
pub use record::{
    Compatibility, DmaAloneRecord, DmaAloneShift, DmaFitPoint, FrictionFactorRecord, JointRecord,
    JointSigma, PartChi2, ResidualRange,
};
pub(crate) use residuals::DmaBlock;
pub(crate) use residuals::moduli_at;

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
