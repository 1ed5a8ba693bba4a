//! Moving DMA points to the fit's reference state by time–temperature
//! superposition, with the convention of `rollfit_model::modulus::shift`:
//!
//! E*(ω, T) = E*_ref(ω a_T),
//!
//! so a point measured at (ω, T) lies on the reference master curve at the
//! reduced frequency ω_r = ω a_T (a_T < 1 above T_ref). No vertical
//! (density–temperature) factor is applied, as in the fit.
//!
//! Which shift:
//! 1. The DMA's own WLF constants ([`DmaWlf`], `--dma-wlf T_REF,C1,C2`)
//!    when given: log10 a_T = W(T) − W(T_fit), W(T) = −C1 (T − T_ref)/(C2 +
//!    T − T_ref), with T_fit the fit's reference temperature (the DMA's
//!    T_ref when the fit has none: a single-temperature fit does not say at
//!    which temperature it was measured).
//! 2. Else the fit's shift (a temperature set): log10 a_T from fit.json,
//!    WLF at any T above its divergence, a free shift only inside its
//!    listed temperatures (linear in T between them), an isotherm within
//!    [`ISOTHERM_TOLERANCE`] of a listed temperature taking its value.
//! 3. Else one temperature (or none) is used as measured; several are an
//!    error asking for `--dma-wlf`: without a shift they do not form one
//!    curve.
//!
//! Points are grouped into isotherms (temperatures within
//! [`ISOTHERM_TOLERANCE`] of a neighbour) and each isotherm is shifted
//! rigidly with its mean temperature: a controller's ±0.02 K scatter
//! should not bend an isotherm, and "the 150 °C isotherm" is what a user
//! names.

use super::{DmaData, DmaPoint, DmaWlf};
use crate::error::ReportError;
use crate::fit_dir::FitDir;

/// Temperatures closer than this (K) belong to one isotherm; also how far a
/// DMA isotherm may lie from a temperature a free shift lists and still
/// take its shift. Controllers hold a set point to ±0.1 K; steps of a
/// temperature programme are ≥ 2 K apart.
pub const ISOTHERM_TOLERANCE: f64 = 0.5;

/// One isotherm of a DMA file.
#[derive(Debug, Clone, PartialEq)]
pub struct Isotherm {
    /// Mean temperature, °C.
    pub temperature: f64,
    /// Indices of its points in `DmaData::points`.
    pub points: Vec<usize>,
}

/// The points at the reference state, with how they got there.
#[derive(Debug, Clone)]
pub struct Shifted {
    /// ω a_T (rad/s) with the measured moduli and temperature, ascending
    /// in reduced ω.
    pub points: Vec<DmaPoint>,
    /// (isotherm temperature °C, log10 a_T) per isotherm, ascending in T;
    /// empty when the file has no temperatures.
    pub log_shifts: Vec<(f64, f64)>,
    /// What shift was used and any extrapolation, for the user.
    pub notes: Vec<String>,
}

/// The isotherms of `points` (those with a temperature), ascending.
pub fn isotherms(points: &[DmaPoint]) -> Vec<Isotherm> {
    let mut order: Vec<(usize, f64)> = points
        .iter()
        .enumerate()
        .filter_map(|(i, p)| p.temperature.map(|t| (i, t)))
        .collect();
    order.sort_by(|a, b| a.1.total_cmp(&b.1));
    let mut groups: Vec<(Vec<usize>, Vec<f64>)> = Vec::new();
    let mut last = f64::NEG_INFINITY;
    for (i, t) in order {
        match groups.last_mut() {
            Some((indices, temps)) if t - last <= ISOTHERM_TOLERANCE => {
                indices.push(i);
                temps.push(t);
            }
            _ => groups.push((vec![i], vec![t])),
        }
        last = t;
    }
    groups
        .into_iter()
        .map(|(points, temps)| Isotherm {
            temperature: temps.iter().sum::<f64>() / temps.len() as f64,
            points,
        })
        .collect()
}

