//! Time–temperature superposition of DMA isotherms (issue 15, first step):
//! the horizontal shift factors a_T found from the data alone, and WLF
//! constants fitted to them with standard errors.
//!
//! Each isotherm j holds E*(ω) at one temperature T_j. Superposition says
//! E*(ω, T) = E*(ω a_T, T_ref): two neighbouring isotherms are the same
//! curves of x = log10 ω up to the shift s = log10 a_{T_{j+1}} − log10 a_{T_j},
//!
//!   log E′_{j+1}(x) = log E′_j(x + s),   log tan δ_{j+1}(x) = log tan δ_j(x + s).
//!
//! s minimises the sum of the two mean squared differences over the
//! overlap (the area between the curves, as the usual TTS tools do): log E′
//! rises monotonically through the transition and fixes s where tan δ is
//! flat, tan δ carries the shape where E′ is on a plateau. The search
//! scans ±15 decades before refining (see `shift::overlap`), so it cannot
//! lock onto the wrong flank of the tan δ peak. Chaining neighbours gives
//! log a_T up to a constant, which makes log a_{T_ref} = 0: at T_ref itself
//! when it was measured, else through the WLF fit.
//!
//! The WLF fit, log a_T = b − C1 (T − T_ref)/(C2 + T − T_ref) with the
//! offset b free (the chain's constant), starts from a scan over C2 with
//! (b, C1) linear, and its standard errors come from the Gauss–Newton
//! curvature, σ² (JᵀJ)⁻¹ with σ² = RSS/(n − 3), at the optimum.
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 11 (reduced variables, WLF equation).
//! - M.L. Williams, R.F. Landel, J.D. Ferry, J. Am. Chem. Soc. 77, 3701
//!   (1955).

use nalgebra::{Matrix3, Vector3};

use crate::error::FitError;
use crate::shift::overlap::{Curve, fit_wlf, joint_relative_shift};

/// One DMA isotherm: E*(ω) at one temperature.
#[derive(Debug, Clone, PartialEq)]
pub struct Isotherm {
    /// Temperature, °C.
    pub temperature: f64,
    /// Angular frequencies, rad/s.
    pub omega: Vec<f64>,
    /// E′ at each frequency, Pa.
    pub storage: Vec<f64>,
    /// E″ at each frequency, Pa.
    pub loss: Vec<f64>,
}

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

/// Shift factors of a set of isotherms.
#[derive(Debug, Clone, PartialEq)]
pub struct IsothermShifts {
    /// Reference temperature, °C.
    pub t_ref: f64,
    /// (T in °C, log10 a_T) per isotherm, in ascending temperature.
    pub log_shift: Vec<(f64, f64)>,
    /// The WLF fit (None with fewer than three temperatures).
    pub wlf: Option<WlfFit>,
}

/// The curves the shift compares: log10 E′ and log10 tan δ against
/// log10 ω.
fn curves(isotherm: &Isotherm) -> [Curve; 2] {
    let points = |y: &dyn Fn(usize) -> f64| {
        Curve::new(
            (0..isotherm.omega.len())
                .map(|i| (isotherm.omega[i].log10(), y(i)))
                .collect(),
        )
    };
    [
        points(&|i| isotherm.storage[i].log10()),
        points(&|i| (isotherm.loss[i] / isotherm.storage[i]).log10()),
    ]
}

