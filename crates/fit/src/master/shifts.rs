//! The shift factors of a set of isotherms: the pairs compared, the
//! determined shifts solved at once, the law chosen, the measured shifts
//! anchored at T_ref and the values applied (the module doc of
//! [`super`], steps 1–3).

use super::horizontal::{Domain, Superposable};
use super::temperature_law::{self, ArrheniusFit, WlfArrheniusFit, WlfFit};
use super::{Isotherm, ShiftLaw, ValidMasterSettings, horizontal, law_choice, network, pairwise};
use crate::error::FitError;

/// The shift of one isotherm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IsothermShift {
    /// Temperature, °C.
    pub temperature: f64,
    /// Points of the isotherm.
    pub points: usize,
    /// Whether the data determine this isotherm's shift relative to the
    /// others (it belongs to the determined part of the pairs).
    pub determined: bool,
    /// log10 a_T measured from the overlap, anchored at T_ref (by the
    /// law's offset, or for "free" by interpolation at T_ref); None where
    /// the data do not determine it.
    pub log_shift_measured: Option<f64>,
    /// 1σ of the measured shift relative to its anchor, decades (infinite
    /// where undetermined).
    pub log_shift_measured_sigma: f64,
    /// log10 a_T applied: the law's value (the measured one for "free").
    pub log_shift: f64,
    /// 1σ of the applied value about T_ref, decades: the law's from its
    /// constants' covariance, the measurement's for "free"; infinite where
    /// the isotherm is undetermined (its value is then the law's
    /// assumption, which the data cannot test).
    pub log_shift_sigma: f64,
    /// log10 b_T applied (0 without vertical shifts).
    pub log_vertical: f64,
}

/// The shift factors of a set of isotherms and their law.
#[derive(Debug, Clone, PartialEq)]
pub struct ShiftFactors {
    /// Reference temperature, °C.
    pub t_ref: f64,
    /// The law applied (never `Auto`).
    pub law: ShiftLaw,
    /// Why the law was chosen (`auto`), or what its test says.
    pub reason: String,
    /// Per isotherm, ascending in temperature.
    pub shifts: Vec<IsothermShift>,
    /// The pairs compared, indices into `shifts`.
    pub pairs: Vec<pairwise::PairShift>,
    /// The WLF fit (tried by the law or by `auto`).
    pub wlf: Option<WlfFit>,
    /// The Arrhenius fit (tried by the law or by `auto`).
    pub arrhenius: Option<ArrheniusFit>,
    /// The WLF–Arrhenius fit (tried by the law or by `auto`).
    pub wlf_arrhenius: Option<WlfArrheniusFit>,
    /// Things the user should know.
    pub warnings: Vec<String>,
}

impl ShiftFactors {
    /// log10 a_T of the law at `t` (°C): WLF, Arrhenius, WLF–Arrhenius, or
    /// the applied shifts interpolated linearly in T (None outside them or
    /// below the WLF divergence).
    pub fn law_at(&self, t: f64) -> Option<f64> {
        match self.law {
            ShiftLaw::Wlf => self.wlf.and_then(|w| w.log_shift(self.t_ref, t)),
            ShiftLaw::Arrhenius => self.arrhenius.map(|a| a.log_shift(self.t_ref, t)),
            ShiftLaw::WlfArrhenius => self.wlf_arrhenius.and_then(|w| w.log_shift(self.t_ref, t)),
            ShiftLaw::Free | ShiftLaw::Auto => {
                let temps: Vec<f64> = self.shifts.iter().map(|s| s.temperature).collect();
                let values: Vec<f64> = self.shifts.iter().map(|s| s.log_shift).collect();
                let (lo, hi) = (temps[0], temps[temps.len() - 1]);
                (lo..=hi)
                    .contains(&t)
                    .then(|| interpolate(&temps, &values, t))
            }
        }
    }

    /// (a_T, b_T) applied to the isotherm at `t` (°C, one of `shifts`).
    pub(crate) fn factors_of(&self, t: f64) -> Result<(f64, f64), FitError> {
        let s = self
            .shifts
            .iter()
            .find(|s| s.temperature == t)
            .ok_or(FitError::Internal("isotherm without a shift"))?;
        Ok((10f64.powf(s.log_shift), 10f64.powf(s.log_vertical)))
    }

