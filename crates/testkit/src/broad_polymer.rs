//! A synthetic replica of a stiff polymer's broad real spectrum:
//! the shape of the master curve `rollfit master` builds from an acrylic
//! adhesive's 20 shear isotherms (E′ from about 0.1 GPa to 9.6 GPa over
//! 16 decades of frequency, tan δ falling from 0.6 to 0.01), written as a
//! causal Prony series, with tabulated shifts that have a kink at 0 °C (a
//! glass transition: nearly Arrhenius below, WLF-like and steeper above),
//! which no WLF law describes.
//!
//! The series: 97 relaxation times log-spaced over 1e-14 … 1e10 s with
//! strengths a log-normal in log10 τ (centre 10 s, 4.5 decades wide),
//! E0 = 30 MPa, E1 = 9.8 GPa. Its loss peak lies at the grid's slow end
//! (ω ≈ 1e-10 rad/s), below any data made here, so the data see only the
//! glassy side: a broad, nearly power-law spectrum.

use rollfit_fit::{FitParams, Measurements, ScaleAnchor, ShiftKind, ShiftSettings, ValidFitParams};
use rollfit_model::{Prony, ViscoelasticModulus};

use crate::materials::LogNormalSpectrum;
use crate::rolling::{set_with_shifts, setup};

/// Static Young's modulus of the replica, Pa.
pub const E0: f64 = 3e7;
/// Glassy Young's modulus of the replica, Pa.
pub const E1: f64 = 9.8e9;
/// The reference temperature of the master curve and the shifts, °C.
pub const T_REF: f64 = 20.0;

/// The replica's master curve at [`T_REF`].
pub fn truth() -> Prony {
    LogNormalSpectrum {
        terms: 97,
        log_tau: (-14.0, 10.0),
        centre: 1.0,
        width: 4.5,
        floor: 0.0,
        e0: E0,
        e1: E1,
    }
    .prony()
}

/// The tabulated log10 a_T (°C → decades, 0 at [`T_REF`]): slopes of 1.0 and
/// 1.1 decades per 20 K below 0 °C, then 2.0, 1.6, 1.3, 1.1 above; linear
/// between the nodes and beyond the ends.
pub fn log_shift(t: f64) -> f64 {
    const NODES: [(f64, f64); 7] = [
        (-40.0, 4.1),
        (-20.0, 3.1),
        (0.0, 2.0),
        (20.0, 0.0),
        (40.0, -1.6),
        (60.0, -2.9),
        (80.0, -4.0),
    ];
    let k = NODES
        .windows(2)
        .position(|w| t <= w[1].0)
        .unwrap_or(NODES.len() - 2);
    let ((t0, a0), (t1, a1)) = (NODES[k], NODES[k + 1]);
    a0 + (a1 - a0) * (t - t0) / (t1 - t0)
}

/// The seven temperatures of the 7 × 21 set, °C.
pub fn temperatures() -> Vec<f64> {
    (0..7).map(|k| -40.0 + 20.0 * k as f64).collect()
}

/// `count` log-spaced speeds from `v_min` over `decades`, m/s.
pub fn speeds(v_min: f64, decades: f64, count: usize) -> Vec<f64> {
    (0..count)
        .map(|i| v_min * 10f64.powf(decades * i as f64 / (count - 1) as f64))
        .collect()
}

/// The held-out shape: 7 temperatures (−40 … 80 °C) × 21 speeds
/// (1e-8 … 1 m/s), 1 % noise (ChaCha8 with `seed`), σ known.
pub fn set_7x21(seed: u64) -> Measurements {
    set_with_shifts(
        truth(),
        &temperatures(),
        &speeds(1e-8, 8.0, 21),
        log_shift,
        0.01,
        seed,
        true,
    )
}

/// A laboratory shape: `count` speeds over 4 decades (1e-5 … 0.1 m/s) at
/// 5 temperatures (−20 … 60 °C), relative noise `noise`, no σ column.
pub fn lab_set(count: usize, noise: f64, seed: u64) -> Measurements {
    let temps: Vec<f64> = (0..5).map(|k| -20.0 + 20.0 * k as f64).collect();
    set_with_shifts(
        truth(),
        &temps,
        &speeds(1e-5, 4.0, count),
        log_shift,
        noise,
        seed,
        false,
    )
}

/// |E| of the truth at 10 rad/s at [`T_REF`], Pa: the anchor of the fits.
pub fn anchor_modulus() -> f64 {
    truth().modulus(10.0).norm()
}

/// The fit of a replica set: shift `kind` about [`T_REF`], anchored at
/// 10 rad/s when `anchored`, no cross-check.
pub fn params(kind: ShiftKind, anchored: bool) -> ValidFitParams {
    FitParams {
        anchor: anchored.then(|| ScaleAnchor::ModulusAt {
            omega: 10.0,
            modulus: anchor_modulus(),
        }),
        shift: ShiftSettings {
            kind,
            t_ref: Some(T_REF),
            cross_check: false,
            ..ShiftSettings::default()
        },
        ..FitParams::default()
    }
    .check(setup())
    .unwrap()
}

/// The largest |fitted − true| log10 a_T over the set's temperatures.
pub fn worst_shift_error(report: &rollfit_fit::FitReport, temps: &[f64]) -> f64 {
    let shift = report.shift.as_ref().expect("a temperature set's shift");
    temps
        .iter()
        .map(|&t| (shift.log_shift_at(t).unwrap() - log_shift(t)).abs())
        .fold(0.0, f64::max)
}
