//! The time–temperature shift of a temperature set as free parameters.
//!
//! Time–temperature superposition: E*(ω, T) = E*(ω a_T, T_ref), hence
//! μ(v, T) = μ_ref(v a_T): a measurement at T is a measurement of the master
//! curve at the reduced speed v a_T. The fit evaluates the master curve at
//! the reduced speeds of all temperatures in one sweep and differentiates
//! through ∂μ/∂ln a_T = ∂μ_ref/∂ln v (the forward model's time-scale column).
//!
//! - WLF: log10 a_T = −C1 ΔT/(C2 + ΔT), ΔT = T − T_ref, with
//!   θ = (ln C1, ln(C2 − C2_floor)), C2_floor = max(0, −min ΔT), so that
//!   C1 > 0 and C2 + ΔT > 0 at every measured temperature:
//!   ∂ln a/∂C1 = −ln10 ΔT/(C2 + ΔT), ∂ln a/∂C2 = ln10 C1 ΔT/(C2 + ΔT)².
//! - Free: θ_j = log10 a_{T_j} for every temperature but T_ref (fixed at 0).
//!
//! # References
//! - M.L. Williams, R.F. Landel, J.D. Ferry, "The temperature dependence of
//!   relaxation mechanisms in amorphous polymers and other glass-forming
//!   liquids", J. Am. Chem. Soc. 77 (1955) 3701–3707.
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 11.

pub(crate) mod overlap;
mod record;
mod temperatures;

use std::f64::consts::LN_10;

use crate::data::Measurements;
use crate::error::FitError;
use crate::params::{ShiftKind, ShiftSettings};
pub use record::{LogShift, ShiftRecord};
pub(crate) use temperatures::{distinct_temperatures, index_of};

#[derive(Debug, Clone)]
enum Kind {
    Wlf { c2_floor: f64 },
    Free,
}

/// θ_s ↦ ln a_T of every data point.
#[derive(Debug, Clone)]
pub(crate) struct ShiftParam {
    kind: Kind,
    t_ref: f64,
    /// The distinct temperatures, ascending.
    temps: Vec<f64>,
    /// Index into `temps` of each data point.
    point_temp: Vec<usize>,
    /// Index of T_ref in `temps` (free shift).
    ref_index: Option<usize>,
}

impl ShiftParam {
    /// The shift for `data` (≥ 2 temperatures) under `settings`.
    pub(crate) fn new(data: &Measurements, settings: &ShiftSettings) -> Result<Self, FitError> {
        let temps = distinct_temperatures(data);
        let column = data.temperature().unwrap_or_default();
        let point_temp = column
            .iter()
            .map(|&t| index_of(&temps, t).unwrap_or(0))
            .collect();
        let t_ref = settings.t_ref.unwrap_or(temps[(temps.len() - 1) / 2]);
        let ref_index = index_of(&temps, t_ref);
        let kind = match settings.kind {
            ShiftKind::Wlf => Kind::Wlf {
                c2_floor: (t_ref - temps[0]).max(0.0),
            },
            ShiftKind::Free => {
                if ref_index.is_none() {
                    return Err(FitError::setting(
                        "T_ref",
                        format!(
                            "{t_ref} °C is not one of the measured temperatures {temps:?}: a free \
                             shift is fixed at a measured temperature (or use the WLF shift)"
                        ),
                    ));
                }
                Kind::Free
            }
        };
        Ok(ShiftParam {
            kind,
            t_ref,
            temps,
            point_temp,
            ref_index,
        })
    }

    /// Reference temperature, °C.
    pub(crate) fn t_ref(&self) -> f64 {
        self.t_ref
    }

    /// The distinct temperatures, ascending, °C.
    pub(crate) fn temperatures(&self) -> &[f64] {
        &self.temps
    }

    /// Number of shift parameters.
    pub(crate) fn count(&self) -> usize {
        match self.kind {
            Kind::Wlf { .. } => 2,
            Kind::Free => self.temps.len() - 1,
        }
    }

