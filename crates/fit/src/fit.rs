//! The fit driver: τ grid, starts, λ choice, solver runs, analysis.
//!
//! 1. The τ grid of [`crate::tau_grid`] for the data's speeds (for
//!    `terms = "auto"`: 1, 2 and 3 per decade, chosen by AICc).
//! 2. A neutral start: a flat spectrum with E1/E0 = 1000 at the anchored
//!    (or starting, or 1 MPa) scale.
//! 3. λ: fixed, or the decreasing path of [`crate::regularization`] with
//!    warm starts, then refinement.
//! 4. At the chosen λ, further starts are run: four spectra concentrated in
//!    a bump at different places of the probed band, and seeded
//!    perturbations of the neutral start (N(0, 1) in each log-parameter);
//!    the best V wins.
//! 5. Curvature, window, determined terms and bands at the optimum.
//!
//! Results are deterministic for a given seed: the solvers are
//! deterministic and the perturbations come from ChaCha8 seeded with it.

use std::cell::Cell;
use std::time::Instant;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

use rollfit_model::ViscoelasticModulus;

use crate::analysis::{
    DETERMINED_RELATIVE_SIGMA, add_bias, curvature, determined_stretch, modulus_point,
    probed_window,
};
use crate::condense::condense;
use crate::data::Measurements;
use crate::error::FitError;
use crate::parametrization::Parametrization;
use crate::params::{Lambda, ModulusAnchor, TermRule, ValidFitParams};
use crate::problem::Problem;
use crate::quality::assess;
use crate::regularization::{LambdaRule, REFINEMENTS, Trial, path};
use crate::report::{
    AnchorRecord, FitReport, LambdaRecord, ModelRecord, RunRecord, TermsRecord, Window,
};
use crate::sanity;
use crate::solvers::{SolverRun, Tolerance, default_budget, run};
use crate::tau_grid::{SOFTEST_MODULUS, probed_band, relaxation_times};
use crate::temperature_set::{
    ShiftStart, cross_check, material_first, temperature_set, wlf_before_free,
};

/// The forward model's relative tolerance on the λ path, in the start
/// probes and in the restarts: those runs only locate λ and a basin, and a
/// 1e-4 error in μ is far below any friction rig's scatter; the chosen λ is
/// solved again at the user's tolerance.
const PATH_MODEL_TOLERANCE: f64 = 1e-4;
/// The relative margin by which a restart, run at the path's tolerances,
/// must beat the chosen fit to replace it (the looser model's error in V is
/// about 1e-4 relative).
const RESTART_MARGIN: f64 = 1e-3;
/// E1/E0 of the neutral start.
const START_RATIO: f64 = 1000.0;
/// Static modulus of the neutral start without anchor or start material, Pa.
const START_MODULUS: f64 = 1e6;
/// Points per decade of the reported master curve.
const CURVE_DENSITY: f64 = 10.0;

/// Fits `data` under `params`.
pub fn fit(rows: &Measurements, params: &ValidFitParams) -> Result<FitReport, FitError> {
    let clock = Instant::now();
    let condensed = condense(rows)?;
    let data = condensed.as_ref().map_or(rows, |c| &c.data);
    let set = temperature_set(data, params)?;
    let range = set.as_ref().map_or_else(|| data.speed_range(), |s| s.range);
    let set = set.as_ref();
    let via_wlf = set.and_then(|s| wlf_before_free(data, params, s));
    let first = match (&via_wlf, set) {
        (None, Some(s)) => material_first(data, params, s),
        _ => None,
    };
    let (mut report, candidates) = match (&params.terms, via_wlf, first) {
        (_, Some((wlf, start)), _) => {
            let candidates = wlf.terms.candidates.clone();
            (free_from_wlf(data, params, wlf, &start)?, candidates)
        }
        (_, None, Some(first)) => {
            let candidates = first.terms.candidates.clone();
            let start = set.ok_or_else(|| FitError::setting("shift", "no temperature set"))?;
            (joint_from_material(data, params, first, start)?, candidates)
        }
        (TermRule::Auto, None, None) => {
            let mut best: Option<(f64, FitReport)> = None;
            let mut candidates = Vec::new();
            let mut runs = Vec::new();
            for density in [1.0, 2.0, 3.0] {
                let tau = grid(range, params, &TermRule::PerDecade(density));
                let r = match fit_on_grid(data, params, tau, None, set) {
                    Ok(r) => r,
                    Err(FitError::InsufficientData(_)) => continue,
                    Err(e) => return Err(e),
                };
                let aicc = aicc(data.len(), r.misfit, r.effective_parameters);
                candidates.push([density, aicc]);
                runs.extend(r.runs.iter().cloned());
                if best.as_ref().is_none_or(|(a, _)| aicc < *a) {
                    best = Some((aicc, r));
                }
            }
            let (_, mut r) = best.ok_or_else(|| {
                FitError::InsufficientData(
                    "too few data points for even one relaxation time per decade".into(),
                )
            })?;
            r.runs = runs;
            (r, candidates)
        }
        (rule, None, None) => (
            fit_on_grid(data, params, grid(range, params, rule), None, set)?,
            Vec::new(),
        ),
    };
    let count = report.model.tau.len();
    let span = (report.model.tau[count - 1] / report.model.tau[0]).log10();
    report.terms = TermsRecord {
        count,
        per_decade: if span > 0.0 {
            (count - 1) as f64 / span
        } else {
            0.0
        },
        rule: match &params.terms {
            TermRule::PerDecade(_) => "per_decade",
            TermRule::Count(_) => "count",
            TermRule::Explicit(_) => "explicit",
            TermRule::Auto => "aicc",
        }
        .into(),
        candidates,
    };
    if let Some(set) = set {
        report.warnings.extend(set.notes.iter().cloned());
        if params.shift.cross_check {
            match cross_check(data, params, &report, set) {
                Ok(check) => {
                    if check.max_difference > 0.3 {
                        report.warnings.push(format!(
                            "the shifts of the joint fit and of the single-temperature fits \
                             differ by up to {:.2} decades (see shift_cross_check)",
                            check.max_difference
                        ));
                    }
                    report.shift_cross_check = Some(check);
                }
                Err(why) => report
                    .warnings
                    .push(format!("shift cross-check not made: {why}")),
            }
        }
    }
    report
        .warnings
        .extend(sanity_warnings(data, params, &report)?);
    if let Some(c) = condensed {
        report.mu_fit = fitted_friction(rows, params, &report)?;
        report.warnings.push(c.note());
        if c.record.scatter.is_some() {
            report.fit_quality.noise_source = "scatter within bins";
        }
        report.condensed = Some(c.record);
    }
    report.evaluations = report.runs.iter().map(|r| r.evaluations).sum();
    report.wall_time_s = clock.elapsed().as_secs_f64();
    if let Some(what) = report.first_non_finite() {
        return Err(FitError::NonFinite(what));
    }
    Ok(report)
}

