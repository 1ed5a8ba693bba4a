//! Globally adaptive Gauss–Kronrod (7, 15) quadrature of vector-valued
//! integrands, for μ of a modulus that is analytic only between knots
//! (`friction::knots`, a tabulated master curve).
//!
//! On each panel [a, b] the 15-point Kronrod rule K and its embedded 7-point
//! Gauss rule G are evaluated from the same 15 function values. K is the
//! panel's value; |K − G| — the error of the far less accurate G — bounds
//! its error. For an analytic integrand the error of K is orders of
//! magnitude below |K − G| (K is exact to degree 22, G to degree 13), so the
//! estimate is deliberately pessimistic: the heuristic sharpening of
//! QUADPACK's QK15 (which scales |K − G| down by (200|K − G|/I_asc)^{3/2})
//! is not used, because the tolerance here is a promise to the caller.
//!
//! The panel with the largest normalised error Σ_k err_k/target_k is
//! bisected until the summed error of every component is below its target
//! max(absolute_k, relative·|I_k|), as in QUADPACK's QAG.
//!
//! # References
//! - R. Piessens, E. de Doncker-Kapenga, C.W. Überhuber, D.K. Kahaner,
//!   *QUADPACK: A Subroutine Package for Automatic Integration*, Springer
//!   1983, §2.2 (QK15 nodes and weights, the QAG strategy).
//! - A.S. Kronrod, *Nodes and Weights of Quadrature Formulas*, Consultants
//!   Bureau, New York 1965.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Kronrod nodes on [−1, 1], non-negative half, descending; the odd entries
/// (1, 3, 5, 7) are the 7-point Gauss nodes.
const XGK: [f64; 8] = [
    0.991_455_371_120_812_6,
    0.949_107_912_342_758_5,
    0.864_864_423_359_769_1,
    0.741_531_185_599_394_4,
    0.586_087_235_467_691_1,
    0.405_845_151_377_397_2,
    0.207_784_955_007_898_5,
    0.0,
];

/// Kronrod weights for [`XGK`].
const WGK: [f64; 8] = [
    0.022_935_322_010_529_225,
    0.063_092_092_629_978_56,
    0.104_790_010_322_250_18,
    0.140_653_259_715_525_92,
    0.169_004_726_639_267_9,
    0.190_350_578_064_785_4,
    0.204_432_940_075_298_9,
    0.209_482_141_084_727_83,
];

/// Gauss weights for XGK[1], XGK[3], XGK[5], XGK[7].
const WG: [f64; 4] = [
    0.129_484_966_168_869_7,
    0.279_705_391_489_276_7,
    0.381_830_050_505_118_9,
    0.417_959_183_673_469_4,
];

/// The 15 abscissae of the rule on [a, b], in the order
/// [`combine`] expects: centre, then ± pairs for XGK[6], XGK[5], …, XGK[0].
#[inline]
pub(crate) fn nodes(a: f64, b: f64) -> [f64; 15] {
    let centre = 0.5 * (a + b);
    let half = 0.5 * (b - a);
    let mut out = [centre; 15];
    for j in 0..7 {
        let dx = half * XGK[6 - j];
        out[1 + 2 * j] = centre - dx;
        out[2 + 2 * j] = centre + dx;
    }
    out
}

/// Kronrod value and |K − G| from the 15 values at [`nodes`]`(a, b)`.
#[inline]
pub(crate) fn combine<const N: usize>(a: f64, b: f64, values: &[[f64; N]; 15]) -> Panel<N> {
    let half = 0.5 * (b - a);
    let mut kronrod = [0.0; N];
    let mut gauss = [0.0; N];
    for k in 0..N {
        kronrod[k] = WGK[7] * values[0][k];
        gauss[k] = WG[3] * values[0][k];
    }
    for j in 0..7 {
        let xi = 6 - j;
        let (lo, hi) = (&values[1 + 2 * j], &values[2 + 2 * j]);
        for k in 0..N {
            let pair = lo[k] + hi[k];
            kronrod[k] += WGK[xi] * pair;
            if xi % 2 == 1 {
                gauss[k] += WG[xi / 2] * pair;
            }
        }
    }
    let mut error = [0.0; N];
    for k in 0..N {
        kronrod[k] *= half;
        gauss[k] *= half;
        error[k] = (kronrod[k] - gauss[k]).abs();
    }
    Panel {
        a,
        b,
        value: kronrod,
        error,
    }
}

