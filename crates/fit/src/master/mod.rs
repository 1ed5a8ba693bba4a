//! From DMA isotherms to a master curve: time–temperature superposition
//! with shift factors found from the data, a law (WLF or Arrhenius) fitted
//! to them with standard errors, and a smooth causal Prony series fitted to
//! the shifted E′ and E″ — the material `rollfit forward` needs, from the
//! measurement a polymer lab already has.
//!
//! Superposition (Ferry ch. 11): E*(ω, T) = b_T E*_ref(ω a_T), a_T the
//! horizontal and b_T the (optional) vertical shift factor, both 1 at the
//! reference temperature T_ref. With the convention of
//! `rollfit_model::modulus::shift`, a point measured at (ω, T) lies on the
//! master curve at the reduced frequency ω a_T with the moduli divided by
//! b_T.
//!
//! Steps, each in its own file:
//! 1. `horizontal`: neighbouring isotherms overlapped in log E′ and
//!    log tan δ give log a_T (and log b_T) up to a constant.
//! 2. [`temperature_law`]: WLF or Arrhenius fitted to those shifts with a
//!    free offset; the offset fixes log a_{T_ref} = 0. With the law
//!    "free" the measured shifts themselves are used, interpolated
//!    linearly in T to fix the constant at T_ref.
//! 3. The data are shifted with the law's a_T (so that the Prony series at
//!    T_ref and the law together reproduce every isotherm, as a scene will
//!    use them) and the measured b_T.
//! 4. [`prony_fit`]: a causal Prony series on the shifted points.
//!
//! Settings are checked before any numerics run
//! ([`MasterSettings::check`] gives [`ValidMasterSettings`]).
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 11.
//! - J. Dealy, D. Plazek, "Time–temperature superposition — a users
//!   guide", Rheology Bulletin 78(2) (2009) 16–31.

pub(crate) mod horizontal;
mod isotherm;
pub mod prony_fit;
pub mod temperature_law;

pub use isotherm::Isotherm;
pub use prony_fit::{PronyFit, TAU_PER_DECADE, fit_prony, tau_grid};
pub use temperature_law::{ArrheniusFit, WlfFit};

use rollfit_model::ViscoelasticModulus;

use crate::error::FitError;

/// The law of the horizontal shift factor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ShiftLaw {
    /// Williams–Landel–Ferry (three isotherms or more).
    #[default]
    Wlf,
    /// The measured shifts, linear in T between isotherms.
    Free,
    /// Arrhenius (two isotherms or more).
    Arrhenius,
}

impl ShiftLaw {
    /// "wlf", "free" or "arrhenius", as on the command line and in
    /// `[material.shift] model`.
    pub fn name(self) -> &'static str {
        match self {
            ShiftLaw::Wlf => "wlf",
            ShiftLaw::Free => "free",
            ShiftLaw::Arrhenius => "arrhenius",
        }
    }
}

/// Settings of a master curve, unchecked.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MasterSettings {
    /// Reference temperature, °C; None: 20 °C when inside the measured
    /// range, else the measured temperature nearest to it.
    pub t_ref: Option<f64>,
    /// The law of a_T.
    pub law: ShiftLaw,
    /// Whether to find vertical shift factors b_T as well.
    pub vertical: bool,
}

/// Settings checked against the isotherms they are for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ValidMasterSettings {
    t_ref: f64,
    law: ShiftLaw,
    vertical: bool,
}

impl ValidMasterSettings {
    /// Reference temperature, °C.
    pub fn t_ref(&self) -> f64 {
        self.t_ref
    }

    /// The law of a_T.
    pub fn law(&self) -> ShiftLaw {
        self.law
    }

    /// Whether vertical factors are found.
    pub fn vertical(&self) -> bool {
        self.vertical
    }
}

/// The default reference temperature, °C.
pub const DEFAULT_T_REF: f64 = 20.0;