/// Free shifts fitted at the λ and on the τ grid of a joint fit with WLF
/// shifts, from its material and shifts (see
/// [`crate::temperature_set::wlf_before_free`] for why); the report keeps
/// the WLF fit's λ rule, path and runs, and says what was done.
fn free_from_wlf(
    data: &Measurements,
    params: &ValidFitParams,
    wlf: FitReport,
    start: &ShiftStart,
) -> Result<FitReport, FitError> {
    let m = &wlf.model;
    let tau = m.tau.clone();
    let param = Parametrization::new(tau.clone(), params.anchor);
    let warm = param.theta_of(m.static_modulus, &m.strengths);
    let mut fixed = params.clone();
    fixed.lambda = Lambda::Fixed(wlf.lambda.value);
    fixed.terms = TermRule::Explicit(tau.clone());
    let mut report = fit_on_grid(data, &fixed, tau, Some(warm), Some(start))?;
    report.lambda = LambdaRecord {
        value: report.lambda.value,
        ..wlf.lambda
    };
    report.runs = wlf.runs.into_iter().chain(report.runs).collect();
    report.warnings.push(format!(
        "free shifts: λ = {:.3e} and the τ grid were chosen with WLF shifts, and the free \
         log10 a_T then fitted at that λ from the WLF solution (at the large λ where the λ path \
         begins, free shifts slide along a power-law curve undetermined)",
        report.lambda.value
    ));
    Ok(report)
}

/// The λ path: [`path`], or from `params.path_top` down.
fn lambda_path(params: &ValidFitParams) -> Vec<f64> {
    match params.path_top {
        Some(top) => std::iter::once(top)
            .chain(path().into_iter().filter(|&l| l < top * 0.999))
            .collect(),
        None => path(),
    }
}

/// The joint fit of a temperature set from a fit of its rows as one curve at
/// the start shift's reduced speeds ([`crate::temperature_set::material_first`]):
/// on that fit's τ grid, from its material and the start shift, with the λ
/// path beginning at its λ. The report keeps the joint fit's λ choice and
/// every run.
fn joint_from_material(
    data: &Measurements,
    params: &ValidFitParams,
    first: FitReport,
    start: &ShiftStart,
) -> Result<FitReport, FitError> {
    let m = &first.model;
    let tau = m.tau.clone();
    let param = Parametrization::new(tau.clone(), params.anchor);
    let warm = param.theta_of(m.static_modulus, &m.strengths);
    let mut joint = params.clone();
    if params.lambda == Lambda::Auto {
        joint.path_top = Some(first.lambda.value.max(path()[path().len() - 1]));
    }
    let mut report = fit_on_grid(data, &joint, tau, Some(warm), Some(start))?;
    report.runs = first
        .runs
        .into_iter()
        .map(|mut r| {
            r.stage = format!("one curve: {}", r.stage);
            r
        })
        .chain(report.runs)
        .collect();
    report.warnings.push(format!(
        "temperature set: the τ grid and the top of the λ path (λ = {:.3e}) come from a fit of \
         all rows as one curve at the starting shifts; the shift and the material were then \
         fitted together from there (at the large λ where the path otherwise begins the \
         spectrum is nearly a power law, along which the temperatures' curves slide \
         undetermined)",
        first.lambda.value
    ));
    Ok(report)
}

/// The fitted μ at every row of `data` (the rows of condensed data): the
/// fitted master curve at v·a_T.
fn fitted_friction(
    data: &Measurements,
    params: &ValidFitParams,
    report: &FitReport,
) -> Result<Vec<f64>, FitError> {
    let speeds = reduced_speeds(data, report);
    let m = &report.model;
    let prony = rollfit_model::Prony::new(m.glassy_modulus, m.strengths.clone(), m.tau.clone())?;
    let setup = &params.setup;
    let scene = rollfit_model::Scene::new(setup.geometry, setup.substrate, setup.contact, prony)?
        .with_tolerance(params.model_tolerance)?;
    Ok(scene.friction_sweep(&speeds)?)
}

/// The speeds of `data` on the master curve: v·a_T for a temperature set.
fn reduced_speeds(data: &Measurements, report: &FitReport) -> Vec<f64> {
    match (&report.shift, data.temperature()) {
        (Some(shift), Some(temps)) => data
            .speeds()
            .iter()
            .zip(temps)
            .map(|(v, t)| v * 10f64.powf(shift.log_shift_at(*t).unwrap_or(0.0)))
            .collect(),
        _ => data.speeds().to_vec(),
    }
}