    /// 1σ of the law at `t` (NaN for "free").
    pub fn law_sigma_at(&self, t: f64) -> f64 {
        match self.law {
            ShiftLaw::Wlf => self.wlf.map_or(f64::NAN, |w| w.sigma_at(self.t_ref, t)),
            ShiftLaw::Arrhenius => self
                .arrhenius
                .map_or(f64::NAN, |a| a.sigma_at(self.t_ref, t)),
            ShiftLaw::WlfArrhenius => self
                .wlf_arrhenius
                .map_or(f64::NAN, |w| w.sigma_at(self.t_ref, t)),
            ShiftLaw::Free | ShiftLaw::Auto => f64::NAN,
        }
    }
}

/// Shift factors of `isotherms` under checked `settings`.
pub fn shift_factors(
    isotherms: &[Isotherm],
    settings: &ValidMasterSettings,
) -> Result<ShiftFactors, FitError> {
    let input: Vec<Superposable> = isotherms
        .iter()
        .map(|iso| Superposable {
            temperature: iso.temperature,
            points: iso.omega.len(),
            curves: horizontal::curves(iso),
        })
        .collect();
    superpose(input, settings, Domain::Frequency)
}

/// Shift factors of isotherms given as the curves the shift compares
/// (frequency sweeps or relaxation runs, `domain`).
pub(crate) fn superpose(
    mut sorted: Vec<Superposable>,
    settings: &ValidMasterSettings,
    domain: Domain,
) -> Result<ShiftFactors, FitError> {
    sorted.sort_by(|a, b| a.temperature.total_cmp(&b.temperature));
    let temps: Vec<f64> = sorted.iter().map(|i| i.temperature).collect();
    let t_ref = settings.t_ref;
    if sorted.len() == 1 {
        return Ok(single(t_ref, &sorted[0]));
    }
    let found = horizontal::pairs(&sorted, settings.vertical, domain)?;
    let network = network::solve(&found.pairs, &temps, t_ref).ok_or_else(|| {
        FitError::InsufficientData(format!(
            "no shift between the isotherms ({} °C) is determined by the data: either {} \
             flat across them (a glassy or rubbery plateau), so any shift fits about \
             equally well, or neighbouring isotherms overlap too little (their best overlap \
             lies at the edge of the {} range the overlap rule allows: a fifth of an \
             isotherm's points, and four, inside its neighbour's range); measure isotherms \
             through the transition, closer in temperature or over {}, or give \
             the shifts in the scene's [material.shift]",
            list_temperatures(&temps),
            domain.curves(),
            domain.axis(),
            domain.wider()
        ))
    })?;
    let observations: Vec<temperature_law::PairObservation> = network
        .pairs
        .iter()
        .map(|p| temperature_law::PairObservation {
            t_lower: temps[p.lower],
            t_upper: temps[p.upper],
            shift: p.shift,
            sigma: p.sigma,
        })
        .collect();
    let determined_temps: Vec<f64> = (0..temps.len())
        .filter(|&i| network.determined[i])
        .map(|i| temps[i])
        .collect();
    let choice = law_choice::choose(settings.law, &observations, &determined_temps, t_ref)?;
    let mut factors = ShiftFactors {
        t_ref,
        law: choice.law,
        reason: choice.reason,
        shifts: Vec::new(),
        pairs: found.pairs.clone(),
        wlf: choice.wlf,
        arrhenius: choice.arrhenius,
        wlf_arrhenius: choice.wlf_arrhenius,
        warnings: choice.warnings,
    };
    let placed = place(&factors, &network, &found, &temps)?;
    factors.warnings.extend(placed.warnings);
    if let Some(rms) = placed.law_rms {
        set_law_rms(&mut factors, rms);
    }
    let undetermined: Vec<f64> = (0..temps.len())
        .filter(|&i| !network.determined[i])
        .map(|i| temps[i])
        .collect();
    if !undetermined.is_empty() {
        factors.warnings.push(format!(
            "the shifts of the isotherms at {} °C are not determined by the data (their overlap \
             with the others is flat, as on a glassy or rubbery plateau, or ends at the edge of \
             the {} range): {}",
            list_temperatures(&undetermined),
            domain.axis(),
            if factors.law == ShiftLaw::Free {
                "they are placed where they overlap their neighbours best, which the data do not \
                 fix"
            } else {
                "they take the law's value"
            }
        ));
    }
    let vertical_offset = interpolate(&temps, &found.log_vertical, t_ref);
    factors.shifts = sorted
        .iter()
        .enumerate()
        .map(|(k, iso)| IsothermShift {
            temperature: iso.temperature,
            points: iso.points,
            determined: network.determined[k],
            log_shift_measured: placed.measured[k].map(|m| m.0),
            log_shift_measured_sigma: placed.measured[k].map_or(f64::INFINITY, |m| m.1),
            log_shift: placed.applied[k].0,
            log_shift_sigma: placed.applied[k].1,
            log_vertical: found.log_vertical[k] - vertical_offset,
        })
        .collect();
    Ok(factors)
}

