//! The one error type of the model crate.

use thiserror::Error;

/// A Poisson's ratio outside the one range every entry point accepts
/// ([`crate::scene::check_poisson`]); the message begins with the key, so
/// that a scene's section or a flag's name can stand in front of it.
#[derive(Debug, Error, Clone, Copy, PartialEq)]
#[error(
    "poisson = {} outside [0, 0.5]: Poisson's ratio of rubber is 0.5 (incompressible) and of \
     the solids rollfit models 0 to 0.5; a negative ν (an auxetic foam) is no rubber, and the \
     exact contact solvers need ν ≥ 0",
    shown(*value)
)]
pub struct PoissonOutOfRange {
    /// The ratio as given.
    pub value: f64,
}

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
    /// Poisson's ratio outside [`crate::scene::POISSON_RANGE`].
    #[error(transparent)]
    Poisson(#[from] PoissonOutOfRange),
    /// A list or table is malformed (lengths, ordering, emptiness).
    #[error("{name}: {problem}")]
    InvalidTable {
        /// Name of the list or table.
        name: String,
        /// What is wrong with it.
        problem: String,
    },
    /// `friction_maximum` was asked for an empty or non-positive speed range.
    #[error("friction maximum: need 0 < v_min < v_max, got [{v_min}, {v_max}]")]
    InvalidSpeedRange {
        /// Lower end, m/s.
        v_min: f64,
        /// Upper end, m/s.
        v_max: f64,
    },
    /// The material reports a frequency range over which its structure
    /// lies that is empty, non-positive or infinite.
    #[error("the material's frequency range [{low}, {high}] rad/s is not usable")]
    UnusableFrequencyRange {
        /// Lower end, rad/s.
        low: f64,
        /// Upper end, rad/s.
        high: f64,
    },
    /// The loss modulus does not vanish like ω^p with 0 < p ≤ 1 at low
    /// frequency, which the tail bounds of the friction integrals assume.
    #[error("the material's low-frequency loss exponent {exponent} is not in (0, 1]")]
    LossExponentOutOfRange {
        /// p of E″ ∝ ω^p as ω → 0.
        exponent: f64,
    },
    /// No finite bound of the loss compliance at low frequency was found,
    /// so the truncation of the friction integral cannot be controlled.
    #[error("the material's loss compliance could not be bounded at low frequency")]
    LossComplianceUnbounded,
    /// The Newton iteration for the contact size at a grid node did not
    /// converge (the contact map is too irregular there).
    #[error("the contact size did not converge at σ = {sigma}")]
    ContactSizeNotConverged {
        /// σ = ln(ω a) of the node.
        sigma: f64,
    },
    /// The friction quadrature grid outgrew its node limit.
    #[error("friction quadrature needs too many nodes")]
    TooManyQuadratureNodes,
    /// `friction_auto` was handed an exact cylinder built for another scene.
    #[error(
        "auto: the exact cylinder's static half-width {exact:e} m is not the scene's {scene:e} m"
    )]
    ExactCylinderMismatch {
        /// Static half-width of the exact cylinder, m.
        exact: f64,
        /// Static half-width of the scene, m.
        scene: f64,
    },
    /// No exact rolling solution exists for this body or substrate.
    #[error("no exact rolling solution: {why}")]
    ExactNotAvailable {
        /// Why not.
        why: &'static str,
    },
    /// The active-set iteration or the linear solves of the exact sphere did
    /// not converge.
    #[error("exact rolling sphere: the contact did not converge at v = {speed} m/s")]
    ExactSphereNotConverged {
        /// Rolling speed, m/s.
        speed: f64,
    },
    /// The exact cylinder's settings leave too few terms or quadrature nodes.
    #[error("exact rolling cylinder: need at least 2 terms and 4 quadrature nodes")]
    ExactTooCoarse,
    /// The collocation system of the exact cylinder is singular (an
    /// internal fault: a valid scene should never produce it).
    #[error("exact rolling cylinder: singular collocation system at v = {speed} m/s")]
    ExactSingularSystem {
        /// Rolling speed, m/s.
        speed: f64,
    },
    /// The Newton iteration for the contact edges of the exact cylinder did
    /// not converge.
    #[error("exact rolling cylinder: the contact edges did not converge at v = {speed} m/s")]
    ExactEdgesNotConverged {
        /// Rolling speed, m/s.
        speed: f64,
    },
    /// A temperature at or below the pole of the WLF form.
    #[error(
        "WLF shift at T = {temperature} °C: C2 + T - T_ref = {denominator} K is not positive \
         (C2 = {c2} K, T_ref = {t_ref} °C); the WLF form diverges at T = T_ref - C2 = {} °C \
         and does not apply at or below it",
        t_ref - c2
    )]
    WlfBeyondPole {
        /// Requested temperature, °C.
        temperature: f64,
        /// C2 + T − T_ref, K.
        denominator: f64,
        /// C2, K.
        c2: f64,
        /// Reference temperature, °C.
        t_ref: f64,
    },
    /// A temperature outside the listed temperatures of a free shift.
    #[error(
        "no shift factor for T = {temperature} °C: it lies outside the temperatures of the \
         free shift, {lowest} to {highest} °C (listed: {listed} °C); log10 a_T is interpolated \
         linearly between listed temperatures but not extrapolated beyond them"
    )]
    OutsideFreeShift {
        /// Requested temperature, °C.
        temperature: f64,
        /// Lowest listed temperature, °C.
        lowest: f64,
        /// Highest listed temperature, °C.
        highest: f64,
        /// The listed temperatures as shown, T_ref marked.
        listed: String,
    },
    /// A temperature outside the listed temperatures of a table of vertical
    /// factors ([`crate::modulus::VerticalShift::table`]).
    #[error(
        "no vertical factor for T = {temperature} °C: it lies outside the temperatures of the \
         table of log10 b_T, {lowest} to {highest} °C (listed: {listed} °C); log10 b_T is \
         interpolated linearly between listed temperatures but not extrapolated beyond them"
    )]
    OutsideVerticalTable {
        /// Requested temperature, °C.
        temperature: f64,
        /// Lowest listed temperature, °C.
        lowest: f64,
        /// Highest listed temperature, °C.
        highest: f64,
        /// The listed temperatures as shown, T_ref marked.
        listed: String,
    },
    /// A film under a sphere: μ or its derivatives came out non-finite (an
    /// internal fault).
    #[error("film under a sphere: {what} not finite at v = {speed:e} m/s")]
    FilmNotFinite {
        /// "μ is" or "the derivatives of μ are".
        what: &'static str,
        /// Rolling speed, m/s.
        speed: f64,
    },
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
pub(crate) fn shown(value: f64) -> String {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The typed variants print fixed sentences: front ends and users read
    /// these texts, and tests elsewhere assert them.
    #[test]
    fn messages_read_as_sentences() {
        let pole = ModelError::WlfBeyondPole {
            temperature: -90.0,
            denominator: -8.4,
            c2: 101.6,
            t_ref: 20.0,
        };
        assert_eq!(
            pole.to_string(),
            "WLF shift at T = -90 °C: C2 + T - T_ref = -8.4 K is not positive (C2 = 101.6 K, \
             T_ref = 20 °C); the WLF form diverges at T = T_ref - C2 = -81.6 °C and does not \
             apply at or below it"
        );
        let free = ModelError::OutsideFreeShift {
            temperature: 90.0,
            lowest: -10.0,
            highest: 60.0,
            listed: "-10, 20 (T_ref), 60".into(),
        };
        assert_eq!(
            free.to_string(),
            "no shift factor for T = 90 °C: it lies outside the temperatures of the free shift, \
             -10 to 60 °C (listed: -10, 20 (T_ref), 60 °C); log10 a_T is interpolated linearly \
             between listed temperatures but not extrapolated beyond them"
        );
    }
}
