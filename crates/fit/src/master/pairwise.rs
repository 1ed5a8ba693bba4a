//! The relative shift of two isotherms with its standard error, or the
//! verdict that the data do not determine it.
//!
//! Two isotherms at T_i < T_j are compared as in [`super::horizontal`]:
//! the warmer one's curves y_j(x) (log10 E′ and log10 tan δ against
//! x = log10 ω) against the colder one's y_i(x + s), linearly interpolated,
//! over the overlap, and the colder one's points against the warmer curve
//! at x − s; M_k(s) is the mean of the two mean squared differences. The
//! shift s minimises M(s) = Σ_k M_k(s) (k = E′, tan δ), found by a scan
//! over ±15 decades and a golden-section refinement. The count n_k below
//! is the mean of the two overlaps.
//!
//! Its uncertainty comes from a profile of the same objective read as a
//! χ²: the residual scatter of each curve at the optimum is taken as its
//! noise, σ_k² = n_k M_k(s₀)/(n_k − p_k) (p_k = 1 for the shift, 2 where a
//! vertical offset is also free), so that
//!
//!   χ²(s) = Σ_k (n_k − p_k) M_k(s)/M_k(s₀),
//!
//! and the 1σ interval is where χ²(s) − χ²(s₀) ≤ 1 (the profile-likelihood
//! interval; Bevington & Robinson ch. 11). A curve whose residuals include
//! the interpolation's own error counts that error as noise, which widens
//! the interval rather than narrowing it. Why a profile and not the
//! curvature alone: on a plateau the objective is flat and not quadratic,
//! and only the profile says how far it stays flat.
//!
//! A shift is *undetermined* when the 2σ interval (Δχ² ≤ 4) reaches the
//! end of the range the overlap rule allows (a fifth of the warmer
//! isotherm's points, and at least four, inside the colder one's range):
//! the data then fit about equally well at the boundary, and the optimum
//! found there is where the rule stopped the search, not a measurement.
//! This is the glassy (or rubbery) plateau, where E′ and tan δ are flat
//! and any shift over decades fits.
//!
//! The coverage of these intervals on synthetic isotherms is measured in
//! the tests (`master/tests.rs`).
//!
//! # References
//! - P.R. Bevington, D.K. Robinson, *Data Reduction and Error Analysis for
//!   the Physical Sciences*, 3rd ed., McGraw-Hill 2003, ch. 11 (confidence
//!   intervals from Δχ²).
//! - J. Dealy, D. Plazek, "Time–temperature superposition — a users
//!   guide", Rheology Bulletin 78(2) (2009) 16–31.
//! - P.S. Kott, "The delete-a-group jackknife", Journal of Official
//!   Statistics 17 (2001) 521–526.

use crate::shift::overlap::{Curve, differences, golden_section};

/// What the data say about the shift of a pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PairVerdict {
    /// Determined, with a finite standard error.
    Determined,
    /// The 2σ interval reaches the end of the allowed overlap: flat
    /// curves (a plateau), or an optimum on the boundary.
    Undetermined,
}

/// The relative shift of isotherm `upper` against `lower`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairShift {
    /// Index of the colder isotherm (ascending temperatures).
    pub lower: usize,
    /// Index of the warmer isotherm.
    pub upper: usize,
    /// s = log10 a_{T_upper} − log10 a_{T_lower} at the best overlap.
    pub shift: f64,
    /// 1σ of `shift`, decades (infinite when undetermined).
    pub sigma: f64,
    /// The mean log E′ offset at `shift` (the vertical step; 0 without
    /// vertical factors).
    pub vertical: f64,
    /// Whether the data determine the shift.
    pub verdict: PairVerdict,
}

/// The most groups the jackknife leaves out in turn per isotherm
/// ([`jackknife_sigma`]): 40 gives its σ² 39 degrees of freedom, a σ good
/// to about 11 %, and keeps the delete-one jackknife, to the bit, for
/// every isotherm of up to 40 frequencies (a DMA sweep is rarely longer).
const JACKKNIFE_GROUPS: usize = 40;

/// Scan step and half-range of the search, decades.
const STEP: f64 = 0.02;
const RANGE: f64 = 15.0;