/// The sanity checks of [`crate::sanity`] on the data and the fitted
/// material, at the reduced speeds (v·a_T) for a temperature set.
fn sanity_warnings(
    data: &Measurements,
    params: &ValidFitParams,
    report: &FitReport,
) -> Result<Vec<String>, FitError> {
    let setup = &params.setup;
    let speeds = reduced_speeds(data, report);
    let m = &report.model;
    let prony = rollfit_model::Prony::new(m.glassy_modulus, m.strengths.clone(), m.tau.clone())?;
    let mut out = sanity::input_warnings(setup, data.speeds(), Some(data.friction()));
    out.extend(sanity::material_warnings(
        setup,
        &speeds,
        &|omega| prony.modulus(omega),
        m.static_modulus,
        m.glassy_modulus,
        true,
    ));
    Ok(out.into_iter().map(|w| w.message).collect())
}

/// Corrected Akaike criterion with k effective parameters.
fn aicc(n: usize, misfit: f64, k: f64) -> f64 {
    let n = n as f64;
    let k = k + 1.0; // the noise level
    n * (misfit / n).ln() + 2.0 * k + 2.0 * k * (k + 1.0) / (n - k - 1.0).max(0.5)
}

fn grid(range: (f64, f64), params: &ValidFitParams, rule: &TermRule) -> Vec<f64> {
    let soft = match (params.anchor, &params.start) {
        (Some(a), _) if a.omega == 0.0 => a.modulus,
        (_, Some(s)) => s.static_modulus,
        _ => SOFTEST_MODULUS,
    };
    let band = probed_band(&params.setup, range, soft, params.e1_max);
    relaxation_times(band, rule)
}

/// The neutral start θ₀.
fn neutral_start(param: &Parametrization, params: &ValidFitParams) -> Vec<f64> {
    let e0 = match (params.anchor, &params.start) {
        (Some(a), _) if a.omega == 0.0 => a.modulus,
        (_, Some(s)) => s.static_modulus,
        _ => START_MODULUS,
    };
    let ratio = match &params.start {
        Some(s) => s.glassy_modulus / s.static_modulus,
        None => START_RATIO.min(0.5 * params.e1_max / e0).max(2.0),
    };
    let n = param.terms();
    let h = vec![e0 * (ratio - 1.0) / n as f64; n];
    param.theta_of(e0, &h)
}

/// An exploratory start may use 1/EXPLORATION_SHARE of a run's budget: it is
/// a probe, and a winner that has not converged is continued with the full
/// budget. (A quarter let a random start on a five-temperature set spend
/// two seconds reaching the minimum the path had already found.)
const EXPLORATION_SHARE: usize = 20;

/// An exploratory start whose best V is still above ABANDON_FACTOR times the
/// incumbent's after ABANDON_AFTER·(n + 1) evaluations (n free parameters:
/// that many Jacobians' worth) is abandoned. On the bundled rubber and the
/// temperature sets, starts that end up winning or tying are within a
/// factor of two by then; the others end in minima ~300 times worse.
const ABANDON_AFTER: usize = 1;
const ABANDON_FACTOR: f64 = 3.0;

/// Centres of the bump starts, as fractions of the probed band in log ω.
const BUMP_CENTRES: [f64; 4] = [0.2, 0.4, 0.6, 0.8];

/// Starts whose spectrum is concentrated in a one-decade Gaussian bump in
/// log τ at [`BUMP_CENTRES`] of the probed band, with the neutral start's
/// E0 and E1. A flat start can settle where the terms a narrow truth needs
/// have died (with H = e^θ a small term's gradient vanishes); a three-term
/// Prony truth is fitted to χ²/N = 2600 from the flat start alone and to
/// 1.6 with these.
fn bump_starts(
    param: &Parametrization,
    params: &ValidFitParams,
    range: (f64, f64),
    neutral: &[f64],
) -> Vec<Vec<f64>> {
    let mapped = param.map(neutral);
    let e0 = mapped.static_modulus;
    let total = mapped.strengths.iter().sum::<f64>();
    let band = probed_band(&params.setup, range, e0, params.e1_max);
    let (lo, hi) = (band.0.log10(), band.1.log10());
    BUMP_CENTRES
        .iter()
        .map(|q| {
            let centre = lo + q * (hi - lo);
            let weights: Vec<f64> = param
                .tau()
                .iter()
                .map(|t| {
                    let x = (1.0 / t).log10() - centre;
                    // Floor: every term stays alive (ln H finite).
                    (-0.5 * x * x).exp().max(1e-9)
                })
                .collect();
            let sum: f64 = weights.iter().sum();
            let h: Vec<f64> = weights.iter().map(|w| total * w / sum).collect();
            param.theta_of(e0, &h)
        })
        .collect()
}

fn record(stage: &str, lambda: f64, r: &SolverRun) -> RunRecord {
    RunRecord {
        stage: stage.into(),
        method: r.method.name(),
        lambda,
        objective: r.objective,
        iterations: r.iterations,
        evaluations: r.evaluations,
        wall_time_s: r.wall_time_s,
        converged: r.stop.converged(),
        stop_reason: r.stop.describe(),
        history: improvements(&r.history),
    }
}

/// The points of a run's (evaluation, best V) record where V improved: the
/// whole convergence curve as a staircase, without the flat stretches that
/// would make fit.json grow with the budget.
fn improvements(history: &[(usize, f64)]) -> Vec<[f64; 2]> {
    let mut points: Vec<[f64; 2]> = Vec::new();
    for &(evaluation, best) in history {
        if points.last().is_none_or(|last| best < last[1]) {
            points.push([evaluation as f64, best]);
        }
    }
    if let (Some(&(evaluation, best)), Some(last)) = (history.last(), points.last())
        && last[0] < evaluation as f64
    {
        points.push([evaluation as f64, best]);
    }
    points
}

