//! Creep compliance of a Prony series (and hence of the standard linear
//! solid, a one-term series).
//!
//! With the relaxation modulus E(t) = E0 + Σ_k H_k e^{−t/τ_k}, the
//! s-multiplied Laplace transform is Ẽ(s) = E1 − Σ_k H_k/(1 + sτ_k)
//! (E*(ω) = Ẽ(iω)), and the creep compliance J(t) obeys sJ̄(s) = 1/Ẽ(s):
//!
//!   J(t) = 1/E1 + Σ_j c_j (1 − e^{−t/λ_j}),   1/Ẽ(s) = 1/E1 + Σ_j c_j/(1 + sλ_j).
//!
//! The retardation times λ_j = −1/s_j come from the zeros s_j of Ẽ. Ẽ
//! increases between its poles −1/τ_k (Ẽ′(s) = Σ H_k τ_k/(1 + sτ_k)² > 0) and
//! runs from −∞ to +∞ on each interval between consecutive poles, and from
//! −∞ to E0 > 0 on (−1/τ_max, 0): in λ, exactly one zero lies in each
//! (τ_(k), τ_(k+1)) of the sorted relaxation times and one in (τ_max, ∞).
//! Each is bracketed and bisected in ln λ to machine precision. The
//! strengths are the residues, c_j = λ_j/Ẽ′(s_j) > 0, and
//! 1/E1 + Σ c_j = 1/E0.
//!
//! Terms with H_k ≤ ε E1 (ε the f64 machine epsilon, [`NEGLIGIBLE_SHARE`])
//! are dropped first. Such a term changes Ẽ by less than the rounding of
//! E1 itself, and its zero lies within about (H_k/E1) τ_k of its pole —
//! closer than the spacing of f64 numbers near τ_k — so bisection cannot
//! separate the two, and the residue computed at the rounded λ is
//! garbage (a term of H ≈ 1e-20 E1 gave a nonsense μ from the exact
//! cylinder). Dropping it changes J(t) by less than ε J.

use crate::modulus::Prony;

/// Strengths H_k ≤ NEGLIGIBLE_SHARE · E1 are dropped from the conversion:
/// the machine epsilon, below which a term does not change E1 in f64 and
/// its retardation time cannot be told from its relaxation time.
pub const NEGLIGIBLE_SHARE: f64 = f64::EPSILON;

/// The creep compliance J(t) = J0 + Σ_j c_j (1 − e^{−t/λ_j}) of a Prony
/// series, in 1/Pa and s.
#[derive(Debug, Clone, PartialEq)]
pub struct CreepCompliance {
    /// Instantaneous (glassy) compliance J(0) = 1/E1, 1/Pa.
    pub instantaneous: f64,
    /// Retardation strengths c_j, 1/Pa (each > 0).
    pub strengths: Vec<f64>,
    /// Retardation times λ_j, s (ascending).
    pub retardation_times: Vec<f64>,
}

