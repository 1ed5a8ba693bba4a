//! Temperature sets: one master curve at T_ref from μ(v) measured at several
//! temperatures, and the cross-check of its shifts.
//!
//! The joint fit (see [`crate::driver`]) fits the Prony master curve and
//! the shift together, evaluating the master curve at the reduced speeds
//! v·a_T ([`crate::shift`]). What this module adds:
//!
//! 1. A model-free start for the shift: the measured ln μ(log10 v) curves of
//!    neighbouring temperatures are overlapped ([`crate::shift::overlap`]),
//!    and for WLF the constants are fitted to those shifts (unless the
//!    scene's `[material.shift]` gives starting constants). The τ grid and
//!    the probed band follow the reduced speeds of this start.
//! 2. The cross-check users ask for: each temperature is fitted alone (the
//!    scale anchor carried to that temperature with the model-free start
//!    shift, so the check does not lean on the joint fit), and the
//!    single-temperature tan δ(ω) curves — which rolling data fix far
//!    better than |E| — are overlapped to estimate the shifts again
//!    ([`cross_check`]).
//!
//! 3. With `shift = "auto"`, the choice of the law from the joint fits
//!    under each ([`law`]).
//!
//! The fits these steps need are the driver's; they are passed in as a
//! function (a [`Fit`]), so that this module does not depend on the driver
//! that uses it.
//!
//! Conditioning (the test-only study `conditioning.rs`): the
//! column-scaled Jacobian J D⁻¹ of a joint fit with free shifts (D the
//! column norms, as Levenberg–Marquardt scales) is as well conditioned as
//! that of its material columns alone, ~1e2 at a λ the data choose and
//! ~1e5 at the bottom of the λ path: the shifts add no near-null
//! direction (a common shift of all temperatures against a shift of the
//! spectrum in τ is pinned by the anchor at T_ref and log a_T(T_ref) = 0),
//! and a slow free fit is the spectrum's ill-posedness at small λ.

#[cfg(test)]
mod conditioning;
pub(crate) mod cross_check;
pub(crate) mod law;

use crate::data::{Measurements, SPEED_RANGE};
use crate::error::FitError;
use crate::params::{ModulusAnchor, ShiftKind, TermRule, ValidFitParams};
use crate::report::FitReport;
use crate::shift::overlap::{Curve, chained_shifts};
use crate::shift::{ShiftParam, distinct_temperatures, index_of};

/// A whole fit of some measurements under some settings: the driver's
/// entry point, [`crate::driver::fit`].
pub(crate) trait Fit:
    Fn(&Measurements, &ValidFitParams) -> Result<FitReport, FitError>
{
}

impl<F: Fn(&Measurements, &ValidFitParams) -> Result<FitReport, FitError>> Fit for F {}

/// The shift of a temperature set with its starting θ_s.
#[derive(Debug, Clone)]
pub(crate) struct ShiftStart {
    pub param: ShiftParam,
    pub theta: Vec<f64>,
    /// Smallest and largest reduced speed at `theta`, m/s.
    pub range: (f64, f64),
    /// How the start was found, for the report's warnings.
    pub notes: Vec<String>,
}

impl ShiftStart {
    /// The same shift starting from `theta`.
    pub(crate) fn with_theta(&self, data: &Measurements, theta: Vec<f64>) -> ShiftStart {
        let range = reduced_range(&self.param, data, &theta);
        ShiftStart {
            param: self.param.clone(),
            theta,
            range,
            notes: Vec::new(),
        }
    }
}

fn reduced_range(param: &ShiftParam, data: &Measurements, theta: &[f64]) -> (f64, f64) {
    let (ln_a, _) = param.point_shifts(theta);
    data.speeds()
        .iter()
        .zip(&ln_a)
        .map(|(v, l)| v * l.exp())
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        })
}

/// The rows of `data` at each of the distinct temperatures `temps`.
pub(super) fn rows_by_temperature(data: &Measurements, temps: &[f64]) -> Vec<Vec<usize>> {
    let mut rows = vec![Vec::new(); temps.len()];
    for (i, &t) in data.temperature().unwrap_or_default().iter().enumerate() {
        if let Some(j) = index_of(temps, t) {
            rows[j].push(i);
        }
    }
    rows
}