/// The fit on one τ grid, from `warm` (a material θ of this grid's
/// parametrisation) instead of the neutral start when given; for a
/// temperature set `set` holds the shift and its starting θ_s.
fn fit_on_grid(
    data: &Measurements,
    params: &ValidFitParams,
    tau: Vec<f64>,
    warm: Option<Vec<f64>>,
    set: Option<&ShiftStart>,
) -> Result<FitReport, FitError> {
    let param = Parametrization::new(tau, params.anchor);
    let free = param.free_count() + set.map_or(0, |s| s.param.count());
    let mut problem = Problem {
        setup: &params.setup,
        data,
        scales: data.residual_scales(),
        param,
        shift: set.map(|s| s.param.clone()),
        lambda: 0.0,
        e1_max: params.e1_max,
        tolerance: params.model_tolerance,
        evaluations: Default::default(),
        budget: Default::default(),
        best: Default::default(),
        history: Default::default(),
        abandon_above: Default::default(),
        abandoned: Default::default(),
    };
    let method = params.method;
    let budget = params
        .max_evaluations
        .unwrap_or_else(|| default_budget(method, free));
    let start_material = warm.unwrap_or_else(|| neutral_start(&problem.param, params));
    let with_shift = |material: Vec<f64>| -> Vec<f64> {
        match set {
            Some(s) => material
                .into_iter()
                .chain(s.theta.iter().copied())
                .collect(),
            None => material,
        }
    };
    let start = with_shift(start_material.clone());
    let range = set.map_or_else(|| data.speed_range(), |s| s.range);
    let sigma_known = data.sigma().is_some();
    let mut runs = Vec::new();
    let mut path_record = Vec::new();
    let mut criterion_record = Vec::new();

    let tolerance = Cell::new(Tolerance::Final);
    // Fit at one λ from θ₀; returns the trial and the run.
    let solve_within = |problem: &mut Problem<'_>,
                        lambda: f64,
                        from: &[f64],
                        stage: &str,
                        runs: &mut Vec<RunRecord>,
                        budget: usize|
     -> Result<(Trial, SolverRun), FitError> {
        problem.lambda = lambda;
        problem.tolerance = match tolerance.get() {
            Tolerance::Path => params.model_tolerance.max(PATH_MODEL_TOLERANCE),
            Tolerance::Final => params.model_tolerance,
        };
        let r = run(method, problem, from, budget, tolerance.get());
        runs.push(record(stage, lambda, &r));
        problem.reset(usize::MAX);
        let e = problem.evaluate(&r.theta, true)?;
        let jac = e.jacobian.as_ref().ok_or_else(|| {
            FitError::InsufficientData("the forward model returned no Jacobian".into())
        })?;
        let c = curvature(jac, data.len(), e.misfit, sigma_known);
        let bound = e.residuals[e.residuals.len() - 1];
        Ok((
            Trial {
                lambda,
                theta: r.theta.clone(),
                misfit: e.misfit,
                effective_parameters: c.effective_parameters,
                penalised: e.objective() - bound * bound,
                log_det: c.log_det,
                penalty_rank: problem.param.terms().saturating_sub(2),
                free: r.theta.len(),
            },
            r,
        ))
    };

    let solve = |problem: &mut Problem<'_>,
                 lambda: f64,
                 from: &[f64],
                 stage: &str,
                 runs: &mut Vec<RunRecord>| {
        solve_within(problem, lambda, from, stage, runs, budget)
    };

    // The starting spectrum: the neutral start and the bumps, each probed
    // briefly at the first λ to be fitted; the best begins. Warm starts
    // would otherwise carry a poor local minimum down the whole λ path (a
    // narrow rubber's flat start stalled at a misfit 100 times the bumps'
    // at every λ).
    let first_lambda = match params.lambda {
        Lambda::Fixed(lambda) => lambda,
        Lambda::Auto => lambda_path(params)[0],
    };
    let mut from = start.clone();
    // Unanchored fits keep the neutral start: the scale profile that bounds
    // their bands walks out from the fit, and from a probed start it stalled
    // (on the bundled rubber, seed 1, the band then covered none of the
    // window against 64 % from the neutral start).
    let probed = params.starts > 1 && params.anchor.is_some();
    if probed {
        tolerance.set(Tolerance::Path);
        let mut best: Option<(f64, Vec<f64>)> = None;
        let candidates = std::iter::once(start.clone()).chain(
            bump_starts(&problem.param, params, range, &start_material)
                .into_iter()
                .map(&with_shift),
        );
        for (k, candidate) in candidates.enumerate() {
            let stage = if k == 0 {
                "start probe: neutral".to_string()
            } else {
                format!("start probe: bump {k}")
            };
            let (_, r) = solve_within(
                &mut problem,
                first_lambda,
                &candidate,
                &stage,
                &mut runs,
                PROBE_JACOBIANS * (free + 1),
            )?;
            if best.as_ref().is_none_or(|b| r.objective < b.0) {
                best = Some((r.objective, r.theta));
            }
        }
        if let Some((_, theta)) = best {
            from = theta;
        }
    }

    let (rule, mut chosen, mut chosen_run) = match params.lambda {
        Lambda::Fixed(lambda) => {
            tolerance.set(Tolerance::Final);
            let (t, r) = solve(&mut problem, lambda, &from, "fixed lambda", &mut runs)?;
            (LambdaRule::Fixed, t, r)
        }
        Lambda::Auto => {
            let rule = if sigma_known {
                LambdaRule::Discrepancy
            } else {
                LambdaRule::MarginalLikelihood
            };
            let n = data.len();
            let mut trials: Vec<(Trial, SolverRun)> = Vec::new();
            // The path is walked at the looser tolerance: its points only
            // locate λ; the chosen one is polished below.
            tolerance.set(Tolerance::Path);
            for lambda in lambda_path(params) {
                let (t, r) = solve(&mut problem, lambda, &from, "lambda path", &mut runs)?;
                from = t.theta.clone();
                path_record.push([lambda, t.misfit, t.effective_parameters]);
                let stop_now = match rule {
                    LambdaRule::Discrepancy => t.misfit <= discrepancy_target(n),
                    _ => {
                        // Past the minimum by two decades of rising criterion.
                        let k = trials.len();
                        k >= 2
                            && t.criterion(rule, n) > trials[k - 1].0.criterion(rule, n)
                            && trials[k - 1].0.criterion(rule, n)
                                > trials[k - 2].0.criterion(rule, n)
                    }
                };
                if rule != LambdaRule::Discrepancy {
                    criterion_record.push([lambda, t.criterion(rule, n)]);
                }
                trials.push((t, r));
                if stop_now {
                    break;
                }
            }
            let (lambda, from) = match rule {
                LambdaRule::Discrepancy => {
                    let (t, _) = refine(rule, n, trials, &mut |lambda, from: &[f64]| {
                        let (t, r) = solve(&mut problem, lambda, from, "refine lambda", &mut runs)?;
                        path_record.push([lambda, t.misfit, t.effective_parameters]);
                        Ok((t, r))
                    })?;
                    (t.lambda, t.theta)
                }
                _ => smoothest_acceptable(rule, n, &trials),
            };
            tolerance.set(Tolerance::Final);
            let (t, r) = solve(&mut problem, lambda, &from, "chosen lambda", &mut runs)?;
            path_record.push([lambda, t.misfit, t.effective_parameters]);
            (rule, t, r)
        }
    };

    // At the chosen λ, the bumps again and seeded perturbations of the
    // neutral start, each abandoned early when hopeless: the path's warm
    // starts can still drift into a poor minimum on the way down (an
    // unanchored fit on 41 speeds ended at E1 = 16 MPa, tan δ 50 % off,
    // where a bump restart finds the truth's basin).
    if params.starts > 1 {
        let mut rng = ChaCha8Rng::seed_from_u64(params.seed);
        let normal = Normal::new(0.0, 1.0).map_err(|e| FitError::setting("seed", e.to_string()))?;
        // The bumps again where they were not probed at the path's start.
        let bumps = if probed {
            Vec::new()
        } else {
            bump_starts(&problem.param, params, range, &start_material)
        };
        let mut others: Vec<(String, Vec<f64>)> = bumps
            .into_iter()
            .enumerate()
            .map(|(k, b)| (format!("bump start {}", k + 1), with_shift(b)))
            .collect();
        for k in 1..params.starts {
            // The material only: the starting shift is already close.
            others.push((
                format!("random start {k}"),
                with_shift(
                    start_material
                        .iter()
                        .map(|t| t + normal.sample(&mut rng))
                        .collect(),
                ),
            ));
        }
        // The restarts run at the path's tolerances; one that beats the
        // chosen fit by more than the looser model's error is solved again
        // at the final tolerance before it replaces it.
        tolerance.set(Tolerance::Path);
        let mut winner: Option<(Trial, SolverRun)> = None;
        for (stage, from) in &others {
            problem.abandon_above.set(Some((
                ABANDON_AFTER * (free + 1),
                ABANDON_FACTOR * chosen_run.objective,
            )));
            let probe = solve_within(
                &mut problem,
                chosen.lambda,
                from,
                stage,
                &mut runs,
                (budget / EXPLORATION_SHARE).max(1),
            );
            problem.abandon_above.set(None);
            let (t, r) = probe?;
            let best = winner
                .as_ref()
                .map_or(chosen_run.objective, |(_, w)| w.objective);
            if r.objective < best * (1.0 - RESTART_MARGIN) {
                winner = Some((t, r));
            }
        }
        tolerance.set(Tolerance::Final);
        let (from, stage) = match winner {
            Some((t, _)) => (Some(t.theta), "polish best start"),
            None if !chosen_run.stop.converged() => {
                (Some(chosen.theta.clone()), "continue best start")
            }
            None => (None, ""),
        };
        if let Some(from) = from {
            let (t, r) = solve(&mut problem, chosen.lambda, &from, stage, &mut runs)?;
            if r.objective <= chosen_run.objective || !chosen_run.stop.converged() {
                chosen = t;
                chosen_run = r;
            }
        }
    }

    // The smoothing bias of the bands: the fit at a tenth of λ (analysis).
    let less_smoothed = if params.bands && chosen.lambda > 0.0 {
        let from = chosen.theta.clone();
        let (t, _) = solve(
            &mut problem,
            chosen.lambda / 10.0,
            &from,
            "band: λ/10",
            &mut runs,
        )?;
        Some(t.theta)
    } else {
        None
    };

    let mut report = analyse(
        data,
        params,
        &mut problem,
        chosen,
        chosen_run,
        rule,
        path_record,
        runs,
        less_smoothed.as_deref(),
        criterion_record,
    )?;
    if params.anchor.is_none() {
        profile_scale(data, params, &mut report, set)?;
    }
    if params.bands {
        restrict_to_determined(&mut report);
    }
    Ok(report)
}

