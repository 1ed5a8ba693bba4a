//! Laws of the shift factor fitted to the determined pairwise shifts, with
//! standard errors and a goodness-of-fit test: WLF, Arrhenius, and WLF
//! above a junction with Arrhenius below.
//!
//! The data are the pairs' relative shifts s_ij ± σ_ij
//! ([`super::pairwise`], those the [`super::network`] keeps). A law L(T)
//! with L(T_ref) = 0 predicts s_ij = L(T_j) − L(T_i), so no free offset is
//! needed and correlations between chained shifts never arise:
//!
//!   χ²(θ) = Σ_(i,j) (s_ij − L(T_j; θ) + L(T_i; θ))² / σ_ij².
//!
//! - WLF: L = −C1 ΔT/(C2 + ΔT), ΔT = T − T_ref. Linear in C1 for fixed C2;
//!   C2 scanned on a log grid above its floor (C2 + ΔT > 0 at every
//!   measured T), then Gauss–Newton on (C1, C2).
//! - Arrhenius: L = A (1/T − 1/T_ref), T in K, A = E_a/(R ln 10); linear.
//! - WLF–Arrhenius (the usual description of amorphous polymers through
//!   T_g: free-volume WLF above, an activated process below; Ferry ch. 11):
//!   f(T) = −C1 z(max(T, T_g)) + A [u(T) − u(T_g)] for T < T_g, with
//!   z = ΔT/(C2 + ΔT), u = 1/T; L = f − f(T_ref). Continuous at T_g.
//!   Linear in (C1, A) for fixed (C2, T_g); T_g scanned at the
//!   midpoints between isotherms, C2 on the grid, then Gauss–Newton on
//!   (C1, C2, A).
//!
//! Errors: covariance (JᵀWJ)⁻¹, scaled by χ²/dof where that exceeds 1
//! (Birge), so a law that misses the shifts does not claim their
//! precision. The test: p = P(χ²_dof ≥ χ²), dof = pairs − parameters (T_g
//! counts as one); a law is accepted at p ≥ [`LAW_P_VALUE`].
//!
//! # References
//! - M.L. Williams, R.F. Landel, J.D. Ferry, J. Am. Chem. Soc. 77, 3701
//!   (1955).
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 11 (WLF and Arrhenius regimes).
//! - P.R. Bevington, D.K. Robinson, *Data Reduction and Error Analysis for
//!   the Physical Sciences*, 3rd ed., McGraw-Hill 2003, ch. 8 and 11.

use nalgebra::{DMatrix, DVector};
use rollfit_model::modulus::{GAS_CONSTANT, ZERO_CELSIUS};
use statrs::distribution::{ChiSquared, ContinuousCDF};

/// p-value at or above which a law describes the shifts.
pub const LAW_P_VALUE: f64 = 0.01;

/// One determined pair as the laws see it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PairObservation {
    /// Colder isotherm, °C.
    pub t_lower: f64,
    /// Warmer isotherm, °C.
    pub t_upper: f64,
    /// log10 a_upper − log10 a_lower.
    pub shift: f64,
    /// Its 1σ, decades.
    pub sigma: f64,
}

/// The χ² test of a law against the determined shifts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawTest {
    /// χ² at the optimum.
    pub chi2: f64,
    /// Degrees of freedom: pairs − parameters.
    pub dof: usize,
    /// P(χ²_dof ≥ χ²); None without spare degrees of freedom.
    pub p_value: Option<f64>,
}

impl LawTest {
    fn new(chi2: f64, pairs: usize, parameters: usize) -> LawTest {
        let dof = pairs.saturating_sub(parameters);
        let p_value = (dof > 0)
            .then(|| ChiSquared::new(dof as f64).ok().map(|d| d.sf(chi2)))
            .flatten();
        LawTest { chi2, dof, p_value }
    }

    /// Whether the law describes the shifts within their errors (a law
    /// with no spare degree of freedom is not contradicted).
    pub fn passes(&self) -> bool {
        self.p_value.is_none_or(|p| p >= LAW_P_VALUE)
    }

