//! The solver runs on one τ grid, from the first start to the analysed
//! optimum:
//!
//! 1. With an anchor and several starts, the neutral (or warm) start and
//!    the bump starts are each probed briefly at the first λ; the best
//!    begins.
//! 2. λ: the fixed one, or the path walked down with warm starts at the
//!    path's looser tolerances and refined ([`super::lambda`]); the chosen
//!    λ is solved again at the user's tolerance.
//! 3. With several starts, the bumps (unless probed) and the seeded
//!    perturbations are run at the chosen λ, each abandoned early when
//!    hopeless; one that beats the chosen fit clearly is polished and
//!    replaces it.
//! 4. With bands, the fit at λ/10 for the smoothing bias; then the
//!    analysis of the optimum ([`super::optimum`]).

use crate::analysis::curvature;
use crate::data::Measurements;
use crate::error::FitError;
use crate::objective::Objective;
use crate::parametrization::Parametrization;
use crate::params::{Lambda, ValidFitParams};
use crate::quality::{RUNS_P_VALUE, runs_test, speed_ordered_groups};
use crate::regularization::{LambdaRule, Trial};
use crate::report::RunRecord;
use crate::solvers::counting::{Abandonment, Counted};
use crate::solvers::{SolverRun, Tolerance, default_budget, run};
use crate::temperature_set::ShiftStart;

use super::lambda::{
    Refinement, criterion_minimum, first_lambda, lambda_path, path_walked, refine,
};
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

/// Jacobians' worth of evaluations (n + 1 each, n free parameters) a start
/// probe may spend: enough to tell a start that is stuck (a narrow rubber's
/// flat start: misfit 100 times the bumps') from one that is not.
const PROBE_JACOBIANS: usize = 1;

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
    let mut grid = GridSolver::new(data, params, tau, set);
    let material = warm.unwrap_or_else(|| neutral_start(&grid.objective.param, params));
    let range = set.map_or_else(|| data.speed_range(), |s| s.range);
    let starts = Starts::new(material, set, range);
    // Unanchored fits keep the neutral start: the scale profile that bounds
    // their bands walks out from the fit, and from a probed start it stalled
    // (on the bundled rubber, seed 1, the band then covered none of the
    // window against 64 % from the neutral start).
    let probed = params.starts > 1 && params.anchor.is_some();
    let from = if probed {
        grid.probe_starts(&starts)?
    } else {
        starts.first()
    };
    let mut choice = match params.lambda {
        Lambda::Fixed(lambda) => grid.fixed_lambda(lambda, &from)?,
        Lambda::Auto => grid.auto_lambda(from)?,
    };
    if params.starts > 1 {
        (choice.trial, choice.run) = grid.restart(&starts, probed, choice.trial, choice.run)?;
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
    data: &'a Measurements,
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
}