    /// θ_s for WLF constants (C1, C2), clamping C2 above its floor.
    pub(crate) fn theta_of_wlf(&self, c1: f64, c2: f64) -> Vec<f64> {
        match self.kind {
            Kind::Wlf { c2_floor } => {
                let excess = (c2 - c2_floor).max(0.05 * c2.max(1.0));
                vec![c1.max(1e-3).ln(), excess.ln()]
            }
            Kind::Free => self
                .temps
                .iter()
                .enumerate()
                .filter(|(j, _)| Some(*j) != self.ref_index)
                .map(|(_, &t)| -c1 * (t - self.t_ref) / (c2 + t - self.t_ref))
                .collect(),
        }
    }

    /// θ_s for log10 a_T per distinct temperature (`log_shift[j]` at
    /// `temperatures()[j]`, relative to any reference): for WLF the best
    /// (C1, C2) of [`overlap::fit_wlf`], else the values relative to T_ref.
    pub(crate) fn theta_of_log_shifts(&self, log_shift: &[f64]) -> Vec<f64> {
        match self.kind {
            Kind::Wlf { c2_floor } => {
                let (c1, c2) = overlap::fit_wlf(&self.temps, log_shift, self.t_ref, c2_floor);
                self.theta_of_wlf(c1, c2)
            }
            Kind::Free => {
                let r = self.ref_index.unwrap_or(0);
                (0..self.temps.len())
                    .filter(|&j| j != r)
                    .map(|j| log_shift[j] - log_shift[r])
                    .collect()
            }
        }
    }

    /// log10 a_T at each distinct temperature, and ∂log10 a_T/∂θ_s (row per
    /// temperature, `count()` columns).
    pub(crate) fn log_shifts(&self, theta: &[f64]) -> (Vec<f64>, Vec<Vec<f64>>) {
        let n = self.count();
        match self.kind {
            Kind::Wlf { c2_floor } => {
                let c1 = theta[0].exp();
                let excess = theta[1].exp();
                let c2 = c2_floor + excess;
                self.temps
                    .iter()
                    .map(|&t| {
                        let dt = t - self.t_ref;
                        let den = c2 + dt;
                        let value = -c1 * dt / den;
                        // ∂/∂ln C1 = value; ∂/∂θ2 = excess · C1 ΔT/den², as
                        // (C1/den)(excess/den) ΔT: C1 and C2 can both grow
                        // without bound at a fixed ratio (WLF's linear
                        // limit), where the product form overflows to NaN.
                        (value, vec![value, (c1 / den) * (excess / den) * dt])
                    })
                    .unzip()
            }
            Kind::Free => {
                let r = self.ref_index.unwrap_or(0);
                self.temps
                    .iter()
                    .enumerate()
                    .map(|(j, _)| {
                        let mut d = vec![0.0; n];
                        if j == r {
                            (0.0, d)
                        } else {
                            let k = if j < r { j } else { j - 1 };
                            d[k] = 1.0;
                            (theta[k], d)
                        }
                    })
                    .unzip()
            }
        }
    }

    /// ln a_T of every data point and ∂ln a_T/∂θ_s (row per point). Fails
    /// where a WLF denominator is not positive.
    pub(crate) fn point_shifts(&self, theta: &[f64]) -> (Vec<f64>, Vec<Vec<f64>>) {
        let (values, grads) = self.log_shifts(theta);
        self.point_temp
            .iter()
            .map(|&j| {
                (
                    LN_10 * values[j],
                    grads[j].iter().map(|g| LN_10 * g).collect(),
                )
            })
            .unzip()
    }

