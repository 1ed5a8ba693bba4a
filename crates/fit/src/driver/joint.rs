//! The joint fit of DMA isotherms and rolling friction ([`crate::joint`]
//! states the method): the DMA part alone, the rolling part alone, both
//! together from the DMA part's start, and the account of the parts.

use std::time::Instant;

use rollfit_model::Prony;

use crate::analysis::probed_window;
use crate::condense::condense;
use crate::data::Measurements;
use crate::error::FitError;
use crate::joint::alone::{DmaAlone, dma_alone};
use crate::joint::consistency::{
    PartShare, Parts, compatibility, friction_factor, residual_ranges,
};
use crate::joint::law::joint_law;
use crate::joint::start::{JointStart, StartChoice, joint_start};
use crate::joint::{DmaFitPoint, DmaRows, JointRecord, JointSigma, PartChi2, moduli_at};
use crate::master::DEFAULT_T_REF;
use crate::params::{FrictionFactor, ShiftKind, ValidFitParams};
use crate::report::{FitReport, RunRecord};
use crate::shift::{distinct_temperatures, index_of};

use super::assemble::{GridOutcome, Whole, assemble, fitted_friction, plausibility_warnings};
use super::terms::terms_record;
use super::{fit_measured, fit_on_grid};

/// The DMA part alone. What is wrong with the isotherms as a whole is the
/// DMA file's problem: the message names that file, not the rolling data's.
fn dma_part_alone(dma: &DmaRows, sigma: Option<f64>) -> Result<DmaAlone, FitError> {
    dma_alone(dma, sigma).map_err(|e| match e {
        FitError::InsufficientData(why) => FitError::DmaData {
            file: dma.source().to_string(),
            why,
        },
        other => other,
    })
}

/// The joint fit of `rows` and the DMA isotherms of `params`.
pub(super) fn fit_joint(
    rows: &Measurements,
    params: &ValidFitParams,
) -> Result<FitReport, FitError> {
    let clock = Instant::now();
    let dma = params
        .dma
        .clone()
        .ok_or(FitError::Internal("a joint fit without DMA data"))?;
    let rows = with_temperature(rows, params)?;
    let condensed = condense(&rows)?;
    let data = condensed.as_ref().map_or(&rows, |c| &c.data);
    let alone = dma_part_alone(&dma, params.dma_sigma)?;
    let (start, rolling_alone) = start_from_parts(data, &dma, params, &alone)?;
    let (weighted, rolling_sigma) = weighted_rows(data, &rolling_alone)?;
    let rolling_unit = rolling_sigma.map_or(1.0, |s| s * s);
    let mut joint = params.clone();
    joint.dma_sigma = Some(alone.sigma);
    joint.starts = 1;
    joint.shift.kind = start.kind;
    joint.shift.t_ref = Some(start.t_ref);
    let outcome = fit_on_grid(
        &weighted,
        &joint,
        start.tau.clone(),
        Some(start.material.clone()),
        Some(&start.shift),
    )?;
    // A part alone fits its own rows at least as well as the joint
    // optimum does, which is one of its candidates (up to κ): an alone fit
    // that stopped above it (a local minimum; rows that κ alone explains)
    // counts at the joint's value, so that Δχ² measures the sharing only.
    let joint_rolling_chi2 = rolling_chi2(&weighted, &outcome.fit);
    let joint_dma_chi2 = outcome.fit.misfit - joint_rolling_chi2;
    let parts = Parts {
        rolling_alone: (
            (rolling_alone.misfit / rolling_unit).min(joint_rolling_chi2),
            rolling_alone.effective_parameters,
        ),
        dma_alone: (alone.chi2.min(joint_dma_chi2), alone.parameters),
        joint: (outcome.fit.misfit, outcome.fit.effective_parameters),
        estimated_dof: estimated_dof(
            (
                data.len(),
                rolling_sigma.is_some(),
                rolling_alone.effective_parameters,
            ),
            (2 * dma.len(), !alone.sigma_given, alone.parameters),
        ),
        shares: [
            PartShare {
                joint: joint_rolling_chi2,
                rows: data.len(),
                sigma: relative_sigma(&weighted),
            },
            PartShare {
                joint: joint_dma_chi2,
                rows: 2 * dma.len(),
                sigma: alone.sigma,
            },
        ],
    };
    let record = JointAccount {
        data: &weighted,
        dma: &dma,
        params: &joint,
        alone: &alone,
        rolling_sigma,
        parts,
    }
    .record(&outcome)?;
    let plausibility = plausibility_warnings(
        &weighted,
        weighted.friction(),
        &joint,
        &outcome.fit,
        &outcome.window,
    )?;
    let condensed = match &condensed {
        Some(c) => Some((c, fitted_friction(&rows, &joint, &outcome.fit)?)),
        None => None,
    };
    // What the user must know goes to the warnings: incompatible parts and
    // an unexplained κ (the record and the summary state the rest).
    let mut notes = start.notes;
    if !record.compatibility.compatible {
        notes.push(record.compatibility.verdict.clone());
    }
    if let Some(k) = record.friction_factor.as_ref().filter(|k| k.unexplained) {
        notes.push(format!("friction factor: {}", k.verdict));
    }
    let terms = terms_record(&outcome.fit.model.tau, &params.terms, Vec::new());
    let mut report = assemble(Whole {
        data: &weighted,
        params: &joint,
        set_notes: notes,
        shift_choice: None,
        grid: outcome,
        terms,
        cross_check: None,
        plausibility,
        condensed,
        wall_time_s: 0.0,
    });
    mark_incompatible(&mut report, &record);
    report.runs = rolling_runs(rolling_alone.runs, report.runs);
    report.evaluations = report.runs.iter().map(|r| r.evaluations).sum();
    report.joint = Some(record);
    report.wall_time_s = clock.elapsed().as_secs_f64();
    if let Some(what) = report.first_non_finite() {
        return Err(FitError::NonFinite(what));
    }
    Ok(report)
}