impl<'a> GridSolver<'a> {
    fn new(
        data: &'a Measurements,
        params: &'a ValidFitParams,
        tau: Vec<f64>,
        set: Option<&ShiftStart>,
    ) -> Self {
        let param = Parametrization::new(tau, params.anchor);
        let free = param.free_count() + set.map_or(0, |s| s.param.count());
        let objective = Objective {
            setup: &params.setup,
            data,
            scales: data.residual_scales(),
            param,
            shift: set.map(|s| s.param.clone()),
            lambda: 0.0,
            e1_max: params.e1_max,
            tolerance: params.model_tolerance,
            // Only a temperature set's rows take b_T.
            vertical: set.and(params.shift.vertical.as_ref()),
        };
        let budget = params
            .max_evaluations
            .unwrap_or_else(|| default_budget(params.method, free));
        GridSolver {
            data,
            params,
            objective,
            free,
            budget,
            tolerance: Tolerance::Final,
            runs: Vec::new(),
            path: Vec::new(),
            groups: speed_ordered_groups(data),
        }
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
        let known = self.data.sigma().map(|_| 1.0);
        let c = curvature(jac, self.data.len(), e.misfit, known);
        let bound = e.residuals[e.residuals.len() - 1];
        let data_residuals = &e.residuals.as_slice()[..self.data.len()];
        let random_signs =
            runs_test(data_residuals, &self.groups).is_none_or(|r| r.p_value >= RUNS_P_VALUE);
        Ok((
            Trial {
                lambda,
                theta: r.theta.clone(),
                misfit: e.misfit,
                effective_parameters: c.effective_parameters,
                penalised: e.objective() - bound * bound,
                log_det: c.log_det,
                penalty_rank: objective.param.terms().saturating_sub(2),
                free: r.theta.len(),
                random_signs,
            },
            r,
        ))
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

    /// The starting θ: the first start and the bumps, each probed briefly
    /// at the first λ to be fitted; the best begins. Warm starts would
    /// otherwise carry a poor local minimum down the whole λ path (a narrow
    /// rubber's flat start stalled at a misfit 100 times the bumps' at every
    /// λ).
    fn probe_starts(&mut self, starts: &Starts<'_>) -> Result<Vec<f64>, FitError> {
        let lambda = first_lambda(self.params);
        self.tolerance = Tolerance::Path;
        let mut best: Option<(f64, Vec<f64>)> = None;
        let candidates =
            std::iter::once(starts.first()).chain(starts.bumps(&self.objective.param, self.params));
        for (k, candidate) in candidates.enumerate() {
            let stage = if k == 0 {
                "start probe: neutral".to_string()
            } else {
                format!("start probe: bump {k}")
            };
            let leg = Leg {
                stage: &stage,
                budget: PROBE_JACOBIANS * (self.free + 1),
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
        let rule = if self.data.sigma().is_some() {
            LambdaRule::Discrepancy
        } else {
            LambdaRule::MarginalLikelihood
        };
        let n = self.data.len();
        let mut trials: Vec<(Trial, SolverRun)> = Vec::new();
        let mut criterion = Vec::new();
        // The path is walked at the looser tolerance: its points only
        // locate λ; the chosen one is polished below.
        self.tolerance = Tolerance::Path;
        for lambda in lambda_path(self.params) {
            let (t, r) = self.solve(lambda, &from, "lambda path")?;
            from = t.theta.clone();
            self.path.push([lambda, t.misfit, t.effective_parameters]);
            let walked = path_walked(rule, n, &trials, &t);
            if rule != LambdaRule::Discrepancy {
                criterion.push([lambda, t.criterion(rule, n)]);
            }
            trials.push((t, r));
            if walked {
                break;
            }
        }
        let (lambda, from, evidence_noise_variance) = match rule {
            LambdaRule::Discrepancy => {
                let (t, _) = refine(rule, n, trials, self)?;
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

    /// At the chosen λ, the bumps again (unless `bumps_probed`) and seeded
    /// perturbations of the starting material, each abandoned early when
    /// hopeless: the path's warm starts can still drift into a poor minimum
    /// on the way down (an unanchored fit on 41 speeds ended at E1 = 16 MPa,
    /// tan δ 50 % off, where a bump restart finds the truth's basin).
    /// Returns the fit that stands.
    fn restart(
        &mut self,
        starts: &Starts<'_>,
        bumps_probed: bool,
        chosen: Trial,
        chosen_run: SolverRun,
    ) -> Result<(Trial, SolverRun), FitError> {
        let others = starts.restarts(&self.objective.param, self.params, bumps_probed)?;
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
        analyse(self.data, self.params, &mut self.objective, chosen)
    }
}

/// The refinement's fits, recorded on the λ path.
impl Refinement for GridSolver<'_> {
    fn refine_at(&mut self, lambda: f64, from: &[f64]) -> Result<(Trial, SolverRun), FitError> {
        let (t, r) = self.solve(lambda, from, "refine lambda")?;
        self.path.push([lambda, t.misfit, t.effective_parameters]);
        Ok((t, r))
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
