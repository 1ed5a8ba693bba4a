//! The viscoelastic memory part of the influence function, applied to the
//! Chebyshev basis of the contact pressure.
//!
//! With the contact interval x = c + b t (t ∈ [−1, 1]) and the pressure
//! p = b √(1 − t²) Σ_n α_n U_n(t), the elastic surface slope is set by
//! H(x) = PV∫ p(s) ds/(x − s) = bπ Σ_n α_n h_n(t), where
//!
//!   h_n(t) = T_{n+1}(t)                      for |t| ≤ 1,
//!   h_n(t) = (t − sgn t √(t² − 1))^{n+1}      for |t| > 1
//!
//! (Erdogan & Gupta 1972; Johnson, *Contact Mechanics*, §2.7). One
//! exponential of the creep compliance, J(t) ∋ c (1 − e^{−t/λ}), adds the
//! memory term c·(1/ℓ)∫_0^∞ e^{−ξ/ℓ} H(x + ξ) dξ with ℓ = vλ (the material
//! point now at x was at x + ξ a time ξ/v ago). In t, with β = b/ℓ, each
//! basis function contributes
//!
//!   M_n(t_k; β) = β ∫_{t_k}^∞ e^{−β(t − t_k)} h_n(t) dt = I_n + e^{−β(1 − t_k)} O_n,
//!
//!   I_n = β ∫_0^{φ_k} e^{−β(cos φ − t_k)} cos((n+1)φ) sin φ dφ   (t = cos φ, t_k = cos φ_k),
//!   O_n = β ∫_0^∞ e^{−β(cosh θ − 1)} e^{−(n+1)θ} sinh θ dθ        (t = cosh θ).
//!
//! Both integrands are smooth (the substitutions remove the √ edge of h_n
//! and the Chebyshev oscillation becomes trigonometric); they are
//! integrated by Gauss–Legendre on panels that follow the exponential's
//! scale 1/β and limit the panel length, so the same rule serves β ≪ 1
//! (high speed, the memory term is small) and β ≫ 1 (low speed, M_n → h_n).
//! The exponential is cut where it falls below e^{−40}.
//!
//! # The collocation matrix for many retardation times
//!
//! The matrix needs Σ_j c_j M_n(t_k; β_j) for all N + 1 collocation points
//! and N basis functions. Integrating each exponential at each point costs
//! O(J N² K) for J retardation times and K ≈ 150 nodes per point, and a
//! speed needs about 11 matrices (Newton's method on the edges): 15 to 30 s
//! per speed for a 200-term Prony series at N = 128.
//! [`CollocationGrid::memory_matrix`] instead splits the exponentials by β
//! (N fixed):
//!
//! - β ≥ β_F = N²/16 (memory short against the contact's resolution):
//!   integrating by parts until the polynomial T_{n+1} is exhausted gives
//!   exactly
//!
//!     I_n = Σ_{p ≤ n+1} [T_{n+1}^{(p)}(t_k) − e^{−β(1 − t_k)} T_{n+1}^{(p)}(1)] / β^p,
//!
//!   so Σ_j c_j M_n = Σ_p g_p T_{n+1}^{(p)}(t_k) + Σ_j c_j e^{−β_j(1 − t_k)} [O_n(β_j) − S_n(β_j)]
//!   with g_p = Σ_j c_j β_j^{−p} and S_n(β) = Σ_p T_{n+1}^{(p)}(1)/β^p; the
//!   second sum matters only at the few points within 40/β_j of the leading
//!   edge. The derivatives follow T_{q+1}^{(p)} = 2t T_q^{(p)} +
//!   2p T_q^{(p−1)} − T_{q−1}^{(p)}. Since |T_{n+1}^{(p)}| ≤ T_{n+1}^{(p)}(1) =
//!   Π_{i<p} ((n+1)² − i²)/(2i + 1), the terms are below 16^p/(2p − 1)!!
//!   (largest ≈ 2e3: three digits lost to cancellation at most), and the
//!   series is cut where the bound falls below 1e-18.
//! - β ≤ 2 (memory long against the contact): the exponential's Taylor
//!   series,
//!
//!     I_n = Σ_p (−1)^p β^{p+1}/p! F_n^{(p)}(t_k),   F_n^{(p)}(t_k) = ∫_{t_k}^1 (t − t_k)^p T_{n+1}(t) dt,
//!
//!   with terms below (2β)^{p+1}/(p + 1)! ≤ 11, so again only the weights
//!   Σ_j c_j (−1)^p β_j^{p+1}/p! depend on the terms. The moments follow
//!   from ∫_t^1 T_q = ½ [(1 − T_{q+1}(t))/(q + 1) − (1 − T_{q−1}(t))/(q − 1)]
//!   and (t − t_k) T_q = ½ (T_{q+1} + T_{|q−1|}) − t_k T_q.
//! - 2 < β < β_F: point by point from the leading edge,
//!
//!     M_n(t_k) = β ∫_{t_k}^{t_{k−1}} e^{−β(t − t_k)} T_{n+1}(t) dt + e^{−β(t_{k−1} − t_k)} M_n(t_{k−1}),
//!
//!   with t_{−1} = 1 and M_n(1) = O_n: each interval between neighbouring
//!   points (length π/(N + 1) in φ, so cos((n+1)φ) turns by less than π)
//!   is integrated once, on nodes shared by all exponentials that fall by
//!   less than e^{−Q} across it (Q = nodes per panel), otherwise on panels
//!   graded at the exponential's scale as above.
//!
//! A matrix then costs O(N² P) for the two series (P ≲ 50 orders), O(N)
//! per retardation time for the outer integrals and their factors (O(N²)
//! for those of the Taylor band), and O(N² Q) for each retardation time in
//! the middle band, which spans log10(N²/32) ≈ 2.7 decades of β at N = 128:
//! the 200-term series above takes about 0.2 s per speed.