/// One isotherm: its own master curve, unshifted.
fn single(t_ref: f64, isotherm: &Superposable) -> ShiftFactors {
    let t = isotherm.temperature;
    ShiftFactors {
        t_ref,
        law: ShiftLaw::Free,
        reason: format!(
            "one isotherm (at {t} °C): no shift to determine; the master curve is that isotherm \
             at T = {t} °C, and the shift law (a_T against T) is not determined — an isotherm at \
             another temperature would determine it",
            t = law_choice::temperature(t)
        ),
        shifts: vec![IsothermShift {
            temperature: t,
            points: isotherm.points,
            determined: true,
            log_shift_measured: Some(0.0),
            log_shift_measured_sigma: 0.0,
            log_shift: 0.0,
            log_shift_sigma: 0.0,
            log_vertical: 0.0,
        }],
        pairs: Vec::new(),
        wlf: None,
        arrhenius: None,
        wlf_arrhenius: None,
        warnings: Vec::new(),
    }
}

/// Where each isotherm goes: (value, σ) measured (None where
/// undetermined) and applied, the RMS of the measured shifts about the
/// law, and what to say.
struct Placed {
    measured: Vec<Option<(f64, f64)>>,
    applied: Vec<(f64, f64)>,
    law_rms: Option<f64>,
    warnings: Vec<String>,
}