    /// χ²/dof (NaN without degrees of freedom).
    fn birge(&self) -> f64 {
        if self.dof > 0 {
            (self.chi2 / self.dof as f64).max(1.0)
        } else {
            1.0
        }
    }
}

/// WLF constants fitted to measured shift factors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WlfFit {
    /// C1 (dimensionless).
    pub c1: f64,
    /// C2, K.
    pub c2: f64,
    /// 1σ of C1 (NaN without spare degrees of freedom).
    pub c1_sigma: f64,
    /// 1σ of C2, K.
    pub c2_sigma: f64,
    /// RMS of the determined measured shifts about the law, decades.
    pub rms: f64,
    /// The goodness-of-fit test.
    pub test: LawTest,
    covariance: [[f64; 2]; 2],
}

impl WlfFit {
    /// log10 a_T at `t` (°C) about `t_ref`, or None at and below the
    /// divergence T = T_ref − C2.
    pub fn log_shift(&self, t_ref: f64, t: f64) -> Option<f64> {
        let dt = t - t_ref;
        (self.c2 + dt > 0.0).then(|| -self.c1 * dt / (self.c2 + dt))
    }

    /// 1σ of log10 a_T at `t` from the constants' covariance.
    pub fn sigma_at(&self, t_ref: f64, t: f64) -> f64 {
        let dt = t - t_ref;
        let g = [-dt / (self.c2 + dt), self.c1 * dt / (self.c2 + dt).powi(2)];
        quadratic(&g, &self.covariance)
    }
}

/// An Arrhenius law fitted to measured shift factors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArrheniusFit {
    /// Activation energy E_a, J/mol.
    pub activation_energy: f64,
    /// 1σ of E_a, J/mol.
    pub activation_energy_sigma: f64,
    /// RMS of the determined measured shifts about the law, decades.
    pub rms: f64,
    /// The goodness-of-fit test.
    pub test: LawTest,
}

impl ArrheniusFit {
    /// log10 a_T at `t` (°C) about `t_ref`.
    pub fn log_shift(&self, t_ref: f64, t: f64) -> f64 {
        self.activation_energy / to_energy() * (inverse_kelvin(t) - inverse_kelvin(t_ref))
    }

    /// 1σ of log10 a_T at `t`.
    pub fn sigma_at(&self, t_ref: f64, t: f64) -> f64 {
        (self.activation_energy_sigma / to_energy() * (inverse_kelvin(t) - inverse_kelvin(t_ref)))
            .abs()
    }
}

/// WLF above the junction T_g, Arrhenius below, continuous at T_g.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WlfArrheniusFit {
    /// WLF C1 about T_ref.
    pub c1: f64,
    /// WLF C2 about T_ref, K.
    pub c2: f64,
    /// The junction, °C.
    pub t_junction: f64,
    /// Activation energy below the junction, J/mol.
    pub activation_energy: f64,
    /// 1σ of C1, C2 (K) and E_a (J/mol), T_g held at its value.
    pub sigma: [f64; 3],
    /// RMS of the determined measured shifts about the law, decades.
    pub rms: f64,
    /// The goodness-of-fit test (T_g counted as a parameter).
    pub test: LawTest,
    covariance: [[f64; 3]; 3],
}

impl WlfArrheniusFit {
    /// The law's shape f(T) (not yet 0 at T_ref) and its gradient in
    /// (C1, C2, A); None below the WLF divergence.
    fn shape(&self, t_ref: f64, t: f64) -> Option<(f64, [f64; 3])> {
        let a = self.activation_energy / to_energy();
        two_branch_shape(t_ref, self.t_junction, self.c1, self.c2, a, t)
    }

    /// log10 a_T at `t` (°C) about `t_ref`.
    pub fn log_shift(&self, t_ref: f64, t: f64) -> Option<f64> {
        Some(self.shape(t_ref, t)?.0 - self.shape(t_ref, t_ref)?.0)
    }