use super::creep::CreepCompliance;
use crate::kernel::quadrature::gauss_legendre_unit;

/// Exponential cut-off: contributions below e^{−CUT} are dropped.
const CUT: f64 = 40.0;

/// Breakpoints in units of the exponential's scale 1/β.
const SCALE_BREAKS: [f64; 5] = [0.5, 2.0, 6.0, 15.0, CUT];

/// Exponentials with β ≤ TAYLOR_BETA use the Taylor series (cancellation
/// grows like e^{2β}).
const TAYLOR_BETA: f64 = 2.0;

/// Exponentials with β ≥ N²/SERIES_RATIO use the derivative series: its
/// terms stay below SERIES_RATIO^p/(2p − 1)!!.
const SERIES_RATIO: f64 = 16.0;

/// Both series are cut where the bound of their terms (per unit strength)
/// falls below this.
const SERIES_TOLERANCE: f64 = 1e-18;

/// acosh(1 + x) for x ≥ 0, accurate for small x.
fn acosh1p(x: f64) -> f64 {
    (x + (x * (2.0 + x)).sqrt()).ln_1p()
}

/// cos φ − cos φ_k for φ near φ_k without cancellation.
fn cos_difference(phi: f64, phi_k: f64) -> f64 {
    2.0 * (0.5 * (phi_k + phi)).sin() * (0.5 * (phi_k - phi)).sin()
}

/// Gauss–Legendre panels for the memory integrals.
#[derive(Debug, Clone)]
pub(crate) struct MemoryQuadrature {
    nodes: Vec<f64>,
    weights: Vec<f64>,
    max_panel: f64,
}

impl MemoryQuadrature {
    /// A rule with `order` nodes per panel and panels at most `max_panel`
    /// long (in φ or θ).
    pub(crate) fn new(order: usize, max_panel: f64) -> Self {
        let (nodes, weights) = gauss_legendre_unit(order);
        MemoryQuadrature {
            nodes,
            weights,
            max_panel,
        }
    }

