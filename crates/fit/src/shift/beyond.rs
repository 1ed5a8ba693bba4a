//! What to say when a shift leaves the range the numbers can hold: a
//! reduced speed v a_T that is 0 or infinite, or a DMA reduced frequency
//! ω a_T outside `crate::master::reach::REDUCED_RANGE` (1e-100 …
//! 1e100 rad/s, beyond which ω τ squared overflows on the τ grid).
//!
//! It happens before any fitting when the shift cannot refer to T_ref:
//! T_ref far outside the measured temperatures (WLF, log10 a_T =
//! −C1 ΔT/(C2 + ΔT), ΔT = T − T_ref, takes the data's singular
//! temperature near T_ref and a_T → 0 at the data), a temperature column
//! in kelvin read as °C (293 … 333 "°C" puts T_ref = 20 °C far below it),
//! or a WLF start with C2 near 0 (the law singular at T_ref itself). The
//! message names T_ref, the measured range, the law's constants where it
//! has them, and what to do.

use super::{Kind, ShiftParam};
use crate::error::FitError;

/// All measured temperatures above this (°C) read like kelvin.
const KELVIN_LIKE: f64 = 150.0;

impl ShiftParam {
    /// The refusal of a shift at θ_s = `theta` that put a_T outside the
    /// floating-point range (module doc).
    pub(crate) fn beyond_range(&self, theta: &[f64]) -> FitError {
        let t_ref = self.t_ref;
        let (lo, hi) = (self.temps[0], self.temps[self.temps.len() - 1]);
        let place = if t_ref < lo {
            format!(
                "{:.1} K below the measured temperatures ({lo} to {hi} °C)",
                lo - t_ref
            )
        } else if t_ref > hi {
            format!(
                "{:.1} K above the measured temperatures ({lo} to {hi} °C)",
                t_ref - hi
            )
        } else {
            format!("inside the measured temperatures ({lo} to {hi} °C)")
        };
        let law = match self.kind {
            Kind::Wlf { c2_floor } => {
                let (c1, c2) = (theta[0].exp(), c2_floor + theta[1].exp());
                format!(
                    "WLF with C1 = {c1:.4}, C2 = {c2:.4} K about T_ref, singular at T_ref − C2 = \
                     {:.1} °C",
                    t_ref - c2
                )
            }
            Kind::Arrhenius => format!("Arrhenius with E_a = {:.4e} J/mol", theta[0].exp()),
            Kind::Free => "free shifts".to_string(),
        };
        let kelvin = if lo > KELVIN_LIKE {
            format!(
                "; the T column reads {lo} to {hi} °C: if it is in kelvin, give its unit (T_K, \
                 \"T [K]\")"
            )
        } else {
            String::new()
        };
        let (values, _) = self.log_shifts(theta);
        let worst = self
            .temps
            .iter()
            .zip(&values)
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
            .map_or(String::new(), |(t, v)| {
                format!(" (log10 a_T = {v:.4e} at {t} °C)")
            });
        FitError::setting(
            "T_ref",
            format!(
                "T_ref = {t_ref} °C lies {place}: the shift to it ({law}) puts a_T at a measured \
                 temperature{worst} beyond what the numbers can hold (a reduced speed or \
                 frequency of 0, infinite, or beyond 1e±100){kelvin}. Choose T_ref inside \
                 the measured range, where the data fix the shift (the law then carries the \
                 master curve to other temperatures), and give a WLF start (the scene's [fit] \
                 shift C1, C2) near the universal C1 = 17.4, C2 = 51.6 K or leave it out"
            ),
        )
    }
}