impl CreepCompliance {
    /// The creep compliance of `prony`. Terms with H_k ≤ ε E1
    /// (`NEGLIGIBLE_SHARE`) are dropped and equal relaxation times
    /// merged.
    pub fn from_prony(prony: &Prony) -> Self {
        let e1 = prony.glassy_modulus();
        let mut terms: Vec<(f64, f64)> = prony
            .relaxation_times()
            .iter()
            .zip(prony.strengths())
            .filter(|(_, h)| **h > NEGLIGIBLE_SHARE * e1)
            .map(|(&t, &h)| (t, h))
            .collect();
        terms.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut merged: Vec<(f64, f64)> = Vec::with_capacity(terms.len());
        for (t, h) in terms {
            match merged.last_mut() {
                Some(last) if last.0 == t => last.1 += h,
                _ => merged.push((t, h)),
            }
        }
        // Ẽ(−1/λ) = E1 − Σ H_k λ/(λ − τ_k).
        let e_of_lambda = |lambda: f64| -> f64 {
            e1 - merged
                .iter()
                .map(|&(t, h)| h * lambda / (lambda - t))
                .sum::<f64>()
        };
        let mut strengths = Vec::with_capacity(merged.len());
        let mut retardation_times = Vec::with_capacity(merged.len());
        for k in 0..merged.len() {
            let lo = merged[k].0;
            // Just above τ_k the function is −∞; at the next pole +∞.
            let hi = match merged.get(k + 1) {
                Some(&(t, _)) => t,
                None => {
                    let mut hi = 2.0 * lo;
                    while e_of_lambda(hi) < 0.0 {
                        hi *= 2.0;
                    }
                    hi
                }
            };
            let (mut a, mut b) = (lo.ln(), hi.ln());
            for _ in 0..200 {
                let m = 0.5 * (a + b);
                if m <= a || m >= b {
                    break;
                }
                let f = e_of_lambda(m.exp());
                if f.is_nan() {
                    break;
                }
                if f < 0.0 {
                    a = m;
                } else {
                    b = m;
                }
            }
            // Pick the end with the smaller |Ẽ| (both are within one ulp).
            let (la, lb) = (a.exp(), b.exp());
            let lambda = if e_of_lambda(la).abs() < e_of_lambda(lb).abs() {
                la
            } else {
                lb
            };
            // Ẽ′(s) at s = −1/λ: Σ H τ/(1 − τ/λ)².
            let s = -1.0 / lambda;
            let de: f64 = merged
                .iter()
                .map(|&(t, h)| {
                    let d = 1.0 + s * t;
                    h * t / (d * d)
                })
                .sum();
            strengths.push(lambda / de);
            retardation_times.push(lambda);
        }
        CreepCompliance {
            instantaneous: 1.0 / e1,
            strengths,
            retardation_times,
        }
    }

    /// J(t), 1/Pa, for t ≥ 0 s.
    pub fn at(&self, t: f64) -> f64 {
        self.instantaneous
            + self
                .strengths
                .iter()
                .zip(&self.retardation_times)
                .map(|(c, l)| c * -(-t / l).exp_m1())
                .sum::<f64>()
    }

    /// The long-time compliance J(∞) = 1/E1 + Σ c_j (= 1/E0), 1/Pa.
    pub fn equilibrium(&self) -> f64 {
        self.instantaneous + self.strengths.iter().sum::<f64>()
    }

    /// The complex compliance 1/E*(ω) = 1/E1 + Σ c_j/(1 + iωλ_j), 1/Pa.
    pub fn complex_compliance(&self, omega: f64) -> num_complex::Complex64 {
        let mut j = num_complex::Complex64::new(self.instantaneous, 0.0);
        for (&c, &l) in self.strengths.iter().zip(&self.retardation_times) {
            j += c / num_complex::Complex64::new(1.0, omega * l);
        }
        j
    }

    /// The same compliance scaled by a constant (e.g. 1 − ν² for the
    /// plane-strain effective compliance).
    pub fn scaled(&self, factor: f64) -> Self {
        CreepCompliance {
            instantaneous: factor * self.instantaneous,
            strengths: self.strengths.iter().map(|c| factor * c).collect(),
            retardation_times: self.retardation_times.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A term of strength 1e-20 E1 beside a real one gives the compliance
    /// of the real one alone, not a residue of the root search for the tiny
    /// one.
    #[test]
    fn negligible_terms_are_harmless() {
        let clean = Prony::new(10.0, vec![9.0], vec![1.0]).unwrap();
        let reference = CreepCompliance::from_prony(&clean);
        for tiny in [1e-20, 1e-30, 1e-17] {
            for tau in [1e-3, 1.0, 1e3] {
                let prony = Prony::new(10.0, vec![9.0, tiny * 10.0], vec![1.0, tau]).unwrap();
                let creep = CreepCompliance::from_prony(&prony);
                assert!(
                    creep.strengths.iter().all(|c| c.is_finite() && *c > 0.0),
                    "{tiny} {tau}: {creep:?}"
                );
                for t in [1e-4, 1e-1, 1.0, 10.0, 1e4] {
                    let (a, b) = (creep.at(t), reference.at(t));
                    assert!((a / b - 1.0).abs() < 1e-12, "{tiny} {tau} {t}: {a} vs {b}");
                }
            }
        }
    }
}
