//! The shift factors of a set of isotherms: the pairs compared, the
//! determined shifts solved at once, the law chosen, the measured shifts
//! anchored at T_ref and the values applied (the module doc of
//! [`super`], steps 1–3).

use super::horizontal::{Domain, Superposable};
use super::pairwise::{
    DETERMINED_SIGMA, MIN_OVERLAP, PairCause, PairShift, PairVerdict, TTS_DISAGREEMENT,
};
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
    /// Whether the data determine this isotherm's shift: it is joined to
    /// the reference part by determined pairs and its measured σ about
    /// T_ref is at most [`DETERMINED_SIGMA`].
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
    /// Candidates `auto` rejected as unable to hold, with the reason.
    pub rejected_laws: Vec<(ShiftLaw, String)>,
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

    /// Whether the isotherm at `t` (°C) has a determined shift (false for
    /// a temperature that is none of them).
    pub fn is_determined(&self, t: f64) -> bool {
        self.shifts
            .iter()
            .any(|s| s.temperature == t && s.determined)
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
    if sorted.len() == 1 {
        return Ok(single(settings.t_ref, &sorted[0]));
    }
    let found = horizontal::pairs(&sorted, settings.vertical);
    let network = network::solve(&found.pairs, &temps, settings.t_ref).ok_or_else(|| {
        FitError::InsufficientData(format!(
            "no shift between the isotherms ({} °C) is determined by the data: {}; measure \
             isotherms through the transition, closer in temperature or over {}, or give the \
             shifts in the scene's [material.shift]",
            list_temperatures(&temps),
            causes(&found.pairs, &temps, domain).join("; "),
            domain.wider()
        ))
    })?;
    let t_ref = reference_temperature(settings, &network, &temps);
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
    let choice = law_choice::choose(
        settings.law,
        &observations,
        &determined_temps,
        &temps,
        t_ref,
    )?;
    let mut factors = ShiftFactors {
        t_ref,
        law: choice.law,
        reason: choice.reason,
        shifts: Vec::new(),
        pairs: found.pairs.clone(),
        wlf: choice.wlf,
        arrhenius: choice.arrhenius,
        wlf_arrhenius: choice.wlf_arrhenius,
        rejected_laws: choice.rejected,
        warnings: choice.warnings,
    };
    let placed = place(&factors, &network, &found, &temps)?;
    factors.warnings.extend(placed.warnings);
    if let Some(rms) = placed.law_rms {
        set_law_rms(&mut factors, rms);
    }
    // One rule for the flag (pairwise::DETERMINED_SIGMA): joined to the
    // reference part, and its σ about T_ref within the rule.
    let determined: Vec<bool> = (0..temps.len())
        .map(|i| placed.measured[i].is_some_and(|m| m.1 <= DETERMINED_SIGMA))
        .collect();
    let undetermined: Vec<f64> = (0..temps.len())
        .filter(|&i| !determined[i])
        .map(|i| temps[i])
        .collect();
    let said = determined_warnings(&factors, &found.pairs, &undetermined, &temps, domain);
    factors.warnings.extend(said);
    let vertical_offset = interpolate(&temps, &found.log_vertical, t_ref);
    factors.shifts = sorted
        .iter()
        .enumerate()
        .map(|(k, iso)| IsothermShift {
            temperature: iso.temperature,
            points: iso.points,
            determined: determined[k],
            log_shift_measured: placed.measured[k].map(|m| m.0),
            log_shift_measured_sigma: placed.measured[k].map_or(f64::INFINITY, |m| m.1),
            log_shift: placed.applied[k].0,
            log_shift_sigma: placed.applied[k].1,
            log_vertical: found.log_vertical[k] - vertical_offset,
        })
        .collect();
    Ok(factors)
}

