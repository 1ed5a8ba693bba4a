//! Measured rolling friction: speeds, friction coefficients, optional
//! standard deviations and temperatures, validated once.
//!
//! Repeated speeds and unsorted rows are normal in real data and accepted as
//! they are; every value must be finite and positive (μ > 0 because the
//! default weights are relative, 1/μ²).

use crate::error::FitError;

/// A validated set of μ(v) measurements.
#[derive(Debug, Clone, PartialEq)]
pub struct Measurements {
    speeds: Vec<f64>,
    friction: Vec<f64>,
    sigma: Option<Vec<f64>>,
    temperature: Option<Vec<f64>>,
}

fn check_column(
    values: &[f64],
    column: &'static str,
    allow_zero_or_negative: bool,
) -> Result<(), FitError> {
    for (i, &value) in values.iter().enumerate() {
        if !value.is_finite() {
            return Err(FitError::InvalidData {
                row: i + 1,
                column,
                value,
                requirement: "must be a finite number",
            });
        }
        if !allow_zero_or_negative && value <= 0.0 {
            return Err(FitError::InvalidData {
                row: i + 1,
                column,
                value,
                requirement: "must be greater than zero",
            });
        }
    }
    Ok(())
}

/// The fewest distinct speeds a fit accepts. Rows, not speeds, would let
/// repeated measurements at one speed pass for information about the shape
/// of μ(v); the smoothness penalty leaves a power-law spectrum (two
/// parameters) and, unanchored, the modulus scale (a third) to the data, and
/// the residuals need at least one degree of freedom of their own.
pub const MIN_DISTINCT_SPEEDS: usize = 4;

/// Number of distinct (speed, temperature) pairs (exact comparison:
/// repeated rows at one speed carry the same number; one speed at two
/// temperatures is two points of the master curve).
fn distinct_count(speeds: &[f64], temperature: Option<&[f64]>) -> usize {
    let mut pairs: Vec<(f64, f64)> = speeds
        .iter()
        .enumerate()
        .map(|(i, &v)| (v, temperature.map_or(0.0, |t| t[i])))
        .collect();
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    pairs.dedup();
    pairs.len()
}

impl Measurements {
    /// Speeds `v` (m/s), friction coefficients `mu`, optional standard
    /// deviations `sigma` of μ and temperatures `temperature` (°C), one
    /// entry per measurement.
    pub fn new(
        speeds: Vec<f64>,
        friction: Vec<f64>,
        sigma: Option<Vec<f64>>,
        temperature: Option<Vec<f64>>,
    ) -> Result<Self, FitError> {
        if speeds.is_empty() {
            return Err(FitError::InsufficientData(
                "the data hold no measurements".into(),
            ));
        }
        let n = speeds.len();
        let lengths_agree = friction.len() == n
            && sigma.as_ref().is_none_or(|s| s.len() == n)
            && temperature.as_ref().is_none_or(|t| t.len() == n);
        if !lengths_agree {
            return Err(FitError::InsufficientData(
                "the data columns have different lengths".into(),
            ));
        }
        check_column(&speeds, "v", false)?;
        check_column(&friction, "mu", false)?;
        if let Some(s) = &sigma {
            check_column(s, "sigma", false)?;
        }
        if let Some(t) = &temperature {
            check_column(t, "T", true)?;
        }
        let distinct = distinct_count(&speeds, temperature.as_deref());
        if distinct < MIN_DISTINCT_SPEEDS {
            return Err(FitError::InsufficientData(format!(
                "the data hold {distinct} distinct speed(s) (per temperature) in {n} row(s); a \
                 fit needs at least {MIN_DISTINCT_SPEEDS} distinct speeds: with the smoothness penalty a power-law \
                 spectrum (level and slope of ln H) and, without an anchor, the modulus scale \
                 are free, and one more speed is needed to tell misfit from noise"
            )));
        }
        Ok(Measurements {
            speeds,
            friction,
            sigma,
            temperature,
        })
    }

    /// Number of measurements.
    pub fn len(&self) -> usize {
        self.speeds.len()
    }

    /// Always false: a validated set holds at least one point.
    pub fn is_empty(&self) -> bool {
        self.speeds.is_empty()
    }

    /// Rolling speeds v_i, m/s.
    pub fn speeds(&self) -> &[f64] {
        &self.speeds
    }

    /// Measured friction coefficients μ_i.
    pub fn friction(&self) -> &[f64] {
        &self.friction
    }

    /// Standard deviations σ_i of μ_i, when measured.
    pub fn sigma(&self) -> Option<&[f64]> {
        self.sigma.as_deref()
    }

    /// Temperatures T_i, °C, when given.
    pub fn temperature(&self) -> Option<&[f64]> {
        self.temperature.as_deref()
    }

    /// The scale s_i of each residual (μ_th − μ_i)/s_i of Eq. (B3): σ_i when
    /// measured, else μ_i (relative weights g_i = 1/μ_i², the sensible
    /// default for data spanning decades).
    pub fn residual_scales(&self) -> Vec<f64> {
        match &self.sigma {
            Some(s) => s.clone(),
            None => self.friction.clone(),
        }
    }

    /// Number of distinct speeds (distinct (speed, temperature) pairs for a
    /// temperature set).
    pub fn distinct_speeds(&self) -> usize {
        distinct_count(&self.speeds, self.temperature.as_deref())
    }

    /// Smallest and largest speed, m/s.
    pub fn speed_range(&self) -> (f64, f64) {
        self.speeds
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            })
    }
}
