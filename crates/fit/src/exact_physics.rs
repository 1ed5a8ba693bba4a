//! Fits against the exact rolling contact by defect correction
//! (`physics = "exact"`).
//!
//! # The problem
//!
//! The fit's model μ_A(v; E) is Persson's Eq. (11) (cylinder) or (17)
//! (sphere): fast, with an analytic Jacobian, but 4–10 % off the exact
//! steady contact μ_X(v; E) near the friction maximum of a broad rubber.
//! Fitting real data with μ_A absorbs that model error into E*(ω) without
//! a trace in χ². μ_X (`rollfit_model::exact::exact_body`) costs about
//! 0.1 s per speed and has no Jacobian, far too slow to sit inside the
//! solvers' thousands of evaluations.
//!
//! # The method
//!
//! Defect correction (Stetter 1978): iterate with the cheap approximate
//! operator, and evaluate the exact one only at each iterate to measure
//! the defect. Here the defect is the ratio r = μ_X/μ_A, which is close to
//! 1 and changes far more slowly with the modulus than μ itself:
//!
//! ```text
//! θ_0     = argmin_θ V_A(θ),  V_A(θ) = Σ_i [(μ_A(v_i; θ) − μ_i)/s_i]² + λ R(θ)   (today's fit)
//! r_i^k   = μ_X(v_i; E_θk) / μ_A(v_i; E_θk)                                    (exact solves)
//! θ_{k+1} = argmin_θ Σ_i [(r_i^k μ_A(v_i; θ) − μ_i)/s_i]² + λ R(θ)
//! ```
//!
//! until max_i |r_i^{k+1}/r_i^k − 1| is at most the accuracy asked of the
//! exact solves (below), or [`MAX_ITERATIONS`] refits. Each refit is the
//! whole approximate fit (λ rule, starts, terms, temperature shift,
//! analysis) on corrected data:
//!
//! ```text
//! (r_i μ_A − μ_i)/s_i = (μ_A − μ_i/r_i) / (s_i/r_i),
//! ```
//!
//! so fitting μ_i/r_i with σ_i/r_i is the corrected model against the
//! measured data, exactly — also with relative weights (s_i = μ_i, whose
//! corrected scale μ_i/r_i is the corrected datum's own relative weight).
//! The driver sees ordinary data: χ², the runs test, the noise estimate and
//! the λ rule are those of the measured μ against r μ_A; its plausibility checks
//! of the measured μ are given the measured rows
//! (`driver::fit_measured`). Only dense data are binned after the
//! correction rather than before, a difference of second order in the
//! change of r across a bin of 1/20 decade.
//!
//! A fixed point θ* has r frozen at its own modulus, so r μ_A = μ_X there:
//! the residuals are those of the exact model. Its normal equations are the
//! exact problem's without the term μ_A ∂r/∂θ, which multiplies residuals
//! of noise size: data the exact model reproduces without noise have the
//! truth as a fixed point, and with noise the difference is of second
//! order. On a broad rubber (tests/exact_physics.rs) the first refit
//! changed r by about 5e-4 and the second by about 1e-5.
//!
//! For a temperature set, r_i is taken at the point's reduced speed
//! v_i·a_T(T_i) on the master curve with the fitted shift: the exact
//! contact of `Prony::shifted(log10 a_T)` at v_i is the master curve's at
//! v_i·a_T, since it depends on time only through v·τ_k. One exact body
//! serves every temperature.
//!
//! # Accuracy and cost
//!
//! Each exact μ is asked for a relative accuracy of a tenth of the data's
//! relative σ (the median σ_i/μ_i; without σ, the scatter within bins or
//! the fit's own noise estimate), within 1e-5 … 1e-3; the same number is
//! the convergence tolerance on r. The solves of one sweep run in parallel
//! (rayon; inside a batch on the batch's pool), at the distinct speeds on
//! the master curve, or — for dense data with more distinct speeds than a
//! grid of 20 per decade — on that grid (the nodes); ln r is interpolated
//! to the rows by cubics in ln v.
//!
//! Every solve after the first at a node is started where the last solve
//! at that node ended (`ExactRolling::exact_friction_from`): the
//! cylinder's secant from the last root, each of the sphere's grids from
//! its last contact set and pressures (the coarse first sweep's 96- and
//! 64-cell grids are the 1e-4 sweeps' two coarser ones). Between refits
//! the modulus moves little, so the start is close, and the answer is the
//! cold solve's to the solvers' own tolerances (crates/model/tests/
//! exact_warm_start.rs). The sphere's active-set iteration, most of a
//! solve at 1e-4, then needs about half its operator applications: on the
//! broad rubber at σ = 0.1 % the last sweep cost 3.6 s of CPU against
//! 9.1 s cold. The cylinder's secant gains nothing measurable.
//!
//! The cylinder (about 0.03 s per solve for the fitted series of the
//! bench, at any accuracy) solves every sweep at the accuracy asked and
//! adaptively, as the sphere does (below): adaptive sweeps need about a
//! third of the solves of sweeps at every node, with the same errors in
//! the study of tests/exact_physics.rs (BENCHMARKS.md, "Fit
//! speed"). Its error estimate is a second solve on a finer mesh
//! (q + 2 nodes per panel, about 0.045 s); only the last sweep's estimates
//! are reported, and which sweep is last is known only once its change
//! is, so the sweeps solve without it and the estimates of the last are
//! made after the loop, from the roots it kept
//! (`ExactRolling::deferred_estimate`: the same numbers).
//!
//! The sphere (0.2–1 s of CPU per solve for the fitted series of the
//! bench; three grids of 96 cells and up
//! at 1e-3, 144 at 1e-4) solves fewer and cheaper:
//!
//! - The first sweep is solved at 1e-3 ([`COARSE_ACCURACY`]) where a finer
//!   accuracy is asked. Only the correction a fit used must match the
//!   correction at that fit's modulus to the accuracy asked for the
//!   iteration to have converged (the fixed point), so only the sweep
//!   that confirms it must be accurate: the change of r is always measured
//!   by a sweep at the accuracy asked, and where the coarse first sweep
//!   finds r ≡ 1 within the tolerance, a sweep at the accuracy asked
//!   confirms it before the approximate fit is taken as the answer.
//! - Every sweep is adaptive ([`adaptive_fill`]): solved at every fourth
//!   node, then, halving the stride, at the nodes where the interpolation
//!   from the solved ones may be off by more than half the accuracy (an
//!   estimate from the difference of the cubic to the interpolants of one
//!   order less and more). A sweep after one at the same accuracy and
//!   nodes with no gap interpolates not ln r but its change ln(r/r'),
//!   which is smooth and small (5e-4 … 1e-5 on the broad rubber), so its
//!   interpolation error is a small fraction of itself; where r' was
//!   itself interpolated, its error (estimated within half the accuracy)
//!   carries over.
//! - The exact sphere's cost per solve itself fell (`rollfit_model::exact::
//!   RollingSphere`: FFT lengths without large prime factors, real-data
//!   transforms, the grids' influence tables built once per grid shape
//!   rather than once per solve; BENCHMARKS.md), and the memory tables'
//!   tail integrals beyond the grid, most of a solve with the corner form,
//!   evaluate the cell's influence by its multipole form through
//!   ρ⁻⁵ (one square root) instead of the corner form (eight logarithms),
//!   to within the corner form's own rounding.
//!
//! `exact_solves` counts the solves made; the error estimates reported
//! are those of the solutions behind the final r (of an earlier sweep at
//! the same accuracy where a node was interpolated against it). On the
//! broad rubber's 41 speeds at σ = 0.1 % (accuracy 1e-4): 11 solves at
//! 1e-3, then 19 and 11 at 1e-4 over two refits (41 solves, against 103
//! at 1e-4 before). Against r solved at all 41 speeds at the reported
//! modulus, the reported ln r is off by at most 5.5e-5 where those solves
//! estimate their own error below the accuracy, and by up to 1.1e-4 at
//! the lowest speeds, where they estimate 1.4e-4 … 2.5e-4 and r jitters
//! from speed to speed by that much (the fit warns of it); see
//! BENCHMARKS.md for times.
//!
//! # References
//!
//! - H.J. Stetter, "The defect correction principle and discretization
//!   methods", Numer. Math. 29 (1978) 425–443.
//! - K. Böhmer, H.J. Stetter (eds.), *Defect Correction Methods: Theory and
//!   Applications*, Computing Supplementum 5, Springer, Vienna 1984.
//! - B.N.J. Persson, "Rolling friction for hard cylinder and sphere on
//!   viscoelastic solid", Eur. Phys. J. E 33 (2010) 327–333, Eqs. (11),
//!   (17) and Appendix B.

