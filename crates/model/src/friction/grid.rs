//! The uniform grid σ_j = σ₀ + jh in σ = ln(ω r(ω)), built lazily outward
//! from σ₀. With the dynamic contact rule σ(s) is a monotone but nonlinear
//! function of s = ln ω, so each node's frequency is found by Newton's method
//! (two modulus evaluations per node), started from a cubic Hermite
//! extrapolation of s(σ) through the two previous nodes, whose slopes
//! ds/dσ each evaluation gives for free. A node is accepted once the Newton
//! step falls below `s_tolerance`: the interpolated Φ then errs by about
//! |d ln Φ/ds|·s_tolerance, far below the quadrature tolerance. With the
//! static rule σ − s is constant.

use num_complex::Complex64;

use super::setup::{Point, Setup};
use crate::error::ModelError;

/// One grid node.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Node {
    /// s = ln ω at the node.
    pub s: f64,
    /// The material part of the integrand there.
    pub point: Point,
    /// Φ = A ds/dσ.
    pub phi: f64,
    /// B_up with Σ_{i>j} Φ_i |W(σ_i − ln v)| ≤ B_up |W(σ_j − ln v)| for
    /// σ_j − ln v > 2, see [`Setup::upper_tail_bound`].
    pub up_bound: f64,
    /// The same below: Σ_{i<j} … ≤ B_down |W(σ_j − ln v)| for σ_j − ln v < −2.
    pub down_bound: f64,
}

/// Nodes j ≥ 0 in `up`, j < 0 in `down` (j = −1 first).
pub(crate) struct Grid<'a, F> {
    setup: &'a Setup,
    modulus: F,
    origin: f64,
    step: f64,
    /// Accepted error of a node's s = ln ω.
    s_tolerance: f64,
    /// 1/(1 − e^{−h}), 1/(1 − e^{−2h}), 1/(1 − e^{−(2−p)h}) and
    /// 1/(1 − e^{−(1+p)h}): sums of the
    /// geometric tail bounds, see [`Grid::make`].
    tail_sums: [f64; 4],
    up: Vec<Node>,
    down: Vec<Node>,
}

/// More nodes than any sane scene needs: guards against a runaway march.
const MAX_NODES: usize = 200_000;

impl<'a, F: Fn(f64) -> (Complex64, Complex64)> Grid<'a, F> {
    /// A grid through σ₀ = `origin` with step `step`, for a quadrature of
    /// relative tolerance `tolerance`.
    pub(crate) fn new(
        setup: &'a Setup,
        modulus: F,
        origin: f64,
        step: f64,
        tolerance: f64,
    ) -> Self {
        Grid {
            setup,
            modulus,
            origin,
            step,
            s_tolerance: (1e-3 * tolerance).clamp(1e-13, 1e-8),
            tail_sums: [
                1.0 / (1.0 - (-step).exp()),
                1.0 / (1.0 - (-2.0 * step).exp()),
                1.0 / (1.0 - (-(2.0 - setup.tail_exponent) * step).exp()),
                1.0 / (1.0 - (-(1.0 + setup.tail_exponent) * step).exp()),
            ],
            up: Vec::new(),
            down: Vec::new(),
        }
    }

    pub(crate) fn origin(&self) -> f64 {
        self.origin
    }

    fn evaluate(&self, s: f64) -> Point {
        let omega = s.exp();
        let (e, slope) = (self.modulus)(omega);
        self.setup.point(s, omega, e, slope)
    }

    /// Solves σ(s) = target by Newton's method from `guess`.
    fn invert(&self, target: f64, guess: f64) -> Result<(f64, Point), ModelError> {
        if let Some(ln_r0) = self.setup.static_ln_size {
            let s = target - ln_r0;
            return Ok((s, self.evaluate(s)));
        }
        let mut s = guess;
        for _ in 0..60 {
            let p = self.evaluate(s);
            if p.dsigma_ds.is_nan() || p.dsigma_ds <= 0.0 || !p.sigma.is_finite() {
                return Err(ModelError::ContactMapNotIncreasing {
                    omega: s.exp(),
                    exponent: self.setup.n,
                });
            }
            let ds = (target - p.sigma) / p.dsigma_ds;
            if ds.abs() <= self.s_tolerance {
                return Ok((s, p));
            }
            // Within a step of h the map is nearly linear; limit wild jumps.
            s += ds.clamp(-2.0, 2.0);
        }
        Err(ModelError::ContactSizeNotConverged { sigma: target })
    }