/// Horizontal shift factors of `isotherms` (any order) about `t_ref` (°C),
/// with a WLF fit when there are three temperatures or more. Refuses
/// isotherms that do not overlap, naming the pair, and repeated
/// temperatures.
pub fn shift_isotherms(isotherms: &[Isotherm], t_ref: f64) -> Result<IsothermShifts, FitError> {
    if isotherms.is_empty() {
        return Err(FitError::InsufficientData("no isotherms".into()));
    }
    let mut sorted: Vec<&Isotherm> = isotherms.iter().collect();
    sorted.sort_by(|a, b| a.temperature.total_cmp(&b.temperature));
    for pair in sorted.windows(2) {
        if pair[0].temperature == pair[1].temperature {
            return Err(FitError::InsufficientData(format!(
                "two isotherms at T = {} °C: merge them or give them their own temperatures",
                pair[0].temperature
            )));
        }
    }
    let all: Vec<[Curve; 2]> = sorted.iter().map(|i| curves(i)).collect();
    let mut chain = vec![0.0];
    for (k, pair) in all.windows(2).enumerate() {
        let lower = [&pair[0][0], &pair[0][1]];
        let upper = [&pair[1][0], &pair[1][1]];
        // upper(x) = lower(x + s): the warmer isotherm is the colder one
        // seen at frequencies 10^s times higher.
        let s = joint_relative_shift(&lower, &upper).ok_or_else(|| {
            FitError::InsufficientData(format!(
                "the isotherms at {} °C and {} °C do not overlap in frequency once shifted (at \
                 least a fifth of the warmer one's points, and four, must fall inside the \
                 colder one's range): measure a temperature between them or over more \
                 frequencies",
                sorted[k].temperature,
                sorted[k + 1].temperature
            ))
        })?;
        chain.push(chain[k] + s);
    }
    let temps: Vec<f64> = sorted.iter().map(|i| i.temperature).collect();
    let wlf = (temps.len() >= 3)
        .then(|| wlf_with_errors(&temps, &chain, t_ref))
        .flatten();
    let offset = match temps.iter().position(|&t| t == t_ref) {
        Some(i) => chain[i],
        None => match &wlf {
            Some((_, b)) => *b,
            None => interpolate(&temps, &chain, t_ref),
        },
    };
    Ok(IsothermShifts {
        t_ref,
        log_shift: temps
            .iter()
            .zip(&chain)
            .map(|(&t, &c)| (t, c - offset))
            .collect(),
        wlf: wlf.map(|(fit, _)| fit),
    })
}

/// Linear interpolation (or extrapolation from the nearest pair) of
/// (x, y) at `at`.
fn interpolate(x: &[f64], y: &[f64], at: f64) -> f64 {
    if x.len() == 1 {
        return y[0];
    }
    let k = x.partition_point(|&xi| xi <= at).clamp(1, x.len() - 1);
    let w = (at - x[k - 1]) / (x[k] - x[k - 1]);
    y[k - 1] * (1.0 - w) + y[k] * w
}