    /// Calls `visit(start, length)` for the panels of the composite rule on
    /// the sorted breakpoints `breaks`, splitting long panels.
    fn for_each_panel<F: FnMut(f64, f64)>(&self, breaks: &[f64], mut visit: F) {
        for pair in breaks.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            if b <= a {
                continue;
            }
            let pieces = ((b - a) / self.max_panel).ceil().max(1.0) as usize;
            let h = (b - a) / pieces as f64;
            for p in 0..pieces {
                visit(a + p as f64 * h, h);
            }
        }
    }

    /// O_n(β), n = 0..out.len(), the part of the memory integral beyond the
    /// leading edge (without its factor e^{−β(1 − t_k)}).
    pub(crate) fn outer(&self, beta: f64, out: &mut [f64]) {
        out.iter_mut().for_each(|o| *o = 0.0);
        let theta_max = acosh1p(CUT / beta);
        let mut breaks = vec![0.0];
        for d in SCALE_BREAKS {
            breaks.push(acosh1p(d / beta).min(theta_max));
        }
        let mut g = 0.125;
        while g < theta_max {
            breaks.push(g);
            g *= 2.0;
        }
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        self.for_each_panel(&breaks, |lo, h| {
            for (x, w) in self.nodes.iter().zip(&self.weights) {
                let theta = lo + h * x;
                let sh = (0.5 * theta).sinh();
                let weight = h * w * beta * (-2.0 * beta * sh * sh).exp() * theta.sinh();
                let decay = (-theta).exp();
                // Beyond n + 1 = CUT/θ the node's e^{−(n+1)θ} is below e^{−CUT}:
                // at large θ (small β) that spares most of the loop.
                let count = (CUT / theta).ceil().min(out.len() as f64) as usize;
                let mut e = weight;
                for o in out[..count].iter_mut() {
                    e *= decay;
                    *o += e;
                }
            }
        });
    }

    /// β ∫_{t_lo}^{t_hi} e^{−β(t − t_lo)} T_{n+1}(t) dt, n = 0..out.len()
    /// (−1 < t_lo < t_hi ≤ 1), on panels graded at the scale 1/β and cut
    /// at CUT/β.
    pub(crate) fn local(
        &self,
        beta: f64,
        t_lo: f64,
        t_hi: f64,
        out: &mut [f64],
        sums: &mut CosineSums,
    ) {
        out.iter_mut().for_each(|o| *o = 0.0);
        let phi_lo = t_lo.acos();
        // Breakpoints in t, converted to φ = acos t (descending in t ↔ ascending φ).
        let mut breaks = [0.0; SCALE_BREAKS.len() + 1];
        breaks[0] = phi_lo;
        let mut count = 1;
        for d in SCALE_BREAKS {
            let t = t_lo + d / beta;
            breaks[count] = t.min(t_hi).acos();
            count += 1;
            if t >= t_hi {
                break;
            }
        }
        let breaks = &mut breaks[..count];
        breaks.sort_by(f64::total_cmp);
        let (mut phis, mut weights) = (Vec::new(), Vec::new());
        self.for_each_panel(breaks, |lo, h| {
            phis.clear();
            weights.clear();
            for (x, w) in self.nodes.iter().zip(&self.weights) {
                let phi = lo + h * x;
                phis.push(phi);
                weights
                    .push(h * w * beta * (-beta * cos_difference(phi, phi_lo)).exp() * phi.sin());
            }
            sums.tabulate(&phis, out.len());
            sums.accumulate(&weights, out);
        });
    }
}

/// The table cos((n+1)φ_q) of a panel's nodes, for sums
/// Σ_q W_q cos((n+1)φ_q) with several sets of weights.
#[derive(Debug, Default)]
pub(crate) struct CosineSums {
    /// cos((n+1)φ_q) at [q·N + n].
    table: Vec<f64>,
    terms: usize,
    current: Vec<f64>,
    previous: Vec<f64>,
    twice_cos: Vec<f64>,
}

impl CosineSums {
    /// Tabulates cos((n+1)φ_q) for n < `terms`. The three-term recurrence
    /// runs over all nodes at once: one node at a time it is a chain of
    /// dependent multiplications, the bottleneck of the per-node loop.
    fn tabulate(&mut self, phis: &[f64], terms: usize) {
        let g = phis.len();
        self.terms = terms;
        self.table.resize(g * terms, 0.0);
        self.current.clear();
        self.previous.clear();
        self.twice_cos.clear();
        for &phi in phis {
            let c = phi.cos();
            self.current.push(c);
            self.previous.push(1.0);
            self.twice_cos.push(2.0 * c);
        }
        for n in 0..terms {
            for q in 0..g {
                let cur = self.current[q];
                self.table[q * terms + n] = cur;
                self.current[q] = self.twice_cos[q] * cur - self.previous[q];
                self.previous[q] = cur;
            }
        }
    }