impl MasterSettings {
    /// Checks the settings and the isotherms: at least one isotherm, each
    /// with finite positive ω, E′, E″ of equal lengths and monotone ω;
    /// distinct temperatures; a reference temperature a single isotherm or
    /// a free shift can reach; enough isotherms for the law.
    pub fn check(&self, isotherms: &[Isotherm]) -> Result<ValidMasterSettings, FitError> {
        if isotherms.is_empty() {
            return Err(FitError::InsufficientData(
                "no isotherms: a master curve needs DMA points".into(),
            ));
        }
        for iso in isotherms {
            check_isotherm(iso)?;
        }
        let mut temps: Vec<f64> = isotherms.iter().map(|i| i.temperature).collect();
        temps.sort_by(f64::total_cmp);
        for pair in temps.windows(2) {
            if pair[0] == pair[1] {
                return Err(FitError::InsufficientData(format!(
                    "two isotherms at T = {} °C: merge them or give them their own temperatures",
                    pair[0]
                )));
            }
        }
        let (lo, hi) = (temps[0], temps[temps.len() - 1]);
        let t_ref = match self.t_ref {
            Some(t) => {
                if !(t.is_finite() && t > -273.15 && t <= 1000.0) {
                    return Err(FitError::setting(
                        "T_ref",
                        format!("{t} °C is not a temperature in (−273.15, 1000] °C"),
                    ));
                }
                t
            }
            None if (lo..=hi).contains(&DEFAULT_T_REF) => DEFAULT_T_REF,
            None => *temps
                .iter()
                .min_by(|a, b| {
                    (*a - DEFAULT_T_REF)
                        .abs()
                        .total_cmp(&(*b - DEFAULT_T_REF).abs())
                })
                .unwrap_or(&lo),
        };
        if temps.len() == 1 && t_ref != lo {
            return Err(FitError::setting(
                "T_ref",
                format!(
                    "one isotherm, at {lo} °C, cannot be moved to T_ref = {t_ref} °C: without a \
                     second temperature there is no shift; leave T_ref out (the master curve is \
                     that isotherm) or measure more temperatures"
                ),
            ));
        }
        if temps.len() > 1 {
            match self.law {
                ShiftLaw::Wlf if temps.len() < 3 => {
                    return Err(FitError::setting(
                        "shift",
                        format!(
                            "WLF has three constants (with the shifts' offset) and {} isotherms \
                             determine two: use the shift \"free\" or \"arrhenius\", or measure \
                             more temperatures",
                            temps.len()
                        ),
                    ));
                }
                ShiftLaw::Free if !(lo..=hi).contains(&t_ref) => {
                    return Err(FitError::setting(
                        "T_ref",
                        format!(
                            "a free shift is known only between the isotherms ({lo} to {hi} °C); \
                             T_ref = {t_ref} °C lies outside: choose T_ref inside, or the shift \
                             \"wlf\" or \"arrhenius\", which extrapolate"
                        ),
                    ));
                }
                _ => {}
            }
        }
        Ok(ValidMasterSettings {
            t_ref,
            law: self.law,
            vertical: self.vertical,
        })
    }
}

/// Finite positive values of equal lengths, monotone ω.
fn check_isotherm(iso: &Isotherm) -> Result<(), FitError> {
    let t = iso.temperature;
    let refuse = |what: String| {
        Err(FitError::InsufficientData(format!(
            "isotherm {t} °C: {what}"
        )))
    };
    if !(t.is_finite() && t > -273.15) {
        return Err(FitError::InsufficientData(format!(
            "isotherm temperature {t} °C is not a temperature"
        )));
    }
    let n = iso.omega.len();
    if n == 0 || iso.storage.len() != n || iso.loss.len() != n {
        return refuse(format!(
            "{n} frequencies, {} storage and {} loss moduli: need equal, non-zero counts",
            iso.storage.len(),
            iso.loss.len()
        ));
    }
    for i in 0..n {
        let (w, s, l) = (iso.omega[i], iso.storage[i], iso.loss[i]);
        if !(w > 0.0 && s > 0.0 && l > 0.0 && w.is_finite() && s.is_finite() && l.is_finite()) {
            return refuse(format!(
                "point {} has ω = {w}, E′ = {s}, E″ = {l}: all must be finite and positive",
                i + 1
            ));
        }
    }
    if let Some(k) = sweep_turn(&iso.omega) {
        let shown: Vec<String> = (k - 1..(k + 2).min(n))
            .map(|j| format!("{:e}", iso.omega[j]))
            .collect();
        return refuse(format!(
            "frequencies are not monotone: points {}–{} go {} rad/s (a sweep runs up or down; a \
             repeated sweep is a second isotherm)",
            k,
            (k + 2).min(n),
            shown.join(", ")
        ));
    }
    Ok(())
}

/// Where a frequency sweep stops being monotone: the first index k ≥ 1
/// at which ω repeats (ω_k = ω_{k−1}) or turns (ω_{k−1}, ω_k, ω_{k+1} not
/// in one direction); None for a sweep that runs up or down throughout.
/// Front ends name the file lines of points k − 1, k, k + 1 with it.
pub fn sweep_turn(omega: &[f64]) -> Option<usize> {
    (1..omega.len()).find(|&k| {
        omega[k] == omega[k - 1]
            || (k + 1 < omega.len() && (omega[k] - omega[k - 1]) * (omega[k + 1] - omega[k]) < 0.0)
    })
}

