//! The τ grid of a fit and the choice of its number of terms.
//!
//! The grid is [`crate::tau_grid`]'s over the band the data's speeds probe.
//! For `terms = "auto"` the fit is made on grids of 1, 2 and 3 terms per
//! decade and the one with the smallest corrected Akaike criterion wins,
//!
//!   AICc = N ln(misfit/N) + 2k + 2k(k + 1)/(N − k − 1),
//!
//! k the effective parameters plus one for the noise level.
//!
//! # References
//! - C.M. Hurvich, C.-L. Tsai, "Regression and time series model selection
//!   in small samples", Biometrika 76 (1989) 297–307.

use crate::error::FitError;
use crate::params::{TermRule, ValidFitParams};
use crate::report::{RunRecord, TermsRecord};
use crate::tau_grid::{SOFTEST_MODULUS, probed_band, relaxation_times};

use super::assemble::GridOutcome;

/// The densities (terms per decade) compared for `terms = "auto"`.
pub(super) const AUTO_DENSITIES: [f64; 3] = [1.0, 2.0, 3.0];

/// The τ grid for `rule` over the band probed by speeds spanning `range`.
pub(super) fn grid(range: (f64, f64), params: &ValidFitParams, rule: &TermRule) -> Vec<f64> {
    let soft = match (params.anchor, &params.start) {
        (Some(a), _) if a.omega == 0.0 => a.modulus,
        (_, Some(s)) => s.static_modulus,
        _ => SOFTEST_MODULUS,
    };
    let band = probed_band(&params.setup, range, soft, params.e1_max);
    relaxation_times(band, rule)
}

/// Corrected Akaike criterion with k effective parameters.
fn aicc(n: usize, misfit: f64, k: f64) -> f64 {
    let n = n as f64;
    let k = k + 1.0; // the noise level
    n * (misfit / n).ln() + 2.0 * k + 2.0 * k * (k + 1.0) / (n - k - 1.0).max(0.5)
}

/// The fits of `terms = "auto"`, offered one density at a time.
#[derive(Default)]
pub(super) struct TermChoice {
    /// The fit with the smallest AICc so far, with its AICc.
    best: Option<(f64, GridOutcome)>,
    /// (density, AICc) of every fit offered.
    candidates: Vec<[f64; 2]>,
    /// The runs of every fit offered, in order.
    runs: Vec<RunRecord>,
}

impl TermChoice {
    /// Offers the fit `outcome` on a grid of `density` terms per decade to
    /// `n` data points.
    pub(super) fn offer(&mut self, density: f64, n: usize, outcome: GridOutcome) {
        let aicc = aicc(n, outcome.fit.misfit, outcome.fit.effective_parameters);
        self.candidates.push([density, aicc]);
        self.runs.extend(outcome.fit.runs.iter().cloned());
        if self.best.as_ref().is_none_or(|(a, _)| aicc < *a) {
            self.best = Some((aicc, outcome));
        }
    }

    /// The winner, holding the runs of every fit, and the candidates.
    pub(super) fn into_best(self) -> Result<(GridOutcome, Vec<[f64; 2]>), FitError> {
        let (_, mut best) = self.best.ok_or_else(|| {
            FitError::InsufficientData(
                "too few data points for even one relaxation time per decade".into(),
            )
        })?;
        best.fit.runs = self.runs;
        Ok((best, self.candidates))
    }
}

/// The record of the terms of the fitted grid `tau` under `rule`.
pub(super) fn terms_record(tau: &[f64], rule: &TermRule, candidates: Vec<[f64; 2]>) -> TermsRecord {
    let count = tau.len();
    let span = (tau[count - 1] / tau[0]).log10();
    TermsRecord {
        count,
        per_decade: if span > 0.0 {
            (count - 1) as f64 / span
        } else {
            0.0
        },
        rule: match rule {
            TermRule::PerDecade(_) => "per_decade",
            TermRule::Count(_) => "count",
            TermRule::Explicit(_) => "explicit",
            TermRule::Auto => "aicc",
        }
        .into(),
        candidates,
    }
}