    /// 1σ of log10 a_T at `t`.
    pub fn sigma_at(&self, t_ref: f64, t: f64) -> f64 {
        match (self.shape(t_ref, t), self.shape(t_ref, t_ref)) {
            (Some((_, g)), Some((_, g0))) => {
                let d = [g[0] - g0[0], g[1] - g0[1], g[2] - g0[2]];
                quadratic(&d, &self.covariance)
            }
            _ => f64::NAN,
        }
    }
}

/// f(T) of the two-branch law and ∂f/∂(C1, C2, A), A in K (E_a/(R ln 10)).
fn two_branch_shape(
    t_ref: f64,
    t_g: f64,
    c1: f64,
    c2: f64,
    a: f64,
    t: f64,
) -> Option<(f64, [f64; 3])> {
    let upper = t.max(t_g);
    let dt = upper - t_ref;
    if c2 + dt <= 0.0 {
        return None;
    }
    let z = dt / (c2 + dt);
    let below = if t < t_g {
        inverse_kelvin(t) - inverse_kelvin(t_g)
    } else {
        0.0
    };
    Some((
        -c1 * z + a * below,
        [-z, c1 * dt / (c2 + dt).powi(2), below],
    ))
}

fn to_energy() -> f64 {
    GAS_CONSTANT * std::f64::consts::LN_10
}

fn inverse_kelvin(t: f64) -> f64 {
    1.0 / (t + ZERO_CELSIUS)
}

/// √(gᵀ C g).
fn quadratic<const N: usize>(g: &[f64; N], c: &[[f64; N]; N]) -> f64 {
    let mut s = 0.0;
    for i in 0..N {
        for j in 0..N {
            s += g[i] * c[i][j] * g[j];
        }
    }
    s.max(0.0).sqrt()
}

/// Weighted linear least squares of the pair differences of basis
/// functions `basis(T)` (q of them): (coefficients, χ²), None if singular.
fn linear_pairs(
    pairs: &[PairObservation],
    q: usize,
    basis: &dyn Fn(f64) -> Option<Vec<f64>>,
) -> Option<(Vec<f64>, f64)> {
    let mut rows = Vec::with_capacity(pairs.len());
    for p in pairs {
        let (lo, hi) = (basis(p.t_lower)?, basis(p.t_upper)?);
        let row: Vec<f64> = (0..q).map(|k| (hi[k] - lo[k]) / p.sigma).collect();
        rows.push((row, p.shift / p.sigma));
    }
    let a = DMatrix::from_fn(rows.len(), q, |i, k| rows[i].0[k]);
    let b = DVector::from_iterator(rows.len(), rows.iter().map(|r| r.1));
    let normal = a.transpose() * &a;
    let solution = normal.cholesky()?.solve(&(a.transpose() * &b));
    let chi2 = (&a * &solution - &b).norm_squared();
    Some((solution.iter().copied().collect(), chi2))
}

/// A law's f(T; θ) and ∂f/∂θ, None where θ is not allowed.
type LawShape<'a, const N: usize> = dyn Fn(&[f64; N], f64) -> Option<(f64, [f64; N])> + 'a;

