//! The rolling cylinder where the pressure's edge layers are too thin for
//! the Chebyshev series: collocation of the Hilbert transform of the
//! pressure on a mesh graded toward the leading edge (see the module
//! documentation of [`super`], "Thin edge layers", for the equations).
//!
//! Unknowns: F at the mesh nodes u_i (u = 1 − t, [`GradedMesh`]) and the
//! tilt c0. Rows: at each node
//!
//!   J0 F(u_i) + Σ_j c_j \[V_j F(u_i) + e^{−β_j u_i} O_j\[F\]\] + c0 = (c + b t_i)/(2bR),
//!
//! and the consistency row ∫ F dt/√(1 − t²) = 0 (no T_0 part: the pressure
//! is bounded at both edges). The memory of term j, β_j = b/(vλ_j),
//!
//!   V_j F(u_i) = β_j ∫_0^{u_i} e^{−β_j (u_i − s)} F(s) ds,
//!
//! is stepped from node to node, V(u_i) = e^{−βΔ} V(u_{i−1}) + β ∫ over
//! [u_{i−1}, u_i], each part on Gauss nodes (graded at the exponential's
//! scale 1/β where it falls by more than e^{−2} across the part). Where a
//! whole panel lies CUT/β or more from its own lower end, the exponential
//! sees only that panel's polynomial P and integration by parts ends:
//!
//!   V_j F(u_i) = Σ_{k<q} (−1/β_j)^k P^{(k)}(u_i)   (exact for P),
//!
//! so all such terms of a panel share one sum Σ_k G_k D^k, G_k = Σ_j c_j
//! (−1/β_j)^k, D the panel's differentiation matrix: a 200-term Prony
//! series costs little more than one term where most memories are short.
//! The outer part O_j\[F\] = β_j ∫_0^∞ e^{−β_j x} F_out(1 + x) dx uses the
//! continuation [`GradedMesh::outer_row`] on nodes in w = √x, doubling
//! panels from 0.3√h0 to √(2 CUT/β_min), shared by all terms.
//!
//! At fixed b the system is linear in the centre c (it enters the
//! right-hand side only): two solves give the c with c0 = 0, and the
//! half-width follows from the load, (π/2) b² α_0 = f_N, by the secant
//! method on ln b.
//!
//! # References
//! - S.C. Hunter, J. Appl. Mech. 28 (1961) 611–617 (the memory of the
//!   rolling contact).
//! - H. Brunner, *Collocation Methods for Volterra Integral and Related
//!   Functional Equations*, Cambridge 2004, ch. 2 (piecewise polynomial
//!   collocation of second-kind Volterra equations).

use std::f64::consts::PI;

use super::creep::CreepCompliance;
use super::cylinder_mesh::{GradedMesh, LocalPart};
use super::cylinder_pressure::PressureProfile;
use super::solver::Factors;
use crate::error::ModelError;

/// Exponentials are cut below e^{−CUT}.
const CUT: f64 = 40.0;

/// The first panel is this fraction of the thinnest layer v τ_min/b wide.
const FIRST_PANEL: f64 = 0.1;

/// Each panel is this many times wider than the previous one …
const GROWTH: f64 = 2.5;

/// … up to this width in u (of 2).
const WIDEST: f64 = 0.5;

/// Gauss nodes per doubling of w = √x outside the contact.
const OUTSIDE_NODES: usize = 10;

/// Secant iterations on ln b before giving up.
const MAX_ITERATIONS: usize = 40;

/// The smallest half-width, relative to the one the contact is set up
/// for, whose longest memory the outside nodes still cover.
const SMALLEST_HALF_WIDTH: f64 = 0.125;

/// The contact at one speed on one graded mesh.
pub(crate) struct GradedContact<'a> {
    compliance: &'a CreepCompliance,
    speed: f64,
    radius: f64,
    load: f64,
    mesh: GradedMesh,
    /// (w, weight) of the outer integrals, x = w².
    outside: Vec<(f64, f64)>,
    /// F_out(1 + w_s²) as rows on the nodal values, [s·M + i].
    outer_rows: Vec<f64>,
    /// ∫ F T_m dt/√(1 − t²) rows: (1/π)·(m = 0), (2/π)·(m = 1, 2).
    moments: [Vec<f64>; 3],
    /// Powers of the panels' differentiation matrix on [0, 1], [k][i·q + l].
    derivative_powers: Vec<Vec<f64>>,
    /// The half-width the contact was set up for, m.
    setup_half_width: f64,
}