use std::time::Instant;

use rayon::prelude::*;
use rollfit_model::exact::{ExactFriction, ExactStart};
use rollfit_model::{Scene, Shape};

mod material;
mod nodes;

#[cfg(test)]
use material::solvable_material;
pub use material::{MAX_CORRECTION_FACTOR, NEGLIGIBLE_STRENGTH};
use material::{checked_ln_ratio, exact_of, poisoned, reduced_speeds};
pub use nodes::interpolate;
use nodes::{adaptive_fill, solve_nodes};

use crate::data::Measurements;
use crate::error::FitError;
use crate::params::ValidFitParams;
use crate::report::{FitReport, PhysicsRecord, RunRecord};

/// The most refits with the corrected model after the first, approximate
/// fit. The correction contracts fast (on a broad rubber by a factor of
/// about 30 per refit), so more than two means something is wrong.
pub const MAX_ITERATIONS: usize = 6;

/// The accuracy asked of each exact μ, relative to the data's relative σ.
pub const ACCURACY_PER_NOISE: f64 = 0.1;

/// The range of the accuracy asked of each exact μ: below 1e-5 the exact
/// cylinder claims no better (`rollfit_model::exact::RESOLVED_ERROR`), and
/// 1e-3 is a tenth of the scatter of a good friction rig.
pub const ACCURACY_RANGE: (f64, f64) = (1e-5, 1e-3);

