//! Where a sweep of `physics = "exact"` solves the exact contact, and how
//! r = μ_exact/μ_approx is carried from the solved speeds to the others:
//! the nodes (distinct reduced speeds, or a grid for dense data), the
//! adaptive sweep with its interpolation error estimate, and the cubic interpolation in ln v (see the parent module's
//! "Accuracy and cost").
//!
//! # References
//!
//! - P.J. Davis, *Interpolation and Approximation*, Dover 1975, Ch. II–III
//!   (Lagrange interpolation and its remainder).

use crate::condense::BINS_PER_DECADE;
use crate::error::FitError;

/// The speeds to solve the exact contact at, increasing: the distinct
/// `reduced` speeds, or, when they are more than a grid of
/// [`BINS_PER_DECADE`] per decade over their range would hold (dense data,
/// which the fit sees in bins of that width anyway), that grid.
pub(super) fn solve_nodes(reduced: &[f64]) -> Vec<f64> {
    let mut distinct = reduced.to_vec();
    distinct.sort_by(f64::total_cmp);
    distinct.dedup();
    let (lo, hi) = (distinct[0], distinct[distinct.len() - 1]);
    let count = ((hi / lo).log10() * BINS_PER_DECADE).ceil() as usize + 1;
    if distinct.len() <= count {
        return distinct;
    }
    let (ln_lo, ln_hi) = (lo.ln(), hi.ln());
    let mut grid: Vec<f64> = (0..count)
        .map(|k| (ln_lo + (ln_hi - ln_lo) * k as f64 / (count - 1) as f64).exp())
        .collect();
    // Both ends exact, so that every row lies inside the grid.
    grid[0] = lo;
    grid[count - 1] = hi;
    grid
}

/// ln r at one node and the error estimate of the exact solution behind it.
pub(super) type NodeSolve = (f64, f64);

/// The exact solves at a batch of nodes (indices), in the batch's order.
pub(super) type SolveBatch<'a> = dyn Fn(&[usize]) -> Result<Vec<NodeSolve>, FitError> + 'a;

/// The solved (node index, (ln r, error estimate)) pairs of an adaptive
/// sweep, in increasing index. `solve` first at every fourth node and the
/// last (every other one with fewer than 2 [`THIN_FROM`] nodes, all with
/// fewer than [`THIN_FROM`]), then in rounds that halve the stride: at
/// each node of the finer stride not yet solved where the interpolation
/// of y = ln r − `base`(i) from the nodes solved so far may be off by
/// more than `tolerance`.
///
/// The estimate at a node is the largest difference between the cubic
/// through the four nearest solved nodes (what is used) and the
/// quadratics through three and the quartics through five nearby solved
/// nodes. The quadratics' error is of order h³ against the cubic's h⁴,
/// so their difference overstates the cubic's error where y has a third
/// derivative; the quartics' difference is the cubic's leading error term
/// itself, which the quadratics miss where y is locally even (a
/// symmetric bump centred on the node). Neither can see a feature
/// narrower than the solved nodes' spacing: r is a ratio of two smooth
/// friction curves, whose features span decades, against 0.8 decade
/// between the first nodes of the broad rubber's 41.
pub(super) fn adaptive_fill(
    nodes: &[f64],
    base: impl Fn(usize) -> f64,
    tolerance: f64,
    solve: &SolveBatch,
) -> Result<(Vec<usize>, Vec<NodeSolve>), FitError> {
    let n = nodes.len();
    let mut stride = match n {
        n if n < THIN_FROM => 1,
        n if n < 2 * THIN_FROM => 2,
        _ => 4,
    };
    let first: Vec<usize> = (0..n).filter(|i| i % stride == 0 || *i == n - 1).collect();
    let found = solve(&first)?;
    let mut solved: Vec<(usize, (f64, f64))> = first.into_iter().zip(found).collect();
    while stride > 1 {
        stride /= 2;
        let speeds: Vec<f64> = solved.iter().map(|(i, _)| nodes[*i]).collect();
        let y: Vec<f64> = solved
            .iter()
            .map(|(i, (ln_r, _))| ln_r - base(*i))
            .collect();
        let doubtful: Vec<usize> = (0..n)
            .step_by(stride)
            .filter(|i| solved.binary_search_by_key(i, |(j, _)| *j).is_err())
            .filter(|&i| interpolation_error(&speeds, &y, nodes[i]) > tolerance)
            .collect();
        if !doubtful.is_empty() {
            let more = solve(&doubtful)?;
            solved.extend(doubtful.into_iter().zip(more));
            solved.sort_by_key(|(i, _)| *i);
        }
    }
    Ok(solved.into_iter().unzip())
}

