//! Shift factors by overlapping curves, without a model.
//!
//! Two curves measured at neighbouring temperatures T_j < T_{j+1} are the
//! same function of the reduced variable: y_{j+1}(x) = y_j(x + s) with
//! x = log10 v (or log10 ω) and s = log10 a_{T_{j+1}} − log10 a_{T_j}. The
//! shift s minimises the mean squared difference over the overlap, found by
//! a scan over ±15 decades (the curves need not be monotone, so a local
//! search from a guess could lock onto the wrong flank) and a golden-section
//! refinement. Chaining neighbours gives log10 a_T up to a constant.
//!
//! Used twice: on the measured ln μ(v) for a model-free starting shift of
//! the joint fit, and on ln tan δ(ω) of single-temperature fits for the
//! cross-check. [`fit_wlf`] then fits WLF constants to such shifts.
//!
//! The σ of a shift between two fitted curves with 1σ bands σ_u(x), σ_l(x)
//! ([`relative_shift_sigma`]): at the least-squares s, Σ_i g_i (u_i −
//! l(x_i + s)) = 0 with g_i = l′(x_i + s), so errors δu, δl of the curves
//! move s by δs = Σ_i g_i (δu_i − δl(x_i + s)) / Σ_i g_i². The points of a
//! fitted curve's band are correlated in a way the band does not record
//! (a fit's error is smooth, and its likeliest form is a shift of the
//! curve, which is what moves s); whatever the correlation,
//! sd(Σ a_i δu_i) ≤ Σ |a_i| σ_u,i, and the two curves, fitted to different
//! data, are independent:
//!
//!   σ_s ≤ [(Σ_i |g_i| σ_u,i)² + (Σ_i |g_i| σ_l(x_i + s))²]^{1/2} / Σ_i g_i²,
//!
//! which is taken as σ_s (exact when each band's error is one shape scaled,
//! of the sign of g).
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, §11.A (reduced variables and shifting by superposition).

/// A curve sampled at ascending x.
#[derive(Debug, Clone, Default)]
pub(crate) struct Curve {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
}

impl Curve {
    /// From unsorted samples (x, y); repeated x are kept.
    pub(crate) fn new(mut points: Vec<(f64, f64)>) -> Self {
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (x, y) = points.into_iter().unzip();
        Curve { x, y }
    }

    /// Linear interpolation at `x` inside the sampled range.
    fn at(&self, x: f64) -> Option<f64> {
        let n = self.x.len();
        if n < 2 || x < self.x[0] || x > self.x[n - 1] {
            return None;
        }
        let k = self.x.partition_point(|&xi| xi <= x).clamp(1, n - 1);
        Some(self.segment_value(k, x))
    }

    /// The linear interpolant of segment [x_{k−1}, x_k] at `x`.
    fn segment_value(&self, k: usize, x: f64) -> f64 {
        let (x0, x1) = (self.x[k - 1], self.x[k]);
        if x1 == x0 {
            return 0.5 * (self.y[k - 1] + self.y[k]);
        }
        let w = (x - x0) / (x1 - x0);
        self.y[k - 1] * (1.0 - w) + self.y[k] * w
    }
}

impl Curve {
    /// The slope dy/dx of the linear interpolant at `x` inside the
    /// sampled range (of the segment holding x).
    fn slope(&self, x: f64) -> Option<f64> {
        let n = self.x.len();
        if n < 2 || x < self.x[0] || x > self.x[n - 1] {
            return None;
        }
        let k = self.x.partition_point(|&xi| xi <= x).clamp(1, n - 1);
        let dx = self.x[k] - self.x[k - 1];
        (dx > 0.0).then(|| (self.y[k] - self.y[k - 1]) / dx)
    }
}

/// The 1σ of the shift `s` with upper(x) ≈ lower(x + s) (from
/// [`relative_shift`]) from the curves' 1σ bands `lower_sigma` and
/// `upper_sigma`, sampled like them (the module doc); None where the
/// overlap is empty or flat (no shift is determined) or a band is not
/// finite.
pub(crate) fn relative_shift_sigma(
    lower: &Curve,
    lower_sigma: &Curve,
    upper: &Curve,
    upper_sigma: &Curve,
    s: f64,
) -> Option<f64> {
    let (mut gg, mut from_upper, mut from_lower) = (0.0, 0.0, 0.0);
    for &x in &upper.x {
        let (Some(g), Some(sl), Some(su)) =
            (lower.slope(x + s), lower_sigma.at(x + s), upper_sigma.at(x))
        else {
            continue;
        };
        gg += g * g;
        from_upper += g.abs() * su;
        from_lower += g.abs() * sl;
    }
    let sigma = from_upper.hypot(from_lower) / gg;
    (gg > 0.0 && sigma.is_finite()).then_some(sigma)
}