/// The approximate fit of corrected rows, with the measured rows for its
/// plausibility checks (`driver::fit_measured`, handed over by the driver, which
/// calls this module).
pub(crate) type ApproximateFit =
    fn(&Measurements, Option<&Measurements>, &ValidFitParams) -> Result<FitReport, FitError>;

/// The fit of `rows` with the exact physics: the approximate fit, then
/// refits of the data corrected by r = μ_exact/μ_approx at each fit's
/// modulus until r stops changing (see the module doc).
pub(crate) fn defect_correction(
    rows: &Measurements,
    params: &ValidFitParams,
    approximate: ApproximateFit,
) -> Result<FitReport, FitError> {
    let clock = Instant::now();
    let progress = &params.progress;
    progress.stage("approximate fit");
    let mut report = approximate(rows, None, params)?;
    let accuracy = (ACCURACY_PER_NOISE * relative_noise(rows, &report))
        .clamp(ACCURACY_RANGE.0, ACCURACY_RANGE.1);
    let schedule = Schedule::of(params.setup.geometry.shape, accuracy);
    progress.stage("exact sweep 1");
    let mut correction = Correction::at(
        rows,
        params,
        &report,
        (schedule.first_accuracy, None),
        schedule.first(),
    )?;
    let mut solves = correction.solves;
    let mut earlier: Vec<RunRecord> = Vec::new();
    // The approximate fit is the fit with r ≡ 1: already converged if the
    // correction at its modulus is within the tolerance of 1.
    let (mut iterations, mut change) = (0, correction.largest());
    loop {
        if change <= accuracy && correction.accuracy <= accuracy {
            break;
        }
        if change <= accuracy {
            // Only the coarse first sweep has r ≡ 1 within the tolerance
            // but was solved less accurately than asked: confirm at the
            // accuracy asked, at the same modulus, before stopping.
            progress.stage("exact sweep, confirming");
            let sweep = schedule.later(None);
            correction =
                Correction::at(rows, params, &report, (accuracy, Some(&correction)), sweep)?;
            solves += correction.solves;
            change = correction.largest();
            continue;
        }
        if iterations >= MAX_ITERATIONS {
            break;
        }
        let corrected = correction.apply(rows)?;
        progress.stage(&format!("refit {}", iterations + 1));
        let next = approximate(&corrected, Some(rows), params)?;
        let stage = match iterations {
            0 => "approximate".to_string(),
            k => format!("correction {k}"),
        };
        earlier.extend(staged(std::mem::replace(&mut report, next).runs, &stage));
        iterations += 1;
        let sweep = schedule.later(Some(&correction));
        progress.stage(&format!("exact sweep {}", iterations + 1));
        let updated = Correction::at(rows, params, &report, (accuracy, Some(&correction)), sweep)?;
        solves += updated.solves;
        change = updated.change_from(&correction);
        correction = updated;
    }
    correction.complete_estimates(params, &report)?;
    finish(
        report,
        Finish {
            correction,
            earlier,
            iterations,
            solves,
            change,
            accuracy,
            clock,
        },
    )
}

