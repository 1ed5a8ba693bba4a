//! Where the joint fit starts from.
//!
//! Its law (chosen by the driver: the one asked for, or for
//! `shift = "auto"` [`super::law`]'s choice on both parts) and its shifts
//! at every temperature of either part, relative to the joint T_ref:
//!
//! - where the DMA isotherms alone determine a shift ([`super::alone`]),
//!   their measured shift, moved onto the rolling fit's axis by the mean
//!   difference at the temperatures both cover (the DMA part's values
//!   as they are where the rolling data cover none);
//! - elsewhere the rolling fit alone's shift: its law, or its free shifts
//!   interpolated linearly in T between the rolling temperatures;
//! - a temperature neither part determines (outside the rolling
//!   temperatures and undetermined by the isotherms; with a law, farther
//!   than one neighbour spacing beyond them) is refused, named.
//!
//! Its spectrum: the DMA master curve's where the isotherms make one,
//! else a smooth series fitted to the DMA points at the starting shifts,
//! moved onto the joint τ grid, which covers the
//! band the rolling speeds probe (at the starting shifts) and the DMA's
//! reduced frequencies.

use rollfit_model::modulus::{Arrhenius, Wlf};
use rollfit_model::{Prony, ViscoelasticModulus};

use crate::data::Measurements;
use crate::error::FitError;
use crate::master::{MasterCurve, fit_prony};
use crate::parametrization::Parametrization;
use crate::params::{FrictionFactor, ShiftKind, ShiftSettings, TermRule, ValidFitParams};
use crate::report::FitReport;
use crate::shift::{ShiftParam, ShiftRecord, distinct_temperatures, index_of};
use crate::tau_grid::{probed_band, relaxation_times};
use crate::temperature_set::ShiftStart;

use super::DmaRows;
use super::alone::DmaAlone;

/// A strength below this fraction of the largest one is raised to it in
/// the start: ln H of an empty term would be −∞.
const START_FLOOR: f64 = 1e-3;

/// Where the joint fit starts.
pub(crate) struct JointStart {
    /// The shift over every temperature of either part, with its start
    /// (and ln κ = 0 last when κ is fitted).
    pub shift: ShiftStart,
    /// The joint τ grid, s.
    pub tau: Vec<f64>,
    /// The material's θ on it.
    pub material: Vec<f64>,
    /// The law fitted.
    pub kind: ShiftKind,
    /// The joint reference temperature, °C.
    pub t_ref: f64,
    /// How the start was found.
    pub notes: Vec<String>,
}

/// The law and reference temperature the driver chose for the joint fit,
/// and the rolling fit alone under that law.
pub(crate) struct StartChoice<'a> {
    /// The joint law (never `Auto`).
    pub kind: ShiftKind,
    /// The joint reference temperature before free shifts move it to a
    /// measured one, °C.
    pub t_ref: f64,
    /// The rolling part fitted alone.
    pub rolling: &'a FitReport,
}

/// The start of the joint fit of `data` (with temperatures) and `rows`
/// from the parts alone (module doc). A temperature neither part
/// determines is refused as the DMA file's problem, named.
pub(crate) fn joint_start(
    data: &Measurements,
    rows: &DmaRows,
    params: &ValidFitParams,
    alone: &DmaAlone,
    choice: StartChoice,
) -> Result<JointStart, FitError> {
    let mut temps = distinct_temperatures(data);
    for t in rows.temperatures() {
        if index_of(&temps, t).is_none() {
            temps.push(t);
        }
    }
    temps.sort_by(f64::total_cmp);
    let mut notes = Vec::new();
    let kind = choice.kind;
    let mut t_ref = choice.t_ref;
    if kind == ShiftKind::Free && index_of(&temps, t_ref).is_none() {
        let nearest = temps
            .iter()
            .copied()
            .min_by(|a, b| (a - t_ref).abs().total_cmp(&(b - t_ref).abs()))
            .unwrap_or(t_ref);
        notes.push(format!(
            "T_ref = {nearest} °C, the measured temperature nearest {t_ref} °C: free shifts are \
             fixed at a measured temperature"
        ));
        t_ref = nearest;
    }
    let rolling = RollingShift::of(data, choice.rolling, kind);
    let log_shift =
        start_shifts(&temps, t_ref, alone, &rolling).map_err(|open| FitError::DmaData {
            file: rows.source().to_string(),
            why: undetermined_message(&open, alone, &rolling),
        })?;
    if alone.master.is_none() {
        notes.push(format!(
            "DMA part: its isotherms alone determine no shift ({}); the joint fit starts from \
             the rolling fit's shifts and fits every shift to both parts",
            alone.undetermined.as_deref().unwrap_or("no overlap")
        ));
    }
    let settings = ShiftSettings {
        kind,
        t_ref: Some(t_ref),
        ..params.shift.clone()
    };
    let param = ShiftParam::over(data, temps.clone(), &settings)?;
    let mut theta = param.theta_of_log_shifts(&log_shift);
    if params.friction_factor == FrictionFactor::Free {
        theta.push(0.0);
    }
    let shift = ShiftStart {
        param,
        theta: Vec::new(),
        range: (1.0, 1.0),
        notes: Vec::new(),
    }
    .with_theta(data, theta);
    let (prony, dma_range) = match &alone.master {
        Some(master) => (master.fit.prony.clone(), master_shift_range(master)),
        None => shifted_master(rows, &temps, &log_shift)?,
    };
    let band = probed_band(
        &params.setup,
        shift.range,
        prony.static_modulus(),
        prony.glassy_modulus().min(params.e1_max),
    );
    let band = (band.0.min(dma_range.0), band.1.max(dma_range.1));
    let rule = match &params.terms {
        TermRule::Auto => TermRule::PerDecade(2.0),
        rule => rule.clone(),
    };
    let tau = relaxation_times(band, &rule);
    let material = material_on(&tau, params, &prony);
    Ok(JointStart {
        shift,
        tau,
        material,
        kind,
        t_ref,
        notes,
    })
}

