//! The relative shift of two isotherms with its standard error, or the
//! verdict that the data do not determine it.
//!
//! Two isotherms at T_i < T_j are compared as in [`super::horizontal`]:
//! the warmer one's curves y_j(x) (log10 E′ and log10 tan δ against
//! x = log10 ω) against the colder one's y_i(x + s), linearly interpolated,
//! over the overlap, and the colder one's points against the warmer curve
//! at x − s; M_k(s) is the mean of the two mean squared differences. The
//! shift s minimises M(s) = Σ_k M_k(s) (k = E′, tan δ), found by a scan
//! over every shift at which the isotherms overlap (below) and a
//! golden-section refinement. The count n_k below
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
//! the interval rather than narrowing it. The noise is never taken below
//! the isotherms' own scatter (from their third differences, which a
//! smooth sweep's trend and curvature do not enter): on an overlap of a
//! few points, two curves can match at one shift by chance far better
//! than their noise, and a profile scaled by that chance is sharp where
//! the data are flat. Why a profile and not the
//! curvature alone: on a plateau the objective is flat and not quadratic,
//! and only the profile says how far it stays flat.
//!
//! The search spans every shift at which the two isotherms overlap: at
//! least [`MIN_OVERLAP`] points of each inside the other's frequency range,
//! whatever the shift (no cap: a step of three decades between neighbours
//! is ordinary when it is measured). Whether the data determine the shift
//! is read from the profile alone:
//! - *flat*: χ²(s) − χ²(s₀) stays below 4 on both sides up to the ends of
//!   the overlap (a glassy or rubbery plateau: any shift fits);
//! - *at the overlap's end*: it stays below 4 on one side up to where the
//!   isotherms stop overlapping, so the best overlap may lie beyond it (a
//!   transition whose overlap is too narrow);
//! - *ambiguous*: another minimum, outside the 2σ interval, comes within
//!   Δχ² < 4 of the best (the curves match at two places);
//! - otherwise σ = max(profile, jackknife), and the shift is *determined*
//!   when σ ≤ [`DETERMINED_SIGMA`] and its 2σ interval lies inside the
//!   overlap. One rule, so the flag and σ never contradict each other.
//!
//! Superposition itself is tested per pair: the shift log E′ alone needs
//! and the one log tan δ alone needs are found the same way, each with
//! its own profile (and jackknife) σ. No single shift superposes the pair
//! (thermorheological complexity, e.g. a β relaxation that shifts with its
//! own activation energy) when
//! - at least one curve fixes a shift of its own (its profile rises by
//!   Δχ² ≥ 4 on both sides); the other's best may lie at the overlap's end
//!   (tan δ of a β relaxation that keeps wanting less shift than E′);
//! - the two differ by more than [`TTS_DISAGREEMENT`] and by more than
//!   twice their combined σ (an end counts as a place, σ = 0);
//! - each curve, judged by its noise, refuses the other's shift throughout
//!   that shift's 2σ interval: its mismatch there exceeds the 99 % quantile
//!   of χ²(n − p) with the isotherms' scatter as the noise (the pair's, or
//!   the whole set's pooled where larger: two isotherms' third differences
//!   give it with about six degrees of freedom). Mutual refusal is what a
//!   plateau's noise cannot fake: a flat curve's profile is bounded by
//!   chance, but it accepts the other curve's shift, and a sloped curve
//!   at the overlap's end is judged by its noise, not by its misfit there;
//! - a bridge over two steps names a failure only when both its curves fix
//!   their shifts: its common shift lies beyond its overlap as a rule on
//!   narrow windows, where nothing is compared.
//!
//! The pair then records which quantity carries the combined shift (the
//! one whose own shift lies nearer to it), and σ is at least half their
//! difference, so that the combined shift is never reported more precise
//! than the choice between the quantities. On the Eplexor-like replica
//! with a β process every failing neighbour pair is named, and on the same
//! set with the β process shifting as the α process none is, over 40 seeds
//! (`replica_tests.rs`).
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

use super::shift_profile::{Profile, best_shift, best_shift_in, rises_on_both_sides};
use statrs::distribution::{ChiSquared, ContinuousCDF};

use crate::shift::overlap::{Curve, differences};

/// The largest 1σ of a shift the data determine, decades: the rule behind
/// every "determined" flag (pairs and isotherms); a factor 2 in a_T.
pub const DETERMINED_SIGMA: f64 = 0.3;

/// The difference, decades, between the shift log E′ alone needs and the
/// one log tan δ alone needs beyond which superposition fails for a pair
/// (module doc).
pub const TTS_DISAGREEMENT: f64 = 0.3;