    /// `out[n] += Σ_q weights[q] cos((n+1)φ_q)` for the tabulated nodes.
    fn accumulate(&self, weights: &[f64], out: &mut [f64]) {
        for (&w, row) in weights.iter().zip(self.table.chunks_exact(self.terms)) {
            for (o, &c) in out.iter_mut().zip(row) {
                *o += w * c;
            }
        }
    }
}

/// The collocation points t_k = cos φ_k, φ_k = π(2k + 1)/(2N + 2), k ≤ N
/// (descending in t), of N Chebyshev terms, and the memory part of the
/// collocation matrix on them.
#[derive(Debug, Clone)]
pub(crate) struct CollocationGrid {
    terms: usize,
    angles: Vec<f64>,
    points: Vec<f64>,
}

impl CollocationGrid {
    /// The grid of `terms` Chebyshev terms (N + 1 points).
    pub(crate) fn new(terms: usize) -> Self {
        let m = terms + 1;
        let angles: Vec<f64> = (0..m)
            .map(|k| std::f64::consts::PI * (2 * k + 1) as f64 / (2 * m) as f64)
            .collect();
        let points = angles.iter().map(|a| a.cos()).collect();
        CollocationGrid {
            terms,
            angles,
            points,
        }
    }

    /// The collocation points t_k.
    pub(crate) fn points(&self) -> &[f64] {
        &self.points
    }

    /// Σ_j c_j M_n(t_k; β_j) at [k·N + n] for β_j = `scale`/λ_j (`scale` =
    /// b/v): the memory part of the collocation matrix, by the three
    /// methods of the module documentation.
    pub(crate) fn memory_matrix(
        &self,
        quadrature: &MemoryQuadrature,
        compliance: &CreepCompliance,
        scale: f64,
    ) -> Vec<f64> {
        let n = self.terms;
        let m = self.points.len();
        let mut a = vec![0.0; m * n];
        let series_beta = (n * n) as f64 / SERIES_RATIO;
        let (taylor, stepped, series) = memory_bands(compliance, scale, series_beta);
        let taylor_weights = self.taylor_weights(&taylor);
        let (series_weights, edge_series) = self.series_weights(&series, series_beta);
        let edge = self.edge_parts(quadrature, &taylor, &series, series_beta, &edge_series);
        // M_n of each middle-band term at the previous point, starting from
        // M_n(1) = O_n.
        let mut state = vec![0.0; stepped.len() * n];
        for (&(_, beta), s) in stepped.iter().zip(state.chunks_exact_mut(n)) {
            quadrature.outer(beta, s);
        }
        // Q Gauss nodes integrate e^{−Q x} cos(πx) over [0, 1] to about 1e-23
        // (the error term (Q/2)^{2Q} 2^{2Q+1} (Q!)^4/((2Q + 1) ((2Q)!)^3) at Q = 24).
        let shared_decay = quadrature.nodes.len() as f64;
        let mut sums = CosineSums::default();
        let mut graded = CosineSums::default();
        let mut local = vec![0.0; n];
        let (mut phis, mut shift, mut sine_weight, mut weights) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut scratch = SeriesScratch::default();
        for (k, row) in a.chunks_exact_mut(n).enumerate() {
            let t = self.points[k];
            if !series.is_empty() {
                scratch.add_derivatives(t, series_beta, &series_weights, row);
            }
            if !taylor.is_empty() {
                scratch.add_moments(t, &taylor_weights, row);
            }
            for (c, beta, x) in &edge {
                let decay = beta * (1.0 - t);
                if decay <= 2.0 * CUT {
                    let f = c * (-decay).exp();
                    row.iter_mut().zip(x).for_each(|(r, &xn)| *r += f * xn);
                }
            }
            if stepped.is_empty() {
                continue;
            }
            // The interval from t_k up to t_{k−1} (t_{−1} = 1).
            let (upper, phi_upper) = if k == 0 {
                (1.0, 0.0)
            } else {
                (self.points[k - 1], self.angles[k - 1])
            };
            let delta = upper - t;
            let mut tabulated = false;
            for (&(c, beta), s) in stepped.iter().zip(state.chunks_exact_mut(n)) {
                local.iter_mut().for_each(|l| *l = 0.0);
                if beta * delta <= shared_decay {
                    if !tabulated {
                        let h = self.angles[k] - phi_upper;
                        phis.clear();
                        shift.clear();
                        sine_weight.clear();
                        for (x, w) in quadrature.nodes.iter().zip(&quadrature.weights) {
                            let phi = phi_upper + h * x;
                            phis.push(phi);
                            shift.push(cos_difference(phi, self.angles[k]));
                            sine_weight.push(h * w * phi.sin());
                        }
                        sums.tabulate(&phis, n);
                        tabulated = true;
                    }
                    weights.clear();
                    weights.extend(
                        shift
                            .iter()
                            .zip(&sine_weight)
                            .map(|(&d, &w)| w * beta * (-beta * d).exp()),
                    );
                    sums.accumulate(&weights, &mut local);
                } else {
                    quadrature.local(beta, t, upper, &mut local, &mut graded);
                }
                let f = (-beta * delta).exp();
                for ((sn, &l), r) in s.iter_mut().zip(&local).zip(row.iter_mut()) {
                    *sn = l + f * *sn;
                    *r += c * *sn;
                }
            }
        }
        a
    }

