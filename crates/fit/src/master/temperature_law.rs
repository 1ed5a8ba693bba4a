//! Laws of the shift factor fitted to the shifts found from the data, with
//! standard errors: WLF and Arrhenius.
//!
//! The shifts from overlapping isotherms are known up to a constant, so
//! each law carries a free offset b that the fit determines with it:
//!
//! - WLF: log10 a_T = b − C1 (T − T_ref)/(C2 + T − T_ref). For each C2 on a
//!   grid (b, C1) are linear; the best grid point is polished by
//!   Gauss–Newton on (b, C1, C2).
//! - Arrhenius: log10 a_T = b + A (1/T − 1/T_ref), T in K, A = E_a/(R ln 10):
//!   linear least squares in (b, A).
//!
//! Standard errors come from the curvature at the optimum,
//! σ² (JᵀJ)⁻¹ with σ² = RSS/(n − p): the scatter of the shifts about the
//! law is taken as their noise. They are NaN when n ≤ p.
//!
//! # References
//! - M.L. Williams, R.F. Landel, J.D. Ferry, J. Am. Chem. Soc. 77, 3701
//!   (1955).
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 11 (WLF and Arrhenius regimes).
//! - P.R. Bevington, D.K. Robinson, *Data Reduction and Error Analysis for
//!   the Physical Sciences*, 3rd ed., McGraw-Hill 2003, ch. 8 (errors of a
//!   least-squares fit from its curvature).

use nalgebra::{Matrix2, Matrix3, Vector3};
use rollfit_model::modulus::{GAS_CONSTANT, ZERO_CELSIUS};

use crate::shift::overlap::fit_wlf;

/// WLF constants fitted to measured shift factors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WlfFit {
    /// C1 (dimensionless).
    pub c1: f64,
    /// C2, K.
    pub c2: f64,
    /// 1σ of C1 (NaN with fewer than four temperatures).
    pub c1_sigma: f64,
    /// 1σ of C2, K (NaN with fewer than four temperatures).
    pub c2_sigma: f64,
    /// RMS of the shifts about the WLF curve, decades.
    pub rms: f64,
}

impl WlfFit {
    /// log10 a_T at `t` (°C) about `t_ref`, or None at and below the
    /// divergence T = T_ref − C2.
    pub fn log_shift(&self, t_ref: f64, t: f64) -> Option<f64> {
        let dt = t - t_ref;
        (self.c2 + dt > 0.0).then(|| -self.c1 * dt / (self.c2 + dt))
    }
}

/// An Arrhenius law fitted to measured shift factors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArrheniusFit {
    /// Activation energy E_a, J/mol.
    pub activation_energy: f64,
    /// 1σ of E_a, J/mol (NaN with fewer than three temperatures).
    pub activation_energy_sigma: f64,
    /// RMS of the shifts about the law, decades.
    pub rms: f64,
}

impl ArrheniusFit {
    /// log10 a_T at `t` (°C) about `t_ref`.
    pub fn log_shift(&self, t_ref: f64, t: f64) -> f64 {
        let slope = self.activation_energy / (GAS_CONSTANT * std::f64::consts::LN_10);
        slope * (1.0 / (t + ZERO_CELSIUS) - 1.0 / (t_ref + ZERO_CELSIUS))
    }
}

/// WLF (C1, C2) with standard errors fitted to `log_shift` at `temps` up to
/// the offset b, which is returned too. None with fewer than three
/// temperatures.
pub(crate) fn fit_wlf_with_errors(
    temps: &[f64],
    log_shift: &[f64],
    t_ref: f64,
) -> Option<(WlfFit, f64)> {
    let n = temps.len();
    if n < 3 {
        return None;
    }
    // C2 + T − T_ref must stay positive at every measured temperature.
    let floor = temps.iter().map(|t| t_ref - t).fold(0.0, f64::max);
    let (mut c1, mut c2) = fit_wlf(temps, log_shift, t_ref, floor);
    let jacobian = |c1: f64, c2: f64| -> Vec<[f64; 3]> {
        temps
            .iter()
            .map(|t| {
                let d = t - t_ref;
                [1.0, -d / (c2 + d), c1 * d / (c2 + d).powi(2)]
            })
            .collect()
    };
    let residuals = |b: f64, c1: f64, c2: f64| -> Vec<f64> {
        temps
            .iter()
            .zip(log_shift)
            .map(|(t, y)| y - (b - c1 * (t - t_ref) / (c2 + t - t_ref)))
            .collect()
    };
    let rss = |r: Vec<f64>| r.iter().map(|x| x * x).sum::<f64>();
    // The offset that goes with the scan's (C1, C2).
    let mut b = temps
        .iter()
        .zip(log_shift)
        .map(|(t, y)| y + c1 * (t - t_ref) / (c2 + t - t_ref))
        .sum::<f64>()
        / n as f64;
    // Gauss–Newton polish of (b, C1, C2) from the scan's optimum.
    for _ in 0..50 {
        let j = jacobian(c1, c2);
        let r = residuals(b, c1, c2);
        let mut jtj = Matrix3::zeros();
        let mut jtr = Vector3::zeros();
        for (row, ri) in j.iter().zip(&r) {
            let v = Vector3::from(*row);
            jtj += v * v.transpose();
            jtr += v * *ri;
        }
        let Some(step) = jtj.try_inverse().map(|inv| inv * jtr) else {
            break;
        };
        let (nb, nc1, nc2) = (b + step[0], c1 + step[1], c2 + step[2]);
        if nc2 <= floor || rss(residuals(nb, nc1, nc2)) > rss(residuals(b, c1, c2)) {
            break;
        }
        (b, c1, c2) = (nb, nc1, nc2);
        if step.norm() < 1e-12 * (1.0 + c2.abs()) {
            break;
        }
    }
    let total = rss(residuals(b, c1, c2));
    let (mut c1_sigma, mut c2_sigma) = (f64::NAN, f64::NAN);
    if n > 3 {
        let mut jtj = Matrix3::zeros();
        for row in jacobian(c1, c2) {
            let v = Vector3::from(row);
            jtj += v * v.transpose();
        }
        if let Some(inv) = jtj.try_inverse() {
            let s2 = total / (n - 3) as f64;
            c1_sigma = (s2 * inv[(1, 1)]).max(0.0).sqrt();
            c2_sigma = (s2 * inv[(2, 2)]).max(0.0).sqrt();
        }
    }
    Some((
        WlfFit {
            c1,
            c2,
            c1_sigma,
            c2_sigma,
            rms: (total / n as f64).sqrt(),
        },
        b,
    ))
}

