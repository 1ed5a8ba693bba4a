//! The scale profile: the bands of an unanchored fit widened by a profile
//! along the modulus scale, the direction rolling data determine worst.
//!
//! The curvature band is local: where V is nearly flat along "stiffer with
//! a little more loss" but the optimum sits against E1_max or the penalty's
//! preference, it can be far too narrow. So the fit is repeated with |E*| at
//! the window's centre ω_c pinned to c·|E*_fit(ω_c)| for the factors
//! [`PROFILE_FACTORS`] (same τ grid and λ); every profile whose data misfit
//! lies within one noise unit of the fit's is as good a description of the
//! data, and the band is widened to enclose all of them (a
//! profile-likelihood interval on the scale; the misfit, not V, decides,
//! because the penalty would otherwise vote for its favourite scale).
//!
//! Each pinned fit starts from its neighbour's shape (continuation): from
//! the neutral start alone a pinned fit far from the optimum can stall in a
//! poor local minimum and cut the profile short with a spurious wall.
//!
//! # References
//! - D.J. Venzon, S.H. Moolgavkar, "A method for computing
//!   profile-likelihood-based confidence intervals", Appl. Statist. 37
//!   (1988) 87–94.

use rollfit_model::{Prony, ViscoelasticModulus};

use crate::data::Measurements;
use crate::error::FitError;
use crate::params::{Lambda, ModulusAnchor, TermRule, ValidFitParams};
use crate::report::{ModulusPoint, RunRecord};
use crate::temperature_set::ShiftStart;

use super::grid::solve_on_grid;
use super::optimum::Optimum;

/// Scale factors of the profile along the weak direction, walked outward
/// from the fit in two chains (stiffer, softer).
const PROFILE_FACTORS: [&[f64]; 2] = [
    &[1.0 / 0.7, 2.0, 2.8, 4.0, 5.6, 8.0, 11.0],
    &[0.7, 0.5, 0.35, 0.2, 0.1],
];

/// Relaxations of λ tried at each point of the scale profile.
const PROFILE_RELAXATION: [f64; 4] = [1.0, 0.1, 0.01, 0.001];

/// The profile of one fit.
pub(super) struct ScaleProfile {
    /// (factor c, misfit, λ) of each pinned fit, by factor.
    pub points: Vec<[f64; 3]>,
    /// Every run of the pinned fits, in order.
    pub runs: Vec<RunRecord>,
    /// The pinned fits that describe the data as well as the fit does.
    accepted: Vec<Prony>,
}

impl ScaleProfile {
    /// Widens the bands of `curve` to enclose every accepted pinned fit.
    pub(super) fn widen(&self, curve: &mut [ModulusPoint]) {
        for point in curve.iter_mut() {
            for p in &self.accepted {
                let e = p.modulus(point.omega);
                point.storage_sigma = point.storage_sigma.max((e.re - point.storage).abs());
                point.loss_sigma = point.loss_sigma.max((e.im - point.loss).abs());
                point.tan_delta_sigma = point
                    .tan_delta_sigma
                    .max((e.im / e.re - point.tan_delta).abs());
                point.magnitude_sigma = point
                    .magnitude_sigma
                    .max((e.norm() - point.magnitude).abs());
            }
        }
    }
}

/// The pinned refits of one fit: what they share.
struct Profiler<'a> {
    data: &'a Measurements,
    params: &'a ValidFitParams,
    /// The fit's shift, continued from its optimum.
    set: Option<ShiftStart>,
    /// The fit's τ grid.
    tau: &'a [f64],
    /// The fit's λ.
    lambda: f64,
    /// ω_c, the centre of the fit's window, rad/s.
    omega_c: f64,
    /// |E*_fit(ω_c)|, Pa.
    centre: f64,
    /// The fit's data misfit.
    misfit: f64,
    /// One noise unit of misfit, s².
    threshold: f64,
    /// Every run so far.
    runs: Vec<RunRecord>,
}

