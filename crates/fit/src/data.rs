//! Measured rolling friction: speeds, friction coefficients, optional
//! standard deviations and temperatures, validated once.
//!
//! Repeated speeds and unsorted rows are normal in real data and accepted as
//! they are; every value must be finite and positive (μ > 0 because the
//! default weights are relative, 1/μ²) and inside the bounds below, which
//! no rolling measurement reaches and which keep every weighted residual,
//! its square and its sum finite.

use crate::error::FitError;

/// A validated set of μ(v) measurements.
#[derive(Debug, Clone, PartialEq)]
pub struct Measurements {
    speeds: Vec<f64>,
    friction: Vec<f64>,
    sigma: Option<Vec<f64>>,
    temperature: Option<Vec<f64>>,
}

/// Accepted speeds, m/s: from 1e-15 m/s (a nanometre in twelve days) to
/// 1000 m/s (the speed of sound in rubber is 50–1500 m/s; a rolling
/// measurement is far slower). Outside, the reduced frequencies overflow the
/// contact map or the modulus.
pub const SPEED_RANGE: (f64, f64) = (1e-15, 1e3);

/// Accepted friction coefficients: from 1e-12 (below any measurement; the
/// relative residual (μ_th − μ)/μ would overflow at μ ~ 1e-300) to 10 (the
/// pressure centroid x̄ = μR lies inside the contact, so μ < r/R < 1; a
/// value of 10 or more is a force, a torque or a percentage, not μ).
pub const FRICTION_RANGE: (f64, f64) = (1e-12, 10.0);

/// The smallest accepted relative standard deviation σ/μ: below it the
/// point's weight exceeds what any measurement can claim and its squared
/// residual overflows.
pub const MIN_RELATIVE_SIGMA: f64 = 1e-9;

/// Accepted temperatures, °C: above absolute zero and below 1000 °C (no
/// rubber survives it; WLF and Arrhenius shifts are meaningless there).
pub const TEMPERATURE_RANGE: (f64, f64) = (-273.15, 1000.0);

/// The requirement a value of `column` (`v`, `mu`, `T`) breaks, if any: a
/// finite number inside the column's range (exclusive of absolute zero).
pub fn column_requirement(column: &str, value: f64) -> Option<&'static str> {
    if !value.is_finite() {
        return Some("must be a finite number");
    }
    match column {
        "v" if value <= 0.0 => Some("must be greater than zero"),
        "v" if value < SPEED_RANGE.0 => Some("must be at least 1e-15 m/s (is the speed in m/s?)"),
        "v" if value > SPEED_RANGE.1 => Some(
            "must be at most 1000 m/s, far above any rolling measurement (is the speed in m/s?)",
        ),
        "mu" if value <= 0.0 => Some("must be greater than zero"),
        "mu" if value < FRICTION_RANGE.0 => {
            Some("must be at least 1e-12, below any measurable friction coefficient")
        }
        "mu" if value >= FRICTION_RANGE.1 => Some(
            "must be below 10: μR is the pressure centroid's offset, which lies inside the \
             contact, so rolling μ is below 1; is the column a force, a torque or a percentage?",
        ),
        "sigma" if value <= 0.0 => Some("must be greater than zero"),
        "T" if value <= TEMPERATURE_RANGE.0 => Some("must be above absolute zero (−273.15 °C)"),
        "T" if value > TEMPERATURE_RANGE.1 => {
            Some("must be at most 1000 °C (is the temperature in °C or K?)")
        }
        _ => None,
    }
}

/// σ must be at least [`MIN_RELATIVE_SIGMA`] of its μ.
pub const SIGMA_REQUIREMENT: &str = "must be at least 1e-9 of the row's mu: a smaller standard deviation gives the point a \
     weight beyond any measurement, and its squared residual overflows";

fn check_column(values: &[f64], column: &'static str) -> Result<(), FitError> {
    for (i, &value) in values.iter().enumerate() {
        if let Some(requirement) = column_requirement(column, value) {
            return Err(FitError::InvalidData {
                row: i + 1,
                column,
                value,
                requirement,
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
            return Err(FitError::ColumnLengths);
        }
        check_column(&speeds, "v")?;
        check_column(&friction, "mu")?;
        if let Some(s) = &sigma {
            check_column(s, "sigma")?;
            if let Some(i) = (0..n).find(|&i| s[i] < MIN_RELATIVE_SIGMA * friction[i]) {
                return Err(FitError::InvalidData {
                    row: i + 1,
                    column: "sigma",
                    value: s[i],
                    requirement: SIGMA_REQUIREMENT,
                });
            }
        }
        if let Some(t) = &temperature {
            check_column(t, "T")?;
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

#[cfg(test)]
mod tests {
    use super::*;

    fn speeds() -> Vec<f64> {
        vec![1e-6, 1e-5, 1e-4, 1e-3, 1e-2]
    }

    fn refused(friction: Vec<f64>, sigma: Option<Vec<f64>>) -> (usize, &'static str) {
        match Measurements::new(speeds(), friction, sigma, None) {
            Err(FitError::InvalidData { row, column, .. }) => (row, column),
            other => panic!("expected a refusal, got {other:?}"),
        }
    }

    /// Values that overflow the weighted residuals are refused
    /// by the library itself, naming the row, not only by the CLI's reader.
    #[test]
    fn values_outside_a_rolling_measurement_are_refused() {
        let mu = vec![0.01, 0.02, 0.03, 0.02, 0.01];
        assert!(Measurements::new(speeds(), mu.clone(), None, None).is_ok());
        let mut big = mu.clone();
        big[2] = 1e300;
        assert_eq!(refused(big, None), (3, "mu"));
        let mut tiny = mu.clone();
        tiny[4] = 1e-300;
        assert_eq!(refused(tiny, None), (5, "mu"));
        let mut sigma: Vec<f64> = mu.iter().map(|m| 0.01 * m).collect();
        sigma[1] = 1e-300;
        assert_eq!(refused(mu.clone(), Some(sigma)), (2, "sigma"));
        let mut fast = speeds();
        fast[4] = 1e300;
        assert!(matches!(
            Measurements::new(fast, mu.clone(), None, None),
            Err(FitError::InvalidData {
                row: 5,
                column: "v",
                ..
            })
        ));
        let cold = vec![-300.0; 5];
        assert!(matches!(
            Measurements::new(speeds(), mu, None, Some(cold)),
            Err(FitError::InvalidData {
                row: 1,
                column: "T",
                ..
            })
        ));
    }

    #[test]
    fn the_bounds_are_inclusive_where_they_say_so() {
        assert_eq!(column_requirement("v", SPEED_RANGE.1), None);
        assert!(column_requirement("v", SPEED_RANGE.1 * 1.0001).is_some());
        assert_eq!(column_requirement("mu", 9.99), None);
        assert!(column_requirement("mu", 10.0).is_some());
        assert_eq!(column_requirement("T", -273.0), None);
        assert!(column_requirement("T", -273.15).is_some());
        assert!(column_requirement("sigma", f64::NAN).is_some());
    }
}
