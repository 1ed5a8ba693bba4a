//! The recovered master curve against DMA data: the comparison's record
//! (compare.json) and its rows as people read them. The errors are
//! computed by [`rollfit_fit::compare`].
//!
//! The DMA points are moved to the fit's reference state
//! ([`ToReference::shifted`]: reduced frequency ω_r = ω a_T) and compared with
//! the recovered E*(ω) = [`FitDir::modulus_at`] at the N points whose ω_r
//! lies in the fit's window [ω_min, ω_max] (fit.json `window`: outside it
//! the μ(v) data do not determine the curve, so differences there say
//! nothing about the fit). With r_i = (x_fit − x_DMA)/x_DMA:
//!
//! - `tan_delta_rms_rel` = √(mean r_i²) for x = tan δ = E″/E′,
//!   `tan_delta_max_rel` = max |r_i|;
//! - `abs_E_rms_rel`, `abs_E_max_rel` the same for x = |E*| = √(E′² + E″²);
//! - `log10_E_storage_rms` = √(mean [log10 E′_fit − log10 E′_DMA]²)
//!   (decades), `log10_E_loss_rms` the same for E″.
//!
//! All moduli are Young's (shear DMA data converted with the fit's ν). The
//! comparison also carries the causality check of the DMA points
//! ([`rollfit_fit::causality`], over all of them, not only the overlap):
//! `dma_kk_misfit_storage`, `dma_kk_misfit_loss`. When the window and the
//! DMA frequencies do not overlap, N = 0 and every metric is null, with a
//! warning giving both ranges.

use serde::Serialize;

use rollfit_fit::compare::modulus_errors;
use rollfit_io::FitDir;
use rollfit_io::dma::{DmaData, DmaOptions, DmaPoint};

use crate::causality::{self, CausalFit};
use crate::dma_shift::ToReference;
use crate::error::ReportError;

/// log10 a_T of one DMA isotherm.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct IsothermShift {
    /// °C.
    #[serde(rename = "T")]
    pub temperature: f64,
    /// log10 a_T towards the fit's reference state.
    #[serde(rename = "log_aT")]
    pub log_shift: f64,
}

/// The comparison; its JSON is compare.json (the contract keys
/// first, then what helps reading them).
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    /// DMA points inside the fit's window.
    pub n_points: usize,
    /// Lowest reduced ω among them, rad/s.
    pub omega_min: Option<f64>,
    /// Highest reduced ω among them, rad/s.
    pub omega_max: Option<f64>,
    /// RMS relative error of tan δ.
    pub tan_delta_rms_rel: Option<f64>,
    /// Largest |relative error| of tan δ.
    pub tan_delta_max_rel: Option<f64>,
    /// RMS relative error of |E*|.
    #[serde(rename = "abs_E_rms_rel")]
    pub abs_modulus_rms_rel: Option<f64>,
    /// Largest |relative error| of |E*|.
    #[serde(rename = "abs_E_max_rel")]
    pub abs_modulus_max_rel: Option<f64>,
    /// RMS log10 error of E′, decades.
    #[serde(rename = "log10_E_storage_rms")]
    pub log10_storage_rms: Option<f64>,
    /// RMS log10 error of E″, decades.
    #[serde(rename = "log10_E_loss_rms")]
    pub log10_loss_rms: Option<f64>,
    /// RMS log10 misfit of the best causal fit to the DMA's E′, decades.
    pub dma_kk_misfit_storage: f64,
    /// RMS log10 misfit of the best causal fit to the DMA's E″, decades.
    pub dma_kk_misfit_loss: f64,
    /// Largest |log10 error| of the causal fit to the DMA's E′, decades.
    pub dma_kk_max_storage: f64,
    /// Largest |log10 error| of the causal fit to the DMA's E″, decades.
    pub dma_kk_max_loss: f64,
    /// The DMA file.
    pub dma_file: String,
    /// "csv" or "trios-lims".
    pub dma_format: &'static str,
    /// What the DMA file held: "young" or "shear".
    pub modulus_kind: &'static str,
    /// ν used for shear → Young's (the fit's).
    pub poisson: f64,
    /// The fit's window, rad/s.
    pub fit_window: [f64; 2],
    /// The DMA's reduced frequency range, rad/s.
    pub dma_omega_range: [f64; 2],
    /// All usable DMA points.
    pub dma_points: usize,
    /// The DMA isotherms and their shifts (empty without temperatures).
    pub dma_shift: Vec<IsothermShift>,
    /// RMS threshold of the causality warning, decades.
    pub kk_misfit_threshold: f64,
    /// Largest-miss threshold, decades.
    pub kk_max_misfit_threshold: f64,
    /// Whether the window and the DMA frequencies miss each other.
    pub overlap_empty: bool,
    /// How the DMA points were shifted.
    pub notes: Vec<String>,
    /// Reading, causality and overlap warnings.
    pub warnings: Vec<String>,
    /// All DMA points at the reference state (reduced ω, Young's moduli),
    /// ascending in ω: for plots.
    #[serde(skip)]
    pub points: Vec<DmaPoint>,
    /// The causal fit of the DMA points: for plots.
    #[serde(skip)]
    pub causal: CausalFit,
}

