//! The uniform grid σ_j = σ₀ + jh in σ = ln(ω r(ω)), built lazily outward
//! from σ₀. With the dynamic contact rule σ(s) is a monotone but nonlinear
//! function of s = ln ω, so each node's frequency is found by Newton's method
//! from its neighbour (two or three modulus evaluations per node); with the
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
}

/// Nodes j ≥ 0 in `up`, j < 0 in `down` (j = −1 first).
pub(crate) struct Grid<'a, F> {
    setup: &'a Setup,
    modulus: F,
    origin: f64,
    step: f64,
    up: Vec<Node>,
    down: Vec<Node>,
}

/// More nodes than any sane scene needs: guards against a runaway march.
const MAX_NODES: usize = 200_000;

impl<'a, F: Fn(f64) -> (Complex64, Complex64)> Grid<'a, F> {
    pub(crate) fn new(setup: &'a Setup, modulus: F, origin: f64, step: f64) -> Self {
        Grid {
            setup,
            modulus,
            origin,
            step,
            up: Vec::new(),
            down: Vec::new(),
        }
    }

    pub(crate) fn origin(&self) -> f64 {
        self.origin
    }

    fn evaluate(&self, s: f64) -> Point {
        let (e, slope) = (self.modulus)(s.exp());
        self.setup.point(s, e, slope)
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
                return Err(ModelError::Evaluation(format!(
                    "the contact map ω·a(ω) is not increasing at ω = {:e} rad/s \
                     (the modulus rises faster than ω^{}); the dynamic contact \
                     size is undefined there",
                    s.exp(),
                    self.setup.n
                )));
            }
            let ds = (target - p.sigma) / p.dsigma_ds;
            // Within a step of h the map is nearly linear; limit wild jumps.
            let ds = ds.clamp(-2.0, 2.0);
            s += ds;
            if ds.abs() < 1e-7 {
                // Newton converges quadratically: after a step of 1e-7 the
                // remaining error in s is ~1e-14.
                let p = self.evaluate(s);
                return Ok((s, p));
            }
        }
        Err(ModelError::Evaluation(format!(
            "the contact size did not converge at σ = {target}"
        )))
    }

    /// Node j, building the nodes between it and the origin if needed.
    pub(crate) fn node(&mut self, j: i64) -> Result<Node, ModelError> {
        if j >= 0 {
            let j = j as usize;
            while self.up.len() <= j {
                let k = self.up.len();
                let target = self.origin + k as f64 * self.step;
                let guess = match (k, self.up.last()) {
                    (_, Some(prev)) => prev.s + self.step / prev.point.dsigma_ds,
                    (_, None) => {
                        target
                            - (self.setup.ln_k
                                - (self.setup.static_modulus / self.setup.plane_strain).ln())
                                / self.setup.n
                    }
                };
                let node = self.make(target, guess)?;
                self.up.push(node);
                if self.up.len() + self.down.len() > MAX_NODES {
                    return Err(ModelError::Evaluation(
                        "friction quadrature needs too many nodes".into(),
                    ));
                }
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
                let prev = if k == 0 { self.up[0] } else { self.down[k - 1] };
                let guess = prev.s - self.step / prev.point.dsigma_ds;
                let node = self.make(target, guess)?;
                self.down.push(node);
                if self.up.len() + self.down.len() > MAX_NODES {
                    return Err(ModelError::Evaluation(
                        "friction quadrature needs too many nodes".into(),
                    ));
                }
            }
            Ok(self.down[j])
        }
    }

    fn make(&self, target: f64, guess: f64) -> Result<Node, ModelError> {
        let (s, point) = self.invert(target, guess)?;
        Ok(Node {
            s,
            point,
            phi: point.a / point.dsigma_ds,
        })
    }
}
