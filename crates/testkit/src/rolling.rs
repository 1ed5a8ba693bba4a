//! Rolling set-ups and synthetic measurements: μ(v) of a known truth
//! under the bundled example's ball (or a cylinder), with multiplicative
//! Gaussian noise drawn from ChaCha8 with a fixed seed, at one temperature
//! or a set shifted by a known law; and how close a fitted curve comes to
//! its truth (RMS errors and band coverage over the determined window).

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use rollfit_fit::{FitReport, Measurements, RollingSetup};
use rollfit_model::ViscoelasticModulus;
use rollfit_model::{ContactSize, Geometry, Scene, Shape, Substrate};

use crate::materials::hn_rubber;

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

/// μ of `truth` at 41 speeds over 8 decades (1e-8 … 1 m/s) with
/// multiplicative Gaussian noise of relative size `noise` (ChaCha8 with
/// `seed`), and σ = noise·μ.
pub fn synthetic<M: ViscoelasticModulus>(truth: M, noise: f64, seed: u64) -> Measurements {
    let s = setup();
    let scene = Scene::new(s.geometry, s.substrate, s.contact, truth).unwrap();
    let speeds: Vec<f64> = (0..41).map(|i| 1e-8 * 10f64.powf(i as f64 * 0.2)).collect();
    let mu = scene.friction_sweep(&speeds).unwrap();
    with_noise(&speeds, &mu, noise, seed)
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
    let speeds: Vec<f64> = (0..41).map(|i| 1e-8 * 10f64.powf(i as f64 * 0.2)).collect();
    shifted_set(truth, temperatures, &speeds, noise, seed, true)
}

/// A laboratory-shaped temperature set: `count` speeds over
/// `decades` from `v_min` at each of `temperatures`, the master curve
/// `truth` at 20 °C shifted by the WLF truth, relative noise `noise`, no
/// sigma column.
pub fn sparse_temperature_set<M: ViscoelasticModulus>(
    truth: M,
    temperatures: &[f64],
    v_min: f64,
    decades: f64,
    count: usize,
    noise: f64,
    seed: u64,
) -> Measurements {
    let speeds: Vec<f64> = (0..count)
        .map(|i| v_min * 10f64.powf(decades * i as f64 / (count - 1) as f64))
        .collect();
    shifted_set(truth, temperatures, &speeds, noise, seed, false)
}

/// μ at `speeds` at each of `temperatures` (WLF truth about 20 °C), with
/// multiplicative Gaussian noise drawn in row order, and σ = noise·μ when
/// `with_sigma`.
fn shifted_set<M: ViscoelasticModulus>(
    truth: M,
    temperatures: &[f64],
    speeds: &[f64],
    noise: f64,
    seed: u64,
    with_sigma: bool,
) -> Measurements {
    set_with_shifts(
        truth,
        temperatures,
        speeds,
        wlf_truth,
        noise,
        seed,
        with_sigma,
    )
}

/// μ of `truth` (the master curve at 20 °C) at `speeds` at each of
/// `temperatures`, shifted by `log_shift` (log10 a_T of T in °C, 0 at
/// 20 °C), with multiplicative Gaussian noise of relative size `noise`
/// (ChaCha8 with `seed`, drawn in row order), and σ = noise·μ when
/// `with_sigma`.
pub fn set_with_shifts<M: ViscoelasticModulus>(
    truth: M,
    temperatures: &[f64],
    speeds: &[f64],
    log_shift: impl Fn(f64) -> f64,
    noise: f64,
    seed: u64,
    with_sigma: bool,
) -> Measurements {
    let s = setup();
    let scene = Scene::new(s.geometry, s.substrate, s.contact, truth).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let normal = Normal::new(0.0, 1.0).unwrap();
    let (mut v, mut mu, mut sigma, mut temps) = (vec![], vec![], vec![], vec![]);
    for &t in temperatures {
        let a = 10f64.powf(log_shift(t));
        let reduced: Vec<f64> = speeds.iter().map(|x| x * a).collect();
        for (x, m) in speeds.iter().zip(scene.friction_sweep(&reduced).unwrap()) {
            v.push(*x);
            mu.push(m * (1.0 + noise * normal.sample(&mut rng)));
            sigma.push(noise * m);
            temps.push(t);
        }
    }
    Measurements::new(v, mu, with_sigma.then_some(sigma), Some(temps)).unwrap()
}

