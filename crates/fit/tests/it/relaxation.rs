//! Time-domain master curves: isotherms of the relaxation modulus E(t)
//! or of the creep compliance D(t)
//! made from a known Prony series under known WLF shifts, with 1 %
//! multiplicative noise, superposed and fitted; the shifts, E(t) or D(t)
//! and μ(v) of the series are held against the truth.

use rollfit_testkit::rolling;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use rollfit_fit::master::relaxation::{
    RelaxationIsotherm, TimeQuantity, build_relaxation_master, build_time_master,
    relaxation_shift_factors, time_turn,
};
use rollfit_fit::master::{MasterSettings, ShiftLaw};
use rollfit_model::exact::CreepCompliance;
use rollfit_model::{Prony, Scene};
use rollfit_testkit::materials::relaxation_truth;

/// Relaxation isotherms at `temperatures` ([`time_isotherms`]).
fn isotherms(temperatures: &[f64], seed: u64) -> Vec<RelaxationIsotherm> {
    time_isotherms(TimeQuantity::Relaxation, temperatures, seed)
}

/// Isotherms of `quantity` at `temperatures`: 31 times over 1 … 1000 s
/// (10 per decade, three decades), E(t, T) = E_ref(t/a_T) or
/// D(t, T) = D_ref(t/a_T) (the truth's exact creep compliance) under the
/// WLF truth, times (1 + 0.01 n) with n standard normal from
/// ChaCha8(`seed`) in row order.
fn time_isotherms(
    quantity: TimeQuantity,
    temperatures: &[f64],
    seed: u64,
) -> Vec<RelaxationIsotherm> {
    let truth = quantity.of_series(&relaxation_truth());
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let normal = Normal::new(0.0, 1.0).unwrap();
    temperatures
        .iter()
        .map(|&temperature| {
            let a = 10f64.powf(rolling::wlf_truth(temperature));
            let time: Vec<f64> = (0..=30).map(|j| 10f64.powf(j as f64 / 10.0)).collect();
            let value = time
                .iter()
                .map(|&t| truth(t / a) * (1.0 + 0.01 * normal.sample(&mut rng)))
                .collect();
            RelaxationIsotherm {
                temperature,
                time,
                value,
            }
        })
        .collect()
}

const TEMPERATURES: [f64; 6] = [-20.0, -10.0, 0.0, 10.0, 20.0, 30.0];

/// Shifts within 0.05 decade of the WLF truth, E(t) of the fitted series
/// within 2 % of the truth over the reduced window, and μ(v) of a ball
/// rolling on it within 2 % at the speeds that probe that window; for
/// three noise seeds.
#[test]
fn recovers_shifts_relaxation_and_friction() {
    for seed in [1, 2, 3] {
        let sets = isotherms(&TEMPERATURES, seed);
        let settings = MasterSettings::default().check_relaxation(&sets).unwrap();
        assert_eq!(settings.t_ref(), 20.0);
        let master = build_relaxation_master(&sets, &settings).unwrap();
        eprintln!("seed {seed}: {}", master.shift.reason);
        let mut worst_shift: f64 = 0.0;
        for s in &master.shift.shifts {
            let truth = rolling::wlf_truth(s.temperature);
            let measured = s.log_shift_measured.expect("every shift determined");
            worst_shift = worst_shift
                .max((s.log_shift - truth).abs())
                .max((measured - truth).abs());
        }
        assert!(worst_shift < 0.05, "seed {seed}: shift error {worst_shift}");

        let points = &master.points;
        let (t_lo, t_hi) = (
            points[0].reduced_time,
            points[points.len() - 1].reduced_time,
        );
        let truth = relaxation_truth();
        let fitted = &master.fit.prony;
        let worst_modulus = (0..=200)
            .map(|j| t_lo * (t_hi / t_lo).powf(j as f64 / 200.0))
            .map(|t| (fitted.relaxation_modulus(t) / truth.relaxation_modulus(t) - 1.0).abs())
            .fold(0.0, f64::max);
        assert!(
            worst_modulus < 0.02,
            "seed {seed}: E(t) error {worst_modulus}"
        );

        let worst_mu = friction_error(&truth, fitted, (t_lo, t_hi));
        assert!(worst_mu < 0.02, "seed {seed}: μ(v) error {worst_mu}");
        eprintln!(
            "seed {seed}: shift {worst_shift:.4} decades, E(t) {:.3} %, μ(v) {:.3} %",
            100.0 * worst_modulus,
            100.0 * worst_mu
        );
    }
}

/// Creep: shifts within 0.05 decade of the WLF truth, the fitted series'
/// exact creep compliance within 2 % of the truth's over the reduced
/// window, and μ(v) of a ball rolling on the series within 2 % at the
/// speeds that probe that window; for three noise seeds.
#[test]
fn recovers_shifts_creep_and_friction() {
    for seed in [1, 2, 3] {
        let sets = time_isotherms(TimeQuantity::Creep, &TEMPERATURES, seed);
        let settings = MasterSettings::default()
            .check_time(&sets, TimeQuantity::Creep)
            .unwrap();
        let master = build_time_master(&sets, TimeQuantity::Creep, &settings).unwrap();
        eprintln!("seed {seed}: {}", master.shift.reason);
        let mut worst_shift: f64 = 0.0;
        for s in &master.shift.shifts {
            let truth = rolling::wlf_truth(s.temperature);
            let measured = s.log_shift_measured.expect("every shift determined");
            worst_shift = worst_shift
                .max((s.log_shift - truth).abs())
                .max((measured - truth).abs());
        }
        assert!(worst_shift < 0.05, "seed {seed}: shift error {worst_shift}");

        let points = &master.points;
        let (t_lo, t_hi) = (
            points[0].reduced_time,
            points[points.len() - 1].reduced_time,
        );
        let truth = relaxation_truth();
        let (exact, fitted) = (
            CreepCompliance::from_prony(&truth),
            CreepCompliance::from_prony(&master.fit.prony),
        );
        let worst_compliance = (0..=200)
            .map(|j| t_lo * (t_hi / t_lo).powf(j as f64 / 200.0))
            .map(|t| (fitted.at(t) / exact.at(t) - 1.0).abs())
            .fold(0.0, f64::max);
        assert!(
            worst_compliance < 0.02,
            "seed {seed}: D(t) error {worst_compliance}"
        );
        let worst_mu = friction_error(&truth, &master.fit.prony, (t_lo, t_hi));
        assert!(worst_mu < 0.02, "seed {seed}: μ(v) error {worst_mu}");
        eprintln!(
            "seed {seed}: shift {worst_shift:.4} decades, D(t) {:.3} %, μ(v) {:.3} %, misfit {:.4} \
             decades",
            100.0 * worst_compliance,
            100.0 * worst_mu,
            master.fit.misfit
        );
    }
}