/// One panel's Kronrod value and error bound.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Panel<const N: usize> {
    pub a: f64,
    pub b: f64,
    pub value: [f64; N],
    pub error: [f64; N],
}

/// Result of [`integrate`].
#[derive(Debug, Clone)]
pub(crate) struct Integral<const N: usize> {
    /// ∫ f, componentwise.
    pub value: [f64; N],
    /// Summed error bounds, componentwise. The callers act on success or
    /// failure only; the bound is kept for tests and diagnostics.
    #[allow(dead_code)]
    pub error: [f64; N],
}

/// Why [`integrate`] gave up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Failure {
    /// The panel budget ran out before the targets were met.
    PanelLimit { error: f64, target: f64 },
    /// A panel became too narrow to split (rounding-limited integrand).
    Resolution { at: f64 },
    /// The integrand returned a value that is not finite.
    NotFinite { at: f64 },
}

/// Accuracy request: component k is done when its summed error bound is at
/// most max(absolute[k], relative·|I_k|).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Targets<const N: usize> {
    pub absolute: [f64; N],
    pub relative: f64,
}

impl<const N: usize> Targets<N> {
    fn of(&self, value: &[f64; N]) -> [f64; N] {
        let mut t = [0.0; N];
        for k in 0..N {
            t[k] = self.absolute[k].max(self.relative * value[k].abs());
        }
        t
    }
}

/// Heap entry: panel ordered by its normalised error.
struct Ranked<const N: usize> {
    key: f64,
    panel: Panel<N>,
}
impl<const N: usize> PartialEq for Ranked<N> {
    fn eq(&self, other: &Self) -> bool {
        self.key.total_cmp(&other.key) == Ordering::Equal
    }
}
impl<const N: usize> Eq for Ranked<N> {}
impl<const N: usize> PartialOrd for Ranked<N> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}
impl<const N: usize> Ord for Ranked<N> {
    fn cmp(&self, other: &Self) -> Ordering {
        self.key.total_cmp(&other.key)
    }
}

/// One Kronrod panel of `f` on [a, b].
fn panel<const N: usize, F: FnMut(f64) -> [f64; N]>(
    f: &mut F,
    a: f64,
    b: f64,
) -> Result<Panel<N>, Failure> {
    let xs = nodes(a, b);
    let mut values = [[0.0; N]; 15];
    for (value, &x) in values.iter_mut().zip(&xs) {
        *value = f(x);
        if value.iter().any(|v| !v.is_finite()) {
            return Err(Failure::NotFinite { at: x });
        }
    }
    Ok(combine(a, b, &values))
}

/// ∫ f over [breaks[0], breaks[last]] with the given breakpoints as initial
/// panels, bisecting the worst panel until every component meets its target
/// or `max_panels` is reached.
pub(crate) fn integrate<const N: usize, F: FnMut(f64) -> [f64; N]>(
    f: F,
    breaks: &[f64],
    targets: Targets<N>,
    max_panels: usize,
) -> Result<Integral<N>, Failure> {
    adapt(f, breaks, targets, max_panels)
}

