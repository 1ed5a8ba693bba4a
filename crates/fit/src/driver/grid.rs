//! The solver runs on one τ grid, from the first start to the analysed
//! optimum:
//!
//! 1. With an anchor and several starts, the neutral (or warm) start, the
//!    bump starts and the seeded perturbations race at the first λ: each
//!    runs [`RACE_EVALUATIONS`] evaluations, and the one with the lowest V
//!    then begins the path.
//! 2. λ: the fixed one, or the path walked down with warm starts at the
//!    path's looser tolerances and refined ([`super::lambda`]); the chosen
//!    λ is solved again at the user's tolerance.
//! 3. Without the race (an unanchored fit with several starts) or at a
//!    fixed λ, the bumps (unless raced) and the seeded perturbations are
//!    run at the chosen λ, each abandoned early when hopeless; one that
//!    beats the chosen fit clearly is polished and replaces it.
//! 4. With bands, the fit at λ/10 for the smoothing bias; then the
//!    analysis of the optimum ([`super::optimum`]).

use crate::analysis::curvature;
use crate::data::Measurements;
use crate::error::FitError;
use crate::joint::DmaBlock;
use crate::objective::Objective;
use crate::parametrization::Parametrization;
use crate::params::{FrictionFactor, Lambda, ValidFitParams};
use crate::quality::{RUNS_P_VALUE, runs_test};
use crate::regularization::{LambdaRule, Trial};
use crate::report::RunRecord;
use crate::solvers::counting::{Abandonment, Counted};
use crate::solvers::{SolverRun, Tolerance, default_budget, run};
use crate::temperature_set::ShiftStart;

use super::lambda::{
    Refinement, bisect_discrepancy, criterion_minimum, first_lambda, lambda_path, path_walked,
};
use super::linearised::Linearisation;
use super::optimum::{Chosen, Optimum, analyse};
use super::starts::{Starts, neutral_start};

/// The forward model's relative tolerance on the λ path, in the start
/// probes and in the restarts: those runs only locate λ and a basin, and a
/// 1e-4 error in μ is far below any friction rig's scatter; the chosen λ is
/// solved again at the user's tolerance.
const PATH_MODEL_TOLERANCE: f64 = 1e-4;
/// The relative margin by which a restart, run at the path's tolerances,
/// must beat the chosen fit to replace it (the looser model's error in V is
/// about 1e-4 relative).
const RESTART_MARGIN: f64 = 1e-3;

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

/// The longest step (in any log-parameter: a factor e in a strength) the
/// path's predictor takes from one path point toward the next.
const PREDICTOR_STEP: f64 = 1.0;

/// Evaluations each start of the race at the path's first λ runs before the
/// lowest V is taken. Starts run to convergence would spend about half a
/// fit's evaluations only to pick where the path begins (BENCHMARKS.md,
/// "The choice of λ"). Over 24 fits of the exploration study (tests/fit_cost.rs: broad
/// and narrow rubbers, ball and cylinder, 15 and 29–41 speeds, six seeds),
/// the start leading after six evaluations was one that also ended lowest
/// (or tied within 1e-7) in every fit where the starts differed: the narrow
/// rubbers, whose flat start ends 85–99.9 % above the best bump; on the
/// broad rubber all starts end in the same point.
const RACE_EVALUATIONS: usize = 6;

