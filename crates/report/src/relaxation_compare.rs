//! A fit's master curve against stress-relaxation or creep data
//! (`rollfit compare DIR RELAXATION.csv`, `rollfit compare DIR CREEP.csv`).
//!
//! Which way to convert, and why: the fit's Prony series is converted to
//! the time domain, E_fit(t) = E0 + Σ_k H_k e^(−t/τ_k) (exact for a Prony
//! series, Ferry 1980 ch. 3; Park & Schapery 1999), and compared with the
//! measured E(t) point by point. The other way — fitting a series to the
//! relaxation data and comparing its E′, E″, tan δ with the fit's — passes
//! the data through an inversion of a Laplace transform, which is
//! ill-posed: E″(ω) ≈ −(π/2) dE/d ln t at t = 1/ω (Ferry ch. 4) is a
//! derivative of noisy data, so the comparison would measure the
//! regularisation as much as the fit. The forward map from the spectrum
//! to E(t) is smoothing and well-posed, so the differences are the fit's
//! and the data's alone.
//!
//! The points are moved to the fit's reference state by the rules of
//! [`crate::dma_shift`] (the DMA's own WLF with `--dma-wlf`, else the
//! fit's shift, else one temperature as measured), in time:
//! t_r = t/a_T (the frequency points' ω a_T). They are compared over the
//! times that the fit's window [ω_min, ω_max] determines,
//! t_r ∈ [1/ω_max, 1/ω_min] (E(t) is fixed by the spectrum at τ ≳ t as
//! E′(ω) is at τ ≳ 1/ω). With r_i = E_fit(t_i)/E_i − 1:
//! `E_relax_rms_rel` = √(mean r_i²), `E_relax_max_rel` = max |r_i|,
//! `log10_E_relax_rms` the RMS of log10(E_fit/E) in decades. All moduli
//! are Young's (a G(t) converted with the fit's ν).
//!
//! Creep data are compared the same way, with the series' exact creep
//! compliance D_fit(t) (`rollfit_model::exact::CreepCompliance`, from the
//! zeros of its Laplace transform) in place of E_fit(t): the forward map
//! again, never D ≈ 1/E. The keys are `D_creep_rms_rel`,
//! `D_creep_max_rel`, `log10_D_creep_rms`; compliances are tensile (a J(t)
//! converted with D = J/(2(1+ν)), the fit's ν).
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 3–4.
//! - S.W. Park, R.A. Schapery, Int. J. Solids Struct. 36 (1999)
//!   1653–1675.

use serde::Serialize;

use rollfit_fit::compare::time_errors;
use rollfit_fit::master::grouping::group_temperatures;
use rollfit_fit::master::relaxation::TimeQuantity;
use rollfit_io::FitDir;
use rollfit_io::dma::DmaOptions;
use rollfit_io::dma::relaxation::RelaxationData;

use crate::compare::IsothermShift;
use crate::dma_shift::isotherm_shifts;
use crate::error::ReportError;

/// The comparison; its JSON is compare.json for a relaxation file.
#[derive(Debug, Clone, Serialize)]
pub struct RelaxationComparison {
    /// Points inside the times the fit's window determines.
    pub n_points: usize,
    /// Shortest reduced time among them, s.
    pub t_min: Option<f64>,
    /// Longest reduced time among them, s.
    pub t_max: Option<f64>,
    /// The errors, under the keys of the quantity compared.
    #[serde(flatten)]
    pub metrics: TimeMetrics,
    /// The relaxation or creep file.
    pub dma_file: String,
    /// "csv-relaxation" or "csv-creep".
    pub dma_format: &'static str,
    /// "young" or "shear".
    pub modulus_kind: &'static str,
    /// ν used for shear → Young's (the fit's).
    pub poisson: f64,
    /// The fit's window as times, [1/ω_max, 1/ω_min], s.
    pub fit_window_time: [f64; 2],
    /// The data's reduced times, s.
    pub dma_time_range: [f64; 2],
    /// All points.
    pub dma_points: usize,
    /// The isotherms and their shifts (empty without temperatures).
    pub dma_shift: Vec<IsothermShift>,
    /// Whether the window and the data miss each other.
    pub overlap_empty: bool,
    /// How the points were shifted.
    pub notes: Vec<String>,
    /// Overlap warnings.
    pub warnings: Vec<String>,
}