/// The reported curve's points inside the window shrunk by half a decade
/// at each end.
fn inner_window(report: &FitReport) -> impl Iterator<Item = &rollfit_fit::ModulusPoint> {
    let lo = report.window.omega_min * 10f64.powf(0.5);
    let hi = report.window.omega_max / 10f64.powf(0.5);
    report
        .curve
        .iter()
        .filter(move |p| p.omega >= lo && p.omega <= hi)
}

/// RMS relative errors of tan δ and |E| against `truth` over the reported
/// window shrunk by half a decade at each end, and the number of curve
/// points compared.
pub fn window_errors<M: ViscoelasticModulus>(report: &FitReport, truth: &M) -> (f64, f64, usize) {
    let (mut se_t, mut se_e, mut n) = (0.0, 0.0, 0);
    for p in inner_window(report) {
        let e = truth.modulus(p.omega);
        se_t += (p.tan_delta / (e.im / e.re) - 1.0).powi(2);
        se_e += (p.magnitude / e.norm() - 1.0).powi(2);
        n += 1;
    }
    let n_f = n.max(1) as f64;
    ((se_t / n_f).sqrt(), (se_e / n_f).sqrt(), n)
}

/// A cylinder of radius 10 mm at 200 N/m on a thick rubber block, ν = 0.49,
/// dynamic contact.
pub fn cylinder_setup() -> RollingSetup {
    RollingSetup {
        geometry: Geometry {
            shape: Shape::Cylinder,
            radius: 0.01,
            load: 200.0,
        },
        substrate: Substrate {
            poisson: 0.49,
            film_thickness: None,
        },
        contact: ContactSize::Dynamic,
    }
}

/// Laboratory-shaped data: `count` log-spaced speeds from `v_min` over
/// `decades` decades, μ of `truth` under `setup` with multiplicative
/// Gaussian noise of relative size `noise` (ChaCha8 with `seed`), and no
/// sigma column.
pub fn sparse<M: ViscoelasticModulus>(
    setup: RollingSetup,
    truth: M,
    v_min: f64,
    decades: f64,
    count: usize,
    noise: f64,
    seed: u64,
) -> Measurements {
    let scene = Scene::new(setup.geometry, setup.substrate, setup.contact, truth).unwrap();
    let speeds: Vec<f64> = (0..count)
        .map(|i| v_min * 10f64.powf(decades * i as f64 / (count - 1) as f64))
        .collect();
    let mu = scene.friction_sweep(&speeds).unwrap();
    let noisy = noisy(&mu, noise, seed);
    Measurements::new(speeds, noisy, None, None).unwrap()
}

/// μ of `truth` under `setup` at `speeds`, without noise.
pub fn exact_friction<M: ViscoelasticModulus>(
    setup: RollingSetup,
    truth: M,
    speeds: &[f64],
) -> Vec<f64> {
    let scene = Scene::new(setup.geometry, setup.substrate, setup.contact, truth).unwrap();
    scene.friction_sweep(speeds).unwrap()
}

/// Whether a fit judged poor says, among its reasons, to try free shifts
/// (`shift = "free"`): the hint of a law the cross-check questions.
pub fn points_to_free_shifts(report: &FitReport) -> bool {
    report
        .fit_quality
        .reasons
        .iter()
        .any(|r| r.contains("shift = \"free\""))
}

/// Fraction of the reported curve's points inside the window shrunk by
/// half a decade at each end where the truth lies within `k` reported σ, for
/// tan δ and |E|.
pub fn band_coverage<M: ViscoelasticModulus>(report: &FitReport, truth: &M, k: f64) -> (f64, f64) {
    let (mut t, mut e, mut n) = (0, 0, 0);
    for p in inner_window(report) {
        let x = truth.modulus(p.omega);
        if (p.tan_delta - x.im / x.re).abs() <= k * p.tan_delta_sigma {
            t += 1;
        }
        if (p.magnitude - x.norm()).abs() <= k * p.magnitude_sigma {
            e += 1;
        }
        n += 1;
    }
    let n = n.max(1) as f64;
    (t as f64 / n, e as f64 / n)
}

/// A 5 mm cylinder at 1000 N/m on a thick rubber, ν = 0.5, dynamic
/// contact.
pub fn exact_cylinder_setup() -> RollingSetup {
    RollingSetup {
        geometry: Geometry {
            shape: Shape::Cylinder,
            radius: 0.005,
            load: 1000.0,
        },
        substrate: Substrate {
            poisson: 0.5,
            film_thickness: None,
        },
        contact: ContactSize::Dynamic,
    }
}

/// μ(v) of one material under one set-up by both physics.
#[derive(Debug, Clone)]
pub struct BothPhysics {
    /// m/s.
    pub speeds: Vec<f64>,
    /// μ of Eq. (11)/(17).
    pub approximate: Vec<f64>,
    /// μ of the exact contact.
    pub exact: Vec<f64>,
}