/// The shift of one isotherm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IsothermShift {
    /// Temperature, °C.
    pub temperature: f64,
    /// Points of the isotherm.
    pub points: usize,
    /// log10 a_T found from the overlap (about the law's offset).
    pub log_shift_measured: f64,
    /// log10 a_T applied: the law's value (the measured one for "free").
    pub log_shift: f64,
    /// log10 b_T applied (0 without vertical shifts).
    pub log_vertical: f64,
}

/// The shift factors of a set of isotherms and their law.
#[derive(Debug, Clone, PartialEq)]
pub struct ShiftFactors {
    /// Reference temperature, °C.
    pub t_ref: f64,
    /// The law applied.
    pub law: ShiftLaw,
    /// Per isotherm, ascending in temperature.
    pub shifts: Vec<IsothermShift>,
    /// The WLF fit (law "wlf").
    pub wlf: Option<WlfFit>,
    /// The Arrhenius fit (law "arrhenius").
    pub arrhenius: Option<ArrheniusFit>,
    /// Things the user should know.
    pub warnings: Vec<String>,
}

impl ShiftFactors {
    /// log10 a_T of the law at `t` (°C): WLF, Arrhenius, or the measured
    /// shifts interpolated linearly in T (None outside them or below the
    /// WLF divergence).
    pub fn law_at(&self, t: f64) -> Option<f64> {
        match self.law {
            ShiftLaw::Wlf => self.wlf.and_then(|w| w.log_shift(self.t_ref, t)),
            ShiftLaw::Arrhenius => self.arrhenius.map(|a| a.log_shift(self.t_ref, t)),
            ShiftLaw::Free => {
                let temps: Vec<f64> = self.shifts.iter().map(|s| s.temperature).collect();
                let values: Vec<f64> = self.shifts.iter().map(|s| s.log_shift).collect();
                let (lo, hi) = (temps[0], temps[temps.len() - 1]);
                (lo..=hi)
                    .contains(&t)
                    .then(|| interpolate(&temps, &values, t))
            }
        }
    }
}

/// A law's RMS scatter above which the user is told it describes the
/// shifts poorly, decades: several times what 1–2 % scatter leaves.
const LAW_RMS_WARNING: f64 = 0.2;

/// Shift factors of `isotherms` under checked `settings`.
pub fn shift_factors(
    isotherms: &[Isotherm],
    settings: &ValidMasterSettings,
) -> Result<ShiftFactors, FitError> {
    let mut sorted: Vec<&Isotherm> = isotherms.iter().collect();
    sorted.sort_by(|a, b| a.temperature.total_cmp(&b.temperature));
    let temps: Vec<f64> = sorted.iter().map(|i| i.temperature).collect();
    let t_ref = settings.t_ref;
    let chain = horizontal::chain(&sorted, settings.vertical)?;
    let mut warnings = Vec::new();
    let (mut wlf, mut arrhenius) = (None, None);
    let single = sorted.len() == 1;
    let (offset, applied): (f64, Vec<f64>) = match settings.law {
        _ if single => (0.0, vec![0.0]),
        ShiftLaw::Free => (interpolate(&temps, &chain.log_shift, t_ref), Vec::new()),
        ShiftLaw::Wlf => {
            let (fit, b) = temperature_law::fit_wlf_with_errors(&temps, &chain.log_shift, t_ref)
                .ok_or_else(|| FitError::InsufficientData("WLF needs three isotherms".into()))?;
            if fit.rms > LAW_RMS_WARNING {
                warnings.push(format!(
                    "WLF describes the measured shifts poorly ({:.2} decades RMS): the isotherms \
                     span regimes with different laws (below T_g shifts follow Arrhenius); \
                     consider --shift free",
                    fit.rms
                ));
            }
            let values = temps
                .iter()
                .map(|&t| fit.log_shift(t_ref, t))
                .collect::<Option<Vec<f64>>>()
                .ok_or_else(|| {
                    FitError::InsufficientData(
                        "the WLF fit diverges inside the measured temperatures".into(),
                    )
                })?;
            wlf = Some(fit);
            (b, values)
        }
        ShiftLaw::Arrhenius => {
            let (fit, b) = temperature_law::fit_arrhenius(&temps, &chain.log_shift, t_ref)
                .ok_or_else(|| {
                    FitError::InsufficientData("Arrhenius needs two isotherms".into())
                })?;
            if fit.rms > LAW_RMS_WARNING {
                warnings.push(format!(
                    "Arrhenius describes the measured shifts poorly ({:.2} decades RMS); \
                     consider --shift wlf or free",
                    fit.rms
                ));
            }
            if fit.activation_energy <= 0.0 {
                return Err(FitError::InsufficientData(format!(
                    "the shifts give a non-positive activation energy ({:.3e} J/mol): warmer \
                     isotherms are not faster; check the temperatures",
                    fit.activation_energy
                )));
            }
            arrhenius = Some(fit);
            (b, temps.iter().map(|&t| fit.log_shift(t_ref, t)).collect())
        }
    };
    let measured: Vec<f64> = chain.log_shift.iter().map(|c| c - offset).collect();
    let applied = if applied.is_empty() {
        measured.clone()
    } else {
        applied
    };
    let vertical_offset = interpolate(&temps, &chain.log_vertical, t_ref);
    let shifts = sorted
        .iter()
        .enumerate()
        .map(|(k, iso)| IsothermShift {
            temperature: iso.temperature,
            points: iso.omega.len(),
            log_shift_measured: measured[k],
            log_shift: applied[k],
            log_vertical: chain.log_vertical[k] - vertical_offset,
        })
        .collect();
    Ok(ShiftFactors {
        t_ref,
        law: settings.law,
        shifts,
        wlf,
        arrhenius,
        warnings,
    })
}

