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
//! The same table serves the strip of plane strain ([`Element::Strip`],
//! one row, C the strip's −(2/π)∫ln kernel). That kernel does not decay,
//! but the recursion is exact for any C whose memory integral converges,
//! and ∫_0^∞ e^{−s} ln(X + ℓs) ds does: the start value is the tail
//! integral of the log kernel's far form, and M grows only like
//! −(2/π) ln ℓ for ℓ ≫ X. Each strip table (C and every M) is then shifted
//! by a constant so that it vanishes at the offset X = nx − 1, one grid
//! length ahead: the reference point of the logarithm is moved to a grid
//! length. This is harmless — a constant c in a table adds c h Σ p = c W
//! (times that table's weight) to the displacement of every cell, which
//! the approach absorbs at the prescribed load, so the pressures do not
//! change — and it keeps the self-influence A(0) that the contact solver's
//! defect estimate divides by positive and of the size of the local
//! stiffness (C(0) − C(X_ref) > 0, and M(0) − M(X_ref) ≥ 0 since
//! |ℓs| ≤ X_ref + ℓs on the whole path), where the unshifted M at high
//! speed, ≈ −(2/π) ln ℓ, would make it negative.
//! The approach of a strip solution is therefore measured from the
//! displacement that the whole load, as a line load, causes one grid
//! length ahead (the absolute approach of plane strain is undefined).
//!
//! # References
//! - S.C. Hunter, J. Appl. Mech. 28 (1961) 611–617.
//! - K.L. Johnson, *Contact Mechanics*, Cambridge 1985, §7.6.
//! - P.J. Davis, P. Rabinowitz, *Methods of Numerical Integration*, 2nd ed.,
//!   Academic Press 1984, §2.5 (product integration).

use std::f64::consts::PI;

use super::cell::{FAR_SQUARE_DISTANCE, MULTIPOLE_DISTANCE, corner, far_field, far_field_square};
use super::element::Element;
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
    /// The boundary element (square cell or plane-strain strip).
    element: Element,
    /// Interpolation nodes in (0, ½) then (½, 1).
    nodes: Vec<f64>,
    /// C(X, Y) at index Y·(2nx − 1) + (X + nx − 1).
    pub elastic: Vec<f64>,
    /// C(X + ξ_q, Y) at index (Y·(2nx − 1) + X + nx − 1)·nodes + q.
    samples: Vec<f64>,
}