/// μ(v) of `truth` under `setup` at 41 speeds log-spaced over 8 decades
/// centred (in log v) on the friction maximum of Eq. (11)/(17): the
/// speeds, μ of the approximate model and μ of the exact contact
/// (`exact_body` at relative accuracy `accuracy`, speeds in parallel).
pub fn exact_and_approximate(
    setup: RollingSetup,
    truth: &rollfit_model::Prony,
    accuracy: f64,
) -> Result<BothPhysics, rollfit_model::ModelError> {
    use rayon::prelude::*;
    let g = setup.geometry;
    let scene = Scene::new(g, setup.substrate, setup.contact, truth.clone())?;
    let peak = scene.friction_maximum(1e-14, 1e3)?.speed;
    let speeds: Vec<f64> = (0..41)
        .map(|i| peak * 10f64.powf(-4.0 + 0.2 * i as f64))
        .collect();
    let approximate = scene.friction_sweep(&speeds)?;
    let body = rollfit_model::exact::exact_body(
        g.shape,
        truth,
        setup.substrate.poisson,
        g.radius,
        g.load,
        accuracy,
    )?;
    let exact = speeds
        .par_iter()
        .map(|&v| body.exact_friction(v).map(|x| x.mu))
        .collect::<Result<Vec<f64>, _>>()?;
    Ok(BothPhysics {
        speeds,
        approximate,
        exact,
    })
}

/// `mu` times (1 + `noise`·n) with n standard normal, drawn in order from
/// ChaCha8 with `seed`: the noise of every synthetic measurement here.
pub fn noisy(mu: &[f64], noise: f64, seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let normal = Normal::new(0.0, 1.0).unwrap();
    mu.iter()
        .map(|m| m * (1.0 + noise * normal.sample(&mut rng)))
        .collect()
}

/// RMS relative error of tan δ against `truth` over the whole reported
/// window (modulus.csv).
pub fn tan_delta_rms(report: &FitReport, truth: &impl ViscoelasticModulus) -> f64 {
    let n = report.curve.len().max(1) as f64;
    let sum: f64 = report
        .curve
        .iter()
        .map(|p| {
            let e = truth.modulus(p.omega);
            (p.tan_delta / (e.im / e.re) - 1.0).powi(2)
        })
        .sum();
    (sum / n).sqrt()
}

/// `mu` at `speeds` with multiplicative Gaussian noise of relative size
/// `noise` (ChaCha8 with `seed`), and σ = noise·μ.
pub fn with_noise(speeds: &[f64], mu: &[f64], noise: f64, seed: u64) -> Measurements {
    let noisy = noisy(mu, noise, seed);
    let sigma: Vec<f64> = mu.iter().map(|m| noise * m).collect();
    Measurements::new(speeds.to_vec(), noisy, Some(sigma), None).unwrap()
}

/// The cost study's temperature set: the bundled rubber at 7 temperatures
/// (−25 … 65 °C in 15 K steps, T_ref = 20 °C among them) × 21 speeds (1e-8 … 1 m/s, 0.4 decade
/// apart) under the WLF truth, 1 % noise (ChaCha8 with `seed`), σ known.
pub fn set_7x21(seed: u64) -> Measurements {
    let temperatures: Vec<f64> = (0..7).map(|k| -25.0 + 15.0 * k as f64).collect();
    let speeds: Vec<f64> = (0..21).map(|i| 1e-8 * 10f64.powf(0.4 * i as f64)).collect();
    set_with_shifts(
        hn_rubber(),
        &temperatures,
        &speeds,
        wlf_truth,
        0.01,
        seed,
        true,
    )
}

/// The fit of [`set_7x21`]: shift `kind` about 20 °C, |E| at 10 rad/s as
/// the anchor, no cross-check (the joint fit alone).
pub fn set_7x21_params(kind: rollfit_fit::ShiftKind) -> rollfit_fit::ValidFitParams {
    rollfit_fit::FitParams {
        anchor: Some(rollfit_fit::ScaleAnchor::ModulusAt {
            omega: 10.0,
            modulus: hn_rubber().modulus(10.0).norm(),
        }),
        shift: rollfit_fit::ShiftSettings {
            kind,
            t_ref: Some(20.0),
            cross_check: false,
            ..rollfit_fit::ShiftSettings::default()
        },
        ..rollfit_fit::FitParams::default()
    }
    .check(setup())
    .unwrap()
}
