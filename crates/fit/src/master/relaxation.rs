//! A master curve from stress-relaxation isotherms: E(t) measured at
//! several temperatures, superposed in log t with the shift machinery of
//! the frequency sweeps, and a smooth Prony series fitted to it.
//!
//! Superposition in time (Ferry 1980, ch. 11): with the convention of
//! `rollfit_model::modulus::shift`, E*(ω, T) = b_T E*_ref(ω a_T). The
//! relaxation modulus is the inverse Fourier transform of E*(ω)/(iω), so
//! the same statement in time reads
//!
//!   E(t, T) = b_T E_ref(t/a_T):
//!
//! a point measured at (t, T) lies on the master curve at the reduced time
//! t_r = t/a_T, while a frequency point goes to ω_r = ω a_T. A warmer solid
//! (a_T < 1) relaxes sooner: its t_r is longer. (A series shifted by
//! τ_k → τ_k a_T gives both at once: e^(−t/(τ_k a_T)) = e^(−(t/a_T)/τ_k).)
//!
//! The shift therefore runs on the curve y = log10 E(t) against
//! x = −log10 t = log10(1/t): on that axis E(t, T)(x) = E_ref(x + log10 a_T),
//! the relation of log E′ against log ω, so the pairs, their standard
//! errors, the network, the laws and `auto` ([`super::horizontal`],
//! [`super::pairwise`], [`super::network`], [`super::law_choice`]) are
//! those of the frequency sweeps unchanged, with log E(t) as the only
//! curve (a relaxation run has no tan δ; with vertical factors the offset
//! of log E is free and the shape of E(t) alone fixes the shift, as in
//! Dealy & Plazek's recipe). Where E(t) is flat (a glassy or rubbery
//! plateau) the pair is undetermined, as for E′.
//!
//! The shifted points are fitted with [`fit_relaxation_prony`]: the series
//! E(t) = E0 + Σ H_k e^(−t/τ_k) is the same object as the frequency fit's,
//! so material.toml carries it in the same form.
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 3 (E(t) and E*(ω) of one spectrum), ch. 11 (reduced
//!   variables, t/a_T).
//! - N.W. Tschoegl, *The Phenomenological Theory of Linear Viscoelastic
//!   Behavior*, Springer 1989, ch. 6 (time–temperature superposition).
//! - J. Dealy, D. Plazek, "Time–temperature superposition — a users
//!   guide", Rheology Bulletin 78(2) (2009) 16–31.

pub use super::relaxation_prony::{RelaxationFit, fit_relaxation_prony};

use super::horizontal::{Domain, Superposable};
use super::shifts::{ShiftFactors, superpose};
use super::{MasterSettings, ValidMasterSettings, series_warnings};
use crate::error::FitError;
use crate::shift::overlap::Curve;
use rollfit_model::ViscoelasticModulus;

/// One stress-relaxation isotherm: E(t) at one temperature.
#[derive(Debug, Clone, PartialEq)]
pub struct RelaxationIsotherm {
    /// Temperature, °C.
    pub temperature: f64,
    /// Times since the step of strain, s, increasing.
    pub time: Vec<f64>,
    /// Relaxation modulus E(t) at each time (Young's), Pa.
    pub modulus: Vec<f64>,
}

/// One relaxation point on the master curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RelaxationPoint {
    /// Reduced time t/a_T, s.
    pub reduced_time: f64,
    /// E(t)/b_T, Pa.
    pub modulus: f64,
    /// The isotherm's temperature, °C.
    pub temperature: f64,
    /// The measured time t, s.
    pub time: f64,
}

/// A relaxation master curve built from isotherms.
#[derive(Debug, Clone)]
pub struct RelaxationMaster {
    /// The shift factors and their law.
    pub shift: ShiftFactors,
    /// Every point at the reference state, ascending in reduced time.
    pub points: Vec<RelaxationPoint>,
    /// The Prony series at T_ref.
    pub fit: RelaxationFit,
    /// Things the user should know (the shift's among them).
    pub warnings: Vec<String>,
}

impl RelaxationMaster {
    /// The verdict on this curve: the shifts' reasons
    /// ([`super::quality::assess`]), and a series that does not follow
    /// the data. E(t) of every linear viscoelastic solid is a non-negative
    /// sum of decaying exponentials (completely monotone: it never rises
    /// with time, Ferry ch. 3), which is the series fitted; its misfit is
    /// therefore at least the distance of the data from any causal E(t),
    /// and one above [`super::quality::NONCAUSAL_FLOOR`] (0.1 decades RMS,
    /// 26 %) is data no relaxation modulus follows, or a series that
    /// missed them. There is no separate floor to tell the two apart, as
    /// E′ and E″ have.
    pub fn quality(&self) -> super::quality::MasterQuality {
        let mut quality = super::quality::assess(&self.shift, None);
        let (misfit, limit) = (self.fit.misfit, super::quality::NONCAUSAL_FLOOR);
        if misfit.is_nan() || misfit > limit {
            quality.reasons.push(format!(
                "the Prony series misses E(t) by {misfit:.3} decades RMS (limit {limit}): a \
                 relaxation modulus never rises with time, and no non-negative series comes \
                 closer to these data; check that the modulus column is E(t) or G(t) after a \
                 step of strain (not a creep compliance, not a stress during loading), its unit, \
                 and that the times count from the step"
            ));
            quality.verdict = "poor";
        }
        quality
    }
}