impl CellTable {
    /// The table of an nx × ny grid of `element`s with `order` nodes on
    /// each half cell (a strip grid has ny = 1; its table is shifted to
    /// vanish at X = nx − 1, see the module documentation).
    pub fn new(nx: usize, ny: usize, order: usize, element: Element) -> Self {
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
            let values = match element {
                Element::Square => corner_differences(nx, ny, *shift),
                Element::Strip => (0..width)
                    .map(|i| element.potential(i as f64 - (nx - 1) as f64 + shift, 0.0))
                    .collect(),
            };
            for (k, c) in values.into_iter().enumerate() {
                if q == 0 {
                    elastic[k] = c;
                } else {
                    samples[k * nodes.len() + q - 1] = c;
                }
            }
        }
        if element == Element::Strip {
            let reference = elastic[width - 1];
            elastic.iter_mut().for_each(|c| *c -= reference);
        }
        CellTable {
            nx,
            ny,
            element,
            nodes,
            elastic,
            samples,
        }
    }

    /// Gauss–Legendre nodes per half cell.
    pub fn order(&self) -> usize {
        self.nodes.len() / 2
    }

    /// The element the table was built for.
    pub fn element(&self) -> Element {
        self.element
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
            let mut next = tail(self.element, self.nx as f64, y as f64, ell, &rule);
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
        if self.element == Element::Strip {
            let reference = out[width - 1];
            out.iter_mut().for_each(|m| *m -= reference);
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
/// grid's leading end (C of a square cell by its multipole form from 40
/// cells on, [`far_potential`]: the tails were about 43 % of a fit's
/// sphere solve with the corner form), by 16-point Gauss–Legendre on panels that double
/// from the scale on which C changes (ρ0/ℓ) up to width 4, to s = 46 (the
/// log kernel grows only like ln s there, e^{−46} ln(ℓ s) is negligible).
/// (`rule`: the 16-point rule on [0, 1], nodes and weights.)
fn tail(element: Element, x0: f64, y: f64, ell: f64, rule: &(Vec<f64>, Vec<f64>)) -> f64 {
    let rho0 = x0.hypot(y);
    let mut step = (rho0 / ell).min(1.0) * 0.5;
    let (mut p, mut sum) = (0.0, 0.0);
    while p < 46.0 {
        let q = (p + step).min(46.0);
        for (t, w) in rule.0.iter().zip(&rule.1) {
            let s = p + t * (q - p);
            sum += w * (q - p) * (-s).exp() * far_potential(element, x0 + ell * s, y);
        }
        p = q;
        step = (2.0 * step).min(4.0);
    }
    sum
}

/// The element's potential at (x, y), for a square cell from
/// [`FAR_SQUARE_DISTANCE`] on by its multipole form (the tail integrals'
/// points all lie beyond the grid, mostly that far).
fn far_potential(element: Element, x: f64, y: f64) -> f64 {
    if element == Element::Square && x * x + y * y >= FAR_SQUARE_DISTANCE * FAR_SQUARE_DISTANCE {
        far_field_square(x, y)
    } else {
        element.potential(x, y)
    }
}

#[cfg(test)]
mod tests {
    use super::super::cell::unit_cell_potential;
    use super::super::strip::unit_strip_potential;
    use super::*;

    /// The tail with the multipole form beyond 40 cells equals the tail
    /// with the corner form everywhere to 1e-11 (the corner form's own
    /// rounding there, `cell::tests`), on rows of a 64-cell grid.
    #[test]
    fn multipole_tail_matches_the_corner_form() {
        let rule = gauss_legendre_unit(16);
        let corner_tail = |x0: f64, y: f64, ell: f64| {
            let mut step = (x0.hypot(y) / ell).min(1.0) * 0.5;
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
        };
        for y in [0.0, 17.0, 58.0] {
            for ell in [1e-3, 0.05, 3.0, 40.0, 1e3, 1e5] {
                let (fast, slow) = (
                    tail(Element::Square, 87.0, y, ell, &rule),
                    corner_tail(87.0, y, ell),
                );
                assert!(
                    (fast / slow - 1.0).abs() < 1e-11,
                    "y {y}, ℓ {ell}: {fast} vs {slow}"
                );
            }
        }
    }

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
        let table = CellTable::new(5, 4, 3, Element::Square);
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

    /// ∫_0^∞ e^{−s} potential(X + ℓ s) ds by a direct, slow quadrature:
    /// panels of width at most 0.02 to s = 60, split where the path crosses
    /// the element's edges X = ±½ (kinks of C on the row Y = 0) and at
    /// s = 4^k/ℓ (the path's distance growing geometrically, for large ℓ).
    fn direct_memory(potential: impl Fn(f64) -> f64, x: f64, ell: f64) -> f64 {
        let rule = gauss_legendre_unit(32);
        let mut breaks = vec![0.0, 60.0];
        let mut s = 1.0 / ell;
        while s < 0.02 {
            breaks.push(s);
            s *= 4.0;
        }
        for edge in [-0.5, 0.5] {
            let s = (edge - x) / ell;
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
                    sum += w * width * (-s).exp() * potential(x + ell * s);
                }
            }
        }
        sum
    }

    /// The recursion against the direct quadrature of
    /// ∫_0^∞ e^{−s} C(X + ℓ s, Y) ds.
    #[test]
    fn memory_matches_direct_quadrature() {
        let table = CellTable::new(6, 4, 12, Element::Square);
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
                let sum = direct_memory(|t| unit_cell_potential(t, y as f64), x as f64, ell);
                let k = y * table.width() + (x + 5) as usize;
                assert!(
                    (m[k] / sum - 1.0).abs() < 2e-7,
                    "ℓ = {ell}, ({x}, {y}): {} vs {sum}",
                    m[k]
                );
            }
        }
    }

    /// The strip's table (plane strain): the recursion, started from the
    /// log kernel's tail, against the direct quadrature, both relative to
    /// the reference offset X = nx − 1 = 5 where the table is zero, to the
    /// square cell's 2e-7 of M (measured at most 3e-10 of M, 1.6e-9
    /// absolute, at ℓ = 1e4); and the elastic row C(X) − C(5).
    #[test]
    fn strip_memory_matches_direct_quadrature() {
        let table = CellTable::new(6, 1, 12, Element::Strip);
        let c = unit_strip_potential;
        for x in -5i32..=5 {
            let want = c(x as f64) - c(5.0);
            assert!((table.elastic[(x + 5) as usize] - want).abs() < 1e-14);
        }
        for ell in [0.05, 0.8, 3.0, 40.0, 1e4, 1e7] {
            let m = table.memory(ell);
            let reference = direct_memory(c, 5.0, ell);
            for x in [-5i32, -1, 0, 2, 4] {
                let direct = direct_memory(c, x as f64, ell);
                let want = direct - reference;
                let got = m[(x + 5) as usize];
                assert!(
                    (got - want).abs() < 2e-7 * direct.abs(),
                    "ℓ = {ell}, {x}: {got} vs {want}"
                );
            }
        }
    }
}