/// The graded solution at one speed.
pub(crate) struct GradedSolution {
    /// Contact centre c, m.
    pub(crate) center: f64,
    /// Contact half-width b, m.
    pub(crate) half_width: f64,
    /// Chebyshev coefficients α_n of the pressure (as in
    /// [`super::RollingSolution`]); α_0 and α_1 those of the load and the
    /// centroid, on the mesh's weighted points.
    pub(crate) alpha: Vec<f64>,
    /// F on the mesh, for the pressure.
    pub(crate) profile: PressureProfile,
    /// Secant iterations.
    pub(crate) iterations: usize,
    /// Mesh nodes.
    pub(crate) nodes: usize,
}

/// F at the nodes and the edges for one half-width.
struct Evaluation {
    center: f64,
    values: Vec<f64>,
    log_load_ratio: f64,
}

impl<'a> GradedContact<'a> {
    /// The contact at speed `v` (m/s) with `order` nodes per panel, the mesh
    /// set up for half-widths near `half_width` (m) and the shortest
    /// relaxation time `shortest_relaxation` (s) of the solid.
    pub(crate) fn new(
        compliance: &'a CreepCompliance,
        shortest_relaxation: f64,
        speed: f64,
        radius: f64,
        load: f64,
        half_width: f64,
        order: usize,
    ) -> Self {
        let layer = speed * shortest_relaxation / half_width;
        let mesh = GradedMesh::new(order, FIRST_PANEL * layer, GROWTH, WIDEST);
        // The half-width may fall during the iteration: the outside nodes
        // reach the longest memory down to an eighth of this b (below it
        // `evaluate` refuses).
        let longest = compliance
            .retardation_times
            .iter()
            .copied()
            .fold(0.0, f64::max);
        let beta_min = SMALLEST_HALF_WIDTH * half_width / (speed * longest);
        let outside = outside_nodes(mesh.panels()[0].1, beta_min);
        let m = mesh.nodes().len();
        let mut outer_rows = Vec::with_capacity(outside.len() * m);
        for &(w, _) in &outside {
            outer_rows.extend(mesh.outer_row(w * w));
        }
        let moments = [
            mesh.functional(|_| 1.0 / PI),
            mesh.functional(|u| 2.0 / PI * (1.0 - u)),
            mesh.functional(|u| 2.0 / PI * (2.0 * (1.0 - u) * (1.0 - u) - 1.0)),
        ];
        let derivative_powers = powers(mesh.derivative(), order);
        GradedContact {
            compliance,
            speed,
            radius,
            load,
            mesh,
            outside,
            outer_rows,
            moments,
            derivative_powers,
            setup_half_width: half_width,
        }
    }

    /// Solves for the edges from `half_width` (m), the secant's second
    /// point `step` further in ln b; `terms` Chebyshev coefficients of the
    /// pressure are returned.
    pub(crate) fn solve(
        &self,
        half_width: f64,
        step: f64,
        tolerance: f64,
        terms: usize,
    ) -> Result<GradedSolution, ModelError> {
        let (mut x0, mut x1) = (half_width.ln(), half_width.ln() + step);
        let mut f0 = self.evaluate(x0.exp())?.log_load_ratio;
        let mut last = self.evaluate(x1.exp())?;
        for iteration in 1..=MAX_ITERATIONS {
            let f1 = last.log_load_ratio;
            let slope = (f1 - f0) / (x1 - x0);
            // ln(load) rises like 2 ln b: a step beyond ±0.5 is a wild
            // secant, not the root.
            let dx = (-f1 / slope).clamp(-0.5, 0.5);
            if !dx.is_finite() {
                break;
            }
            (x0, f0) = (x1, f1);
            x1 += dx;
            last = self.evaluate(x1.exp())?;
            if dx.abs() <= tolerance {
                let profile = self.mesh.pressure_profile(&last.values);
                let mut alpha = profile.chebyshev_coefficients(terms.max(2), self.mesh.fine_rule());
                for (a, moment) in alpha.iter_mut().zip(&self.moments[1..]) {
                    *a = moment.iter().zip(&last.values).map(|(r, f)| r * f).sum();
                }
                return Ok(GradedSolution {
                    center: last.center,
                    half_width: x1.exp(),
                    alpha,
                    profile,
                    iterations: iteration,
                    nodes: self.mesh.nodes().len(),
                });
            }
        }
        Err(ModelError::ExactEdgesNotConverged { speed: self.speed })
    }