/// What the loop of [`defect_correction`] ends with.
struct Finish {
    /// The correction at the last fit's modulus.
    correction: Correction,
    /// The runs of the fits before the last, staged.
    earlier: Vec<RunRecord>,
    iterations: usize,
    solves: usize,
    /// max |Δr/r| of the last iteration.
    change: f64,
    accuracy: f64,
    clock: Instant,
}

/// The last fit's report with the exact μ as its fitted μ, every run, the
/// physics record and the warnings about it.
fn finish(mut report: FitReport, done: Finish) -> Result<FitReport, FitError> {
    let Finish {
        correction,
        earlier,
        iterations,
        solves,
        change,
        accuracy,
        clock,
    } = done;
    let converged = change <= accuracy;
    if !converged {
        report.warnings.push(format!(
            "physics = \"exact\": the correction r = μ_exact/μ_approx still changed by up to \
             {change:.1e} (tolerance {accuracy:.1e}) in the last of {iterations} refits; the \
             modulus is the last refit's, against a correction that had not settled"
        ));
    }
    if correction.uncertain > 0 {
        report.warnings.push(format!(
            "physics = \"exact\": the exact solution estimates its own error at up to {:.1e} \
             at {} of {} speeds, above the accuracy {accuracy:.1e} asked (a tenth of the data's \
             relative σ); the correction there is that uncertain",
            correction.max_error_estimate, correction.uncertain, correction.estimated
        ));
    }
    // r_i μ_approx(v_i) with r at the final modulus: the exact μ of the
    // reported modulus.
    report.mu_fit = report
        .mu_fit
        .iter()
        .zip(&correction.ratio)
        .map(|(mu, r)| mu * r)
        .collect();
    report.runs = earlier.into_iter().chain(report.runs).collect();
    report.evaluations = report.runs.iter().map(|r| r.evaluations).sum();
    report.physics = Some(PhysicsRecord {
        kind: "exact",
        iterations,
        exact_solves: solves,
        converged,
        max_correction: correction.largest(),
        accuracy,
        max_error_estimate: correction.max_error_estimate,
        tolerance: accuracy,
        last_change: change,
        correction: correction.ratio,
    });
    report.wall_time_s = clock.elapsed().as_secs_f64();
    if let Some(what) = report.first_non_finite() {
        return Err(FitError::NonFinite(what));
    }
    Ok(report)
}

/// The runs of an earlier fit, their stage prefixed with `stage`.
fn staged(runs: Vec<RunRecord>, stage: &str) -> impl Iterator<Item = RunRecord> + '_ {
    runs.into_iter().map(move |mut r| {
        r.stage = format!("{stage}: {}", r.stage);
        r
    })
}