/// WLF (C1, C2) with standard errors fitted to `log_shift` at `temps` up to
/// the offset b, which is returned too.
fn wlf_with_errors(temps: &[f64], log_shift: &[f64], t_ref: f64) -> Option<(WlfFit, f64)> {
    // C2 + T − T_ref must stay positive at every measured temperature.
    let floor = temps.iter().map(|t| t_ref - t).fold(0.0, f64::max);
    let (mut c1, mut c2) = fit_wlf(temps, log_shift, t_ref, floor);
    let n = temps.len();
    let model = |c1: f64, c2: f64| -> (f64, Vec<f64>) {
        let z: Vec<f64> = temps
            .iter()
            .map(|t| (t - t_ref) / (c2 + t - t_ref))
            .collect();
        let b = log_shift
            .iter()
            .zip(&z)
            .map(|(y, z)| y + c1 * z)
            .sum::<f64>()
            / n as f64;
        (b, z)
    };
    // Gauss–Newton polish of (b, C1, C2) from the scan's optimum.
    let mut b = model(c1, c2).0;
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
    for _ in 0..20 {
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
        let rss = |r: Vec<f64>| r.iter().map(|x| x * x).sum::<f64>();
        if nc2 <= floor || rss(residuals(nb, nc1, nc2)) > rss(residuals(b, c1, c2)) {
            break;
        }
        (b, c1, c2) = (nb, nc1, nc2);
        if step.norm() < 1e-12 * (1.0 + c2.abs()) {
            break;
        }
    }
    let r = residuals(b, c1, c2);
    let rss: f64 = r.iter().map(|x| x * x).sum();
    let (mut c1_sigma, mut c2_sigma) = (f64::NAN, f64::NAN);
    if n > 3 {
        let mut jtj = Matrix3::zeros();
        for row in jacobian(c1, c2) {
            let v = Vector3::from(row);
            jtj += v * v.transpose();
        }
        if let Some(inv) = jtj.try_inverse() {
            let s2 = rss / (n - 3) as f64;
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
            rms: (rss / n as f64).sqrt(),
        },
        b,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;
    use rand_distr::{Distribution, Normal};
    use rollfit_model::{HavriliakNegami, ViscoelasticModulus};

    /// Isotherms of a known master curve under known WLF constants, 15
    /// frequencies over 0.1…100 rad/s each (a DMA sweep), relative noise
    /// `noise` on E′ and E″.
    fn synthetic(temps: &[f64], c1: f64, c2: f64, noise: f64, seed: u64) -> Vec<Isotherm> {
        let master = HavriliakNegami::new(2e6, 2e9, 1e-3, 0.55, 0.4).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let normal = Normal::new(0.0, 1.0).unwrap();
        temps
            .iter()
            .map(|&t| {
                let a = 10f64.powf(-c1 * (t - 20.0) / (c2 + t - 20.0));
                let omega: Vec<f64> = (0..15)
                    .map(|i| 0.1 * 10f64.powf(i as f64 / 14.0 * 3.0))
                    .collect();
                let e: Vec<_> = omega.iter().map(|w| master.modulus(w * a)).collect();
                Isotherm {
                    temperature: t,
                    storage: e
                        .iter()
                        .map(|e| e.re * (1.0 + noise * normal.sample(&mut rng)))
                        .collect(),
                    loss: e
                        .iter()
                        .map(|e| e.im * (1.0 + noise * normal.sample(&mut rng)))
                        .collect(),
                    omega,
                }
            })
            .collect()
    }

    /// Issue 15's target: on synthetic isotherms with 1 % noise, log a_T
    /// within 0.05 decade, and the WLF constants within 3σ of the truth.
    #[test]
    fn shifts_of_noisy_isotherms_are_recovered() {
        let temps: Vec<f64> = (0..9).map(|k| -20.0 + 10.0 * k as f64).collect();
        let (c1, c2) = (10.5, 120.0);
        for seed in 0..5 {
            let isotherms = synthetic(&temps, c1, c2, 0.01, seed);
            let shifts = shift_isotherms(&isotherms, 20.0).unwrap();
            let worst = shifts
                .log_shift
                .iter()
                .map(|&(t, l)| (l + c1 * (t - 20.0) / (c2 + t - 20.0)).abs())
                .fold(0.0, f64::max);
            eprintln!(
                "seed {seed}: worst log a_T error {worst:.4}; {:?}",
                shifts.wlf
            );
            for &(t, log_a) in &shifts.log_shift {
                let truth = -c1 * (t - 20.0) / (c2 + t - 20.0);
                assert!(
                    (log_a - truth).abs() <= 0.05,
                    "seed {seed}, T = {t}: log a_T {log_a} vs {truth}"
                );
            }
            let wlf = shifts.wlf.unwrap();
            assert!((wlf.c1 - c1).abs() <= 3.0 * wlf.c1_sigma + 1e-3, "{wlf:?}");
            assert!((wlf.c2 - c2).abs() <= 3.0 * wlf.c2_sigma + 1e-1, "{wlf:?}");
        }
    }

    /// T_ref between the measured temperatures: a_T is 1 there by the WLF
    /// fit, and the shifts still match the truth.
    #[test]
    fn a_reference_between_isotherms_is_placed_by_wlf() {
        let temps: Vec<f64> = (0..6).map(|k| -15.0 + 10.0 * k as f64).collect();
        let isotherms = synthetic(&temps, 8.86, 101.6, 0.0, 0);
        let shifts = shift_isotherms(&isotherms, 20.0).unwrap();
        for &(t, log_a) in &shifts.log_shift {
            let truth = -8.86 * (t - 20.0) / (101.6 + t - 20.0);
            assert!((log_a - truth).abs() <= 0.02, "T = {t}: {log_a} vs {truth}");
        }
    }

    /// Isotherms that cannot overlap are refused naming the pair; one
    /// isotherm is its own master curve.
    #[test]
    fn gaps_are_refused_and_one_isotherm_is_unshifted() {
        let mut isotherms = synthetic(&[0.0, 10.0], 8.86, 101.6, 0.0, 0);
        for w in &mut isotherms[1].omega {
            *w *= 1e20;
        }
        let m = shift_isotherms(&isotherms, 0.0).unwrap_err().to_string();
        assert!(m.contains("0 °C and 10 °C do not overlap"), "{m}");
        let one = synthetic(&[30.0], 8.86, 101.6, 0.0, 0);
        let shifts = shift_isotherms(&one, 30.0).unwrap();
        assert_eq!(shifts.log_shift, vec![(30.0, 0.0)]);
        assert!(shifts.wlf.is_none());
    }
}
