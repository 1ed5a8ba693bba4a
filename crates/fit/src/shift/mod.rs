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
//! - Arrhenius: log10 a_T = E_a/(R ln 10) (1/T − 1/T_ref), T in K
//!   (°C + 273.15), with θ = ln E_a so that E_a > 0:
//!   ∂log10 a_T/∂θ = log10 a_T (the law is linear in E_a).
//! - Free: θ_j = log10 a_{T_j} for every temperature but T_ref (fixed at 0).
//!
//! The 1σ of each log10 a_T is √(g C gᵀ), g = ∂log10 a_T/∂θ_s and C the
//! covariance block of θ_s ([`crate::analysis`]: s² H⁺, with the noise
//! scaling of the fit's other σ), widened like the bands of the master
//! curve by the smoothing bias, the change of log10 a_T when the fit is
//! made again at λ/10, added in quadrature ([`ShiftRecord::add_bias`]). A shift parameter the data do not move
//! (its column of the data Jacobian vanishes: a temperature whose μ(v) is
//! flat in ln v) has no finite σ; the pseudo-inverse would report 0 for it,
//! so its variance is set to ∞ and its σ is written as null.
//!
//! # References
//! - M.L. Williams, R.F. Landel, J.D. Ferry, "The temperature dependence of
//!   relaxation mechanisms in amorphous polymers and other glass-forming
//!   liquids", J. Am. Chem. Soc. 77 (1955) 3701–3707.
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 11 (WLF, and the Arrhenius law below T_g).

mod beyond;
pub(crate) mod overlap;
mod record;
mod temperatures;

use std::f64::consts::LN_10;

use rollfit_model::modulus::{GAS_CONSTANT, ZERO_CELSIUS};

use crate::data::Measurements;
use crate::error::FitError;
use crate::params::{ShiftKind, ShiftSettings};
pub use record::{LogShift, ShiftRecord};
pub(crate) use temperatures::{distinct_temperatures, index_of};

#[derive(Debug, Clone)]
enum Kind {
    Wlf { c2_floor: f64 },
    Arrhenius,
    Free,
}

/// Smallest activation energy a start takes, J/mol: shifts that do not
/// fall with temperature have no Arrhenius law, and the fit starts from a
/// nearly flat one instead of a negative E_a.
const MIN_START_ENERGY: f64 = 1e3;