    /// F and the centre with c0 = 0 at half-width b, and ln(load/f_N).
    fn evaluate(&self, b: f64) -> Result<Evaluation, ModelError> {
        if !(b >= SMALLEST_HALF_WIDTH * self.setup_half_width && b.is_finite()) {
            // The outer integrals would miss the longest memory.
            return Err(ModelError::ExactEdgesNotConverged { speed: self.speed });
        }
        let m = self.mesh.nodes().len();
        let factors = Factors::new(self.matrix(b), m + 1)
            .ok_or(ModelError::ExactSingularSystem { speed: self.speed })?;
        let mut unit = vec![1.0; m + 1];
        unit[m] = 0.0;
        let mut slope: Vec<f64> = self.mesh.nodes().iter().map(|u| 1.0 - u).collect();
        slope.push(0.0);
        let (y1, yt) = (factors.solve(unit), factors.solve(slope));
        // Right-hand side g0 + g1 t, g0 = c/(2bR), g1 = 1/(2R): c0 = 0 fixes g0.
        let g1 = 1.0 / (2.0 * self.radius);
        let g0 = -g1 * yt[m] / y1[m];
        let values: Vec<f64> = y1[..m]
            .iter()
            .zip(&yt[..m])
            .map(|(a, b)| g0 * a + g1 * b)
            .collect();
        let alpha0: f64 = self.moments[1]
            .iter()
            .zip(&values)
            .map(|(r, f)| r * f)
            .sum();
        let load = 0.5 * PI * b * b * alpha0;
        if !(load > 0.0 && load.is_finite()) {
            return Err(ModelError::ExactSingularSystem { speed: self.speed });
        }
        Ok(Evaluation {
            center: 2.0 * b * self.radius * g0,
            values,
            log_load_ratio: (load / self.load).ln(),
        })
    }

    /// The (M + 1)² matrix at half-width b: rows at the nodes and the
    /// consistency row; columns the nodal values and the tilt.
    fn matrix(&self, b: f64) -> Vec<f64> {
        let m = self.mesh.nodes().len();
        let n = m + 1;
        let mut a = vec![0.0; n * n];
        for i in 0..m {
            a[i * n + i] = self.compliance.instantaneous;
            a[i * n + m] = 1.0;
        }
        a[m * n..m * n + m].copy_from_slice(&self.moments[0]);
        let q = self.mesh.order();
        let panels = self.mesh.panels().len();
        // Σ_j c_j (−1/β_j)^k of the terms that turn short at each panel.
        let mut short_from = vec![0.0; panels * q];
        let mut state = vec![0.0; m];
        for (&c, &lambda) in self
            .compliance
            .strengths
            .iter()
            .zip(&self.compliance.retardation_times)
        {
            let beta = b / (self.speed * lambda);
            if let Some(p) = self.step_memory(c, beta, &mut state, &mut a) {
                let mut w = c;
                for g in &mut short_from[p * q..(p + 1) * q] {
                    *g += w;
                    w *= -1.0 / beta;
                }
            }
            self.add_outer(c, beta, &mut a);
        }
        self.add_short_memory(&short_from, &mut a);
        a
    }

