//! The joint fit's master curve: the DMA isotherms of a joint
//! fit of DMA and rolling data at their reduced frequencies ω a_T under the
//! joint shift, coloured by isotherm temperature, with the joint Prony
//! series on top, tan δ below and the shift factors at the right. It is the
//! picture `rollfit master` draws ([`DmaMasterFigure`]) with the joint
//! fit's points, curve and shift, so that the two read alike.
//!
//! The points are fit.json's `joint.dma`. Where the scene gives vertical
//! factors b_T the record's fitted moduli carry b_T; the points are divided
//! by it (b_T = E′_fit / E′_ref(ω a_T), the ratio of the record's value to
//! the reference curve's) so that every isotherm lies on the one reference
//! curve, as a DMA master curve draws them. Without vertical factors the
//! ratio is 1.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::dma_master::{DmaMasterFigure, MasterCurveFit, ShiftMarker, ShiftedPoint};
use super::isotherm_key::celsius;
use super::parts::isotherms;
use super::shift_panel::fitted_law_legend;
use super::{DrawResult, Figure};
use rollfit_fit::JointRecord;
use rollfit_io::fit_dir::FitDir;

/// Points of the drawn Prony curve.
const CURVE_POINTS: usize = 240;
/// Decades the curve extends beyond the DMA points and the fit's window.
const CURVE_MARGIN_DECADES: f64 = 0.3;
/// Samples of the shift law's curve.
const LAW_POINTS: usize = 100;
/// Temperatures closer than this, °C, are one isotherm.
const SAME_TEMPERATURE: f64 = 1e-6;

/// The joint master curve: what [`DmaMasterFigure`] draws, owned.
pub struct JointMasterFigure {
    /// DMA points at ω a_T, divided by b_T where known.
    pub points: Vec<ShiftedPoint>,
    /// The joint Prony series over the DMA points and the fit's window.
    pub curve: MasterCurveFit,
    /// Reference temperature, °C.
    pub t_ref: f64,
    /// log10 a_T of the fitted temperatures and of the DMA isotherms.
    pub shifts: Vec<ShiftMarker>,
    /// The shift law (T °C, log10 a_T), densely; empty for free shifts.
    pub shift_curve: Vec<(f64, f64)>,
    /// The law and its constants, for the shift panel's legend.
    pub shift_law: Vec<String>,
    /// The DMA file, as fit.json names it.
    pub dma_source: String,
}

impl JointMasterFigure {
    /// The figure of `fit`'s joint record `joint`.
    pub fn of(fit: &FitDir, joint: &JointRecord) -> JointMasterFigure {
        let points: Vec<ShiftedPoint> = joint
            .dma
            .iter()
            .map(|p| {
                let reference = fit.modulus_at(p.reduced_omega).re;
                let vertical = p.storage_fit / reference;
                let vertical = if vertical.is_finite() && vertical > 0.0 {
                    vertical
                } else {
                    1.0
                };
                ShiftedPoint {
                    reduced_omega: p.reduced_omega,
                    storage: p.storage / vertical,
                    loss: p.loss / vertical,
                    temperature: p.temperature,
                }
            })
            .collect();
        let shift = fit.summary.shift.as_ref();
        let t_ref = shift.map_or_else(
            || points.first().map_or(f64::NAN, |p| p.temperature),
            |s| s.t_ref,
        );
        let mut shifts: Vec<ShiftMarker> = shift
            .map(|s| {
                s.log_shift
                    .iter()
                    .map(|p| ShiftMarker {
                        temperature: p.temperature,
                        log_shift: p.log_shift,
                        sigma: p.log_shift_sigma,
                        determined: p.log_shift_sigma.is_finite(),
                    })
                    .collect()
            })
            .unwrap_or_default();
        // A DMA isotherm fit.json lists no shift for was moved by the law's
        // a_T: shown hollow, as a value applied.
        for p in &joint.dma {
            let listed = shifts
                .iter()
                .any(|s| (s.temperature - p.temperature).abs() < SAME_TEMPERATURE);
            let log_shift = (p.reduced_omega / p.omega).log10();
            if !listed && log_shift.is_finite() {
                shifts.push(ShiftMarker {
                    temperature: p.temperature,
                    log_shift,
                    sigma: f64::NAN,
                    determined: false,
                });
            }
        }
        shifts.sort_by(|a, b| a.temperature.total_cmp(&b.temperature));
        let shift_curve = match shift {
            Some(s) if s.model == "wlf" || s.model == "arrhenius" => {
                let (lo, hi) = shifts.iter().fold((t_ref, t_ref), |(lo, hi), m| {
                    (lo.min(m.temperature), hi.max(m.temperature))
                });
                (0..=LAW_POINTS)
                    .filter_map(|i| {
                        let t = lo + (hi - lo) * i as f64 / LAW_POINTS as f64;
                        s.log_shift_at(t).map(|l| (t, l))
                    })
                    .collect()
            }
            _ => Vec::new(),
        };
        JointMasterFigure {
            curve: sampled_curve(fit, &points),
            points,
            t_ref,
            shifts,
            shift_curve,
            shift_law: shift.map(fitted_law_legend).unwrap_or_default(),
            dma_source: joint.dma_source.clone(),
        }
    }

    fn inner(&self) -> DmaMasterFigure<'_> {
        DmaMasterFigure {
            points: &self.points,
            fit: &self.curve,
            t_ref: self.t_ref,
            shifts: &self.shifts,
            shift_curve: &self.shift_curve,
            shift_law: &self.shift_law,
            modulus_symbol: "E",
            verdict: None,
        }
    }
}

/// The joint Prony series (fit.json's, at the reference state) over the
/// DMA points' reduced frequencies and the fit's window.
fn sampled_curve(fit: &FitDir, points: &[ShiftedPoint]) -> MasterCurveFit {
    let window = fit.summary.window;
    let (lo, hi) = points
        .iter()
        .map(|p| p.reduced_omega)
        .filter(|w| *w > 0.0 && w.is_finite())
        .fold((window.omega_min, window.omega_max), |(lo, hi), w| {
            (lo.min(w), hi.max(w))
        });
    let (lo, hi) = (
        lo.log10() - CURVE_MARGIN_DECADES,
        hi.log10() + CURVE_MARGIN_DECADES,
    );
    let omega: Vec<f64> = (0..CURVE_POINTS)
        .map(|i| 10f64.powf(lo + (hi - lo) * i as f64 / (CURVE_POINTS - 1) as f64))
        .collect();
    let moduli: Vec<_> = omega.iter().map(|&w| fit.modulus_at(w)).collect();
    MasterCurveFit {
        storage: moduli.iter().map(|e| e.re).collect(),
        loss: moduli.iter().map(|e| e.im).collect(),
        omega,
    }
}

impl Figure for JointMasterFigure {
    fn name(&self) -> &'static str {
        "joint_master"
    }

    fn caption(&self) -> String {
        let isotherms = isotherms(self.points.iter().map(|p| p.temperature));
        format!(
            "Joint master curve at T_ref = {}: the {} points of {} DMA isotherm{} ({}) at their reduced frequencies ω a_T under the joint shift, E′ (filled) and E″ (open) coloured by temperature, with the joint fit's Prony curve (black) that also describes the rolling friction; tan δ = E″/E′ below; right, log10 a_T per temperature (hollow: the law's value applied) and the shift law with its constants.",
            celsius(self.t_ref),
            self.points.len(),
            isotherms.len(),
            if isotherms.len() == 1 { "" } else { "s" },
            self.dma_source,
        )
    }

    fn size(&self) -> (u32, u32) {
        self.inner().size()
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        self.inner().draw(root)
    }
}