/// T_ref (°C): the user's, else 20 °C when inside the determined part of
/// `network`, else that part's temperature nearest 20 °C.
fn reference_temperature(
    settings: &ValidMasterSettings,
    network: &network::Network,
    temps: &[f64],
) -> f64 {
    if settings.t_ref_given {
        return settings.t_ref;
    }
    let part: Vec<f64> = (0..temps.len())
        .filter(|&i| network.determined[i])
        .map(|i| temps[i])
        .collect();
    if (part[0]..=part[part.len() - 1]).contains(&super::DEFAULT_T_REF) {
        return super::DEFAULT_T_REF;
    }
    *part
        .iter()
        .min_by(|a, b| {
            (*a - super::DEFAULT_T_REF)
                .abs()
                .total_cmp(&(*b - super::DEFAULT_T_REF).abs())
        })
        .unwrap_or(&part[0])
}

/// What to say about the isotherms at `undetermined` (°C) and the pairs
/// where superposition fails.
fn determined_warnings(
    factors: &ShiftFactors,
    pairs: &[PairShift],
    undetermined: &[f64],
    temps: &[f64],
    domain: Domain,
) -> Vec<String> {
    let mut warnings = Vec::new();
    if !undetermined.is_empty() {
        let pairs_said = causes(pairs, temps, domain);
        warnings.push(format!(
            "the shifts of the isotherms at {} °C are not determined by the data (σ about T_ref \
             above {DETERMINED_SIGMA} decade, or not joined to the determined part): {}; {}",
            list_temperatures(undetermined),
            if pairs_said.is_empty() {
                "their pairs' errors add up along the chain".to_string()
            } else {
                pairs_said.join("; ")
            },
            if factors.law == ShiftLaw::Free {
                "they are placed where they overlap their neighbours best, which the data do not \
                 fix"
            } else {
                "they take the law's value"
            }
        ));
    }
    let failing: Vec<String> = pairs
        .iter()
        .filter(|p| p.tts_fails)
        .map(|p| tts_failure(p, temps))
        .collect();
    if !failing.is_empty() {
        warnings.push(format!(
            "time–temperature superposition fails (E′ and tan δ need different shifts, by more \
             than {TTS_DISAGREEMENT} decade): {}; no single shift superposes both there, and \
             those shifts carry at least half the difference as σ",
            failing.join("; ")
        ));
    }
    warnings
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
        rejected_laws: Vec::new(),
        warnings: Vec::new(),
    }
}

/// Why each undetermined neighbour pair is not a measurement, with its
/// numbers (a plateau, a too-narrow overlap, two equal minima, a wide
/// interval, too few points).
pub(crate) fn causes(pairs: &[PairShift], temps: &[f64], domain: Domain) -> Vec<String> {
    pairs
        .iter()
        .filter(|p| p.verdict == PairVerdict::Undetermined && p.upper == p.lower + 1)
        .map(|p| {
            let between = format!(
                "{}–{} °C",
                law_choice::temperature(temps[p.lower]),
                law_choice::temperature(temps[p.upper])
            );
            let change = |decades: f64| format!("{:.0} %", (10f64.powf(decades) - 1.0) * 100.0);
            let varies = match domain {
                Domain::Frequency => format!(
                    "E′ changes by at most {} and tan δ lies between {:.3} and {:.3} across an \
                     isotherm",
                    change(p.spans[0]),
                    10f64.powf(p.second_range[0]),
                    10f64.powf(p.second_range[1])
                ),
                Domain::Time => format!(
                    "E(t) changes by at most {} across an isotherm",
                    change(p.spans[0])
                ),
            };
            match p.cause {
                PairCause::Flat | PairCause::OverlapEnd if p.tts_fails => format!(
                    "{between} superposition fails ({}); no shift in their overlap serves both",
                    disagreement(p)
                ),
                PairCause::Flat => format!(
                    "{between} flat, a plateau ({varies}): any shift fits about equally well"
                ),
                PairCause::OverlapEnd => format!(
                    "{between} the best overlap ({:.2} decades) lies where the isotherms stop \
                     overlapping ({:.2} decade in common; {varies}): the transition's overlap \
                     is too narrow, measure a temperature between them or a wider {} range",
                    p.shift,
                    p.overlap,
                    domain.axis()
                ),
                PairCause::Ambiguous => format!(
                    "{between} two shifts, apart by more than 2σ, fit about equally well \
                     ({varies})"
                ),
                PairCause::Wide if p.tts_fails => format!(
                    "{between} superposition fails ({}): σ = {:.2} decade",
                    disagreement(p),
                    p.sigma
                ),
                PairCause::Wide => format!(
                    "{between} σ = {:.2} decade exceeds {DETERMINED_SIGMA} ({varies})",
                    p.sigma
                ),
                PairCause::TooFewPoints => format!(
                    "{between} too few points: fewer than {MIN_OVERLAP} points of an isotherm \
                     fall inside the other's {} range at any shift",
                    domain.axis()
                ),
                PairCause::Measured => format!("{between} measured"),
            }
        })
        .collect()
}

