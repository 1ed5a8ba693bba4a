//! The exact body and material of a fitted modulus for the defect
//! correction (the parent module): the fitted Prony series without its
//! negligible terms, the rows' speeds on the master curve, and the check
//! that an exact solution has not failed.

use rollfit_model::Prony;
use rollfit_model::exact::{ExactRolling, exact_body};

use crate::data::Measurements;
use crate::error::FitError;
use crate::params::ValidFitParams;
use crate::report::{FitReport, ModelRecord};

/// Strengths below this fraction of E1 are left out of the fitted Prony
/// series before the exact solves. The smoothness penalty on ln H_k lets
/// the strengths outside the window fall to 1e-40 E1 and below, and with
/// such terms the exact cylinder fails without saying so: a fitted,
/// nearly single-term series with strengths down to 1e-42 E1 gave
/// μ = 8.5 where Eq. (11) gives 1.8e-5, with an error estimate of 1e-3;
/// without the terms below 1e-20 E1 the two agreed to 1e-4. Leaving them
/// out changes E*(ω) by less than their sum, a few 1e-12 relative, far
/// below the accuracy asked.
pub const NEGLIGIBLE_STRENGTH: f64 = 1e-12;

/// The largest factor by which μ_exact and Eq. (11)/(17) may differ before
/// the exact solution is taken to have failed: the approximation is
/// 4–10 % off near the friction maximum of a broad rubber and closer
/// elsewhere, so a factor of two is no approximation error.
pub const MAX_CORRECTION_FACTOR: f64 = 2.0;

/// The exact body of the set-up with the fitted modulus of `report`
/// (without its negligible terms, [`solvable_material`]) at `accuracy`,
/// and that modulus.
pub(super) fn exact_of(
    params: &ValidFitParams,
    report: &FitReport,
    accuracy: f64,
) -> Result<(Box<dyn ExactRolling>, Prony), FitError> {
    let prony = solvable_material(&report.model)?;
    let setup = &params.setup;
    let g = setup.geometry;
    let body = exact_body(
        g.shape,
        &prony,
        setup.substrate.poisson,
        g.radius,
        g.load,
        accuracy,
    )?;
    Ok((body, prony))
}

/// The fitted Prony series without its negligible terms (strengths below
/// [`NEGLIGIBLE_STRENGTH`] E1; the largest term is always kept), E0 kept.
pub(super) fn solvable_material(m: &ModelRecord) -> Result<Prony, FitError> {
    let floor = NEGLIGIBLE_STRENGTH * m.glassy_modulus;
    let largest = m.strengths.iter().copied().fold(0.0, f64::max);
    let (mut strengths, mut tau, mut dropped) = (Vec::new(), Vec::new(), 0.0);
    for (&h, &t) in m.strengths.iter().zip(&m.tau) {
        if h >= floor || h == largest {
            strengths.push(h);
            tau.push(t);
        } else {
            dropped += h;
        }
    }
    Ok(Prony::new(m.glassy_modulus - dropped, strengths, tau)?)
}

/// The rows' speeds on the master curve: v·a_T with the fitted shift for a
/// temperature set.
pub(super) fn reduced_speeds(rows: &Measurements, report: &FitReport) -> Vec<f64> {
    match (&report.shift, rows.temperature()) {
        (Some(shift), Some(temps)) => rows
            .speeds()
            .iter()
            .zip(temps)
            .map(|(v, t)| v * 10f64.powf(shift.log_shift_at(*t).unwrap_or(0.0)))
            .collect(),
        _ => rows.speeds().to_vec(),
    }
}

/// The error of a solve whose sibling panicked while holding the starts.
pub(super) fn poisoned(speed: f64) -> FitError {
    FitError::ExactPhysics {
        speed,
        problem: "another exact solve of the sweep panicked".to_string(),
    }
}

/// ln(μ_exact/μ_approx) at speed `v`, or the error that the exact
/// solution has failed (see [`MAX_CORRECTION_FACTOR`]).
pub(super) fn checked_ln_ratio(v: f64, exact: f64, approximate: f64) -> Result<f64, FitError> {
    let r = exact / approximate;
    if r.is_finite() && r.ln().abs() <= MAX_CORRECTION_FACTOR.ln() {
        return Ok(r.ln());
    }
    Err(FitError::ExactPhysics {
        speed: v,
        problem: format!(
            "μ = {exact:e} where Eq. (11)/(17) gives {approximate:e}; the two differ by far \
             less than a factor of {MAX_CORRECTION_FACTOR}, so the exact solution has failed \
             for this modulus (use physics = \"approximate\")"
        ),
    })
}
