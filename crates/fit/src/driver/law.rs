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
use crate::report::{FitReport, RunRecord};
use crate::shift::distinct_temperatures;
use crate::temperature_set::law::{LawCandidate, LawFit, ShiftChoice, law_name};
use crate::temperature_set::{ShiftStart, material_first, temperature_set};

use super::assemble::GridOutcome;
use super::{approximate_fit, at_lambda_of, describes_data, joint_from_material, master_curve};

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
    if !describes_data(&wlf.fit.fit_quality) {
        return laws_at_free_lambda(data, params, (wlf, candidates), free_set, wlf_set).map(Some);
    }
    tested_laws(data, params, wlf, candidates, free_set).map(Some)
}

/// A joint fit and the (density, AICc) of `terms = "auto"` behind it.
type Refit = (GridOutcome, Vec<[f64; 2]>);

/// A law fitted with a λ of its own, as a joint fit from a fit of all rows
/// as one curve ([`crate::temperature_set::material_first`]) at the first
/// of `starts` whose one curve describes the data, else at the one whose
/// shifts superpose the rows best (the lowest misfit of the one curve);
/// `None` when every one-curve fit fails, or the joint fit from the
/// chosen one lands on a material no Prony series holds. With the terms
/// candidates of that fit; the runs of the other starts' one-curve fits
/// come first among the outcome's runs.
///
/// Why a λ of its own: the λ of a law the data reject was chosen for shifts
/// the data reject. On shifts with a kink at T_g (7 temperatures, 1 %
/// noise) WLF's discrepancy principle walked to the bottom of the path,
/// λ = 1e-8, where the fit is all but unregularised and the free shifts
/// fitted there crawl through its ill-conditioned valley (hundreds to
/// thousands of Levenberg–Marquardt iterations). Why several starts: the
/// rejected law's shifts can be far from the data's (on the broad-spectrum
/// replica of tests/broad_spectrum.rs the one curve at WLF's shifts leaves
/// χ²/N = 65, at the model-free overlap of the μ(v) curves 1.6), while on
/// sets whose μ(v) curves barely overlap the overlap is the poorer start.
pub(super) fn own_lambda(
    data: &Measurements,
    params: &ValidFitParams,
    starts: &[ShiftStart],
) -> Result<Option<Refit>, FitError> {
    let mut best: Option<(FitReport, &ShiftStart)> = None;
    let mut others: Vec<RunRecord> = Vec::new();
    for start in starts {
        if best
            .as_ref()
            .is_some_and(|(b, _)| describes_data(&b.fit_quality))
        {
            break;
        }
        let Some(first) = material_first(data, params, start, approximate_fit) else {
            continue;
        };
        let loser = match &best {
            Some((b, _)) if b.misfit <= first.misfit => first,
            _ => match best.replace((first, start)) {
                Some((old, _)) => old,
                None => continue,
            },
        };
        others.extend(loser.runs.into_iter().map(|mut r| {
            r.stage = format!("one curve, other start: {}", r.stage);
            r
        }));
    }
    let Some((first, start)) = best else {
        return Ok(None);
    };
    let candidates = first.terms.candidates.clone();
    // A joint fit that lands on a material no Prony series holds in double
    // precision (E1/E0 beyond 1e16: E0 = E1 − ΣH rounds to zero) is a
    // route that failed, like a one-curve fit that fails: the caller's
    // other route answers.
    let mut joint = match joint_from_material(data, params, first, start) {
        Ok(joint) => joint,
        Err(FitError::Model(_)) => return Ok(None),
        Err(e) => return Err(e),
    };
    joint.fit.runs = others.into_iter().chain(joint.fit.runs).collect();
    Ok(Some((joint, candidates)))
}

/// log10 a_T of `grid`'s shift at `temps` (0 where it has none).
fn log_shifts(grid: &GridOutcome, temps: &[f64]) -> Vec<f64> {
    let shift = grid.fit.shift.as_ref();
    temps
        .iter()
        .map(|&t| shift.and_then(|s| s.log_shift_at(t)).unwrap_or(0.0))
        .collect()
}