/// "E′ alone needs −1.92, tan δ alone −0.07 decades".
fn disagreement(p: &PairShift) -> String {
    let names = ["E′", "tan δ"];
    match p.curve_bounded {
        [true, false] | [false, true] => {
            let (fixed, other) = if p.curve_bounded[0] { (0, 1) } else { (1, 0) };
            format!(
                "{} alone needs {:.2} decades, which {} rejects: {} alone fits best at {:.2}, \
                 where the isotherms stop overlapping",
                names[fixed],
                p.curve_shift[fixed],
                names[other],
                names[other],
                p.curve_shift[other]
            )
        }
        _ => format!(
            "E′ alone needs {:.2}, tan δ alone {:.2} decades",
            p.curve_shift[0], p.curve_shift[1]
        ),
    }
}

/// A pair where superposition fails, for messages: its temperatures, the
/// two shifts and the quantity that carries the combined one, with why:
/// the summed mismatch is ruled by the curve that changes more, in
/// decades, across an isotherm.
pub(crate) fn tts_failure(p: &PairShift, temps: &[f64]) -> String {
    let names = ["E′", "tan δ"];
    let (carrier, other) = (p.carrier.min(1), 1 - p.carrier.min(1));
    format!(
        "{}–{} °C: {}; the shift ({:.2} ± {:.2}) follows {}, which changes by {:.3} decade \
         across an isotherm against {:.3} for {}",
        law_choice::temperature(temps[p.lower]),
        law_choice::temperature(temps[p.upper]),
        disagreement(p),
        p.shift,
        p.sigma,
        names[carrier],
        p.spans[carrier],
        p.spans[other],
        names[other]
    )
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
/// value between determined ones and [`beyond_determined`] outside their
/// range; without a law, the neighbour overlaps chained from the nearest
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
            (Some(values), None) if !members.is_empty() && !within(&members, i) => (
                beyond_determined(values, &found.pairs, nearest_determined(i), i),
                f64::INFINITY,
            ),
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

/// Whether isotherm `i` lies between the coldest and the warmest of the
/// determined isotherms `members` (ascending indices).
fn within(members: &[usize], i: usize) -> bool {
    members.first().is_some_and(|&lo| lo <= i) && members.last().is_some_and(|&hi| i <= hi)
}

/// An undetermined isotherm `i` beyond the determined isotherms' range,
/// placed step by step outward from the nearest determined isotherm `k`:
/// a law fitted inside the range is an extrapolation there, so each
/// neighbour step is the pair's shift where its data say something (a
/// bounded profile, or a pair where superposition fails whose modulus
/// fixes a shift of its own: the pair's shift then lies between the two
/// quantities') and the law's step only where they do not (a plateau, too
/// few points).
fn beyond_determined(law_values: &[f64], pairs: &[PairShift], k: usize, i: usize) -> f64 {
    let step = |j: usize| {
        let data = pairs
            .iter()
            .find(|p| p.lower == j && p.upper == j + 1)
            .filter(|p| {
                matches!(p.cause, PairCause::Measured | PairCause::Wide)
                    || (p.tts_fails && p.curve_bounded[0])
            });
        data.map_or(law_values[j + 1] - law_values[j], |p| p.shift)
    };
    if i > k {
        law_values[k] + (k..i).map(step).sum::<f64>()
    } else {
        law_values[k] - (i..k).map(step).sum::<f64>()
    }
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
