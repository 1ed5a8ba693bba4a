//! The result of a fit, put together once everything in it is known: the
//! fit on its τ grid with the window the data determine ([`GridOutcome`]),
//! then the parts only the whole fit knows ([`Whole`]) — the term rule, the
//! shift cross-check, the plausibility warnings, the condensing of dense data and
//! the totals.

use rollfit_model::{Prony, ViscoelasticModulus};

use crate::analysis::{DETERMINED_RELATIVE_SIGMA, determined_stretch};
use crate::condense::Condensed;
use crate::data::Measurements;
use crate::error::FitError;
use crate::extrapolation::extrapolations;
use crate::params::ValidFitParams;
use crate::quality::FitQuality;
use crate::report::{
    AnchorRecord, CrossCheckRow, FitReport, ScaleRecord, ShiftChoice, ShiftCrossCheck, ShiftRecord,
    TermsRecord, Window,
};
use crate::vertical::{LoadGroups, scene_under_load};
use rollfit_model::plausibility;

use super::optimum::Optimum;
use super::profile::ScaleProfile;

/// What the fit on one τ grid found.
#[derive(Debug, Clone)]
pub(super) struct GridOutcome {
    /// The analysed optimum, its bands widened by the scale profile and its
    /// curve cut to `window`.
    pub fit: Optimum,
    /// The window the data determine (the probed window without bands).
    pub window: Window,
    /// (factor, misfit, λ) of the scale profile of an unanchored fit.
    pub scale_profile: Vec<[f64; 3]>,
    /// How well the data determine an unanchored fit's scale.
    pub scale: Option<ScaleRecord>,
}

impl GridOutcome {
    /// The outcome of `fit`, with the scale `profile` of an unanchored fit
    /// and, with `bands`, the window and curve cut to what the data
    /// determine.
    pub(super) fn new(mut fit: Optimum, profile: Option<ScaleProfile>, bands: bool) -> Self {
        let (scale_profile, scale) = match profile {
            Some(profile) => {
                profile.widen(&mut fit.curve);
                fit.runs.extend(profile.runs);
                (profile.points, Some(profile.record))
            }
            None => (Vec::new(), None),
        };
        let window = if bands {
            restrict_to_determined(&mut fit)
        } else {
            fit.probed_window
        };
        GridOutcome {
            fit,
            window,
            scale_profile,
            scale,
        }
    }
}

/// Cuts the curve to the stretch the data determine
/// ([`determined_stretch`]) and returns its window; when tan δ is
/// determined to [`DETERMINED_RELATIVE_SIGMA`] nowhere, keeps the probed
/// window and warns.
fn restrict_to_determined(fit: &mut Optimum) -> Window {
    match determined_stretch(&fit.curve) {
        Some((first, last)) if last > first => {
            fit.curve.truncate(last + 1);
            fit.curve.drain(..first);
            Window {
                omega_min: fit.curve[0].omega,
                omega_max: fit.curve[fit.curve.len() - 1].omega,
            }
        }
        _ => {
            fit.warnings.push(format!(
                "the data determine tan δ to ±{:.0} % (1σ) at no frequency: the whole probed \
                 window is reported, and its bands are wide",
                100.0 * DETERMINED_RELATIVE_SIGMA
            ));
            fit.probed_window
        }
    }
}

/// Everything the report of a whole fit is made of.
pub(super) struct Whole<'x> {
    /// The data fitted (the bins of condensed data).
    pub data: &'x Measurements,
    /// The settings.
    pub params: &'x ValidFitParams,
    /// The fit of the master curve.
    pub grid: GridOutcome,
    /// How the number of terms was chosen.
    pub terms: TermsRecord,
    /// How a temperature set's starting shift was found.
    pub set_notes: Vec<String>,
    /// With `shift = "auto"`: how the law was chosen.
    pub shift_choice: Option<ShiftChoice>,
    /// The shift cross-check of a temperature set, or why it was not made.
    pub cross_check: Option<Result<ShiftCrossCheck, String>>,
    /// The plausibility warnings on data and result.
    pub plausibility: Vec<plausibility::Warning>,
    /// Dense data: how they were condensed, and the fitted μ at every row.
    pub condensed: Option<(&'x Condensed, Vec<f64>)>,
    /// Wall time of the whole fit, s.
    pub wall_time_s: f64,
}

