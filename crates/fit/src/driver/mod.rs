//! The fit driver: τ grid, starts, λ choice, solver runs, analysis.
//!
//! 1. The τ grid of [`crate::tau_grid`] for the data's speeds (for
//!    `terms = "auto"`: 1, 2 and 3 per decade, chosen by AICc).
//! 2. A neutral start: a flat spectrum with E1/E0 = 1000 at the anchored
//!    (or starting, or 1 MPa) scale.
//! 3. With an anchor, the starts race at the first λ: the neutral start,
//!    four spectra concentrated in a bump at different places of the
//!    probed band, and seeded perturbations of the neutral start (N(0, 1)
//!    in each log-parameter) each run a few evaluations, and the lowest V
//!    goes on.
//! 4. λ: fixed, or the decreasing path of [`crate::regularization`] with
//!    warm starts moved by the Gauss–Newton predictor, then refinement on
//!    the linearisation of the fits next to the rule's λ, confirmed by a
//!    fit there (`linearised.rs`, `lambda.rs`).
//! 5. Without the race (unanchored fits) or at a fixed λ, the bumps and the
//!    perturbations are run at the chosen λ; the best V wins.
//! 6. Curvature, window, determined terms and bands at the optimum.
//!
//! Results are deterministic for a given seed: the solvers are
//! deterministic and the perturbations come from ChaCha8 seeded with it.
//!
//! With `physics = "exact"` the entry [`fit`] hands the whole of this to
//! [`crate::exact_physics`], which runs it on corrected data (through
//! `fit_measured`, so that the plausibility checks of μ see the measured
//! rows) until the correction stops changing.
//!
//! Where each step lives: the entry [`fit`] and the fits a temperature set
//! is built from (here); the τ grid and the choice of terms (`terms.rs`);
//! the starts (`starts.rs`); λ (`lambda.rs`) and the linearisation it
//! predicts from (`linearised.rs`); the solver runs on one grid
//! (`grid.rs`); the analysis of the optimum (`optimum.rs`); the scale
//! profile of an unanchored fit (`profile.rs`); the fits `shift = "auto"`
//! compares (`law.rs`); the report (`assemble.rs`).
//! The objective is the crate's `objective` module's, the solvers are
//! [`crate::solvers`]'.

mod assemble;
mod grid;
mod joint;
mod lambda;
mod law;
mod linearised;
mod optimum;
mod profile;
mod starts;
mod terms;

use std::time::Instant;

use crate::condense::condense;
use crate::data::Measurements;
use crate::error::FitError;
use crate::exact_physics::defect_correction;
use crate::parametrization::Parametrization;
use crate::params::{Lambda, ModulusAnchor, Physics, ShiftKind, TermRule, ValidFitParams};
use crate::regularization::path;
use crate::report::{FitReport, LambdaRecord, ModelRecord};
use crate::temperature_set::cross_check::cross_check;
use crate::temperature_set::{ShiftStart, material_first, temperature_set, wlf_before_free};
use crate::vertical;

use assemble::{GridOutcome, Whole, assemble, fitted_friction, plausibility_warnings};
use grid::solve_on_grid;
use law::choose_law;
use profile::profile_scale;
use terms::{AUTO_DENSITIES, TermChoice, grid, terms_record};

/// How far (a factor, either side of its geometric centre) the 2σ interval
/// of an unanchored fit's E0 may reach before the scale counts as
/// undetermined
/// ([`crate::report::ScaleRecord`]). A factor 3 in E0 moves the Hertz
/// contact radius by 3^{1/3} ≈ 1.44 for a ball (√3 for a cylinder) and
/// with it every contact frequency v/a by 0.16–0.24 decade, about the
/// width over which tan δ is resolved from 15 speeds; beyond it the master
/// curve's place on the frequency axis is as uncertain as its shape.
pub const SCALE_FACTOR_LIMIT: f64 = 3.0;

/// Fits `data` under `params`: with the approximate physics (Eq. (11) or
/// (17)) directly, with the exact physics by defect correction around such
/// fits ([`crate::exact_physics`]).
pub fn fit(rows: &Measurements, params: &ValidFitParams) -> Result<FitReport, FitError> {
    if params.dma.is_some() {
        let report = joint::fit_joint(rows, params);
        params.cancel.check()?;
        return report;
    }
    crate::joint::refuse_without_dma(params)?;
    let report = match params.physics {
        Physics::Approximate => fit_measured(rows, None, params),
        Physics::Exact => {
            vertical::refuse_exact(rows, params)?;
            defect_correction(rows, params, fit_measured)
        }
    };
    // A stage that tolerates a failed run may have gone on after the
    // cancellation; what it made is not the fit asked for.
    params.cancel.check()?;
    report
}