/// Mean squared mismatch of upper(x) against lower(x + s), summed over the
/// pairs of curves (e.g. log E′ and log tan δ of two isotherms), and the
/// number of overlapping points of the first pair. A pair with
/// `free_offset` may also differ by a constant, upper(x) = lower(x + s) + c
/// (a vertical shift): its mismatch is taken about the best c, i.e. the
/// variance of the differences.
fn mismatch(lower: &[&Curve], upper: &[&Curve], free_offset: &[bool], s: f64) -> (f64, usize) {
    let mut total = 0.0;
    let mut first = None;
    for (k, (lower, upper)) in lower.iter().zip(upper).enumerate() {
        let (sum, sum_sq, n) = differences(lower, upper, s);
        total += if n == 0 {
            f64::INFINITY
        } else if free_offset.get(k).copied().unwrap_or(false) {
            let mean = sum / n as f64;
            (sum_sq / n as f64 - mean * mean).max(0.0)
        } else {
            sum_sq / n as f64
        };
        first.get_or_insert(n);
    }
    (total, first.unwrap_or(0))
}

/// Σ d, Σ d² and the count of d = upper(x) − lower(x + s) over upper's
/// points inside lower's range.
///
/// Upper's x + s ascend, so the segment of lower holding each is found by
/// walking one index forward, not by a search per point: linear in the
/// points, which matters for isotherms of thousands of frequencies (issue
/// 36). The segment and its arithmetic are [`Curve::at`]'s, to the bit.
pub(crate) fn differences(lower: &Curve, upper: &Curve, s: f64) -> (f64, f64, usize) {
    let (mut sum, mut sum_sq, mut n) = (0.0, 0.0, 0);
    let m = lower.x.len();
    if m < 2 {
        return (sum, sum_sq, n);
    }
    // The count of lower's x ≤ the current x + s: Curve::at's partition
    // point, non-decreasing along upper.
    let mut below = 0;
    for (&x, &y) in upper.x.iter().zip(&upper.y) {
        let at = x + s;
        if at < lower.x[0] || at > lower.x[m - 1] {
            continue;
        }
        while below < m && lower.x[below] <= at {
            below += 1;
        }
        let d = y - lower.segment_value(below.clamp(1, m - 1), at);
        sum += d;
        sum_sq += d * d;
        n += 1;
    }
    (sum, sum_sq, n)
}

/// The shift s with upper(x) ≈ lower(x + s), or None if the curves never
/// overlap on at least a fifth of the shorter curve's points (and four
/// points).
pub(crate) fn relative_shift(lower: &Curve, upper: &Curve) -> Option<f64> {
    joint_relative_shift(&[lower], &[upper], &[])
}

/// The one shift s with upper_k(x) ≈ lower_k(x + s) (+ a constant for the
/// pairs with `free_offset`) for every pair k, the summed mean squared
/// mismatches least; None if the first pair never overlaps on at least a
/// fifth of its shorter curve's points (and four). (Of the shorter: a
/// short curve inside a long one's range overlaps on all its points, which
/// a fifth of the long one's can exceed — a single fit that determines
/// tan δ over half a decade against its neighbour's five decades.)
pub(crate) fn joint_relative_shift(
    lower: &[&Curve],
    upper: &[&Curve],
    free_offset: &[bool],
) -> Option<f64> {
    let need = (upper[0].x.len().min(lower[0].x.len()) / 5).max(4);
    let cost = |s: f64| {
        let (m, n) = mismatch(lower, upper, free_offset, s);
        if n >= need { m } else { f64::INFINITY }
    };
    const STEP: f64 = 0.02;
    let mut best = (f64::INFINITY, 0.0);
    let steps = (15.0 / STEP) as i64;
    for i in -steps..=steps {
        let s = i as f64 * STEP;
        let c = cost(s);
        if c < best.0 {
            best = (c, s);
        }
    }
    if !best.0.is_finite() {
        return None;
    }
    let s = golden_section(&cost, best.1 - STEP, best.1 + STEP, 40);
    Some(if cost(s) <= best.0 { s } else { best.1 })
}

/// The minimum of a unimodal `f` on [a, b] by golden section in
/// `iterations` steps (each shrinks the bracket by 0.618).
pub(crate) fn golden_section(
    f: &dyn Fn(f64) -> f64,
    mut a: f64,
    mut b: f64,
    iterations: usize,
) -> f64 {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..iterations {
        let c = b - g * (b - a);
        let d = a + g * (b - a);
        if f(c) < f(d) {
            b = d;
        } else {
            a = c;
        }
    }
    0.5 * (a + b)
}

/// log10 a_T of curves at ascending temperatures, relative to the first,
/// by chaining neighbours; None where a pair does not overlap.
pub(crate) fn chained_shifts(curves: &[Curve]) -> Option<Vec<f64>> {
    let mut out = vec![0.0];
    for pair in curves.windows(2) {
        let s = relative_shift(&pair[0], &pair[1])?;
        out.push(out[out.len() - 1] + s);
    }
    Some(out)
}

