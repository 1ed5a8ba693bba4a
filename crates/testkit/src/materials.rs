//! The test materials: each defined once, named by what it is.
//!
//! Moduli in Pa, times in s. The Prony series are in the paper's form
//! E*(ω) = E1 − Σ H_k/(1 + iωτ_k), E0 = E1 − Σ H_k.

use rollfit_model::{HavriliakNegami, Prony, StandardLinearSolid};

/// The bundled example's truth (data/hn-rubber.toml): a broad
/// Havriliak–Negami rubber, E0 = 2 MPa, E1 = 2 GPa, τ = 1 ms, α = 0.55,
/// β = 0.4.
pub fn hn_rubber() -> HavriliakNegami {
    HavriliakNegami::new(2e6, 2e9, 1e-3, 0.55, 0.4).unwrap()
}

/// A rubber with a narrower, more symmetric transition than [`hn_rubber`]:
/// HN with E0 = 5 MPa, E1 = 1.5 GPa, τ = 10 µs, α = 0.7, β = 0.25.
pub fn narrow_rubber() -> HavriliakNegami {
    HavriliakNegami::new(5e6, 1.5e9, 1e-5, 0.7, 0.25).unwrap()
}

/// The standard linear solid of Persson's Fig. 2 family: E0 = 1 MPa,
/// E1 = `ratio` MPa, τ = 1 s.
pub fn sls(ratio: f64) -> StandardLinearSolid {
    StandardLinearSolid::new(1e6, ratio * 1e6, 1.0).unwrap()
}

/// A 3-term Prony series: E1 = 100 MPa, H = 50, 30, 15 MPa at
/// τ = 1e-4, 1e-2, 1 s (E0 = 5 MPa).
pub fn prony3() -> Prony {
    Prony::new(1e8, vec![5e7, 3e7, 1.5e7], vec![1e-4, 1e-2, 1.0]).unwrap()
}

/// A broad series of `terms` relaxation times a decade apart from
/// 10^`first_exponent` s, the strengths 2 MPa · (1 + 0.3 sin 0.7k) ·
/// 10^(`decade_slope` k): a rising, gently rippled spectrum (fixed, not
/// random); E0 = 2 MPa.
pub fn rippled_prony(terms: i32, first_exponent: i32, decade_slope: f64) -> Prony {
    let tau: Vec<f64> = (0..terms).map(|k| 10f64.powi(k + first_exponent)).collect();
    let h: Vec<f64> = (0..terms)
        .map(|k| {
            2e6 * (1.0 + 0.3 * (f64::from(k) * 0.7).sin()) * 10f64.powf(f64::from(k) * decade_slope)
        })
        .collect();
    let e1 = 2e6 + h.iter().sum::<f64>();
    Prony::new(e1, h, tau).unwrap()
}

/// A smooth spectrum: `terms` relaxation times log-spaced over
/// 10^`log_tau.0` … 10^`log_tau.1` s, the strengths a log-normal bump in
/// log10 τ (centre `centre`, width `width` decades) on a relative floor
/// `floor`, scaled so that the series runs from `e0` to `e1`.
pub struct LogNormalSpectrum {
    pub terms: usize,
    pub log_tau: (f64, f64),
    pub centre: f64,
    pub width: f64,
    pub floor: f64,
    pub e0: f64,
    pub e1: f64,
}

impl LogNormalSpectrum {
    /// The series.
    pub fn prony(&self) -> Prony {
        let n = self.terms;
        let (lo, hi) = self.log_tau;
        let tau: Vec<f64> = (0..n)
            .map(|k| 10f64.powf(lo + (hi - lo) * k as f64 / (n - 1) as f64))
            .collect();
        let w: Vec<f64> = tau
            .iter()
            .map(|t| (-0.5 * ((t.log10() - self.centre) / self.width).powi(2)).exp() + self.floor)
            .collect();
        let total: f64 = w.iter().sum();
        let h = w.iter().map(|x| (self.e1 - self.e0) * x / total).collect();
        Prony::new(self.e1, h, tau).unwrap()
    }
}

/// The broad rubber of 200 terms (`rubber_200` of the model crate's exact
/// solvers): relaxation times over 1e-12 … 1e8 s, a bump around 1e-5 s
/// three decades wide on a floor of 1e-3; E0 = 2 MPa, E1 = 2 GPa.
pub fn rubber_200() -> Prony {
    LogNormalSpectrum {
        terms: 200,
        log_tau: (-12.0, 8.0),
        centre: -5.0,
        width: 3.0,
        floor: 1e-3,
        e0: 2e6,
        e1: 2e9,
    }
    .prony()
}

/// The relaxation isotherms' truth at T_ref = 20 °C: a broad transition,
/// a smooth spectrum sampled two terms per decade (τ_k from 1e-7 to 1e5 s)
/// with log10 H_k falling 0.35 per decade from 1.5e8 Pa, and E0 = 2e5 Pa,
/// so that E(t) falls throughout a measured window and every pair of
/// isotherms has a slope to overlap on. (A series of one term per decade
/// is not a material's smooth spectrum: its E(t) ripples by about ±2 %
/// between its τ_k, which a smoothed fit does not follow.)
pub fn relaxation_truth() -> Prony {
    let tau: Vec<f64> = (0..=24)
        .map(|k| 10f64.powf(-7.0 + 0.5 * k as f64))
        .collect();
    let h: Vec<f64> = (0..tau.len())
        .map(|k| 1.5e8 * 10f64.powf(-0.175 * k as f64))
        .collect();
    let e0 = 2e5;
    Prony::new(e0 + h.iter().sum::<f64>(), h, tau).unwrap()
}

/// A 64-bit linear congruential generator (Knuth's MMIX constants): seeded
/// random numbers without a crate, for the model crate's random solids.
pub struct Lcg(pub u64);

impl Lcg {
    /// The next number, uniform in [0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A random broad solid: `terms` relaxation times a decade apart, the k-th
/// at 10^(k + `first_log_tau` + `jitter`·u) s (u uniform in [0, 1));
/// strengths over two decades from 1 MPa; E0 between 1 and 5 MPa.
pub fn random_prony(rng: &mut Lcg, terms: usize, first_log_tau: f64, jitter: f64) -> Prony {
    let tau: Vec<f64> = (0..terms)
        .map(|k| 10f64.powf(k as f64 + first_log_tau + jitter * rng.uniform()))
        .collect();
    let h: Vec<f64> = (0..terms)
        .map(|_| 1e6 * 10f64.powf(2.0 * rng.uniform()))
        .collect();
    let e0 = 1e6 * (1.0 + 4.0 * rng.uniform());
    Prony::new(e0 + h.iter().sum::<f64>(), h, tau).unwrap()
}
