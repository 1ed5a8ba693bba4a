//! The fits `shift = "auto"` compares ([`crate::temperature_set::law`]
//! says how it chooses):
//!
//! 1. The joint fit with WLF shifts, as `shift = "wlf"` makes it (its λ
//!    path, τ grid and starts).
//! 2. The free shifts at that λ, on that grid, from that solution (as
//!    `shift = "free"` makes them, [`super::free_from_wlf`]); WLF is tested
//!    against them.
//! 3. Only when WLF is rejected: Arrhenius at the same λ and grid, from the
//!    free fit's material and its E_a fitted to the free shifts.
//! 4. When WLF is rejected, the law chosen (Arrhenius or free) is fitted
//!    again with a λ of its own ([`own_lambda`]): the WLF fit's λ was
//!    chosen for shifts the data reject.
//!
//! The chosen fit carries the runs of all, in order. With two temperatures
//! there is one shift, which no law can be tested on: free. When T_ref is
//! not a measured temperature free shifts cannot be fitted (they are fixed
//! at T_ref): WLF, untested.

use crate::data::Measurements;
use crate::error::FitError;
use crate::params::{ShiftKind, ValidFitParams};
use crate::shift::distinct_temperatures;
use crate::temperature_set::law::{LawCandidate, LawFit, ShiftChoice, law_name};
use crate::temperature_set::{ShiftStart, material_first, temperature_set};

use super::assemble::GridOutcome;
use super::{approximate_fit, at_lambda_of, joint_from_material, master_curve};

/// The fit `shift = "auto"` chose, and what goes with it.
pub(super) struct ChosenLaw {
    /// The joint fit under the chosen law.
    pub grid: GridOutcome,
    /// (density, AICc) of `terms = "auto"`, from the WLF fit.
    pub candidates: Vec<[f64; 2]>,
    /// The start the cross-check carries the anchor with: the model-free
    /// overlap of the μ(v) curves where there is one.
    pub set: ShiftStart,
    /// How the law was chosen.
    pub choice: ShiftChoice,
}

/// `params` with the shift law `kind`.
fn with_kind(params: &ValidFitParams, kind: ShiftKind) -> ValidFitParams {
    let mut p = params.clone();
    p.shift.kind = kind;
    p
}

/// The set's shift under `params`' law, which has one (≥ 2 temperatures).
fn start_of(data: &Measurements, params: &ValidFitParams) -> Result<ShiftStart, FitError> {
    temperature_set(data, params)?.ok_or(FitError::Internal(
        "a temperature set lost its temperatures",
    ))
}

/// How the choice sees the fit `grid` with `parameters` shift constants.
fn law_fit(model: &'static str, parameters: usize, grid: &GridOutcome) -> LawFit {
    LawFit {
        model,
        parameters,
        objective: grid.fit.objective,
        misfit: grid.fit.misfit,
        effective_parameters: grid.fit.effective_parameters,
    }
}

/// Appends the runs of `other` (a fit the choice compared) to `grid`'s,
/// staged `auto, <law>: …`.
fn absorb_runs(grid: &mut GridOutcome, other: &GridOutcome, model: &str) {
    grid.fit
        .runs
        .extend(other.fit.runs.iter().cloned().map(|mut r| {
            r.stage = format!("auto, {}: {}", law_name(model), r.stage);
            r
        }));
}

/// The law of a temperature set (≥ 2 temperatures) chosen from its data;
/// `None` for data at one temperature.
pub(super) fn choose_law(
    data: &Measurements,
    params: &ValidFitParams,
) -> Result<Option<ChosenLaw>, FitError> {
    let temps = distinct_temperatures(data);
    if temps.len() < 2 {
        return Ok(None);
    }
    let free_params = with_kind(params, ShiftKind::Free);
    let free_set = match temperature_set(data, &free_params) {
        Ok(set) => set,
        // T_ref is not a measured temperature: free shifts cannot be fitted.
        Err(FitError::InvalidSetting { .. }) => None,
        Err(e) => return Err(e),
    };
    if temps.len() == 2
        && let Some(set) = free_set
    {
        let (grid, candidates) = master_curve(data, &free_params, Some(&set))?;
        let choice = ShiftChoice::untested(
            &law_fit("free", 1, &grid),
            "two temperatures: one shift, which no law can be tested on; it is fitted free".into(),
        );
        return Ok(Some(ChosenLaw {
            grid,
            candidates,
            set,
            choice,
        }));
    }
    let wlf_params = with_kind(params, ShiftKind::Wlf);
    let wlf_set = start_of(data, &wlf_params)?;
    let (wlf, candidates) = master_curve(data, &wlf_params, Some(&wlf_set))?;
    let Some(free_set) = free_set else {
        let choice = ShiftChoice::untested(
            &law_fit("wlf", 2, &wlf),
            format!(
                "T_ref = {} °C is not a measured temperature, so free shifts (fixed at T_ref) \
                 cannot be fitted to test a law against; WLF is kept untested (set T_ref to one \
                 of the measured temperatures to let the data choose)",
                wlf_set.param.t_ref()
            ),
        );
        return Ok(Some(ChosenLaw {
            grid: wlf,
            candidates,
            set: wlf_set,
            choice,
        }));
    };
    tested_laws(data, params, wlf, candidates, free_set).map(Some)
}

