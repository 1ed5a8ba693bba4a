//! The memory part of the influence coefficients: what a cell's pressure
//! still does to the surface after the material has moved on.
//!
//! In the frame of the sphere (rolling at v in +x) the material now at
//! (x, y) was at (x + vt, y) a time t ago, so a creep compliance
//! J(t) = J0 + Σ_j c_j (1 − e^{−t/λ_j}) turns the elastic influence C of a
//! cell ([`super::cell`]) into
//!
//!   A(X, Y) = J0 C(X, Y) + Σ_j c_j M(X, Y; ℓ_j),
//!   M(X, Y; ℓ) = ∫_0^∞ e^{−s} C(X + ℓ s, Y) ds,   ℓ_j = vλ_j / h,
//!
//! in cell units (Hunter 1961 for the cylinder; Johnson §7.6). On the
//! integer offsets X of the grid M obeys the exact recursion
//!
//!   M(X) = ∫_0^1 e^{−ξ/ℓ}/ℓ · C(X + ξ, Y) dξ + e^{−1/ℓ} M(X + 1),
//!
//! run from the far leading side (where M is the tail integral, evaluated
//! with the multipole form of C) down to the trailing side. The interval
//! integral is done by product integration: C(X + ξ) is interpolated by
//! Lagrange polynomials through Gauss–Legendre nodes on each half of
//! [0, 1] (split at ½, where C has its x ln x kink on the row Y = 0), and
//! the polynomials are integrated exactly against e^{−ξ/ℓ}/ℓ. The samples
//! of C at the nodes depend on the grid only, not on the speed or the
//! material: they are tabulated once ([`CellTable`]), and each retardation
//! time at each speed costs one weighted sum per grid offset.
//!
//! # References
//! - S.C. Hunter, J. Appl. Mech. 28 (1961) 611–617.
//! - K.L. Johnson, *Contact Mechanics*, Cambridge 1985, §7.6.
//! - P.J. Davis, P. Rabinowitz, *Methods of Numerical Integration*, 2nd ed.,
//!   Academic Press 1984, §2.5 (product integration).

use std::f64::consts::PI;

use super::cell::{MULTIPOLE_DISTANCE, corner, far_field, unit_cell_potential};
use crate::kernel::quadrature::gauss_legendre_unit;

/// The elastic influence C and its samples at the product-integration
/// nodes, on the offsets X = −(nx − 1) … nx − 1, Y = 0 … ny − 1 (C is
/// even in Y).
#[derive(Debug, Clone)]
pub(crate) struct CellTable {
    /// Cells of the grid along x.
    pub nx: usize,
    /// Cells of the grid along y.
    pub ny: usize,
    /// Interpolation nodes in (0, ½) then (½, 1).
    nodes: Vec<f64>,
    /// C(X, Y) at index Y·(2nx − 1) + (X + nx − 1).
    pub elastic: Vec<f64>,
    /// C(X + ξ_q, Y) at index (Y·(2nx − 1) + X + nx − 1)·nodes + q.
    samples: Vec<f64>,
}

impl CellTable {
    /// The table of an nx × ny grid with `order` nodes on each half cell.
    pub fn new(nx: usize, ny: usize, order: usize) -> Self {
        let (x, _) = gauss_legendre_unit(order);
        let nodes: Vec<f64> = x
            .iter()
            .map(|t| 0.5 * t)
            .chain(x.iter().map(|t| 0.5 + 0.5 * t))
            .collect();
        let width = 2 * nx - 1;
        let mut elastic = vec![0.0; width * ny];
        let mut samples = vec![0.0; width * ny * nodes.len()];
        // Neighbouring offsets share cell corners: F is evaluated once per
        // corner and C taken as its second difference (a quarter of the
        // work of evaluating C point by point).
        let shifts: Vec<f64> = std::iter::once(0.0).chain(nodes.iter().copied()).collect();
        for (q, shift) in shifts.iter().enumerate() {
            let values = corner_differences(nx, ny, *shift);
            for (k, c) in values.into_iter().enumerate() {
                if q == 0 {
                    elastic[k] = c;
                } else {
                    samples[k * nodes.len() + q - 1] = c;
                }
            }
        }
        CellTable {
            nx,
            ny,
            nodes,
            elastic,
            samples,
        }
    }

    /// Gauss–Legendre nodes per half cell.
    pub fn order(&self) -> usize {
        self.nodes.len() / 2
    }

    /// Row length 2nx − 1 of the offset tables.
    pub fn width(&self) -> usize {
        2 * self.nx - 1
    }

