//! The one error type of the fit crate.

use rollfit_model::ModelError;
use thiserror::Error;

/// Everything that can stop a fit before it produces a result.
///
/// Settings and data are validated before any numerics run (see
/// [`crate::FitParams::check`] and [`crate::Measurements::new`]); a fit that
/// runs but does not converge is not an error — it is reported in
/// [`crate::FitReport::converged`] with the reason.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum FitError {
    /// The causality check of measured moduli was given no points.
    #[error("causality check: no DMA points")]
    NoCausalityPoints,
    /// Measured moduli whose weights in the causality check overflow.
    #[error(
        "causality check: the DMA moduli span more than a floating-point number can weigh (a \
         modulus near 1e-308?)"
    )]
    CausalityModuliOutOfRange,
    /// A measured value is unusable (row numbers count data rows from 1).
    #[error("data row {row}: {column} = {value}: {requirement}")]
    InvalidData {
        /// Data row, counting from 1.
        row: usize,
        /// Column name (`v`, `mu`, `sigma`, `T`).
        column: &'static str,
        /// The offending value.
        value: f64,
        /// What the value must satisfy.
        requirement: &'static str,
    },
    /// The data set as a whole cannot be fitted (too few measurements,
    /// speeds, temperatures or isotherms; the text says which and why).
    #[error("{0}")]
    InsufficientData(String),
    /// The DMA isotherms of a joint fit, as a whole, cannot be used (the
    /// text says why); `file` names their file as the front end gave it.
    #[error("DMA file {file}: {why}")]
    DmaData {
        /// The DMA file, as [`crate::DmaRows`] names it.
        file: String,
        /// What is wrong with its isotherms.
        why: String,
    },
    /// The columns handed to [`crate::Measurements::new`] differ in length.
    #[error("the data columns have different lengths")]
    ColumnLengths,
    /// A fit setting is outside its valid range.
    #[error("fit setting `{key}`: {problem}")]
    InvalidSetting {
        /// Key as used in the scene file's `[fit]` table or on the command line.
        key: String,
        /// What is wrong.
        problem: String,
    },
    /// The fit ended with a number that is not finite (the key names it);
    /// no result can be trusted or written.
    #[error(
        "the fit produced a number that is not finite ({0}); the data or the scene hold values \
         the model cannot represent"
    )]
    NonFinite(String),
    /// A broken invariant of the fit itself, not a fault of the input: a
    /// front end reports it as a fault of rollfit, not of the user's files.
    #[error(
        "internal fault of the fit: {0} (a bug in rollfit; please report it with the scene and data)"
    )]
    Internal(&'static str),
    /// With `physics = "exact"`: the exact rolling contact of a fitted
    /// modulus failed, or gave a μ no exact solution can have, at one speed
    /// on the master curve.
    #[error(
        "physics = \"exact\": the exact rolling contact of the fitted modulus at \
         v = {speed:e} m/s (on the master curve): {problem}"
    )]
    ExactPhysics {
        /// The speed, m/s (v·a_T for a temperature set).
        speed: f64,
        /// What went wrong.
        problem: String,
    },
    /// The fit was cancelled through its [`crate::Cancel`] flag (Ctrl-C
    /// in a Python session).
    #[error("the fit was cancelled")]
    Cancelled,
    /// The forward model refused a scene or a material.
    #[error(transparent)]
    Model(#[from] ModelError),
}

impl FitError {
    /// Shorthand for [`FitError::InvalidSetting`].
    pub fn setting(key: &str, problem: impl Into<String>) -> Self {
        FitError::InvalidSetting {
            key: key.to_string(),
            problem: problem.into(),
        }
    }
}
