//! The graded mesh of the layer-resolving cylinder solution
//! ([`super::cylinder_graded`]): the contact in the distance from the
//! leading edge, u = 1 − t ∈ [0, 2] (t = (x − c)/b), cut into panels that
//! grow geometrically from the leading edge,
//!
//!   [0, h0], [h0, h0(1 + r)], …, width h0 r^k up to `widest`, then equal,
//!
//! with Gauss–Legendre nodes on each. The unknown F(t) (the Hilbert
//! transform of the pressure inside the contact) is the Lagrange
//! interpolant of its nodal values on each panel.
//!
//! Working in u rather than t keeps the nodes of the thinnest panels
//! (h0 ≈ 1e-12 for E1/E0 = 1e4 at vτ/a0 = 1e-4) exact: 1 − 1e-12 carries
//! only four digits of u.
//!
//! The mesh also supplies the integrals with the Chebyshev weight,
//! ∫ F g dt/√(1 − t²) = ∫ F g du/√(u(2 − u)), as weights on the nodal
//! values. Up to u = 1 the substitution u = s² removes the inverse square
//! root, du/√(u(2 − u)) = 2 ds/√(2 − s²), and on the last panel
//! 2 − u = h s² does (see `weighted_points`).
//!
//! # References
//! - J.-P. Berrut, L.N. Trefethen, "Barycentric Lagrange interpolation",
//!   SIAM Rev. 46 (2004) 501–517 (the interpolant and its derivative).
//! - F.G. Tricomi, *Integral Equations*, Interscience 1957, ch. IV (the
//!   Cauchy integral of F/√(1 − t²) off the interval, `outer_row`).

use super::cylinder_pressure::PressureProfile;
use crate::kernel::quadrature::gauss_legendre_unit;

/// One integration point of ∫ F g du/√(u(2 − u)): the weight includes the
/// Chebyshev weight; F there is the interpolant of its panel.
#[derive(Debug, Clone)]
struct WeightedPoint {
    u: f64,
    weight: f64,
    panel: usize,
}

/// The local integral of the memory stepping over [a, b] (part of the
/// interval between two neighbouring nodes, inside one panel): Gauss nodes
/// s_g with weights and the Lagrange basis of the panel there.
#[derive(Debug, Clone)]
pub(crate) struct LocalPart {
    pub(crate) panel: usize,
    pub(crate) a: f64,
    pub(crate) b: f64,
    /// Gauss nodes s_g in [a, b].
    pub(crate) nodes: Vec<f64>,
    /// Gauss weights (length of [a, b] included).
    pub(crate) weights: Vec<f64>,
    /// L_l(s_g) at [g·q + l].
    pub(crate) lagrange: Vec<f64>,
}

/// Panels graded geometrically from the leading edge (u = 0), q Gauss
/// nodes on each.
#[derive(Debug, Clone)]
pub(crate) struct GradedMesh {
    order: usize,
    panels: Vec<(f64, f64)>,
    nodes: Vec<f64>,
    /// Gauss–Legendre nodes and weights of the panels on [0, 1] (ascending).
    unit: (Vec<f64>, Vec<f64>),
    /// Barycentric weights of `unit`'s nodes.
    barycentric: Vec<f64>,
    /// d/dξ of the Lagrange basis at the nodes (ξ ∈ [0, 1]), [i·q + l].
    derivative: Vec<f64>,
    /// The 2q-point rule of the end panels (in s) and of the near-singular
    /// outer integrals.
    fine: (Vec<f64>, Vec<f64>),
    weighted: Vec<WeightedPoint>,
    /// The Lagrange basis of each weighted point's panel at it, [k·q + l].
    weighted_lagrange: Vec<f64>,
    /// Per node i, the parts of [u_{i−1}, u_i] (u_{−1} = 0) by panel.
    local: Vec<Vec<LocalPart>>,
}

impl GradedMesh {
    /// `order` nodes per panel; the first panel `first` wide, each next
    /// `ratio` times the previous up to `widest`.
    pub(crate) fn new(order: usize, first: f64, ratio: f64, widest: f64) -> Self {
        let unit = gauss_legendre_unit(order);
        let barycentric = barycentric_weights(&unit.0);
        let derivative = differentiation_matrix(&unit.0, &barycentric);
        let mut panels = Vec::new();
        let (mut lo, mut width) = (0.0f64, first.min(widest));
        while lo < 2.0 {
            // The last panel takes the rest rather than leave a sliver.
            let w = if lo + 1.5 * width >= 2.0 {
                2.0 - lo
            } else {
                width
            };
            panels.push((lo, lo + w));
            lo += w;
            width = (width * ratio).min(widest);
        }
        let nodes = panels
            .iter()
            .flat_map(|&(lo, hi)| unit.0.iter().map(move |x| lo + (hi - lo) * x))
            .collect();
        let mut mesh = GradedMesh {
            order,
            panels,
            nodes,
            unit,
            barycentric,
            derivative,
            fine: gauss_legendre_unit(2 * order),
            weighted: Vec::new(),
            weighted_lagrange: Vec::new(),
            local: Vec::new(),
        };
        mesh.weighted_points();
        mesh.local_parts();
        mesh
    }