/// The fit on one τ grid, from `warm` (a material θ of this grid's
/// parametrisation) instead of the neutral start when given; for a
/// temperature set `set` holds the shift and its starting θ_s.
pub(super) fn solve_on_grid(
    data: &Measurements,
    params: &ValidFitParams,
    tau: Vec<f64>,
    warm: Option<Vec<f64>>,
    set: Option<&ShiftStart>,
) -> Result<Optimum, FitError> {
    let mut grid = GridSolver::new(data, params, tau, set)?;
    let material = warm.unwrap_or_else(|| neutral_start(&grid.objective.param, params));
    let range = set.map_or_else(|| data.speed_range(), |s| s.range);
    let starts = Starts::new(material, set, range);
    // Unanchored fits keep the neutral start: the scale profile that bounds
    // their bands walks out from the fit, and from a probed start it stalled
    // (on the bundled rubber, seed 1, the band then covered none of the
    // window against 64 % from the neutral start).
    let raced = params.starts > 1 && params.anchor.is_some();
    let from = if raced {
        grid.race_starts(&starts)?
    } else {
        starts.first()
    };
    let mut choice = match params.lambda {
        Lambda::Fixed(lambda) => grid.fixed_lambda(lambda, &from)?,
        Lambda::Auto => grid.auto_lambda(from)?,
    };
    // With λ by the data the race and the path's warm starts are the
    // exploration: restarts at the chosen λ never won in the exploration
    // study's fits. At a fixed λ nothing else explores that λ, and at
    // λ = 0 (ill-posed: terms die and their gradients vanish) the seeded
    // restarts still find lower minima than any raced start.
    let fixed = matches!(params.lambda, Lambda::Fixed(_));
    if params.starts > 1 && (!raced || fixed) {
        (choice.trial, choice.run) = grid.restart(&starts, raced, choice.trial, choice.run)?;
    }
    let less_smoothed = grid.less_smoothed(&choice.trial)?;
    grid.analyse(choice, less_smoothed)
}

/// The λ chosen on a grid and the fit there.
struct LambdaChoice {
    rule: LambdaRule,
    trial: Trial,
    run: SolverRun,
    /// (λ, criterion) along the path for the criterion rules.
    criterion: Vec<[f64; 2]>,
    /// The marginal likelihood's noise variance at its minimum.
    evidence_noise_variance: Option<f64>,
}

/// One solver run as the grid asks for it.
struct Leg<'s> {
    /// What the run is for, as the run records name it.
    stage: &'s str,
    /// Evaluations allowed.
    budget: usize,
    /// When the run is given up as hopeless.
    abandon: Option<Abandonment>,
}

/// The fits on one τ grid: the objective and what their runs share.
struct GridSolver<'a> {
    params: &'a ValidFitParams,
    objective: Objective<'a>,
    /// Free parameters: the material's and the shift's.
    free: usize,
    /// Evaluations allowed to a full run.
    budget: usize,
    /// How tightly the current phase's runs converge.
    tolerance: Tolerance,
    /// Every run so far.
    runs: Vec<RunRecord>,
    /// (λ, misfit, effective parameters) of every fit along the λ path.
    path: Vec<[f64; 3]>,
    /// The data's rows in the runs test's order (by temperature, by speed).
    groups: Vec<Vec<usize>>,
    /// The linearisation the λ refinement predicts from, kept while it
    /// predicts from the same fit.
    linearisation: Option<Linearisation>,
}

impl<'a> GridSolver<'a> {
    fn new(
        data: &'a Measurements,
        params: &'a ValidFitParams,
        tau: Vec<f64>,
        set: Option<&ShiftStart>,
    ) -> Result<Self, FitError> {
        let param = Parametrization::new(tau, params.anchor);
        let shift = set.map(|s| s.param.clone());
        let dma = match params.dma.as_deref() {
            Some(rows) => {
                let sigma = params.dma_sigma.ok_or(FitError::Internal(
                    "a joint fit reached its objective without the DMA moduli's σ",
                ))?;
                Some(DmaBlock::new(
                    rows,
                    shift.as_ref(),
                    sigma,
                    params.shift.vertical.as_ref(),
                )?)
            }
            None => None,
        };
        let friction_factor = dma.is_some() && params.friction_factor == FrictionFactor::Free;
        let objective = Objective {
            setup: &params.setup,
            data,
            scales: data.residual_scales(),
            param,
            shift,
            lambda: 0.0,
            e1_max: params.e1_max,
            tolerance: params.model_tolerance,
            // Only a temperature set's rows take b_T.
            vertical: set.and(params.shift.vertical.as_ref()),
            dma,
            friction_factor,
            noise_known: params.noise_known(data),
        };
        let free = objective.free_count();
        let groups = objective.runs_groups();
        let budget = params
            .max_evaluations
            .unwrap_or_else(|| default_budget(params.method, free));
        Ok(GridSolver {
            params,
            objective,
            free,
            budget,
            tolerance: Tolerance::Final,
            runs: Vec::new(),
            path: Vec::new(),
            groups,
            linearisation: None,
        })
    }