/// None for data at one temperature (or without `T`); else the shift of the
/// set and a model-free start.
pub(crate) fn temperature_set(
    data: &Measurements,
    params: &ValidFitParams,
) -> Result<Option<ShiftStart>, FitError> {
    let temps = distinct_temperatures(data);
    if temps.len() < 2 {
        return Ok(None);
    }
    let param = ShiftParam::new(data, &params.shift)?;
    let rows = rows_by_temperature(data, &temps);
    if let Some((j, r)) = rows.iter().enumerate().find(|(_, r)| r.len() < 2) {
        return Err(FitError::InsufficientData(format!(
            "T = {} °C has {} measurement(s): a temperature set needs at least two speeds at \
             every temperature",
            temps[j],
            r.len()
        )));
    }
    let mut notes = Vec::new();
    let theta = match (params.shift.kind, params.shift.wlf_start) {
        (ShiftKind::Wlf, Some((c1, c2))) => {
            // WLF diverges at T_ref − C2 and does not hold at or below it:
            // constants singular at a measured temperature describe
            // another material, or C2 is not in K.
            let (t_ref, singular) = (param.t_ref(), param.t_ref() - c2);
            if let Some(&cold) = temps.iter().find(|&&t| t <= singular) {
                return Err(FitError::setting(
                    "[material.shift]",
                    format!(
                        "WLF with C1 = {c1}, C2 = {c2} K about T_ref = {t_ref} °C is singular at \
                         T_ref - C2 = {singular} °C, at or above the measured temperature \
                         {cold} °C, where the law gives no shift: give C2 above {} K (in K), \
                         or leave C1 and C2 out to start the shift from the data",
                        t_ref - cold
                    ),
                ));
            }
            notes.push(format!(
                "WLF started from the scene's C1 = {c1}, C2 = {c2} K"
            ));
            param.theta_of_wlf(c1, c2)
        }
        _ => {
            let curves: Vec<Curve> = rows
                .iter()
                .map(|r| {
                    Curve::new(
                        r.iter()
                            .map(|&i| (data.speeds()[i].log10(), data.friction()[i].ln()))
                            .collect(),
                    )
                })
                .collect();
            match chained_shifts(&curves) {
                Some(chain) => param.theta_of_log_shifts(&chain),
                None => {
                    notes.push(
                        "the μ(v) curves of neighbouring temperatures do not overlap, so the \
                         shift started from WLF with C1 = 8.86, C2 = 101.6 K; check the \
                         fitted shift"
                            .into(),
                    );
                    param.theta_of_wlf(8.86, 101.6)
                }
            }
        }
    };
    let range = reduced_range(&param, data, &theta);
    Ok(Some(ShiftStart {
        param,
        theta,
        range,
        notes,
    }))
}

/// The joint fit with WLF shifts that a free shift starts from (three or
/// more temperatures), and the free shift's start at its log10 a_T; `None`
/// when the WLF fit fails (the free fit then starts from the overlap).
///
/// A free shift is not determined where the master curve is smooth: at the
/// large λ that begin the λ path the spectrum is nearly a power law, whose
/// μ(v) is a power law too, and every temperature's curve slides along it.
/// Walked down from there, a laboratory set (5 temperatures × 12 speeds over
/// 4 decades, 20 K apart) ended 10 decades off at −20 °C with a 27 %
/// misfit, while WLF's two constants, tied to every temperature at once,
/// gave the shifts within 0.04 decade. So λ and the τ grid are chosen with
/// WLF shifts (by `fit_set`), and the free shifts are then fitted at that λ
/// from the WLF solution ([`crate::driver`]).
pub(crate) fn wlf_before_free(
    data: &Measurements,
    params: &ValidFitParams,
    start: &ShiftStart,
    fit_set: impl Fit,
) -> Option<(FitReport, ShiftStart)> {
    let temps = start.param.temperatures().to_vec();
    if params.shift.kind != ShiftKind::Free || temps.len() < 3 {
        return None;
    }
    let mut wlf = params.clone();
    wlf.shift.kind = ShiftKind::Wlf;
    // Only the WLF fit's material, λ and runs are used: its own cross-check
    // would be work thrown away.
    wlf.shift.cross_check = false;
    wlf.bands = false;
    let report = fit_set(data, &wlf).ok()?;
    let shift = report.shift.as_ref()?;
    let log_shift: Vec<f64> = temps
        .iter()
        .map(|&t| shift.log_shift_at(t).unwrap_or(0.0))
        .collect();
    let theta = start.param.theta_of_log_shifts(&log_shift);
    let free = start.with_theta(data, theta);
    Some((report, free))
}

