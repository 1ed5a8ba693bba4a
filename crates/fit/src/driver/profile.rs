//! The scale profile of an unanchored fit: how well the data determine the
//! modulus scale, the direction rolling data determine worst.
//!
//! Without an anchor, μ(v) fixes the modulus scale only through the
//! contact size (a ∝ E^{-1/3} for a ball, E^{-1/2} for a cylinder) and the
//! non-linear dependence of μ on tan δ. Where tan δ is small, a softer
//! rubber with proportionally less loss gives nearly the same μ(v): the fit
//! can slide along that valley to a "rubber" of a few Pa whose contact is
//! larger than the ball, and describe the data well. So the scale is
//! measured, not assumed:
//!
//! 1. The range of E0 in which the model holds: from the largest of
//!    10 kPa ([`MIN_RUBBER_MODULUS`]) and the E0 at which the rubbery
//!    (static) Hertz contact reaches the trusted size R/3
//!    ([`MAX_CONTACT_RATIO`]) up to a tenth of E1_max.
//! 2. The profile: E0 pinned (the anchored parametrisation with ω_a = 0)
//!    on a grid of half-decade steps walked outward from the fit's E0
//!    (clamped into the range), the shape refitted at each step from its
//!    neighbour's (continuation) at one λ_p for all steps, so that misfits
//!    compare on one footing: the fit's λ, or, where the unanchored optimum
//!    left the range or its λ ran to the top of the path (the valley's flat
//!    far end), the λ the data choose for a fit pinned at the start. The walk stops where Δχ² exceeds
//!    [`PROFILE_STOP`] or at the range's end.
//! 3. Δχ² = (misfit − min misfit)/s², s² the noise variance at the best
//!    step (1 with a measured σ). The 2σ interval is where Δχ² ≤ 4 (a
//!    profile-likelihood interval, Venzon & Moolgavkar), its ends refined by
//!    one bisection of the bracketing step and interpolated linearly in
//!    ln E0; an end that reaches the range's edge is open, and so is one
//!    beyond which the profile stays below Δχ² = 9 ([`DECISIVE`], 3σ) up
//!    to the range's edge (a plateau that noise lifts just over 4).
//! 4. The scale counts as determined when the interval (an open end taken
//!    at the range's edge: the model's own limits bound the scale there too)
//!    spans at most a factor [`SCALE_FACTOR_LIMIT`] either side of its
//!    geometric centre; otherwise it is
//!    undetermined and the command line refuses the fit unless asked to
//!    keep it.
//! 5. On a one-sided profile — its minimum at an end of the profiled range,
//!    where the misfit falls or stays flat up to the model's own limit (the
//!    R/3 contact, E1_max) — that end is the worst estimate inside the
//!    interval: the result is refitted with E0 pinned at the centre in
//!    ln E0 of the 2σ interval (an open end closed by the range), which the
//!    record and the bands keep. Otherwise, when the unanchored optimum
//!    lies outside the range or more than one
//!    noise unit (Δχ² > 1) above the profile's minimum — the penalty, which
//!    prefers some shapes, has pulled it along the valley — the result is
//!    refitted with E0 pinned at the profile's minimum (a parabola through
//!    the best step and its neighbours in ln E0): the profile likelihood's
//!    maximum within the model's range. The data misfit, not the penalised
//!    objective, decides the scale.
//!
//! The steps within one noise unit (Δχ² ≤ 1) describe the data as well as
//! the result and widen its bands ([`ScaleProfile::widen`]).
//!
//! # References
//! - D.J. Venzon, S.H. Moolgavkar, "A method for computing
//!   profile-likelihood-based confidence intervals", Appl. Statist. 37
//!   (1988) 87–94.
//! - K.L. Johnson, *Contact Mechanics*, Cambridge University Press 1985,
//!   §4.2 (the Hertz contact size).

use rollfit_model::{Prony, ViscoelasticModulus};

use crate::data::Measurements;
use crate::error::FitError;
use crate::params::{Lambda, ModulusAnchor, TermRule, ValidFitParams};
use crate::regularization::LambdaRule;
use crate::report::{ModulusPoint, RunRecord, ScaleRecord};
use crate::tau_grid::contact_size;
use crate::temperature_set::ShiftStart;
use rollfit_model::plausibility::{MAX_CONTACT_RATIO, MIN_RUBBER_MODULUS};