    /// Per term of the Taylor and series bands: the part beyond the leading
    /// edge, (c, β, X_n), added as c e^{−β(1 − t_k)} X_n. The series terms'
    /// X_n have the series' own edge part removed.
    fn edge_parts(
        &self,
        quadrature: &MemoryQuadrature,
        taylor: &[(f64, f64)],
        series: &[(f64, f64)],
        series_beta: f64,
        edge_series: &[f64],
    ) -> Vec<(f64, f64, Vec<f64>)> {
        let n = self.terms;
        let mut edge: Vec<(f64, f64, Vec<f64>)> = Vec::new();
        for &(c, beta) in taylor {
            let mut outer = vec![0.0; n];
            quadrature.outer(beta, &mut outer);
            edge.push((c, beta, outer));
        }
        for &(c, beta) in series {
            // e^{−β(1 − t_0)} < e^{−2 CUT}: negligible even against the
            // series' largest terms.
            if beta * (1.0 - self.points[0]) > 2.0 * CUT {
                continue;
            }
            let mut x = vec![0.0; n];
            quadrature.outer(beta, &mut x);
            let ratio = series_beta / beta;
            let mut power = 1.0;
            for row in edge_series.chunks_exact(n) {
                for (xn, &d) in x.iter_mut().zip(row) {
                    *xn -= power * d;
                }
                power *= ratio;
            }
            edge.push((c, beta, x));
        }
        edge
    }

    /// The weights Σ_j c_j (−1)^p β_j^{p+1}/p! of the Taylor moments, up to
    /// the order where (2β)^{p+1}/(p + 1)! < SERIES_TOLERANCE.
    fn taylor_weights(&self, terms: &[(f64, f64)]) -> Vec<f64> {
        let largest = terms.iter().map(|t| t.1).fold(0.0, f64::max);
        let mut orders = 1;
        let mut bound = 2.0 * largest;
        while bound >= SERIES_TOLERANCE {
            orders += 1;
            bound *= 2.0 * largest / orders as f64;
        }
        let mut weights = vec![0.0; orders];
        for &(c, beta) in terms {
            let mut w = c * beta;
            for (p, wp) in weights.iter_mut().enumerate() {
                *wp += w;
                w *= -beta / (p + 1) as f64;
            }
        }
        weights
    }