/// One DMA point on the master curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MasterPoint {
    /// Reduced frequency ω a_T, rad/s.
    pub reduced_omega: f64,
    /// E′/b_T, Pa.
    pub storage: f64,
    /// E″/b_T, Pa.
    pub loss: f64,
    /// The isotherm's temperature, °C.
    pub temperature: f64,
    /// The measured frequency ω, rad/s.
    pub omega: f64,
}

/// A master curve built from isotherms.
#[derive(Debug, Clone)]
pub struct MasterCurve {
    /// The shift factors and their law.
    pub shift: ShiftFactors,
    /// Every point at the reference state, ascending in reduced ω.
    pub points: Vec<MasterPoint>,
    /// The Prony series at T_ref.
    pub fit: PronyFit,
    /// Things the user should know (the shift's among them).
    pub warnings: Vec<String>,
}

/// Shifts the isotherms and fits the Prony series (module doc).
pub fn build_master_curve(
    isotherms: &[Isotherm],
    settings: &ValidMasterSettings,
) -> Result<MasterCurve, FitError> {
    let shift = shift_factors(isotherms, settings)?;
    let mut points = Vec::new();
    for iso in isotherms {
        let s = shift
            .shifts
            .iter()
            .find(|s| s.temperature == iso.temperature)
            .copied()
            .ok_or(FitError::Internal("isotherm without a shift"))?;
        let (a, b) = (10f64.powf(s.log_shift), 10f64.powf(s.log_vertical));
        for i in 0..iso.omega.len() {
            points.push(MasterPoint {
                reduced_omega: iso.omega[i] * a,
                storage: iso.storage[i] / b,
                loss: iso.loss[i] / b,
                temperature: iso.temperature,
                omega: iso.omega[i],
            });
        }
    }
    points.sort_by(|p, q| p.reduced_omega.total_cmp(&q.reduced_omega));
    let omega: Vec<f64> = points.iter().map(|p| p.reduced_omega).collect();
    let storage: Vec<f64> = points.iter().map(|p| p.storage).collect();
    let loss: Vec<f64> = points.iter().map(|p| p.loss).collect();
    let fit = fit_prony(&omega, &storage, &loss)?;
    let mut warnings = shift.warnings.clone();
    let lowest = storage.iter().fold(f64::INFINITY, |m, &e| m.min(e));
    let static_modulus = fit.prony.static_modulus();
    if static_modulus < 1e-3 * lowest {
        warnings.push(format!(
            "the data reach no rubbery plateau: the static modulus E0 = {static_modulus:.3e} Pa is \
             not determined (the series falls below the smallest measured E′, {lowest:.3e} Pa, \
             outside the data); μ at speeds below the master curve's range, and static contact \
             sizes, depend on it"
        ));
    }
    if !fit.converged {
        warnings.push(
            "the Prony fit stopped before its convergence test passed; the series is the best \
             found"
                .into(),
        );
    }
    Ok(MasterCurve {
        shift,
        points,
        fit,
        warnings,
    })
}

/// Linear interpolation (or extrapolation from the nearest pair) of
/// ascending (x, y) at `at`.
fn interpolate(x: &[f64], y: &[f64], at: f64) -> f64 {
    if x.len() == 1 {
        return y[0];
    }
    let k = x.partition_point(|&xi| xi <= at).clamp(1, x.len() - 1);
    let w = (at - x[k - 1]) / (x[k] - x[k - 1]);
    y[k - 1] * (1.0 - w) + y[k] * w
}

#[cfg(test)]
mod tests;