/// Arrhenius E_a with its standard error fitted to `log_shift` at `temps`
/// (°C) up to the offset b, which is returned too. None with fewer than
/// two temperatures.
pub(crate) fn fit_arrhenius(
    temps: &[f64],
    log_shift: &[f64],
    t_ref: f64,
) -> Option<(ArrheniusFit, f64)> {
    let n = temps.len();
    if n < 2 {
        return None;
    }
    // log a = b + A z, z = 1/T − 1/T_ref (1/K).
    let z: Vec<f64> = temps
        .iter()
        .map(|t| 1.0 / (t + ZERO_CELSIUS) - 1.0 / (t_ref + ZERO_CELSIUS))
        .collect();
    let mut ata = Matrix2::zeros();
    let (mut aty0, mut aty1) = (0.0, 0.0);
    for (zi, yi) in z.iter().zip(log_shift) {
        ata += Matrix2::new(1.0, *zi, *zi, zi * zi);
        aty0 += yi;
        aty1 += zi * yi;
    }
    let inv = ata.try_inverse()?;
    let b = inv[(0, 0)] * aty0 + inv[(0, 1)] * aty1;
    let slope = inv[(1, 0)] * aty0 + inv[(1, 1)] * aty1;
    let total: f64 = z
        .iter()
        .zip(log_shift)
        .map(|(zi, yi)| (yi - b - slope * zi).powi(2))
        .sum();
    let to_energy = GAS_CONSTANT * std::f64::consts::LN_10;
    let sigma = if n > 2 {
        (total / (n - 2) as f64 * inv[(1, 1)]).max(0.0).sqrt() * to_energy
    } else {
        f64::NAN
    };
    Some((
        ArrheniusFit {
            activation_energy: slope * to_energy,
            activation_energy_sigma: sigma,
            rms: (total / n as f64).sqrt(),
        },
        b,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// WLF constants and an offset are recovered from exact shifts.
    #[test]
    fn wlf_from_exact_shifts() {
        let temps: Vec<f64> = (0..8).map(|k| -30.0 + 15.0 * k as f64).collect();
        let (c1, c2) = (9.5, 130.0);
        let y: Vec<f64> = temps
            .iter()
            .map(|t| 2.5 - c1 * (t - 20.0) / (c2 + t - 20.0))
            .collect();
        let (fit, b) = fit_wlf_with_errors(&temps, &y, 20.0).unwrap();
        assert!(
            (fit.c1 - c1).abs() < 1e-6 && (fit.c2 - c2).abs() < 1e-4,
            "{fit:?}"
        );
        assert!((b - 2.5).abs() < 1e-6);
        assert!(fit.rms < 1e-8);
    }

    /// Arrhenius E_a and offset from exact shifts; with scatter the
    /// standard error matches the spread over many noisy sets (slow
    /// oracle: a Monte Carlo of the same least squares).
    #[test]
    fn arrhenius_from_shifts() {
        let temps = [-20.0, 0.0, 20.0, 40.0, 60.0];
        let law = ArrheniusFit {
            activation_energy: 1.5e5,
            activation_energy_sigma: 0.0,
            rms: 0.0,
        };
        let y: Vec<f64> = temps
            .iter()
            .map(|&t| law.log_shift(20.0, t) - 0.7)
            .collect();
        let (fit, b) = fit_arrhenius(&temps, &y, 20.0).unwrap();
        assert!((fit.activation_energy / 1.5e5 - 1.0).abs() < 1e-10);
        assert!((b + 0.7).abs() < 1e-10);
        // Noise of 0.05 decade: the spread of E_a over 400 sets against
        // the mean reported σ.
        use rand::SeedableRng;
        use rand_distr::{Distribution, Normal};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let normal = Normal::new(0.0, 0.05).unwrap();
        let (mut values, mut sigmas) = (Vec::new(), Vec::new());
        for _ in 0..400 {
            let noisy: Vec<f64> = y.iter().map(|v| v + normal.sample(&mut rng)).collect();
            let (f, _) = fit_arrhenius(&temps, &noisy, 20.0).unwrap();
            values.push(f.activation_energy);
            sigmas.push(f.activation_energy_sigma);
        }
        let mean = values.iter().sum::<f64>() / 400.0;
        let spread = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / 399.0).sqrt();
        let reported = sigmas.iter().sum::<f64>() / 400.0;
        assert!(
            (reported / spread - 1.0).abs() < 0.2,
            "reported σ {reported:.4e} vs spread {spread:.4e}"
        );
    }
}
