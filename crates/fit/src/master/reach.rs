//! Whether the shifted isotherms stay where a master curve can be built:
//! every reduced frequency ω a_T (or reduced time t/a_T of relaxation
//! data) a finite number inside [`REDUCED_RANGE`].
//!
//! A shift law diverges at its singular temperature: WLF,
//! log10 a_T = −C1 (T − T_ref)/(C2 + T − T_ref), at T∞ = T_ref − C2
//! (Ferry ch. 11), Arrhenius, log10 a_T = E_a/(R ln 10)·(1/T − 1/T_ref),
//! at absolute zero. A T_ref at or just above T∞ puts every measured
//! isotherm an unbounded number of decades away (a_T → 0 above it): the
//! reduced frequencies underflow to 0 or overflow, and no Prony series on
//! them exists. Such a T_ref is refused before the series is fitted,
//! naming T_ref, the singular temperature and the measured range.
//!
//! Why [1e-100, 1e100] rad/s (or s): a reduced relaxation time of 1e100 s is
//! 82 decades beyond the age of the universe (4e17 s); no measurement can
//! test a curve there, and a τ grid spanning the range would hold
//! thousands of terms. Master curves of real polymers, even at T_ref near
//! T_g, span some 10–30 decades.
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 11.

use super::{ShiftFactors, ShiftLaw};
use crate::error::FitError;

/// Accepted reduced frequencies (rad/s) and reduced times (s) (module doc).
pub const REDUCED_RANGE: (f64, f64) = (1e-100, 1e100);

/// Refuses a shift that moves a point of the isotherm at temperature
/// `point.0` (°C) to the reduced value `point.1` outside
/// [`REDUCED_RANGE`]; `quantity` names it ("reduced frequency ω a_T",
/// rad/s, or "reduced time t/a_T", s).
pub(crate) fn check_reach(
    shift: &ShiftFactors,
    reduced: impl IntoIterator<Item = (f64, f64)>,
    quantity: (&str, &str),
) -> Result<(), FitError> {
    let (lo, hi) = REDUCED_RANGE;
    let Some((t, value)) = reduced
        .into_iter()
        .find(|&(_, x)| !(x.is_finite() && (lo..=hi).contains(&x)))
    else {
        return Ok(());
    };
    let (name, unit) = quantity;
    let temps: Vec<f64> = shift.shifts.iter().map(|s| s.temperature).collect();
    let (first, last) = (temps[0], temps[temps.len() - 1]);
    let t_ref = shift.t_ref;
    let log_a = shift
        .shifts
        .iter()
        .find(|s| s.temperature == t)
        .map_or(f64::NAN, |s| s.log_shift);
    let reached = if log_a.is_finite() {
        format!("a_T = 10^{log_a:.0}")
    } else {
        "an a_T that is not a number".to_string()
    };
    let singular = match singular_temperature(shift) {
        Some((at, law)) => format!(
            "{law} is singular at {at:.2} °C, where a_T is infinite, and T_ref lies at or near \
             it; "
        ),
        None => String::new(),
    };
    Err(FitError::setting(
        "T_ref",
        format!(
            "T_ref = {t_ref} °C: shifted to it, the isotherm at {t} °C reaches {reached} (a \
             {name} of {value:.3e} {unit}, outside {lo:e} … {hi:e} {unit}); {singular}the \
             isotherms were measured from {first} to {last} °C: choose T_ref well above the \
             singular temperature, best inside the measured range"
        ),
    ))
}

/// The singular temperature of the law applied (°C) and how messages
/// name it, where the law has one.
fn singular_temperature(shift: &ShiftFactors) -> Option<(f64, String)> {
    let t_ref = shift.t_ref;
    let wlf = |c1: f64, c2: f64| {
        (
            t_ref - c2,
            format!("the WLF law fitted to the shifts (C1 = {c1:.3}, C2 = {c2:.3} K about T_ref)"),
        )
    };
    let absolute_zero = |what: &str| (-273.15, format!("{what} (absolute zero)"));
    match shift.law {
        ShiftLaw::Wlf => shift.wlf.map(|w| wlf(w.c1, w.c2)),
        ShiftLaw::Arrhenius => Some(absolute_zero("the Arrhenius law")),
        ShiftLaw::WlfArrhenius => shift.wlf_arrhenius.map(|w| {
            if t_ref < w.t_junction {
                absolute_zero("the Arrhenius branch below the junction")
            } else {
                wlf(w.c1, w.c2)
            }
        }),
        ShiftLaw::Free | ShiftLaw::Auto => None,
    }
}