use super::SCALE_FACTOR_LIMIT;
use super::grid::solve_on_grid;
use super::optimum::Optimum;
use super::starts::neutral_start;
use crate::parametrization::Parametrization;

/// Step of the profile's grid in E0 (half a decade).
const PROFILE_STEP: f64 = 3.162_277_660_168_379_5;

/// Δχ² beyond which a walk stops: 5σ, from where no step returns within
/// the 2σ interval unless a second valley exists.
const PROFILE_STOP: f64 = 25.0;

/// λ_p/λ: the profile's smoothing relative to the fit's, by how the fit's
/// λ was chosen. At the marginal likelihood's maximum the data, not the
/// penalty, shape the misfit: λ itself (a tenth of it made the pinned fits
/// crawl at small λ, median cost 3.3 times the fit's instead of 2.1,
/// without moving an interval's end past the truth). The discrepancy
/// principle (σ measured) and a given λ lean to the smooth side (the
/// largest λ with χ² ≤ N): a tenth, else the penalty builds the profile's
/// wall (on the bundled example at λ itself the interval's upper end fell
/// to 1.6 MPa, below the true 2 MPa).
fn profile_relaxation(rule: LambdaRule) -> f64 {
    match rule {
        LambdaRule::MarginalLikelihood => 1.0,
        LambdaRule::Discrepancy | LambdaRule::Gcv | LambdaRule::Fixed => 0.1,
    }
}

/// Bisections of the step that brackets an end of the 2σ interval: the
/// profile can rise from 0 to hundreds within one step (E0 above the
/// rubbery plateau the slowest speeds see is a cliff), where interpolation
/// over the whole step would put the end far inside; four halve the half
/// decade to 1/32 decade (7 % in E0).
const BISECTIONS: usize = 4;

/// Δχ² of the 2σ interval.
const TWO_SIGMA: f64 = 4.0;

/// Δχ² that a profile must pass somewhere beyond a 2σ end, before the
/// range's edge, for that end to bound the scale (module doc, step 3):
/// 3σ. A plateau that noise lifts to just over 4 is no bound: chosen among
/// many such fits, its crossing excludes the truth far more often than 5 %.
const DECISIVE: f64 = 9.0;

/// Δχ² of the steps that widen the bands (1σ).
const ONE_SIGMA: f64 = 1.0;

/// One step of the profile.
struct Step {
    /// E0 pinned, Pa.
    e0: f64,
    /// The data misfit.
    misfit: f64,
    /// The noise variance s² at this step (1 with a measured σ).
    noise_variance: f64,
    /// ln(H_k/E0) of the refitted shape.
    shape: Vec<f64>,
    /// The refitted material (None where E1/E0 is beyond what a Prony
    /// series in double precision holds: such a step widens no band).
    prony: Option<Prony>,
}

/// The profile of one fit.
pub(super) struct ScaleProfile {
    /// (E0/E0 of the result, misfit, λ_p) of each step, by E0.
    pub points: Vec<[f64; 3]>,
    /// Every run of the pinned fits, in order.
    pub runs: Vec<RunRecord>,
    /// What fit.json says of the scale.
    pub record: ScaleRecord,
    /// When the unanchored optimum lies outside the range or the interval,
    /// or the profile is one-sided: where to pin the result.
    pub refit: Option<Refit>,
    /// The steps within one noise unit of the best.
    accepted: Vec<Prony>,
}

