//! The χ² profile of one shift between two isotherms: the search for its
//! minimum (a coarse scan over the run of shifts at which the isotherms
//! overlap, a fine scan about its best point and a golden-section
//! refinement) and where Δχ² crosses a level (bisection between scan
//! points), from which [`super::pairwise`] reads σ and the causes of an
//! undetermined shift. The cost is any function of the shift that is
//! infinite where the overlap rule refuses it.

use crate::shift::overlap::golden_section;

/// Scan step of the search, decades.
pub(super) const STEP: f64 = 0.02;

/// The χ² profile of a pair about its optimum.
pub(super) struct Profile<'a> {
    pub chi2: &'a dyn Fn(f64) -> f64,
    pub chi0: f64,
    pub s0: f64,
    pub run: (f64, f64),
}

impl Profile<'_> {
    /// Where Δχ² first exceeds `level` walking from s₀ in `direction`
    /// (bisected between scan points), or None if it never does before the
    /// overlap ends.
    pub fn crossing(&self, level: f64, direction: f64) -> Option<f64> {
        let (s_min, s_max) = self.run;
        let mut inside = self.s0;
        let mut k = 1;
        loop {
            let s = self.s0 + direction * k as f64 * STEP;
            if s < s_min - 1e-12 || s > s_max + 1e-12 {
                // The last allowed point may still be above the level.
                let edge = if direction > 0.0 { s_max } else { s_min };
                if (self.chi2)(edge) - self.chi0 > level {
                    return Some(bisect(self.chi2, self.chi0 + level, inside, edge));
                }
                return None;
            }
            if (self.chi2)(s) - self.chi0 > level {
                return Some(bisect(self.chi2, self.chi0 + level, inside, s));
            }
            inside = s;
            k += 1;
        }
    }

    /// Whether a shift outside (left, right), more than one scan step
    /// beyond, comes within Δχ² < `level` of the optimum.
    pub fn second_minimum(&self, left: f64, right: f64, level: f64) -> bool {
        let (s_min, s_max) = self.run;
        let coarse = 5.0 * STEP;
        let count = ((s_max - s_min) / coarse).ceil().max(1.0) as usize;
        (0..=count)
            .map(|j| s_min + (s_max - s_min) * j as f64 / count as f64)
            .filter(|&s| s < left - coarse || s > right + coarse)
            .any(|s| (self.chi2)(s) - self.chi0 < level)
    }
}

/// Whether `profile` rises by more than `level` above its value at `at`
/// somewhere on each side inside [s_min, s_max].
pub(super) fn rises_on_both_sides(
    profile: &dyn Fn(f64) -> f64,
    at: f64,
    s_min: f64,
    s_max: f64,
    level: f64,
) -> bool {
    let base = profile(at);
    let side = |from: f64, to: f64| {
        let count = ((to - from).abs() / STEP).ceil().max(1.0) as usize;
        (1..=count).any(|j| {
            let c = profile(from + (to - from) * j as f64 / count as f64);
            c.is_finite() && c - base > level
        })
    };
    side(at, s_min) && side(at, s_max)
}

/// The shift of least `cost` by a scan over `range` (where the isotherms
/// can overlap at all) and a golden-section refinement, with the ends of
/// the run of allowed (finite-cost) shifts around it: (s₀, s_min, s_max).
pub(super) fn best_shift(
    cost: &dyn Fn(f64) -> f64,
    range: Option<(f64, f64)>,
) -> Option<(f64, f64, f64)> {
    let (from, to) = range?;
    // A coarse scan finds the allowed run (the curves vary on the scale of
    // a decade); the best shift is then searched inside it.
    let coarse = 5.0 * STEP;
    let steps = ((to - from) / coarse).ceil().max(1.0) as usize;
    let grid: Vec<f64> = (0..=steps)
        .map(|i| from + (to - from) * i as f64 / steps as f64)
        .collect();
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
pub(super) fn best_shift_in(
    cost: &dyn Fn(f64) -> f64,
    s_min: f64,
    s_max: f64,
) -> Option<(f64, f64, f64)> {
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