/// The joint law and start, and the rolling part fitted alone under
/// that law ([`crate::joint::start`]).
fn start_from_parts(
    data: &Measurements,
    dma: &DmaRows,
    params: &ValidFitParams,
    alone: &DmaAlone,
) -> Result<(JointStart, FitReport), FitError> {
    let t_ref = reference_temperature(data, dma, params, alone);
    let (kind, rolling_alone, law_note) = rolling_and_law(data, params, alone, t_ref)?;
    let mut start = joint_start(
        data,
        dma,
        params,
        alone,
        StartChoice {
            kind,
            t_ref,
            rolling: &rolling_alone,
        },
    )?;
    start.notes.splice(0..0, law_note);
    Ok((start, rolling_alone))
}

/// The rows weighted by their σ: their own, or the rolling fit alone's
/// relative noise times μ (returned too) when they have no σ column.
fn weighted_rows(
    data: &Measurements,
    rolling_alone: &FitReport,
) -> Result<(Measurements, Option<f64>), FitError> {
    if data.sigma().is_some() {
        return Ok((data.clone(), None));
    }
    let s = rolling_alone.noise;
    let sigma = data.friction().iter().map(|m| s * m).collect();
    let weighted = Measurements::new(
        data.speeds().to_vec(),
        data.friction().to_vec(),
        Some(sigma),
        data.temperature().map(|t| t.to_vec()),
    )?;
    Ok((weighted, Some(s)))
}

/// The RMS of σ_i/μ_i over the weighted rows: their relative σ.
fn relative_sigma(weighted: &Measurements) -> f64 {
    let sigma = weighted.sigma().unwrap_or_default();
    let n = sigma.len().max(1) as f64;
    (sigma
        .iter()
        .zip(weighted.friction())
        .map(|(s, m)| (s / m).powi(2))
        .sum::<f64>()
        / n)
        .sqrt()
}

/// Σ ((μ_fit − μ)/σ)² over the rolling rows of `fit`.
fn rolling_chi2(weighted: &Measurements, fit: &super::optimum::Optimum) -> f64 {
    (0..weighted.len())
        .map(|i| {
            let sigma = weighted.sigma().map_or(1.0, |s| s[i]);
            ((fit.mu[i] - weighted.friction()[i]) / sigma).powi(2)
        })
        .sum()
}

/// Incompatible parts make a "good" verdict "poor", with the reason.
fn mark_incompatible(report: &mut FitReport, record: &JointRecord) {
    if record.compatibility.compatible {
        return;
    }
    let reason = format!(
        "the DMA and rolling parts are {}",
        record.compatibility.verdict
    );
    report.fit_quality.reasons.push(reason);
    if report.fit_quality.verdict == "good" {
        report.fit_quality.verdict = "poor";
    }
}

/// The rolling fit alone's runs, staged as such, before the joint fit's.
fn rolling_runs(alone: Vec<RunRecord>, joint: Vec<RunRecord>) -> Vec<RunRecord> {
    alone
        .into_iter()
        .map(|mut r| {
            r.stage = format!("rolling alone: {}", r.stage);
            r
        })
        .chain(joint)
        .collect()
}