/// The fit with the approximate physics whatever `params` ask: the fits a
/// temperature set is started from and cross-checked with (inside a defect
/// correction they fit its corrected data, and must not correct again).
fn approximate_fit(rows: &Measurements, params: &ValidFitParams) -> Result<FitReport, FitError> {
    fit_measured(rows, None, params)
}

/// The fit of `rows` with the approximate physics. `measured`: the rows as
/// measured when `rows` are a defect correction's corrected ones (μ_i/r_i,
/// σ_i/r_i); the plausibility checks of the measured μ then see them, condensed
/// like `rows`.
pub(crate) fn fit_measured(
    rows: &Measurements,
    measured: Option<&Measurements>,
    params: &ValidFitParams,
) -> Result<FitReport, FitError> {
    let clock = Instant::now();
    let condensed = condense(rows)?;
    let data = condensed.as_ref().map_or(rows, |c| &c.data);
    // Vertical factors undefined at a measured temperature are refused
    // here, before any numerics, naming the key.
    let vertical_note = if crate::shift::distinct_temperatures(data).len() > 1 {
        vertical::note(data, params.shift.vertical.as_ref())?
    } else {
        None
    };
    let (outcome, candidates, set, shift_choice) = match params.shift.kind {
        ShiftKind::Auto => match choose_law(data, params)? {
            Some(l) => (l.grid, l.candidates, Some(l.set), Some(l.choice)),
            None => {
                let (outcome, candidates) = master_curve(data, params, None)?;
                (outcome, candidates, None, None)
            }
        },
        _ => {
            let set = temperature_set(data, params)?;
            let (outcome, candidates) = master_curve(data, params, set.as_ref())?;
            (outcome, candidates, set, None)
        }
    };
    let set = set.as_ref();
    let mut set_notes = set.map_or_else(Vec::new, |s| s.notes.clone());
    if set.is_some() {
        set_notes.extend(vertical_note);
    }
    let terms = terms_record(&outcome.fit.model.tau, &params.terms, candidates);
    let cross_check = match set {
        Some(set) if params.shift.cross_check => Some(cross_check(
            data,
            params,
            outcome.fit.shift.as_ref(),
            set,
            approximate_fit,
        )),
        _ => None,
    };
    let measured_bins = match measured {
        Some(m) => Some(condense(m)?.map_or_else(|| m.clone(), |c| c.data)),
        None => None,
    };
    let friction = measured_bins.as_ref().unwrap_or(data).friction();
    let plausibility =
        plausibility_warnings(data, friction, params, &outcome.fit, &outcome.window)?;
    let condensed = match &condensed {
        Some(c) => {
            let mu_fit = fitted_friction(rows, params, &outcome.fit)?;
            Some((c, mu_fit))
        }
        None => None,
    };
    let report = assemble(Whole {
        data,
        params,
        set_notes,
        shift_choice,
        grid: outcome,
        terms,
        cross_check,
        plausibility,
        condensed,
        wall_time_s: clock.elapsed().as_secs_f64(),
    });
    if let Some(what) = report.first_non_finite() {
        return Err(FitError::NonFinite(what));
    }
    Ok(report)
}