    /// Nodes per panel, q.
    pub(crate) fn order(&self) -> usize {
        self.order
    }

    /// The nodes u_i, ascending (from the leading edge).
    pub(crate) fn nodes(&self) -> &[f64] {
        &self.nodes
    }

    /// The panels (lo, hi) in u.
    pub(crate) fn panels(&self) -> &[(f64, f64)] {
        &self.panels
    }

    /// The parts of the stepping interval ending at node i.
    pub(crate) fn local_parts_of(&self, node: usize) -> &[LocalPart] {
        &self.local[node]
    }

    /// The Gauss rule of the panels on [0, 1].
    pub(crate) fn unit_rule(&self) -> &(Vec<f64>, Vec<f64>) {
        &self.unit
    }

    /// d/dξ of the Lagrange basis at the nodes on [0, 1], [i·q + l].
    pub(crate) fn derivative(&self) -> &[f64] {
        &self.derivative
    }

    /// The Lagrange basis of panel `panel` at u: `out[l]` = L_l(u).
    pub(crate) fn lagrange(&self, panel: usize, u: f64, out: &mut [f64]) {
        let (lo, hi) = self.panels[panel];
        let xi = (u - lo) / (hi - lo);
        let nodes = &self.unit.0;
        if let Some(l) = nodes.iter().position(|&x| x == xi) {
            out.fill(0.0);
            out[l] = 1.0;
            return;
        }
        let mut sum = 0.0;
        for ((o, &x), &w) in out.iter_mut().zip(nodes).zip(&self.barycentric) {
            *o = w / (xi - x);
            sum += *o;
        }
        out.iter_mut().for_each(|o| *o /= sum);
    }

    /// The points of ∫ F g du/√(u(2 − u)). The weight's inverse square
    /// root at u = 0 is near every panel of the geometric part (a panel
    /// [h, 3.5h] has it 0.4 lengths away: Gauss–Legendre in u would lose
    /// about 1e-9 there), so up to u = 1 the rule is Gauss in s = √u,
    /// du/√(u(2 − u)) = 2 ds/√(2 − s²), with 2q nodes (F is a polynomial
    /// of degree 2q − 2 in s); beyond, Gauss in u, and on the last panel in
    /// s with 2 − u = h s².
    fn weighted_points(&mut self) {
        let q = self.order;
        let last = self.panels.len() - 1;
        let mut lagrange = vec![0.0; q];
        for p in 0..=last {
            let (lo, hi) = self.panels[p];
            let h = hi - lo;
            if p == last {
                for k in 0..self.fine.0.len() {
                    let (s, w) = (self.fine.0[k], self.fine.1[k]);
                    let u = 2.0 - h * s * s;
                    let weight = w * 2.0 * h.sqrt() / (2.0 - h * s * s).sqrt();
                    self.lagrange(p, u, &mut lagrange);
                    self.push_weighted(u, weight, p, &lagrange);
                }
            } else if hi <= 1.0 {
                let (a, b) = (lo.sqrt(), hi.sqrt());
                for k in 0..self.fine.0.len() {
                    let s = a + (b - a) * self.fine.0[k];
                    let u = s * s;
                    let weight = (b - a) * self.fine.1[k] * 2.0 / (2.0 - u).sqrt();
                    self.lagrange(p, u, &mut lagrange);
                    self.push_weighted(u, weight, p, &lagrange);
                }
            } else {
                for l in 0..q {
                    let u = self.nodes[p * q + l];
                    lagrange.fill(0.0);
                    lagrange[l] = 1.0;
                    let weight = self.unit.1[l] * h / (u * (2.0 - u)).sqrt();
                    self.push_weighted(u, weight, p, &lagrange);
                }
            }
        }
    }

    fn push_weighted(&mut self, u: f64, weight: f64, panel: usize, lagrange: &[f64]) {
        self.weighted.push(WeightedPoint { u, weight, panel });
        self.weighted_lagrange.extend_from_slice(lagrange);
    }