/// The largest relative μ(v) difference of the fitted series against the
/// truth at the speeds probing the reduced window [t_lo, t_hi].
///
/// Which speeds: a rolling sphere samples E*(ω) for ω from v/r to about
/// 10 v/r (r the contact radius, DESIGN.md §2), and E*(ω) is what the
/// relaxation data fix where 1/ω lies inside the window (E′(ω) ≈ E(t),
/// E″(ω) ≈ −(π/2) dE/d ln t at t = 1/ω: Ferry ch. 4), so the band must lie
/// in [1/t_hi, 1/t_lo]: v ≥ r/t_hi and 10 v ≤ r/t_lo. The radius depends
/// on the modulus sampled (Hertz, r = (3FR/(4E_eff))^⅓); the stiffest E in
/// the window gives the smallest r, the softest the largest. And E″(ω)
/// weighs the spectrum H(τ) by ωτ/(1 + ω²τ²), above half its peak for
/// ωτ in [2 − √3, 2 + √3] (±0.57 decade), so the band keeps a factor
/// m = 2 + √3 from the window's ends, where E(t) fixes H(τ) from one side
/// only: v ∈ [m r_max/t_hi, r_min/(10 m t_lo)], whatever the radius.
fn friction_error(truth: &Prony, fitted: &Prony, (t_lo, t_hi): (f64, f64)) -> f64 {
    let s = rolling::setup();
    let radius = |e: f64| {
        let effective = e / (1.0 - s.substrate.poisson.powi(2));
        (3.0 * s.geometry.load * s.geometry.radius / (4.0 * effective)).cbrt()
    };
    let (r_min, r_max) = (
        radius(truth.relaxation_modulus(t_lo)),
        radius(truth.relaxation_modulus(t_hi)),
    );
    let margin = 2.0 + 3f64.sqrt();
    let (v_lo, v_hi) = (margin * r_max / t_hi, r_min / (10.0 * margin * t_lo));
    assert!(
        v_hi > 10.0 * v_lo,
        "a window of speeds: {v_lo:e} … {v_hi:e}"
    );
    let decades = (v_hi / v_lo).log10();
    let count = (4.0 * decades).ceil() as usize;
    let speeds: Vec<f64> = (0..=count)
        .map(|i| v_lo * 10f64.powf(decades * i as f64 / count as f64))
        .collect();
    let mu = |m: &Prony| {
        Scene::new(s.geometry, s.substrate, s.contact, m.clone())
            .unwrap()
            .friction_sweep(&speeds)
            .unwrap()
    };
    mu(truth)
        .iter()
        .zip(mu(fitted))
        .map(|(t, f)| (f / t - 1.0).abs())
        .fold(0.0, f64::max)
}

/// The sign of the shift in time: a warmer isotherm relaxes sooner, so its
/// a_T < 1 (log10 a_T < 0 above T_ref) and its points move to longer
/// reduced times t/a_T; a colder one the reverse.
#[test]
fn warmer_isotherms_move_to_longer_times() {
    let sets = isotherms(&[10.0, 20.0, 30.0], 7);
    let settings = MasterSettings {
        law: ShiftLaw::Free,
        ..MasterSettings::default()
    }
    .check_relaxation(&sets)
    .unwrap();
    let shift = relaxation_shift_factors(&sets, &settings).unwrap();
    let at = |t: f64| {
        shift
            .shifts
            .iter()
            .find(|s| s.temperature == t)
            .unwrap()
            .log_shift
    };
    assert!(at(30.0) < -0.5 && at(10.0) > 0.5, "{:?}", shift.shifts);
    let master = build_relaxation_master(&sets, &settings).unwrap();
    for p in &master.points {
        match p.temperature {
            t if t > 20.0 => assert!(p.reduced_time > p.time),
            t if t < 20.0 => assert!(p.reduced_time < p.time),
            _ => assert_eq!(p.reduced_time, p.time),
        }
    }
}

/// Times that do not increase are refused, naming the points; the
/// turn is found where it is.
#[test]
fn refuses_times_that_do_not_increase() {
    assert_eq!(time_turn(&[1.0, 2.0, 3.0]), None);
    assert_eq!(time_turn(&[1.0, 2.0, 2.0, 3.0]), Some(2));
    assert_eq!(time_turn(&[1.0, 3.0, 2.0]), Some(2));
    let mut sets = isotherms(&[10.0, 20.0, 30.0], 7);
    sets[1].time.swap(4, 5);
    let error = MasterSettings::default()
        .check_relaxation(&sets)
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("points 5 and 6") && error.contains("20 °C"),
        "{error}"
    );
}