/// The shift of `upper` against `lower` (the same curves of each: log E′
/// and log tan δ of a frequency sweep, log E(t) of a relaxation isotherm,
/// the first one the modulus), or None where the pair never overlaps as
/// the rule asks. With `vertical` the first curves may also differ by a
/// constant.
pub(crate) fn pair_shift(
    lower: &[Curve],
    upper: &[Curve],
    vertical: bool,
    indices: (usize, usize),
) -> Option<PairShift> {
    let free_offset = offsets(lower.len(), vertical);
    let need = (upper[0].x.len() / 5).max(4);
    let parts = |s: f64| mismatch(lower, upper, &free_offset, need, s);
    let cost = |s: f64| parts(s).map_or(f64::INFINITY, |p| total(&p));

    let (s0, s_min, s_max) = best_shift(&cost)?;
    let at_optimum = parts(s0)?;
    // χ² weights: (n_k − p_k)/M_k(s₀), the residual scatter as the noise.
    let weights: Vec<f64> = (0..at_optimum.len())
        .map(|k| {
            let (m, n) = at_optimum[k];
            let p = if free_offset[k] { 2.0 } else { 1.0 };
            let dof = (n as f64 - p).max(1.0);
            // Curves equal to rounding: the scatter of doubles, not zero.
            dof / m.max(1e-24)
        })
        .collect();
    let chi2 = |s: f64| -> f64 {
        parts(s).map_or(f64::INFINITY, |p| {
            p.iter().zip(&weights).map(|(q, w)| w * q.0).sum::<f64>()
        })
    };
    let chi0 = chi2(s0);
    // Where Δχ² first exceeds `level` walking from s₀ towards `end`
    // (bisected between scan points), or None if it never does inside the
    // allowed run.
    let crossing = |level: f64, direction: f64| -> Option<f64> {
        let mut inside = s0;
        let mut k = 1;
        loop {
            let s = s0 + direction * k as f64 * STEP;
            if s < s_min - 1e-12 || s > s_max + 1e-12 {
                // The last allowed scan point may still be below the level;
                // the run ends there.
                let edge = if direction > 0.0 { s_max } else { s_min };
                if chi2(edge) - chi0 > level {
                    return Some(bisect(&chi2, chi0 + level, inside, edge));
                }
                return None;
            }
            if chi2(s) - chi0 > level {
                return Some(bisect(&chi2, chi0 + level, inside, s));
            }
            inside = s;
            k += 1;
        }
    };
    let vertical_step = if vertical {
        let (sum, _, n) = differences(&lower[0], &upper[0], s0);
        if n > 0 { sum / n as f64 } else { 0.0 }
    } else {
        0.0
    };
    let wide = [crossing(4.0, -1.0), crossing(4.0, 1.0)];
    let (sigma, verdict) = if wide.iter().any(Option::is_none) {
        (f64::INFINITY, PairVerdict::Undetermined)
    } else {
        match (crossing(1.0, -1.0), crossing(1.0, 1.0)) {
            (Some(left), Some(right)) => {
                let profile = 0.5 * (right - left);
                let jackknife = jackknife_sigma(lower, upper, &free_offset, (s_min, s_max));
                let sigma = profile.max(jackknife);
                // On flat noisy curves the profile is as noisy as the data
                // and can show a sharp minimum; the jackknife's estimates
                // then scatter over the allowed range.
                if s0 - 2.0 * sigma <= s_min || s0 + 2.0 * sigma >= s_max {
                    (f64::INFINITY, PairVerdict::Undetermined)
                } else {
                    (sigma, PairVerdict::Determined)
                }
            }
            _ => (f64::INFINITY, PairVerdict::Undetermined),
        }
    };
    Some(PairShift {
        lower: indices.0,
        upper: indices.1,
        shift: s0,
        sigma,
        vertical: vertical_step,
        verdict,
    })
}

/// Whether each curve's offset is free: the modulus's (the first) with
/// vertical factors, never the others (tan δ, which b_T leaves alone).
fn offsets(curves: usize, vertical: bool) -> Vec<bool> {
    (0..curves).map(|k| k == 0 && vertical).collect()
}