    /// The fit at `lambda` from `from` as `leg` asks: the trial at the run's
    /// best point (with its curvature statistics) and the run.
    fn solve_leg(
        &mut self,
        lambda: f64,
        from: &[f64],
        leg: Leg<'_>,
    ) -> Result<(Trial, SolverRun), FitError> {
        let objective = &mut self.objective;
        objective.lambda = lambda;
        objective.tolerance = match self.tolerance {
            Tolerance::Path => self.params.model_tolerance.max(PATH_MODEL_TOLERANCE),
            Tolerance::Final => self.params.model_tolerance,
        };
        self.params.cancel.check()?;
        let counted = Counted::new(objective, leg.budget).abandoning(leg.abandon);
        let r = run(self.params.method, counted, from, self.tolerance);
        self.runs.push(record(leg.stage, lambda, &r));
        let e = objective.evaluate(&r.theta, true)?;
        let jac = e
            .jacobian
            .as_ref()
            .ok_or(FitError::Internal("the forward model returned no Jacobian"))?;
        let known = objective.noise_known.then_some(1.0);
        let c = curvature(jac, objective.data_rows(), e.misfit, known);
        let bound = e.residuals[e.residuals.len() - 1];
        let data_residuals = &e.residuals.as_slice()[..objective.data_rows()];
        let random_signs =
            runs_test(data_residuals, &self.groups).is_none_or(|r| r.p_value >= RUNS_P_VALUE);
        let trial = Trial {
            lambda,
            theta: r.theta.clone(),
            misfit: e.misfit,
            effective_parameters: c.effective_parameters,
            penalised: e.objective() - bound * bound,
            log_det: c.log_det,
            penalty_rank: objective.param.terms().saturating_sub(2),
            free: r.theta.len(),
            random_signs,
        };
        // The evaluation behind the trial is its linearisation: kept, the
        // λ refinement and the path's predictor need no evaluation of
        // their own.
        self.linearisation = Some(Linearisation::of(objective, &trial, e)?);
        Ok((trial, r))
    }

    /// Keeps the linearisation at `base` (a fit's trial): the one kept from
    /// the latest run when it is that fit's, else made afresh.
    fn linearise_at(&mut self, base: &Trial) -> Result<(), FitError> {
        let current = self
            .linearisation
            .take()
            .filter(|l| l.lambda() == base.lambda && l.theta() == base.theta.as_slice());
        let linearisation = match current {
            Some(l) => l,
            None => {
                self.objective.lambda = base.lambda;
                let e = self.objective.evaluate(&base.theta, true)?;
                Linearisation::of(&self.objective, base, e)?
            }
        };
        self.linearisation = Some(linearisation);
        Ok(())
    }

    /// The fit at `lambda` from `from` with the full budget.
    fn solve(
        &mut self,
        lambda: f64,
        from: &[f64],
        stage: &str,
    ) -> Result<(Trial, SolverRun), FitError> {
        let budget = self.budget;
        self.solve_leg(
            lambda,
            from,
            Leg {
                stage,
                budget,
                abandon: None,
            },
        )
    }

    /// The starting θ: the first start, the bumps and the seeded
    /// perturbations race at the first λ to be fitted; the lowest V after
    /// [`RACE_EVALUATIONS`] begins. Warm starts would otherwise carry a poor
    /// local minimum down the whole λ path (a narrow rubber's flat start
    /// stalled at a misfit 100 times the bumps' at every λ), and the
    /// perturbations, once run at the chosen λ, never won there (none of the
    /// 24 fits of the exploration study) at 50–110 evaluations a fit.
    fn race_starts(&mut self, starts: &Starts<'_>) -> Result<Vec<f64>, FitError> {
        let lambda = first_lambda(self.params);
        self.tolerance = Tolerance::Path;
        let mut best: Option<(f64, Vec<f64>)> = None;
        let param = &self.objective.param;
        let candidates = std::iter::once(("start probe: neutral".to_string(), starts.first()))
            .chain(
                starts
                    .bumps(param, self.params)
                    .into_iter()
                    .enumerate()
                    .map(|(k, b)| (format!("start probe: bump {}", k + 1), b)),
            )
            .chain(
                starts
                    .perturbations(self.params)?
                    .into_iter()
                    .enumerate()
                    .map(|(k, p)| (format!("start probe: random {}", k + 1), p)),
            )
            .collect::<Vec<_>>();
        for (stage, candidate) in candidates {
            let leg = Leg {
                stage: &stage,
                budget: RACE_EVALUATIONS,
                abandon: None,
            };
            let (_, r) = self.solve_leg(lambda, &candidate, leg)?;
            if best.as_ref().is_none_or(|b| r.objective < b.0) {
                best = Some((r.objective, r.theta));
            }
        }
        Ok(best.map_or_else(|| starts.first(), |(_, theta)| theta))
    }