impl ScaleProfile {
    /// Widens the bands of `curve` to enclose every accepted step.
    pub(super) fn widen(&self, curve: &mut [ModulusPoint]) {
        for point in curve.iter_mut() {
            for p in &self.accepted {
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
    }

    /// The record and the factors of [`Self::points`] for a result whose
    /// E0 is `e0` (the refit's, which differs a little from the step's).
    pub(super) fn rescale_to(&mut self, e0: f64) {
        let old = self.record.static_modulus;
        for p in &mut self.points {
            p[0] *= old / e0;
        }
        self.record.static_modulus = e0;
        self.record.status = status(self.record.low, self.record.high, self.record.range);
        self.record.reason = reason(&self.record);
    }
}

/// The range of E0 (Pa) in which the model's assumptions hold for the
/// rubbery contact (module doc, step 1).
pub(crate) fn static_modulus_range(params: &ValidFitParams) -> [f64; 2] {
    let setup = &params.setup;
    // The contact size scales as E^{-1/3} (ball) or E^{-1/2} (cylinder):
    // its exponent read off two moduli, so no formula is repeated here.
    let (a1, a2) = (contact_size(setup, 1.0), contact_size(setup, 2.0));
    let exponent = (a1 / a2).ln() / 2f64.ln();
    let limit = MAX_CONTACT_RATIO * setup.geometry.radius;
    let smallest_valid = (a1 / limit).powf(1.0 / exponent);
    [smallest_valid.max(MIN_RUBBER_MODULUS), 0.1 * params.e1_max]
}

/// Where the result of an unanchored fit is pinned instead of its own
/// optimum (module doc, step 5).
pub(super) struct Refit {
    /// E0, Pa.
    pub e0: f64,
    /// The shape (ln(H_k/E0)) to start from.
    pub shape: Vec<f64>,
    /// Whether `e0` is the centre of a one-sided profile's 2σ interval (else
    /// the profile's minimum).
    pub centre: bool,
}

/// The pinned refits: what they share.
struct Profiler<'a> {
    data: &'a Measurements,
    params: &'a ValidFitParams,
    /// The fit's shift, continued from its optimum.
    set: Option<ShiftStart>,
    /// The fit's τ grid.
    tau: &'a [f64],
    /// λ_p.
    lambda: f64,
    /// The shape every step also starts from (besides its neighbour's).
    reference: Vec<f64>,
    /// Every run so far.
    runs: Vec<RunRecord>,
}

/// The scale profile of the unanchored fit `fit` (module doc).
pub(super) fn profile_scale(
    data: &Measurements,
    params: &ValidFitParams,
    fit: &Optimum,
    set: Option<&ShiftStart>,
) -> Result<ScaleProfile, FitError> {
    let m = &fit.model;
    let range = static_modulus_range(params);
    let mut profiler = Profiler {
        data,
        params,
        set: set.map(|s| s.with_theta(data, fit.shift_theta.clone())),
        tau: &m.tau,
        lambda: fit.lambda.value * profile_relaxation(fit.lambda.rule),
        reference: Vec::new(),
        runs: Vec::new(),
    };
    if range[0] >= range[1] || range[0].is_nan() {
        return Ok(ScaleProfile {
            points: Vec::new(),
            runs: Vec::new(),
            record: no_range(m.static_modulus, range),
            refit: Some(Refit {
                e0: range[0],
                shape: shape(m.strengths.iter(), m.static_modulus),
                centre: false,
            }),
            accepted: Vec::new(),
        });
    }
    let start = m.static_modulus.clamp(range[0], range[1]);
    profiler.reference = shape(m.strengths.iter(), m.static_modulus);
    // An optimum outside the range, or one whose λ ran to the top of the
    // path (the valley's flat far end), says nothing of the smoothing the
    // data want: a fit pinned at `start` with λ chosen by the data sets it.
    let top = super::lambda::lambda_path(params)[0];
    if start != m.static_modulus {
        // The optimum's shape at an E0 outside the range can be absurd
        // (E1/E0 beyond 1e15 at a few Pa): the neutral start instead.
        let pinned = profiler.pinned_params(start);
        let param = Parametrization::new(m.tau.clone(), pinned.anchor);
        profiler.reference = neutral_start(&param, &pinned);
    }
    if start != m.static_modulus || fit.lambda.value >= top * 0.999 {
        let reference = profiler.reference_fit(start)?;
        profiler.lambda = reference.lambda.value * profile_relaxation(reference.lambda.rule);
        profiler.reference = shape(
            reference.model.strengths.iter(),
            reference.model.static_modulus,
        );
    }
    let from = profiler.reference.clone();
    let Some(first) = profiler.pinned(start, &from, None)? else {
        let mut record = no_range(m.static_modulus, range);
        record.reason = format!(
            "the shape could not be refitted with E0 pinned at {start:.3e} Pa, so the data's \
             hold on the scale is unknown; {ANCHORS}"
        );
        return Ok(ScaleProfile {
            points: Vec::new(),
            runs: profiler.runs,
            record,
            refit: None,
            accepted: Vec::new(),
        });
    };
    let mut steps = vec![first];
    for upward in [true, false] {
        profiler.walk(upward, range, &mut steps)?;
    }
    steps.sort_by(|a, b| a.e0.total_cmp(&b.e0));
    let (low, high) = profiler.interval(&mut steps, range)?;
    let best = best_step(&steps);
    let unit = steps[best].noise_variance;
    let misfit_min = steps[best].misfit;
    let e0_fit = m.static_modulus;
    // The fit's own E0 is the first step when it lies in the range.
    let own = (e0_fit == start).then(|| steps.iter().find(|s| s.e0 == start));
    let own_delta = own.flatten().map(|s| (s.misfit - misfit_min) / unit);
    let interval = [low.unwrap_or(range[0]), high.unwrap_or(range[1])];
    let own_is_estimate = own_delta.is_some_and(|d| d <= ONE_SIGMA);
    let refit = refit_at(&steps, best, interval, own_is_estimate);
    let e0 = refit.as_ref().map_or(e0_fit, |r| r.e0);
    let delta = |s: &Step| (s.misfit - misfit_min) / unit;
    let mut record = ScaleRecord {
        status: status(low, high, range),
        static_modulus: e0,
        low,
        high,
        range,
        profile: steps.iter().map(|s| [s.e0, delta(s)]).collect(),
        reason: String::new(),
    };
    record.reason = reason(&record);
    Ok(ScaleProfile {
        points: steps
            .iter()
            .map(|s| [s.e0 / e0, s.misfit, profiler.lambda])
            .collect(),
        runs: profiler.runs,
        record,
        refit,
        accepted: steps
            .iter()
            .filter(|s| delta(s) <= ONE_SIGMA)
            .filter_map(|s| s.prony.clone())
            .collect(),
    })
}

impl Profiler<'_> {
    /// Walks from the first step (`steps[0]`) up or down in
    /// [`PROFILE_STEP`]s to the range's end or until Δχ² passes
    /// [`PROFILE_STOP`], each step continued from the previous step's shape.
    fn walk(
        &mut self,
        upward: bool,
        range: [f64; 2],
        steps: &mut Vec<Step>,
    ) -> Result<(), FitError> {
        let mut shape = steps[0].shape.clone();
        let mut e0 = steps[0].e0;
        loop {
            let at_end = if upward {
                e0 >= range[1]
            } else {
                e0 <= range[0]
            };
            if at_end {
                return Ok(());
            }
            e0 = if upward {
                (e0 * PROFILE_STEP).min(range[1])
            } else {
                (e0 / PROFILE_STEP).max(range[0])
            };
            let b = &steps[best_step(steps)];
            let Some(step) = self.pinned(e0, &shape, Some((b.misfit, b.noise_variance)))? else {
                return Ok(());
            };
            shape = step.shape.clone();
            steps.push(step);
            let best = best_step(steps);
            let last = &steps[steps.len() - 1];
            if (last.misfit - steps[best].misfit) / steps[best].noise_variance > PROFILE_STOP {
                return Ok(());
            }
        }
    }