/// The master curve (and a temperature set's shift) with the AICc of each
/// density tried: for a free shift of three or more temperatures from a
/// WLF fit, for another set from a fit of its rows as one curve, else on
/// the grid of the term rule.
fn master_curve(
    data: &Measurements,
    params: &ValidFitParams,
    set: Option<&ShiftStart>,
) -> Result<(GridOutcome, Vec<[f64; 2]>), FitError> {
    let range = set.map_or_else(|| data.speed_range(), |s| s.range);
    let via_wlf = set.and_then(|s| wlf_before_free(data, params, s, approximate_fit));
    let first = match (&via_wlf, set) {
        (None, Some(s)) => material_first(data, params, s, approximate_fit),
        _ => None,
    };
    match (&params.terms, via_wlf, first) {
        (_, Some((wlf, start)), _) => {
            let candidates = wlf.terms.candidates.clone();
            if describes_data(&wlf.fit_quality) {
                return Ok((free_from_wlf(data, params, wlf, &start)?, candidates));
            }
            // A WLF fit that does not describe the data chose its λ for
            // shifts the data reject: the free shifts get their own (as
            // `auto` gives them, `law::own_lambda`), from the model-free
            // overlap or WLF's shifts, whichever superposes the rows best.
            let overlap = set.into_iter().cloned();
            let starts: Vec<ShiftStart> = overlap.chain([start.clone()]).collect();
            match law::own_lambda(data, params, &starts)? {
                Some((mut own, candidates)) => {
                    own.fit.runs = wlf.runs.into_iter().chain(own.fit.runs).collect();
                    Ok((own, candidates))
                }
                None => Ok((free_from_wlf(data, params, wlf, &start)?, candidates)),
            }
        }
        (_, None, Some(first)) => {
            let candidates = first.terms.candidates.clone();
            let start = set.ok_or_else(|| FitError::setting("shift", "no temperature set"))?;
            Ok((joint_from_material(data, params, first, start)?, candidates))
        }
        (TermRule::Auto, None, None) => {
            let mut choice = TermChoice::default();
            for density in AUTO_DENSITIES {
                let tau = grid(range, params, &TermRule::PerDecade(density));
                match fit_on_grid(data, params, tau, None, set) {
                    Ok(outcome) => choice.offer(density, data.len(), outcome),
                    Err(FitError::InsufficientData(_)) => continue,
                    Err(e) => return Err(e),
                }
            }
            choice.into_best()
        }
        (rule, None, None) => Ok((
            fit_on_grid(data, params, grid(range, params, rule), None, set)?,
            Vec::new(),
        )),
    }
}

/// Whether a fit's own tests of its residuals pass: the χ² test (σ
/// measured), the runs test and the plausibility of an estimated noise
/// ([`crate::quality`]). Not the verdict: "invalid" (the assumptions
/// judged at the fitted material) overrides "poor" there, and a fit whose
/// modulus is questioned may still miss the data, or describe them.
fn describes_data(quality: &crate::quality::FitQuality) -> bool {
    use crate::quality::{IMPLAUSIBLE_NOISE, POOR_P_VALUE, RUNS_P_VALUE};
    let chi2 = quality.chi2_p_value.is_none_or(|p| p >= POOR_P_VALUE);
    let runs = quality.runs.is_none_or(|r| r.p_value >= RUNS_P_VALUE);
    let noise = quality.noise_source == "measured" || quality.noise <= IMPLAUSIBLE_NOISE;
    chi2 && runs && noise
}

/// The fit on one τ grid, from `warm` (a material θ of this grid's
/// parametrisation) instead of the neutral start when given; for a
/// temperature set `set` holds the shift and its starting θ_s. An
/// unanchored fit's bands are widened by its scale profile.
fn fit_on_grid(
    data: &Measurements,
    params: &ValidFitParams,
    tau: Vec<f64>,
    warm: Option<Vec<f64>>,
    set: Option<&ShiftStart>,
) -> Result<GridOutcome, FitError> {
    let optimum = solve_on_grid(data, params, tau.clone(), warm, set)?;
    if params.scale_fixed() || !params.profile {
        return Ok(GridOutcome::new(optimum, None, params.bands));
    }
    let mut profile = profile_scale(data, params, &optimum, set)?;
    let optimum = match profile.refit.take() {
        None => optimum,
        Some(profile::Refit { e0, shape, centre }) => {
            let mut pinned = params.clone();
            pinned.anchor = Some(ModulusAnchor {
                omega: 0.0,
                modulus: e0,
                source: "profile",
            });
            let set = set.map(|s| s.with_theta(data, optimum.shift_theta.clone()));
            let mut refit = solve_on_grid(data, &pinned, tau, Some(shape), set.as_ref())?;
            refit.runs = optimum.runs.into_iter().chain(refit.runs).collect();
            refit.warnings.push(if centre {
                format!(
                    "the scale profile is one-sided (its misfit is least at an end of the range \
                     of E0 where the model holds, an edge and not an estimate); the result is \
                     the fit at the centre of its 2σ interval in log E0, E0 = {e0:.3e} Pa \
                     (the unanchored optimum had E0 = {:.3e} Pa; the interval is fit.json's \
                     scale and widens the bands)",
                    optimum.model.static_modulus
                )
            } else {
                format!(
                    "the unanchored optimum (E0 = {:.3e} Pa) lies outside the range of E0 where \
                     the model holds or outside the scale profile's 2σ interval; the result is \
                     the fit at the profile's best E0 = {e0:.3e} Pa",
                    optimum.model.static_modulus
                )
            });
            profile.rescale_to(refit.model.static_modulus);
            refit
        }
    };
    Ok(GridOutcome::new(optimum, Some(profile), params.bands))
}

