//! # rollfit-fit
//!
//! The inverse problem of rollfit (Persson 2010, Appendix B): recover a
//! rubber's viscoelastic master curve E*(ω) from rolling-friction
//! measurements μ(v).
//!
//! Where each piece lives:
//! - [`data`]: validated measurements; `condense`: dense rows to bins.
//! - `params`: fit settings, checked before any numerics run.
//! - [`tau_grid`]: the relaxation-time grid and the rule for its ends.
//! - `parametrization`: θ ↦ Prony series, positivity and scale anchors.
//! - `objective`: the objective of Eq. (B3) as residuals with exact Jacobian.
//! - `solvers`: Levenberg–Marquardt (default), L-BFGS and Nelder–Mead, each
//!   run on the objective through a wrapper that counts its evaluations.
//! - `regularization`: the data-driven choice of the smoothness weight λ.
//! - `shift`: the time–temperature shift of a temperature set (WLF or free)
//!   and shifts by overlapping curves.
//! - `analysis`: the determined window, determined terms, uncertainty bands.
//! - [`quality`]: goodness of fit (χ² and runs tests).
//! - `extrapolation`: the fitted values beyond the window the data determine.
//! - `temperature_set`: the start and the cross-check of a temperature set's
//!   shift; [`vertical`]: its vertical factors b_T, as a load per row.
//! - [`exact_physics`]: fits against the exact rolling contact by defect
//!   correction around the approximate model (`physics = "exact"`).
//! - `driver`: the driver tying them together, entered by [`fit()`];
//!   [`report`]: its result.
//! - [`master`]: DMA isotherms to a master curve: shift factors, their
//!   WLF or Arrhenius law, and a smooth causal Prony series.
//! - [`causality`]: the Kramers–Kronig check of measured E′ and E″ (can any
//!   linear viscoelastic solid have both?), by non-negative least squares;
//!   [`compare`]: the errors of a fitted curve against measured values.

//! # Example
//!
//! μ(v) at 21 speeds made by the forward model from a standard linear
//! solid (σ = 1 % given, no noise), fitted back: in the middle of the
//! window of frequencies the speeds determine, the recovered tan δ is the
//! truth's to better than 1 % (measured: 0.26 %).
//!
//! ```
//! use rollfit_fit::{FitParams, Measurements, RollingSetup, fit};
//! use rollfit_model::{
//!     ContactSize, Geometry, Prony, Scene, Shape, StandardLinearSolid, Substrate,
//!     ViscoelasticModulus,
//! };
//!
//! let setup = RollingSetup {
//!     geometry: Geometry { shape: Shape::Sphere, radius: 0.01, load: 1.0 },
//!     substrate: Substrate { poisson: 0.5, film_thickness: None },
//!     contact: ContactSize::Dynamic,
//! };
//! let truth = StandardLinearSolid::new(1e6, 1e8, 1e-2)?;
//! let scene = Scene::new(setup.geometry, setup.substrate, setup.contact, truth.clone())?;
//! let speeds: Vec<f64> = (0..21).map(|k| 10f64.powf(-6.0 + 0.3 * k as f64)).collect();
//! let mu = scene.friction_sweep(&speeds)?;
//! let sigma = mu.iter().map(|m| 0.01 * m).collect();
//! let data = Measurements::new(speeds, mu, Some(sigma), None)?;
//!
//! let report = fit(&data, &FitParams::default().check(setup)?)?;
//! assert!(report.converged);
//! let m = &report.model;
//! let recovered = Prony::new(m.glassy_modulus, m.strengths.clone(), m.tau.clone())?;
//! let middle = (report.window.omega_min * report.window.omega_max).sqrt();
//! let (e, t) = (recovered.modulus(middle), truth.modulus(middle));
//! let error = (e.im / e.re) / (t.im / t.re) - 1.0;
//! assert!(error.abs() < 0.01, "tan δ off by {error} at {middle:e} rad/s");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

// The modules other crates use.
pub mod causality;
pub mod compare;
pub mod data;
pub mod exact_physics;
pub mod joint;
pub mod master;
pub mod quality;
pub mod report;
pub mod settings;
pub mod tau_grid;
pub mod vertical;

// The inverse problem's machinery, reached through the items below.
mod analysis;
mod cancel;
mod condense;
mod dma_rows;
mod driver;
mod error;
mod extrapolation;
mod objective;
mod parametrization;
mod params;
mod progress;
mod regularization;
mod shift;
mod solvers;
mod temperature_set;

pub use cancel::Cancel;
pub use data::Measurements;
pub use driver::fit;
pub use error::FitError;
pub use joint::{DmaRows, JointRecord};
pub use params::{
    FitParams, FrictionFactor, Lambda, Method, ModulusAnchor, Physics, RollingSetup, ScaleAnchor,
    ShiftKind, ShiftSettings, ShiftSubstitute, StartMaterial, TermRule, ValidFitParams,
};
pub use progress::{Observer, Progress};
pub use quality::FitQuality;
pub use report::{
    CrossCheckRow, FitReport, LawCandidate, LogShift, ModulusPoint, PhysicsRecord, ScaleRecord,
    ShiftChoice, ShiftCrossCheck, ShiftRecord,
};
pub use settings::{FitSettings, SettingValue};