/// See the module doc.
pub(crate) fn to_reference(
    data: &DmaData,
    fit: &FitDir,
    options: &super::DmaOptions,
) -> Result<Shifted, ReportError> {
    let file = data.path.display();
    let isotherms = isotherms(&data.points);
    let without_t = data
        .points
        .iter()
        .filter(|p| p.temperature.is_none())
        .count();
    if without_t > 0 && without_t < data.points.len() {
        return Err(ReportError::format(
            &data.path,
            format!(
                "{without_t} of {} points have no temperature: cannot tell which isotherm they belong to",
                data.points.len()
            ),
        ));
    }
    let fit_shift = fit.summary.shift.as_ref();
    let mut notes = Vec::new();
    let mut log_shifts = Vec::with_capacity(isotherms.len());

    if let Some(wlf) = options.wlf {
        let target = fit_shift.map_or(wlf.t_ref, |s| s.t_ref);
        let at_target = dma_log_shift(&wlf, target, data)?;
        for iso in &isotherms {
            log_shifts.push((
                iso.temperature,
                dma_log_shift(&wlf, iso.temperature, data)? - at_target,
            ));
        }
        notes.push(match fit_shift {
            Some(s) => format!(
                "{file}: shifted to the fit's T_ref = {} °C with the DMA's WLF (T_ref = {} °C, C1 = {}, C2 = {} K)",
                s.t_ref, wlf.t_ref, wlf.c1, wlf.c2
            ),
            None => format!(
                "{file}: shifted to T_ref = {} °C with the DMA's WLF (C1 = {}, C2 = {} K); the fit has no temperature and is taken to be at {} °C",
                wlf.t_ref, wlf.c1, wlf.c2, wlf.t_ref
            ),
        });
    } else if let Some(shift) = fit_shift {
        let listed: Vec<f64> = shift.log_shift.iter().map(|s| s.temperature).collect();
        let (lo, hi) = listed
            .iter()
            .fold((shift.t_ref, shift.t_ref), |(lo, hi), &t| {
                (lo.min(t), hi.max(t))
            });
        let mut extrapolated = Vec::new();
        for iso in &isotherms {
            // A free shift is known at its listed temperatures; an isotherm
            // a controller held 0.02 K off one of them takes its value.
            let t = listed
                .iter()
                .copied()
                .find(|l| (l - iso.temperature).abs() <= ISOTHERM_TOLERANCE)
                .unwrap_or(iso.temperature);
            let log_shift = shift.log_shift_at(t).ok_or_else(|| {
                ReportError::Unanswerable(format!(
                    "{file}: the DMA isotherm at {:.1} °C cannot be shifted with the fit's {} shift (it covers {lo} to {hi} °C{}); give the DMA's own WLF constants with --dma-wlf T_REF,C1,C2 (`rollfit master` finds them from the isotherms)",
                    iso.temperature,
                    shift.model,
                    if shift.c1.is_some() { ", and WLF diverges below T_ref − C2" } else { "" }
                ))
            })?;
            if t < lo - ISOTHERM_TOLERANCE || t > hi + ISOTHERM_TOLERANCE {
                extrapolated.push(format!("{:.1}", iso.temperature));
            }
            log_shifts.push((iso.temperature, log_shift));
        }
        if isotherms.is_empty() {
            notes.push(format!(
                "{file}: no temperature in the DMA file; taken as measured at the fit's T_ref = {} °C",
                shift.t_ref
            ));
        } else {
            notes.push(format!(
                "{file}: shifted to the fit's T_ref = {} °C with the fit's {} shift",
                shift.t_ref, shift.model
            ));
        }
        if !extrapolated.is_empty() {
            notes.push(format!(
                "{file}: isotherms at {} °C lie outside the fit's temperatures ({lo} to {hi} °C): the fit's WLF is extrapolated there",
                extrapolated.join(", ")
            ));
        }
    } else {
        match isotherms.as_slice() {
            [] => {}
            [only] => {
                log_shifts.push((only.temperature, 0.0));
                notes.push(format!(
                    "{file}: one temperature ({:.1} °C) and the fit has none: compared as measured",
                    only.temperature
                ));
            }
            several => {
                let temps: Vec<String> = several
                    .iter()
                    .map(|i| format!("{:.1}", i.temperature))
                    .collect();
                return Err(ReportError::Unanswerable(format!(
                    "{file}: {} temperatures ({} °C) but the fit has no shift (it is not a temperature set): give the DMA's own WLF constants with --dma-wlf T_REF,C1,C2 (`rollfit master` finds them from the isotherms)",
                    several.len(),
                    temps.join(", ")
                )));
            }
        }
    }

    let mut points = data.points.clone();
    for (iso, (_, log_shift)) in isotherms.iter().zip(&log_shifts) {
        let factor = 10f64.powf(*log_shift);
        for &i in &iso.points {
            points[i].omega *= factor;
        }
    }
    points.sort_by(|a, b| a.omega.total_cmp(&b.omega));
    Ok(Shifted {
        points,
        log_shifts,
        notes,
    })
}

fn dma_log_shift(wlf: &DmaWlf, t: f64, data: &DmaData) -> Result<f64, ReportError> {
    wlf.log_shift_at(t).ok_or_else(|| {
        ReportError::Unanswerable(format!(
            "{}: {t:.1} °C is at or below the divergence of the DMA's WLF (T_ref − C2 = {} °C): it cannot be shifted",
            data.path.display(),
            wlf.t_ref - wlf.c2
        ))
    })
}