/// The scale profile of the unanchored fit `fit` (module doc).
pub(super) fn profile_scale(
    data: &Measurements,
    params: &ValidFitParams,
    fit: &Optimum,
    set: Option<&ShiftStart>,
) -> Result<ScaleProfile, FitError> {
    let window = fit.probed_window;
    let omega_c = (window.omega_min * window.omega_max).sqrt();
    let m = &fit.model;
    let fitted = Prony::new(m.glassy_modulus, m.strengths.clone(), m.tau.clone())?;
    let mut profiler = Profiler {
        data,
        params,
        set: set.map(|s| s.with_theta(data, fit.shift_theta.clone())),
        tau: &m.tau,
        lambda: fit.lambda.value,
        omega_c,
        centre: fitted.modulus(omega_c).norm(),
        misfit: fit.misfit,
        threshold: fit.noise * fit.noise,
        runs: Vec::new(),
    };
    let mut accepted = Vec::new();
    let mut points = Vec::new();
    // The fit's own shape in the pinned parametrisation: H_k/E0.
    let own_shape = shape(m.strengths.iter(), m.static_modulus);
    for chain in PROFILE_FACTORS {
        let mut from = own_shape.clone();
        for &factor in chain {
            let Some(r) = profiler.pinned(factor, &mut from)? else {
                break;
            };
            points.push([factor, r.misfit, r.lambda.value]);
            let pm = &r.model;
            if profiler.as_good(r.misfit) {
                accepted.push(Prony::new(
                    pm.glassy_modulus,
                    pm.strengths.clone(),
                    pm.tau.clone(),
                )?);
            }
        }
    }
    points.sort_by(|a, b| a[0].total_cmp(&b[0]));
    Ok(ScaleProfile {
        points,
        runs: profiler.runs,
        accepted,
    })
}

impl Profiler<'_> {
    /// Whether a data misfit describes the data as well as the fit does:
    /// within one noise unit of its misfit.
    fn as_good(&self, misfit: f64) -> bool {
        misfit - self.misfit <= self.threshold
    }

    /// The fit with |E*(ω_c)| pinned to `factor` times the fit's, from the
    /// shape `from` (updated to each refit's shape): the weakest smoothing
    /// among λ, λ/10, … λ/1000 that describes the data as well as the fit
    /// does ([`Self::as_good`]), else the weakest tried. At the fit's λ alone the penalty, not the data, would build the wall of
    /// the profile. `None` when the model cannot reach the pinned scale at
    /// all, which ends the chain.
    fn pinned(&mut self, factor: f64, from: &mut Vec<f64>) -> Result<Option<Optimum>, FitError> {
        let mut r = None;
        for relax in PROFILE_RELAXATION {
            let mut pinned = self.params.clone();
            pinned.anchor = Some(ModulusAnchor {
                omega: self.omega_c,
                modulus: factor * self.centre,
                source: "profile",
            });
            pinned.lambda = Lambda::Fixed(self.lambda * relax);
            pinned.starts = 1;
            pinned.bands = false;
            pinned.terms = TermRule::Explicit(self.tau.to_vec());
            let trial = match solve_on_grid(
                self.data,
                &pinned,
                self.tau.to_vec(),
                Some(from.clone()),
                self.set.as_ref(),
            ) {
                Ok(t) => t,
                // A pinned scale the model cannot reach ends the relaxation.
                Err(FitError::Model(_)) => break,
                Err(e) => return Err(e),
            };
            *from = shape(trial.model.strengths.iter(), trial.model.static_modulus);
            self.runs.extend(trial.runs.iter().cloned().map(|mut run| {
                run.stage = format!("scale profile ×{factor:.2}: {}", run.stage);
                run
            }));
            let good = self.as_good(trial.misfit);
            r = Some(trial);
            if good {
                break;
            }
        }
        Ok(r)
    }
}

/// ln(H_k/E0): a material's shape in the pinned parametrisation.
fn shape<'h>(strengths: impl Iterator<Item = &'h f64>, static_modulus: f64) -> Vec<f64> {
    strengths.map(|h| (h / static_modulus).ln()).collect()
}