    /// The fit at the user's fixed λ.
    fn fixed_lambda(&mut self, lambda: f64, from: &[f64]) -> Result<LambdaChoice, FitError> {
        self.tolerance = if self.params.coarse {
            Tolerance::Path
        } else {
            Tolerance::Final
        };
        let (trial, run) = self.solve(lambda, from, "fixed lambda")?;
        Ok(LambdaChoice {
            rule: LambdaRule::Fixed,
            trial,
            run,
            criterion: Vec::new(),
            evidence_noise_variance: None,
        })
    }

    /// λ by the data: the path walked down from `from` with warm starts,
    /// the rule's λ located on it, and the fit there.
    fn auto_lambda(&mut self, mut from: Vec<f64>) -> Result<LambdaChoice, FitError> {
        let rule = if self.objective.noise_known {
            LambdaRule::Discrepancy
        } else {
            LambdaRule::MarginalLikelihood
        };
        let n = self.objective.data_rows();
        let mut trials: Vec<(Trial, SolverRun)> = Vec::new();
        let mut criterion = Vec::new();
        // The path is walked at the looser tolerance: its points only
        // locate λ; the chosen one is polished below.
        self.tolerance = Tolerance::Path;
        let lambdas = lambda_path(self.params);
        for (j, &lambda) in lambdas.iter().enumerate() {
            let (t, r) = self.solve(lambda, &from, "lambda path")?;
            self.path.push([lambda, t.misfit, t.effective_parameters]);
            let walked = path_walked(rule, n, &trials, &t);
            if rule != LambdaRule::Discrepancy {
                criterion.push([lambda, t.criterion(rule, n)]);
            }
            // The next point starts where this fit's linearisation predicts
            // it (the predictor of a continuation method): on the cost
            // study's 15-speed fits the path took 984 evaluations over
            // eight seeds against 1,170 from this fit's θ.
            if !walked && let Some(&next) = lambdas.get(j + 1) {
                from = self.predict(next, &t)?.theta;
            }
            trials.push((t, r));
            if walked {
                break;
            }
        }
        let (lambda, from, evidence_noise_variance) = match rule {
            LambdaRule::Discrepancy => {
                let (t, _) = bisect_discrepancy(n, trials, self)?;
                (t.lambda, t.theta, None)
            }
            _ => {
                let minimum = criterion_minimum(rule, n, &trials);
                (minimum.lambda, minimum.from, minimum.noise_variance)
            }
        };
        self.tolerance = Tolerance::Final;
        let (trial, run) = self.solve(lambda, &from, "chosen lambda")?;
        self.path
            .push([lambda, trial.misfit, trial.effective_parameters]);
        Ok(LambdaChoice {
            rule,
            trial,
            run,
            criterion,
            evidence_noise_variance,
        })
    }

