//! The one error type of the model crate.

use thiserror::Error;

/// Everything that can go wrong when a scene or a modulus is built or evaluated.
///
/// Parameters are checked when a model object is built, so the numerical code
/// behind a validated object does not fail on bad input; the few variants that
/// can arise during evaluation say which quantity left its valid range.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ModelError {
    /// A scalar parameter is outside its physical range.
    #[error("{name} = {}: {requirement}", shown(*value))]
    InvalidParameter {
        /// Parameter name as used in scene files (e.g. `radius`).
        name: String,
        /// The offending value.
        value: f64,
        /// What the value must satisfy.
        requirement: String,
    },
    /// A list or table is malformed (lengths, ordering, emptiness).
    #[error("{name}: {problem}")]
    InvalidTable {
        /// Name of the list or table.
        name: String,
        /// What is wrong with it.
        problem: String,
    },
    /// The evaluation cannot proceed for this combination of inputs.
    #[error("{0}")]
    Evaluation(String),
    /// The contact map σ = ln(ω a(ω)) stops increasing: the modulus rises
    /// faster than ω^n (n = 3 for a sphere, 2 for a cylinder: a ∝ |E|^{−1/n})
    /// near `omega`, so no contact size solves ω a(ω) = v there. Typed, so
    /// that a front end can point at the table rows that cause it.
    #[error(
        "the contact map ω·a(ω) is not increasing at ω = {omega:e} rad/s (the modulus rises \
         faster than ω^{exponent}); the dynamic contact size is undefined there"
    )]
    ContactMapNotIncreasing {
        /// Angular frequency of the evaluated material, rad/s.
        omega: f64,
        /// n of the rule |E*| ∝ ω^n the modulus outgrows.
        exponent: f64,
    },
}

/// A value as a message shows it: as written for ordinary magnitudes,
/// in exponent form for the extreme ones (1e308 rather than 309 digits).
fn shown(value: f64) -> String {
    let magnitude = value.abs();
    if magnitude == 0.0 || !magnitude.is_finite() || (1e-4..1e9).contains(&magnitude) {
        value.to_string()
    } else {
        format!("{value:e}")
    }
}

impl ModelError {
    /// Shorthand for [`ModelError::InvalidParameter`].
    pub fn parameter(name: &str, value: f64, requirement: &str) -> Self {
        ModelError::InvalidParameter {
            name: name.to_string(),
            value,
            requirement: requirement.to_string(),
        }
    }

    /// Shorthand for [`ModelError::InvalidTable`].
    pub fn table(name: &str, problem: impl Into<String>) -> Self {
        ModelError::InvalidTable {
            name: name.to_string(),
            problem: problem.into(),
        }
    }
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn require_positive(name: &str, value: f64) -> Result<f64, ModelError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(ModelError::parameter(
            name,
            value,
            "must be a finite number greater than zero",
        ))
    }
}

/// Checks that `value` is finite and not negative.
pub(crate) fn require_non_negative(name: &str, value: f64) -> Result<f64, ModelError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(ModelError::parameter(
            name,
            value,
            "must be a finite number, zero or greater",
        ))
    }
}