/// The sum of the curves' mean squared mismatches. In curve order from
/// +0, so that two curves give M_0 + M_1 to the bit.
fn total(parts: &[(f64, usize)]) -> f64 {
    parts.iter().fold(0.0, |sum, p| sum + p.0)
}

/// Per curve (log E′, log tan δ; or log E(t)): the mean squared mismatch
/// of upper(x) against lower(x + s) (about its mean where the offset is
/// free) and the overlap count; None where the first curve's overlap is
/// shorter than `need` points or a curve does not overlap.
fn mismatch(
    lower: &[Curve],
    upper: &[Curve],
    free_offset: &[bool],
    need: usize,
    s: f64,
) -> Option<Vec<(f64, usize)>> {
    let mut out = vec![(0.0, 0); lower.len()];
    for k in 0..lower.len() {
        // Both ways: the upper points against the lower curve at x + s and
        // the lower points against the upper curve at x − s, so that
        // neither isotherm's sampling decides alone (on a flat overlap
        // the two one-way optima can lie decades apart).
        let one = differences(&lower[k], &upper[k], s);
        let other = differences(&upper[k], &lower[k], -s);
        if one.2 == 0 || other.2 == 0 || (k == 0 && one.2 < need) {
            return None;
        }
        let mean_square = |(sum, sum_sq, n): (f64, f64, usize)| {
            // upper − lower one way, lower − upper the other: the offset
            // changes sign.
            let mean = sum / n as f64;
            if free_offset[k] {
                (sum_sq / n as f64 - mean * mean).max(0.0)
            } else {
                sum_sq / n as f64
            }
        };
        out[k] = (
            0.5 * (mean_square(one) + mean_square(other)),
            (one.2 + other.2).div_ceil(2),
        );
    }
    Some(out)
}

/// The shift of least `cost` by a scan over ±[`RANGE`] and a
/// golden-section refinement, with the ends of the run of allowed
/// (finite-cost) shifts around it: (s₀, s_min, s_max).
fn best_shift(cost: &dyn Fn(f64) -> f64) -> Option<(f64, f64, f64)> {
    // A coarse scan finds the allowed run (the curves vary on the scale of
    // a decade); the best shift is then searched inside it.
    let coarse = 5.0 * STEP;
    let steps = (RANGE / coarse) as i64;
    let grid: Vec<f64> = (-steps..=steps).map(|i| i as f64 * coarse).collect();
    let costs: Vec<f64> = grid.iter().map(|&s| cost(s)).collect();
    let best = (0..grid.len())
        .filter(|&i| costs[i].is_finite())
        .min_by(|&a, &b| costs[a].total_cmp(&costs[b]))?;
    let mut lo = best;
    while lo > 0 && costs[lo - 1].is_finite() {
        lo -= 1;
    }
    let mut hi = best;
    while hi + 1 < grid.len() && costs[hi + 1].is_finite() {
        hi += 1;
    }
    // The run's ends to a fine step: bisection on where the overlap rule
    // starts to refuse.
    let edge = |inside: f64, outside: f64| {
        let (mut a, mut b) = (inside, outside);
        while (b - a).abs() > 1e-3 * STEP {
            let m = 0.5 * (a + b);
            if cost(m).is_finite() { a = m } else { b = m }
        }
        a
    };
    let s_min = if lo > 0 {
        edge(grid[lo], grid[lo - 1])
    } else {
        grid[lo]
    };
    let s_max = if hi + 1 < grid.len() {
        edge(grid[hi], grid[hi + 1])
    } else {
        grid[hi]
    };
    best_shift_in(cost, s_min, s_max)
}