    /// The report's record at θ_s with covariance `cov` of θ_s.
    pub(crate) fn record(&self, theta: &[f64], cov: &nalgebra::DMatrix<f64>) -> ShiftRecord {
        let (values, grads) = self.log_shifts(theta);
        let sd = |g: &[f64]| {
            let g = nalgebra::DVector::from_column_slice(g);
            (g.transpose() * cov * &g)[(0, 0)].max(0.0).sqrt()
        };
        let log_shift = self
            .temps
            .iter()
            .zip(values.iter().zip(&grads))
            .map(|(&t, (&v, g))| LogShift {
                temperature: t,
                log_shift: v,
                log_shift_sigma: sd(g),
            })
            .collect();
        match self.kind {
            Kind::Wlf { c2_floor } => {
                let c1 = theta[0].exp();
                let excess = theta[1].exp();
                ShiftRecord::Wlf {
                    t_ref: self.t_ref,
                    c1,
                    c2: c2_floor + excess,
                    c1_sigma: c1 * cov[(0, 0)].max(0.0).sqrt(),
                    c2_sigma: excess * cov[(1, 1)].max(0.0).sqrt(),
                    log_shift,
                }
            }
            Kind::Free => ShiftRecord::Free {
                t_ref: self.t_ref,
                log_shift,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn set() -> Measurements {
        let t = [-20.0, 0.0, 20.0, 40.0, 60.0];
        let mut v = Vec::new();
        let mut mu = Vec::new();
        let mut temps = Vec::new();
        for &ti in &t {
            for k in 0..3 {
                v.push(10f64.powi(k));
                mu.push(0.1);
                temps.push(ti);
            }
        }
        Measurements::new(v, mu, None, Some(temps)).unwrap()
    }

    /// The shift derivatives against central differences, both models.
    #[test]
    fn derivatives_match_differences() {
        let data = set();
        for (kind, theta) in [
            (ShiftKind::Wlf, vec![8.86f64.ln(), (101.6f64 - 40.0).ln()]),
            (ShiftKind::Free, vec![3.1, 1.2, -1.4, -2.2]),
        ] {
            let settings = ShiftSettings {
                kind,
                t_ref: Some(20.0),
                ..ShiftSettings::default()
            };
            let shift = ShiftParam::new(&data, &settings).unwrap();
            let (_, grads) = shift.point_shifts(&theta);
            for k in 0..theta.len() {
                let h = 1e-6;
                let mut up = theta.clone();
                let mut down = theta.clone();
                up[k] += h;
                down[k] -= h;
                let (a, _) = shift.point_shifts(&up);
                let (b, _) = shift.point_shifts(&down);
                for i in 0..a.len() {
                    let fd = (a[i] - b[i]) / (2.0 * h);
                    assert!((grads[i][k] - fd).abs() < 1e-7 * (1.0 + fd.abs()));
                }
            }
        }
    }

    /// WLF with the textbook constants: the shift at T_ref is 0 and at
    /// T_ref − 10 K about one decade towards higher a_T.
    #[test]
    fn wlf_record_reproduces_its_constants() {
        let data = set();
        let shift = ShiftParam::new(&data, &ShiftSettings::default()).unwrap();
        assert_eq!(shift.t_ref(), 20.0);
        let theta = shift.theta_of_wlf(8.86, 101.6);
        let cov = nalgebra::DMatrix::zeros(2, 2);
        match shift.record(&theta, &cov) {
            ShiftRecord::Wlf {
                c1, c2, log_shift, ..
            } => {
                assert!((c1 - 8.86).abs() < 1e-12 && (c2 - 101.6).abs() < 1e-12);
                let at = |t: f64| log_shift.iter().find(|s| s.temperature == t).unwrap();
                assert_eq!(at(20.0).log_shift, 0.0);
                let expected = 8.86 * 20.0 / (101.6 - 20.0);
                assert!((at(0.0).log_shift - expected).abs() < 1e-12);
            }
            other => panic!("{other:?}"),
        }
    }

    /// A free shift needs T_ref among the measured temperatures.
    #[test]
    fn free_shift_refuses_an_unmeasured_reference() {
        let settings = ShiftSettings {
            kind: ShiftKind::Free,
            t_ref: Some(25.0),
            ..ShiftSettings::default()
        };
        let e = ShiftParam::new(&set(), &settings).unwrap_err();
        assert!(e.to_string().contains("25 °C"), "{e}");
    }
}
