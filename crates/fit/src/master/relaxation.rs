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
//! Creep isotherms ([`TimeQuantity::Creep`]: the tensile creep compliance
//! D(t) after a step of stress, a shear J(t) converted by the reader) go
//! through the same pipeline. The compliance of one spectrum shifts as its
//! modulus does, D(t, T) = D_ref(t/a_T)/b_T, so 1/D(t, T) =
//! b_T (1/D_ref)(t/a_T): the shift compares log10 (1/D) against −log10 t,
//! exactly the relaxation curve with 1/D in place of E, and every shift
//! statement above holds unchanged. The reduced points carry D b_T. The
//! series is then fitted through its exact creep compliance
//! ([`fit_creep_prony`]), not through D ≈ 1/E.
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 3 (E(t) and E*(ω) of one spectrum), ch. 11 (reduced
//!   variables, t/a_T).
//! - N.W. Tschoegl, *The Phenomenological Theory of Linear Viscoelastic
//!   Behavior*, Springer 1989, ch. 6 (time–temperature superposition).
//! - J. Dealy, D. Plazek, "Time–temperature superposition — a users
//!   guide", Rheology Bulletin 78(2) (2009) 16–31.

pub use super::creep_prony::{CREEP_METHOD, fit_creep_prony};
pub use super::relaxation_prony::{RELAXATION_METHOD, RelaxationFit, fit_relaxation_prony};

use super::horizontal::{Domain, Superposable};
use super::isotherm::Sweep;
use super::repeats::Averaged;
use super::shifts::{ShiftFactors, superpose};
use super::{MasterSettings, ValidMasterSettings, series_warnings};
use crate::error::FitError;
use crate::shift::overlap::Curve;
use rollfit_model::ViscoelasticModulus;

/// What a time-domain isotherm measures (module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimeQuantity {
    /// The relaxation modulus E(t) after a step of strain (Young's), Pa.
    Relaxation,
    /// The creep compliance D(t) after a step of stress (tensile), 1/Pa.
    Creep,
}

impl TimeQuantity {
    /// "relaxation" or "creep" (master.json's `quantity`).
    pub fn name(self) -> &'static str {
        match self {
            TimeQuantity::Relaxation => "relaxation",
            TimeQuantity::Creep => "creep",
        }
    }

    /// The symbol of the (Young's or tensile) quantity: E(t) or D(t).
    pub fn symbol(self) -> &'static str {
        match self {
            TimeQuantity::Relaxation => "E(t)",
            TimeQuantity::Creep => "D(t)",
        }
    }

    /// Its SI unit.
    pub fn unit(self) -> &'static str {
        match self {
            TimeQuantity::Relaxation => "Pa",
            TimeQuantity::Creep => "1/Pa",
        }
    }

    /// The value as the modulus the shift compares: E, or 1/D.
    pub fn as_modulus(self, value: f64) -> f64 {
        match self {
            TimeQuantity::Relaxation => value,
            TimeQuantity::Creep => 1.0 / value,
        }
    }

    /// A Prony series' value of this quantity at time `t` (s): E(t), or
    /// its exact creep compliance.
    pub fn of_series(self, prony: &rollfit_model::Prony) -> impl Fn(f64) -> f64 + use<> {
        let (quantity, prony) = (self, prony.clone());
        let creep = (quantity == TimeQuantity::Creep)
            .then(|| rollfit_model::exact::CreepCompliance::from_prony(&prony));
        move |t| match &creep {
            None => prony.relaxation_modulus(t),
            Some(creep) => creep.at(t),
        }
    }
}

/// One time-domain isotherm: E(t) or D(t) at one temperature.
#[derive(Debug, Clone, PartialEq)]
pub struct RelaxationIsotherm {
    /// Temperature, °C.
    pub temperature: f64,
    /// Times since the step of strain or stress, s, increasing.
    pub time: Vec<f64>,
    /// The quantity at each time: E(t) (Young's), Pa, or D(t) (tensile),
    /// 1/Pa.
    pub value: Vec<f64>,
}

