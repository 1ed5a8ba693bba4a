//! What the DMA isotherms say alone.
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
//! Isotherms that do not overlap (a sweep of two decades at temperatures
//! whose shifts are two decades apart) determine no shift between them:
//! no master curve can be built from them alone. The DMA part alone is
//! then each isotherm its own curve (a smooth Prony series per isotherm,
//! p the sum of their effective parameters): its σ and χ² are still
//! measured, and the joint fit takes every shift from the rolling data
//! (`crate::driver`'s `joint.rs`). Which shifts the DMA part alone
//! determines, with their σ, is reported ([`DmaAloneRecord`]). Where
//! only some are determined, the part alone is the master curve of those
//! and each other isotherm its own series (the full master curve places
//! them by a law the data cannot test, and their misfit there is not
//! noise).

use rollfit_model::ViscoelasticModulus;

use crate::error::FitError;
use crate::master::{
    Isotherm, MasterCurve, MasterSettings, ShiftLaw, build_master_curve, fit_prony,
};

use super::DmaRows;
use super::record::{DmaAloneRecord, DmaAloneShift};

/// The DMA isotherms fitted alone.
pub(crate) struct DmaAlone {
    /// The master curve of the isotherms; None where the data determine
    /// no shift between them (`undetermined` says why).
    pub master: Option<MasterCurve>,
    /// Why the isotherms alone make no master curve.
    pub undetermined: Option<String>,
    /// The isotherms' temperatures, ascending, °C.
    pub temperatures: Vec<f64>,
    /// Relative σ of E′ and E″.
    pub sigma: f64,
    /// Whether σ was given (`dma_sigma`) rather than estimated.
    pub sigma_given: bool,
    /// Σ r²/σ² of the DMA fit alone at the DMA points.
    pub chi2: f64,
    /// Effective parameters of the DMA fit alone.
    pub parameters: f64,
}

/// The master curve of `rows` and its χ² (module doc); each isotherm
/// alone where the master curve cannot be built from the shifts the
/// isotherms determine. Errors only for isotherms nothing can use
/// (settings or moduli `rollfit master` refuses).
pub(crate) fn dma_alone(rows: &DmaRows, sigma: Option<f64>) -> Result<DmaAlone, FitError> {
    let settings = MasterSettings::default().check(rows.isotherms())?;
    let (master, undetermined, squares, parameters) =
        match build_master_curve(rows.isotherms(), &settings) {
            Ok(master) => {
                let (squares, parameters) = partial_misfit(rows, &master)?;
                (Some(master), None, squares, parameters)
            }
            Err(FitError::InsufficientData(why)) => {
                let (squares, parameters) = isotherms_misfit(rows.isotherms())?;
                (None, Some(why), squares, parameters)
            }
            Err(e) => return Err(e),
        };
    let residuals = 2.0 * rows.len() as f64;
    let (sigma, sigma_given) = match sigma {
        Some(s) => (s, true),
        None => ((squares / (residuals - parameters).max(1.0)).sqrt(), false),
    };
    // A perfect series (synthetic data without noise) would give σ = 0:
    // the floor is the smallest σ `dma_sigma` accepts.
    let sigma = sigma.max(super::DMA_SIGMA_RANGE.0);
    let mut temperatures = rows.temperatures();
    temperatures.sort_by(f64::total_cmp);
    Ok(DmaAlone {
        chi2: squares / (sigma * sigma),
        master,
        undetermined,
        temperatures,
        sigma,
        sigma_given,
        parameters,
    })
}

/// Σ of squared ln residuals of the master curve at its points, and its
/// effective parameters (the series' plus the law's).
fn master_misfit(master: &MasterCurve) -> (f64, f64) {
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
    (squares, master.fit.effective_parameters + law_parameters)
}