    /// `params` with E0 pinned to `e0` (Pa).
    fn pinned_params(&self, e0: f64) -> ValidFitParams {
        let mut pinned = self.params.clone();
        pinned.anchor = Some(ModulusAnchor {
            omega: 0.0,
            modulus: e0,
            source: "profile",
        });
        pinned.starts = 1;
        pinned.bands = false;
        pinned.terms = TermRule::Explicit(self.tau.to_vec());
        pinned
    }

    /// The fit with E0 pinned to `e0` and λ chosen by the data, from the
    /// reference shape.
    fn reference_fit(&mut self, e0: f64) -> Result<Optimum, FitError> {
        let pinned = self.pinned_params(e0);
        let r = solve_on_grid(
            self.data,
            &pinned,
            self.tau.to_vec(),
            Some(self.reference.clone()),
            self.set.as_ref(),
        )?;
        self.log(e0, &r);
        Ok(r)
    }

    /// The fit with E0 pinned to `e0` (Pa) at λ_p from the shape `from`;
    /// where it lies beyond 2σ of `best` (the best misfit so far and its
    /// noise variance), again from the reference shape, keeping the better
    /// (continuation alone can stall in a poor local minimum and raise a
    /// spurious wall). `None` when the model cannot reach that E0 at all.
    fn pinned(
        &mut self,
        e0: f64,
        from: &[f64],
        best: Option<(f64, f64)>,
    ) -> Result<Option<Step>, FitError> {
        let mut pinned = self.pinned_params(e0);
        pinned.lambda = Lambda::Fixed(self.lambda);
        pinned.coarse = true;
        let mut kept: Option<Optimum> = None;
        for start in [from.to_vec(), self.reference.clone()] {
            if let Some(k) = &kept {
                let beyond =
                    best.is_some_and(|(misfit, unit)| (k.misfit - misfit) / unit > TWO_SIGMA);
                if !beyond || start == from {
                    break;
                }
            }
            let trial = match solve_on_grid(
                self.data,
                &pinned,
                self.tau.to_vec(),
                Some(start),
                self.set.as_ref(),
            ) {
                Ok(t) => t,
                Err(FitError::Model(_)) => continue,
                Err(e) => return Err(e),
            };
            self.log(e0, &trial);
            if kept.as_ref().is_none_or(|b| trial.objective < b.objective) {
                kept = Some(trial);
            }
        }
        let Some(trial) = kept else {
            return Ok(None);
        };
        let m = &trial.model;
        Ok(Some(Step {
            e0,
            misfit: trial.misfit,
            noise_variance: trial.noise * trial.noise,
            shape: shape(m.strengths.iter(), m.static_modulus),
            prony: Prony::new(m.glassy_modulus, m.strengths.clone(), m.tau.clone()).ok(),
        }))
    }

