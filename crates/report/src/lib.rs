//! Reports of a rollfit fit (docs/ARCHITECTURE.md, "Crates"): the pictures
//! a user would otherwise draw by hand (μ(v) with residuals and the fitted
//! curve on a dense grid of speeds, the recovered master curve with its
//! window and bands, the relaxation spectrum, convergence, temperature-set
//! plots), one self-contained HTML page that leads with the fit's verdict
//! and scale, and the comparison of the recovered master curve with DMA
//! data (its record and rows; the numbers, the errors and the causality
//! (Kramers–Kronig) check of the DMA data themselves, are
//! [`rollfit_fit::compare`] and [`rollfit_fit::causality`]).
//!
//! Everything here works on a fit folder and DMA data as the io crate reads
//! them ([`rollfit_io::FitDir`], [`rollfit_io::dma::DmaData`]), and on the
//! fit's scene for the dense fitted μ(v) ([`fitted_friction`]), and returns
//! bytes or numbers; it reads and writes no file itself.

pub mod causality;
pub mod compare;
pub mod dma_shift;
mod error;
pub mod fitted_friction;
pub mod html;
pub mod master_input;
pub mod plot;
pub mod relaxation_compare;

pub use error::ReportError;