/// The fewest points of each isotherm inside the other's range at which a
/// shift is compared: two, the fewest that carry a slope each way.
pub const MIN_OVERLAP: usize = 2;

/// What the data say about the shift of a pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PairVerdict {
    /// Determined: σ ≤ [`DETERMINED_SIGMA`] and the 2σ interval inside the
    /// overlap.
    Determined,
    /// Not determined; [`PairShift::cause`] says why.
    Undetermined,
}

/// Why a pair's shift is what it is (module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PairCause {
    /// A measurement: the profile is bounded on both sides.
    Measured,
    /// The profile is flat across the whole overlap (a plateau).
    Flat,
    /// The profile stays low up to where the isotherms stop overlapping.
    OverlapEnd,
    /// Two separate minima fit about equally well.
    Ambiguous,
    /// Bounded, but σ > [`DETERMINED_SIGMA`] or 2σ leaves the overlap.
    Wide,
    /// Fewer than [`MIN_OVERLAP`] points of an isotherm can overlap the
    /// other at any shift.
    TooFewPoints,
}

/// The relative shift of isotherm `upper` against `lower`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairShift {
    /// Index of the colder isotherm (ascending temperatures).
    pub lower: usize,
    /// Index of the warmer isotherm.
    pub upper: usize,
    /// s = log10 a_{T_upper} − log10 a_{T_lower} at the best overlap (0
    /// where the isotherms cannot overlap).
    pub shift: f64,
    /// 1σ of `shift`, decades (infinite where the profile gives none).
    pub sigma: f64,
    /// The mean log E′ offset at `shift` (the vertical step; 0 without
    /// vertical factors).
    pub vertical: f64,
    /// Whether the data determine the shift.
    pub verdict: PairVerdict,
    /// Why (a measurement, or the cause it is not one).
    pub cause: PairCause,
    /// The overlap of the two frequency ranges at `shift`, decades.
    pub overlap: f64,
    /// The shift each curve alone needs (log E′ or log E(t), log tan δ;
    /// NaN where there is no second curve), decades.
    pub curve_shift: [f64; 2],
    /// Whether each curve alone fixes its shift (its own profile rises by
    /// Δχ² ≥ 4 on both sides inside the overlap).
    pub curve_bounded: [bool; 2],
    /// Whether superposition fails here: both curves fix their shifts and
    /// these differ by more than [`TTS_DISAGREEMENT`].
    pub tts_fails: bool,
    /// The curve whose own shift lies nearer `shift` (0: the modulus, 1:
    /// tan δ): the quantity that carries the combined shift.
    pub carrier: usize,
    /// The largest change of each curve across one isotherm of the pair
    /// (max − min of its log10 values), decades: what a plateau lacks.
    pub spans: [f64; 2],
    /// The smallest and largest value of the second curve (log10 tan δ) in
    /// the two isotherms (NaN without one).
    pub second_range: [f64; 2],
}

/// The most groups the jackknife leaves out in turn per isotherm
/// ([`jackknife_sigma`]): 40 gives its σ² 39 degrees of freedom, a σ good
/// to about 11 %, and keeps the delete-one jackknife, to the bit, for
/// every isotherm of up to 40 frequencies (a DMA sweep is rarely longer).
const JACKKNIFE_GROUPS: usize = 40;