/// The error estimate of [`interpolate`] at `x` (see [`adaptive_fill`]):
/// the largest difference between the cubic and the polynomials one
/// order below and above it, through the nearest three or five nodes
/// shifted to either side; infinite with fewer than four nodes.
fn interpolation_error(nodes: &[f64], values: &[f64], x: f64) -> f64 {
    let n = nodes.len();
    if n < 4 {
        return f64::INFINITY;
    }
    let cubic = interpolate(nodes, values, x);
    let k = nodes.partition_point(|&v| v < x);
    let stencils = [(3, 2), (3, 1), (5, 3), (5, 2)];
    stencils
        .into_iter()
        .filter(|&(width, _)| width <= n)
        .map(|(width, left)| {
            let first = k.saturating_sub(left).min(n - width);
            let stencil = first..first + width;
            (cubic - lagrange(&nodes[stencil.clone()], &values[stencil], x)).abs()
        })
        .fold(0.0, f64::max)
}

/// The fewest nodes an adaptive sweep thins at all (every other one, and
/// from twice as many every fourth): fewer leave too few for a cubic
/// between them.
const THIN_FROM: usize = 12;

/// `values` (given at the increasing `nodes`) at `x`: the node's own value
/// where x is a node, else the cubic in ln v through the four nearest
/// nodes (fewer where there are fewer). Public (as
/// [`crate::exact_physics::interpolate`]) so that a report carries
/// ln r = ln(μ_exact/μ_approx) between the data's speeds as the fit does.
pub fn interpolate(nodes: &[f64], values: &[f64], x: f64) -> f64 {
    let k = nodes.partition_point(|&n| n < x);
    if k < nodes.len() && nodes[k] == x {
        return values[k];
    }
    let n = nodes.len();
    let width = n.min(4);
    // Two nodes on each side of x where possible.
    let first = k.saturating_sub(2).min(n - width);
    lagrange(
        &nodes[first..first + width],
        &values[first..first + width],
        x,
    )
}