/// A joint fit and the (density, AICc) of `terms = "auto"` behind it.
type Refit = (GridOutcome, Vec<[f64; 2]>);

/// The law chosen where WLF is rejected (`fitted`, at the WLF fit's λ,
/// under `params` and the shift of `set`) fitted again with a λ of its
/// own, as a joint fit from a fit of all rows as one curve at its shifts
/// ([`crate::temperature_set::material_first`]); `None` when that one-curve
/// fit fails. With the terms candidates of that fit.
///
/// Why: the λ of the WLF fit was chosen for shifts the data reject. On
/// shifts with a kink at T_g (7 temperatures, 1 % noise) its discrepancy
/// principle walked to the bottom of the path, λ = 1e-8, where the fit is
/// all but unregularised: χ²/N 0.75, and over 10 seeds the free log10 a_T
/// were within their 1σ at 50 % of the temperatures and within 2σ at 80 %.
pub(super) fn own_lambda(
    data: &Measurements,
    params: &ValidFitParams,
    set: &ShiftStart,
    fitted: &GridOutcome,
) -> Result<Option<Refit>, FitError> {
    let start = set.with_theta(data, fitted.fit.shift_theta.clone());
    let Some(first) = material_first(data, params, &start, approximate_fit) else {
        return Ok(None);
    };
    let candidates = first.terms.candidates.clone();
    Ok(Some((
        joint_from_material(data, params, first, &start)?,
        candidates,
    )))
}

/// The law chosen by testing WLF (`wlf`, the joint fit with WLF shifts)
/// and, when the data reject it, Arrhenius against the free shifts
/// (`free_set`: their parametrisation and model-free start).
fn tested_laws(
    data: &Measurements,
    params: &ValidFitParams,
    mut wlf: GridOutcome,
    candidates: Vec<[f64; 2]>,
    free_set: ShiftStart,
) -> Result<ChosenLaw, FitError> {
    let temps = free_set.param.temperatures().to_vec();
    let n = data.len();
    let log_shift_of = |grid: &GridOutcome| -> Vec<f64> {
        let shift = grid.fit.shift.as_ref();
        temps
            .iter()
            .map(|&t| shift.and_then(|s| s.log_shift_at(t)).unwrap_or(0.0))
            .collect()
    };
    let free_params = with_kind(params, ShiftKind::Free);
    let free_start = free_set.with_theta(
        data,
        free_set.param.theta_of_log_shifts(&log_shift_of(&wlf)),
    );
    let free = at_lambda_of(
        data,
        &free_params,
        &wlf.fit.model,
        &wlf.fit.lambda,
        &free_start,
    )?;
    let free_fit = law_fit("free", temps.len() - 1, &free);
    let wlf_test = LawCandidate::tested(&law_fit("wlf", 2, &wlf), &free_fit, n);
    if wlf_test.rejected == Some(false) {
        absorb_runs(&mut wlf, &free, "free");
        let choice = ShiftChoice::first_accepted(vec![wlf_test], LawCandidate::free(&free_fit));
        return Ok(ChosenLaw {
            grid: wlf,
            candidates,
            set: free_set,
            choice,
        });
    }
    let arrhenius_params = with_kind(params, ShiftKind::Arrhenius);
    let arrhenius_set = start_of(data, &arrhenius_params)?;
    let arrhenius_start = arrhenius_set.with_theta(
        data,
        arrhenius_set
            .param
            .theta_of_log_shifts(&log_shift_of(&free)),
    );
    let arrhenius = at_lambda_of(
        data,
        &arrhenius_params,
        &free.fit.model,
        &wlf.fit.lambda,
        &arrhenius_start,
    )?;
    let arrhenius_test = LawCandidate::tested(&law_fit("arrhenius", 1, &arrhenius), &free_fit, n);
    let choice = ShiftChoice::first_accepted(
        vec![wlf_test, arrhenius_test],
        LawCandidate::free(&free_fit),
    );
    let (fitted, kind_params, set) = if choice.model == "arrhenius" {
        (&arrhenius, &arrhenius_params, &arrhenius_set)
    } else {
        (&free, &free_params, &free_set)
    };
    let (mut grid, candidates) = own_lambda(data, kind_params, set, fitted)?.unwrap_or_else(|| {
        let mut grid = fitted.clone();
        grid.fit.warnings.push(format!(
            "shift law: λ = {:.3e} and the τ grid were chosen with WLF shifts, which the data \
             reject, and the {} fitted at that λ from the WLF solution (the fit of all rows as \
             one curve that would give them their own λ failed)",
            grid.fit.lambda.value,
            law_name(choice.model)
        ));
        (grid, candidates)
    });
    // Every run, in the order made: WLF's, the free shifts', Arrhenius',
    // then the chosen law's own.
    let own = std::mem::replace(&mut grid.fit.runs, std::mem::take(&mut wlf.fit.runs));
    absorb_runs(&mut grid, &free, "free");
    absorb_runs(&mut grid, &arrhenius, "arrhenius");
    grid.fit.runs.extend(own);
    Ok(ChosenLaw {
        grid,
        candidates,
        set: free_set,
        choice,
    })
}