impl Sweep for RelaxationIsotherm {
    fn from_averaged(temperature: f64, averaged: Averaged) -> Self {
        RelaxationIsotherm {
            temperature,
            time: averaged.abscissa,
            value: averaged.quantities.into_iter().next().unwrap_or_default(),
        }
    }
}

/// One time-domain point on the master curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RelaxationPoint {
    /// Reduced time t/a_T, s.
    pub reduced_time: f64,
    /// E(t)/b_T, Pa, or D(t) b_T, 1/Pa.
    pub value: f64,
    /// The isotherm's temperature, °C.
    pub temperature: f64,
    /// The measured time t, s.
    pub time: f64,
}

/// A time-domain master curve built from isotherms.
#[derive(Debug, Clone)]
pub struct RelaxationMaster {
    /// What the isotherms measure.
    pub quantity: TimeQuantity,
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
        if (misfit.is_nan() || misfit > limit) && self.quantity == TimeQuantity::Creep {
            quality.reasons.push(format!(
                "the Prony series' creep compliance misses D(t) by {misfit:.3} decades RMS \
                 (limit {limit}): a creep compliance never falls with time and bends as one \
                 spectrum allows, and no non-negative series comes closer to these data; check \
                 that the column is a creep compliance J(t) or D(t) after a step of stress, its \
                 unit, and that the times count from the step"
            ));
            quality.verdict = "poor";
        } else if misfit.is_nan() || misfit > limit {
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
        self.check_time(isotherms, TimeQuantity::Relaxation)
    }

    /// [`MasterSettings::check_relaxation`] for isotherms of `quantity`:
    /// a creep compliance D(t) must lie where 1/D is a modulus
    /// ([`super::scale::check_modulus_scale`]'s range turned over).
    pub fn check_time(
        &self,
        isotherms: &[RelaxationIsotherm],
        quantity: TimeQuantity,
    ) -> Result<ValidMasterSettings, FitError> {
        if isotherms.is_empty() {
            return Err(FitError::InsufficientData(format!(
                "no isotherms: a master curve needs {} points",
                quantity.name()
            )));
        }
        for iso in isotherms {
            check_isotherm(iso, quantity)?;
        }
        for iso in isotherms {
            match quantity {
                TimeQuantity::Relaxation => {
                    let points = (1..).zip(&iso.value).map(|(k, &e)| (k, "E(t)", e));
                    super::scale::check_modulus_scale(iso.temperature, points)?;
                }
                TimeQuantity::Creep => check_compliance_scale(iso)?,
            }
        }
        self.check_temperatures(isotherms.iter().map(|i| i.temperature).collect())
    }
}

/// Refuses a creep compliance whose reciprocal lies outside the moduli a
/// master curve takes (1 … 1e13 Pa).
fn check_compliance_scale(iso: &RelaxationIsotherm) -> Result<(), FitError> {
    let (lo, hi) = crate::dma_rows::DMA_MODULUS_RANGE;
    match (1..)
        .zip(&iso.value)
        .find(|&(_, &d)| !(d.is_finite() && (1.0 / hi..=1.0 / lo).contains(&d)))
    {
        None => Ok(()),
        Some((point, d)) => Err(FitError::InsufficientData(format!(
            "isotherm at {} °C, point {point}: D(t) = {d} 1/Pa must lie in 1e-13 … 1 1/Pa (is \
             the compliance in 1/Pa? a rubber's compliance in 1/MPa read as 1/Pa lies a factor \
             1e6 too high: give the column its unit, e.g. \"J [1/MPa]\")",
            iso.temperature
        ))),
    }
}

