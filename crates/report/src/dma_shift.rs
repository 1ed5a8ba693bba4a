//! Moving DMA points to a fit's reference state by time–temperature
//! superposition (docs/ARCHITECTURE.md, "Data flow", `compare`), with the
//! convention of `rollfit_model::modulus::shift`:
//!
//! E*(ω, T) = E*_ref(ω a_T),
//!
//! so a point measured at (ω, T) lies on the reference master curve at the
//! reduced frequency ω_r = ω a_T (a_T < 1 above T_ref). No vertical
//! (density–temperature) factor is applied, as in the fit. This is a step
//! of the comparison, not of reading: the DMA file is read by
//! [`rollfit_io::dma`], the fit folder by [`rollfit_io::fit_dir`].
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
//! Points are grouped into isotherms ([`rollfit_fit::master::grouping`]; the
//! points of a temperature ramp by exact temperature) and
//! each isotherm is shifted rigidly with its mean temperature: a
//! controller's ±0.02 K scatter should not bend an isotherm, and "the
//! 150 °C isotherm" is what a user names.

use std::path::Path;

use rollfit_fit::master::grouping::{Group, ISOTHERM_TOLERANCE};
use rollfit_io::FitDir;
use rollfit_io::dma::{DmaData, DmaOptions, DmaPoint, DmaWlf};
use rollfit_io::fit_dir::ShiftSummary;

use crate::error::ReportError;

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

/// DMA data moved to a fit's reference state (see the module doc).
pub trait ToReference {
    /// The points moved to the fit's reference state (ω·a_T), sorted by
    /// reduced ω, with notes on how (which shift, extrapolations).
    fn shifted(&self, fit: &FitDir, options: &DmaOptions) -> Result<Shifted, ReportError>;

    /// The points of [`ToReference::shifted`] alone.
    fn at_reference(
        &self,
        fit: &FitDir,
        options: &DmaOptions,
    ) -> Result<Vec<DmaPoint>, ReportError> {
        Ok(self.shifted(fit, options)?.points)
    }
}

impl ToReference for DmaData {
    fn shifted(&self, fit: &FitDir, options: &DmaOptions) -> Result<Shifted, ReportError> {
        to_reference(self, fit, options)
    }
}

/// log10 a_T per isotherm and notes for the user.
pub(crate) type Shifts = (Vec<(f64, f64)>, Vec<String>);