    /// Keeps the runs of a pinned fit at `e0`.
    fn log(&mut self, e0: f64, fit: &Optimum) {
        self.runs.extend(fit.runs.iter().cloned().map(|mut run| {
            run.stage = format!("scale profile E0 = {e0:.3e} Pa: {}", run.stage);
            run
        }));
    }

    /// The 2σ interval (module doc, step 3): `None` at an end that reaches
    /// the range's edge. Adds the bisection steps to `steps`.
    fn interval(
        &mut self,
        steps: &mut Vec<Step>,
        range: [f64; 2],
    ) -> Result<(Option<f64>, Option<f64>), FitError> {
        let mut ends = [None, None];
        for (k, end) in ends.iter_mut().enumerate() {
            let best = best_step(steps);
            let (unit, min) = (steps[best].noise_variance, steps[best].misfit);
            let delta = |s: &Step| (s.misfit - min) / unit;
            // The outermost step within 2σ on this side, and the next step
            // outward (beyond 2σ), if any.
            let within: Vec<usize> = (0..steps.len())
                .filter(|&i| delta(&steps[i]) <= TWO_SIGMA)
                .collect();
            let inner = if k == 0 {
                within[0]
            } else {
                within[within.len() - 1]
            };
            let outer = if k == 0 {
                inner.checked_sub(1)
            } else {
                Some(inner + 1).filter(|&i| i < steps.len())
            };
            let Some(outer) = outer else {
                let edge = if k == 0 { range[0] } else { range[1] };
                *end = (steps[inner].e0 != edge).then_some(steps[inner].e0);
                continue;
            };
            // Beyond the crossing the profile stays below DECISIVE up to
            // the range's edge: a plateau the noise lifts just over 2σ, not
            // a bound the data set; that end is open.
            let beyond = if k == 0 {
                0..inner
            } else {
                inner + 1..steps.len()
            };
            let edge_reached = if k == 0 {
                steps[0].e0 <= range[0]
            } else {
                steps[steps.len() - 1].e0 >= range[1]
            };
            if edge_reached && steps[beyond].iter().all(|s| delta(s) < DECISIVE) {
                continue;
            }
            let mut from = steps[inner].shape.clone();
            let (mut a, mut b) = (
                (steps[inner].e0, delta(&steps[inner])),
                (steps[outer].e0, delta(&steps[outer])),
            );
            for _ in 0..BISECTIONS {
                let middle = (a.0 * b.0).sqrt();
                let Some(step) = self.pinned(middle, &from, Some((min, unit)))? else {
                    break;
                };
                let d = (step.misfit - min) / unit;
                if d <= TWO_SIGMA {
                    a = (middle, d);
                    from = step.shape.clone();
                } else {
                    b = (middle, d);
                }
                steps.push(step);
            }
            steps.sort_by(|x, y| x.e0.total_cmp(&y.e0));
            let t = ((TWO_SIGMA - a.1) / (b.1 - a.1)).clamp(0.0, 1.0);
            *end = Some((a.0.ln() + t * (b.0.ln() - a.0.ln())).exp());
        }
        Ok((ends[0], ends[1]))
    }
}