    /// The row r with ∫ F g du/√(u(2 − u)) = r·F (F the nodal values), for
    /// g a function of u.
    pub(crate) fn functional(&self, g: impl Fn(f64) -> f64) -> Vec<f64> {
        let mut row = vec![0.0; self.nodes.len()];
        self.add_functional(&g, false, &mut row);
        row
    }

    /// Adds the functional of g to `row`, leaving out the first panel if
    /// `skip_first`.
    fn add_functional(&self, g: &impl Fn(f64) -> f64, skip_first: bool, row: &mut [f64]) {
        let q = self.order;
        for (point, basis) in self
            .weighted
            .iter()
            .zip(self.weighted_lagrange.chunks_exact(q))
        {
            if skip_first && point.panel == 0 {
                continue;
            }
            let value = point.weight * g(point.u);
            let cols = &mut row[point.panel * q..(point.panel + 1) * q];
            cols.iter_mut()
                .zip(basis)
                .for_each(|(r, l)| *r += value * l);
        }
    }

    /// The bounded continuation of F outside the contact at s = 1 + x,
    /// as a row on the nodal values:
    ///
    ///   F_out(1 + x) = (1/π) ∫ F(t) [√(x(x + 2))/(x + u) − 1] du/√(u(2 − u))
    ///
    /// (the −1 removes the T_0 part, zero for the solution, and makes the
    /// kernel decay as x → ∞). The kernel peaks at u ≈ 0 with width x; where
    /// x is narrower than the first panel, that panel is integrated on
    /// nodes graded in s (u = h0 s²) around √(x/h0).
    pub(crate) fn outer_row(&self, x: f64) -> Vec<f64> {
        let root = (x * (x + 2.0)).sqrt();
        let kernel = |u: f64| (root / (x + u) - 1.0) / std::f64::consts::PI;
        let h0 = self.panels[0].1;
        let mut row = vec![0.0; self.nodes.len()];
        if x >= 4.0 * h0 {
            self.add_functional(&kernel, false, &mut row);
            return row;
        }
        self.add_functional(&kernel, true, &mut row);
        // The kernel is a Lorentzian in s of width √(x/h0), with a 1/s² tail:
        // breaks at a quarter of the width, then doubling.
        let centre = (x / h0).sqrt();
        let mut breaks = vec![0.0];
        let mut s = 0.25 * centre;
        while s < 1.0 {
            breaks.push(s);
            s *= 2.0;
        }
        breaks.push(1.0);
        let q = self.order;
        let mut lagrange = vec![0.0; q];
        for pair in breaks.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            for (s, w) in self.fine.0.iter().zip(&self.fine.1) {
                let s = a + (b - a) * s;
                let u = h0 * s * s;
                let weight = (b - a) * w * 2.0 * h0.sqrt() / (2.0 - u).sqrt();
                self.lagrange(0, u, &mut lagrange);
                let value = weight * kernel(u);
                row[..q]
                    .iter_mut()
                    .zip(&lagrange)
                    .for_each(|(r, l)| *r += value * l);
            }
        }
        row
    }

    /// Splits each stepping interval [u_{i−1}, u_i] at panel ends and puts
    /// q + 2 Gauss nodes on each part (two more than the basis needs:
    /// exact for the basis times e^{−β(u_i − s)} to ~1e-14 where
    /// β(b − a) ≤ 2, see [`super::cylinder_graded`]).
    fn local_parts(&mut self) {
        let q = self.order;
        let rule = gauss_legendre_unit(q + 2);
        let mut local = Vec::with_capacity(self.nodes.len());
        for (i, &u) in self.nodes.iter().enumerate() {
            let p = i / q;
            let previous = if i == 0 { 0.0 } else { self.nodes[i - 1] };
            let lo = self.panels[p].0;
            let mut parts = Vec::with_capacity(2);
            if previous < lo {
                parts.push(self.part(p - 1, previous, lo, &rule));
            }
            parts.push(self.part(p, previous.max(lo), u, &rule));
            local.push(parts);
        }
        self.local = local;
    }

    /// F with nodal values `values` as a [`PressureProfile`].
    pub(crate) fn pressure_profile(&self, values: &[f64]) -> PressureProfile {
        let q = self.order;
        let points = self
            .weighted
            .iter()
            .zip(self.weighted_lagrange.chunks_exact(q))
            .map(|(point, basis)| {
                let f = basis
                    .iter()
                    .zip(&values[point.panel * q..(point.panel + 1) * q])
                    .map(|(l, v)| l * v)
                    .sum();
                (point.u, point.weight, f)
            })
            .collect();
        PressureProfile {
            panels: self.panels.clone(),
            unit_nodes: self.unit.0.clone(),
            barycentric: self.barycentric.clone(),
            values: values.to_vec(),
            points,
        }
    }

    /// The 2q-point Gauss rule on [0, 1].
    pub(crate) fn fine_rule(&self) -> &(Vec<f64>, Vec<f64>) {
        &self.fine
    }

    fn part(&self, panel: usize, a: f64, b: f64, rule: &(Vec<f64>, Vec<f64>)) -> LocalPart {
        let q = self.order;
        let nodes: Vec<f64> = rule.0.iter().map(|x| a + (b - a) * x).collect();
        let weights = rule.1.iter().map(|w| (b - a) * w).collect();
        let mut lagrange = vec![0.0; nodes.len() * q];
        for (s, row) in nodes.iter().zip(lagrange.chunks_exact_mut(q)) {
            self.lagrange(panel, *s, row);
        }
        LocalPart {
            panel,
            a,
            b,
            nodes,
            weights,
            lagrange,
        }
    }
}

