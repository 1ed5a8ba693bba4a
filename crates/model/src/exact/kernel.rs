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
//! The exponential is cut where it falls below e^{−40}. For β > 1e9 the
//! inner integral is h_n(t_k) + h_n′(t_k)/β (error O(N⁴/β²)).

use crate::kernel::quadrature::gauss_legendre_unit;

/// Exponential cut-off: contributions below e^{−CUT} are dropped.
const CUT: f64 = 40.0;

/// Above this β the inner integral uses its two-term asymptotic expansion
/// (the panels would be narrower than the resolution of t).
const ASYMPTOTIC_BETA: f64 = 1e9;

/// Breakpoints in units of the exponential's scale 1/β.
const SCALE_BREAKS: [f64; 5] = [0.5, 2.0, 6.0, 15.0, CUT];

/// acosh(1 + x) for x ≥ 0, accurate for small x.
fn acosh1p(x: f64) -> f64 {
    (x + (x * (2.0 + x)).sqrt()).ln_1p()
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

    /// Calls `visit(x, w)` for the nodes of the composite rule on the
    /// sorted breakpoints `breaks`, splitting long panels.
    fn for_each_node<F: FnMut(f64, f64)>(&self, breaks: &[f64], mut visit: F) {
        for pair in breaks.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            if b <= a {
                continue;
            }
            let pieces = ((b - a) / self.max_panel).ceil().max(1.0) as usize;
            let h = (b - a) / pieces as f64;
            for p in 0..pieces {
                let lo = a + p as f64 * h;
                for (x, w) in self.nodes.iter().zip(&self.weights) {
                    visit(lo + h * x, h * w);
                }
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
        self.for_each_node(&breaks, |theta, w| {
            let sh = (0.5 * theta).sinh();
            let weight = w * beta * (-2.0 * beta * sh * sh).exp() * theta.sinh();
            let decay = (-theta).exp();
            let mut e = weight;
            for o in out.iter_mut() {
                e *= decay;
                *o += e;
            }
        });
    }

    /// I_n(t_k; β), n = 0..out.len(), the part of the memory integral inside
    /// the contact (t from t_k to the leading edge t = 1).
    pub(crate) fn inner(&self, beta: f64, t_k: f64, out: &mut [f64]) {
        out.iter_mut().for_each(|o| *o = 0.0);
        if beta > ASYMPTOTIC_BETA {
            // Memory far shorter than the contact: β∫e^{−βs} h(t_k + s) ds
            // = h(t_k) + h′(t_k)/β + O(N⁴/β²), with T′_{n+1} = (n+1) U_n.
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
            return;
        }
        let phi_k = t_k.acos();
        // Breakpoints in t, converted to φ = acos t (descending in t ↔ ascending φ).
        let mut breaks = vec![phi_k];
        for d in SCALE_BREAKS {
            let t = t_k + d / beta;
            if t < 1.0 {
                breaks.push(t.acos());
            } else {
                breaks.push(0.0);
                break;
            }
        }
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        self.for_each_node(&breaks, |phi, w| {
            let (s, c) = phi.sin_cos();
            let weight = w * beta * (-beta * (c - t_k)).exp() * s;
            // cos((n+1)φ) by the three-term recurrence.
            let (mut prev, mut cur) = (1.0, c);
            for o in out.iter_mut() {
                *o += weight * cur;
                let next = 2.0 * c * cur - prev;
                prev = cur;
                cur = next;
            }
        });
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
                q.inner(beta, t_k, &mut inner);
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
}