    /// Node j, building the nodes between it and the origin if needed.
    pub(crate) fn node(&mut self, j: i64) -> Result<Node, ModelError> {
        if j >= 0 {
            let j = j as usize;
            while self.up.len() <= j {
                let k = self.up.len();
                let target = self.origin + k as f64 * self.step;
                let guess = match k {
                    0 => {
                        target
                            - (self.setup.ln_k
                                - (self.setup.static_modulus / self.setup.plane_strain).ln())
                                / self.setup.n
                    }
                    1 => extrapolate_linear(&self.up[0], self.step),
                    _ => extrapolate_hermite(&self.up[k - 2], &self.up[k - 1], self.step),
                };
                let node = self.make(target, guess)?;
                self.up.push(node);
                self.check_size()?;
            }
            Ok(self.up[j])
        } else {
            let j = (-j - 1) as usize;
            if self.up.is_empty() {
                self.node(0)?;
            }
            while self.down.len() <= j {
                let k = self.down.len();
                let target = self.origin - (k as f64 + 1.0) * self.step;
                let guess = match k {
                    0 => extrapolate_linear(&self.up[0], -self.step),
                    1 => extrapolate_hermite(&self.up[0], &self.down[0], -self.step),
                    _ => extrapolate_hermite(&self.down[k - 2], &self.down[k - 1], -self.step),
                };
                let node = self.make(target, guess)?;
                self.down.push(node);
                self.check_size()?;
            }
            Ok(self.down[j])
        }
    }

    fn check_size(&self) -> Result<(), ModelError> {
        if self.up.len() + self.down.len() > MAX_NODES {
            return Err(ModelError::TooManyQuadratureNodes);
        }
        Ok(())
    }

    fn make(&self, target: f64, guess: f64) -> Result<Node, ModelError> {
        let (s, point) = self.invert(target, guess)?;
        let setup = self.setup;
        // Above, W decays like e^{−2τ}. With the local bounds of a positive
        // spectrum, κe^{σ}|W| shrinks at least by e^{−h} a step and a
        // constant bound on Φ by e^{−2h}; with only the global bound
        // Φ ≤ κe^{pσ}, by e^{−(2−p)h}. Below, Φ ≤ κe^{pσ} and W decays at
        // least like e^{τ}: successive terms shrink by e^{−(1+p)h} or faster.
        // Each sum is then bounded by its first term over one minus the ratio.
        let p = setup.tail_exponent;
        let e_sigma = target.exp();
        let e_p_sigma = if p == 1.0 {
            e_sigma
        } else {
            (p * target).exp()
        };
        let [up_sum, up_sum_constant, up_sum_global, down_sum] = self.tail_sums;
        let up_bound = match setup.upper_tail_bound(&point) {
            Some((kappa, constant)) => (kappa * e_sigma * up_sum).min(constant * up_sum_constant),
            None => setup.tail_bound * e_p_sigma * up_sum_global,
        };
        let down_bound = setup.tail_bound * e_p_sigma * down_sum;
        Ok(Node {
            s,
            point,
            phi: point.a / point.dsigma_ds,
            up_bound,
            down_bound,
        })
    }
}

/// s at σ(`last`) + `h` from the tangent at `last`.
fn extrapolate_linear(last: &Node, h: f64) -> f64 {
    last.s + h / last.point.dsigma_ds
}

/// s at σ(`last`) + `h` from the cubic Hermite interpolant of s(σ) through
/// `older` (at σ − h) and `last`: values and slopes ds/dσ at both ends,
/// evaluated one step beyond (the Hermite basis at t = 2 is 5, 2, −4, 4).
fn extrapolate_hermite(older: &Node, last: &Node, h: f64) -> f64 {
    5.0 * older.s + 2.0 * h / older.point.dsigma_ds - 4.0 * last.s + 4.0 * h / last.point.dsigma_ds
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The message names the frequency in full and the exponent.
    #[test]
    fn the_contact_map_error_names_its_frequency_and_exponent() {
        for (omega, n) in [(5.98e-3, 3.0), (1.0 / 3.0, 2.0)] {
            let message = ModelError::ContactMapNotIncreasing { omega, exponent: n }.to_string();
            assert!(
                message.starts_with(&format!(
                    "the contact map ω·a(ω) is not increasing at ω = {omega:e} rad/s"
                )) && message.contains(&format!("faster than ω^{n})")),
                "{message}"
            );
        }
    }
}
