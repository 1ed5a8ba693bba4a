//! The fitted μ(v) on a dense grid of speeds, for friction.png:
//! mu.csv holds the fit's μ at the measured speeds only, and a line
//! through those has kinks where the data are sparse.
//!
//! The curve is the model's friction sweep (Persson 2010, Eqs. (11) and
//! (17)) of the Prony series in fit.json under the fit's scene, computed as
//! the fit computes mu.csv's `mu_fit` (`fitted_friction` in the fit
//! crate's driver): per temperature at the reduced speeds v·a_T of the
//! shift in fit.json, under the load F/b_T where the scene gives vertical
//! factors b_T ([`rollfit_fit::vertical`]), and with `physics = "exact"`
//! times r = μ_exact/μ_approx carried between the measured speeds by the
//! cubic in ln v the fit itself uses
//! ([`rollfit_fit::exact_physics::interpolate`]). It spans each
//! temperature's measured speeds with [`DENSE_POINTS`] log-spaced speeds:
//! the model, not an interpolant, between the points.
//!
//! A joint fit with DMA data that fitted the friction factor κ
//! (fit.json's `joint.friction_factor`) describes μ_measured = κ μ_theory:
//! its mu.csv's `mu_fit` carries κ, and so does the curve here
//! ([`friction_factor`]).
//!
//! The scene is not in the fit folder; the caller reads it (fit.json's
//! `input.scene`) and hands over what the curve needs ([`RollingScene`]).
//! A scene edited since the fit would draw another curve, so the same
//! computation at the measured speeds must first reproduce `mu_fit` to
//! [`MATCH_TOLERANCE`]; otherwise no curve is drawn
//! ([`ReportError::SceneMismatch`]).
//!
//! # References
//! - B.N.J. Persson, "Rolling friction for hard cylinder and sphere on
//!   viscoelastic solid", Eur. Phys. J. E 33 (2010) 327–333.

use rollfit_fit::exact_physics::interpolate;
use rollfit_fit::vertical::{load_factor, scene_under_load};
use rollfit_fit::{FitParams, RollingSetup};
use rollfit_io::fit_dir::{FitDir, FitSummary, FrictionRow};
use rollfit_io::scene::log_spaced;
use rollfit_model::{Prony, VerticalShift};

use crate::error::ReportError;

/// Speeds of the dense curve per temperature: 240 over the 2–9 decades a
/// rolling sweep spans is 25–120 per decade, so that the line has no
/// visible corner at a friction peak a decade wide.
pub const DENSE_POINTS: usize = 240;

/// Largest relative difference between mu.csv's `mu_fit` and the scene's
/// μ at the measured speeds for the scene to count as the fit's: a
/// thousand times the default quadrature tolerance (a `--tolerance` given
/// to the fit changes μ by about that tolerance), and a hundredth of any
/// change of radius, load or ν that a picture would show.
pub const MATCH_TOLERANCE: f64 = 1e-3;

/// What the fitted μ(v) needs besides the Prony series: the scene's
/// rolling set-up, its quadrature tolerance and its known vertical
/// factors b_T.
#[derive(Debug, Clone, PartialEq)]
pub struct RollingScene {
    /// Body, load, substrate and contact-size rule.
    pub setup: RollingSetup,
    /// Relative tolerance of the model's quadrature.
    pub tolerance: f64,
    /// Vertical factors b_T of the scene's `[material.shift]` (used for a
    /// temperature set only, as in the fit).
    pub vertical: Option<VerticalShift>,
}

impl RollingScene {
    /// The scene of a fit from its set-up and its settings as a scene file
    /// gives them (`rollfit_io::scene::SceneFile::fit_setup`).
    pub fn new(setup: RollingSetup, params: &FitParams) -> RollingScene {
        RollingScene {
            setup,
            tolerance: params.model_tolerance,
            vertical: params.shift.vertical.clone(),
        }
    }
}

/// The fitted μ(v) of one temperature on the dense grid.
#[derive(Debug, Clone, PartialEq)]
pub struct FittedCurve {
    /// °C (None for data without a temperature column).
    pub temperature: Option<f64>,
    /// Measured speeds v, m/s (not reduced), log-spaced from the
    /// temperature's lowest measured speed to its highest, both exact.
    pub speeds: Vec<f64>,
    /// μ of the fit at each speed.
    pub friction: Vec<f64>,
}

/// The fitted line friction.png draws.
#[derive(Debug, Clone, PartialEq)]
pub enum FittedLine {
    /// The fitted μ(v) on a dense grid, one curve per temperature in the
    /// order of [`temperature_groups`].
    Dense(Vec<FittedCurve>),
    /// mu.csv's `mu_fit` at the measured speeds joined by straight lines,
    /// because the dense curve could not be computed (`why`).
    AtData {
        /// Why there is no dense curve.
        why: String,
    },
}

impl FittedLine {
    /// The dense curve of `fit` under `scene`, or why there is none.
    pub fn of(fit: &FitDir, scene: &RollingScene) -> FittedLine {
        match dense_curves(fit, scene) {
            Ok(curves) => FittedLine::Dense(curves),
            Err(e) => FittedLine::AtData { why: e.to_string() },
        }
    }
}

/// The friction factor κ a joint fit multiplies the model's μ by
/// (μ_measured = κ μ_theory): fit.json's `joint.friction_factor`, else 1.
pub fn friction_factor(summary: &FitSummary) -> f64 {
    summary
        .joint
        .as_ref()
        .and_then(|j| j.friction_factor.as_ref())
        .map_or(1.0, |k| k.value)
}