/// Cuts the window and the curve to the stretch the data determine
/// ([`determined_stretch`]); when tan δ is determined to
/// [`DETERMINED_RELATIVE_SIGMA`] nowhere, keeps the probed window and warns.
fn restrict_to_determined(report: &mut FitReport) {
    match determined_stretch(&report.curve) {
        Some((first, last)) if last > first => {
            report.curve.truncate(last + 1);
            report.curve.drain(..first);
            report.window = Window {
                omega_min: report.curve[0].omega,
                omega_max: report.curve[report.curve.len() - 1].omega,
            };
        }
        _ => report.warnings.push(format!(
            "the data determine tan δ to ±{:.0} % (1σ) at no frequency: the whole probed \
             window is reported, and its bands are wide",
            100.0 * DETERMINED_RELATIVE_SIGMA
        )),
    }
}

/// Scale factors of the profile along the weak direction, walked outward
/// from the fit in two chains (stiffer, softer).
const PROFILE_FACTORS: [&[f64]; 2] = [
    &[1.0 / 0.7, 2.0, 2.8, 4.0, 5.6, 8.0, 11.0],
    &[0.7, 0.5, 0.35, 0.2, 0.1],
];

/// Relaxations of λ tried at each point of the scale profile.
const PROFILE_RELAXATION: [f64; 4] = [1.0, 0.1, 0.01, 0.001];