/// x(T) = (1/T − 1/T_ref)/(R ln 10), T in K: log10 a_T = E_a x(T).
fn arrhenius_x(t: f64, t_ref: f64) -> f64 {
    (1.0 / (t + ZERO_CELSIUS) - 1.0 / (t_ref + ZERO_CELSIUS)) / (GAS_CONSTANT * LN_10)
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
        ShiftParam::over(data, distinct_temperatures(data), settings)
    }

    /// The shift of `data`'s rows over the temperatures `temps` (ascending
    /// and distinct, every row's among them, at least one): a joint fit's
    /// DMA isotherms add temperatures the rolling rows lack.
    pub(crate) fn over(
        data: &Measurements,
        temps: Vec<f64>,
        settings: &ShiftSettings,
    ) -> Result<Self, FitError> {
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
            ShiftKind::Arrhenius => Kind::Arrhenius,
            ShiftKind::Auto => {
                return Err(FitError::Internal(
                    "the shift law \"auto\" reached the shift's parametrisation unresolved",
                ));
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
            Kind::Arrhenius => 1,
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
            Kind::Arrhenius => {
                let log_shift: Vec<f64> = self
                    .temps
                    .iter()
                    .map(|&t| -c1 * (t - self.t_ref) / (c2 + t - self.t_ref))
                    .collect();
                self.theta_of_log_shifts(&log_shift)
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
            Kind::Arrhenius => {
                // Least squares through T_ref: the shifts are relative, so
                // each is taken about the one nearest T_ref.
                let r = nearest(&self.temps, self.t_ref);
                let x0 = arrhenius_x(self.temps[r], self.t_ref);
                let (sxy, sxx) =
                    self.temps
                        .iter()
                        .zip(log_shift)
                        .fold((0.0, 0.0), |(sxy, sxx), (&t, &y)| {
                            let x = arrhenius_x(t, self.t_ref) - x0;
                            (sxy + x * (y - log_shift[r]), sxx + x * x)
                        });
                let energy = if sxx > 0.0 { sxy / sxx } else { 0.0 };
                vec![energy.max(MIN_START_ENERGY).ln()]
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
            Kind::Arrhenius => {
                let energy = theta[0].exp();
                self.temps
                    .iter()
                    .map(|&t| {
                        let value = energy * arrhenius_x(t, self.t_ref);
                        (value, vec![value])
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

    /// The report's record at θ_s with covariance `cov` of θ_s (an
    /// infinite diagonal entry: a parameter the data do not determine).
    pub(crate) fn record(&self, theta: &[f64], cov: &nalgebra::DMatrix<f64>) -> ShiftRecord {
        let (values, grads) = self.log_shifts(theta);
        let sd = |g: &[f64]| standard_deviation(g, cov);
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
                    c1_sigma: c1 * standard_deviation(&[1.0, 0.0], cov),
                    c2_sigma: excess * standard_deviation(&[0.0, 1.0], cov),
                    log_shift,
                }
            }
            Kind::Arrhenius => {
                let energy = theta[0].exp();
                ShiftRecord::Arrhenius {
                    t_ref: self.t_ref,
                    activation_energy: energy,
                    activation_energy_sigma: energy * standard_deviation(&[1.0], cov),
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

/// √(g C gᵀ). Where C holds an infinite variance (an undetermined
/// parameter), summed over the entries g touches only, so that a parameter
/// `g` does not depend on gives no NaN: ∞ where g touches it. NaN stays NaN
/// (f64::max would turn it into 0).
fn standard_deviation(g: &[f64], cov: &nalgebra::DMatrix<f64>) -> f64 {
    let variance = if cov.iter().all(|c| c.is_finite()) {
        let g = nalgebra::DVector::from_column_slice(g);
        (g.transpose() * cov * &g)[(0, 0)]
    } else {
        let touched = || g.iter().enumerate().filter(|(_, x)| **x != 0.0);
        touched()
            .map(|(i, gi)| touched().map(|(j, gj)| gi * cov[(i, j)] * gj).sum::<f64>())
            .sum()
    };
    // A rounding-negative variance of a well-determined parameter is 0.
    if variance < 0.0 { 0.0 } else { variance.sqrt() }
}

/// The index of the temperature nearest `t`.
fn nearest(temps: &[f64], t: f64) -> usize {
    (0..temps.len())
        .min_by(|&a, &b| (temps[a] - t).abs().total_cmp(&(temps[b] - t).abs()))
        .unwrap_or(0)
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
            (ShiftKind::Arrhenius, vec![2e5f64.ln()]),
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
        let settings = ShiftSettings {
            kind: ShiftKind::Wlf,
            ..ShiftSettings::default()
        };
        let shift = ShiftParam::new(&data, &settings).unwrap();
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

    /// Arrhenius: the start from shifts that follow the law (given relative
    /// to another temperature than T_ref) is the law's E_a, the record
    /// holds it, and a parameter the data do not determine gets no finite
    /// σ, written as null.
    #[test]
    fn arrhenius_start_and_record() {
        let settings = ShiftSettings {
            kind: ShiftKind::Arrhenius,
            t_ref: Some(20.0),
            ..ShiftSettings::default()
        };
        let shift = ShiftParam::new(&set(), &settings).unwrap();
        let energy = 1.5e5;
        let log_shift: Vec<f64> = shift
            .temperatures()
            .iter()
            .map(|&t| energy * arrhenius_x(t, 20.0) + 3.0)
            .collect();
        let theta = shift.theta_of_log_shifts(&log_shift);
        assert!((theta[0].exp() / energy - 1.0).abs() < 1e-12, "{theta:?}");
        let cov = nalgebra::DMatrix::from_element(1, 1, f64::INFINITY);
        let record = shift.record(&theta, &cov);
        let ShiftRecord::Arrhenius {
            activation_energy,
            activation_energy_sigma,
            log_shift: rows,
            ..
        } = &record
        else {
            panic!("{record:?}")
        };
        assert!((activation_energy / energy - 1.0).abs() < 1e-12);
        assert!(activation_energy_sigma.is_infinite());
        assert!((rows[0].log_shift - (log_shift[0] - 3.0)).abs() < 1e-12);
        assert_eq!(rows[2].log_shift_sigma, 0.0, "at T_ref");
        assert!(rows[0].log_shift_sigma.is_infinite());
        let json = serde_json::to_value(&record).unwrap();
        assert_eq!(json["model"], "arrhenius");
        assert!(json["E_a_sigma"].is_null() && json["log_aT"][0]["log_aT_sigma"].is_null());
        assert_eq!(json["log_aT"][2]["log_aT_sigma"], 0.0);
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