/// Where to pin the result (module doc, step 5), given the profile's
/// `steps` (by E0), the `best` one, the 2σ `interval` (open ends closed by
/// the range) and whether the fit's own E0 lies within one noise unit of
/// the minimum; None keeps the fit's own optimum.
fn refit_at(
    steps: &[Step],
    best: usize,
    interval: [f64; 2],
    own_is_estimate: bool,
) -> Option<Refit> {
    if best == 0 || best + 1 == steps.len() {
        // One-sided: the misfit falls to an end of the profiled range (the
        // model's own limit, such as the R/3 contact) or is flat there; the
        // minimum is an edge, the worst point to report. The centre in
        // ln E0 of the 2σ interval is the estimate; the interval stays in
        // the record and the bands.
        let centre = (interval[0] * interval[1]).sqrt();
        let near = (0..steps.len())
            .min_by(|&a, &b| {
                let d = |i: usize| (steps[i].e0 / centre).ln().abs();
                d(a).total_cmp(&d(b))
            })
            .unwrap_or(best);
        return Some(Refit {
            e0: centre,
            shape: steps[near].shape.clone(),
            centre: true,
        });
    }
    if own_is_estimate {
        return None;
    }
    Some(Refit {
        e0: vertex(steps, best).clamp(interval[0], interval[1]),
        shape: steps[best].shape.clone(),
        centre: false,
    })
}

/// Index of the step with the smallest misfit.
fn best_step(steps: &[Step]) -> usize {
    (0..steps.len())
        .min_by(|&a, &b| steps[a].misfit.total_cmp(&steps[b].misfit))
        .unwrap_or(0)
}

/// The minimum in ln E0 of the parabola through the best step and its
/// neighbours (the best step's E0 at an end, or where the parabola opens
/// downward), kept between the neighbours.
fn vertex(steps: &[Step], best: usize) -> f64 {
    if best == 0 || best + 1 >= steps.len() {
        return steps[best].e0;
    }
    let (x0, x1, x2) = (
        steps[best - 1].e0.ln(),
        steps[best].e0.ln(),
        steps[best + 1].e0.ln(),
    );
    let (y0, y1, y2) = (
        steps[best - 1].misfit,
        steps[best].misfit,
        steps[best + 1].misfit,
    );
    let numerator = (x1 - x0).powi(2) * (y1 - y2) - (x1 - x2).powi(2) * (y1 - y0);
    let denominator = (x1 - x0) * (y1 - y2) - (x1 - x2) * (y1 - y0);
    if denominator == 0.0 || !denominator.is_finite() {
        return steps[best].e0;
    }
    let x = x1 - 0.5 * numerator / denominator;
    x.clamp(x0, x2).exp()
}

/// "data" when the interval, an open end closed by the range in which the
/// model holds, spans at most [`SCALE_FACTOR_LIMIT`]² (a factor
/// [`SCALE_FACTOR_LIMIT`] either side of its geometric centre): the data and
/// the model's own limits then fix the scale. The reported E0 lies inside.
fn status(low: Option<f64>, high: Option<f64>, range: [f64; 2]) -> &'static str {
    let (l, h) = (low.unwrap_or(range[0]), high.unwrap_or(range[1]));
    if h / l <= SCALE_FACTOR_LIMIT * SCALE_FACTOR_LIMIT {
        "data"
    } else {
        "undetermined"
    }
}

/// The anchors that fix the scale, and what each needs.
pub(crate) const ANCHORS: &str = "anchor the scale in the scene's [fit] with one of: E0 = … \
     (the static modulus in Pa, from a tensile, compression or indentation test at low rate), \
     E_at = { omega = …, E = … } (|E*| in Pa at one angular frequency in rad/s, e.g. one DMA \
     point) or contact_radius = { v = …, r = … } (a contact radius in m measured at one speed \
     in m/s, e.g. through a transparent ball)";