/// The rows with a temperature: their own, or all at T_ref when the
/// rolling data have no `T` column (a joint fit places them on the DMA's
/// temperature axis).
fn with_temperature(
    rows: &Measurements,
    params: &ValidFitParams,
) -> Result<Measurements, FitError> {
    if rows.temperature().is_some() {
        return Ok(rows.clone());
    }
    let t = params.shift.t_ref.ok_or_else(|| {
        FitError::setting(
            "T_ref",
            "the rolling data have no T column: a joint fit with DMA data needs the \
             temperature of the rolling measurement (add a T column, or give T_ref, the \
             temperature the rolling data were measured at)",
        )
    })?;
    Measurements::new(
        rows.speeds().to_vec(),
        rows.friction().to_vec(),
        rows.sigma().map(|s| s.to_vec()),
        Some(vec![t; rows.len()]),
    )
}

/// The joint T_ref, °C: the given one, else the DMA master's, else
/// 20 °C where the temperatures of both parts reach it, else the one of
/// them nearest to it.
fn reference_temperature(
    data: &Measurements,
    dma: &DmaRows,
    params: &ValidFitParams,
    alone: &DmaAlone,
) -> f64 {
    if let Some(t) = params.shift.t_ref {
        return t;
    }
    if let Some(master) = &alone.master {
        return master.shift.t_ref;
    }
    let mut temps = distinct_temperatures(data);
    temps.extend(dma.temperatures());
    temps.sort_by(f64::total_cmp);
    let (lo, hi) = (temps[0], temps[temps.len() - 1]);
    if (lo..=hi).contains(&DEFAULT_T_REF) {
        return DEFAULT_T_REF;
    }
    temps
        .into_iter()
        .min_by(|a, b| {
            (a - DEFAULT_T_REF)
                .abs()
                .total_cmp(&(b - DEFAULT_T_REF).abs())
        })
        .unwrap_or(DEFAULT_T_REF)
}

/// The joint law, the rolling part fitted alone under it, and what the
/// choice says. The law asked for, or with `auto` the one both parts'
/// shifts support ([`crate::joint::law`], from the rolling fit's free
/// shifts; the rolling part is then fitted again under that law when it
/// is not free); with one temperature in all, free.
fn rolling_and_law(
    data: &Measurements,
    params: &ValidFitParams,
    alone: &DmaAlone,
    t_ref: f64,
) -> Result<(ShiftKind, FitReport, Option<String>), FitError> {
    let rolling_temps = distinct_temperatures(data);
    let all = alone
        .temperatures
        .iter()
        .filter(|&&t| index_of(&rolling_temps, t).is_none())
        .count()
        + rolling_temps.len();
    match (all, params.shift.kind) {
        (1, _) => {
            let rolling = rolling_fit(data, params, ShiftKind::Free, t_ref)?;
            return Ok((ShiftKind::Free, rolling, None));
        }
        (_, ShiftKind::Auto) => {}
        (_, kind) => return Ok((kind, rolling_fit(data, params, kind, t_ref)?, None)),
    }
    let free = (rolling_temps.len() > 1)
        .then(|| rolling_fit(data, params, ShiftKind::Free, t_ref))
        .transpose()?;
    let (kind, note) = joint_law(alone, free.as_ref().and_then(|f| f.shift.as_ref()), t_ref);
    let rolling = match free {
        Some(free) if kind == ShiftKind::Free => free,
        Some(free) => {
            let mut law = rolling_fit(data, params, kind, t_ref)?;
            law.runs = free
                .runs
                .into_iter()
                .map(|mut r| {
                    r.stage = format!("free shifts for the law: {}", r.stage);
                    r
                })
                .chain(law.runs)
                .collect();
            law
        }
        None => rolling_fit(data, params, kind, t_ref)?,
    };
    Ok((kind, rolling, Some(note)))
}

/// The rolling part fitted alone under `kind` about `t_ref`.
fn rolling_fit(
    data: &Measurements,
    params: &ValidFitParams,
    kind: ShiftKind,
    t_ref: f64,
) -> Result<FitReport, FitError> {
    fit_measured(data, None, &rolling_params(data, params, kind, t_ref))
}

/// The settings of the rolling part fitted alone: no DMA, the law `kind`
/// (at the joint T_ref unless free shifts need a rolling temperature), no
/// cross-check and no scale profile (its χ² is what the test needs).
fn rolling_params(
    data: &Measurements,
    params: &ValidFitParams,
    kind: ShiftKind,
    t_ref: f64,
) -> ValidFitParams {
    let mut single = params.clone();
    single.dma = None;
    single.dma_sigma = None;
    single.friction_factor = FrictionFactor::One;
    single.shift.cross_check = false;
    single.profile = false;
    single.evidence = true;
    single.shift.kind = kind;
    let rolling_temps = distinct_temperatures(data);
    single.shift.t_ref = match kind {
        ShiftKind::Free => rolling_temps
            .iter()
            .any(|&t| (t - t_ref).abs() < 1e-9)
            .then_some(t_ref),
        _ => Some(t_ref),
    };
    single
}