/// The report of the whole fit.
pub(super) fn assemble(whole: Whole<'_>) -> FitReport {
    let Whole {
        data,
        params,
        grid,
        terms,
        set_notes,
        shift_choice,
        cross_check,
        plausibility,
        condensed,
        wall_time_s,
    } = whole;
    let GridOutcome {
        fit,
        window,
        scale_profile,
        scale,
    } = grid;
    let mut warnings = fit.warnings;
    if let Some(scale) = &scale {
        warnings.push(format!("no scale anchor: {}", scale.reason));
    }
    warnings.extend(set_notes);
    let shift_cross_check = match cross_check {
        Some(Ok(check)) => {
            warnings.extend(check.disagreeing().map(cross_check_warning));
            Some(check)
        }
        Some(Err(why)) => {
            warnings.push(format!("shift cross-check not made: {why}"));
            None
        }
        None => None,
    };
    let mut fit_quality = fit.fit_quality;
    judge_assumptions(&mut fit_quality, &mut warnings, plausibility);
    // A law the scene asked for and the fit does not have is said, never
    // silently replaced.
    let shift_choice = shift_choice.or_else(|| {
        let substitute = params.shift.substituted.as_ref()?;
        let shift = fit.shift.as_ref()?;
        Some(ShiftChoice::substitute(shift.model_name(), substitute))
    });
    if let Some(c) = &shift_choice {
        warnings.push(format!("shift law {}: {}", c.model, c.reason));
    }
    if let Some(hint) = free_shift_hint(&fit_quality, fit.shift.as_ref(), &shift_cross_check) {
        warnings.push(format!("fit quality: {hint}"));
        fit_quality.reasons.push(hint);
    }
    let (condensed, mu_fit) = match condensed {
        Some((c, mu_fit)) => {
            warnings.push(c.note());
            if c.record.scatter.is_some() {
                fit_quality.noise_source = "scatter within bins";
            }
            (Some(c.record.clone()), mu_fit)
        }
        None => (None, fit.mu),
    };
    let extrapolated = extrapolations(
        fit.model.static_modulus,
        fit.model.glassy_modulus,
        &fit.curve,
    );
    FitReport {
        extrapolated,
        model: fit.model,
        poisson: params.setup.substrate.poisson,
        window,
        probed_window: fit.probed_window,
        shift: fit.shift,
        shift_choice,
        method: fit.method.name(),
        objective: fit.objective,
        misfit: fit.misfit,
        misfit_per_point: fit.misfit_per_point,
        sigma_weights: data.sigma().is_some(),
        iterations: fit.iterations,
        evaluations: fit.runs.iter().map(|r| r.evaluations).sum(),
        converged: fit.stop.converged(),
        stop_reason: fit.stop.describe(),
        wall_time_s,
        lambda: fit.lambda,
        terms,
        anchor: params.anchor.map(|a| AnchorRecord {
            source: a.source,
            omega: a.omega,
            modulus: a.modulus,
        }),
        effective_parameters: fit.effective_parameters,
        noise: fit.noise,
        fit_quality,
        seed: params.seed,
        warnings,
        runs: fit.runs,
        history: fit.history,
        scale_profile,
        scale,
        shift_cross_check,
        condensed,
        physics: None,
        joint: None,
        shift_theta: fit.shift_theta,
        curve: fit.curve,
        mu_fit,
    }
}

/// The plausibility warnings into `warnings`; those that say the fitted material
/// breaks one of the model's assumptions where the data determine it (a
/// contact small against the body, small strains, a viscoelastic solid's
/// modulus: [`plausibility`]'s checks 1, 2 and 4) make the verdict "invalid": the
/// model has described the data with a material for which the model does
/// not hold, so the fit describes nothing. Extrapolations beyond the window
/// are warnings only.
fn judge_assumptions(
    quality: &mut FitQuality,
    warnings: &mut Vec<String>,
    checks: Vec<plausibility::Warning>,
) {
    for w in checks {
        match w.assumption {
            Some(assumption) => {
                let reason = format!(
                    "invalid: the fitted material breaks the model's assumption of a \
                     {assumption}: {}",
                    w.message
                );
                warnings.push(format!("fit quality: {reason}"));
                quality.reasons.push(reason);
                quality.verdict = "invalid";
            }
            None => warnings.push(w.message),
        }
    }
}

/// The warning of a temperature whose single and joint shifts differ by
/// more than their combined σ allows (`CrossCheckRow::beyond_sigma`): the
/// difference, its σ, and what limits that temperature's single fit.
fn cross_check_warning(row: &CrossCheckRow) -> String {
    let sigma = row.difference_sigma.unwrap_or(f64::NAN);
    let limits = match row.single_fit_limits.as_slice() {
        [] => String::new(),
        limits => format!(" (that temperature alone: {})", limits.join(", ")),
    };
    format!(
        "shift cross-check: at T = {} °C the fit of that temperature alone puts log10 a_T \
         {:+.2} decades from the joint fit's, {:.1} times their combined σ of {sigma:.2}{limits}; \
         the joint shift there is questioned (see shift_cross_check)",
        row.temperature,
        row.difference,
        row.difference.abs() / sigma
    )
}