/// The errors of E(t) or D(t), each under its compare.json key.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum TimeMetrics {
    /// Relaxation modulus E(t).
    Relaxation {
        /// RMS relative error of E(t).
        #[serde(rename = "E_relax_rms_rel")]
        rms_rel: Option<f64>,
        /// Largest |relative error| of E(t).
        #[serde(rename = "E_relax_max_rel")]
        max_rel: Option<f64>,
        /// RMS log10 error of E(t), decades.
        #[serde(rename = "log10_E_relax_rms")]
        log10_rms: Option<f64>,
    },
    /// Tensile creep compliance D(t).
    Creep {
        /// RMS relative error of D(t).
        #[serde(rename = "D_creep_rms_rel")]
        rms_rel: Option<f64>,
        /// Largest |relative error| of D(t).
        #[serde(rename = "D_creep_max_rel")]
        max_rel: Option<f64>,
        /// RMS log10 error of D(t), decades.
        #[serde(rename = "log10_D_creep_rms")]
        log10_rms: Option<f64>,
    },
}

impl TimeMetrics {
    /// (RMS relative, largest |relative|, RMS log10 decades).
    pub fn values(&self) -> (Option<f64>, Option<f64>, Option<f64>) {
        match *self {
            TimeMetrics::Relaxation {
                rms_rel,
                max_rel,
                log10_rms,
            }
            | TimeMetrics::Creep {
                rms_rel,
                max_rel,
                log10_rms,
            } => (rms_rel, max_rel, log10_rms),
        }
    }
}

/// Compares the fit's E(t), or its creep compliance, with `data` (module
/// doc).
pub fn compare_relaxation(
    fit: &FitDir,
    data: &RelaxationData,
    options: &DmaOptions,
) -> Result<RelaxationComparison, ReportError> {
    let isotherms = group_temperatures(data.points.iter().map(|p| p.temperature));
    let (log_shifts, notes) = isotherm_shifts(&data.path, &isotherms, fit, options)?;
    // (t_r, E): t_r = t/a_T.
    let mut points: Vec<(f64, f64)> = data.points.iter().map(|p| (p.time, p.value)).collect();
    for (iso, (_, log_shift)) in isotherms.iter().zip(&log_shifts) {
        let factor = 10f64.powf(*log_shift);
        for &i in &iso.points {
            points[i].0 /= factor;
        }
    }
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    let window = fit.summary.window;
    let (t_lo, t_hi) = (1.0 / window.omega_max, 1.0 / window.omega_min);
    let inside: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|p| p.0 >= t_lo && p.0 <= t_hi)
        .collect();
    let series = data.quantity.of_series(&fit.master_curve);
    let (rms_rel, max_rel, log10_rms) = time_errors(&inside, &series);
    let creep = data.quantity == TimeQuantity::Creep;
    let metrics = if creep {
        TimeMetrics::Creep {
            rms_rel,
            max_rel,
            log10_rms,
        }
    } else {
        TimeMetrics::Relaxation {
            rms_rel,
            max_rel,
            log10_rms,
        }
    };
    let range = [points[0].0, points[points.len() - 1].0];
    let mut warnings = Vec::new();
    if inside.is_empty() {
        warnings.push(format!(
            "no {} point lies in the times the fit determines: [{t_lo:.3e}, {t_hi:.3e}] \
             s (1/ω of the fit's window) and the data's [{:.3e}, {:.3e}] s at the fit's \
             reference state do not overlap; no metric can be computed",
            data.quantity.name(),
            range[0],
            range[1]
        ));
    }
    Ok(RelaxationComparison {
        n_points: inside.len(),
        t_min: inside.first().map(|p| p.0),
        t_max: inside.last().map(|p| p.0),
        metrics,
        dma_file: data.path.display().to_string(),
        dma_format: if creep { "csv-creep" } else { "csv-relaxation" },
        modulus_kind: data.kind.name(),
        poisson: fit.summary.poisson,
        fit_window_time: [t_lo, t_hi],
        dma_time_range: range,
        dma_points: points.len(),
        dma_shift: log_shifts
            .iter()
            .map(|&(temperature, log_shift)| IsothermShift {
                temperature,
                log_shift,
            })
            .collect(),
        overlap_empty: inside.is_empty(),
        notes: data.notes.iter().cloned().chain(notes).collect(),
        warnings,
    })
}