/// What the joint record is made from.
struct JointAccount<'a> {
    data: &'a Measurements,
    dma: &'a DmaRows,
    params: &'a ValidFitParams,
    alone: &'a DmaAlone,
    rolling_sigma: Option<f64>,
    parts: Parts,
}

impl JointAccount<'_> {
    /// The record at the joint optimum `outcome`.
    fn record(self, outcome: &GridOutcome) -> Result<JointRecord, FitError> {
        let fit = &outcome.fit;
        let m = &fit.model;
        let prony = Prony::new(m.glassy_modulus, m.strengths.clone(), m.tau.clone())?;
        let log_shift = |t: f64| {
            fit.shift
                .as_ref()
                .and_then(|s| s.log_shift_at(t))
                .unwrap_or(0.0)
        };
        let log_vertical = |t: f64| {
            self.params
                .shift
                .vertical
                .as_ref()
                .map_or(Ok(0.0), |v| v.log10_factor(t))
        };
        // Rolling rows: residuals at their contact frequencies.
        let temps = self.data.temperature().unwrap_or_default();
        let (mut rolling_omega, mut rolling_residuals) = (Vec::new(), Vec::new());
        let mut rolling_chi2 = 0.0;
        for i in 0..self.data.len() {
            let v = self.data.speeds()[i] * 10f64.powf(log_shift(temps[i]));
            let sigma = self.data.sigma().map_or(1.0, |s| s[i]);
            let r = (fit.mu[i] - self.data.friction()[i]) / sigma;
            rolling_chi2 += r * r;
            rolling_omega.push(probed_window(&self.params.setup, &prony, (v, v)).0);
            rolling_residuals.push(r);
        }
        let sigma = self.alone.sigma;
        let mut points = Vec::with_capacity(self.dma.len());
        let (mut omega, mut r1, mut r2) = (Vec::new(), Vec::new(), Vec::new());
        let mut dma_chi2 = 0.0;
        for (t, w, e1, e2) in self.dma.points() {
            let reduced = w * 10f64.powf(log_shift(t));
            let b = 10f64.powf(log_vertical(t)?);
            let (f1, f2) = moduli_at(m.static_modulus, &m.strengths, &m.tau, reduced);
            let (s1, s2) = ((b * f1 / e1).ln() / sigma, (b * f2 / e2).ln() / sigma);
            dma_chi2 += s1 * s1 + s2 * s2;
            omega.push(reduced);
            r1.push(s1);
            r2.push(s2);
            points.push(DmaFitPoint {
                temperature: t,
                omega: w,
                reduced_omega: reduced,
                storage: e1,
                loss: e2,
                storage_fit: b * f1,
                loss_fit: b * f2,
            });
        }
        let mut residual_ranges_all =
            residual_ranges("rolling", &rolling_omega, &rolling_residuals);
        residual_ranges_all.extend(residual_ranges("dma E′", &omega, &r1));
        residual_ranges_all.extend(residual_ranges("dma E″", &omega, &r2));
        let friction_factor = fit.friction_factor.map(|(k, s)| friction_factor(k, s));
        Ok(JointRecord {
            dma_source: self.dma.source().to_string(),
            dma_points: self.dma.len(),
            rolling_points: self.data.len(),
            sigma: JointSigma {
                dma: sigma,
                dma_source: given(self.alone.sigma_given),
                rolling: self.rolling_sigma,
                rolling_source: given(self.rolling_sigma.is_none()),
            },
            chi2: PartChi2 {
                rolling_joint: rolling_chi2,
                dma_joint: dma_chi2,
                rolling_alone: self.parts.rolling_alone.0,
                dma_alone: self.parts.dma_alone.0,
                rolling_alone_parameters: self.parts.rolling_alone.1,
                dma_alone_parameters: self.parts.dma_alone.1,
                joint_parameters: self.parts.joint.1,
            },
            dma_alone: self.alone.record(),
            compatibility: compatibility(&self.parts, fit.friction_factor.is_some()),
            friction_factor,
            residual_ranges: residual_ranges_all,
            dma: points,
            notes: Vec::new(),
        })
    }
}

/// Σ (N − p) over the parts, (N, estimated, p), whose σ was estimated.
fn estimated_dof(rolling: (usize, bool, f64), dma: (usize, bool, f64)) -> f64 {
    [rolling, dma]
        .iter()
        .filter(|(_, estimated, _)| *estimated)
        .map(|(n, _, p)| (*n as f64 - p).max(1.0))
        .sum()
}

/// "given" or "estimated".
fn given(yes: bool) -> String {
    if yes { "given" } else { "estimated" }.to_string()
}