fn adapt<const N: usize, F: FnMut(f64) -> [f64; N]>(
    mut f: F,
    breaks: &[f64],
    targets: Targets<N>,
    max_panels: usize,
) -> Result<Integral<N>, Failure> {
    let mut total = [0.0; N];
    let mut error = [0.0; N];
    let mut panels = Vec::with_capacity(breaks.len().saturating_sub(1));
    for w in breaks.windows(2) {
        if w[1] > w[0] {
            let p = panel(&mut f, w[0], w[1])?;
            for k in 0..N {
                total[k] += p.value[k];
                error[k] += p.error[k];
            }
            panels.push(p);
        }
    }
    let done = |total: &[f64; N], error: &[f64; N]| {
        let t = targets.of(total);
        (0..N).all(|k| error[k] <= t[k])
    };
    if done(&total, &error) {
        return Ok(Integral {
            value: total,
            error,
        });
    }
    let rank = |p: Panel<N>, t: &[f64; N]| {
        let key = (0..N)
            .map(|k| {
                if t[k] > 0.0 {
                    p.error[k] / t[k]
                } else {
                    p.error[k] * f64::MAX.sqrt()
                }
            })
            .sum::<f64>();
        Ranked { key, panel: p }
    };
    // Ranks use the targets of the initial estimate: they only order the
    // panels, and the initial estimate fixes the scale well enough.
    let scale = targets.of(&total);
    let mut heap: BinaryHeap<Ranked<N>> = panels.into_iter().map(|p| rank(p, &scale)).collect();
    let initial = heap.len();
    // Panels alive; each split adds one (two new, one retired).
    let mut count = initial;
    while !done(&total, &error) {
        let Some(worst) = heap.pop() else {
            break;
        };
        let p = worst.panel;
        if count >= max_panels {
            let t = targets.of(&total);
            let (e, tt) = (0..N)
                .map(|k| (error[k], t[k]))
                .max_by(|x, y| (x.0 / x.1).total_cmp(&(y.0 / y.1)))
                .unwrap_or((0.0, 0.0));
            return Err(Failure::PanelLimit {
                error: e,
                target: tt,
            });
        }
        let mid = 0.5 * (p.a + p.b);
        if !(mid > p.a && mid < p.b) || (p.b - p.a) <= 1e-13 * (p.a.abs() + p.b.abs()) {
            return Err(Failure::Resolution { at: mid });
        }
        let left = panel(&mut f, p.a, mid)?;
        let right = panel(&mut f, mid, p.b)?;
        for k in 0..N {
            total[k] += left.value[k] + right.value[k] - p.value[k];
            error[k] += left.error[k] + right.error[k] - p.error[k];
        }
        heap.push(rank(left, &scale));
        heap.push(rank(right, &scale));
        count += 1;
    }
    // Re-sum: the running updates accumulate rounding over many splits.
    let mut value = [0.0; N];
    let mut err = [0.0; N];
    for r in &heap {
        for k in 0..N {
            value[k] += r.panel.value[k];
            err[k] += r.panel.error[k];
        }
    }
    Ok(Integral { value, error: err })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kernel::quadrature::gauss_legendre_unit;

    #[test]
    fn kronrod_exact_to_degree_22_gauss_to_13() {
        for deg in 0..=22 {
            let p = panel(&mut |x: f64| [x.powi(deg)], -1.0, 1.0).unwrap();
            let exact = if deg % 2 == 1 {
                0.0
            } else {
                2.0 / (deg as f64 + 1.0)
            };
            assert!((p.value[0] - exact).abs() < 2e-16, "K deg {deg}");
            if deg <= 13 {
                assert!(p.error[0] < 2e-16, "G deg {deg}: {}", p.error[0]);
            }
        }
        // Degree 24 is not integrated exactly by K15: the rule is the real one.
        let p = panel(&mut |x: f64| [x.powi(24)], -1.0, 1.0).unwrap();
        assert!((p.value[0] - 2.0 / 25.0).abs() > 1e-10);
    }

    #[test]
    fn gauss_nodes_are_the_legendre_nodes() {
        let (x, _) = gauss_legendre_unit(7);
        let mut ours: Vec<f64> = [1, 3, 5, 7]
            .iter()
            .flat_map(|&i| [0.5 * (1.0 - XGK[i]), 0.5 * (1.0 + XGK[i])])
            .collect();
        ours.sort_by(f64::total_cmp);
        ours.dedup();
        let mut theirs = x.clone();
        theirs.sort_by(f64::total_cmp);
        for (a, b) in ours.iter().zip(&theirs) {
            assert!((a - b).abs() < 1e-15);
        }
    }

    #[test]
    fn adaptive_meets_tolerance_on_a_peak_and_an_oscillation() {
        // ∫₀¹ 1/(1e-4 + (x − 0.3)²) dx and ∫₀^{50} cos²(x)/(1+x²) dx.
        let peak = integrate(
            |x| [1.0 / (1e-4 + (x - 0.3) * (x - 0.3))],
            &[0.0, 1.0],
            Targets {
                absolute: [0.0],
                relative: 1e-12,
            },
            1000,
        )
        .unwrap();
        let exact = 100.0 * ((0.7f64 / 0.01).atan() + (0.3f64 / 0.01).atan());
        assert!(
            (peak.value[0] / exact - 1.0).abs() < 1e-12,
            "{}",
            peak.value[0]
        );
        let too_few = integrate(
            |x| [1.0 / (1e-4 + (x - 0.3) * (x - 0.3))],
            &[0.0, 1.0],
            Targets {
                absolute: [0.0],
                relative: 1e-12,
            },
            3,
        );
        assert!(matches!(too_few, Err(Failure::PanelLimit { .. })));
        let nan = integrate(
            |x| [x.ln()],
            &[-1.0, 1.0],
            Targets {
                absolute: [0.0],
                relative: 1e-8,
            },
            100,
        );
        assert!(matches!(nan, Err(Failure::NotFinite { .. })));
    }
}