    /// The weights Σ_j c_j (β_F/β_j)^p of the scaled derivatives
    /// T^{(p)}/β_F^p, up to the order where their bound (per unit
    /// strength) falls below SERIES_TOLERANCE or the series ends (p > N),
    /// and the scaled derivatives at t = 1 ([p·N + n], for S_n).
    fn series_weights(&self, terms: &[(f64, f64)], series_beta: f64) -> (Vec<f64>, Vec<f64>) {
        if terms.is_empty() {
            return (Vec::new(), Vec::new());
        }
        let smallest = terms.iter().map(|t| t.1).fold(f64::INFINITY, f64::min);
        let nn = (self.terms * self.terms) as f64;
        let mut orders = 1;
        let mut bound = 1.0;
        while orders <= self.terms && bound >= SERIES_TOLERANCE {
            let i = (orders - 1) as f64;
            bound *= (nn - i * i) / ((2.0 * i + 1.0) * smallest);
            orders += 1;
        }
        let mut weights = vec![0.0; orders];
        for &(c, beta) in terms {
            let ratio = series_beta / beta;
            let mut w = c;
            for wp in weights.iter_mut() {
                *wp += w;
                w *= ratio;
            }
        }
        let mut at_edge = vec![0.0; orders * self.terms];
        let mut scratch = SeriesScratch::default();
        for (p, row) in at_edge.chunks_exact_mut(self.terms).enumerate() {
            let mut unit = vec![0.0; orders];
            unit[p] = 1.0;
            scratch.add_derivatives(1.0, series_beta, &unit, row);
        }
        (weights, at_edge)
    }
}

/// Work arrays of the two series.
#[derive(Debug, Default)]
struct SeriesScratch {
    previous: Vec<f64>,
    current: Vec<f64>,
    next: Vec<f64>,
    chebyshev: Vec<f64>,
}

impl SeriesScratch {
    /// `row[n] += Σ_p weights[p] T_{n+1}^{(p)}(t)/β_F^p`. The scaling by β_F^p
    /// keeps the derivatives (up to N^{2p}/(2p − 1)!!) in range.
    fn add_derivatives(&mut self, t: f64, beta_f: f64, weights: &[f64], row: &mut [f64]) {
        let orders = weights.len();
        let (prev, cur, next) = (&mut self.previous, &mut self.current, &mut self.next);
        for v in [&mut *prev, &mut *cur, &mut *next] {
            v.clear();
            v.resize(orders, 0.0);
        }
        // T_0 and T_1 = t.
        prev[0] = 1.0;
        cur[0] = t;
        if orders > 1 {
            cur[1] = 1.0 / beta_f;
        }
        for r in row.iter_mut() {
            *r += cur.iter().zip(weights).map(|(d, w)| d * w).sum::<f64>();
            next[0] = 2.0 * t * cur[0] - prev[0];
            for p in 1..orders {
                next[p] = 2.0 * t * cur[p] + (2 * p) as f64 / beta_f * cur[p - 1] - prev[p];
            }
            std::mem::swap(prev, cur);
            std::mem::swap(cur, next);
        }
    }

    /// `row[n] += Σ_p weights[p] ∫_t^1 (s − t)^p T_{n+1}(s) ds`.
    fn add_moments(&mut self, t: f64, weights: &[f64], row: &mut [f64]) {
        let orders = weights.len();
        let n = row.len();
        // Moments of order p are needed for q ≤ N + (orders − 1 − p).
        let top = n + orders;
        let cheb = &mut self.chebyshev;
        cheb.clear();
        cheb.resize(top + 2, 0.0);
        cheb[0] = 1.0;
        cheb[1] = t;
        for q in 1..=top {
            cheb[q + 1] = 2.0 * t * cheb[q] - cheb[q - 1];
        }
        let (cur, next) = (&mut self.current, &mut self.next);
        cur.clear();
        cur.resize(top + 1, 0.0);
        next.clear();
        next.resize(top + 1, 0.0);
        cur[0] = 1.0 - t;
        cur[1] = 0.5 * (1.0 - t * t);
        for q in 2..=top {
            cur[q] =
                0.5 * ((1.0 - cheb[q + 1]) / (q + 1) as f64 - (1.0 - cheb[q - 1]) / (q - 1) as f64);
        }
        for (p, &w) in weights.iter().enumerate() {
            row.iter_mut()
                .zip(&cur[1..=n])
                .for_each(|(r, &f)| *r += w * f);
            if p + 1 == orders {
                break;
            }
            let limit = top - p - 1;
            next[0] = cur[1] - t * cur[0];
            for q in 1..=limit {
                next[q] = 0.5 * (cur[q + 1] + cur[q - 1]) - t * cur[q];
            }
            std::mem::swap(cur, next);
        }
    }
}