/// The fit (by `fit_curve`) of all rows of a set as one curve at the start
/// shift's reduced speeds v·a_T (no shift fitted), which gives the joint fit
/// its τ grid, its starting material and the top of its λ path
/// ([`crate::driver`]). `None` when that fit fails; the joint fit then walks
/// the whole λ path.
///
/// Why: at the large λ where the λ path begins, the spectrum is nearly a
/// power law and so is μ(v); the temperatures' curves slide along it, and
/// a laboratory set (5 temperatures × 15 speeds over 4 decades) walked down
/// from there ended with WLF's C1 and C2 both near 1e189 (their linear
/// limit) and a 40 % misfit.
pub(crate) fn material_first(
    data: &Measurements,
    params: &ValidFitParams,
    start: &ShiftStart,
    fit_curve: impl Fit,
) -> Option<FitReport> {
    let (ln_a, _) = start.param.point_shifts(&start.theta);
    let reduced: Vec<f64> = data
        .speeds()
        .iter()
        .zip(&ln_a)
        .map(|(v, l)| v * l.exp())
        .collect();
    // Reduced speeds of a cold temperature can lie above the speeds a
    // measurement may have (1000 m/s); the one curve is then fitted in a
    // frame whose clock runs 10^k times slower: speeds u = v·a_T/10^k, and
    // with E_k(ω) = E*(ω 10^k) μ_k(u) = μ_ref(v·a_T) (the time–temperature
    // argument again), so the anchor's ω is divided and the times τ are
    // multiplied by 10^k, and divided back after the fit.
    let k = frame_decades(&reduced)?;
    let scale = 10f64.powi(k);
    let one_curve = Measurements::new(
        reduced.iter().map(|u| u / scale).collect(),
        data.friction().to_vec(),
        data.sigma().map(|s| s.to_vec()),
        None,
    )
    .ok()?;
    // Without a temperature column the rows are one curve: no shift, and so
    // no cross-check, is fitted to them.
    let mut single = params.clone();
    single.bands = false;
    if k != 0 {
        single.anchor = params.anchor.map(|a| ModulusAnchor {
            omega: a.omega / scale,
            ..a
        });
        if let TermRule::Explicit(tau) = &params.terms {
            single.terms = TermRule::Explicit(tau.iter().map(|t| t * scale).collect());
        }
    }
    let mut report = fit_curve(&one_curve, &single).ok()?;
    if k != 0 {
        for tau in &mut report.model.tau {
            *tau /= scale;
        }
    }
    Some(report)
}

/// The whole number k of decades by which speeds `reduced` are divided to
/// lie within the speeds a measurement may have ([`SPEED_RANGE`]): 0 when
/// they do, `None` when they span more than that range.
fn frame_decades(reduced: &[f64]) -> Option<i32> {
    let (lo, hi) = reduced
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), &u| {
            (lo.min(u), hi.max(u))
        });
    let (min, max) = SPEED_RANGE;
    let k = if hi > max {
        (hi / max).log10().ceil()
    } else if lo < min {
        (lo / min).log10().floor()
    } else {
        0.0
    };
    let scale = 10f64.powf(k);
    (lo / scale >= min && hi / scale <= max).then_some(k as i32)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reduced speeds inside the accepted range stay in their frame; above
    /// or below it they are moved by whole decades just inside; a span
    /// wider than the range has no frame.
    #[test]
    fn the_one_curve_frame_moves_by_whole_decades() {
        assert_eq!(frame_decades(&[1e-8, 1.0]), Some(0));
        assert_eq!(frame_decades(&[1e-6, 5e5]), Some(3));
        assert_eq!(frame_decades(&[3e-18, 1e-3]), Some(-3));
        assert_eq!(frame_decades(&[1e-9, 5e11]), None);
    }
}