/// For a poor fit under a law whose shifts the cross-check questions (a
/// temperature's single and joint shifts beyond their combined σ, as the
/// warnings say): the law may be what the data reject, and free shifts
/// follow any law.
fn free_shift_hint(
    quality: &FitQuality,
    shift: Option<&ShiftRecord>,
    check: &Option<ShiftCrossCheck>,
) -> Option<String> {
    let (Some(shift), Some(check)) = (shift, check) else {
        return None;
    };
    let questioned: Vec<&CrossCheckRow> = check.disagreeing().collect();
    if !quality.is_poor() || matches!(shift, ShiftRecord::Free { .. }) || questioned.is_empty() {
        return None;
    }
    let worst = questioned
        .iter()
        .fold(0.0f64, |m, r| m.max(r.difference.abs()));
    let temperatures: Vec<String> = questioned
        .iter()
        .map(|r| format!("{} °C", r.temperature))
        .collect();
    Some(format!(
        "fitted alone, single temperatures put log10 a_T up to {worst:.2} decades off the {} \
         law, beyond their σ at {} (shift_cross_check): the shifts may not follow it; fit one \
         shift per temperature with shift = \"free\" (the scene's [fit], or --shift free), or \
         let the data choose with shift = \"auto\"",
        crate::temperature_set::law::law_name(shift.model_name()),
        temperatures.join(", ")
    ))
}

/// The fitted μ at every row of `data` (the rows of condensed data): the
/// fitted master curve at v·a_T, under the load F/b_T with vertical
/// factors ([`crate::vertical`]).
pub(super) fn fitted_friction(
    data: &Measurements,
    params: &ValidFitParams,
    fit: &Optimum,
) -> Result<Vec<f64>, FitError> {
    let speeds = reduced_speeds(data, fit);
    let m = &fit.model;
    let prony = Prony::new(m.glassy_modulus, m.strengths.clone(), m.tau.clone())?;
    let setup = &params.setup;
    let scene_at = |factor| scene_under_load(setup, prony.clone(), params.model_tolerance, factor);
    let vertical = fit.shift.as_ref().and(params.shift.vertical.as_ref());
    let mu = match LoadGroups::of(data, vertical)? {
        Some(groups) => groups.friction_sweep(scene_at, &speeds)?,
        None => scene_at(1.0)?.friction_sweep(&speeds)?,
    };
    // A joint fit's κ: μ_measured = κ μ_theory.
    let kappa = fit.friction_factor.map_or(1.0, |(k, _)| k);
    Ok(mu.into_iter().map(|m| kappa * m).collect())
}

/// The speeds of `data` on the master curve: v·a_T for a temperature set.
fn reduced_speeds(data: &Measurements, fit: &Optimum) -> Vec<f64> {
    match (&fit.shift, data.temperature()) {
        (Some(shift), Some(temps)) => data
            .speeds()
            .iter()
            .zip(temps)
            .map(|(v, t)| v * 10f64.powf(shift.log_shift_at(*t).unwrap_or(0.0)))
            .collect(),
        _ => data.speeds().to_vec(),
    }
}

/// The plausibility checks of [`plausibility`] on the data, their measured μ
/// `friction` (one per point of `data`: the data's own, or the measured μ
/// of a defect correction's corrected data) and the fitted material, at the
/// reduced speeds (v·a_T) for a temperature set, the material judged inside
/// `window`, where the data determine it.
pub(super) fn plausibility_warnings(
    data: &Measurements,
    friction: &[f64],
    params: &ValidFitParams,
    fit: &Optimum,
    window: &Window,
) -> Result<Vec<plausibility::Warning>, FitError> {
    let setup = &params.setup;
    let speeds = reduced_speeds(data, fit);
    let m = &fit.model;
    let prony = Prony::new(m.glassy_modulus, m.strengths.clone(), m.tau.clone())?;
    let mut out = plausibility::input_warnings(setup, data.speeds(), Some(friction));
    out.extend(plausibility::fitted_material_warnings(
        setup,
        &speeds,
        &|omega| prony.modulus(omega),
        m.static_modulus,
        m.glassy_modulus,
        [window.omega_min, window.omega_max],
    ));
    Ok(out)
}
