//! The shift law of a temperature set chosen by the data
//! (`shift = "auto"`, the default), the Arrhenius law, and the σ of each
//! log10 a_T (fixed seeds).
//!
//! The truth: the bundled broad Havriliak–Negami rubber as the master curve
//! at 20 °C; 7 temperatures (−40 … 50 °C, 15 K apart) × 21 speeds over 5
//! decades (1 µm/s … 10 cm/s); 1 % noise with σ given; one scale anchor, |E|
//! at 10 rad/s at the fit's T_ref. The fit's settings are the defaults: its
//! T_ref is then the middle temperature, 5 °C, and the truth is compared
//! there.

use rollfit_testkit::materials::hn_rubber;
use rollfit_testkit::rolling::{
    points_to_free_shifts, set_with_shifts, setup, tan_delta_rms, wlf_truth,
};

use rollfit_fit::{FitParams, FitReport, Measurements, ScaleAnchor, ShiftKind, ShiftRecord, fit};
use rollfit_model::modulus::{GAS_CONSTANT, ZERO_CELSIUS};
use rollfit_model::{HavriliakNegami, Shifted, ViscoelasticModulus};

const TEMPERATURES: [f64; 7] = [-40.0, -25.0, -10.0, 5.0, 20.0, 35.0, 50.0];

/// The glass transition of the kinked truth, °C.
const T_GLASS: f64 = -10.0;
/// Its activation energy below T_g, J/mol: about half the slope of WLF at
/// T_g, as a glassy polymer's shifts flatten below T_g.
const ENERGY_BELOW: f64 = 1.2e5;

/// log10 a_T per unit E_a: (1/T − 1/T_0)/(R ln 10), T and T_0 in °C.
fn arrhenius_x(t: f64, t0: f64) -> f64 {
    (1.0 / (t + ZERO_CELSIUS) - 1.0 / (t0 + ZERO_CELSIUS)) / (GAS_CONSTANT * 10f64.ln())
}

/// Shifts that are not WLF: WLF (C1 = 8.86, C2 = 101.6 K about 20 °C)
/// above T_g, Arrhenius below it, continuous at T_g (a kink of the slope).
fn kinked_truth(t: f64) -> f64 {
    if t >= T_GLASS {
        wlf_truth(t)
    } else {
        wlf_truth(T_GLASS) + ENERGY_BELOW * arrhenius_x(t, T_GLASS)
    }
}

fn speeds() -> Vec<f64> {
    (0..21)
        .map(|i| 1e-6 * 10f64.powf(0.25 * i as f64))
        .collect()
}

fn data(log_shift: impl Fn(f64) -> f64, seed: u64) -> Measurements {
    set_with_shifts(
        hn_rubber(),
        &TEMPERATURES,
        &speeds(),
        log_shift,
        0.01,
        seed,
        true,
    )
}

/// The truth's master curve at the fit's reference temperature.
fn truth_at(log_shift: &impl Fn(f64) -> f64, t_ref: f64) -> Shifted<HavriliakNegami> {
    Shifted::new(hn_rubber(), log_shift(t_ref)).unwrap()
}

/// Default settings with `kind` and the anchor at 10 rad/s at the default
/// T_ref (the middle temperature, 5 °C) from `log_shift`.
fn params(kind: ShiftKind, log_shift: &impl Fn(f64) -> f64) -> rollfit_fit::ValidFitParams {
    params_at(kind, log_shift, None)
}

/// [`params`] with the reference temperature `t_ref` (None: the default).
fn params_at(
    kind: ShiftKind,
    log_shift: &impl Fn(f64) -> f64,
    t_ref: Option<f64>,
) -> rollfit_fit::ValidFitParams {
    let mut p = FitParams {
        anchor: Some(ScaleAnchor::ModulusAt {
            omega: 10.0,
            modulus: truth_at(log_shift, t_ref.unwrap_or(5.0))
                .modulus(10.0)
                .norm(),
        }),
        ..FitParams::default()
    };
    p.shift.kind = kind;
    p.shift.t_ref = t_ref;
    p.check(setup()).unwrap()
}