/// The memory matrix one exponential and one point at a time, on panels
/// graded at each exponential's scale over the whole of [t_k, 1]
/// (O(J N² Q)): the slow reference of the tests.
/// Above β = 1e9 those panels would be narrower than the resolution of t,
/// and the inner integral is h_n(t_k) + h_n′(t_k)/β (error O(N⁴/β²)).
/// (c_j, β_j) of the compliance terms of one memory band.
type MemoryTerms = Vec<(f64, f64)>;

/// The terms (c_j, β_j = `scale`/λ_j) of the compliance split by memory:
/// short (β ≤ TAYLOR_BETA: Taylor moments), middle (term by term) and long
/// (β ≥ `series_beta`: derivative series).
fn memory_bands(
    compliance: &CreepCompliance,
    scale: f64,
    series_beta: f64,
) -> (MemoryTerms, MemoryTerms, MemoryTerms) {
    let (mut taylor, mut stepped, mut series) = (Vec::new(), Vec::new(), Vec::new());
    for (&c, &lambda) in compliance
        .strengths
        .iter()
        .zip(&compliance.retardation_times)
    {
        let beta = scale / lambda;
        if beta <= TAYLOR_BETA {
            taylor.push((c, beta));
        } else if beta < series_beta {
            stepped.push((c, beta));
        } else {
            series.push((c, beta));
        }
    }
    (taylor, stepped, series)
}

#[cfg(test)]
pub(crate) fn memory_matrix_per_term(
    quadrature: &MemoryQuadrature,
    grid: &CollocationGrid,
    compliance: &CreepCompliance,
    scale: f64,
) -> Vec<f64> {
    let n = grid.terms;
    let mut a = vec![0.0; grid.points.len() * n];
    let (mut outer, mut inner) = (vec![0.0; n], vec![0.0; n]);
    let mut sums = CosineSums::default();
    for (&c, &lambda) in compliance
        .strengths
        .iter()
        .zip(&compliance.retardation_times)
    {
        let beta = scale / lambda;
        quadrature.outer(beta, &mut outer);
        for (row, &t) in a.chunks_exact_mut(n).zip(&grid.points) {
            per_term_inner(quadrature, beta, t, &mut inner, &mut sums);
            let e = (-beta * (1.0 - t)).exp();
            for (r, (i, o)) in row.iter_mut().zip(inner.iter().zip(&outer)) {
                *r += c * (i + e * o);
            }
        }
    }
    a
}

