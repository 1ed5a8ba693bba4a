//! Free parameters θ of the fit and their map to a Prony series.
//!
//! The material is E*(ω) = E0 + Σ_k H_k (1 − D_k(ω)), D_k = 1/(1 + iωτ_k),
//! on fixed relaxation times τ_k (Eq. B2 with E1 = E0 + Σ H_k). Positivity
//! of E0 and every H_k is kept by reparametrisation: the optimiser sees
//! logarithms.
//!
//! - Without a scale anchor, θ = (ln E0, ln H_1, …, ln H_n).
//! - With an anchor |E*(ω_a)| = E_a (ω_a = 0 for a known E0) the scale is
//!   eliminated exactly: θ = (ln Ĥ_1, …, ln Ĥ_n) describes a shape with
//!   Ê0 = 1, and the physical series is c·Ê with c = E_a/|Ê(ω_a)|, so the
//!   anchor holds for every θ and the optimiser cannot trade it away.
//!
//! Derivatives follow by the chain rule: with p = (E0, H) = c·p̂,
//! ∂p_i/∂θ_j = p_i (δ_ij + ∂ln c/∂θ_j), where
//! ∂ln c/∂θ_j = −Re[conj(Ê) Ĥ_j (1 − D_j(ω_a))]/|Ê|² (zero for ω_a = 0).

use num_complex::Complex64;
use rollfit_model::Prony;

use crate::error::FitError;
use crate::params::ModulusAnchor;

/// θ ↦ (E0, H) on fixed τ.
#[derive(Debug, Clone)]
pub(crate) struct Parametrization {
    tau: Vec<f64>,
    anchor: Option<ModulusAnchor>,
}

/// The material at one θ, with what the chain rule needs.
#[derive(Debug, Clone)]
pub(crate) struct Mapped {
    /// E0, Pa.
    pub static_modulus: f64,
    /// H_k, Pa.
    pub strengths: Vec<f64>,
    /// ∂ln c/∂θ_j (empty without an anchor).
    pub dln_scale: Vec<f64>,
}

impl Mapped {
    /// E1 = E0 + Σ H_k, Pa.
    pub fn glassy_modulus(&self) -> f64 {
        self.static_modulus + self.strengths.iter().sum::<f64>()
    }
}

impl Parametrization {
    pub(crate) fn new(tau: Vec<f64>, anchor: Option<ModulusAnchor>) -> Self {
        Parametrization { tau, anchor }
    }

    /// Relaxation times τ_k, s.
    pub(crate) fn tau(&self) -> &[f64] {
        &self.tau
    }

    /// Number of terms n.
    pub(crate) fn terms(&self) -> usize {
        self.tau.len()
    }

    /// Number of free parameters.
    pub(crate) fn free_count(&self) -> usize {
        match self.anchor {
            Some(_) => self.tau.len(),
            None => self.tau.len() + 1,
        }
    }

    /// Index in θ of ln H_1 (the ln H_k are contiguous).
    pub(crate) fn first_strength(&self) -> usize {
        match self.anchor {
            Some(_) => 0,
            None => 1,
        }
    }

    /// θ for a given (E0, H); with an anchor the scale is dropped (the
    /// anchor re-imposes it).
    pub(crate) fn theta_of(&self, static_modulus: f64, strengths: &[f64]) -> Vec<f64> {
        match self.anchor {
            Some(_) => strengths
                .iter()
                .map(|h| (h / static_modulus).ln())
                .collect(),
            None => std::iter::once(static_modulus.ln())
                .chain(strengths.iter().map(|h| h.ln()))
                .collect(),
        }
    }

    /// The material at θ.
    pub(crate) fn map(&self, theta: &[f64]) -> Mapped {
        match self.anchor {
            None => Mapped {
                static_modulus: theta[0].exp(),
                strengths: theta[1..].iter().map(|t| t.exp()).collect(),
                dln_scale: Vec::new(),
            },
            Some(a) => {
                let shape: Vec<f64> = theta.iter().map(|t| t.exp()).collect();
                let mut e_hat = Complex64::new(1.0, 0.0);
                let mut parts = Vec::with_capacity(shape.len());
                for (&h, &tau) in shape.iter().zip(&self.tau) {
                    let one_minus_d = one_minus_debye(a.omega, tau);
                    e_hat += h * one_minus_d;
                    parts.push(h * one_minus_d);
                }
                let norm_sqr = e_hat.norm_sqr();
                let scale = a.modulus / norm_sqr.sqrt();
                let dln_scale = parts
                    .iter()
                    .map(|p| -(e_hat.conj() * p).re / norm_sqr)
                    .collect();
                Mapped {
                    static_modulus: scale,
                    strengths: shape.iter().map(|h| scale * h).collect(),
                    dln_scale,
                }
            }
        }
    }