/// The polynomial in ln v through (`nodes`, `values`) at `x`.
fn lagrange(nodes: &[f64], values: &[f64], x: f64) -> f64 {
    let t = x.ln();
    (0..nodes.len())
        .map(|i| {
            let weight: f64 = (0..nodes.len())
                .filter(|&j| j != i)
                .map(|j| (t - nodes[j].ln()) / (nodes[i].ln() - nodes[j].ln()))
                .product();
            weight * values[i]
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sparse data are solved at each distinct speed; dense data on a grid
    /// of 20 per decade with both ends exact.
    #[test]
    fn nodes_are_the_distinct_speeds_or_a_grid() {
        let speeds = [1e-3, 1e-5, 1e-3, 1e-4];
        assert_eq!(solve_nodes(&speeds), vec![1e-5, 1e-4, 1e-3]);
        let dense: Vec<f64> = (0..1000)
            .map(|i| 1e-6 * 10f64.powf(i as f64 / 500.0))
            .collect();
        let grid = solve_nodes(&dense);
        assert_eq!(grid.len(), 41);
        assert_eq!((grid[0], grid[40]), (dense[0], dense[999]));
        assert!(grid.windows(2).all(|w| w[1] > w[0]));
    }

    /// Exact at nodes, and exact for a cubic in ln v between them (with
    /// two nodes, linear); the first sweep keeps every other speed and the
    /// last.
    #[test]
    fn interpolation_is_cubic_in_ln_v() {
        let nodes: Vec<f64> = [-6.0, -5.2, -4.0, -3.1, -2.0, -1.0]
            .iter()
            .map(|e| 10f64.powf(*e))
            .collect();
        let cubic = |v: f64| {
            let t = v.ln();
            0.3 - 0.02 * t + 1e-3 * t * t - 2e-5 * t * t * t
        };
        let values: Vec<f64> = nodes.iter().map(|&v| cubic(v)).collect();
        assert_eq!(interpolate(&nodes, &values, nodes[3]), values[3]);
        for e in [-5.9, -5.5, -4.7, -3.5, -2.5, -1.1] {
            let v = 10f64.powf(e);
            assert!(
                (interpolate(&nodes, &values, v) - cubic(v)).abs() < 1e-12,
                "{e}"
            );
        }
        let two = [1e-4, 1e-2];
        assert!((interpolate(&two, &[1.0, 3.0], 1e-3) - 2.0).abs() < 1e-12);
    }

    /// An adaptive sweep solves every fourth node and then only where the
    /// interpolation estimate exceeds the tolerance: none for a cubic in
    /// ln v, the skipped nodes beside a narrow bump that the thinned nodes
    /// straddle; against a base equal to the function up to a cubic, none
    /// again; all of a short sweep.
    #[test]
    fn adaptive_sweeps_solve_where_the_interpolation_is_doubtful() {
        let nodes: Vec<f64> = (0..41).map(|i| 10f64.powf(-8.0 + 0.2 * i as f64)).collect();
        let cubic = |v: f64| {
            let t = v.ln() + 10.0;
            0.05 - 2e-3 * t + 1e-4 * t * t - 1e-7 * t * t * t
        };
        // A bump of height 1e-3 and width 0.6 decade at node 9 (skipped).
        let bump = |v: f64| 1e-3 * (-((v.log10() + 6.2) / 0.6).powi(2)).exp();
        let run = |f: &dyn Fn(f64) -> f64, base: &dyn Fn(usize) -> f64| {
            let calls = std::cell::RefCell::new(Vec::new());
            let solve = |at: &[usize]| -> Result<Vec<(f64, f64)>, FitError> {
                calls.borrow_mut().extend_from_slice(at);
                Ok(at.iter().map(|&i| (f(nodes[i]), 1e-6)).collect())
            };
            let (solved, found) = adaptive_fill(&nodes, base, 1e-5, &solve).unwrap();
            assert!(solved.windows(2).all(|w| w[1] > w[0]));
            for (&i, (y, _)) in solved.iter().zip(&found) {
                assert_eq!(*y, f(nodes[i]));
            }
            let mut extra: Vec<usize> = calls
                .into_inner()
                .into_iter()
                .filter(|i| i % 4 != 0)
                .collect();
            extra.sort();
            extra
        };
        assert_eq!(run(&cubic, &|_| 0.0), Vec::<usize>::new());
        let bumped = |v: f64| cubic(v) + bump(v);
        let extra = run(&bumped, &|_| 0.0);
        assert!(extra.contains(&9), "{extra:?}");
        assert!(extra.len() < 16, "{extra:?}");
        // The base carries the bump: what is interpolated is the cubic.
        let base = |i: usize| bump(nodes[i]);
        assert_eq!(run(&bumped, &base), Vec::<usize>::new());
        // Fewer than four solved nodes cannot estimate: all are solved.
        let short = &nodes[..5];
        let solve = |at: &[usize]| -> Result<Vec<(f64, f64)>, FitError> {
            Ok(at.iter().map(|&i| (cubic(short[i]), 0.0)).collect())
        };
        let (solved, _) = adaptive_fill(short, |_| 0.0, 1.0, &solve).unwrap();
        assert_eq!(solved, vec![0, 1, 2, 3, 4]);
    }
}
