//! The pressure of a solution on the graded mesh ([`super::cylinder_mesh`]):
//! from F, the Hilbert transform of the pressure inside the contact, by the
//! bounded inversion of the finite Hilbert transform (Tricomi 1957, ch. IV):
//!
//!   p(t) = b √(1 − t²) (1/π) PV∫ F(s) ds/(√(1 − s²)(s − t))
//!        = b √(1 − t²) (1/π) ∫ [F(s) − F(t)]/(s − t) ds/√(1 − s²),
//!
//! since PV∫ ds/(√(1 − s²)(s − t)) = 0 inside the interval; the divided
//! difference is smooth, so the mesh's weighted quadrature applies. (With
//! F = T_{n+1} this is √(1 − t²) U_n(t), the Chebyshev basis.)
//!
//! A truncated Chebyshev series cannot stand in for it: an edge layer
//! thinner than the series resolves leaves a √((1 + t)/(1 − t)) part in the
//! pressure whose coefficients do not decay before n ≈ δ^{−1/2}, and its
//! truncation oscillates below zero across the whole contact.
//!
//! # References
//! - F.G. Tricomi, *Integral Equations*, Interscience 1957, ch. IV (the
//!   finite Hilbert transform and its inversion bounded at both ends).
//! - F. Erdogan, G.D. Gupta, Q. Appl. Math. 29 (1972) 525–534 (the
//!   Chebyshev pair T_{n+1} ↔ √(1 − t²) U_n).

use std::f64::consts::PI;

/// F on the graded mesh, kept with a solution for its pressure.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PressureProfile {
    /// Panels (lo, hi) in u = 1 − t.
    pub(crate) panels: Vec<(f64, f64)>,
    /// Gauss nodes of a panel on [0, 1] and their barycentric weights.
    pub(crate) unit_nodes: Vec<f64>,
    pub(crate) barycentric: Vec<f64>,
    /// F at the mesh nodes.
    pub(crate) values: Vec<f64>,
    /// The mesh's weighted points (u_k, weight_k including 1/√(u(2 − u)),
    /// F(u_k)).
    pub(crate) points: Vec<(f64, f64, f64)>,
}

impl PressureProfile {
    /// F at u ∈ [0, 2] (the interpolant of its panel).
    pub(crate) fn value(&self, u: f64) -> f64 {
        let p = self
            .panels
            .partition_point(|&(_, hi)| hi < u)
            .min(self.panels.len() - 1);
        let (lo, hi) = self.panels[p];
        self.interpolate(p, (u - lo) / (hi - lo))
    }

    /// The interpolant of panel p at ξ ∈ [0, 1] (barycentric, second form).
    fn interpolate(&self, p: usize, xi: f64) -> f64 {
        let q = self.unit_nodes.len();
        let values = &self.values[p * q..(p + 1) * q];
        if let Some(l) = self.unit_nodes.iter().position(|&x| x == xi) {
            return values[l];
        }
        let (mut numerator, mut denominator) = (0.0, 0.0);
        for ((&x, &w), &v) in self.unit_nodes.iter().zip(&self.barycentric).zip(values) {
            let c = w / (xi - x);
            numerator += c * v;
            denominator += c;
        }
        numerator / denominator
    }

    /// p/b at u = 1 − t ∈ (0, 2), the inversion of the module
    /// documentation on the weighted points (s_k − t = u − u_k).
    pub(crate) fn reduced_pressure(&self, u: f64) -> f64 {
        let f = self.value(u);
        let mut sum = 0.0;
        for &(uk, weight, fk) in &self.points {
            let gap = u - uk;
            let difference = if gap == 0.0 {
                // At a point itself the divided difference is −dF/du
                // (t = 1 − u).
                let h = 1e-7 * u.min(2.0 - u);
                (self.value(u - h) - self.value(u + h)) / (2.0 * h)
            } else {
                (fk - f) / gap
            };
            sum += weight * difference;
        }
        (u * (2.0 - u)).sqrt() * sum / PI
    }

    /// The Chebyshev coefficients α_n = (2/π) ∫ F T_{n+1} dt/√(1 − t²),
    /// n < `count`, of the interpolant: in θ = arccos t, dt/√(1 − t²) =
    /// dθ, each panel cut into pieces at most π/(count + 1) long (half a
    /// turn of the highest cos((n + 1)θ)) with `rule` on each.
    pub(crate) fn chebyshev_coefficients(
        &self,
        count: usize,
        rule: &(Vec<f64>, Vec<f64>),
    ) -> Vec<f64> {
        let mut alpha = vec![0.0; count];
        let longest = PI / (count + 1) as f64;
        for (p, &(lo, hi)) in self.panels.iter().enumerate() {
            // θ = 2 asin(√(u/2)) keeps its digits near u = 0.
            let (a, b) = (angle(lo), angle(hi));
            let pieces = ((b - a) / longest).ceil().max(1.0) as usize;
            let width = (b - a) / pieces as f64;
            for piece in 0..pieces {
                for (x, w) in rule.0.iter().zip(&rule.1) {
                    let theta = a + width * (piece as f64 + x);
                    let u = 2.0 * (0.5 * theta).sin().powi(2);
                    let xi = ((u - lo) / (hi - lo)).clamp(0.0, 1.0);
                    let scale = 2.0 / PI * width * w * self.interpolate(p, xi);
                    let t = theta.cos();
                    let (mut previous, mut current) = (1.0, t);
                    for a in alpha.iter_mut() {
                        *a += scale * current;
                        let next = 2.0 * t * current - previous;
                        previous = current;
                        current = next;
                    }
                }
            }
        }
        alpha
    }
}

/// θ = arccos(1 − u) = 2 asin(√(u/2)).
fn angle(u: f64) -> f64 {
    2.0 * (0.5 * u).sqrt().min(1.0).asin()
}