    /// Adds c·V F of one term at the nodes, stepping from the leading edge
    /// until the first panel where the memory is short; returns that panel.
    fn step_memory(&self, c: f64, beta: f64, state: &mut [f64], a: &mut [f64]) -> Option<usize> {
        let mesh = &self.mesh;
        let (q, n) = (mesh.order(), mesh.nodes().len() + 1);
        let nodes = mesh.nodes();
        state.fill(0.0);
        // Columns before `live` have decayed below e^{−2 CUT}.
        let mut live = 0;
        let mut local = vec![0.0; q];
        for (p, &(lo, _)) in mesh.panels().iter().enumerate() {
            if beta * (nodes[p * q] - lo) >= CUT {
                return Some(p);
            }
            let top = (p + 1) * q;
            for i in p * q..top {
                let previous = if i == 0 { 0.0 } else { nodes[i - 1] };
                let decay = (-beta * (nodes[i] - previous)).exp();
                state[live..top].iter_mut().for_each(|s| *s *= decay);
                while live < p * q && beta * (nodes[i] - mesh.panels()[live / q].1) > 2.0 * CUT {
                    state[live..live + q].fill(0.0);
                    live += q;
                }
                for part in mesh.local_parts_of(i) {
                    self.local_integral(beta, nodes[i], part, &mut local);
                    let cols = &mut state[part.panel * q..(part.panel + 1) * q];
                    cols.iter_mut().zip(&local).for_each(|(s, l)| *s += l);
                }
                let row = &mut a[i * n + live..i * n + top];
                row.iter_mut()
                    .zip(&state[live..top])
                    .for_each(|(r, s)| *r += c * s);
            }
        }
        None
    }

    /// β ∫_a^b e^{−β(u − s)} L_l(s) ds of the part's panel basis into `out`.
    fn local_integral(&self, beta: f64, u: f64, part: &LocalPart, out: &mut [f64]) {
        out.fill(0.0);
        let q = self.mesh.order();
        if beta * (part.b - part.a) <= 2.0 {
            for ((s, w), basis) in part
                .nodes
                .iter()
                .zip(&part.weights)
                .zip(part.lagrange.chunks_exact(q))
            {
                let weight = beta * w * (-beta * (u - s)).exp();
                out.iter_mut()
                    .zip(basis)
                    .for_each(|(o, l)| *o += weight * l);
            }
            return;
        }
        // Graded at the scale 1/β below b; nothing below b − CUT/β.
        let start = part.a.max(part.b - CUT / beta);
        let mut breaks = vec![part.b, start];
        breaks.extend(
            [0.5, 2.0, 6.0, 15.0]
                .iter()
                .map(|d| part.b - d / beta)
                .filter(|&s| s > start),
        );
        breaks.sort_by(f64::total_cmp);
        let rule = self.mesh.unit_rule();
        let mut basis = vec![0.0; q];
        for pair in breaks.windows(2) {
            let (lo, hi) = (pair[0], pair[1]);
            for (x, w) in rule.0.iter().zip(&rule.1) {
                let s = lo + (hi - lo) * x;
                let weight = beta * (hi - lo) * w * (-beta * (u - s)).exp();
                self.mesh.lagrange(part.panel, s, &mut basis);
                out.iter_mut()
                    .zip(&basis)
                    .for_each(|(o, l)| *o += weight * l);
            }
        }
    }

    /// The short memories: Σ_k G_k D^k on each panel's own block, G the
    /// sums of the terms short from that panel on.
    fn add_short_memory(&self, short_from: &[f64], a: &mut [f64]) {
        let q = self.mesh.order();
        let n = self.mesh.nodes().len() + 1;
        let mut sums = vec![0.0; q];
        for (p, &(lo, hi)) in self.mesh.panels().iter().enumerate() {
            sums.iter_mut()
                .zip(&short_from[p * q..(p + 1) * q])
                .for_each(|(s, g)| *s += g);
            let mut scale = 1.0;
            for (k, power) in self.derivative_powers.iter().enumerate() {
                let g = sums[k] * scale;
                scale /= hi - lo;
                if g == 0.0 {
                    continue;
                }
                for i in 0..q {
                    let row = &mut a[(p * q + i) * n + p * q..(p * q + i) * n + (p + 1) * q];
                    row.iter_mut()
                        .zip(&power[i * q..(i + 1) * q])
                        .for_each(|(r, d)| *r += g * d);
                }
            }
        }
    }