/// The shift of `upper` against `lower` (the same curves of each: log E′
/// and log tan δ of a frequency sweep, log E(t) of a relaxation isotherm,
/// the first one the modulus), with its verdict and cause. With `vertical`
/// the first curves may also differ by a constant. `noise` is the whole
/// set's noise variance per point of each curve ([`pooled_scatter`]).
pub(crate) fn pair_shift(
    lower: &[Curve],
    upper: &[Curve],
    vertical: bool,
    noise: &[f64],
    indices: (usize, usize),
) -> PairShift {
    let free_offset = offsets(lower.len(), vertical);
    let parts = |s: f64| mismatch(lower, upper, &free_offset, MIN_OVERLAP, s);
    let cost = |s: f64| parts(s).map_or(f64::INFINITY, |p| total(&p));
    let spans = curve_spans(lower, upper);
    let second_range = second_range(lower, upper);
    let mut out = PairShift {
        lower: indices.0,
        upper: indices.1,
        shift: 0.0,
        sigma: f64::INFINITY,
        vertical: 0.0,
        verdict: PairVerdict::Undetermined,
        cause: PairCause::TooFewPoints,
        overlap: 0.0,
        curve_shift: [f64::NAN; 2],
        curve_bounded: [false; 2],
        tts_fails: false,
        carrier: 0,
        spans,
        second_range,
    };
    let Some((s0, s_min, s_max)) = best_shift(&cost, overlap_range(&lower[0], &upper[0])) else {
        return out;
    };
    out.shift = s0;
    out.overlap = overlap_at(&lower[0], &upper[0], s0);
    let Some(at_optimum) = parts(s0) else {
        return out;
    };
    // χ² weights: (n_k − p_k)/M_k(s₀), the residual scatter as the noise,
    // but never below the isotherms' own scatter: on a small overlap two
    // points can match by chance far better than their noise allows, and
    // a profile scaled by that chance would be sharp where the data are
    // flat.
    let dof = |k: usize, n: usize| dof(free_offset[k], n);
    let floor: Vec<f64> = (0..lower.len())
        .map(|k| 5.0 / 6.0 * (scatter(&lower[k].y) + scatter(&upper[k].y)))
        .collect();
    // Curves equal to rounding: the scatter of doubles, not zero.
    let weights: Vec<f64> = (0..at_optimum.len())
        .map(|k| dof(k, at_optimum[k].1) / at_optimum[k].0.max(floor[k]).max(1e-24))
        .collect();
    let chi2 = |s: f64| -> f64 {
        parts(s).map_or(f64::INFINITY, |p| {
            p.iter().zip(&weights).map(|(q, w)| w * q.0).sum::<f64>()
        })
    };
    if vertical {
        let (sum, _, n) = differences(&lower[0], &upper[0], s0);
        out.vertical = if n > 0 { sum / n as f64 } else { 0.0 };
    }
    test_superposition(
        lower,
        upper,
        &free_offset,
        &noise_floor(&floor, noise),
        (s_min, s_max),
        &mut out,
    );
    let disagreement = (out.curve_shift[0] - out.curve_shift[1]).abs();
    if lower.len() > 1 {
        out.carrier =
            usize::from((out.curve_shift[1] - s0).abs() < (out.curve_shift[0] - s0).abs());
    }
    let profile = Profile {
        chi2: &chi2,
        chi0: chi2(s0),
        s0,
        run: (s_min, s_max),
    };
    let wide = [profile.crossing(4.0, -1.0), profile.crossing(4.0, 1.0)];
    out.cause = match wide {
        [None, None] => PairCause::Flat,
        [None, Some(_)] | [Some(_), None] => PairCause::OverlapEnd,
        [Some(left), Some(right)] => {
            if profile.second_minimum(left, right, 4.0) {
                PairCause::Ambiguous
            } else {
                match (profile.crossing(1.0, -1.0), profile.crossing(1.0, 1.0)) {
                    (Some(left), Some(right)) => {
                        let jackknife = jackknife_sigma(lower, upper, &free_offset, (s_min, s_max));
                        let mut sigma = (0.5 * (right - left)).max(jackknife);
                        if out.tts_fails {
                            sigma = sigma.max(0.5 * disagreement);
                        }
                        out.sigma = sigma;
                        // On flat noisy curves the profile is as noisy as
                        // the data and can show a sharp minimum; the
                        // jackknife's estimates then scatter over the
                        // overlap, and 2σ leaves it.
                        let inside = s0 - 2.0 * sigma > s_min && s0 + 2.0 * sigma < s_max;
                        if inside && sigma <= DETERMINED_SIGMA {
                            PairCause::Measured
                        } else {
                            PairCause::Wide
                        }
                    }
                    _ => PairCause::Flat,
                }
            }
        }
    };
    if out.cause == PairCause::Measured {
        out.verdict = PairVerdict::Determined;
    }
    out
}

/// Degrees of freedom of a curve's mismatch over `n` points: one for the
/// shift, one more where its offset is free.
fn dof(free_offset: bool, n: usize) -> f64 {
    let p = if free_offset { 2.0 } else { 1.0 };
    (n as f64 - p).max(1.0)
}