/// The data's relative σ: the median σ_i/μ_i when measured; else the
/// scatter within bins of condensed data, or the fit's estimate of the
/// relative noise from its residuals.
fn relative_noise(rows: &Measurements, report: &FitReport) -> f64 {
    match rows.sigma() {
        Some(sigma) => {
            let mut relative: Vec<f64> = sigma
                .iter()
                .zip(rows.friction())
                .map(|(s, mu)| s / mu)
                .collect();
            relative.sort_by(f64::total_cmp);
            relative[relative.len() / 2]
        }
        None => report
            .condensed
            .as_ref()
            .and_then(|c| c.scatter)
            .unwrap_or(report.noise),
    }
}

/// Which accuracy the exact solves of one fit use.
#[derive(Debug, Clone, Copy)]
struct Schedule {
    /// The accuracy of the first sweep.
    first_accuracy: f64,
}

impl Schedule {
    /// The cylinder solves every sweep at the accuracy asked: its solve
    /// costs the same at any accuracy. The sphere's solve costs 1–6 s and
    /// grows steeply with the accuracy (144 cells at 1e-4 cost about three
    /// times 96 cells at 1e-3), so its first sweep, which only sets where
    /// the iteration starts, is solved at [`COARSE_ACCURACY`] (or the
    /// accuracy asked, if coarser). Every sweep of both is adaptive: even
    /// the cylinder's cheap solves are worth sparing (a third of the solves
    /// of sweeps at every node, BENCHMARKS.md, "Fit speed").
    fn of(shape: Shape, accuracy: f64) -> Schedule {
        match shape {
            Shape::Cylinder => Schedule {
                first_accuracy: accuracy,
            },
            Shape::Sphere => Schedule {
                first_accuracy: accuracy.max(COARSE_ACCURACY),
            },
        }
    }

    /// The first sweep: adaptive from every fourth speed.
    fn first(self) -> Sweep<'static> {
        Sweep::Adaptive(None)
    }

    /// The sweep after `previous` (the correction the last fit used; none
    /// to confirm r ≡ 1).
    fn later(self, previous: Option<&Correction>) -> Sweep<'_> {
        Sweep::Adaptive(previous)
    }
}

/// The accuracy of the sphere's first sweep where a finer one is asked:
/// 96 cells, against 144 at 1e-4.
pub const COARSE_ACCURACY: f64 = 1e-3;

/// The share of the accuracy asked that the interpolation of an adaptive
/// sweep may add to r at a speed it did not solve at.
pub const INTERPOLATION_SHARE: f64 = 0.5;

/// Where an exact sweep solves.
#[derive(Clone, Copy)]
enum Sweep<'a> {
    /// Every fourth speed of [`solve_nodes`] and the last, then, halving
    /// the stride, those where the interpolation's error estimate exceeds
    /// [`INTERPOLATION_SHARE`] of the accuracy (see [`adaptive_fill`]).
    /// What is interpolated is ln r, or ln(r/r') against an earlier
    /// correction r' when that one covers the same speeds at the same
    /// accuracy without a gap (solved, or itself filled within the
    /// share): the change of r from one refit to the next is far smaller
    /// and smoother than r itself.
    Adaptive(Option<&'a Correction>),
}

/// r = μ_exact/μ_approx at one fit's modulus, per data row.
struct Correction {
    /// r_i per row.
    ratio: Vec<f64>,
    /// The speeds on the master curve r was found at ([`solve_nodes`]).
    nodes: Vec<f64>,
    /// ln r at each of `nodes`.
    ln_ratio: Vec<f64>,
    /// The error estimate of the exact solution behind each node's r
    /// (none where r was interpolated without one).
    estimates: Vec<Option<f64>>,
    /// The accuracy the exact solutions were asked for.
    accuracy: f64,
    /// Whether r at every node is solved, or interpolated with an
    /// estimated error within [`INTERPOLATION_SHARE`] of `accuracy`.
    complete: bool,
    /// Exact solves made.
    solves: usize,
    /// Where the last solve at each node ended (in this sweep or an
    /// earlier one), to start the next sweep's solve there from.
    starts: Vec<Option<ExactStart>>,
    /// The largest error the exact solutions estimated for themselves.
    max_error_estimate: f64,
    /// Solutions whose error estimate exceeds the accuracy asked.
    uncertain: usize,
    /// Nodes with an error estimate (solved in this sweep or, for an
    /// adaptive sweep against a base, in the base's).
    estimated: usize,
}