/// What the profile says, in words.
fn reason(r: &ScaleRecord) -> String {
    let end = |x: Option<f64>, edge: f64, side: &str| match x {
        Some(x) => format!("{x:.3e} Pa"),
        None => format!("the {side} E0 the model allows ({edge:.3e} Pa)"),
    };
    let interval = format!(
        "E0 from {} to {} describes the data as well at 2σ (profile Δχ² ≤ 4 with the shape \
         refitted at each E0)",
        end(r.low, r.range[0], "lowest"),
        end(r.high, r.range[1], "highest")
    );
    if r.status == "data" {
        format!(
            "the data determine the modulus scale: E0 = {:.3e} Pa; {interval}",
            r.static_modulus
        )
    } else {
        format!(
            "the data do not determine the modulus scale: {interval}, more than a factor {} \
             either side of its centre (the fit's E0 = {:.3e} Pa); {ANCHORS}",
            SCALE_FACTOR_LIMIT, r.static_modulus
        )
    }
}

/// The record when no E0 satisfies the model's assumptions.
fn no_range(e0: f64, range: [f64; 2]) -> ScaleRecord {
    ScaleRecord {
        status: "undetermined",
        static_modulus: e0,
        low: None,
        high: None,
        range,
        profile: Vec::new(),
        reason: format!(
            "no E0 keeps the rubbery contact within R/3 below a tenth of E1_max (E0 would need \
             at least {:.3e} Pa): check geometry.radius and geometry.load; {ANCHORS}",
            range[0]
        ),
    }
}

/// ln(H_k/E0): a material's shape in the pinned parametrisation.
fn shape<'h>(strengths: impl Iterator<Item = &'h f64>, static_modulus: f64) -> Vec<f64> {
    strengths.map(|h| (h / static_modulus).ln()).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Steps at `e0` (Pa) with misfits `misfit` (noise variance 1), the
    /// shape ln(H/E0) = [ln E0] to tell them apart.
    fn steps(points: &[(f64, f64)]) -> Vec<Step> {
        points
            .iter()
            .map(|&(e0, misfit)| Step {
                e0,
                misfit,
                noise_variance: 1.0,
                shape: vec![e0.ln()],
                prony: None,
            })
            .collect()
    }

    /// The held-out set's profile: least at the range's lower end (the R/3
    /// limit, 0.75 MPa), Δχ² = 4 at 1.67 MPa. The estimate is the centre
    /// of 0.75 … 1.67 MPa in ln E0, 1.12 MPa, not the edge.
    #[test]
    fn a_one_sided_profile_reports_the_interval_centre() {
        let s = steps(&[(0.75e6, 0.0), (1.0e6, 0.8), (1.4e6, 2.5), (2.4e6, 9.0)]);
        let r = refit_at(&s, best_step(&s), [0.75e6, 1.67e6], true).unwrap();
        assert!(r.centre);
        assert!((r.e0 / (0.75e6f64 * 1.67e6).sqrt() - 1.0).abs() < 1e-12);
        // Started from the step nearest the centre (1.0 MPa).
        assert_eq!(r.shape, vec![1.0e6f64.ln()]);
        // Flat up to the upper end: the same rule.
        let s = steps(&[(1e5, 9.0), (3e5, 1.0), (1e6, 0.1), (3e6, 0.0)]);
        let r = refit_at(&s, best_step(&s), [2e5, 3e6], false).unwrap();
        assert!(r.centre && (r.e0 / (2e5f64 * 3e6).sqrt() - 1.0).abs() < 1e-12);
    }

    /// A minimum inside the profile: the fit's own E0 when it lies within
    /// one noise unit, else the parabola's vertex.
    #[test]
    fn an_inside_minimum_is_the_estimate() {
        // Misfit (ln E0 − ln 1e6)² sampled at half decades: vertex at 1 MPa.
        let at = |e0: f64| (e0, (e0 / 1e6).ln().powi(2));
        let s = steps(&[at(1e5), at(3.2e5), at(1.1e6), at(3.5e6), at(1e7)]);
        let best = best_step(&s);
        assert!(refit_at(&s, best, [3e5, 3e6], true).is_none());
        let r = refit_at(&s, best, [3e5, 3e6], false).unwrap();
        assert!(!r.centre && (r.e0 / 1e6 - 1.0).abs() < 1e-9, "{}", r.e0);
    }
}
