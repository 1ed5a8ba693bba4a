//! Shift factors of DMA isotherms found from the data alone: the
//! horizontal shift log a_T of each isotherm, and optionally the vertical
//! one log b_T, relative to the coldest isotherm.
//!
//! Each isotherm j holds E*(ω) at one temperature T_j. Superposition says
//! E*(ω, T) = b_T E*(ω a_T, T_ref): two neighbouring isotherms are the same
//! curves of x = log10 ω up to the shift s = log10 a_{T_{j+1}} − log10 a_{T_j}
//! (and c = log10 b_{T_{j+1}} − log10 b_{T_j}),
//!
//!   log E′_{j+1}(x) = log E′_j(x + s) + c,   log tan δ_{j+1}(x) = log tan δ_j(x + s).
//!
//! s minimises the sum of the two mean squared differences over the
//! overlap (the area between the curves, as the usual TTS tools do): log E′
//! rises monotonically through the transition and fixes s where tan δ is
//! flat, tan δ carries the shape where E′ is on a plateau. With vertical
//! shifts the E′ term is taken about its best constant c, so that only
//! tan δ, which b_T leaves alone, and the shape of E′ decide s; c is then
//! the mean log E′ difference at that s. The search scans ±15 decades before
//! refining (see `shift::overlap`), so it cannot lock onto the wrong flank
//! of the tan δ peak. Chaining neighbours gives log a_T (and log b_T) up to
//! a constant, which the driver ([`super`]) fixes at T_ref.
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 11 (reduced variables, the vertical factor T ρ/(T_ref ρ_ref)).
//! - J. Dealy, D. Plazek, "Time–temperature superposition — a users guide",
//!   Rheology Bulletin 78(2) (2009) 16–31 (shifting by overlap, vertical
//!   factors from data).

use super::isotherm::Isotherm;
use crate::error::FitError;
use crate::shift::overlap::{Curve, joint_relative_shift, offset_at};

/// log10 a_T and log10 b_T of isotherms at ascending temperatures,
/// relative to the first (both start at 0).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Chain {
    /// log10 a_T relative to the coldest isotherm.
    pub log_shift: Vec<f64>,
    /// log10 b_T relative to the coldest isotherm (zeros without vertical
    /// shifts).
    pub log_vertical: Vec<f64>,
}

/// The curves the shift compares: log10 E′ and log10 tan δ against
/// log10 ω.
fn curves(isotherm: &Isotherm) -> [Curve; 2] {
    let points = |y: &dyn Fn(usize) -> f64| {
        Curve::new(
            (0..isotherm.omega.len())
                .map(|i| (isotherm.omega[i].log10(), y(i)))
                .collect(),
        )
    };
    [
        points(&|i| isotherm.storage[i].log10()),
        points(&|i| (isotherm.loss[i] / isotherm.storage[i]).log10()),
    ]
}

/// Chains neighbour shifts over `sorted` (ascending, distinct
/// temperatures); refuses a pair that does not overlap, naming it.
pub(crate) fn chain(sorted: &[&Isotherm], vertical: bool) -> Result<Chain, FitError> {
    let all: Vec<[Curve; 2]> = sorted.iter().map(|i| curves(i)).collect();
    let mut out = Chain {
        log_shift: vec![0.0],
        log_vertical: vec![0.0],
    };
    for (k, pair) in all.windows(2).enumerate() {
        let lower = [&pair[0][0], &pair[0][1]];
        let upper = [&pair[1][0], &pair[1][1]];
        // upper(x) = lower(x + s): the warmer isotherm is the colder one
        // seen at frequencies 10^s times higher.
        let s = joint_relative_shift(&lower, &upper, &[vertical, false]).ok_or_else(|| {
            FitError::InsufficientData(format!(
                "the isotherms at {} °C and {} °C do not overlap in frequency once shifted (at \
                 least a fifth of the warmer one's points, and four, must fall inside the \
                 colder one's range): measure a temperature between them or over more \
                 frequencies",
                sorted[k].temperature,
                sorted[k + 1].temperature
            ))
        })?;
        let c = if vertical {
            offset_at(&pair[0][0], &pair[1][0], s).unwrap_or(0.0)
        } else {
            0.0
        };
        out.log_shift.push(out.log_shift[k] + s);
        out.log_vertical.push(out.log_vertical[k] + c);
    }
    Ok(out)
}