impl Correction {
    /// r at the modulus (and shift) of `report` at every row of `rows`:
    /// the exact contact solved in parallel at the rows' distinct reduced
    /// speeds (or a grid, see [`solve_nodes`]; where the `sweep` says),
    /// the approximate model at the same speeds, ln r interpolated to the
    /// rows. The solves are asked for `accuracy` and started where the
    /// `earlier` correction's solves at the same node ended (a warm start,
    /// `ExactRolling::exact_friction_from`: the same μ with fewer
    /// iterations), where it has the same nodes.
    fn at(
        rows: &Measurements,
        params: &ValidFitParams,
        report: &FitReport,
        (accuracy, earlier): (f64, Option<&Correction>),
        sweep: Sweep,
    ) -> Result<Correction, FitError> {
        let (body, prony) = exact_of(params, report, accuracy)?;
        let setup = &params.setup;
        let approximate_model = Scene::new(setup.geometry, setup.substrate, setup.contact, prony)?
            .with_tolerance(params.model_tolerance)?;
        let reduced = reduced_speeds(rows, report);
        let nodes = solve_nodes(&reduced);
        let starts = std::sync::Mutex::new(match earlier {
            Some(e) if e.nodes == nodes => e.starts.clone(),
            _ => vec![None; nodes.len()],
        });
        // ln r at a batch of nodes (indices), solved in parallel, with the
        // solutions' error estimates; each solve started where the last
        // one at its node ended, and its own end kept for the next.
        let solve = |at: &[usize]| -> Result<Vec<(f64, f64)>, FitError> {
            let speeds: Vec<f64> = at.iter().map(|&i| nodes[i]).collect();
            params.progress.planned(speeds.len());
            let exact: Vec<ExactFriction> = at
                .par_iter()
                .map(|&i| -> Result<ExactFriction, FitError> {
                    let v = nodes[i];
                    let start = starts.lock().map_err(|_| poisoned(v))?[i].take();
                    // The estimate only of the last sweep's solves is
                    // reported: where it costs a solve of its own (the
                    // cylinder), it is made once the loop has ended.
                    let (solved, end) = body
                        .exact_friction_unestimated_from(v, start.as_ref())
                        .map_err(|e| FitError::ExactPhysics {
                            speed: v,
                            problem: e.to_string(),
                        })?;
                    starts.lock().map_err(|_| poisoned(v))?[i] = Some(end);
                    params.progress.solved();
                    Ok(solved)
                })
                .collect::<Result<_, _>>()?;
            let approximate = approximate_model.friction_sweep(&speeds)?;
            speeds
                .iter()
                .zip(&exact)
                .zip(&approximate)
                .map(|((&v, x), &a)| Ok((checked_ln_ratio(v, x.mu, a)?, x.error_estimate)))
                .collect()
        };
        let Sweep::Adaptive(base) = sweep;
        let base = base.filter(|b| b.complete && b.accuracy == accuracy && b.nodes == nodes);
        let base_ln = |i: usize| base.map_or(0.0, |b| b.ln_ratio[i]);
        let tolerance = INTERPOLATION_SHARE * accuracy;
        let (solved, found) = adaptive_fill(&nodes, base_ln, tolerance, &solve)?;
        let complete = true;
        // What is interpolated: ln r, or ln(r/r') against the base.
        let solved_speeds: Vec<f64> = solved.iter().map(|&i| nodes[i]).collect();
        let solved_values: Vec<f64> = solved
            .iter()
            .zip(&found)
            .map(|(&i, (ln_r, _))| ln_r - base_ln(i))
            .collect();
        let ln_ratio: Vec<f64> = (0..nodes.len())
            .map(|i| interpolate(&solved_speeds, &solved_values, nodes[i]) + base_ln(i))
            .collect();
        let base_at = |v: f64| base.map_or(0.0, |b| interpolate(&nodes, &b.ln_ratio, v));
        let ratio = reduced
            .iter()
            .map(|&v| (interpolate(&solved_speeds, &solved_values, v) + base_at(v)).exp())
            .collect::<Vec<f64>>();
        // Each node's estimate: its solve's, or the base's where it was
        // not solved again.
        let mut node_estimates =
            base.map_or_else(|| vec![None; nodes.len()], |b| b.estimates.clone());
        for (&i, (_, e)) in solved.iter().zip(&found) {
            node_estimates[i] = Some(*e);
        }
        let mut correction = Correction {
            ratio,
            solves: solved.len(),
            starts: starts.into_inner().map_err(|_| poisoned(nodes[0]))?,
            max_error_estimate: 0.0,
            uncertain: 0,
            estimated: 0,
            nodes,
            ln_ratio,
            estimates: node_estimates,
            accuracy,
            complete,
        };
        correction.tally();
        Ok(correction)
    }