    /// M(X, Y; ℓ) on the table's offsets, same layout as `elastic`, for a
    /// memory length `ell` in cells.
    pub fn memory(&self, ell: f64) -> Vec<f64> {
        let weights = product_weights(&self.nodes, ell);
        let decay = (-1.0 / ell).exp();
        let (width, n) = (self.width(), self.nodes.len());
        let mut out = vec![0.0; self.elastic.len()];
        let rule = gauss_legendre_unit(16);
        for y in 0..self.ny {
            let mut next = tail(self.nx as f64, y as f64, ell, &rule);
            for i in (0..width).rev() {
                let k = y * width + i;
                let local: f64 = self.samples[k * n..(k + 1) * n]
                    .iter()
                    .zip(&weights)
                    .map(|(c, w)| c * w)
                    .sum();
                next = local + decay * next;
                out[k] = next;
            }
        }
        out
    }
}

/// C(X + shift, Y) for X = −(nx − 1) … nx − 1, Y = 0 … ny − 1 (layout of
/// [`CellTable::elastic`]), from the corner function on the shared corners;
/// the multipole form where the offset is far.
fn corner_differences(nx: usize, ny: usize, shift: f64) -> Vec<f64> {
    let width = 2 * nx - 1;
    // Corners s_a = a − (nx − 1) − ½ + shift, t_b = b − ½ (b = 0 … ny), in
    // the frame of the field point: s = corner − field = −(that).
    let s: Vec<f64> = (0..=width)
        .map(|a| -(a as f64 - (nx - 1) as f64 - 0.5 + shift))
        .collect();
    let t: Vec<f64> = (0..=ny).map(|b| -(b as f64 - 0.5)).collect();
    let mut f = vec![0.0; s.len() * t.len()];
    for (b, tb) in t.iter().enumerate() {
        for (a, sa) in s.iter().enumerate() {
            f[b * s.len() + a] = corner(*sa, *tb);
        }
    }
    let mut out = vec![0.0; width * ny];
    for y in 0..ny {
        for i in 0..width {
            let x = i as f64 - (nx - 1) as f64 + shift;
            let rho = x.hypot(y as f64);
            out[y * width + i] = if rho > MULTIPOLE_DISTANCE {
                far_field(rho)
            } else {
                // Cell [x−½, x+½] × [y−½, y+½] relative to the field point
                // at the origin: s from −(x+½) … −(x−½) is reversed in a.
                let (a0, a1) = (i, i + 1);
                let (b0, b1) = (y, y + 1);
                let at = |a: usize, b: usize| f[b * s.len() + a];
                (at(a0, b0) - at(a1, b0) - at(a0, b1) + at(a1, b1)) / PI
            };
        }
    }
    out
}

/// W_q = ∫_0^1 e^{−ξ/ℓ}/ℓ L_q(ξ) dξ for the Lagrange basis L_q of each half
/// cell's nodes (zero on the other half). The integrals are taken by
/// 16-point Gauss–Legendre on panels graded geometrically from each half's
/// left end in steps of ℓ, so that the exponential is resolved for any ℓ.
fn product_weights(nodes: &[f64], ell: f64) -> Vec<f64> {
    let half = nodes.len() / 2;
    let rule = gauss_legendre_unit(16);
    let mut weights = vec![0.0; nodes.len()];
    for (part, (a, b)) in [(0.0, 0.5), (0.5, 1.0)].into_iter().enumerate() {
        let local = &nodes[part * half..(part + 1) * half];
        for (p, q) in graded_panels(a, b, ell) {
            for (t, w) in rule.0.iter().zip(&rule.1) {
                let xi = p + t * (q - p);
                let f = w * (q - p) * (-xi / ell).exp() / ell;
                if f == 0.0 {
                    continue;
                }
                for (k, weight) in weights[part * half..(part + 1) * half]
                    .iter_mut()
                    .enumerate()
                {
                    *weight += f * lagrange(local, k, xi);
                }
            }
        }
    }
    weights
}

/// Panels of [a, b]: a, a + ℓ, a + 2ℓ, a + 4ℓ, … (at most quarter-width
/// panels), stopping where e^{−(ξ − a)/ℓ} has fallen below 1e-20.
fn graded_panels(a: f64, b: f64, ell: f64) -> Vec<(f64, f64)> {
    let max_width = 0.25 * (b - a);
    let end = b.min(a + 46.0 * ell);
    let mut panels = Vec::new();
    let (mut p, mut step) = (a, ell.min(max_width));
    while p < end {
        let q = (p + step).min(end);
        panels.push((p, q));
        p = q;
        step = (2.0 * step).min(max_width);
    }
    panels
}

/// The k-th Lagrange basis polynomial through `nodes`, at ξ.
fn lagrange(nodes: &[f64], k: usize, xi: f64) -> f64 {
    nodes
        .iter()
        .enumerate()
        .filter(|(j, _)| *j != k)
        .map(|(_, &xj)| (xi - xj) / (nodes[k] - xj))
        .product()
}