/// Barycentric weights 1/Π_{m≠l}(x_l − x_m).
fn barycentric_weights(nodes: &[f64]) -> Vec<f64> {
    (0..nodes.len())
        .map(|l| {
            1.0 / (0..nodes.len())
                .filter(|&m| m != l)
                .map(|m| nodes[l] - nodes[m])
                .product::<f64>()
        })
        .collect()
}

/// D\[i\]\[l\] = L_l′(x_i) from the barycentric weights (Berrut & Trefethen,
/// SIAM Rev. 46 (2004), §9), the diagonal from Σ_l L_l′ = 0.
fn differentiation_matrix(nodes: &[f64], weights: &[f64]) -> Vec<f64> {
    let q = nodes.len();
    let mut d = vec![0.0; q * q];
    for i in 0..q {
        let mut diagonal = 0.0;
        for l in (0..q).filter(|&l| l != i) {
            let value = (weights[l] / weights[i]) / (nodes[i] - nodes[l]);
            d[i * q + l] = value;
            diagonal -= value;
        }
        d[i * q + i] = diagonal;
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// The weighted integrals are exact for the Chebyshev moments
    /// ∫ T_m dt/√(1 − t²) = π δ_{m0} of smooth functions, and resolve a
    /// layer e^{−κu} (∫ = π e^{−κ} I_0(κ), here against the series of I_0).
    #[test]
    fn weighted_integrals_are_accurate() {
        let mesh = GradedMesh::new(8, 1e-9, 2.5, 0.5);
        let ones = vec![1.0; mesh.nodes().len()];
        for m in 0..6 {
            let row = mesh.functional(|u| {
                let t: f64 = 1.0 - u;
                (m as f64 * t.acos()).cos()
            });
            let got: f64 = row.iter().zip(&ones).map(|(a, b)| a * b).sum();
            let want = if m == 0 { PI } else { 0.0 };
            assert!((got - want).abs() < 1e-13, "m = {m}: {got}");
        }
        // e^{−κ} I_0(κ) ≈ (1 + 1/(8κ) + 9/(128κ²)) / √(2πκ) at κ = 1e8.
        let kappa = 1e8;
        let layer: Vec<f64> = mesh.nodes().iter().map(|u| (-kappa * u).exp()).collect();
        let row = mesh.functional(|_| 1.0);
        let got: f64 = row.iter().zip(&layer).map(|(a, b)| a * b).sum();
        let want = PI * (1.0 + 1.0 / (8.0 * kappa) + 9.0 / (128.0 * kappa * kappa))
            / (2.0 * PI * kappa).sqrt();
        assert!((got / want - 1.0).abs() < 1e-10, "{got} vs {want}");
    }

    /// F = T_1(t) = 1 − u continues outside as r = s − √(s² − 1), also where
    /// x is far below the first panel.
    #[test]
    fn outer_continuation_of_t1() {
        let mesh = GradedMesh::new(8, 1e-6, 2.5, 0.5);
        let f: Vec<f64> = mesh.nodes().iter().map(|u| 1.0 - u).collect();
        for x in [1e-12, 1e-8, 1e-6, 1e-3, 0.5, 10.0, 1e6] {
            let row = mesh.outer_row(x);
            let got: f64 = row.iter().zip(&f).map(|(a, b)| a * b).sum();
            // r = s − √(s² − 1) = 1/(s + √(s² − 1)) without cancellation.
            let want = 1.0 / (1.0 + x + (x * (x + 2.0)).sqrt());
            assert!((got - want).abs() < 1e-12, "x = {x}: {got} vs {want}");
        }
    }
}
