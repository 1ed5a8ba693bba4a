//! The joint fit's synthetic case, shared by the fit crate's joint tests
//! and its benchmark: a truth with two relaxation processes (the broad rubber and a
//! slow filler tail), six DMA isotherms × ten frequencies (0.1 … 100 Hz)
//! under the WLF truth, and four rolling temperatures × twelve speeds
//! (1e-6 … 1 m/s).

use num_complex::Complex64;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use rollfit_fit::Measurements;
use rollfit_fit::master::Isotherm;
use rollfit_model::{HavriliakNegami, ViscoelasticModulus};

use crate::materials::hn_rubber;
use crate::rolling::{set_with_shifts, wlf_truth};

/// The broad rubber plus a slow, broad filler process (Cole–Cole,
/// τ = 30 s, strength 1.5 MPa): E* = E*_rubber + E*_filler − ε, the filler
/// written as a Havriliak–Negami with static modulus ε.
#[derive(Clone)]
pub struct TwoProcesses {
    rubber: HavriliakNegami,
    filler: HavriliakNegami,
}

const FILLER_FLOOR: f64 = 1.0;

pub fn truth() -> TwoProcesses {
    TwoProcesses {
        rubber: hn_rubber(),
        filler: HavriliakNegami::new(FILLER_FLOOR, 1.5e6 + FILLER_FLOOR, 30.0, 0.35, 1.0).unwrap(),
    }
}

impl ViscoelasticModulus for TwoProcesses {
    fn modulus(&self, omega: f64) -> Complex64 {
        self.rubber.modulus(omega) + self.filler.modulus(omega) - FILLER_FLOOR
    }
    fn modulus_and_log_slope(&self, omega: f64) -> (Complex64, Complex64) {
        let (a, da) = self.rubber.modulus_and_log_slope(omega);
        let (b, db) = self.filler.modulus_and_log_slope(omega);
        (a + b - FILLER_FLOOR, da + db)
    }
    fn static_modulus(&self) -> f64 {
        self.rubber.static_modulus() + self.filler.static_modulus() - FILLER_FLOOR
    }
    fn loss_slope_at_zero(&self) -> f64 {
        self.rubber.loss_slope_at_zero() + self.filler.loss_slope_at_zero()
    }
    fn loss_exponent_at_zero(&self) -> f64 {
        self.rubber
            .loss_exponent_at_zero()
            .min(self.filler.loss_exponent_at_zero())
    }
    fn structure_range(&self) -> (f64, f64) {
        let (a, b) = (self.rubber.structure_range(), self.filler.structure_range());
        (a.0.min(b.0), a.1.max(b.1))
    }
}

/// DMA temperatures, °C.
pub const DMA_TEMPERATURES: [f64; 6] = [-10.0, 0.0, 10.0, 20.0, 30.0, 40.0];
/// Rolling temperatures, °C.
pub const ROLLING_TEMPERATURES: [f64; 4] = [0.0, 20.0, 40.0, 60.0];

/// Six isotherms × ten frequencies 0.1 … 100 Hz of `truth` under the WLF
/// truth, E′ and E″ each with relative Gaussian noise `noise`.
pub fn dma_isotherms<M: ViscoelasticModulus>(truth: &M, noise: f64, seed: u64) -> Vec<Isotherm> {
    sampled_isotherms(truth, noise, seed, 10)
}

/// [`dma_isotherms`] with `count` frequencies per isotherm.
pub fn sampled_isotherms<M: ViscoelasticModulus>(
    truth: &M,
    noise: f64,
    seed: u64,
    count: usize,
) -> Vec<Isotherm> {
    let omega: Vec<f64> = (0..count)
        .map(|i| {
            let step = 3.0 * i as f64 / (count - 1) as f64;
            2.0 * std::f64::consts::PI * 0.1 * 10f64.powf(step)
        })
        .collect();
    isotherms_with_shifts(truth, &DMA_TEMPERATURES, &omega, wlf_truth, noise, seed)
}

/// Isotherms of `truth` at `temperatures` (°C), each at the frequencies
/// `omega` (rad/s), shifted by `log_shift` (log10 a_T of T, 0 at the
/// truth's reference), E′ and E″ each with relative Gaussian noise `noise`
/// (ChaCha8 with `seed`, drawn isotherm by isotherm, E′ before E″).
pub fn isotherms_with_shifts<M: ViscoelasticModulus>(
    truth: &M,
    temperatures: &[f64],
    omega: &[f64],
    log_shift: impl Fn(f64) -> f64,
    noise: f64,
    seed: u64,
) -> Vec<Isotherm> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let normal = Normal::new(0.0, noise).unwrap();
    temperatures
        .iter()
        .map(|&t| {
            let a = 10f64.powf(log_shift(t));
            let (mut storage, mut loss) = (Vec::new(), Vec::new());
            for &w in omega {
                let e = truth.modulus(w * a);
                storage.push(e.re * (1.0 + normal.sample(&mut rng)));
                loss.push(e.im * (1.0 + normal.sample(&mut rng)));
            }
            Isotherm {
                temperature: t,
                omega: omega.to_vec(),
                storage,
                loss,
            }
        })
        .collect()
}

/// Four temperatures × twelve speeds 1e-6 … 1 m/s, μ times `factor`, 2 %
/// noise, no σ column.
pub fn rolling<M: ViscoelasticModulus + Clone>(truth: &M, factor: f64, seed: u64) -> Measurements {
    let speeds: Vec<f64> = (0..12)
        .map(|i| 1e-6 * 10f64.powf(6.0 * i as f64 / 11.0))
        .collect();
    let set = set_with_shifts(
        truth.clone(),
        &ROLLING_TEMPERATURES,
        &speeds,
        wlf_truth,
        0.02,
        seed,
        false,
    );
    let mu = set.friction().iter().map(|m| m * factor).collect();
    Measurements::new(
        set.speeds().to_vec(),
        mu,
        None,
        set.temperature().map(|t| t.to_vec()),
    )
    .unwrap()
}