/// The largest |log10 a_T − truth| over the temperatures (both relative
/// to the fit's T_ref), with each printed.
fn worst_shift(report: &FitReport, log_shift: &impl Fn(f64) -> f64) -> f64 {
    let shift = report
        .shift
        .as_ref()
        .expect("a temperature set has a shift");
    let t_ref = shift.t_ref();
    let mut worst = 0.0f64;
    for s in shift.log_shifts() {
        let truth = log_shift(s.temperature) - log_shift(t_ref);
        eprintln!(
            "  T {:>5}: log a_T {:8.4} ± {:.4} (truth {truth:8.4})",
            s.temperature, s.log_shift, s.log_shift_sigma
        );
        worst = worst.max((s.log_shift - truth).abs());
    }
    worst
}

/// Shifts with a kink at T_g, which WLF does not
/// describe. With the default settings the fit succeeds (not poor),
/// every log10 a_T is within 0.05 decade of the truth and tan δ within 3 %
/// RMS over the fit's window; `auto` says it rejected WLF.
#[test]
fn shifts_that_are_not_wlf_are_fitted_by_default() {
    assert_eq!(FitParams::default().shift.kind, ShiftKind::Auto);
    for seed in [1, 2] {
        let report = fit(
            &data(kinked_truth, seed),
            &params(ShiftKind::Auto, &kinked_truth),
        )
        .unwrap();
        let choice = report
            .shift_choice
            .as_ref()
            .expect("auto records its choice");
        let worst = worst_shift(&report, &kinked_truth);
        for r in &report.runs {
            eprintln!("DEBUG {} λ {:.3e} V {:.6e}", r.stage, r.lambda, r.objective);
        }
        eprintln!(
            "DEBUG lambda {:?} {:?}",
            report.lambda.value, report.lambda.rule
        );
        let t = tan_delta_rms(&report, &truth_at(&kinked_truth, 5.0));
        eprintln!(
            "seed {seed}: law {} ({}), worst log a_T {worst:.4}, tan δ {t:.4} over {} points \
             {:.2e}…{:.2e} rad/s, χ²/N {:.3}, quality {}, {:.1} s",
            choice.model,
            choice.reason,
            report.curve.len(),
            report.window.omega_min,
            report.window.omega_max,
            report.misfit_per_point,
            report.fit_quality.verdict,
            report.wall_time_s
        );
        assert!(report.converged, "{}", report.stop_reason);
        assert!(!report.fit_quality.is_poor(), "{:?}", report.fit_quality);
        assert_ne!(choice.model, "wlf", "{choice:?}");
        assert_eq!(choice.candidates[0].rejected, Some(true), "{choice:?}");
        assert_eq!(report.shift.as_ref().unwrap().model_name(), choice.model);
        assert!(worst <= 0.05, "log a_T off by {worst}");
        assert!(t <= 0.03, "tan δ {t}");
        assert!(
            report.curve.len() >= 30,
            "window of {} points",
            report.curve.len()
        );
    }
}

/// `shift = "free"` on the kinked shifts fits as well as `auto` (which
/// chooses free shifts there): the WLF fit its λ would come from is poor,
/// so the free shifts get their own λ.
#[test]
fn explicit_free_shifts_fit_kinked_shifts() {
    let report = fit(
        &data(kinked_truth, 1),
        &params(ShiftKind::Free, &kinked_truth),
    )
    .unwrap();
    let worst = worst_shift(&report, &kinked_truth);
    let t = tan_delta_rms(&report, &truth_at(&kinked_truth, 5.0));
    eprintln!(
        "free: worst log a_T {worst:.4}, tan δ {t:.4}, λ {:.3e}, χ²/N {:.3}",
        report.lambda.value, report.misfit_per_point
    );
    assert!(!report.fit_quality.is_poor(), "{:?}", report.fit_quality);
    assert!(worst <= 0.05 && t <= 0.03, "{worst} {t}");
}