    /// The Prony series of a mapped θ.
    pub(crate) fn prony(&self, m: &Mapped) -> Result<Prony, FitError> {
        Ok(Prony::new(
            m.glassy_modulus(),
            m.strengths.clone(),
            self.tau.clone(),
        )?)
    }

    /// Pulls a gradient with respect to p = (E0, H_1..H_n) back to θ.
    pub(crate) fn pullback(&self, m: &Mapped, grad_p: &[f64], out: &mut [f64]) {
        let n = self.tau.len();
        match self.anchor {
            None => {
                out[0] = grad_p[0] * m.static_modulus;
                for k in 0..n {
                    out[k + 1] = grad_p[k + 1] * m.strengths[k];
                }
            }
            Some(_) => {
                // Σ_i ∂f/∂p_i p_i: the response to the common scale c.
                let scale_response = grad_p[0] * m.static_modulus
                    + (0..n).map(|k| grad_p[k + 1] * m.strengths[k]).sum::<f64>();
                for k in 0..n {
                    out[k] = grad_p[k + 1] * m.strengths[k] + scale_response * m.dln_scale[k];
                }
            }
        }
    }
}

/// 1 − D(ω) = iωτ/(1 + iωτ).
pub(crate) fn one_minus_debye(omega: f64, tau: f64) -> Complex64 {
    let w = omega * tau;
    let inv = 1.0 / (1.0 + w * w);
    Complex64::new(w * w * inv, w * inv)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rollfit_model::ViscoelasticModulus;

    fn tau() -> Vec<f64> {
        (0..6).map(|k| 10f64.powi(k - 3)).collect()
    }

    #[test]
    fn anchor_holds_for_any_theta() {
        let a = ModulusAnchor {
            omega: 3.0,
            modulus: 7e7,
            source: "E_at",
        };
        let p = Parametrization::new(tau(), Some(a));
        for seed in 0..5 {
            let theta: Vec<f64> = (0..6)
                .map(|k| ((k * 7 + seed * 3) % 5) as f64 - 1.0)
                .collect();
            let prony = p.prony(&p.map(&theta)).unwrap();
            let e = prony.modulus(3.0).norm();
            assert!((e / 7e7 - 1.0).abs() < 1e-13);
        }
    }

    #[test]
    fn pullback_matches_finite_differences() {
        // f(p) = |E*(ω)| at some ω, differentiated through the map.
        for anchor in [
            None,
            Some(ModulusAnchor {
                omega: 0.0,
                modulus: 2e6,
                source: "E0",
            }),
            Some(ModulusAnchor {
                omega: 40.0,
                modulus: 1e8,
                source: "E_at",
            }),
        ] {
            let p = Parametrization::new(tau(), anchor);
            let theta: Vec<f64> = (0..p.free_count())
                .map(|k| 14.0 + 0.3 * (k as f64).sin())
                .collect();
            let omega = 0.7;
            let f = |th: &[f64]| p.prony(&p.map(th)).unwrap().modulus(omega).norm();
            let m = p.map(&theta);
            let e = p.prony(&m).unwrap().modulus(omega);
            let mut grad_p = vec![e.re / e.norm()];
            for &t in p.tau() {
                grad_p.push((e.conj() * one_minus_debye(omega, t)).re / e.norm());
            }
            let mut grad = vec![0.0; p.free_count()];
            p.pullback(&m, &grad_p, &mut grad);
            for j in 0..p.free_count() {
                let mut up = theta.clone();
                let mut dn = theta.clone();
                up[j] += 1e-6;
                dn[j] -= 1e-6;
                let fd = (f(&up) - f(&dn)) / 2e-6;
                assert!(
                    (grad[j] - fd).abs() <= 1e-6 * e.norm(),
                    "{anchor:?} j={j}: {} vs {fd}",
                    grad[j]
                );
            }
        }
    }
}
