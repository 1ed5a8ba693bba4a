//! # rollfit-fit
//!
//! The inverse problem of rollfit (Persson 2010, Appendix B): recover a
//! rubber's viscoelastic master curve E*(ω) from rolling-friction
//! measurements μ(v).
//!
//! Where each piece lives:
//! - [`data`]: validated measurements; [`condense`]: dense rows to bins.
//! - [`params`]: fit settings, checked before any numerics run.
//! - [`tau_grid`]: the relaxation-time grid and the rule for its ends.
//! - `parametrization`: θ ↦ Prony series, positivity and scale anchors.
//! - `problem`: the objective of Eq. (B3) as residuals with exact Jacobian.
//! - [`solvers`]: Levenberg–Marquardt (default), L-BFGS and Nelder–Mead.
//! - `regularization`: the data-driven choice of the smoothness weight λ.
//! - `shift`: the time–temperature shift of a temperature set (WLF or free)
//!   and shifts by overlapping curves.
//! - `analysis`: the determined window, determined terms, uncertainty bands.
//! - [`quality`]: goodness of fit (χ² and runs tests).
//! - [`sanity`]: warnings for inputs and results outside the theory or any lab.
//! - [`fit`]: the driver tying them together; [`report`]: its result.
//! - [`master`]: DMA isotherms to a master curve: shift factors, their
//!   WLF or Arrhenius law, and a smooth causal Prony series.

pub mod condense;
pub mod data;
pub mod error;
pub mod fit;
pub mod master;
pub mod params;
pub mod regularization;
pub mod report;
pub mod sanity;
pub mod solvers;
pub mod tau_grid;

mod analysis;
mod parametrization;
mod problem;
pub mod quality;
mod shift;
mod temperature_set;

pub use data::Measurements;
pub use error::FitError;
pub use fit::fit;
pub use params::{
    FitParams, Lambda, Method, ModulusAnchor, RollingSetup, ScaleAnchor, ShiftKind, ShiftSettings,
    StartMaterial, TermRule, ValidFitParams,
};
pub use quality::FitQuality;
pub use report::{CrossCheckRow, FitReport, LogShift, ModulusPoint, ShiftCrossCheck, ShiftRecord};