    /// The error estimates' summary: the largest, how many exceed the
    /// accuracy, how many nodes have one.
    fn tally(&mut self) {
        let estimates = self.estimates.iter().flatten();
        self.max_error_estimate = estimates
            .clone()
            .filter(|e| e.is_finite())
            .fold(0.0, |m: f64, e| m.max(*e));
        self.uncertain = estimates.clone().filter(|e| **e > self.accuracy).count();
        self.estimated = estimates.count();
    }

    /// The error estimates the solves behind this (the last) correction
    /// left out (`ExactRolling::exact_friction_unestimated_from`), made
    /// now at the modulus of `report`, which those solves were made at:
    /// the numbers the solves would have given with them.
    fn complete_estimates(
        &mut self,
        params: &ValidFitParams,
        report: &FitReport,
    ) -> Result<(), FitError> {
        let pending: Vec<usize> = (0..self.nodes.len())
            .filter(|&i| self.estimates[i].is_some_and(f64::is_nan) && self.starts[i].is_some())
            .collect();
        if pending.is_empty() {
            return Ok(());
        }
        let (body, _) = exact_of(params, report, self.accuracy)?;
        let found: Vec<Option<f64>> = pending
            .par_iter()
            .map(|&i| {
                let (v, end) = (self.nodes[i], self.starts[i].as_ref());
                let estimate = end.map(|end| body.deferred_estimate(v, end)).transpose();
                estimate
                    .map(Option::flatten)
                    .map_err(|e| FitError::ExactPhysics {
                        speed: v,
                        problem: e.to_string(),
                    })
            })
            .collect::<Result<_, _>>()?;
        for (i, estimate) in pending.into_iter().zip(found) {
            if estimate.is_some() {
                self.estimates[i] = estimate;
            }
        }
        self.tally();
        Ok(())
    }

    /// max_i |r_i − 1|.
    fn largest(&self) -> f64 {
        self.ratio
            .iter()
            .fold(0.0, |m: f64, r| m.max((r - 1.0).abs()))
    }

    /// max_i |r_i/r'_i − 1| against an `earlier` correction.
    fn change_from(&self, earlier: &Correction) -> f64 {
        self.ratio
            .iter()
            .zip(&earlier.ratio)
            .fold(0.0, |m: f64, (r, e)| m.max((r / e - 1.0).abs()))
    }

    /// The corrected data: μ_i/r_i with σ_i/r_i (see the module doc).
    fn apply(&self, rows: &Measurements) -> Result<Measurements, FitError> {
        let divide = |values: &[f64]| -> Vec<f64> {
            values.iter().zip(&self.ratio).map(|(x, r)| x / r).collect()
        };
        Measurements::new(
            rows.speeds().to_vec(),
            divide(rows.friction()),
            rows.sigma().map(divide),
            rows.temperature().map(<[f64]>::to_vec),
        )
    }
}

#[cfg(test)]
mod tests {
    use rollfit_model::exact::exact_body;
    use rollfit_model::{ContactSize, Geometry, ModelError, Prony, Shape, Substrate};

    use super::*;
    use crate::params::{FitParams, Physics, RollingSetup};
    use crate::report::ModelRecord;

