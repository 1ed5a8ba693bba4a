//! Reports of a rollfit fit: the pictures a user would otherwise draw by
//! hand (μ(v) with residuals, the recovered master curve with its window and
//! bands, the relaxation spectrum, convergence, temperature-set plots), one
//! self-contained HTML page, and the comparison of the recovered master
//! curve with DMA data, including a causality (Kramers–Kronig) check of the
//! DMA data themselves.
//!
//! Everything here reads a fit directory as `rollfit fit` writes it
//! ([`FitDir`]) and returns bytes; the command line writes them (atomically).

pub mod causality;
pub mod compare;
pub mod dma;
pub mod error;
pub mod fit_dir;
pub mod html;
pub mod plot;

pub use error::ReportError;
pub use fit_dir::FitDir;