    /// At the chosen λ, the bumps (unless `bumps_raced`) and seeded
    /// perturbations of the starting material, each abandoned early when
    /// hopeless: the path's warm starts can still drift into a poor minimum
    /// on the way down (an unanchored fit on 41 speeds ended at E1 = 16 MPa,
    /// tan δ 50 % off, where a bump restart finds the truth's basin).
    /// Returns the fit that stands.
    fn restart(
        &mut self,
        starts: &Starts<'_>,
        bumps_raced: bool,
        chosen: Trial,
        chosen_run: SolverRun,
    ) -> Result<(Trial, SolverRun), FitError> {
        let others = starts.restarts(&self.objective.param, self.params, bumps_raced)?;
        // The restarts run at the path's tolerances; one that beats the
        // chosen fit by more than the looser model's error is solved again
        // at the final tolerance before it replaces it.
        self.tolerance = Tolerance::Path;
        let mut winner: Option<(Trial, SolverRun)> = None;
        for (stage, from) in &others {
            let leg = Leg {
                stage,
                budget: (self.budget / EXPLORATION_SHARE).max(1),
                abandon: Some(Abandonment {
                    after: ABANDON_AFTER * (self.free + 1),
                    above: ABANDON_FACTOR * chosen_run.objective,
                }),
            };
            let (t, r) = self.solve_leg(chosen.lambda, from, leg)?;
            let best = winner
                .as_ref()
                .map_or(chosen_run.objective, |(_, w)| w.objective);
            if r.objective < best * (1.0 - RESTART_MARGIN) {
                winner = Some((t, r));
            }
        }
        self.tolerance = Tolerance::Final;
        let (from, stage) = match winner {
            Some((t, _)) => (t.theta, "polish best start"),
            None if !chosen_run.stop.converged() => (chosen.theta.clone(), "continue best start"),
            None => return Ok((chosen, chosen_run)),
        };
        let (t, r) = self.solve(chosen.lambda, &from, stage)?;
        if r.objective <= chosen_run.objective || !chosen_run.stop.converged() {
            Ok((t, r))
        } else {
            Ok((chosen, chosen_run))
        }
    }

    /// With bands, θ of the fit at a tenth of the chosen λ: the smoothing
    /// bias of the bands (see [`crate::analysis`]).
    fn less_smoothed(&mut self, chosen: &Trial) -> Result<Option<Vec<f64>>, FitError> {
        if !(self.params.bands && chosen.lambda > 0.0) {
            return Ok(None);
        }
        let from = chosen.theta.clone();
        let (t, _) = self.solve(chosen.lambda / 10.0, &from, "band: λ/10")?;
        Ok(Some(t.theta))
    }

    /// The analysed optimum of `choice`.
    fn analyse(
        mut self,
        choice: LambdaChoice,
        less_smoothed: Option<Vec<f64>>,
    ) -> Result<Optimum, FitError> {
        let chosen = Chosen {
            trial: choice.trial,
            run: choice.run,
            rule: choice.rule,
            path: self.path,
            criterion: choice.criterion,
            runs: self.runs,
            less_smoothed,
            evidence_noise_variance: choice.evidence_noise_variance,
        };
        analyse(self.params, &mut self.objective, chosen)
    }
}

/// The refinement's fits, recorded on the λ path; its predictions from
/// the linearisation of the latest fit asked about.
impl Refinement for GridSolver<'_> {
    fn refine_at(&mut self, lambda: f64, from: &[f64]) -> Result<(Trial, SolverRun), FitError> {
        let (t, r) = self.solve(lambda, from, "refine lambda")?;
        self.path.push([lambda, t.misfit, t.effective_parameters]);
        Ok((t, r))
    }

    /// The predicted trial, its θ the start of a fit at `lambda`: the
    /// predicted step shortened to at most [`PREDICTOR_STEP`] in every
    /// log-parameter, since the linearisation holds only near `base` (a
    /// full step of a poorly fitted temperature set's single-temperature
    /// fit overflowed E1).
    fn predict(&mut self, lambda: f64, base: &Trial) -> Result<Trial, FitError> {
        self.linearise_at(base)?;
        let mut predicted = match &self.linearisation {
            Some(l) => l.predict(lambda, &self.groups),
            None => return Err(FitError::Internal("no linearisation")),
        };
        let longest = predicted
            .theta
            .iter()
            .zip(&base.theta)
            .map(|(p, b)| (p - b).abs())
            .fold(0.0, f64::max);
        if longest.is_nan() || longest > PREDICTOR_STEP {
            let shorten = if longest.is_finite() {
                PREDICTOR_STEP / longest
            } else {
                0.0
            };
            for (p, b) in predicted.theta.iter_mut().zip(&base.theta) {
                *p = b + shorten * (*p - b);
            }
        }
        // A step that leaves the materials the model accepts (the anchored
        // parametrisation's E0 = E1 − ΣH reaching zero) is no start.
        let param = &self.objective.param;
        if param.prony(&param.map(&predicted.theta)).is_err() {
            predicted.theta = base.theta.clone();
        }
        Ok(predicted)
    }
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
