//! The DMA isotherms of a joint fit ([`crate::joint`]), validated
//! once, as [`crate::data`] validates the rolling rows.

use crate::data::TEMPERATURE_RANGE;
use crate::error::FitError;
use crate::master::Isotherm;

/// Accepted moduli, Pa: from 1 Pa (a gel) to 1e13 Pa (stiffer than
/// diamond); outside, the numbers are not a rubber's E′ or E″ in Pa.
pub const DMA_MODULUS_RANGE: (f64, f64) = (1.0, 1e13);

/// Accepted angular frequencies, rad/s: a DMA sweep spans 1e-3 … 1e3 Hz;
/// the range leaves room for reduced frequencies without overflowing a_T.
pub const DMA_OMEGA_RANGE: (f64, f64) = (1e-8, 1e8);

/// DMA isotherms in Young's moduli, each point a measurement of the master
/// curve at its reduced frequency ω a_T (`source` names the file in
/// messages and in fit.json).
#[derive(Debug, Clone, PartialEq)]
pub struct DmaRows {
    isotherms: Vec<Isotherm>,
    source: String,
}

impl DmaRows {
    /// Checks the isotherms: at least one; at every point a finite ω, E′,
    /// E″ inside their ranges; equal lengths; at least two points each;
    /// distinct temperatures inside the data's range.
    pub fn new(isotherms: Vec<Isotherm>, source: impl Into<String>) -> Result<DmaRows, FitError> {
        let source = source.into();
        let bad = |problem: String| FitError::setting("dma", format!("{source}: {problem}"));
        if isotherms.is_empty() {
            return Err(bad("no DMA points".into()));
        }
        for iso in &isotherms {
            let t = iso.temperature;
            if !(t > TEMPERATURE_RANGE.0 && t <= TEMPERATURE_RANGE.1) {
                return Err(bad(format!(
                    "isotherm at {t} °C: the temperature must lie above absolute zero and at most \
                     1000 °C"
                )));
            }
            let n = iso.omega.len();
            if iso.storage.len() != n || iso.loss.len() != n {
                return Err(bad(format!(
                    "isotherm at {t} °C: ω, E′ and E″ have different lengths"
                )));
            }
            if n < 2 {
                return Err(bad(format!(
                    "isotherm at {t} °C has {n} point(s): a joint fit needs at least two \
                     frequencies per isotherm"
                )));
            }
            for k in 0..n {
                let inside = |x: f64, (lo, hi): (f64, f64)| x.is_finite() && x >= lo && x <= hi;
                let (w, e1, e2) = (iso.omega[k], iso.storage[k], iso.loss[k]);
                if !inside(w, DMA_OMEGA_RANGE) {
                    return Err(bad(format!(
                        "isotherm at {t} °C, point {}: ω = {w} rad/s must lie in 1e-8 … 1e8 rad/s",
                        k + 1
                    )));
                }
                for (name, e) in [("E′", e1), ("E″", e2)] {
                    if !inside(e, DMA_MODULUS_RANGE) {
                        return Err(bad(format!(
                            "isotherm at {t} °C, point {}: {name} = {e} Pa must lie in 1 … 1e13 \
                             Pa (is the modulus in Pa?)",
                            k + 1
                        )));
                    }
                }
            }
        }
        let mut temps: Vec<f64> = isotherms.iter().map(|i| i.temperature).collect();
        temps.sort_by(f64::total_cmp);
        if let Some(w) = temps.windows(2).find(|w| w[0] == w[1]) {
            return Err(bad(format!("two isotherms at {} °C", w[0])));
        }
        Ok(DmaRows { isotherms, source })
    }

    /// The isotherms as given.
    pub fn isotherms(&self) -> &[Isotherm] {
        &self.isotherms
    }

    /// The file (or other source) the isotherms came from.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// Number of (ω, T) points; each gives two residuals (E′ and E″).
    pub fn len(&self) -> usize {
        self.isotherms.iter().map(|i| i.omega.len()).sum()
    }

    /// Whether there is no point (never, once validated).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The isotherms' temperatures, ascending, °C.
    pub fn temperatures(&self) -> Vec<f64> {
        let mut t: Vec<f64> = self.isotherms.iter().map(|i| i.temperature).collect();
        t.sort_by(f64::total_cmp);
        t
    }

    /// Every point as (temperature °C, ω rad/s, E′ Pa, E″ Pa), isotherm by
    /// isotherm in the given order.
    pub fn points(&self) -> impl Iterator<Item = (f64, f64, f64, f64)> + '_ {
        self.isotherms.iter().flat_map(|iso| {
            (0..iso.omega.len())
                .map(move |k| (iso.temperature, iso.omega[k], iso.storage[k], iso.loss[k]))
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn isotherm(t: f64) -> Isotherm {
        Isotherm {
            temperature: t,
            omega: vec![1.0, 10.0, 100.0],
            storage: vec![1e6, 2e6, 4e6],
            loss: vec![1e5, 3e5, 9e5],
        }
    }

    #[test]
    fn bad_isotherms_are_refused_naming_the_point() {
        assert!(DmaRows::new(vec![isotherm(0.0), isotherm(20.0)], "d.csv").is_ok());
        let mut kpa = isotherm(20.0);
        kpa.storage[1] = 0.5;
        let e = DmaRows::new(vec![kpa], "d.csv").unwrap_err().to_string();
        assert!(
            e.contains("d.csv") && e.contains("point 2") && e.contains("E′"),
            "{e}"
        );
        let e = DmaRows::new(vec![isotherm(5.0), isotherm(5.0)], "d.csv")
            .unwrap_err()
            .to_string();
        assert!(e.contains("two isotherms at 5"), "{e}");
        let mut short = isotherm(5.0);
        short.omega.truncate(1);
        assert!(DmaRows::new(vec![short], "d.csv").is_err());
        assert!(DmaRows::new(Vec::new(), "d.csv").is_err());
    }
}