/// The shift of least `cost` in [s_min, s_max]: a coarse scan, a fine one
/// around its best point, a golden-section refinement; (s₀, s_min, s_max).
fn best_shift_in(cost: &dyn Fn(f64) -> f64, s_min: f64, s_max: f64) -> Option<(f64, f64, f64)> {
    let coarse = 5.0 * STEP;
    let count = ((s_max - s_min) / coarse).ceil().max(1.0) as usize;
    let (mut best_s, mut best_cost) = (s_min, f64::INFINITY);
    for j in 0..=count {
        let s = s_min + (s_max - s_min) * j as f64 / count as f64;
        let c = cost(s);
        if c < best_cost {
            (best_s, best_cost) = (s, c);
        }
    }
    if !best_cost.is_finite() {
        return None;
    }
    let centre = best_s;
    for k in -5..=5 {
        let s = centre + k as f64 * STEP;
        if (s_min..=s_max).contains(&s) {
            let c = cost(s);
            if c < best_cost {
                (best_s, best_cost) = (s, c);
            }
        }
    }
    let (a, b) = ((best_s - STEP).max(s_min), (best_s + STEP).min(s_max));
    let refined = golden_section(cost, a, b, 40);
    let s0 = if cost(refined) <= best_cost {
        refined
    } else {
        best_s
    };
    Some((s0, s_min, s_max))
}

/// The two-sample jackknife of the shift: each group of points of the
/// upper isotherm, then of the lower one, left out in turn and the shift
/// found again over the `allowed` run;
/// σ² = Σ_samples (m−1)/m Σ_g (s_(g) − s̄)² over a sample's m groups.
///
/// An isotherm of at most [`JACKKNIFE_GROUPS`] points has a group per
/// point: the delete-one jackknife. A longer one is dealt into that many
/// interleaved groups (point i to group i mod G, so that each group spans
/// the whole sweep), the delete-a-group jackknife (Kott 2001), whose
/// variance has G − 1 degrees of freedom whatever the points: its cost
/// stays G refits per side where delete-one's grows as n refits of n
/// points each, n² (issue 36: 300 frequencies per isotherm took minutes).
fn jackknife_sigma(
    lower: &[Curve],
    upper: &[Curve],
    free_offset: &[bool],
    allowed: (f64, f64),
) -> f64 {
    let without = |curves: &[Curve], group: usize, groups: usize| -> Vec<Curve> {
        let drop = |c: &Curve| {
            let keep = |(i, _): &(usize, &f64)| i % groups != group;
            Curve {
                x: c.x
                    .iter()
                    .enumerate()
                    .filter(keep)
                    .map(|(_, &v)| v)
                    .collect(),
                y: c.y
                    .iter()
                    .enumerate()
                    .filter(keep)
                    .map(|(_, &v)| v)
                    .collect(),
            }
        };
        curves.iter().map(drop).collect()
    };
    let need = (upper[0].x.len() / 5).max(4);
    let minimum = |lower: &[Curve], upper: &[Curve]| -> Option<f64> {
        let cost = |s: f64| {
            mismatch(lower, upper, free_offset, need, s).map_or(f64::INFINITY, |p| total(&p))
        };
        // Searched afresh over the whole allowed run, so that a minimum
        // that noise made is free to move.
        let (s, _, _) = best_shift_in(&cost, allowed.0, allowed.1)?;
        cost(s).is_finite().then_some(s)
    };
    let mut variance = 0.0;
    for side in 0..2 {
        let n = if side == 0 {
            upper[0].x.len()
        } else {
            lower[0].x.len()
        };
        let groups = n.min(JACKKNIFE_GROUPS);
        let values: Vec<f64> = (0..groups)
            .filter_map(|g| {
                if side == 0 {
                    minimum(lower, &without(upper, g, groups))
                } else {
                    minimum(&without(lower, g, groups), upper)
                }
            })
            .collect();
        let m = values.len() as f64;
        if m < 2.0 {
            return f64::INFINITY;
        }
        let mean = values.iter().sum::<f64>() / m;
        variance += (m - 1.0) / m * values.iter().map(|v| (v - mean).powi(2)).sum::<f64>();
    }
    variance.sqrt()
}

/// The point between `inside` (below `target`) and `outside` (above) where
/// `f` crosses `target`, by bisection.
fn bisect(f: &dyn Fn(f64) -> f64, target: f64, inside: f64, outside: f64) -> f64 {
    let (mut a, mut b) = (inside, outside);
    for _ in 0..50 {
        let m = 0.5 * (a + b);
        if f(m) > target {
            b = m;
        } else {
            a = m;
        }
    }
    0.5 * (a + b)
}