/// Gauss–Newton on a law's continuous parameters from `start`, minimising
/// the pairs' χ²: (parameters, χ², the unscaled covariance (JᵀWJ)⁻¹).
/// `law(θ, T)` gives f(T) and ∂f/∂θ, or None where θ is not allowed.
fn polish<const N: usize>(
    pairs: &[PairObservation],
    start: [f64; N],
    law: &LawShape<'_, N>,
) -> Option<([f64; N], f64, [[f64; N]; N])> {
    let system = |theta: &[f64; N]| -> Option<(DMatrix<f64>, DVector<f64>)> {
        let mut j = DMatrix::zeros(pairs.len(), N);
        let mut r = DVector::zeros(pairs.len());
        for (i, p) in pairs.iter().enumerate() {
            let (lo, glo) = law(theta, p.t_lower)?;
            let (hi, ghi) = law(theta, p.t_upper)?;
            r[i] = (p.shift - (hi - lo)) / p.sigma;
            for k in 0..N {
                j[(i, k)] = (ghi[k] - glo[k]) / p.sigma;
            }
        }
        Some((j, r))
    };
    let mut theta = start;
    let (mut j, mut r) = system(&theta)?;
    for _ in 0..60 {
        let normal = j.transpose() * &j;
        let Some(step) = normal
            .clone()
            .cholesky()
            .map(|c| c.solve(&(j.transpose() * &r)))
        else {
            break;
        };
        let mut next = theta;
        for k in 0..N {
            next[k] += step[k];
        }
        match system(&next) {
            Some((nj, nr)) if nr.norm_squared() < r.norm_squared() => {
                let small = step.norm() < 1e-12 * (1.0 + next.iter().map(|x| x.abs()).sum::<f64>());
                theta = next;
                (j, r) = (nj, nr);
                if small {
                    break;
                }
            }
            _ => break,
        }
    }
    let inverse = (j.transpose() * &j).try_inverse()?;
    let mut covariance = [[0.0; N]; N];
    for a in 0..N {
        for b in 0..N {
            covariance[a][b] = inverse[(a, b)];
        }
    }
    Some((theta, r.norm_squared(), covariance))
}

fn scaled<const N: usize>(mut c: [[f64; N]; N], factor: f64) -> [[f64; N]; N] {
    for row in &mut c {
        for x in row {
            *x *= factor;
        }
    }
    c
}

/// The C2 grid: floor + 10^(−1 … 4) K.
fn c2_grid(floor: f64) -> impl Iterator<Item = f64> {
    (0..=250).map(move |i| floor + 10f64.powf(-1.0 + 5.0 * i as f64 / 250.0))
}

/// C2 + ΔT must stay positive at every temperature `temps` reaches.
fn c2_floor(t_ref: f64, lowest: f64) -> f64 {
    (t_ref - lowest).max(0.0)
}

fn temperatures(pairs: &[PairObservation]) -> Vec<f64> {
    let mut t: Vec<f64> = pairs.iter().flat_map(|p| [p.t_lower, p.t_upper]).collect();
    t.sort_by(f64::total_cmp);
    t.dedup();
    t
}

/// WLF fitted to the pairs; None with fewer than two pairs or no positive
/// C1.
pub(crate) fn fit_wlf(pairs: &[PairObservation], t_ref: f64) -> Option<WlfFit> {
    if pairs.len() < 2 {
        return None;
    }
    let temps = temperatures(pairs);
    let floor = c2_floor(t_ref, temps[0]);
    let mut best: Option<(f64, f64, f64)> = None;
    for c2 in c2_grid(floor) {
        let basis = |t: f64| Some(vec![-(t - t_ref) / (c2 + t - t_ref)]);
        let Some((c, chi2)) = linear_pairs(pairs, 1, &basis) else {
            continue;
        };
        if c[0] > 0.0 && best.is_none_or(|b| chi2 < b.0) {
            best = Some((chi2, c[0], c2));
        }
    }
    let (_, c1, c2) = best?;
    let law = |theta: &[f64; 2], t: f64| -> Option<(f64, [f64; 2])> {
        let dt = t - t_ref;
        let d = theta[1] + dt;
        (d > 0.0 && theta[1] > floor && theta[0] > 0.0)
            .then(|| (-theta[0] * dt / d, [-dt / d, theta[0] * dt / (d * d)]))
    };
    let (theta, chi2, covariance) = polish(pairs, [c1, c2], &law)?;
    let test = LawTest::new(chi2, pairs.len(), 2);
    let covariance = scaled(covariance, test.birge());
    Some(WlfFit {
        c1: theta[0],
        c2: theta[1],
        c1_sigma: covariance[0][0].sqrt(),
        c2_sigma: covariance[1][1].sqrt(),
        rms: f64::NAN,
        test,
        covariance,
    })
}