/// I_n(t_k; β) of one exponential (see [`memory_matrix_per_term`]).
#[cfg(test)]
fn per_term_inner(
    quadrature: &MemoryQuadrature,
    beta: f64,
    t_k: f64,
    out: &mut [f64],
    sums: &mut CosineSums,
) {
    if beta > 1e9 {
        // β∫e^{−βs} h(t_k + s) ds = h(t_k) + h′(t_k)/β + O(N⁴/β²), with
        // T′_{n+1} = (n+1) U_n.
        let (mut t_prev, mut t_cur) = (1.0, t_k);
        let (mut u_prev, mut u_cur) = (0.0, 1.0);
        for (n, o) in out.iter_mut().enumerate() {
            *o = t_cur + (n + 1) as f64 * u_cur / beta;
            let t_next = 2.0 * t_k * t_cur - t_prev;
            t_prev = t_cur;
            t_cur = t_next;
            let u_next = 2.0 * t_k * u_cur - u_prev;
            u_prev = u_cur;
            u_cur = u_next;
        }
    } else {
        quadrature.local(beta, t_k, 1.0, out, sums);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute-force M_n, n < count, by the midpoint rule in t (slow oracle).
    fn brute(beta: f64, t_k: f64, count: usize) -> Vec<f64> {
        let t_end = t_k + 45.0 / beta;
        let steps = 2_000_000;
        let dt = (t_end - t_k) / steps as f64;
        let mut sum = vec![0.0; count];
        for i in 0..steps {
            let t = t_k + (i as f64 + 0.5) * dt;
            let e = (-beta * (t - t_k)).exp();
            if t <= 1.0 {
                let phi = t.acos();
                for (n, s) in sum.iter_mut().enumerate() {
                    *s += e * ((n + 1) as f64 * phi).cos();
                }
            } else {
                let r = t - (t * t - 1.0).sqrt();
                let mut p = 1.0;
                for s in sum.iter_mut() {
                    p *= r;
                    *s += e * p;
                }
            }
        }
        sum.iter().map(|s| beta * s * dt).collect()
    }

    #[test]
    fn memory_integrals_match_brute_force() {
        let q = MemoryQuadrature::new(24, 0.5);
        let n = 8;
        for &beta in &[0.05, 1.0, 7.0, 200.0] {
            for &t_k in &[-0.9, 0.0, 0.7, 0.99] {
                let mut inner = vec![0.0; n];
                let mut outer = vec![0.0; n];
                per_term_inner(&q, beta, t_k, &mut inner, &mut CosineSums::default());
                q.outer(beta, &mut outer);
                let oracle = brute(beta, t_k, n);
                for k in 0..n {
                    let m = inner[k] + (-beta * (1.0 - t_k)).exp() * outer[k];
                    let b = oracle[k];
                    assert!(
                        (m - b).abs() < 2e-6 * (1.0 + b.abs()),
                        "β {beta} t {t_k} n {k}: {m} vs {b}"
                    );
                }
            }
        }
    }

    /// A compliance with `count` exponentials of strengths 1 … 2 whose β
    /// at `scale` = 1 run log-uniformly from 10^`lo` to 10^`hi`.
    fn spread(count: usize, lo: f64, hi: f64) -> CreepCompliance {
        let strengths = (0..count)
            .map(|j| 1.0 + (0.7 * j as f64).sin().abs())
            .collect();
        let retardation_times = (0..count)
            .map(|j| 10f64.powf(-(lo + (hi - lo) * j as f64 / (count - 1) as f64)))
            .collect();
        CreepCompliance {
            instantaneous: 1.0,
            strengths,
            retardation_times,
        }
    }

    /// The three methods of `memory_matrix` (Taylor series, stepping from
    /// the leading edge on shared and on graded nodes, derivative series)
    /// reproduce the per-term quadrature. The reference uses panels of 0.1
    /// (at 0.5 its error reaches 1e-6 for n ≈ 128:
    /// 64 radians of cos((n+1)φ) on 24 nodes). Measured: ≤ 9.3e-13 of Σc,
    /// the largest at b/v = 30, where β reaches 3e6 and the reference's
    /// narrowest panels start to lose digits.
    #[test]
    fn memory_matrix_matches_per_term_quadrature() {
        let fast = MemoryQuadrature::new(24, 0.5);
        let reference = MemoryQuadrature::new(24, 0.1);
        // β from 1e-6 to 1e5: every method at every N here (β_F = N²/16 =
        // 36 … 1024). Above 1e5 the reference's own panels lose accuracy.
        let compliance = spread(67, -6.0, 5.0);
        let total: f64 = compliance.strengths.iter().sum();
        for terms in [24, 61, 128] {
            let grid = CollocationGrid::new(terms);
            for scale in [0.01, 1.0, 30.0] {
                let a = grid.memory_matrix(&fast, &compliance, scale);
                let b = memory_matrix_per_term(&reference, &grid, &compliance, scale);
                let worst = a
                    .iter()
                    .zip(&b)
                    .map(|(x, y)| (x - y).abs())
                    .fold(0.0, f64::max)
                    / total;
                println!("N = {terms}, b/v = {scale}: worst difference {worst:.1e} of Σc");
                assert!(worst < 3e-12, "N = {terms}, b/v = {scale}: {worst:e}");
            }
        }
    }

    /// Very short memory (β ≥ 1e10): the derivative series against the
    /// two-term expansion h + h′/β (error N⁴/(3β²) ≤ 1e-13 here).
    #[test]
    fn derivative_series_matches_the_short_memory_limit() {
        let q = MemoryQuadrature::new(24, 0.5);
        let compliance = spread(7, 10.5, 13.0);
        let total: f64 = compliance.strengths.iter().sum();
        for terms in [24, 128] {
            let grid = CollocationGrid::new(terms);
            let a = grid.memory_matrix(&q, &compliance, 1.0);
            let b = memory_matrix_per_term(&q, &grid, &compliance, 1.0);
            let worst = a
                .iter()
                .zip(&b)
                .map(|(x, y)| (x - y).abs())
                .fold(0.0, f64::max)
                / total;
            assert!(worst < 1e-12, "N = {terms}: {worst:e}");
        }
    }
}
