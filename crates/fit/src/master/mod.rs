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
//! 1. `horizontal` and [`pairwise`]: neighbouring isotherms overlapped in
//!    log E′ and log tan δ give each pair's relative shift with its
//!    standard error, or the verdict that the data do not determine it (a
//!    plateau, or an optimum on the edge of the allowed overlap), and
//!    log b_T up to a constant.
//! 2. `network`: the determined pairs solved all at once for log a_T (up
//!    to a constant) with its covariance; isotherms outside the largest
//!    connected part are undetermined.
//! 3. [`temperature_law`]: WLF, Arrhenius, or WLF above a junction with
//!    Arrhenius below, fitted to the determined pairs with weights 1/σ²
//!    and judged by a χ² test; `auto` ([`law_choice`]) takes the first
//!    that describes the shifts, else the measured shifts themselves
//!    ("free", interpolated linearly in T). The measured shifts are
//!    anchored at T_ref: by the law's offset, or for "free" by
//!    interpolation at T_ref. Undetermined isotherms between determined
//!    ones take the law's value (for "free", the place where they overlap
//!    their neighbour best), marked as such; beyond the determined range,
//!    where the law would be an extrapolation, each step outward is the
//!    pair's overlap where its profile is bounded and the law's step only
//!    across a plateau.
//! 4. The data are shifted with the applied a_T (so that the Prony series
//!    at T_ref and the law together reproduce every isotherm, as a scene
//!    will use them) and the measured b_T.
//! 5. [`prony_fit`]: a causal Prony series on the shifted points (on
//!    bins of 1/50 decade when they are thousands, [`condense`]).
//!
//! Settings are checked before any numerics run
//! ([`MasterSettings::check`] gives [`ValidMasterSettings`]).
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 11.
//! - J. Dealy, D. Plazek, "Time–temperature superposition — a users
//!   guide", Rheology Bulletin 78(2) (2009) 16–31.

pub mod condense;
mod creep_prony;
mod creep_rows;
pub mod grouping;
pub(crate) mod horizontal;
mod isotherm;
pub mod law_choice;
mod network;
pub mod pairwise;
pub mod pipeline;
pub mod prony_fit;
pub mod quality;
pub mod reach;
pub mod relaxation;
mod relaxation_prony;
pub mod repeats;
mod scale;
mod shift_profile;
mod shifts;
pub mod temperature_law;
pub mod van_gurp_palmen;

pub use isotherm::{Isotherm, Sweep};
pub use prony_fit::{PronyFit, TAU_PER_DECADE, fit_prony, tau_grid};
pub use shifts::{IsothermShift, ShiftFactors, shift_factors};
pub use temperature_law::{ArrheniusFit, LawTest, WlfArrheniusFit, WlfFit};
pub use van_gurp_palmen::{VanGurpPalmen, van_gurp_palmen};

use rollfit_model::ViscoelasticModulus;

use crate::error::FitError;

/// The law of the horizontal shift factor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ShiftLaw {
    /// Chosen by the data ([`law_choice`]): the first of WLF, WLF–Arrhenius
    /// or Arrhenius that describes the determined shifts, else free.
    #[default]
    Auto,
    /// Williams–Landel–Ferry (three isotherms or more).
    Wlf,
    /// The measured shifts, linear in T between isotherms.
    Free,
    /// Arrhenius (two isotherms or more).
    Arrhenius,
    /// WLF above a junction T_g, Arrhenius below (five isotherms or more).
    WlfArrhenius,
}

impl ShiftLaw {
    /// "auto", "wlf", "free", "arrhenius" or "wlf-arrhenius", as on the
    /// command line and in `[material.shift] model`.
    pub fn name(self) -> &'static str {
        match self {
            ShiftLaw::Auto => "auto",
            ShiftLaw::Wlf => "wlf",
            ShiftLaw::Free => "free",
            ShiftLaw::Arrhenius => "arrhenius",
            ShiftLaw::WlfArrhenius => "wlf-arrhenius",
        }
    }
}

