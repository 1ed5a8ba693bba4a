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
//! the λ rule are those of the measured μ against r μ_A; its sanity checks
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
//! (rayon; inside a batch on the batch's pool), one per distinct speed on
//! the master curve, or — for dense data with more distinct speeds than a
//! grid of 20 per decade — on that grid; ln r is interpolated to the rows
//! by cubics in ln v. The first sweep, which only sets where the iteration
//! starts, solves at every other of those speeds. Cost: the exact sweeps
//! (one thinned, then one per refit, about 0.13 s per solve for a fitted
//! 32-term series) and (refits + 1) approximate fits of about 0.1 s.
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
use rollfit_model::exact::{ExactFriction, exact_body};
use rollfit_model::{Prony, Scene};

use crate::condense::BINS_PER_DECADE;
use crate::data::Measurements;
use crate::error::FitError;
use crate::params::ValidFitParams;
use crate::report::{FitReport, ModelRecord, PhysicsRecord, RunRecord};

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

/// Strengths below this fraction of E1 are left out of the fitted Prony
/// series before the exact solves. The smoothness penalty on ln H_k lets
/// the strengths outside the window fall to 1e-40 E1 and below, and with
/// such terms the exact cylinder fails without saying so: a fitted,
/// nearly single-term series with strengths down to 1e-42 E1 gave
/// μ = 8.5 where Eq. (11) gives 1.8e-5, with an error estimate of 1e-3;
/// without the terms below 1e-20 E1 the two agreed to 1e-4. Leaving them
/// out changes E*(ω) by less than their sum, a few 1e-12 relative, far
/// below the accuracy asked.
pub const NEGLIGIBLE_STRENGTH: f64 = 1e-12;

/// The largest factor by which μ_exact and Eq. (11)/(17) may differ before
/// the exact solution is taken to have failed: the approximation is
/// 4–10 % off near the friction maximum of a broad rubber and closer
/// elsewhere, so a factor of two is no approximation error.
pub const MAX_CORRECTION_FACTOR: f64 = 2.0;

/// The approximate fit of corrected rows, with the measured rows for its
/// sanity checks (`driver::fit_measured`, handed over by the driver, which
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
    let mut report = approximate(rows, None, params)?;
    let accuracy = (ACCURACY_PER_NOISE * relative_noise(rows, &report))
        .clamp(ACCURACY_RANGE.0, ACCURACY_RANGE.1);
    let mut correction = Correction::at(rows, params, &report, accuracy, Sweep::First)?;
    let mut solves = correction.solves;
    let mut earlier: Vec<RunRecord> = Vec::new();
    // The approximate fit is the fit with r ≡ 1: already converged if the
    // correction at its modulus is within the tolerance of 1.
    let (mut iterations, mut change) = (0, correction.largest());
    while iterations < MAX_ITERATIONS && change > accuracy {
        let corrected = correction.apply(rows)?;
        let next = approximate(&corrected, Some(rows), params)?;
        let stage = match iterations {
            0 => "approximate".to_string(),
            k => format!("correction {k}"),
        };
        earlier.extend(staged(std::mem::replace(&mut report, next).runs, &stage));
        iterations += 1;
        let updated = Correction::at(rows, params, &report, accuracy, Sweep::Full)?;
        solves += updated.solves;
        change = updated.change_from(&correction);
        correction = updated;
    }
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
            correction.max_error_estimate, correction.uncertain, correction.nodes
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

/// Where an exact sweep solves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Sweep {
    /// The first sweep, at the approximate fit: every other speed of
    /// [`solve_nodes`] (see [`thinned`]).
    First,
    /// Every speed of [`solve_nodes`].
    Full,
}

/// r = μ_exact/μ_approx at one fit's modulus, per data row.
struct Correction {
    /// r_i per row.
    ratio: Vec<f64>,
    /// Exact solves made.
    solves: usize,
    /// Speeds on the master curve solved at.
    nodes: usize,
    /// The largest error the exact solutions estimated for themselves.
    max_error_estimate: f64,
    /// Solutions whose error estimate exceeds the accuracy asked.
    uncertain: usize,
}