/// Each curve alone (module doc): its own best shift in `run`, whether its
/// own profile fixes it, and whether the two differ beyond their errors
/// and [`TTS_DISAGREEMENT`]; recorded in `out`.
fn test_superposition(
    lower: &[Curve],
    upper: &[Curve],
    free_offset: &[bool],
    floor: &[f64],
    (s_min, s_max): (f64, f64),
    out: &mut PairShift,
) {
    let parts = |s: f64| mismatch(lower, upper, free_offset, MIN_OVERLAP, s);
    // Each curve alone: its own best shift, whether its own profile
    // (noise from its own residuals there) fixes it, and its 1σ.
    let mut curve_sigma = [f64::INFINITY; 2];
    let mut weight = [f64::NAN; 2];
    for k in 0..lower.len().min(2) {
        let own = |s: f64| parts(s).map_or(f64::INFINITY, |p| p[k].0);
        if let Some((sk, _, _)) = best_shift_in(&own, s_min, s_max) {
            let n = parts(sk).map_or(0, |p| p[k].1);
            let w = dof(free_offset[k], n) / own(sk).max(floor[k]).max(1e-24);
            weight[k] = w;
            let profile = |s: f64| w * own(s);
            out.curve_shift[k] = sk;
            out.curve_bounded[k] = rises_on_both_sides(&profile, sk, s_min, s_max, 4.0);
            let own_profile = Profile {
                chi2: &profile,
                chi0: profile(sk),
                s0: sk,
                run: (s_min, s_max),
            };
            if let (Some(left), Some(right)) = (
                own_profile.crossing(1.0, -1.0),
                own_profile.crossing(1.0, 1.0),
            ) {
                curve_sigma[k] = 0.5 * (right - left);
            }
        }
    }
    // A difference the curves' own errors explain is no failure. A nearly
    // flat curve's own profile understates its error (its optimum is the
    // noise's), so each curve's σ is also its jackknife's.
    let disagreement = (out.curve_shift[0] - out.curve_shift[1]).abs();
    if lower.len() < 2 || out.curve_bounded == [false, false] || disagreement <= TTS_DISAGREEMENT {
        return;
    }
    // A curve whose best overlap lies at the overlap's end says the common
    // shift may lie beyond it, where nothing is compared. Between
    // neighbours the other curve's refusal of that end speaks against
    // it; a bridge over two steps (linking isotherms whose neighbours
    // are undetermined) has its common shift beyond its overlap as a rule
    // on narrow windows, so only a bridge whose curves both fix their
    // shifts names a failure.
    let bridge = out.upper > out.lower + 1;
    if bridge && out.curve_bounded != [true, true] {
        return;
    }
    for (k, sigma) in curve_sigma.iter_mut().enumerate() {
        if out.curve_bounded[k] {
            let jackknife = jackknife_sigma(
                &lower[k..=k],
                &upper[k..=k],
                &free_offset[k..=k],
                (s_min, s_max),
            );
            *sigma = sigma.max(jackknife);
        } else {
            // A best overlap at the overlap's end is a place, not a
            // measurement: it is judged where it lies.
            *sigma = 0.0;
        }
    }
    if disagreement <= 2.0 * curve_sigma[0].hypot(curve_sigma[1]) {
        return;
    }
    // Each curve, judged by its own noise, refuses the other's shift
    // everywhere within that shift's 2σ. Without this a plateau's noise,
    // which bounds a flat curve's profile by chance, names failures where
    // one shift superposes both; and a curve whose best overlap lies at
    // the overlap's end, matching poorly even there, is judged by its
    // scatter and not by that misfit.
    let params = |k: usize| usize::from(free_offset[k]);
    let refuses = |k: usize, (s, sigma): (f64, f64)| {
        let (lo, hi) = ((s - 2.0 * sigma).max(s_min), (s + 2.0 * sigma).min(s_max));
        const STEPS: usize = 40;
        lo <= hi
            && (0..=STEPS).all(|i| {
                let at = lo + (hi - lo) * i as f64 / STEPS as f64;
                parts(at).is_some_and(|p| beyond_noise(p[k], floor[k], params(k)))
            })
    };
    out.tts_fails = refuses(0, (out.curve_shift[1], curve_sigma[1]))
        && refuses(1, (out.curve_shift[0], curve_sigma[0]));
}

/// Whether a curve's mismatch `(M, n)` at one shift is more than its own
/// noise gives: χ² = n M/floor above the 99 % quantile of χ²(n − p), with
/// p the curve's fitted parameters at that shift (the shift is imposed,
/// not fitted: only a free offset costs a degree of freedom). The noise is the isotherms' scatter
/// (`floor`, from third differences), not the residual at the curve's own
/// optimum: where that optimum lies at the overlap's end the curve
/// matches poorly even there, and a profile scaled by that misfit hides
/// the rejection. A flat curve matches at every shift and refuses none.
fn beyond_noise((m, n): (f64, usize), floor: f64, params: usize) -> bool {
    let dof = n.saturating_sub(params).max(1) as f64;
    let limit = ChiSquared::new(dof).map_or(f64::INFINITY, |d| d.inverse_cdf(0.99));
    floor > 0.0 && n as f64 * m / floor > limit
}

