//! The independent side of the file tests: a Prony series and the WLF law
//! written out by hand, so that what a reader or a comparison computes is
//! checked against formulas that share no code with it.

/// A Prony series in the paper's form E*(ω) = E1 − Σ H_k/(1 + iωτ_k),
/// written out: E′ = E1 − Σ H_k/(1 + ω²τ²), E″ = Σ H_k ωτ/(1 + ω²τ²).
#[derive(Clone)]
pub struct Series {
    /// Glassy modulus E1, Pa.
    pub e1: f64,
    /// Strengths H_k, Pa.
    pub h: Vec<f64>,
    /// Relaxation times τ_k, s.
    pub tau: Vec<f64>,
}

impl Series {
    /// (E′, E″) at `omega` rad/s, Pa.
    pub fn at(&self, omega: f64) -> (f64, f64) {
        let mut storage = self.e1;
        let mut loss = 0.0;
        for (h, tau) in self.h.iter().zip(&self.tau) {
            let x = omega * tau;
            storage -= h / (1.0 + x * x);
            loss += h * x / (1.0 + x * x);
        }
        (storage, loss)
    }

    /// A broad rubber: E0 = 2 MPa, E1 = 2 GPa, one term per decade with a
    /// smooth (log-normal) strength distribution centred at τ = 1e-4 s.
    pub fn broad_rubber() -> Series {
        let tau: Vec<f64> = (-12..=4).map(|k| 10f64.powi(k)).collect();
        let weights: Vec<f64> = tau
            .iter()
            .map(|t| (-(t.log10() + 4.0).powi(2) / 8.0).exp())
            .collect();
        let total: f64 = weights.iter().sum();
        let (e0, e1) = (2e6, 2e9);
        Series {
            e1,
            h: weights.iter().map(|w| (e1 - e0) * w / total).collect(),
            tau,
        }
    }
}

/// WLF written out: log10 a_T = −C1 (T − T_ref)/(C2 + T − T_ref).
pub fn wlf(t: f64, t_ref: f64, c1: f64, c2: f64) -> f64 {
    -c1 * (t - t_ref) / (c2 + t - t_ref)
}