/// How a metric's value reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MetricKind {
    /// A count.
    Count,
    /// An angular frequency, rad/s.
    Frequency,
    /// A relative error (also shown in per cent).
    Relative,
    /// A log10 error in decades (also shown as a factor).
    Decades,
    /// A causality misfit in decades, with its warning threshold.
    Misfit(ThresholdKind),
}

/// Which causality threshold a misfit is held against.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ThresholdKind {
    /// The RMS threshold.
    Rms,
    /// The largest-miss threshold.
    Largest,
}

/// One metric as people read it: its compare.json key, value and meaning.
#[derive(Debug, Clone, PartialEq)]
pub struct MetricRow {
    /// The compare.json key.
    pub key: &'static str,
    /// The value; `None` without overlap.
    pub value: Option<f64>,
    /// How to read it.
    pub kind: MetricKind,
    /// What it is, in words.
    pub meaning: String,
}

impl Comparison {
    /// The metrics in compare.json's order with their meanings: the one
    /// list that the `compare` table and the report page both show.
    pub fn metric_rows(&self) -> Vec<MetricRow> {
        let row = |key, value, kind, meaning: &str| MetricRow {
            key,
            value,
            kind,
            meaning: meaning.to_string(),
        };
        let misfit = |key, value, which, meaning: &str| {
            let threshold = match which {
                ThresholdKind::Rms => self.kk_misfit_threshold,
                ThresholdKind::Largest => self.kk_max_misfit_threshold,
            };
            MetricRow {
                key,
                value: Some(value),
                kind: MetricKind::Misfit(which),
                meaning: format!("{meaning} (warn > {threshold})"),
            }
        };
        vec![
            row(
                "n_points",
                Some(self.n_points as f64),
                MetricKind::Count,
                "DMA points inside the fit's window",
            ),
            row(
                "omega_min",
                self.omega_min,
                MetricKind::Frequency,
                "lowest of them, rad/s (reduced)",
            ),
            row(
                "omega_max",
                self.omega_max,
                MetricKind::Frequency,
                "highest of them, rad/s (reduced)",
            ),
            row(
                "tan_delta_rms_rel",
                self.tan_delta_rms_rel,
                MetricKind::Relative,
                "RMS relative error of tan δ",
            ),
            row(
                "tan_delta_max_rel",
                self.tan_delta_max_rel,
                MetricKind::Relative,
                "largest |relative error| of tan δ",
            ),
            row(
                "abs_E_rms_rel",
                self.abs_modulus_rms_rel,
                MetricKind::Relative,
                "RMS relative error of |E*|",
            ),
            row(
                "abs_E_max_rel",
                self.abs_modulus_max_rel,
                MetricKind::Relative,
                "largest |relative error| of |E*|",
            ),
            row(
                "log10_E_storage_rms",
                self.log10_storage_rms,
                MetricKind::Decades,
                "RMS log10 error of E′, decades",
            ),
            row(
                "log10_E_loss_rms",
                self.log10_loss_rms,
                MetricKind::Decades,
                "RMS log10 error of E″, decades",
            ),
            misfit(
                "dma_kk_misfit_storage",
                self.dma_kk_misfit_storage,
                ThresholdKind::Rms,
                "causal fit to the DMA's E′, RMS decades",
            ),
            misfit(
                "dma_kk_misfit_loss",
                self.dma_kk_misfit_loss,
                ThresholdKind::Rms,
                "causal fit to the DMA's E″, RMS decades",
            ),
            misfit(
                "dma_kk_max_storage",
                self.dma_kk_max_storage,
                ThresholdKind::Largest,
                "causal fit to the DMA's E′, largest miss, decades",
            ),
            misfit(
                "dma_kk_max_loss",
                self.dma_kk_max_loss,
                ThresholdKind::Largest,
                "causal fit to the DMA's E″, largest miss, decades",
            ),
        ]
    }
}