/// Arrhenius fitted to the pairs; None without a pair.
pub(crate) fn fit_arrhenius(pairs: &[PairObservation], t_ref: f64) -> Option<ArrheniusFit> {
    if pairs.is_empty() {
        return None;
    }
    let basis = |t: f64| Some(vec![inverse_kelvin(t) - inverse_kelvin(t_ref)]);
    let (c, chi2) = linear_pairs(pairs, 1, &basis)?;
    let test = LawTest::new(chi2, pairs.len(), 1);
    // Unscaled variance of A: 1/Σ w (Δu)².
    let information: f64 = pairs
        .iter()
        .map(|p| ((inverse_kelvin(p.t_upper) - inverse_kelvin(p.t_lower)) / p.sigma).powi(2))
        .sum();
    let sigma = (test.birge() / information).sqrt();
    Some(ArrheniusFit {
        activation_energy: c[0] * to_energy(),
        activation_energy_sigma: sigma * to_energy(),
        rms: f64::NAN,
        test,
    })
}

/// WLF above a junction and Arrhenius below, fitted to the pairs; None
/// with fewer than four pairs or where no junction leaves at least one
/// pair below it and two above with positive C1 and E_a.
pub(crate) fn fit_wlf_arrhenius(pairs: &[PairObservation], t_ref: f64) -> Option<WlfArrheniusFit> {
    if pairs.len() < 4 {
        return None;
    }
    let temps = temperatures(pairs);
    let mut best: Option<(f64, f64, f64, f64, f64)> = None;
    for w in temps.windows(2) {
        let t_g = 0.5 * (w[0] + w[1]);
        let below = pairs.iter().filter(|p| p.t_lower < t_g).count();
        let above = pairs.iter().filter(|p| p.t_upper > t_g).count();
        if below < 1 || above < 2 {
            continue;
        }
        let floor = c2_floor(t_ref, t_g.max(temps[0]));
        for c2 in c2_grid(floor) {
            let basis = |t: f64| {
                two_branch_shape(t_ref, t_g, 1.0, c2, 0.0, t).map(|(_, g)| vec![g[0], g[2]])
            };
            let Some((c, chi2)) = linear_pairs(pairs, 2, &basis) else {
                continue;
            };
            if c[0] > 0.0 && c[1] > 0.0 && best.is_none_or(|b| chi2 < b.0) {
                best = Some((chi2, c[0], c2, c[1], t_g));
            }
        }
    }
    let (_, c1, c2, a, t_g) = best?;
    let floor = c2_floor(t_ref, t_g.max(temps[0]));
    let law = |theta: &[f64; 3], t: f64| -> Option<(f64, [f64; 3])> {
        if theta[0] <= 0.0 || theta[2] <= 0.0 || theta[1] <= floor {
            return None;
        }
        two_branch_shape(t_ref, t_g, theta[0], theta[1], theta[2], t)
    };
    let (theta, chi2, covariance) = polish(pairs, [c1, c2, a], &law)?;
    let test = LawTest::new(chi2, pairs.len(), 4);
    // The covariance stays in (C1, C2, A), as σ propagation uses A.
    let covariance = scaled(covariance, test.birge());
    let sigma = [
        covariance[0][0].sqrt(),
        covariance[1][1].sqrt(),
        covariance[2][2].sqrt() * to_energy(),
    ];
    Some(WlfArrheniusFit {
        c1: theta[0],
        c2: theta[1],
        t_junction: t_g,
        activation_energy: theta[2] * to_energy(),
        sigma,
        rms: f64::NAN,
        test,
        covariance,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};

    /// Neighbour pairs of `law` at `temps` with σ and the given noise.
    fn pairs_of(
        temps: &[f64],
        law: &dyn Fn(f64) -> f64,
        sigma: f64,
        rng: &mut rand_chacha::ChaCha8Rng,
    ) -> Vec<PairObservation> {
        let normal = Normal::new(0.0, sigma).unwrap();
        temps
            .windows(2)
            .map(|w| PairObservation {
                t_lower: w[0],
                t_upper: w[1],
                shift: law(w[1]) - law(w[0]) + normal.sample(rng),
                sigma,
            })
            .collect()
    }

    /// WLF constants are recovered from exact pairs; with noise the
    /// reported σ of C1 matches the spread over many sets (slow oracle:
    /// a Monte Carlo of the same fit).
    #[test]
    fn wlf_from_pairs() {
        let temps: Vec<f64> = (0..8).map(|k| -30.0 + 15.0 * k as f64).collect();
        let (c1, c2) = (9.5, 130.0);
        let law = move |t: f64| -c1 * (t - 20.0) / (c2 + t - 20.0);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let exact = pairs_of(&temps, &law, 1e-9, &mut rng);
        let fit = fit_wlf(&exact, 20.0).unwrap();
        assert!(
            (fit.c1 - c1).abs() < 1e-4 && (fit.c2 - c2).abs() < 1e-3,
            "{fit:?}"
        );
        let (mut values, mut sigmas) = (Vec::new(), Vec::new());
        for _ in 0..300 {
            let noisy = pairs_of(&temps, &law, 0.03, &mut rng);
            let f = fit_wlf(&noisy, 20.0).unwrap();
            values.push(f.log_shift(20.0, 80.0).unwrap());
            sigmas.push(f.sigma_at(20.0, 80.0));
        }
        let n = values.len() as f64;
        let mean = values.iter().sum::<f64>() / n;
        let spread = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        let reported = sigmas.iter().sum::<f64>() / n;
        assert!(
            (reported / spread - 1.0).abs() < 0.25,
            "σ at 80 °C: reported {reported:.4} vs spread {spread:.4}"
        );
    }

    /// Arrhenius E_a from exact pairs, and its test passes on noise of the
    /// stated size about 99 % of the time.
    #[test]
    fn arrhenius_from_pairs() {
        let temps = [-20.0, 0.0, 20.0, 40.0, 60.0];
        let energy = 1.5e5;
        let law = move |t: f64| energy / to_energy() * (inverse_kelvin(t) - inverse_kelvin(20.0));
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let fit = fit_arrhenius(&pairs_of(&temps, &law, 1e-9, &mut rng), 20.0).unwrap();
        assert!(
            (fit.activation_energy / energy - 1.0).abs() < 1e-6,
            "{fit:?}"
        );
        let passed = (0..400)
            .filter(|_| {
                fit_arrhenius(&pairs_of(&temps, &law, 0.05, &mut rng), 20.0)
                    .unwrap()
                    .test
                    .passes()
            })
            .count();
        assert!((380..=400).contains(&passed), "{passed} of 400 passed");
    }

    /// A law with a kink at T_g: WLF fails its test, the two-branch law
    /// finds the junction and reproduces the shifts.
    #[test]
    fn two_branch_law_finds_the_kink() {
        let temps: Vec<f64> = (0..12).map(|k| -40.0 + 10.0 * k as f64).collect();
        let (c1, c2, t_g, energy) = (8.0, 120.0, -5.0, 2.5e5);
        let shape = |t: f64| {
            two_branch_shape(20.0, t_g, c1, c2, energy / to_energy(), t)
                .unwrap()
                .0
        };
        let law = move |t: f64| shape(t) - shape(20.0);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        let pairs = pairs_of(&temps, &law, 0.01, &mut rng);
        let wlf = fit_wlf(&pairs, 20.0).unwrap();
        assert!(!wlf.test.passes(), "{wlf:?}");
        let two = fit_wlf_arrhenius(&pairs, 20.0).unwrap();
        assert!(two.test.passes(), "{two:?}");
        for &t in &temps {
            let got = two.log_shift(20.0, t).unwrap();
            assert!(
                (got - law(t)).abs() < 3.0 * two.sigma_at(20.0, t) + 0.02,
                "T = {t}: {got} vs {}",
                law(t)
            );
        }
    }
}