/// Finite positive values of equal lengths, increasing times.
fn check_isotherm(iso: &RelaxationIsotherm, quantity: TimeQuantity) -> Result<(), FitError> {
    let t = iso.temperature;
    let refuse = |what: String| {
        Err(FitError::InsufficientData(format!(
            "{} isotherm {t} °C: {what}",
            quantity.name()
        )))
    };
    if !(t.is_finite() && t > -273.15) {
        return Err(FitError::InsufficientData(format!(
            "isotherm temperature {t} °C is not a temperature"
        )));
    }
    let n = iso.time.len();
    let values = match quantity {
        TimeQuantity::Relaxation => "moduli",
        TimeQuantity::Creep => "compliances",
    };
    if n == 0 || iso.value.len() != n {
        return refuse(format!(
            "{n} times and {} {values}: need equal, non-zero counts",
            iso.value.len()
        ));
    }
    for (i, (&time, &e)) in iso.time.iter().zip(&iso.value).enumerate() {
        if !(time > 0.0 && e > 0.0 && time.is_finite() && e.is_finite()) {
            return refuse(format!(
                "point {} has t = {time} s, {} = {e} {}: both must be finite and positive",
                i + 1,
                quantity.symbol(),
                quantity.unit()
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

/// The curve the shift compares: log10 E(t), or log10 (1/D(t)), against
/// −log10 t (module doc).
fn curve(iso: &RelaxationIsotherm, quantity: TimeQuantity) -> Curve {
    Curve::new(
        iso.time
            .iter()
            .zip(&iso.value)
            .map(|(t, &v)| (-t.log10(), quantity.as_modulus(v).log10()))
            .collect(),
    )
}

/// The shift factors of relaxation isotherms (module doc).
pub fn relaxation_shift_factors(
    isotherms: &[RelaxationIsotherm],
    settings: &ValidMasterSettings,
) -> Result<ShiftFactors, FitError> {
    time_shift_factors(isotherms, TimeQuantity::Relaxation, settings)
}

/// The shift factors of time-domain isotherms of `quantity` (module doc).
pub fn time_shift_factors(
    isotherms: &[RelaxationIsotherm],
    quantity: TimeQuantity,
    settings: &ValidMasterSettings,
) -> Result<ShiftFactors, FitError> {
    let input = isotherms
        .iter()
        .map(|iso| Superposable {
            temperature: iso.temperature,
            points: iso.time.len(),
            curves: vec![curve(iso, quantity)],
        })
        .collect();
    superpose(input, settings, Domain::Time)
}

/// Shifts the relaxation isotherms and fits the Prony series (module doc).
pub fn build_relaxation_master(
    isotherms: &[RelaxationIsotherm],
    settings: &ValidMasterSettings,
) -> Result<RelaxationMaster, FitError> {
    build_time_master(isotherms, TimeQuantity::Relaxation, settings)
}

/// Shifts time-domain isotherms of `quantity` and fits the Prony series,
/// to E(t) directly or through its exact creep compliance (module doc).
pub fn build_time_master(
    isotherms: &[RelaxationIsotherm],
    quantity: TimeQuantity,
    settings: &ValidMasterSettings,
) -> Result<RelaxationMaster, FitError> {
    let shift = time_shift_factors(isotherms, quantity, settings)?;
    let mut points = Vec::new();
    for iso in isotherms {
        let (a, b) = shift.factors_of(iso.temperature)?;
        for (&t, &v) in iso.time.iter().zip(&iso.value) {
            points.push(RelaxationPoint {
                // t_r = t/a_T (module doc): the opposite of ω a_T.
                reduced_time: t / a,
                // E_ref = E/b_T; D_ref = D b_T.
                value: quantity.as_modulus(quantity.as_modulus(v) / b),
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
    let value: Vec<f64> = points.iter().map(|p| p.value).collect();
    let fit = match quantity {
        TimeQuantity::Relaxation => fit_relaxation_prony(&time, &value)?,
        TimeQuantity::Creep => fit_creep_prony(&time, &value)?,
    };
    let lowest = value
        .iter()
        .fold(f64::INFINITY, |m, &v| m.min(quantity.as_modulus(v)));
    let measured = match quantity {
        TimeQuantity::Relaxation => "E(t)",
        TimeQuantity::Creep => "1/D(t)",
    };
    let warnings = series_warnings(
        &shift,
        (lowest, fit.prony.static_modulus()),
        fit.converged,
        (measured, "at long times beyond the data"),
    );
    Ok(RelaxationMaster {
        quantity,
        shift,
        points,
        fit,
        warnings,
    })
}