/// The misfit of the part alone where `master` leaves isotherms
/// undetermined: the master curve of the determined isotherms alone, and
/// each other isotherm its own series. Why: `master` places those by its
/// law, which the data cannot test; their misfit there is the law's, not
/// the noise, and read as σ it weighted the DMA part seven times too
/// little (two of four isotherms undetermined, 1 % noise estimated as
/// 7.2 %).
fn partial_misfit(rows: &DmaRows, master: &MasterCurve) -> Result<(f64, f64), FitError> {
    let (determined, open): (Vec<Isotherm>, Vec<Isotherm>) = rows
        .isotherms()
        .iter()
        .cloned()
        .partition(|iso| master.shift.is_determined(iso.temperature));
    if open.is_empty() {
        return Ok(master_misfit(master));
    }
    let (squares, parameters) = if determined.len() > 1 {
        let settings = MasterSettings::default().check(&determined)?;
        match build_master_curve(&determined, &settings) {
            Ok(part) => master_misfit(&part),
            Err(FitError::InsufficientData(_)) => isotherms_misfit(&determined)?,
            Err(e) => return Err(e),
        }
    } else {
        isotherms_misfit(&determined)?
    };
    let (others, other_parameters) = isotherms_misfit(&open)?;
    Ok((squares + others, parameters + other_parameters))
}

/// Σ of squared ln residuals of each isotherm's own series, and the sum of
/// their effective parameters; an isotherm too short for a series (two
/// points) is described exactly by its two moduli per point.
fn isotherms_misfit(isotherms: &[Isotherm]) -> Result<(f64, f64), FitError> {
    let (mut squares, mut parameters) = (0.0, 0.0);
    for iso in isotherms {
        if iso.omega.len() < 3 {
            parameters += 2.0 * iso.omega.len() as f64;
            continue;
        }
        let fit = fit_prony(&iso.omega, &iso.storage, &iso.loss)?;
        for k in 0..iso.omega.len() {
            let e = fit.prony.modulus(iso.omega[k]);
            squares += (e.re / iso.storage[k]).ln().powi(2) + (e.im / iso.loss[k]).ln().powi(2);
        }
        parameters += fit.effective_parameters;
    }
    Ok((squares, parameters))
}

impl DmaAlone {
    /// log10 a_T of the isotherm at `t` about the DMA master's T_ref, where
    /// the isotherms alone determine it.
    pub fn determined_shift(&self, t: f64) -> Option<f64> {
        let master = self.master.as_ref()?;
        master
            .shift
            .shifts
            .iter()
            .find(|s| s.temperature == t && s.determined)
            .map(|s| s.log_shift)
    }

    /// The record of the part alone (fit.json's `joint.dma_alone`).
    pub fn record(&self) -> DmaAloneRecord {
        let Some(master) = &self.master else {
            return DmaAloneRecord {
                verdict: format!(
                    "the DMA isotherms alone do not determine any shift between them ({}); every \
                     shift comes from the rolling data and the joint fit",
                    self.undetermined.as_deref().unwrap_or("no overlap")
                ),
                law: None,
                t_ref: None,
                shifts: self
                    .temperatures
                    .iter()
                    .map(|&t| DmaAloneShift {
                        temperature: t,
                        determined: false,
                        log_shift: None,
                        log_shift_sigma: None,
                    })
                    .collect(),
            };
        };
        let shift = &master.shift;
        let shifts: Vec<DmaAloneShift> = shift
            .shifts
            .iter()
            .map(|s| DmaAloneShift {
                temperature: s.temperature,
                determined: s.determined,
                log_shift: s.log_shift_measured,
                log_shift_sigma: s
                    .log_shift_measured_sigma
                    .is_finite()
                    .then_some(s.log_shift_measured_sigma),
            })
            .collect();
        let open: Vec<String> = shifts
            .iter()
            .filter(|s| !s.determined)
            .map(|s| format!("{}", s.temperature))
            .collect();
        let verdict = if open.is_empty() {
            format!(
                "the DMA isotherms alone determine every shift ({} law, {})",
                shift.law.name(),
                shift.reason
            )
        } else {
            format!(
                "the DMA isotherms alone do not determine the shifts at {} °C; those come from \
                 the rolling data and the joint fit ({} law on the determined ones)",
                open.join(", "),
                shift.law.name()
            )
        };
        DmaAloneRecord {
            verdict,
            law: Some(shift.law.name().to_string()),
            t_ref: Some(shift.t_ref),
            shifts,
        }
    }
}
