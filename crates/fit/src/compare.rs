//! Errors of a fitted master curve against measured values, the numbers
//! of `rollfit compare` (docs/ARCHITECTURE.md, "Contract", compare.json).
//!
//! In the frequency domain, at the N measured points inside the fit's
//! window, with r_i = (x_fit − x_measured)/x_measured:
//!
//! - tan δ = E″/E′ and |E*| = √(E′² + E″²): RMS √(mean r_i²) and the
//!   largest |r_i|;
//! - E′ and E″: the RMS of log10(x_fit/x_measured), in decades.
//!
//! In the time domain (a relaxation modulus E(t) or a creep compliance
//! D(t), the fit's own exact transform against the measured value):
//! r_i = x_fit/x_measured − 1, its RMS and largest |r_i|, and the RMS of
//! log10(x_fit/x_measured). With no point (N = 0) every number is `None`.

use num_complex::Complex64;

use crate::causality::ModulusSample;

/// RMS and largest |·| of a set of errors; `None` for none.
pub fn rms_max(errors: &[f64]) -> (Option<f64>, Option<f64>) {
    if errors.is_empty() {
        return (None, None);
    }
    let rms = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
    let max = errors.iter().map(|e| e.abs()).fold(0.0, f64::max);
    (Some(rms), Some(max))
}

/// The frequency-domain errors of the module doc.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModulusErrors {
    /// RMS relative error of tan δ.
    pub tan_delta_rms_rel: Option<f64>,
    /// Largest |relative error| of tan δ.
    pub tan_delta_max_rel: Option<f64>,
    /// RMS relative error of |E*|.
    pub abs_modulus_rms_rel: Option<f64>,
    /// Largest |relative error| of |E*|.
    pub abs_modulus_max_rel: Option<f64>,
    /// RMS log10 error of E′, decades.
    pub log10_storage_rms: Option<f64>,
    /// RMS log10 error of E″, decades.
    pub log10_loss_rms: Option<f64>,
}

/// The errors of `fitted` (E*(ω), Pa, at the reduced ω in rad/s) at the
/// measured `points` (all of them: the caller keeps those inside the
/// fit's window).
pub fn modulus_errors(
    points: &[ModulusSample],
    fitted: &dyn Fn(f64) -> Complex64,
) -> ModulusErrors {
    let (mut tan_delta, mut abs_modulus, mut storage, mut loss) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for p in points {
        let e = fitted(p.omega);
        let measured_tan_delta = p.loss / p.storage;
        let measured_abs = p.storage.hypot(p.loss);
        tan_delta.push((e.im / e.re - measured_tan_delta) / measured_tan_delta);
        abs_modulus.push((e.norm() - measured_abs) / measured_abs);
        storage.push((e.re / p.storage).log10());
        loss.push((e.im / p.loss).log10());
    }
    let (tan_delta_rms_rel, tan_delta_max_rel) = rms_max(&tan_delta);
    let (abs_modulus_rms_rel, abs_modulus_max_rel) = rms_max(&abs_modulus);
    ModulusErrors {
        tan_delta_rms_rel,
        tan_delta_max_rel,
        abs_modulus_rms_rel,
        abs_modulus_max_rel,
        log10_storage_rms: rms_max(&storage).0,
        log10_loss_rms: rms_max(&loss).0,
    }
}

/// The time-domain errors of the module doc of `fitted` (E(t) or D(t) at
/// the reduced time t, s) at the measured (t, value) `points`: (RMS
/// relative, largest |relative|, RMS log10 in decades).
pub fn time_errors(
    points: &[(f64, f64)],
    fitted: &dyn Fn(f64) -> f64,
) -> (Option<f64>, Option<f64>, Option<f64>) {
    let (mut relative, mut decades) = (Vec::new(), Vec::new());
    for &(t, value) in points {
        let x = fitted(t);
        relative.push(x / value - 1.0);
        decades.push((x / value).log10());
    }
    let (rms_rel, max_rel) = rms_max(&relative);
    (rms_rel, max_rel, rms_max(&decades).0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rms_and_largest_of_known_errors() {
        assert_eq!(rms_max(&[]), (None, None));
        let (rms, max) = rms_max(&[3.0, -4.0]);
        assert!((rms.unwrap() - 12.5f64.sqrt()).abs() < 1e-15);
        assert_eq!(max, Some(4.0));
    }

    /// A fit 10 % high in E′ and E″ alike: tan δ exact, |E*| 10 % high,
    /// both moduli log10(1.1) decades off at every point.
    #[test]
    fn a_uniform_factor_shows_in_modulus_and_not_in_tan_delta() {
        let points: Vec<ModulusSample> = [1.0, 10.0, 100.0]
            .iter()
            .map(|&omega| ModulusSample {
                omega,
                storage: 1e6 * omega,
                loss: 2e5 * omega,
                temperature: None,
            })
            .collect();
        let fitted = |omega: f64| Complex64::new(1.1e6 * omega, 2.2e5 * omega);
        let e = modulus_errors(&points, &fitted);
        assert!(e.tan_delta_max_rel.unwrap() < 1e-14);
        assert!((e.abs_modulus_rms_rel.unwrap() - 0.1).abs() < 1e-12);
        assert!((e.log10_storage_rms.unwrap() - 1.1f64.log10()).abs() < 1e-12);
        assert!((e.log10_loss_rms.unwrap() - 1.1f64.log10()).abs() < 1e-12);
        let (rms, max, decades) = time_errors(&[(1.0, 2.0), (2.0, 4.0)], &|t| 2.2 * t);
        assert!((rms.unwrap() - 0.1).abs() < 1e-12 && (max.unwrap() - 0.1).abs() < 1e-12);
        assert!((decades.unwrap() - 1.1f64.log10()).abs() < 1e-12);
        assert_eq!(time_errors(&[], &|t| t), (None, None, None));
    }
}