impl Correction {
    /// r at the modulus (and shift) of `report` at every row of `rows`:
    /// the exact contact solved in parallel at the rows' distinct reduced
    /// speeds (or a grid, see [`solve_nodes`]; thinned for the first
    /// `sweep`), the approximate model at the same speeds, ln r
    /// interpolated to the rows.
    fn at(
        rows: &Measurements,
        params: &ValidFitParams,
        report: &FitReport,
        accuracy: f64,
        sweep: Sweep,
    ) -> Result<Correction, FitError> {
        let prony = solvable_material(&report.model)?;
        let setup = &params.setup;
        let g = setup.geometry;
        let body = exact_body(
            g.shape,
            &prony,
            setup.substrate.poisson,
            g.radius,
            g.load,
            accuracy,
        )?;
        let reduced = reduced_speeds(rows, report);
        let nodes = match sweep {
            Sweep::First => thinned(solve_nodes(&reduced)),
            Sweep::Full => solve_nodes(&reduced),
        };
        let exact: Vec<ExactFriction> = nodes
            .par_iter()
            .map(|&v| {
                body.exact_friction(v).map_err(|e| FitError::ExactPhysics {
                    speed: v,
                    problem: e.to_string(),
                })
            })
            .collect::<Result<_, _>>()?;
        let approximate = Scene::new(g, setup.substrate, setup.contact, prony)?
            .with_tolerance(params.model_tolerance)?
            .friction_sweep(&nodes)?;
        let mut ln_ratio = Vec::with_capacity(nodes.len());
        for ((v, x), a) in nodes.iter().zip(&exact).zip(&approximate) {
            let r = x.mu / a;
            if !(r.is_finite() && r.ln().abs() <= MAX_CORRECTION_FACTOR.ln()) {
                return Err(FitError::ExactPhysics {
                    speed: *v,
                    problem: format!(
                        "μ = {:e} where Eq. (11)/(17) gives {a:e}; the two differ by far less \
                         than a factor of {MAX_CORRECTION_FACTOR}, so the exact solution has \
                         failed for this modulus (use physics = \"approximate\")",
                        x.mu
                    ),
                });
            }
            ln_ratio.push(r.ln());
        }
        let ratio = reduced
            .iter()
            .map(|&v| interpolate(&nodes, &ln_ratio, v).exp())
            .collect::<Vec<f64>>();
        let estimates = exact.iter().map(|x| x.error_estimate);
        Ok(Correction {
            ratio,
            solves: nodes.len(),
            nodes: nodes.len(),
            max_error_estimate: estimates
                .clone()
                .filter(|e| e.is_finite())
                .fold(0.0, f64::max),
            uncertain: estimates.filter(|e| *e > accuracy).count(),
        })
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

/// The fitted Prony series without its negligible terms (strengths below
/// [`NEGLIGIBLE_STRENGTH`] E1; the largest term is always kept), E0 kept.
fn solvable_material(m: &ModelRecord) -> Result<Prony, FitError> {
    let floor = NEGLIGIBLE_STRENGTH * m.glassy_modulus;
    let largest = m.strengths.iter().copied().fold(0.0, f64::max);
    let (mut strengths, mut tau, mut dropped) = (Vec::new(), Vec::new(), 0.0);
    for (&h, &t) in m.strengths.iter().zip(&m.tau) {
        if h >= floor || h == largest {
            strengths.push(h);
            tau.push(t);
        } else {
            dropped += h;
        }
    }
    Ok(Prony::new(m.glassy_modulus - dropped, strengths, tau)?)
}

/// The rows' speeds on the master curve: v·a_T with the fitted shift for a
/// temperature set.
fn reduced_speeds(rows: &Measurements, report: &FitReport) -> Vec<f64> {
    match (&report.shift, rows.temperature()) {
        (Some(shift), Some(temps)) => rows
            .speeds()
            .iter()
            .zip(temps)
            .map(|(v, t)| v * 10f64.powf(shift.log_shift_at(*t).unwrap_or(0.0)))
            .collect(),
        _ => rows.speeds().to_vec(),
    }
}

/// The speeds to solve the exact contact at, increasing: the distinct
/// `reduced` speeds, or, when they are more than a grid of
/// [`BINS_PER_DECADE`] per decade over their range would hold (dense data,
/// which the fit sees in bins of that width anyway), that grid.
fn solve_nodes(reduced: &[f64]) -> Vec<f64> {
    let mut distinct = reduced.to_vec();
    distinct.sort_by(f64::total_cmp);
    distinct.dedup();
    let (lo, hi) = (distinct[0], distinct[distinct.len() - 1]);
    let count = ((hi / lo).log10() * BINS_PER_DECADE).ceil() as usize + 1;
    if distinct.len() <= count {
        return distinct;
    }
    let (ln_lo, ln_hi) = (lo.ln(), hi.ln());
    let mut grid: Vec<f64> = (0..count)
        .map(|k| (ln_lo + (ln_hi - ln_lo) * k as f64 / (count - 1) as f64).exp())
        .collect();
    // Both ends exact, so that every row lies inside the grid.
    grid[0] = lo;
    grid[count - 1] = hi;
    grid
}

/// The first sweep's speeds: every other one of `nodes` and the last
/// (when there are at least [`THIN_FROM`]). The first correction only
/// sets where the iteration starts: its fixed point is made by the full
/// sweeps that follow, and an error of the first r costs at most another
/// refit. Interpolated from every other speed of the broad rubber's 41
/// (0.4 decade apart), ln r was off by at most 2e-4 (cubic), a fifth of
/// the tolerance at 1 % noise, while the first sweep costs half.
fn thinned(nodes: Vec<f64>) -> Vec<f64> {
    if nodes.len() < THIN_FROM {
        return nodes;
    }
    let last = nodes.len() - 1;
    nodes
        .iter()
        .enumerate()
        .filter(|(i, _)| i % 2 == 0 || *i == last)
        .map(|(_, &v)| v)
        .collect()
}

/// The fewest speeds whose first sweep is thinned: fewer leave too few
/// for a cubic between them.
const THIN_FROM: usize = 12;

/// `values` (given at the increasing `nodes`) at `x`: the node's own value
/// where x is a node, else the cubic in ln v through the four nearest
/// nodes (fewer where there are fewer).
fn interpolate(nodes: &[f64], values: &[f64], x: f64) -> f64 {
    let k = nodes.partition_point(|&n| n < x);
    if k < nodes.len() && nodes[k] == x {
        return values[k];
    }
    let n = nodes.len();
    let width = n.min(4);
    // Two nodes on each side of x where possible.
    let first = k.saturating_sub(2).min(n - width);
    let stencil = first..first + width;
    let t = x.ln();
    stencil
        .clone()
        .map(|i| {
            let weight: f64 = stencil
                .clone()
                .filter(|&j| j != i)
                .map(|j| (t - nodes[j].ln()) / (nodes[i].ln() - nodes[j].ln()))
                .product();
            weight * values[i]
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use rollfit_model::{ContactSize, Geometry, ModelError, Shape, Substrate};

    use super::*;
    use crate::params::{FitParams, Physics, RollingSetup};

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

    /// Sparse data are solved at each distinct speed; dense data on a grid
    /// of 20 per decade with both ends exact.
    #[test]
    fn nodes_are_the_distinct_speeds_or_a_grid() {
        let speeds = [1e-3, 1e-5, 1e-3, 1e-4];
        assert_eq!(solve_nodes(&speeds), vec![1e-5, 1e-4, 1e-3]);
        let dense: Vec<f64> = (0..1000)
            .map(|i| 1e-6 * 10f64.powf(i as f64 / 500.0))
            .collect();
        let grid = solve_nodes(&dense);
        assert_eq!(grid.len(), 41);
        assert_eq!((grid[0], grid[40]), (dense[0], dense[999]));
        assert!(grid.windows(2).all(|w| w[1] > w[0]));
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

    /// Exact at nodes, and exact for a cubic in ln v between them (with
    /// two nodes, linear); the first sweep keeps every other speed and the
    /// last.
    #[test]
    fn interpolation_is_cubic_in_ln_v() {
        let nodes: Vec<f64> = [-6.0, -5.2, -4.0, -3.1, -2.0, -1.0]
            .iter()
            .map(|e| 10f64.powf(*e))
            .collect();
        let cubic = |v: f64| {
            let t = v.ln();
            0.3 - 0.02 * t + 1e-3 * t * t - 2e-5 * t * t * t
        };
        let values: Vec<f64> = nodes.iter().map(|&v| cubic(v)).collect();
        assert_eq!(interpolate(&nodes, &values, nodes[3]), values[3]);
        for e in [-5.9, -5.5, -4.7, -3.5, -2.5, -1.1] {
            let v = 10f64.powf(e);
            assert!(
                (interpolate(&nodes, &values, v) - cubic(v)).abs() < 1e-12,
                "{e}"
            );
        }
        let two = [1e-4, 1e-2];
        assert!((interpolate(&two, &[1.0, 3.0], 1e-3) - 2.0).abs() < 1e-12);
        let speeds: Vec<f64> = (0..13).map(|i| 10f64.powi(i - 12)).collect();
        let first = thinned(speeds.clone());
        assert_eq!(first.len(), 7);
        assert_eq!(
            (first[0], first[1], first[6]),
            (speeds[0], speeds[2], speeds[12])
        );
        let even = thinned(speeds[..12].to_vec());
        assert_eq!((even.len(), even[5], even[6]), (7, speeds[10], speeds[11]));
        assert_eq!(thinned(speeds[..11].to_vec()).len(), 11);
    }
}