/// WLF constants (C1, C2) that best fit log10 a_T = `log_shift` at
/// `temps` up to a constant offset (least squares), with C2 > `c2_floor`.
/// For each C2 on a log grid the model is linear in (C1, offset); the best
/// pair wins. Falls back to C1 = 8.86, C2 = 101.6 K (Williams–Landel–Ferry's
/// constants for T_ref ≈ T_g + 50 K) if no positive C1 fits.
pub(crate) fn fit_wlf(temps: &[f64], log_shift: &[f64], t_ref: f64, c2_floor: f64) -> (f64, f64) {
    let mut best: Option<(f64, f64, f64)> = None;
    for i in 0..=400 {
        let c2 = c2_floor + 10f64.powf(-1.0 + 4.0 * i as f64 / 400.0);
        // log a = −C1 z + b, z = ΔT/(C2 + ΔT).
        let z: Vec<f64> = temps
            .iter()
            .map(|&t| (t - t_ref) / (c2 + t - t_ref))
            .collect();
        let n = z.len() as f64;
        let (mz, my) = (z.iter().sum::<f64>() / n, log_shift.iter().sum::<f64>() / n);
        let (mut szz, mut szy) = (0.0, 0.0);
        for (zi, yi) in z.iter().zip(log_shift) {
            szz += (zi - mz) * (zi - mz);
            szy += (zi - mz) * (yi - my);
        }
        if szz <= 0.0 {
            continue;
        }
        let c1 = -szy / szz;
        if c1 <= 0.0 {
            continue;
        }
        let b = my + c1 * mz;
        let rss: f64 = z
            .iter()
            .zip(log_shift)
            .map(|(zi, yi)| (yi - (b - c1 * zi)).powi(2))
            .sum();
        if best.is_none_or(|(r, _, _)| rss < r) {
            best = Some((rss, c1, c2));
        }
    }
    best.map_or((8.86, 101.6f64.max(c2_floor + 1.0)), |(_, c1, c2)| (c1, c2))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bell curve shifted by known amounts is put back to within the
    /// sampling's resolution.
    #[test]
    fn shifted_bells_are_recovered() {
        let bell = |x: f64| -(x - 1.0).powi(2) / 8.0;
        let shifts = [0.0, 1.3, 2.9, 3.7];
        let curves: Vec<Curve> = shifts
            .iter()
            .map(|s| {
                Curve::new(
                    (0..41)
                        .map(|i| {
                            let x = -6.0 + 0.2 * i as f64;
                            (x, bell(x + s))
                        })
                        .collect(),
                )
            })
            .collect();
        let got = chained_shifts(&curves).unwrap();
        for (g, s) in got.iter().zip(shifts) {
            assert!((g - s).abs() < 2e-3, "{g} vs {s}");
        }
    }

    /// Curves that never overlap give no shift.
    #[test]
    fn disjoint_curves_give_none() {
        let a = Curve::new((0..10).map(|i| (i as f64, 1.0)).collect());
        let b = Curve::new((0..10).map(|i| (i as f64, 5.0 + i as f64)).collect());
        // Any overlap fits, but b rises where a is flat: still a shift; only
        // a too-short overlap is refused.
        let short = Curve::new((0..3).map(|i| (i as f64, 1.0)).collect());
        assert!(relative_shift(&a, &b).is_some());
        assert!(relative_shift(&a, &short).is_none());
    }

    /// The σ of a shift between two bands: a straight line of slope g
    /// with bands of constant σ over n overlapping points gives
    /// √2 n σ |g| / (n g²) = √2 σ/|g|, the shift a common displacement of
    /// either curve by σ causes; a flat overlap determines nothing.
    #[test]
    fn a_shift_sigma_is_the_bands_over_the_slope() {
        let line = |offset: f64| {
            Curve::new(
                (0..21)
                    .map(|i| (0.1 * i as f64, 0.5 * (0.1 * i as f64 + offset)))
                    .collect(),
            )
        };
        let band = Curve::new((0..21).map(|i| (0.1 * i as f64, 0.02)).collect());
        let (lower, upper) = (line(0.0), line(0.4));
        let s = relative_shift(&lower, &upper).unwrap();
        assert!((s - 0.4).abs() < 1e-6, "{s}");
        let sigma = relative_shift_sigma(&lower, &band, &upper, &band, s).unwrap();
        assert!((sigma - 2f64.sqrt() * 0.02 / 0.5).abs() < 1e-9, "{sigma}");
        let flat = Curve::new((0..21).map(|i| (0.1 * i as f64, 1.0)).collect());
        assert!(relative_shift_sigma(&flat, &band, &flat, &band, 0.0).is_none());
    }

    /// WLF constants are recovered from exact shifts with an offset.
    #[test]
    fn wlf_constants_from_exact_shifts() {
        let temps = [-20.0, 0.0, 20.0, 40.0, 60.0];
        let (c1, c2) = (8.86, 101.6);
        let log_shift: Vec<f64> = temps
            .iter()
            .map(|t| 3.0 - c1 * (t - 20.0) / (c2 + t - 20.0))
            .collect();
        let (f1, f2) = fit_wlf(&temps, &log_shift, 20.0, 40.0);
        assert!((f1 / c1 - 1.0).abs() < 0.02, "{f1}");
        assert!((f2 / c2 - 1.0).abs() < 0.02, "{f2}");
    }
}