    fn setup(shape: Shape, film_thickness: Option<f64>) -> RollingSetup {
        RollingSetup {
            geometry: Geometry {
                shape,
                radius: 0.005,
                load: 1.0,
            },
            substrate: Substrate {
                poisson: 0.5,
                film_thickness,
            },
            contact: ContactSize::Dynamic,
        }
    }

    fn exact(setup: RollingSetup) -> Result<ValidFitParams, crate::FitError> {
        FitParams {
            physics: Physics::Exact,
            ..FitParams::default()
        }
        .check(setup)
    }

    /// `physics = "exact"` is refused, naming the key, on a film and where
    /// `exact_body` has no body (passing its reason on); the cylinder on a
    /// half-space is accepted, and the approximate physics everywhere.
    #[test]
    fn exact_physics_needs_an_exact_body_on_a_half_space() {
        assert!(exact(setup(Shape::Cylinder, None)).is_ok());
        let e = exact(setup(Shape::Cylinder, Some(1e-3)))
            .unwrap_err()
            .to_string();
        assert!(e.contains("`physics`") && e.contains("film"), "{e}");
        let probe = Prony::new(1e9, vec![1e9 - 1e6], vec![1.0]).unwrap();
        let sphere = exact(setup(Shape::Sphere, None));
        match exact_body(Shape::Sphere, &probe, 0.5, 0.005, 1.0, 1e-3) {
            Err(ModelError::ExactNotAvailable { why }) => {
                let e = sphere.unwrap_err().to_string();
                assert!(e.contains("`physics`") && e.contains(why), "{e}");
            }
            Err(other) => panic!("{other}"),
            Ok(_) => assert!(sphere.is_ok()),
        }
        for shape in [Shape::Sphere, Shape::Cylinder] {
            let params = FitParams::default().check(setup(shape, Some(1e-3)));
            assert!(params.is_ok());
        }
    }

    /// Terms below 1e-12 E1 are left out, E0 kept; the largest stays.
    #[test]
    fn negligible_terms_are_left_out_of_the_exact_material() {
        let model = |strengths: Vec<f64>| ModelRecord {
            kind: "prony",
            glassy_modulus: 1e9,
            static_modulus: 1e9 - strengths.iter().sum::<f64>(),
            tau: vec![1e-3, 1e-2, 1e-1],
            determined: vec![true; 3],
            ln_strength_sigma: vec![0.0; 3],
            strengths,
        };
        // The floor is 1e-12 E1 = 1e-3 Pa.
        let p = solvable_material(&model(vec![1e-40, 5e8, 1e-2])).unwrap();
        assert_eq!(p.relaxation_times(), &[1e-2, 1e-1]);
        let static_modulus = p.glassy_modulus() - p.strengths().iter().sum::<f64>();
        assert!((static_modulus - (1e9 - 5e8 - 1e-2 - 1e-40)).abs() < 1e-6);
        let p = solvable_material(&model(vec![1e-40, 5e8, 1e-4])).unwrap();
        assert_eq!(p.relaxation_times(), &[1e-2]);
        let p = solvable_material(&model(vec![1e-40, 1e-30, 1e-35])).unwrap();
        assert_eq!(p.relaxation_times(), &[1e-2]);
    }

    /// The cylinder keeps one accuracy; the sphere's first sweep is
    /// coarse where a finer accuracy is asked; both sweep adaptively.
    #[test]
    fn only_the_sphere_schedules_a_coarse_first_sweep() {
        let c = Schedule::of(Shape::Cylinder, 1e-4);
        assert_eq!(c.first_accuracy, 1e-4);
        assert!(matches!(c.later(None), Sweep::Adaptive(None)));
        assert!(matches!(c.first(), Sweep::Adaptive(None)));
        let s = Schedule::of(Shape::Sphere, 1e-4);
        assert_eq!(s.first_accuracy, COARSE_ACCURACY);
        assert!(matches!(s.later(None), Sweep::Adaptive(None)));
        assert!(matches!(s.first(), Sweep::Adaptive(None)));
        assert_eq!(Schedule::of(Shape::Sphere, 1e-3).first_accuracy, 1e-3);
    }
}