/// Widens the bands of an unanchored fit by a profile along the modulus
/// scale, the direction rolling data determine worst.
///
/// The curvature band is local: where V is nearly flat along "stiffer with
/// a little more loss" but the optimum sits against E1_max or the penalty's
/// preference, it can be far too narrow. So the fit is repeated with |E*| at
/// the window's centre ω_c pinned to c·|E*_fit(ω_c)| for the factors
/// [`PROFILE_FACTORS`] (same τ grid and λ); every profile whose data misfit
/// lies within one noise unit of the fit's is as good a description of the
/// data, and the band is widened to enclose all of them (a
/// profile-likelihood interval on the scale; the misfit, not V, decides,
/// because the penalty would otherwise vote for its favourite scale).
///
/// Each pinned fit starts from its neighbour's shape (continuation): from
/// the neutral start alone a pinned fit far from the optimum can stall in a
/// poor local minimum and cut the profile short with a spurious wall.
///
/// # References
/// - D.J. Venzon, S.H. Moolgavkar, "A method for computing
///   profile-likelihood-based confidence intervals", Appl. Statist. 37
///   (1988) 87–94.
fn profile_scale(
    data: &Measurements,
    params: &ValidFitParams,
    report: &mut FitReport,
    set: Option<&ShiftStart>,
) -> Result<(), FitError> {
    let set = set.map(|s| s.with_theta(data, report.shift_theta.clone()));
    use rollfit_model::Prony;
    let omega_c = (report.window.omega_min * report.window.omega_max).sqrt();
    let m = &report.model;
    let fitted = Prony::new(m.glassy_modulus, m.strengths.clone(), m.tau.clone())?;
    let centre = fitted.modulus(omega_c).norm();
    let threshold = report.noise * report.noise;
    let best = report.misfit;
    let mut accepted = Vec::new();
    let mut profile = Vec::new();
    // The fit's own shape in the pinned parametrisation: H_k/E0.
    let own_shape: Vec<f64> = m
        .strengths
        .iter()
        .map(|h| (h / m.static_modulus).ln())
        .collect();
    for chain in PROFILE_FACTORS {
        let mut from = own_shape.clone();
        for &factor in chain {
            // The weakest smoothing among λ, λ/10, … λ/1000 that still
            // describes the data as well as the fit does (within one noise
            // unit): at the fit's λ alone the penalty, not the data, would
            // build the wall of the profile.
            let mut r = None;
            for relax in PROFILE_RELAXATION {
                let mut pinned = params.clone();
                pinned.anchor = Some(ModulusAnchor {
                    omega: omega_c,
                    modulus: factor * centre,
                    source: "profile",
                });
                pinned.lambda = Lambda::Fixed(report.lambda.value * relax);
                pinned.starts = 1;
                pinned.bands = false;
                pinned.terms = TermRule::Explicit(m.tau.clone());
                let trial = match fit_on_grid(
                    data,
                    &pinned,
                    m.tau.clone(),
                    Some(from.clone()),
                    set.as_ref(),
                ) {
                    Ok(t) => t,
                    // A pinned scale the model cannot reach ends the chain.
                    Err(FitError::Model(_)) => break,
                    Err(e) => return Err(e),
                };
                from = trial
                    .model
                    .strengths
                    .iter()
                    .map(|h| (h / trial.model.static_modulus).ln())
                    .collect();
                report
                    .runs
                    .extend(trial.runs.iter().cloned().map(|mut run| {
                        run.stage = format!("scale profile ×{factor:.2}: {}", run.stage);
                        run
                    }));
                let good = trial.misfit - best <= threshold;
                r = Some(trial);
                if good {
                    break;
                }
            }
            let Some(r) = r else { break };
            profile.push([factor, r.misfit, r.lambda.value]);
            let pm = &r.model;
            if r.misfit - best <= threshold {
                accepted.push(Prony::new(
                    pm.glassy_modulus,
                    pm.strengths.clone(),
                    pm.tau.clone(),
                )?);
            }
        }
    }
    profile.sort_by(|a, b| a[0].total_cmp(&b[0]));
    for point in report.curve.iter_mut() {
        for p in &accepted {
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
    report.scale_profile = profile;
    Ok(())
}

/// The misfit the discrepancy principle aims at: χ² = N (Morozov). (The
/// variant N − t, t the effective parameters, was tried on the bundled
/// rubber: it picks λ a hundred times smaller and lets tan δ wiggle by
/// ±3 % without improving |E|.)
fn discrepancy_target(n: usize) -> f64 {
    n as f64
}

/// Jacobians' worth of evaluations (n + 1 each, n free parameters) a start
/// probe may spend: enough to tell a start that is stuck (a narrow rubber's
/// flat start: misfit 100 times the bumps') from one that is not.
const PROBE_JACOBIANS: usize = 1;

/// How much worse than the best (in −2 ln p, twice the log Bayes factor)
/// the chosen λ may be: the smoothest λ the data do not reject with strong
/// evidence (2 ln B < 6 on the scale of Kass and Raftery). On 15 speeds the
/// marginal likelihood's minimum is shallow toward small λ, and a noise
/// draw that happens to look smooth pulls it there: in one seed of ten the
/// fit then absorbed two thirds of the noise, estimated it at a third of
/// its size and drew bands three times too narrow. Leaning to the smooth
/// side within the evidence's own resolution avoids that; the smoothing
/// bias it adds is in the bands (analysis).
///
/// # References
/// - R.E. Kass, A.E. Raftery, "Bayes factors", J. Amer. Statist. Assoc.
///   90 (1995) 773–795.
const EVIDENCE_TOLERANCE: f64 = 6.0;

/// The largest λ whose criterion is within [`EVIDENCE_TOLERANCE`] of the
/// best path point (interpolated linearly in ln λ between the bracketing
/// path points), with the θ of the nearest path point at or below it to
/// start from.
fn smoothest_acceptable(
    rule: LambdaRule,
    n: usize,
    trials: &[(Trial, SolverRun)],
) -> (f64, Vec<f64>) {
    let score = |k: usize| trials[k].0.criterion(rule, n);
    let best = (0..trials.len())
        .min_by(|&a, &b| score(a).total_cmp(&score(b)))
        .unwrap_or(0);
    let limit = score(best) + EVIDENCE_TOLERANCE;
    // The path runs from large to small λ: walk back from the best point to
    // the first (largest-λ) point still within the limit.
    let mut k = best;
    while k > 0 && score(k - 1) <= limit {
        k -= 1;
    }
    let from = trials[k].0.theta.clone();
    if k == 0 {
        return (trials[0].0.lambda, from);
    }
    // Between trials[k − 1] (above the limit) and trials[k] (within).
    let (x0, x1) = (trials[k - 1].0.lambda.ln(), trials[k].0.lambda.ln());
    let (y0, y1) = (score(k - 1), score(k));
    let fraction = ((limit - y1) / (y0 - y1)).clamp(0.0, 1.0);
    let x = x1 + fraction * (x0 - x1);
    (
        if x.is_finite() {
            x.exp()
        } else {
            trials[k].0.lambda
        },
        from,
    )
}

type Solve<'s> = dyn FnMut(f64, &[f64]) -> Result<(Trial, SolverRun), FitError> + 's;

/// Refines λ between path points.
fn refine(
    rule: LambdaRule,
    n: usize,
    trials: Vec<(Trial, SolverRun)>,
    solve: &mut Solve<'_>,
) -> Result<(Trial, SolverRun), FitError> {
    let mut trials = trials;
    match rule {
        LambdaRule::Discrepancy => {
            let last = trials.len() - 1;
            if trials[last].0.misfit > discrepancy_target(n) || last == 0 {
                // Never reached χ² = N (or already at the largest λ): keep the
                // path's best end.
                let best = trials
                    .into_iter()
                    .min_by(|a, b| a.0.misfit.total_cmp(&b.0.misfit))
                    .ok_or_else(|| FitError::InsufficientData("empty λ path".into()))?;
                return Ok(best);
            }
            // Bisection in ln λ between trials[last − 1] (χ² > N) and
            // trials[last] (χ² ≤ N); keep the largest λ with χ² ≤ N.
            let mut above = trials[last - 1].clone();
            let mut below = trials.swap_remove(last);
            for _ in 0..REFINEMENTS {
                let lambda = (above.0.lambda * below.0.lambda).sqrt();
                let from = below.0.theta.clone();
                let t = solve(lambda, &from)?;
                if t.0.misfit <= discrepancy_target(n) {
                    below = t;
                } else {
                    above = t;
                }
            }
            Ok(below)
        }
        LambdaRule::Gcv | LambdaRule::MarginalLikelihood | LambdaRule::Fixed => {
            let score = |t: &(Trial, SolverRun)| t.0.criterion(rule, n);
            let best = trials
                .iter()
                .enumerate()
                .min_by(|a, b| score(a.1).total_cmp(&score(b.1)))
                .map(|(i, _)| i)
                .unwrap_or(0);
            // Golden-section search in ln λ over the neighbouring path points.
            let lo = trials[best.saturating_sub(1)].0.lambda.ln();
            let hi = trials[(best + 1).min(trials.len() - 1)].0.lambda.ln();
            let mut incumbent = trials.swap_remove(best);
            if lo == hi {
                return Ok(incumbent);
            }
            let (mut a, mut b) = (lo.min(hi), lo.max(hi));
            let golden = 0.5 * (5f64.sqrt() - 1.0);
            for _ in 0..REFINEMENTS {
                let c = b - golden * (b - a);
                let d = a + golden * (b - a);
                let from = incumbent.0.theta.clone();
                let tc = solve(c.exp(), &from)?;
                let td = solve(d.exp(), &from)?;
                if score(&tc) < score(&td) {
                    b = d;
                    if score(&tc) < score(&incumbent) {
                        incumbent = tc;
                    }
                } else {
                    a = c;
                    if score(&td) < score(&incumbent) {
                        incumbent = td;
                    }
                }
            }
            Ok(incumbent)
        }
    }
}

/// The data's row indices by temperature (one group without a `T`
/// column), each in order of speed: the order of the runs test.
fn speed_ordered_groups(data: &Measurements) -> Vec<Vec<usize>> {
    let mut groups: Vec<(f64, Vec<usize>)> = Vec::new();
    for i in 0..data.len() {
        let t = data.temperature().map_or(0.0, |t| t[i]);
        match groups.iter_mut().find(|(g, _)| *g == t) {
            Some((_, rows)) => rows.push(i),
            None => groups.push((t, vec![i])),
        }
    }
    let speeds = data.speeds();
    groups
        .into_iter()
        .map(|(_, mut rows)| {
            rows.sort_by(|&a, &b| speeds[a].total_cmp(&speeds[b]));
            rows
        })
        .collect()
}

/// Curvature, window, determined terms, bands and the report.
#[allow(clippy::too_many_arguments)]
fn analyse(
    data: &Measurements,
    params: &ValidFitParams,
    problem: &mut Problem<'_>,
    chosen: Trial,
    chosen_run: SolverRun,
    rule: LambdaRule,
    path_record: Vec<[f64; 3]>,
    runs: Vec<RunRecord>,
    less_smoothed: Option<&[f64]>,
    criterion: Vec<[f64; 2]>,
) -> Result<FitReport, FitError> {
    problem.lambda = chosen.lambda;
    problem.reset(usize::MAX);
    let e = problem.evaluate(&chosen.theta, true)?;
    let jac = e.jacobian.as_ref().ok_or_else(|| {
        FitError::InsufficientData("the forward model returned no Jacobian".into())
    })?;
    let sigma_known = data.sigma().is_some();
    let c = curvature(jac, data.len(), e.misfit, sigma_known);
    let param = &problem.param;
    let n_material = param.free_count();
    let mapped = param.map(&chosen.theta[..n_material]);
    let prony = param.prony(&mapped)?;
    let (omega_min, omega_max) =
        probed_window(&params.setup, &prony, problem.reduced_range(&chosen.theta));
    // The material's block of the covariance is its marginal covariance.
    let material_covariance = c
        .covariance
        .view((0, 0), (n_material, n_material))
        .into_owned();
    let n_shift = chosen.theta.len() - n_material;
    let shift_theta = chosen.theta[n_material..].to_vec();
    let shift = problem.shift.as_ref().map(|s| {
        let block = c
            .covariance
            .view((n_material, n_material), (n_shift, n_shift))
            .into_owned();
        s.record(&shift_theta, &block)
    });
    let first = param.first_strength();
    let determined: Vec<bool> = param
        .tau()
        .iter()
        .enumerate()
        .map(|(k, &tau)| {
            let omega = 1.0 / tau;
            let near = omega >= omega_min / 10.0 && omega <= omega_max * 10.0;
            near && c.sensitivity[first + k] >= c.noise_variance
        })
        .collect();
    let ln_strength_sigma = (0..param.terms())
        .map(|k| c.covariance[(first + k, first + k)].max(0.0).sqrt())
        .collect();
    let decades = (omega_max / omega_min).log10();
    let points = (decades * CURVE_DENSITY).ceil().max(1.0) as usize + 1;
    let other = match less_smoothed {
        Some(theta) => Some(param.prony(&param.map(&theta[..n_material]))?),
        None => None,
    };
    let curve = (0..points)
        .map(|i| {
            let omega = omega_min * (omega_max / omega_min).powf(i as f64 / (points - 1) as f64);
            let mut point = modulus_point(param, &mapped, &material_covariance, omega);
            if let Some(other) = &other {
                add_bias(&mut point, other.modulus(omega));
            }
            point
        })
        .collect();

    let mut warnings = Vec::new();
    if params.anchor.is_none() {
        warnings.push(
            "no scale anchor ([fit] E0, E_at or contact_radius): rolling friction fixes the \
             shape of tan δ(ω) far better than the level of |E|, so the modulus scale is weakly \
             determined; see the uncertainty band"
                .into(),
        );
    }
    if !chosen_run.stop.converged() {
        warnings.push(format!(
            "the final {} run did not converge: {}",
            chosen_run.method.name(),
            chosen_run.stop.describe()
        ));
    }
    if rule == LambdaRule::Discrepancy && e.misfit > data.len() as f64 * 1.5 {
        warnings.push(format!(
            "χ²/N = {:.2} stays above 1 at every λ: the model does not reach the noise floor \
             (underestimated σ, or physics the model lacks)",
            e.misfit / data.len() as f64
        ));
    }
    if mapped.glassy_modulus() > 0.999 * params.e1_max {
        warnings.push(format!(
            "the glassy modulus E1 sits at its bound E1_max = {:e} Pa",
            params.e1_max
        ));
    }
    let undetermined = determined.iter().filter(|d| !**d).count();
    if undetermined > 0 {
        warnings.push(format!(
            "{undetermined} of {} relaxation times are not determined by the data \
             (marked in model.determined); they only extend E* outside the window",
            determined.len()
        ));
    }
    let fit_quality = assess(
        &e.residuals.as_slice()[..data.len()],
        &speed_ordered_groups(data),
        c.effective_parameters,
        sigma_known,
        c.noise_variance.sqrt(),
    );
    warnings.extend(
        fit_quality
            .reasons
            .iter()
            .map(|r| format!("fit quality: {r}")),
    );
    let method = chosen_run.method;
    Ok(FitReport {
        model: ModelRecord {
            kind: "prony",
            glassy_modulus: mapped.glassy_modulus(),
            static_modulus: mapped.static_modulus,
            tau: param.tau().to_vec(),
            strengths: mapped.strengths.clone(),
            determined,
            ln_strength_sigma,
        },
        poisson: params.setup.substrate.poisson,
        window: Window {
            omega_min,
            omega_max,
        },
        probed_window: Window {
            omega_min,
            omega_max,
        },
        method: method.name(),
        objective: e.objective(),
        misfit: e.misfit,
        misfit_per_point: e.misfit / data.len() as f64,
        sigma_weights: sigma_known,
        iterations: chosen_run.iterations,
        evaluations: 0,
        converged: chosen_run.stop.converged(),
        stop_reason: chosen_run.stop.describe(),
        wall_time_s: 0.0,
        lambda: LambdaRecord {
            value: chosen.lambda,
            rule,
            path: path_record,
            criterion,
        },
        terms: TermsRecord {
            count: 0,
            per_decade: 0.0,
            rule: String::new(),
            candidates: Vec::new(),
        },
        anchor: params.anchor.map(|a| AnchorRecord {
            source: a.source,
            omega: a.omega,
            modulus: a.modulus,
        }),
        effective_parameters: c.effective_parameters,
        noise: c.noise_variance.sqrt(),
        fit_quality,
        seed: params.seed,
        warnings,
        runs,
        history: chosen_run
            .history
            .iter()
            .map(|&(k, v)| [k as f64, v])
            .collect(),
        curve,
        scale_profile: Vec::new(),
        shift,
        shift_cross_check: None,
        condensed: None,
        shift_theta,
        mu_fit: e.mu.clone(),
    })
}
