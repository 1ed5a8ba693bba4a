//! Shared by the fit crate's tests: the bundled example's rolling set-up,
//! its broad-rubber truth, and synthetic measurements with seeded noise.

// Each test binary uses a different subset of these helpers.
#![allow(dead_code)]

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use rollfit_fit::{FitReport, Measurements, RollingSetup};
use rollfit_model::ViscoelasticModulus;
use rollfit_model::{ContactSize, Geometry, HavriliakNegami, Scene, Shape, Substrate};

/// A 5 mm steel ball at 1 N on a thick rubber block, ν = 0.5, dynamic
/// contact (data/hn-rubber.toml).
pub fn setup() -> RollingSetup {
    RollingSetup {
        geometry: Geometry {
            shape: Shape::Sphere,
            radius: 0.005,
            load: 1.0,
        },
        substrate: Substrate {
            poisson: 0.5,
            film_thickness: None,
        },
        contact: ContactSize::Dynamic,
    }
}

/// The bundled example's truth: a broad Havriliak–Negami rubber,
/// E0 = 2 MPa, E1 = 2 GPa, τ = 1 ms, α = 0.55, β = 0.4.
pub fn hn_rubber() -> HavriliakNegami {
    HavriliakNegami::new(2e6, 2e9, 1e-3, 0.55, 0.4).unwrap()
}

/// μ of `truth` at 41 speeds over 8 decades (1e-8 … 1 m/s) with
/// multiplicative Gaussian noise of relative size `noise` (ChaCha8 with
/// `seed`), and σ = noise·μ.
pub fn synthetic<M: ViscoelasticModulus>(truth: M, noise: f64, seed: u64) -> Measurements {
    let s = setup();
    let scene = Scene::new(s.geometry, s.substrate, s.contact, truth).unwrap();
    let speeds: Vec<f64> = (0..41).map(|i| 1e-8 * 10f64.powf(i as f64 * 0.2)).collect();
    let mu = scene.friction_sweep(&speeds).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let normal = Normal::new(0.0, 1.0).unwrap();
    let noisy: Vec<f64> = mu
        .iter()
        .map(|m| m * (1.0 + noise * normal.sample(&mut rng)))
        .collect();
    let sigma: Vec<f64> = mu.iter().map(|m| noise * m).collect();
    Measurements::new(speeds, noisy, Some(sigma), None).unwrap()
}

/// The WLF truth of the synthetic temperature sets: C1 = 8.86,
/// C2 = 101.6 K at T_ref = 20 °C (log10 a_T).
pub fn wlf_truth(t: f64) -> f64 {
    -8.86 * (t - 20.0) / (101.6 + t - 20.0)
}

/// A temperature set of `truth` (the master curve at 20 °C) under the WLF
/// truth: 41 speeds over 8 decades at each of `temperatures`, multiplicative
/// Gaussian noise of relative size `noise` (ChaCha8 with `seed`, drawn in
/// row order), σ = noise·μ.
pub fn temperature_set<M: ViscoelasticModulus>(
    truth: M,
    temperatures: &[f64],
    noise: f64,
    seed: u64,
) -> Measurements {
    let s = setup();
    let scene = Scene::new(s.geometry, s.substrate, s.contact, truth).unwrap();
    let speeds: Vec<f64> = (0..41).map(|i| 1e-8 * 10f64.powf(i as f64 * 0.2)).collect();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let normal = Normal::new(0.0, 1.0).unwrap();
    let (mut v, mut mu, mut sigma, mut temps) = (vec![], vec![], vec![], vec![]);
    for &t in temperatures {
        let a = 10f64.powf(wlf_truth(t));
        let reduced: Vec<f64> = speeds.iter().map(|x| x * a).collect();
        for (x, m) in speeds.iter().zip(scene.friction_sweep(&reduced).unwrap()) {
            v.push(*x);
            mu.push(m * (1.0 + noise * normal.sample(&mut rng)));
            sigma.push(noise * m);
            temps.push(t);
        }
    }
    Measurements::new(v, mu, Some(sigma), Some(temps)).unwrap()
}

/// RMS relative errors of tan δ and |E| against `truth` over the reported
/// window shrunk by half a decade at each end, and the number of curve
/// points compared.
pub fn window_errors<M: ViscoelasticModulus>(report: &FitReport, truth: &M) -> (f64, f64, usize) {
    let lo = report.window.omega_min * 10f64.powf(0.5);
    let hi = report.window.omega_max / 10f64.powf(0.5);
    let (mut se_t, mut se_e, mut n) = (0.0, 0.0, 0);
    for p in report
        .curve
        .iter()
        .filter(|p| p.omega >= lo && p.omega <= hi)
    {
        let e = truth.modulus(p.omega);
        se_t += (p.tan_delta / (e.im / e.re) - 1.0).powi(2);
        se_e += (p.magnitude / e.norm() - 1.0).powi(2);
        n += 1;
    }
    let n_f = n.max(1) as f64;
    ((se_t / n_f).sqrt(), (se_e / n_f).sqrt(), n)
}