    /// c e^{−β u_i} O\[F\] at the nodes, O\[F\] = Σ_s 2β w_s e^{−β w_s²} W_s F_out(1 + w_s²).
    fn add_outer(&self, c: f64, beta: f64, a: &mut [f64]) {
        let nodes = self.mesh.nodes();
        let (m, n) = (nodes.len(), nodes.len() + 1);
        if beta * nodes[0] > 2.0 * CUT {
            return;
        }
        let mut outer = vec![0.0; m];
        for (&(w, weight), row) in self.outside.iter().zip(self.outer_rows.chunks_exact(m)) {
            let exponent = beta * w * w;
            if exponent > 2.0 * CUT {
                break;
            }
            let factor = 2.0 * beta * w * (-exponent).exp() * weight;
            outer
                .iter_mut()
                .zip(row)
                .for_each(|(o, r)| *o += factor * r);
        }
        for (i, &u) in nodes.iter().enumerate() {
            if beta * u > 2.0 * CUT {
                break;
            }
            let factor = c * (-beta * u).exp();
            a[i * n..i * n + m]
                .iter_mut()
                .zip(&outer)
                .for_each(|(r, o)| *r += factor * o);
        }
    }
}

/// Gauss nodes (w, weight) on [0, w0] and on doubling panels up to
/// √(2 CUT/β_min), w0 = 0.3 √h0 (h0 the first panel: F_out ∝ √x there).
fn outside_nodes(first_panel: f64, beta_min: f64) -> Vec<(f64, f64)> {
    let rule = crate::kernel::quadrature::gauss_legendre_unit(OUTSIDE_NODES);
    let mut edges = vec![0.0, 0.3 * first_panel.sqrt()];
    let end = (2.0 * CUT / beta_min).sqrt();
    while edges[edges.len() - 1] < end {
        edges.push(2.0 * edges[edges.len() - 1]);
    }
    let mut nodes = Vec::with_capacity(OUTSIDE_NODES * edges.len());
    for pair in edges.windows(2) {
        let (lo, hi) = (pair[0], pair[1]);
        for (x, w) in rule.0.iter().zip(&rule.1) {
            nodes.push((lo + (hi - lo) * x, (hi - lo) * w));
        }
    }
    nodes
}