/// Rows of mu.csv grouped by temperature (one group without a T column),
/// in the file's order of first appearance, each sorted by speed.
pub fn temperature_groups(rows: &[FrictionRow]) -> Vec<(Option<f64>, Vec<FrictionRow>)> {
    let mut groups: Vec<(Option<f64>, Vec<FrictionRow>)> = Vec::new();
    for row in rows {
        match groups.iter_mut().find(|(t, _)| *t == row.temperature) {
            Some((_, members)) => members.push(*row),
            None => groups.push((row.temperature, vec![*row])),
        }
    }
    for (_, members) in &mut groups {
        members.sort_by(|a, b| a.speed.total_cmp(&b.speed));
    }
    groups
}

/// The fitted μ(v) of `fit` under `scene` on [`DENSE_POINTS`] speeds per
/// temperature; an error when the scene does not reproduce mu.csv's
/// `mu_fit` ([`MATCH_TOLERANCE`]) or the model cannot be evaluated.
pub fn dense_curves(fit: &FitDir, scene: &RollingScene) -> Result<Vec<FittedCurve>, ReportError> {
    let prony = fit.master_curve.clone();
    temperature_groups(&fit.friction)
        .iter()
        .map(|(t, members)| group_curve(fit, scene, &prony, *t, members))
        .collect()
}

/// The dense curve of one temperature's rows `members` (sorted by speed).
fn group_curve(
    fit: &FitDir,
    scene: &RollingScene,
    prony: &Prony,
    temperature: Option<f64>,
    members: &[FrictionRow],
) -> Result<FittedCurve, ReportError> {
    let failed = |message: String| ReportError::FittedFriction { message };
    let (log_shift, factor) = match (temperature, &fit.summary.shift) {
        (Some(t), Some(shift)) => {
            let log_shift = shift.log_shift_at(t).ok_or_else(|| {
                failed(format!("fit.json's shift gives no log10 a_T at T = {t} °C"))
            })?;
            let factor =
                load_factor(scene.vertical.as_ref(), t).map_err(|e| failed(e.to_string()))?;
            (log_shift, factor)
        }
        _ => (0.0, 1.0),
    };
    let model = scene_under_load(&scene.setup, prony.clone(), scene.tolerance, factor)
        .map_err(|e| failed(e.to_string()))?;
    // κ is 1 but for a joint fit that fitted it; times 1 leaves every
    // other fit's curve as it was, to the bit.
    let kappa = friction_factor(&fit.summary);
    // μ at v·a_T, written as the fit writes it so that the speeds agree to
    // the bit.
    let sweep = |speeds: &[f64]| -> Result<Vec<f64>, ReportError> {
        let reduced: Vec<f64> = speeds.iter().map(|v| v * 10f64.powf(log_shift)).collect();
        let mu = model
            .friction_sweep(&reduced)
            .map_err(|e| failed(e.to_string()))?;
        Ok(mu.into_iter().map(|m| kappa * m).collect())
    };
    let correction = ExactCorrection::of(fit, members);

    let measured: Vec<f64> = members.iter().map(|r| r.speed).collect();
    let at_data = sweep(&measured)?;
    for (r, mu) in members.iter().zip(at_data) {
        let mu = mu * correction.at(r.speed);
        let off = (mu / r.mu_fit - 1.0).abs();
        if off.is_nan() || off > MATCH_TOLERANCE {
            return Err(ReportError::SceneMismatch {
                off,
                speed: r.speed,
                temperature,
            });
        }
    }

    let speeds = log_spaced(measured[0], measured[measured.len() - 1], DENSE_POINTS);
    debug_assert_eq!(speeds.len(), DENSE_POINTS);
    let friction = sweep(&speeds)?
        .into_iter()
        .zip(&speeds)
        .map(|(mu, &v)| mu * correction.at(v))
        .collect();
    Ok(FittedCurve {
        temperature,
        speeds,
        friction,
    })
}

/// r = μ_exact/μ_approx of a fit with `physics = "exact"` between one
/// temperature's measured speeds (1 for the approximate physics).
struct ExactCorrection {
    /// Distinct measured speeds, increasing, m/s.
    speeds: Vec<f64>,
    /// ln r at each.
    ln_r: Vec<f64>,
}

impl ExactCorrection {
    /// From mu.csv's `exact_correction` of `members` (sorted by speed);
    /// none unless every row has one.
    fn of(fit: &FitDir, members: &[FrictionRow]) -> ExactCorrection {
        let mut correction = ExactCorrection {
            speeds: Vec::new(),
            ln_r: Vec::new(),
        };
        if fit.summary.physics.is_none() || members.iter().any(|r| r.exact_correction.is_none()) {
            return correction;
        }
        for r in members {
            // Rows at one speed share r: the fit interpolates r from its
            // solved speeds to the rows.
            if correction.speeds.last() != Some(&r.speed) {
                correction.speeds.push(r.speed);
                correction.ln_r.push(r.exact_correction.unwrap_or(1.0).ln());
            }
        }
        correction
    }

    /// r at speed `v` (within the measured range).
    fn at(&self, v: f64) -> f64 {
        if self.speeds.is_empty() {
            1.0
        } else {
            interpolate(&self.speeds, &self.ln_r, v).exp()
        }
    }
}