/// "WLF", "Arrhenius" or "free", as the report's warnings name laws.
pub(crate) fn kind_name(kind: ShiftKind) -> &'static str {
    match kind {
        ShiftKind::Wlf => "WLF",
        ShiftKind::Arrhenius => "Arrhenius",
        ShiftKind::Free | ShiftKind::Auto => "free",
    }
}

/// The rolling fit alone's shift, as the start reads it.
struct RollingShift {
    /// Its record (None: rolling data at one temperature).
    record: Option<ShiftRecord>,
    /// The temperatures it covers, °C: its measured ones, a law one
    /// neighbour spacing beyond them.
    covered: (f64, f64),
}

impl RollingShift {
    fn of(data: &Measurements, rolling: &FitReport, kind: ShiftKind) -> RollingShift {
        let temps = distinct_temperatures(data);
        let (lo, hi) = (temps[0], temps[temps.len() - 1]);
        let record = rolling.shift.clone();
        let law = matches!(
            (kind, &record),
            (ShiftKind::Wlf, Some(ShiftRecord::Wlf { .. }))
                | (ShiftKind::Arrhenius, Some(ShiftRecord::Arrhenius { .. }))
        );
        let reach = if law {
            temps.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max)
        } else {
            0.0
        };
        RollingShift {
            record,
            covered: (lo - reach, hi + reach),
        }
    }

    /// log10 a_T at `t` about the rolling fit's T_ref where it covers `t`
    /// (0 for data at one temperature, at that temperature).
    fn at(&self, t: f64) -> Option<f64> {
        if !(self.covered.0..=self.covered.1).contains(&t) {
            return None;
        }
        let Some(record) = &self.record else {
            return Some(0.0);
        };
        match record {
            ShiftRecord::Wlf { t_ref, c1, c2, .. } => {
                Wlf::new(*t_ref, *c1, *c2).ok()?.log10_shift(t).ok()
            }
            ShiftRecord::Arrhenius {
                t_ref,
                activation_energy,
                ..
            } => Arrhenius::new(*t_ref, *activation_energy)
                .ok()?
                .log10_shift(t)
                .ok(),
            ShiftRecord::Free { log_shift, .. } => {
                let x: Vec<f64> = log_shift.iter().map(|s| s.temperature).collect();
                let y: Vec<f64> = log_shift.iter().map(|s| s.log_shift).collect();
                Some(linear(&x, &y, t))
            }
        }
    }
}

/// Linear interpolation of ascending (x, y) at `at` (inside x).
fn linear(x: &[f64], y: &[f64], at: f64) -> f64 {
    if x.len() == 1 {
        return y[0];
    }
    let k = x.partition_point(|&xi| xi <= at).clamp(1, x.len() - 1);
    let w = (at - x[k - 1]) / (x[k] - x[k - 1]);
    y[k - 1] * (1.0 - w) + y[k] * w
}