/// See the module doc.
fn to_reference(
    data: &DmaData,
    fit: &FitDir,
    options: &DmaOptions,
) -> Result<Shifted, ReportError> {
    // A ramp's points are grouped by exact temperature: each shifted at
    // its own.
    let isotherms = data.grouping().isotherms;
    let without = data
        .points
        .iter()
        .filter(|p| p.temperature.is_none())
        .count();
    if without > 0 && without < data.points.len() {
        return Err(ReportError::MixedTemperatures {
            path: data.path.clone(),
            without,
            total: data.points.len(),
        });
    }
    let (log_shifts, notes) = isotherm_shifts(&data.path, &isotherms, fit, options)?;
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

/// log10 a_T of each isotherm of the file at `path` towards the fit's
/// reference state, by the rules of the module doc, with notes; shared by
/// frequency sweeps and relaxation runs (`crate::relaxation_compare`).
pub(crate) fn isotherm_shifts(
    path: &Path,
    isotherms: &[Group],
    fit: &FitDir,
    options: &DmaOptions,
) -> Result<Shifts, ReportError> {
    let fit_shift = fit.summary.shift.as_ref();
    match (options.wlf, fit_shift) {
        (Some(wlf), _) => dma_wlf_shifts(path, isotherms, &wlf, fit_shift),
        (None, Some(shift)) => fit_shifts(path, isotherms, shift),
        (None, None) => as_measured(path, isotherms),
    }
}

/// Rule 1: the DMA's own WLF, towards the fit's T_ref (or its own).
fn dma_wlf_shifts(
    path: &Path,
    isotherms: &[Group],
    wlf: &DmaWlf,
    fit_shift: Option<&ShiftSummary>,
) -> Result<Shifts, ReportError> {
    let file = path.display();
    let target = fit_shift.map_or(wlf.t_ref, |s| s.t_ref);
    let at_target = dma_log_shift(wlf, target, path)?;
    let mut log_shifts = Vec::with_capacity(isotherms.len());
    for iso in isotherms {
        log_shifts.push((
            iso.temperature,
            dma_log_shift(wlf, iso.temperature, path)? - at_target,
        ));
    }
    let note = match fit_shift {
        Some(s) => format!(
            "{file}: shifted to the fit's T_ref = {} °C with the DMA's WLF (T_ref = {} °C, C1 = {}, C2 = {} K)",
            s.t_ref, wlf.t_ref, wlf.c1, wlf.c2
        ),
        None => format!(
            "{file}: shifted to T_ref = {} °C with the DMA's WLF (C1 = {}, C2 = {} K); the fit has no temperature and is taken to be at {} °C",
            wlf.t_ref, wlf.c1, wlf.c2, wlf.t_ref
        ),
    };
    Ok((log_shifts, vec![note]))
}

/// Rule 2: the fit's own shift (a temperature set).
fn fit_shifts(
    path: &Path,
    isotherms: &[Group],
    shift: &ShiftSummary,
) -> Result<Shifts, ReportError> {
    let file = path.display();
    let listed: Vec<f64> = shift.log_shift.iter().map(|s| s.temperature).collect();
    let (lo, hi) = listed
        .iter()
        .fold((shift.t_ref, shift.t_ref), |(lo, hi), &t| {
            (lo.min(t), hi.max(t))
        });
    let mut extrapolated = Vec::new();
    let mut log_shifts = Vec::with_capacity(isotherms.len());
    for iso in isotherms {
        // A free shift is known at its listed temperatures; an isotherm
        // a controller held 0.02 K off one of them takes its value.
        let t = listed
            .iter()
            .copied()
            .find(|l| (l - iso.temperature).abs() <= ISOTHERM_TOLERANCE)
            .unwrap_or(iso.temperature);
        let log_shift = shift
            .log_shift_at(t)
            .ok_or_else(|| ReportError::OutsideFitShift {
                path: path.to_path_buf(),
                temperature: iso.temperature,
                model: shift.model.clone(),
                lo,
                hi,
                wlf: shift.c1.is_some(),
            })?;
        if t < lo - ISOTHERM_TOLERANCE || t > hi + ISOTHERM_TOLERANCE {
            extrapolated.push(format!("{:.1}", iso.temperature));
        }
        log_shifts.push((iso.temperature, log_shift));
    }
    let mut notes = Vec::new();
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
    // A temperature ramp's points are grouped by exact temperature: list
    // the range, not thousands of them.
    extrapolated.dedup();
    let shown = match extrapolated.as_slice() {
        [first, .., last] if extrapolated.len() > 8 => {
            format!("{first} … {last} °C ({} temperatures)", extrapolated.len())
        }
        all => format!("{} °C", all.join(", ")),
    };
    if !extrapolated.is_empty() {
        notes.push(format!(
            "{file}: isotherms at {shown} lie outside the fit's temperatures ({lo} to {hi} °C): the fit's {} law is extrapolated there",
            if shift.model == "arrhenius" { "Arrhenius" } else { "WLF" }
        ));
    }
    Ok((log_shifts, notes))
}

/// Rule 3: no shift; one temperature (or none) as measured.
fn as_measured(path: &Path, isotherms: &[Group]) -> Result<Shifts, ReportError> {
    match isotherms {
        [] => Ok((Vec::new(), Vec::new())),
        [only] => Ok((
            vec![(only.temperature, 0.0)],
            vec![format!(
                "{}: one temperature ({:.1} °C) and the fit has none: compared as measured",
                path.display(),
                only.temperature
            )],
        )),
        several => Err(ReportError::NoShift {
            path: path.to_path_buf(),
            temperatures: several.iter().map(|i| i.temperature).collect(),
        }),
    }
}

fn dma_log_shift(wlf: &DmaWlf, t: f64, path: &Path) -> Result<f64, ReportError> {
    wlf.log_shift_at(t)
        .ok_or_else(|| ReportError::BelowDmaWlfPole {
            path: path.to_path_buf(),
            temperature: t,
            pole: wlf.t_ref - wlf.c2,
        })
}