impl MetricRow {
    /// The value as the table shows it ("—" without one).
    pub fn value_text(&self) -> String {
        match (self.value, self.kind) {
            (None, _) => "—".to_string(),
            (Some(v), MetricKind::Count) => format!("{v:.0}"),
            (Some(v), MetricKind::Frequency) => format!("{v:.3e}"),
            // Small errors in exponent form: "0.0000" would hide a 1e-6.
            (Some(v), _) if v != 0.0 && v.abs() < 1e-3 => format!("{v:.3e}"),
            (Some(v), _) => format!("{v:.4}"),
        }
    }

    /// The meaning with the value restated where that helps (per cent, a
    /// factor).
    pub fn meaning_text(&self) -> String {
        match (self.value, self.kind) {
            (Some(v), MetricKind::Relative) => format!("{} ({:.1} %)", self.meaning, 100.0 * v),
            (Some(v), MetricKind::Decades) => {
                format!("{} (×{:.3})", self.meaning, 10f64.powf(v))
            }
            _ => self.meaning.clone(),
        }
    }

    /// Whether a causality misfit is above its warning threshold.
    pub fn warns(&self, comparison: &Comparison) -> bool {
        match (self.value, self.kind) {
            (Some(v), MetricKind::Misfit(ThresholdKind::Rms)) => v > comparison.kk_misfit_threshold,
            (Some(v), MetricKind::Misfit(ThresholdKind::Largest)) => {
                v > comparison.kk_max_misfit_threshold
            }
            _ => false,
        }
    }
}

/// Compares the fit's master curve with `dma` (see the module doc).
pub fn compare(
    fit: &FitDir,
    dma: &DmaData,
    options: &DmaOptions,
) -> Result<Comparison, ReportError> {
    let shifted = dma.shifted(fit, options)?;
    let points = shifted.points;
    let causal = causality::check(&points)?;
    let window = fit.summary.window;
    let inside: Vec<DmaPoint> = points
        .iter()
        .copied()
        .filter(|p| p.omega >= window.omega_min && p.omega <= window.omega_max)
        .collect();
    let errors = modulus_errors(&causality::samples(&inside), &|omega| fit.modulus_at(omega));
    let omega_lo = points[0].omega;
    let omega_hi = points[points.len() - 1].omega;
    let mut warnings = dma.warnings.clone();
    warnings.extend(causal.warnings.iter().cloned());
    let overlap_empty = inside.is_empty();
    if overlap_empty {
        warnings.push(format!(
            "no DMA point lies in the fit's window: the fit's window [{:.3e}, {:.3e}] rad/s and the DMA's [{omega_lo:.3e}, {omega_hi:.3e}] rad/s (at the fit's reference state) do not overlap; no metric can be computed",
            window.omega_min, window.omega_max
        ));
    }
    Ok(Comparison {
        n_points: inside.len(),
        omega_min: inside.first().map(|p| p.omega),
        omega_max: inside.last().map(|p| p.omega),
        tan_delta_rms_rel: errors.tan_delta_rms_rel,
        tan_delta_max_rel: errors.tan_delta_max_rel,
        abs_modulus_rms_rel: errors.abs_modulus_rms_rel,
        abs_modulus_max_rel: errors.abs_modulus_max_rel,
        log10_storage_rms: errors.log10_storage_rms,
        log10_loss_rms: errors.log10_loss_rms,
        dma_kk_misfit_storage: causal.misfit_storage,
        dma_kk_misfit_loss: causal.misfit_loss,
        dma_kk_max_storage: causal.max_misfit_storage.0,
        dma_kk_max_loss: causal.max_misfit_loss.0,
        dma_file: dma.path.display().to_string(),
        dma_format: dma.format,
        modulus_kind: dma.kind.name(),
        poisson: fit.summary.poisson,
        fit_window: [window.omega_min, window.omega_max],
        dma_omega_range: [omega_lo, omega_hi],
        dma_points: points.len(),
        dma_shift: shifted
            .log_shifts
            .iter()
            .map(|&(temperature, log_shift)| IsothermShift {
                temperature,
                log_shift,
            })
            .collect(),
        kk_misfit_threshold: causality::KK_MISFIT_THRESHOLD,
        kk_max_misfit_threshold: causality::KK_MAX_MISFIT_THRESHOLD,
        overlap_empty,
        notes: dma.notes.iter().cloned().chain(shifted.notes).collect(),
        warnings,
        points,
        causal,
    })
}