/// D^k, k < q, of a q × q matrix D (row-major).
fn powers(d: &[f64], q: usize) -> Vec<Vec<f64>> {
    let mut out = Vec::with_capacity(q);
    let mut current = vec![0.0; q * q];
    for i in 0..q {
        current[i * q + i] = 1.0;
    }
    for _ in 0..q {
        let mut next = vec![0.0; q * q];
        for i in 0..q {
            for r in 0..q {
                let dir = d[i * q + r];
                for l in 0..q {
                    next[i * q + l] += dir * current[r * q + l];
                }
            }
        }
        out.push(current);
        current = next;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One retardation term (c = 1, λ s) and no instantaneous part.
    fn one_term(lambda: f64) -> CreepCompliance {
        CreepCompliance {
            instantaneous: 0.0,
            strengths: vec![1.0],
            retardation_times: vec![lambda],
        }
    }

    /// The memory part of the matrix at half-width b/v = 1 s: Σ_j c_j V_j
    /// F at the nodes for one term of memory β.
    fn memory_applied(contact: &GradedContact, beta: f64, f: &[f64]) -> Vec<f64> {
        let m = f.len();
        let n = m + 1;
        let q = contact.mesh.order();
        let mut a = vec![0.0; n * n];
        let mut short_from = vec![0.0; contact.mesh.panels().len() * q];
        let mut state = vec![0.0; m];
        if let Some(p) = contact.step_memory(1.0, beta, &mut state, &mut a) {
            let mut w = 1.0;
            for g in &mut short_from[p * q..(p + 1) * q] {
                *g += w;
                w *= -1.0 / beta;
            }
        }
        contact.add_short_memory(&short_from, &mut a);
        (0..m)
            .map(|i| a[i * n..i * n + m].iter().zip(f).map(|(x, y)| x * y).sum())
            .collect()
    }

    /// The memory part of the matrix for memories from long (β = 0.3:
    /// stepped on plain Gauss nodes) through the graded local integrals to
    /// short (β = 1e9: the derivative series from the first panels on):
    /// exact for a polynomial, V[u²](u) = u² − 2u/β + 2(1 − e^{−βu})/β²
    /// (measured ≤ 4e-15), and for a layer F = e^{−κu}, V F = β/(β − κ)
    /// (e^{−κu} − e^{−βu}), to the accuracy of its interpolant (measured
    /// ≤ 3.5e-9 with 12 nodes per panel, the same with 8 to ~1e-7).
    #[test]
    fn memory_matches_closed_forms() {
        let compliance = one_term(1.0);
        // Layer 1e-6 wide at b/v = 1 s: κ = 1e6.
        let contact = GradedContact::new(&compliance, 1e-6, 1.0, 0.01, 100.0, 1.0, 12);
        let nodes = contact.mesh.nodes().to_vec();
        let kappa = 1e6;
        let square: Vec<f64> = nodes.iter().map(|u| u * u).collect();
        let layer: Vec<f64> = nodes.iter().map(|u| (-kappa * u).exp()).collect();
        for beta in [0.3, 30.0, 3e4, 3e7, 1e9] {
            let (mut polynomial, mut exponential) = (0.0f64, 0.0f64);
            let applied = memory_applied(&contact, beta, &square);
            for (&u, got) in nodes.iter().zip(applied) {
                let want = u * u - 2.0 * u / beta - 2.0 * (-beta * u).exp_m1() / (beta * beta);
                polynomial = polynomial.max((got - want).abs());
            }
            let applied = memory_applied(&contact, beta, &layer);
            for (&u, got) in nodes.iter().zip(applied) {
                let want = beta / (beta - kappa) * ((-kappa * u).exp() - (-beta * u).exp());
                exponential = exponential.max((got - want).abs());
            }
            println!("β = {beta:e}: polynomial {polynomial:.1e}, layer {exponential:.1e}");
            assert!(polynomial < 1e-13, "β = {beta}: {polynomial:e}");
            assert!(exponential < 1e-8, "β = {beta}: {exponential:e}");
        }
    }

    /// The outer memory of F = T_1(t) = 1 − u, whose continuation is
    /// s − √(s² − 1): O(β) = β ∫ e^{−βx} (1 + x − √(x(x + 2))) dx, against
    /// the trapezoid rule in w = √x on a fine grid. Measured ≤ 1e-12.
    #[test]
    fn outer_memory_of_t1() {
        // λ = 1e4 s: the outside nodes reach β = 1e-4/8.
        let compliance = one_term(1e4);
        let contact = GradedContact::new(&compliance, 1e-4, 1.0, 0.01, 100.0, 1.0, 8);
        let nodes = contact.mesh.nodes().to_vec();
        let (m, n) = (nodes.len(), nodes.len() + 1);
        let t1: Vec<f64> = nodes.iter().map(|u| 1.0 - u).collect();
        for beta in [1e-3, 1.0, 1e3, 1e5] {
            let mut a = vec![0.0; n * n];
            contact.add_outer(1.0, beta, &mut a);
            // Row 0: e^{−β u_0} O.
            let got: f64 =
                a[..m].iter().zip(&t1).map(|(x, f)| x * f).sum::<f64>() / (-beta * nodes[0]).exp();
            let end = (60.0 / beta).sqrt();
            let steps = 400_000;
            let h = end / steps as f64;
            // Trapezoid plus its end correction h² f′(0)/12, f′(0) = 2β.
            let want: f64 = (1..steps)
                .map(|k| {
                    let w = k as f64 * h;
                    let x = w * w;
                    let r = 1.0 / (1.0 + x + (x * (x + 2.0)).sqrt());
                    2.0 * beta * w * (-beta * x).exp() * r * h
                })
                .sum::<f64>()
                + h * h * 2.0 * beta / 12.0;
            assert!(
                (got - want).abs() < 1e-9 * want.abs().max(1e-3),
                "β = {beta}: {got} vs {want}"
            );
        }
    }
}