/// Where a relaxation run stops increasing in time: the first index k ≥ 1
/// with t_k ≤ t_{k−1}, None when the times increase throughout. Front ends
/// name the file lines of points k − 1 and k with it.
pub fn time_turn(time: &[f64]) -> Option<usize> {
    (1..time.len()).find(|&k| time[k] <= time[k - 1])
}

impl MasterSettings {
    /// Checks the settings against relaxation isotherms: each with finite
    /// positive t and E(t) of equal lengths and increasing times, then the
    /// temperatures as [`MasterSettings::check`] does.
    pub fn check_relaxation(
        &self,
        isotherms: &[RelaxationIsotherm],
    ) -> Result<ValidMasterSettings, FitError> {
        if isotherms.is_empty() {
            return Err(FitError::InsufficientData(
                "no isotherms: a master curve needs relaxation points".into(),
            ));
        }
        for iso in isotherms {
            check_isotherm(iso)?;
        }
        for iso in isotherms {
            let points = (1..).zip(&iso.modulus).map(|(k, &e)| (k, "E(t)", e));
            super::scale::check_modulus_scale(iso.temperature, points)?;
        }
        self.check_temperatures(isotherms.iter().map(|i| i.temperature).collect())
    }
}

/// Finite positive values of equal lengths, increasing times.
fn check_isotherm(iso: &RelaxationIsotherm) -> Result<(), FitError> {
    let t = iso.temperature;
    let refuse = |what: String| {
        Err(FitError::InsufficientData(format!(
            "relaxation isotherm {t} °C: {what}"
        )))
    };
    if !(t.is_finite() && t > -273.15) {
        return Err(FitError::InsufficientData(format!(
            "isotherm temperature {t} °C is not a temperature"
        )));
    }
    let n = iso.time.len();
    if n == 0 || iso.modulus.len() != n {
        return refuse(format!(
            "{n} times and {} moduli: need equal, non-zero counts",
            iso.modulus.len()
        ));
    }
    for (i, (&time, &e)) in iso.time.iter().zip(&iso.modulus).enumerate() {
        if !(time > 0.0 && e > 0.0 && time.is_finite() && e.is_finite()) {
            return refuse(format!(
                "point {} has t = {time} s, E(t) = {e} Pa: both must be finite and positive",
                i + 1
            ));
        }
    }
    if let Some(k) = time_turn(&iso.time) {
        return refuse(format!(
            "times do not increase: points {} and {} are at t = {:e} s and {:e} s",
            k,
            k + 1,
            iso.time[k - 1],
            iso.time[k]
        ));
    }
    Ok(())
}

/// The curve the shift compares: log10 E(t) against −log10 t (module doc).
fn curve(iso: &RelaxationIsotherm) -> Curve {
    Curve::new(
        iso.time
            .iter()
            .zip(&iso.modulus)
            .map(|(t, e)| (-t.log10(), e.log10()))
            .collect(),
    )
}

/// The shift factors of relaxation isotherms (module doc).
pub fn relaxation_shift_factors(
    isotherms: &[RelaxationIsotherm],
    settings: &ValidMasterSettings,
) -> Result<ShiftFactors, FitError> {
    let input = isotherms
        .iter()
        .map(|iso| Superposable {
            temperature: iso.temperature,
            points: iso.time.len(),
            curves: vec![curve(iso)],
        })
        .collect();
    superpose(input, settings, Domain::Time)
}

/// Shifts the relaxation isotherms and fits the Prony series (module doc).
pub fn build_relaxation_master(
    isotherms: &[RelaxationIsotherm],
    settings: &ValidMasterSettings,
) -> Result<RelaxationMaster, FitError> {
    let shift = relaxation_shift_factors(isotherms, settings)?;
    let mut points = Vec::new();
    for iso in isotherms {
        let (a, b) = shift.factors_of(iso.temperature)?;
        for (&t, &e) in iso.time.iter().zip(&iso.modulus) {
            points.push(RelaxationPoint {
                // t_r = t/a_T (module doc): the opposite of ω a_T.
                reduced_time: t / a,
                modulus: e / b,
                temperature: iso.temperature,
                time: t,
            });
        }
    }
    super::reach::check_reach(
        &shift,
        points.iter().map(|p| (p.temperature, p.reduced_time)),
        ("reduced time t/a_T", "s"),
    )?;
    points.sort_by(|p, q| p.reduced_time.total_cmp(&q.reduced_time));
    let time: Vec<f64> = points.iter().map(|p| p.reduced_time).collect();
    let modulus: Vec<f64> = points.iter().map(|p| p.modulus).collect();
    let fit = fit_relaxation_prony(&time, &modulus)?;
    let lowest = modulus.iter().fold(f64::INFINITY, |m, &e| m.min(e));
    let warnings = series_warnings(
        &shift,
        (lowest, fit.prony.static_modulus()),
        fit.converged,
        ("E(t)", "at long times beyond the data"),
    );
    Ok(RelaxationMaster {
        shift,
        points,
        fit,
        warnings,
    })
}