/// Anchors the measured shifts at T_ref and places every isotherm (module
/// doc of [`super`], step 3): the anchor a·x is the law's offset (the mean
/// of x − L over the determined isotherms), or for "free" the measured
/// shifts interpolated at T_ref. Undetermined isotherms take the law's
/// value; without a law, the neighbour overlaps chained from the nearest
/// determined isotherm.
fn place(
    factors: &ShiftFactors,
    network: &network::Network,
    found: &horizontal::Pairs,
    temps: &[f64],
) -> Result<Placed, FitError> {
    let law = factors.law;
    let t_ref = factors.t_ref;
    let members: Vec<usize> = (0..temps.len())
        .filter(|&i| network.determined[i])
        .collect();
    let law_values: Option<Vec<f64>> = match law {
        ShiftLaw::Free => None,
        _ => Some(
            temps
                .iter()
                .map(|&t| factors.law_at(t))
                .collect::<Option<Vec<f64>>>()
                .ok_or_else(|| {
                    FitError::InsufficientData(format!(
                        "the {} law diverges inside the measured temperatures",
                        law.name()
                    ))
                })?,
        ),
    };
    let mut warnings = Vec::new();
    let mut anchor = vec![0.0; temps.len()];
    let offset = match &law_values {
        Some(values) => {
            let m = members.len() as f64;
            for &i in &members {
                anchor[i] = 1.0 / m;
            }
            members
                .iter()
                .map(|&i| network.log_shift[i] - values[i])
                .sum::<f64>()
                / m
        }
        None => {
            let (weights, outside) = interpolation_weights(&members, temps, t_ref);
            if outside {
                warnings.push(format!(
                    "T_ref = {t_ref} °C lies outside the isotherms whose shifts the data \
                     determine ({} to {} °C): the free shifts are extrapolated linearly to it",
                    law_choice::temperature(temps[members[0]]),
                    law_choice::temperature(temps[members[members.len() - 1]])
                ));
            }
            for (i, w) in weights {
                anchor[i] = w;
            }
            anchor
                .iter()
                .zip(&network.log_shift)
                .map(|(a, x)| a * x)
                .sum()
        }
    };
    let measured: Vec<Option<(f64, f64)>> = (0..temps.len())
        .map(|i| {
            network.determined[i].then(|| {
                let mut c: Vec<f64> = anchor.iter().map(|a| -a).collect();
                c[i] += 1.0;
                (network.log_shift[i] - offset, network.variance(&c).sqrt())
            })
        })
        .collect();
    let nearest_determined = |i: usize| {
        members
            .iter()
            .copied()
            .min_by_key(|&k| k.abs_diff(i))
            .unwrap_or(0)
    };
    let applied: Vec<(f64, f64)> = (0..temps.len())
        .map(|i| match (&law_values, measured[i]) {
            // The law's σ holds where the law does; at an undetermined
            // isotherm the data cannot tell, so its value is the law's
            // assumption and carries no σ.
            (Some(values), Some(_)) => (values[i], factors.law_sigma_at(temps[i])),
            (Some(values), None) => (values[i], f64::INFINITY),
            (None, Some(m)) => m,
            (None, None) => {
                let k = nearest_determined(i);
                let base = measured[k].map_or(0.0, |m| m.0);
                (base + found.chained[i] - found.chained[k], f64::INFINITY)
            }
        })
        .collect();
    let law_rms = law_values.as_ref().map(|values| {
        let residuals: Vec<f64> = members
            .iter()
            .filter_map(|&i| measured[i].map(|m| m.0 - values[i]))
            .collect();
        (residuals.iter().map(|r| r * r).sum::<f64>() / residuals.len() as f64).sqrt()
    });
    Ok(Placed {
        measured,
        applied,
        law_rms,
        warnings,
    })
}

/// The applied law's RMS scatter of the measured shifts about it.
fn set_law_rms(factors: &mut ShiftFactors, rms: f64) {
    match factors.law {
        ShiftLaw::Wlf => {
            if let Some(w) = factors.wlf.as_mut() {
                w.rms = rms;
            }
        }
        ShiftLaw::Arrhenius => {
            if let Some(a) = factors.arrhenius.as_mut() {
                a.rms = rms;
            }
        }
        ShiftLaw::WlfArrhenius => {
            if let Some(w) = factors.wlf_arrhenius.as_mut() {
                w.rms = rms;
            }
        }
        ShiftLaw::Free | ShiftLaw::Auto => {}
    }
}

/// "-50, -40, -30" for the messages: each to 0.01 K, as controllers
/// scatter about their set point.
fn list_temperatures(temps: &[f64]) -> String {
    temps
        .iter()
        .map(|&t| law_choice::temperature(t))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Weights (index, w) of the linear interpolation at `at` between the
/// temperatures of `members` (ascending indices into `temps`), and whether
/// `at` lies outside them (then the nearest pair extrapolates).
fn interpolation_weights(members: &[usize], temps: &[f64], at: f64) -> (Vec<(usize, f64)>, bool) {
    if members.len() == 1 {
        return (vec![(members[0], 1.0)], temps[members[0]] != at);
    }
    let x: Vec<f64> = members.iter().map(|&i| temps[i]).collect();
    let outside = at < x[0] || at > x[x.len() - 1];
    let k = x.partition_point(|&xi| xi <= at).clamp(1, x.len() - 1);
    let w = (at - x[k - 1]) / (x[k] - x[k - 1]);
    (vec![(members[k - 1], 1.0 - w), (members[k], w)], outside)
}

/// Linear interpolation (or extrapolation from the nearest pair) of
/// ascending (x, y) at `at`.
pub(super) fn interpolate(x: &[f64], y: &[f64], at: f64) -> f64 {
    if x.len() == 1 {
        return y[0];
    }
    let k = x.partition_point(|&xi| xi <= at).clamp(1, x.len() - 1);
    let w = (at - x[k - 1]) / (x[k] - x[k - 1]);
    y[k - 1] * (1.0 - w) + y[k] * w
}