/// The shifts at which any of `upper`'s points can fall inside `lower`'s
/// range: upper(x) against lower(x + s).
fn overlap_range(lower: &Curve, upper: &Curve) -> Option<(f64, f64)> {
    let (l0, l1) = (lower.x.first()?, lower.x.last()?);
    let (u0, u1) = (upper.x.first()?, upper.x.last()?);
    Some((l0 - u1, l1 - u0))
}

/// The overlap of the two ranges at shift `s`, decades.
fn overlap_at(lower: &Curve, upper: &Curve, s: f64) -> f64 {
    match (
        lower.x.first(),
        lower.x.last(),
        upper.x.first(),
        upper.x.last(),
    ) {
        (Some(l0), Some(l1), Some(u0), Some(u1)) => {
            ((l1 - s).min(*u1) - (l0 - s).max(*u0)).max(0.0)
        }
        _ => 0.0,
    }
}

/// Per curve, the noise variance of the isotherms `all` pooled: the sum of
/// their squared third differences over 20 times their count ([`scatter`]
/// summed before dividing), so that every isotherm's points count.
pub(crate) fn pooled_scatter(all: &[&[Curve]]) -> Vec<f64> {
    let curves = all.iter().map(|c| c.len()).min().unwrap_or(0);
    (0..curves)
        .map(|k| {
            let (sum, count) = all
                .iter()
                .map(|c| &c[k].y)
                .filter(|y| y.len() >= 4)
                .fold((0.0, 0usize), |(sum, count), y| {
                    (sum + scatter(y) * (y.len() - 3) as f64, count + y.len() - 3)
                });
            if count == 0 { 0.0 } else { sum / count as f64 }
        })
        .collect()
}

/// The variance of a curve's noise from its third differences,
/// var(y_{i+1} − 3y_i + 3y_{i−1} − y_{i−2}) = 20 σ² for white noise, to
/// which a linear or quadratic trend adds nothing (the sweep's curvature
/// does not pass for noise); 0 with fewer than four points.
fn scatter(y: &[f64]) -> f64 {
    if y.len() < 4 {
        return 0.0;
    }
    let sum: f64 = y
        .windows(4)
        .map(|w| (w[3] - 3.0 * w[2] + 3.0 * w[1] - w[0]).powi(2))
        .sum();
    sum / (y.len() - 3) as f64 / 20.0
}

/// The smallest and largest value of the second curve in the two
/// isotherms (NaN without one).
fn second_range(lower: &[Curve], upper: &[Curve]) -> [f64; 2] {
    if lower.len() < 2 {
        return [f64::NAN; 2];
    }
    let all = lower[1].y.iter().chain(&upper[1].y);
    let lo = all.clone().copied().fold(f64::INFINITY, f64::min);
    [lo, all.copied().fold(f64::NEG_INFINITY, f64::max)]
}

/// The noise the superposition test judges each curve by: the pair's
/// scatter `floor`, or the set's pooled `noise` (a variance per point,
/// [`pooled_scatter`]) where larger. Two isotherms' third differences give
/// the noise with about six degrees of freedom, and a pair whose scatter
/// came out low by chance would refuse shifts its noise allows.
fn noise_floor(floor: &[f64], noise: &[f64]) -> Vec<f64> {
    floor
        .iter()
        .enumerate()
        .map(|(k, f)| f.max(5.0 / 3.0 * noise.get(k).copied().unwrap_or(0.0)))
        .collect()
}

/// Per curve (up to two), the largest max − min of its values within one
/// isotherm of the pair.
fn curve_spans(lower: &[Curve], upper: &[Curve]) -> [f64; 2] {
    let span = |c: &Curve| {
        let lo = c.y.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = c.y.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        (hi - lo).max(0.0)
    };
    let mut out = [f64::NAN; 2];
    for k in 0..lower.len().min(2) {
        out[k] = span(&lower[k]).max(span(&upper[k]));
    }
    out
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
/// shorter than `need` points either way or a curve does not overlap.
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
        if one.2 == 0 || other.2 == 0 || (k == 0 && (one.2 < need || other.2 < need)) {
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
/// points each, n² (minutes at 300 frequencies per isotherm).
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
    let minimum = |lower: &[Curve], upper: &[Curve]| -> Option<f64> {
        let cost = |s: f64| {
            mismatch(lower, upper, free_offset, MIN_OVERLAP, s).map_or(f64::INFINITY, |p| total(&p))
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
