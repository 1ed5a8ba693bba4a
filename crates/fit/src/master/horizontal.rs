//! Shift factors of DMA isotherms found from the data alone: the
//! horizontal shift of every pair of neighbouring isotherms with its
//! standard error (or the verdict that the data do not determine it), and
//! optionally the vertical step log b_T between them.
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
//! refining, so it cannot lock onto the wrong flank of the tan δ peak; the
//! standard error and the verdict come from the profile of the same
//! objective ([`super::pairwise`]). Where a neighbour pair is undetermined,
//! the next-neighbour pairs around it are tried as bridges. The shifts
//! themselves are then solved all at once ([`super::network`]).
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 11 (reduced variables, the vertical factor T ρ/(T_ref ρ_ref)).
//! - J. Dealy, D. Plazek, "Time–temperature superposition — a users guide",
//!   Rheology Bulletin 78(2) (2009) 16–31 (shifting by overlap, vertical
//!   factors from data).

use rayon::prelude::*;

use super::condense::bins;
use super::isotherm::Isotherm;
use super::pairwise::{PairCause, PairShift, PairVerdict, pair_shift, pooled_scatter};
use crate::shift::overlap::Curve;

/// What the isotherms were measured against: frequency sweeps, or
/// stress-relaxation runs in time ([`super::relaxation`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Domain {
    /// E*(ω): the curves log E′ and log tan δ against log ω.
    Frequency,
    /// E(t): the curve log E(t) against −log t.
    Time,
}

impl Domain {
    /// "frequency" or "time", for messages.
    pub(crate) fn axis(self) -> &'static str {
        match self {
            Domain::Frequency => "frequency",
            Domain::Time => "time",
        }
    }

    /// What more data would be, for messages.
    pub(crate) fn wider(self) -> &'static str {
        match self {
            Domain::Frequency => "more frequencies",
            Domain::Time => "longer times",
        }
    }
}

/// One isotherm as the shift sees it.
#[derive(Debug, Clone)]
pub(crate) struct Superposable {
    /// °C.
    pub temperature: f64,
    /// Its points.
    pub points: usize,
    /// The curves compared (the modulus's first).
    pub curves: Vec<Curve>,
}

/// The pairs of isotherms at ascending temperatures.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Pairs {
    /// Every pair compared: neighbours first, then bridges.
    pub pairs: Vec<PairShift>,
    /// The neighbours' best-overlap shifts chained from the coldest
    /// isotherm (0), determined or not: where an undetermined isotherm is
    /// placed when no law places it.
    pub chained: Vec<f64>,
    /// log10 b_T relative to the coldest isotherm (zeros without vertical
    /// shifts).
    pub log_vertical: Vec<f64>,
}

/// An isotherm of more frequencies than this is compared by its bins of
/// 1/[`ISOTHERM_BINS_PER_DECADE`] decade ([`curves`]).
const BIN_ISOTHERM_ABOVE: usize = 60;

/// Bins per decade of a dense isotherm's curves.
const ISOTHERM_BINS_PER_DECADE: f64 = 10.0;

/// The curves the shift compares: log10 E′ and log10 tan δ against
/// log10 ω.
///
/// An isotherm of more than [`BIN_ISOTHERM_ABOVE`] frequencies gives the
/// curves of its bins of a tenth of a decade ([`super::condense::bins`];
/// the mean log10 of each quantity in a bin). Two reasons, both measured
/// (`master::tests::pairwise_calibration_study`, 60 seeds, 1 % noise):
/// - honesty: a pair's σ comes from the residual scatter of one curve
///   against the other's linear interpolant, whose noise varies with where
///   the shifted points fall between the neighbour's (half at mid-segment,
///   whole at a node); on densely sampled curves that pulls the optimum
///   towards mid-segment shifts by more than σ. Point by point, 150
///   frequencies an isotherm gave RMS error/σ 2.9 and 2σ coverage 45 %,
///   600 gave 2.0 and 66 %; on bins, 150, 600 and 3000 frequencies give
///   0.90, 0.81, 0.79 and 98–99 % (10 to 60 points, not binned: 0.88–1.15
///   and 92–97 %).
/// - cost: a pair's shift is a scan of the overlap per trial shift and a
///   jackknife of refits; thousands of frequencies an isotherm
///   made that minutes, bins make it independent of the count.
///
/// The bin means carry the points' information about a shift of curves
/// that vary on the scale of a decade: their scatter is the points'
/// reduced by √n, and the shift's σ is measured from it.
pub(crate) fn curves(isotherm: &Isotherm) -> Vec<Curve> {
    if isotherm.omega.len() > BIN_ISOTHERM_ABOVE {
        let tan_delta: Vec<f64> = (0..isotherm.omega.len())
            .map(|i| isotherm.loss[i] / isotherm.storage[i])
            .collect();
        let b = bins(
            &isotherm.omega,
            &isotherm.storage,
            &tan_delta,
            ISOTHERM_BINS_PER_DECADE,
        );
        let curve = |y: &[f64]| Curve {
            x: b.omega.iter().map(|w| w.log10()).collect(),
            y: y.iter().map(|v| v.log10()).collect(),
        };
        return vec![curve(&b.storage), curve(&b.loss)];
    }
    let points = |y: &dyn Fn(usize) -> f64| {
        Curve::new(
            (0..isotherm.omega.len())
                .map(|i| (isotherm.omega[i].log10(), y(i)))
                .collect(),
        )
    };
    vec![
        points(&|i| isotherm.storage[i].log10()),
        points(&|i| (isotherm.loss[i] / isotherm.storage[i]).log10()),
    ]
}

/// The pairs of `sorted` (ascending, distinct temperatures). A pair that
/// cannot overlap is an undetermined pair of zero shift
/// ([`super::pairwise::PairCause::TooFewPoints`]); whether any shift is
/// determined is the network's question.
pub(crate) fn pairs(sorted: &[Superposable], vertical: bool) -> Pairs {
    let all: Vec<&[Curve]> = sorted.iter().map(|i| i.curves.as_slice()).collect();
    let noise = pooled_scatter(&all);
    let mut out = Pairs {
        pairs: Vec::new(),
        chained: vec![0.0],
        log_vertical: vec![0.0],
    };
    // The pairs are independent (each one's jackknife costs a few hundred
    // objective scans): in parallel, collected in order.
    // upper(x) = lower(x + s): the warmer isotherm is the colder one seen
    // at frequencies 10^s times higher.
    let neighbours: Vec<PairShift> = (0..all.len().saturating_sub(1))
        .into_par_iter()
        .map(|k| pair_shift(all[k], all[k + 1], vertical, &noise, (k, k + 1)))
        .collect();
    for (k, pair) in neighbours.into_iter().enumerate() {
        out.chained.push(out.chained[k] + pair.shift);
        out.log_vertical.push(out.log_vertical[k] + pair.vertical);
        out.pairs.push(pair);
    }
    let undetermined = |k: usize| out.pairs[k].verdict == PairVerdict::Undetermined;
    let bridges: Vec<PairShift> = (0..all.len().saturating_sub(2))
        .filter(|&k| undetermined(k) || undetermined(k + 1))
        .collect::<Vec<usize>>()
        .into_par_iter()
        .map(|k| pair_shift(all[k], all[k + 2], vertical, &noise, (k, k + 2)))
        .filter(|p| p.cause != PairCause::TooFewPoints)
        .collect();
    out.pairs.extend(bridges);
    out
}