/// Settings of a master curve, unchecked.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MasterSettings {
    /// Reference temperature, °C; None: 20 °C when inside the isotherms
    /// whose shifts the data determine, else the one of them nearest to
    /// it.
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
    t_ref_given: bool,
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

    /// The settings with the reference temperature the shifts resolved
    /// ([`ShiftFactors::t_ref`]: without a T_ref given, the shifts move it
    /// into the determined part).
    pub fn resolved(self, shift: &ShiftFactors) -> ValidMasterSettings {
        ValidMasterSettings {
            t_ref: shift.t_ref,
            ..self
        }
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
        for iso in isotherms {
            let points = (1..).zip(&iso.storage).zip(&iso.loss);
            scale::check_modulus_scale(
                iso.temperature,
                points.flat_map(|((k, &e1), &e2)| [(k, "E′", e1), (k, "E″", e2)]),
            )?;
        }
        self.check_temperatures(isotherms.iter().map(|i| i.temperature).collect())
    }

    /// The checks of [`MasterSettings::check`] that concern the
    /// temperatures alone (at least one, each isotherm checked already).
    pub(crate) fn check_temperatures(
        &self,
        mut temps: Vec<f64>,
    ) -> Result<ValidMasterSettings, FitError> {
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
                ShiftLaw::WlfArrhenius if temps.len() < 5 => {
                    return Err(FitError::setting(
                        "shift",
                        format!(
                            "WLF above a junction with Arrhenius below has four constants and {} \
                             isotherms cannot test them: use the shift \"wlf\", \"arrhenius\" or \
                             \"free\", or measure more temperatures",
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
            t_ref_given: self.t_ref.is_some(),
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
    /// The reduced frequencies (ω a_T, rad/s) the isotherms whose shifts
    /// the data determine cover: the part of the curve that is measured
    /// rather than placed by the law; None where no isotherm is.
    pub determined_window: Option<[f64; 2]>,
    /// The van Gurp–Palmen test of the unshifted isotherms: every point
    /// (log10 |E*|, δ), the pairs' numbers and the ranges.
    pub van_gurp_palmen: VanGurpPalmen,
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
        let (a, b) = shift.factors_of(iso.temperature)?;
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
    reach::check_reach(
        &shift,
        points.iter().map(|p| (p.temperature, p.reduced_omega)),
        ("reduced frequency ω a_T", "rad/s"),
    )?;
    points.sort_by(|p, q| p.reduced_omega.total_cmp(&q.reduced_omega));
    let omega: Vec<f64> = points.iter().map(|p| p.reduced_omega).collect();
    let storage: Vec<f64> = points.iter().map(|p| p.storage).collect();
    let loss: Vec<f64> = points.iter().map(|p| p.loss).collect();
    let fit = fit_prony(&omega, &storage, &loss)?;
    let lowest = storage.iter().fold(f64::INFINITY, |m, &e| m.min(e));
    let warnings = series_warnings(
        &shift,
        (lowest, fit.prony.static_modulus()),
        fit.converged,
        ("E′", "outside the data"),
    );
    let determined_window = window(
        points
            .iter()
            .filter(|p| shift.is_determined(p.temperature))
            .map(|p| p.reduced_omega),
    );
    Ok(MasterCurve {
        shift,
        points,
        fit,
        determined_window,
        van_gurp_palmen: van_gurp_palmen(isotherms),
        warnings,
    })
}

/// The smallest and largest of `values`; None for none.
pub(crate) fn window(values: impl Iterator<Item = f64>) -> Option<[f64; 2]> {
    values.fold(None, |w, v| match w {
        None => Some([v, v]),
        Some([lo, hi]) => Some([lo.min(v), hi.max(v)]),
    })
}

/// The shift's warnings and the series': no rubbery plateau when the
/// fitted E0 (`moduli.1`) lies far below the smallest measured modulus
/// (`moduli.0`, of `words.0`, the series falling below it `words.1`), and
/// an unconverged fit.
pub(crate) fn series_warnings(
    shift: &ShiftFactors,
    moduli: (f64, f64),
    converged: bool,
    words: (&str, &str),
) -> Vec<String> {
    let mut warnings = shift.warnings.clone();
    let (lowest, static_modulus) = moduli;
    let (measured, beyond) = words;
    if static_modulus < 1e-3 * lowest {
        warnings.push(format!(
            "the data reach no rubbery plateau: the static modulus E0 = {static_modulus:.3e} Pa is \
             not determined (the series falls below the smallest measured {measured}, \
             {lowest:.3e} Pa, {beyond}); μ at speeds below the master curve's range, and static \
             contact sizes, depend on it"
        ));
    }
    if !converged {
        warnings.push(
            "the Prony fit stopped before its convergence test passed; the series is the best \
             found"
                .into(),
        );
    }
    warnings
}

#[cfg(test)]
mod replica_tests;
#[cfg(test)]
mod tests;