/// Free shifts fitted at the λ and on the τ grid of a joint fit with WLF
/// shifts, from its material and shifts (see
/// [`crate::temperature_set::wlf_before_free`] for why); the outcome keeps
/// the WLF fit's λ rule, path and runs, and says what was done.
fn free_from_wlf(
    data: &Measurements,
    params: &ValidFitParams,
    wlf: FitReport,
    start: &ShiftStart,
) -> Result<GridOutcome, FitError> {
    let mut outcome = at_lambda_of(data, params, &wlf.model, &wlf.lambda, start)?;
    let fit = &mut outcome.fit;
    fit.runs = wlf.runs.into_iter().chain(fit.runs.drain(..)).collect();
    fit.warnings.push(format!(
        "free shifts: λ = {:.3e} and the τ grid were chosen with WLF shifts, and the free \
         log10 a_T then fitted at that λ from the WLF solution (at the large λ where the λ path \
         begins, free shifts slide along a power-law curve undetermined)",
        fit.lambda.value
    ));
    Ok(outcome)
}

/// The joint fit with the shift of `start` at the λ (`lambda`) and on the
/// τ grid of another fit of the same set, from its material `model` alone
/// (no bump or seeded restarts: that fit has made them); the outcome
/// carries that fit's λ rule and path.
fn at_lambda_of(
    data: &Measurements,
    params: &ValidFitParams,
    model: &ModelRecord,
    lambda: &LambdaRecord,
    start: &ShiftStart,
) -> Result<GridOutcome, FitError> {
    let tau = model.tau.clone();
    let param = Parametrization::new(tau.clone(), params.anchor);
    let warm = param.theta_of(model.static_modulus, &model.strengths);
    let mut fixed = params.clone();
    fixed.lambda = Lambda::Fixed(lambda.value);
    fixed.terms = TermRule::Explicit(tau.clone());
    // One start, the other fit's optimum: that fit has already probed the
    // bump spectra and the seeded perturbations at this λ on this grid, and
    // the material they would restart (the shift stays at `start`) is the
    // one it rejected them for: they would cost nearly all of the free
    // stage's evaluations and never win (BENCHMARKS.md, "Temperature
    // sets").
    fixed.starts = 1;
    let mut outcome = fit_on_grid(data, &fixed, tau, Some(warm), Some(start))?;
    outcome.fit.lambda = LambdaRecord {
        value: outcome.fit.lambda.value,
        ..lambda.clone()
    };
    Ok(outcome)
}

/// The joint fit of a temperature set from a fit of its rows as one curve at
/// the start shift's reduced speeds ([`crate::temperature_set::material_first`]):
/// on that fit's τ grid, from its material and the start shift, with the λ
/// path beginning at its λ. The outcome keeps the joint fit's λ choice and
/// every run.
fn joint_from_material(
    data: &Measurements,
    params: &ValidFitParams,
    first: FitReport,
    start: &ShiftStart,
) -> Result<GridOutcome, FitError> {
    let m = &first.model;
    let tau = m.tau.clone();
    let param = Parametrization::new(tau.clone(), params.anchor);
    let warm = param.theta_of(m.static_modulus, &m.strengths);
    let mut joint = params.clone();
    if params.lambda == Lambda::Auto {
        joint.path_top = Some(first.lambda.value.max(path()[path().len() - 1]));
    }
    let mut outcome = fit_on_grid(data, &joint, tau, Some(warm), Some(start))?;
    let fit = &mut outcome.fit;
    fit.runs = first
        .runs
        .into_iter()
        .map(|mut r| {
            r.stage = format!("one curve: {}", r.stage);
            r
        })
        .chain(fit.runs.drain(..))
        .collect();
    fit.warnings.push(format!(
        "temperature set: the τ grid and the top of the λ path (λ = {:.3e}) come from a fit of \
         all rows as one curve at the starting shifts; the shift and the material were then \
         fitted together from there (at the large λ where the path otherwise begins the \
         spectrum is nearly a power law, along which the temperatures' curves slide \
         undetermined)",
        first.lambda.value
    ));
    Ok(outcome)
}
