//! What the DMA isotherms say alone, and where the joint fit starts from.
//!
//! The DMA part alone is what `rollfit master` makes of the file
//! ([`crate::master`]): shifts found by overlapping neighbouring
//! isotherms, a law fitted to them, and a smooth Prony series on the
//! shifted points. Its residuals in ln E′ and ln E″ give
//!
//!   χ²_DMA,alone = Σ r²/σ²,   σ² = Σ r²/(2N − p)  when σ is not given,
//!
//! p the Prony fit's effective parameters plus the law's (or the
//! determined free shifts'), which the compatibility test needs.
//!
//! The joint fit starts from that master curve: its law (for
//! `shift = "auto"`) and its shifts at every temperature of either part,
//! relative to the joint T_ref; its spectrum moved onto the joint τ grid,
//! which covers the band the rolling speeds probe (at the starting
//! shifts) and the DMA's reduced frequencies.

use rollfit_model::ViscoelasticModulus;

use crate::data::Measurements;
use crate::error::FitError;
use crate::master::{MasterCurve, MasterSettings, ShiftLaw, build_master_curve};
use crate::parametrization::Parametrization;
use crate::params::{FrictionFactor, ShiftKind, ShiftSettings, TermRule, ValidFitParams};
use crate::shift::{ShiftParam, distinct_temperatures, index_of};
use crate::tau_grid::{probed_band, relaxation_times};
use crate::temperature_set::ShiftStart;

use super::DmaRows;

/// A strength below this fraction of the largest one is raised to it in
/// the start: ln H of an empty term would be −∞.
const START_FLOOR: f64 = 1e-3;

/// The DMA isotherms fitted alone.
pub(crate) struct DmaAlone {
    /// The master curve of the isotherms.
    pub master: MasterCurve,
    /// Relative σ of E′ and E″.
    pub sigma: f64,
    /// Whether σ was given (`dma_sigma`) rather than estimated.
    pub sigma_given: bool,
    /// Σ r²/σ² of the master curve at the DMA points.
    pub chi2: f64,
    /// Effective parameters of the DMA fit alone.
    pub parameters: f64,
}

/// The master curve of `rows` and its χ² (module doc).
pub(crate) fn dma_alone(rows: &DmaRows, sigma: Option<f64>) -> Result<DmaAlone, FitError> {
    let settings = MasterSettings::default().check(rows.isotherms())?;
    let master = build_master_curve(rows.isotherms(), &settings)?;
    let prony = &master.fit.prony;
    let squares: f64 = master
        .points
        .iter()
        .map(|p| {
            let e = prony.modulus(p.reduced_omega);
            (e.re / p.storage).ln().powi(2) + (e.im / p.loss).ln().powi(2)
        })
        .sum();
    let shift = &master.shift;
    let law_parameters = match shift.law {
        ShiftLaw::Wlf => 2.0,
        ShiftLaw::Arrhenius => 1.0,
        ShiftLaw::WlfArrhenius => 3.0,
        ShiftLaw::Free | ShiftLaw::Auto => {
            shift.shifts.iter().filter(|s| s.determined).count() as f64 - 1.0
        }
    }
    .max(0.0);
    let parameters = master.fit.effective_parameters + law_parameters;
    let residuals = 2.0 * rows.len() as f64;
    let (sigma, sigma_given) = match sigma {
        Some(s) => (s, true),
        None => ((squares / (residuals - parameters).max(1.0)).sqrt(), false),
    };
    // A perfect series (synthetic data without noise) would give σ = 0:
    // the floor is the smallest σ `dma_sigma` accepts.
    let sigma = sigma.max(super::DMA_SIGMA_RANGE.0);
    Ok(DmaAlone {
        chi2: squares / (sigma * sigma),
        master,
        sigma,
        sigma_given,
        parameters,
    })
}

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

/// The start of the joint fit of `data` (with temperatures) and `rows`
/// from the DMA part alone (module doc).
pub(crate) fn joint_start(
    data: &Measurements,
    rows: &DmaRows,
    params: &ValidFitParams,
    alone: &DmaAlone,
) -> Result<JointStart, FitError> {
    let mut temps = distinct_temperatures(data);
    for t in rows.temperatures() {
        if index_of(&temps, t).is_none() {
            temps.push(t);
        }
    }
    temps.sort_by(f64::total_cmp);
    let mut notes = Vec::new();
    let master_shift = &alone.master.shift;
    let kind = match (temps.len(), params.shift.kind) {
        (1, _) => ShiftKind::Free,
        (_, ShiftKind::Auto) => {
            let kind = match master_shift.law {
                ShiftLaw::Wlf => ShiftKind::Wlf,
                ShiftLaw::Arrhenius => ShiftKind::Arrhenius,
                _ => ShiftKind::Free,
            };
            notes.push(format!(
                "shift law {}: the law the DMA isotherms alone choose ({}: {})",
                kind_name(kind),
                master_shift.law.name(),
                master_shift.reason
            ));
            kind
        }
        (_, kind) => kind,
    };
    let mut t_ref = params.shift.t_ref.unwrap_or(master_shift.t_ref);
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
    let settings = ShiftSettings {
        kind,
        t_ref: Some(t_ref),
        ..params.shift.clone()
    };
    let param = ShiftParam::over(data, temps.clone(), &settings)?;
    let log_shift = start_shifts(&temps, t_ref, alone);
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
    let prony = &alone.master.fit.prony;
    let rolling = probed_band(
        &params.setup,
        shift.range,
        prony.static_modulus(),
        prony.glassy_modulus().min(params.e1_max),
    );
    let dma_range = master_shift_range(alone);
    let band = (rolling.0.min(dma_range.0), rolling.1.max(dma_range.1));
    let rule = match &params.terms {
        TermRule::Auto => TermRule::PerDecade(2.0),
        rule => rule.clone(),
    };
    let tau = relaxation_times(band, &rule);
    let material = material_on(&tau, params, prony);
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

/// log10 a_T at each of `temps` relative to `t_ref` from the DMA part's
/// law (its applied shifts interpolated for a free law); where it has no
/// value (outside a free law's isotherms, below the WLF divergence) the
/// nearest temperature's.
fn start_shifts(temps: &[f64], t_ref: f64, alone: &DmaAlone) -> Vec<f64> {
    let law = &alone.master.shift;
    let known: Vec<(f64, f64)> = temps
        .iter()
        .chain(std::iter::once(&t_ref))
        .filter_map(|&t| law.law_at(t).map(|s| (t, s)))
        .collect();
    let at = |t: f64| {
        law.law_at(t).unwrap_or_else(|| {
            known
                .iter()
                .min_by(|a, b| (a.0 - t).abs().total_cmp(&(b.0 - t).abs()))
                .map_or(0.0, |k| k.1)
        })
    };
    let reference = at(t_ref);
    temps.iter().map(|&t| at(t) - reference).collect()
}

/// The DMA points' reduced frequencies (rad/s) at the DMA part's shifts.
fn master_shift_range(alone: &DmaAlone) -> (f64, f64) {
    alone
        .master
        .points
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
            (lo.min(p.reduced_omega), hi.max(p.reduced_omega))
        })
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