/// log10 a_T at each of `temps` relative to `t_ref` (module doc): the DMA
/// part's determined shifts on their own reference where they reach
/// `t_ref`, else moved onto the rolling fit's; elsewhere the rolling fit's.
/// Err: the temperatures neither part determines.
fn start_shifts(
    temps: &[f64],
    t_ref: f64,
    alone: &DmaAlone,
    rolling: &RollingShift,
) -> Result<Vec<f64>, Vec<f64>> {
    let determined: Vec<(f64, f64)> = temps
        .iter()
        .filter_map(|&t| alone.determined_shift(t).map(|s| (t, s)))
        .collect();
    // The DMA part's value at T_ref where its determined isotherms reach
    // it (its law, or its shifts interpolated).
    let dma_ref = match (&alone.master, determined.first(), determined.last()) {
        (Some(m), Some(lo), Some(hi)) if (lo.0..=hi.0).contains(&t_ref) => m.shift.law_at(t_ref),
        _ => None,
    };
    let rolling_ref = rolling.at(t_ref);
    let common: Vec<(f64, f64)> = determined
        .iter()
        .filter_map(|&(t, d)| rolling.at(t).map(|r| (d, r)))
        .collect();
    let mean = |f: &dyn Fn(f64, f64) -> f64| {
        (!common.is_empty())
            .then(|| common.iter().map(|&(d, r)| f(d, r)).sum::<f64>() / common.len() as f64)
    };
    // Both parts on the joint axis, 0 at T_ref: x = d + c_dma, x = r + c_rolling.
    let (c_dma, c_rolling) = match (dma_ref, rolling_ref) {
        (Some(d0), Some(r0)) => (Some(-d0), Some(-r0)),
        (Some(d0), None) => (Some(-d0), mean(&|d, r| d - d0 - r)),
        (None, Some(r0)) => (mean(&|d, r| r - r0 - d), Some(-r0)),
        (None, None) => (None, None),
    };
    let mut open = Vec::new();
    let values: Vec<f64> = temps
        .iter()
        .map(|&t| {
            let dma = alone.determined_shift(t).zip(c_dma).map(|(d, c)| d + c);
            let from_rolling = rolling.at(t).zip(c_rolling).map(|(r, c)| r + c);
            dma.or(from_rolling).unwrap_or_else(|| {
                open.push(t);
                0.0
            })
        })
        .collect();
    if open.is_empty() {
        Ok(values)
    } else {
        Err(open)
    }
}

/// Why the temperatures `open` have no shift: neither the isotherms'
/// overlaps nor the rolling data reach them.
fn undetermined_message(open: &[f64], alone: &DmaAlone, rolling: &RollingShift) -> String {
    let list: Vec<String> = open.iter().map(|t| format!("{t}")).collect();
    let dma = match &alone.undetermined {
        Some(why) => format!("the isotherms alone determine no shift ({why})"),
        None => "their isotherms do not overlap the isotherms whose shifts are determined".into(),
    };
    format!(
        "the shift at {} °C is determined by neither part: {dma}, and the rolling data cover \
         {} to {} °C only; measure DMA isotherms that overlap their neighbours there (closer in \
         temperature or over a wider frequency range) or rolling data at that temperature",
        list.join(", "),
        rolling.covered.0,
        rolling.covered.1
    )
}

/// The DMA points' reduced frequencies (rad/s) at the DMA master's shifts.
fn master_shift_range(master: &MasterCurve) -> (f64, f64) {
    master
        .points
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
            (lo.min(p.reduced_omega), hi.max(p.reduced_omega))
        })
}

/// The DMA points at the start's shifts `log_shift` at `temps`, with a
/// smooth causal Prony series fitted to them ([`fit_prony`]) and their
/// range of reduced frequencies (rad/s): the DMA master curve on the
/// rolling data's shifts, where the isotherms alone give none. Why not the
/// rolling fit's own spectrum: without an anchor it places the modulus
/// scale only weakly (μ goes roughly as tan δ |E|^(−1/3)), and started
/// off the DMA moduli the free shifts slide the isotherms along the curve
/// to where its modulus matches theirs, decades from the truth.
fn shifted_master(
    rows: &DmaRows,
    temps: &[f64],
    log_shift: &[f64],
) -> Result<(Prony, (f64, f64)), FitError> {
    let mut points: Vec<(f64, f64, f64)> = rows
        .points()
        .map(|(t, w, e1, e2)| {
            let x = index_of(temps, t).map_or(0.0, |k| log_shift[k]);
            (w * 10f64.powf(x), e1, e2)
        })
        .collect();
    points.sort_by(|a, b| a.0.total_cmp(&b.0));
    let omega: Vec<f64> = points.iter().map(|p| p.0).collect();
    let storage: Vec<f64> = points.iter().map(|p| p.1).collect();
    let loss: Vec<f64> = points.iter().map(|p| p.2).collect();
    let fit = fit_prony(&omega, &storage, &loss)?;
    Ok((fit.prony, (omega[0], omega[omega.len() - 1])))
}

/// The DMA part's spectrum on the grid `tau`: each of its strengths added
/// to the nearest τ of the grid (in ln τ), empty terms raised to
/// [`START_FLOOR`] of the largest, as θ of the joint parametrisation.
fn material_on(tau: &[f64], params: &ValidFitParams, prony: &rollfit_model::Prony) -> Vec<f64> {
    let mut h = vec![0.0; tau.len()];
    for (&strength, &t) in prony.strengths().iter().zip(prony.relaxation_times()) {
        let nearest = (0..tau.len())
            .min_by(|&a, &b| (tau[a] / t).ln().abs().total_cmp(&(tau[b] / t).ln().abs()))
            .unwrap_or(0);
        h[nearest] += strength;
    }
    let largest = h.iter().fold(0.0f64, |m, &x| m.max(x));
    for x in &mut h {
        *x = x.max(START_FLOOR * largest);
    }
    let e0 = prony.static_modulus().max(START_FLOOR * largest);
    Parametrization::new(tau.to_vec(), params.anchor).theta_of(e0, &h)
}