/// Data made with WLF shifts keep WLF under `auto`, with C1, C2 within 5 %
/// and every log10 a_T within 0.1 decade (the WLF targets of temperature_set.rs). Measured:
/// F = 0.68 (p = 0.61) on seed 1; log10 a_T within 0.072 decade, the worst
/// at −40 °C, 11 decades from T_ref on the glassy plateau (2.9 σ).
#[test]
fn wlf_shifts_keep_wlf_under_auto() {
    for seed in [1, 2] {
        let report = fit(&data(wlf_truth, seed), &params(ShiftKind::Auto, &wlf_truth)).unwrap();
        let choice = report
            .shift_choice
            .as_ref()
            .expect("auto records its choice");
        let worst = worst_shift(&report, &wlf_truth);
        assert_eq!(choice.model, "wlf", "{choice:?}");
        let Some(ShiftRecord::Wlf { c1, c2, .. }) = &report.shift else {
            panic!("{:?}", report.shift)
        };
        eprintln!(
            "seed {seed}: law {} ({}), C1 {c1:.4} C2 {c2:.3}, worst log a_T {worst:.4}, χ²/N \
             {:.3}, {:.1} s",
            choice.model, choice.reason, report.misfit_per_point, report.wall_time_s
        );
        // C1, C2 about T_ref = 5 °C: the same law as 8.86, 101.6 K about 20 °C.
        let (c1_ref, c2_ref) = (8.86 * 101.6 / (101.6 - 15.0), 101.6 - 15.0);
        assert!((c1 / c1_ref - 1.0).abs() < 0.05, "C1 {c1} vs {c1_ref}");
        assert!((c2 / c2_ref - 1.0).abs() < 0.05, "C2 {c2} vs {c2_ref}");
        assert!(worst <= 0.1, "log a_T off by {worst}");
        assert!(!report.fit_quality.is_poor(), "{:?}", report.fit_quality);
    }
}

/// `shift = "arrhenius"` on data made with Arrhenius shifts (E_a = 200
/// kJ/mol about 20 °C): E_a within 2 % (several of its σ apart at most),
/// every log10 a_T within 0.05 decade, each with a finite σ.
#[test]
fn arrhenius_shifts_are_recovered() {
    let energy = 2e5;
    let truth = |t: f64| energy * arrhenius_x(t, 20.0);
    let report = fit(&data(truth, 3), &params(ShiftKind::Arrhenius, &truth)).unwrap();
    let worst = worst_shift(&report, &truth);
    let Some(ShiftRecord::Arrhenius {
        activation_energy,
        activation_energy_sigma,
        t_ref,
        log_shift,
    }) = &report.shift
    else {
        panic!("{:?}", report.shift)
    };
    eprintln!(
        "E_a {activation_energy:.1} ± {activation_energy_sigma:.1} J/mol, worst log a_T \
         {worst:.4}, χ²/N {:.3}",
        report.misfit_per_point
    );
    assert_eq!(*t_ref, 5.0);
    assert!((activation_energy / energy - 1.0).abs() < 0.02);
    assert!(activation_energy_sigma.is_finite() && *activation_energy_sigma > 0.0);
    assert!(log_shift.iter().all(|s| s.log_shift_sigma.is_finite()));
    assert!(worst <= 0.05, "log a_T off by {worst}");
    assert!(report.shift_choice.is_none());
}

/// The same kinked shifts fitted with `shift = "wlf"` are judged
/// poor, and since the cross-check finds single-temperature shifts off the
/// law, the verdict's reasons (which `rollfit fit` prints when it refuses
/// the fit) name `shift = "free"`.
#[test]
fn a_poor_wlf_fit_of_kinked_shifts_names_free_shifts() {
    let report = fit(
        &data(kinked_truth, 1),
        &params(ShiftKind::Wlf, &kinked_truth),
    )
    .unwrap();
    let check = report.shift_cross_check.as_ref().expect("a cross-check");
    eprintln!(
        "χ²/N {:.2}, cross-check max difference {:.3}, reasons {:#?}",
        report.misfit_per_point, check.max_difference, report.fit_quality.reasons
    );
    assert!(report.fit_quality.is_poor(), "{:?}", report.fit_quality);
    assert!(report.shift_choice.is_none());
    assert!(
        points_to_free_shifts(&report),
        "{:?}",
        report.fit_quality.reasons
    );
}