/// M(X0, Y; ℓ) = ∫_0^∞ e^{−s} C(X0 + ℓ s, Y) ds for X0 at or beyond the
/// grid's leading end (C switches to its multipole form by itself far
/// away), by 16-point Gauss–Legendre on panels that double
/// from the scale on which C changes (ρ0/ℓ) up to width 4, to s = 46.
/// (`rule`: the 16-point rule on [0, 1], nodes and weights).
fn tail(x0: f64, y: f64, ell: f64, rule: &(Vec<f64>, Vec<f64>)) -> f64 {
    let rho0 = x0.hypot(y);
    let mut step = (rho0 / ell).min(1.0) * 0.5;
    let (mut p, mut sum) = (0.0, 0.0);
    while p < 46.0 {
        let q = (p + step).min(46.0);
        for (t, w) in rule.0.iter().zip(&rule.1) {
            let s = p + t * (q - p);
            sum += w * (q - p) * (-s).exp() * unit_cell_potential(x0 + ell * s, y);
        }
        p = q;
        step = (2.0 * step).min(4.0);
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The weights integrate constants and the node polynomials exactly:
    /// Σ W_q = 1 − e^{−1/ℓ}, and Σ W_q ξ_q² = ∫ ξ² e^{−ξ/ℓ}/ℓ.
    #[test]
    fn product_weights_are_exact_for_polynomials() {
        let (x, _) = gauss_legendre_unit(8);
        let nodes: Vec<f64> = x
            .iter()
            .map(|t| 0.5 * t)
            .chain(x.iter().map(|t| 0.5 + 0.5 * t))
            .collect();
        for ell in [1e-4, 0.03, 0.7, 5.0, 300.0] {
            let w = product_weights(&nodes, ell);
            let sum: f64 = w.iter().sum();
            let want = -(-1.0 / ell).exp_m1();
            assert!(
                (sum / want - 1.0).abs() < 1e-12,
                "ℓ = {ell}: {sum} vs {want}"
            );
            // ∫_0^1 ξ² e^{−ξ/ℓ}/ℓ dξ = 2ℓ² − e^{−1/ℓ}(1 + 2ℓ + 2ℓ²), which
            // cancels for large ℓ.
            if ell > 10.0 {
                continue;
            }
            let second: f64 = w.iter().zip(&nodes).map(|(w, x)| w * x * x).sum();
            let exact = 2.0 * ell * ell - (-1.0 / ell).exp() * (1.0 + 2.0 * ell + 2.0 * ell * ell);
            assert!(
                (second - exact).abs() < 1e-12 * exact.abs() + 1e-15,
                "ℓ = {ell}: {second} vs {exact}"
            );
        }
    }

    /// The shared-corner table equals C evaluated point by point.
    #[test]
    fn table_equals_pointwise_potential() {
        let table = CellTable::new(5, 4, 3);
        for y in 0..4 {
            for i in 0..9 {
                let x = i as f64 - 4.0;
                let k = y * 9 + i;
                let want = unit_cell_potential(x, y as f64);
                assert!((table.elastic[k] - want).abs() < 1e-13, "({x}, {y})");
                for (q, xi) in table.nodes.iter().enumerate() {
                    let want = unit_cell_potential(x + xi, y as f64);
                    let got = table.samples[k * 6 + q];
                    assert!(
                        (got - want).abs() < 1e-13,
                        "({x} + {xi}, {y}): {got} vs {want}"
                    );
                }
            }
        }
    }

    /// The recursion against a direct, slow quadrature of
    /// ∫_0^∞ e^{−s} C(X + ℓ s, Y) ds (adaptive in s, split where the path
    /// crosses the cell's edges).
    #[test]
    fn memory_matches_direct_quadrature() {
        let table = CellTable::new(6, 4, 12);
        let rule = gauss_legendre_unit(32);
        for ell in [0.05, 0.8, 3.0, 40.0] {
            let m = table.memory(ell);
            for (x, y) in [
                (-5i32, 0usize),
                (-1, 0),
                (0, 0),
                (2, 0),
                (0, 1),
                (-3, 2),
                (5, 3),
            ] {
                // Panels of width 0.02 between the points where the path
                // crosses the cell's edges x = ±½ (kinks of C on Y = 0).
                let mut breaks = vec![0.0, 60.0];
                for edge in [-0.5, 0.5] {
                    let s = (edge - x as f64) / ell;
                    if s > 0.0 && s < 60.0 {
                        breaks.push(s);
                    }
                }
                breaks.sort_by(f64::total_cmp);
                let mut sum = 0.0;
                for pair in breaks.windows(2) {
                    let panels = ((pair[1] - pair[0]) / 0.02).ceil().max(1.0) as usize;
                    let width = (pair[1] - pair[0]) / panels as f64;
                    for k in 0..panels {
                        let p = pair[0] + k as f64 * width;
                        for (t, w) in rule.0.iter().zip(&rule.1) {
                            let s = p + t * width;
                            sum += w
                                * width
                                * (-s).exp()
                                * unit_cell_potential(x as f64 + ell * s, y as f64);
                        }
                    }
                }
                let k = y * table.width() + (x + 5) as usize;
                assert!(
                    (m[k] / sum - 1.0).abs() < 2e-7,
                    "ℓ = {ell}, ({x}, {y}): {} vs {sum}",
                    m[k]
                );
            }
        }
    }
}