/// The law chosen where the WLF fit (`wlf`) does not describe the data:
/// the free shifts first, with a λ of their own ([`own_lambda`], from the
/// model-free overlap or WLF's shifts, `free_set` and `wlf`); then WLF and
/// Arrhenius at that λ, on that grid, from the free fit's material and
/// their constants fitted to its shifts, each tested against it; the
/// chosen law's fit is the one at the free shifts' λ (a law the test
/// accepts describes the data as well as the free shifts, so their λ
/// suits it).
///
/// Why: the WLF fit's λ was chosen for shifts the data reject (the
/// discrepancy rule walks to the path's floor when no λ brings χ² to N),
/// and free shifts fitted there crawled: on the broad-spectrum replica of
/// tests/broad_spectrum.rs 340 evaluations, on the real-curve set of issue
/// 46 4,218 Levenberg–Marquardt iterations. With λ of their own they take
/// tens.
fn laws_at_free_lambda(
    data: &Measurements,
    params: &ValidFitParams,
    (mut wlf, wlf_candidates): Refit,
    free_set: ShiftStart,
    wlf_set: ShiftStart,
) -> Result<ChosenLaw, FitError> {
    let temps = free_set.param.temperatures().to_vec();
    let n = data.len();
    let free_params = with_kind(params, ShiftKind::Free);
    let from_wlf = free_set.with_theta(
        data,
        free_set
            .param
            .theta_of_log_shifts(&log_shifts(&wlf, &temps)),
    );
    let starts = [free_set.clone(), from_wlf.clone()];
    let (free, candidates) = match own_lambda(data, &free_params, &starts)? {
        Some(refit) => refit,
        None => (
            at_lambda_of(
                data,
                &free_params,
                &wlf.fit.model,
                &wlf.fit.lambda,
                &from_wlf,
            )?,
            wlf_candidates,
        ),
    };
    let free_fit = law_fit("free", temps.len() - 1, &free);
    let free_shifts = log_shifts(&free, &temps);
    let law_at_free = |kind: ShiftKind, set: &ShiftStart| -> Result<GridOutcome, FitError> {
        let start = set.with_theta(data, set.param.theta_of_log_shifts(&free_shifts));
        at_lambda_of(
            data,
            &with_kind(params, kind),
            &free.fit.model,
            &free.fit.lambda,
            &start,
        )
    };
    let wlf_refit = law_at_free(ShiftKind::Wlf, &wlf_set)?;
    let wlf_test = LawCandidate::tested(&law_fit("wlf", 2, &wlf_refit), &free_fit, n);
    let arrhenius_set = start_of(data, &with_kind(params, ShiftKind::Arrhenius))?;
    let mut laws = vec![("wlf", wlf_refit, wlf_test)];
    if laws[0].2.rejected != Some(false) {
        let arrhenius = law_at_free(ShiftKind::Arrhenius, &arrhenius_set)?;
        let test = LawCandidate::tested(&law_fit("arrhenius", 1, &arrhenius), &free_fit, n);
        laws.push(("arrhenius", arrhenius, test));
    }
    let choice = ShiftChoice::first_accepted(
        laws.iter().map(|(_, _, t)| t.clone()).collect(),
        LawCandidate::free(&free_fit),
    );
    let mut grid = match laws.iter().find(|(m, _, _)| *m == choice.model) {
        Some((_, law, _)) => law.clone(),
        None => free.clone(),
    };
    // Every run, in the order made: WLF's, the free shifts', the laws'
    // at the free shifts' λ.
    let chosen = std::mem::replace(&mut grid.fit.runs, std::mem::take(&mut wlf.fit.runs));
    if choice.model != "free" {
        absorb_runs(&mut grid, &free, "free");
    }
    for (model, law, _) in &laws {
        if *model != choice.model {
            absorb_runs(&mut grid, law, model);
        }
    }
    grid.fit.runs.extend(chosen);
    Ok(ChosenLaw {
        grid,
        candidates,
        set: free_set,
        choice,
    })
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
    let refit_from = set.with_theta(data, fitted.fit.shift_theta.clone());
    let (mut grid, candidates) =
        own_lambda(data, kind_params, &[refit_from])?.unwrap_or_else(|| {
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