/// The σ of log10 a_T against the truth over `SEEDS` noise seeds (default
/// 10, seeds 100…), kinked and WLF shifts under `auto`: the fraction of
/// temperatures (T_ref aside) with |error| ≤ σ and ≤ 2σ, and the mean z =
/// error/σ per temperature. A study (`cargo test --release -p rollfit-fit
/// --test it shift_law::coverage -- --ignored --nocapture`); it asserts only
/// that every σ but T_ref's is finite and positive.
///
/// Measured (10 seeds, 60 temperature-fits each): kinked (free shifts)
/// within σ at 55 %, within 2σ at 82 %; WLF within σ at 55 %, within 2σ at
/// 97 %. The σ are about 1.4 times too small for free shifts, and the
/// errors are not centred: mean z is +0.4…+1.2 below T_ref and −0.2…−0.7
/// above it (a stretch of the shifts by about 0.2 %), which neither the
/// curvature nor the smoothing-bias term (the fit at λ/10) sees.
#[test]
#[ignore]
fn coverage_of_the_shift_sigma() {
    let seeds: u64 = std::env::var("SEEDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(10);
    let truths: [(&str, &dyn Fn(f64) -> f64); 2] = [("kinked", &kinked_truth), ("wlf", &wlf_truth)];
    for (name, truth) in truths {
        let (mut one, mut two, mut n) = (0, 0, 0);
        let mut z_sum = vec![0.0; TEMPERATURES.len()];
        for seed in 0..seeds {
            let report = fit(&data(truth, 100 + seed), &params(ShiftKind::Auto, &truth)).unwrap();
            let shift = report.shift.as_ref().unwrap();
            let t_ref = shift.t_ref();
            for (j, s) in shift.log_shifts().iter().enumerate() {
                if s.temperature == t_ref {
                    continue;
                }
                assert!(
                    s.log_shift_sigma.is_finite() && s.log_shift_sigma > 0.0,
                    "{s:?}"
                );
                let z = (s.log_shift - (truth(s.temperature) - truth(t_ref))) / s.log_shift_sigma;
                one += usize::from(z.abs() <= 1.0);
                two += usize::from(z.abs() <= 2.0);
                z_sum[j] += z;
                n += 1;
            }
        }
        let (f1, f2) = (one as f64 / n as f64, two as f64 / n as f64);
        let mean: Vec<String> = TEMPERATURES
            .iter()
            .zip(&z_sum)
            .map(|(t, z)| format!("{t}: {:.2}", z / seeds as f64))
            .collect();
        eprintln!(
            "{name}: |error| ≤ σ at {f1:.2}, ≤ 2σ at {f2:.2} of {n}; mean z {}",
            mean.join(", ")
        );
    }
}

/// Where no law can be tested, `auto` says so: with two temperatures the
/// one shift is fitted free; with T_ref between the measured temperatures
/// free shifts (fixed at T_ref) cannot be fitted, and WLF is kept untested.
#[test]
fn auto_without_a_test_says_why() {
    let two = set_with_shifts(
        hn_rubber(),
        &[5.0, 20.0],
        &speeds(),
        wlf_truth,
        0.01,
        4,
        true,
    );
    let report = fit(&two, &params(ShiftKind::Auto, &wlf_truth)).unwrap();
    let choice = report.shift_choice.as_ref().unwrap();
    assert_eq!(
        (choice.model, report.shift.as_ref().unwrap().model_name()),
        ("free", "free")
    );
    assert!(
        choice.reason.contains("two temperatures"),
        "{}",
        choice.reason
    );
    let unmeasured = params_at(ShiftKind::Auto, &wlf_truth, Some(12.5));
    let report = fit(&data(wlf_truth, 4), &unmeasured).unwrap();
    let choice = report.shift_choice.as_ref().unwrap();
    assert_eq!(choice.model, "wlf");
    assert!(
        choice.reason.contains("not a measured temperature"),
        "{}",
        choice.reason
    );
    assert_eq!(choice.candidates[0].rejected, None);
}
