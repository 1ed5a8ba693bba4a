//! Fits judged where the data are: a replica of the held-out stiff
//! polymer whose correct fit was refused as "invalid" for an E0 that only
//! the Prony series' extrapolation below the window holds.
//!
//! The truth: a broad Prony spectrum over 20 decades of τ (1e-12 … 1e8 s
//! at T_ref = 20 °C), shaped like a real glassy polymer's master curve —
//! a log-normal bump 3.5 decades wide at 1e-6 s holding most of the
//! strength on a floor that reaches to the longest times — with
//! E′ ≈ 0.1 GPa at the lowest frequency the set probes and ≈ 9.6 GPa at
//! the highest, E0 = 1 MPa far below the window. The shifts are tabulated
//! and not WLF: from −10 to 20 °C the measured shifts of the 3M 468MP
//! acrylic's DMA isotherms (`rollfit master` on them, rounded to 0.01
//! decade), whose slope grows to 1.1 decades per 10 K at −10 °C; below,
//! a branch of one decade per 10 K (a kink at −10 °C). 7 temperatures × 21 speeds (1 µm/s … 10 cm/s), 1 % noise with
//! σ given, |E| at 10 rad/s at T_ref as the anchor.

use rollfit_testkit::rolling::{set_with_shifts, setup, tan_delta_rms};

use rollfit_fit::{FitParams, Measurements, ScaleAnchor, ShiftKind, fit};
use rollfit_model::{Prony, ViscoelasticModulus};
use rollfit_testkit::materials::LogNormalSpectrum;

/// (T in °C, log10 a_T about 20 °C) of the truth.
const SHIFTS: [(f64, f64); 7] = [
    (-40.0, 5.76),
    (-30.0, 4.76),
    (-20.0, 3.76),
    (-10.0, 2.76),
    (0.0, 1.65),
    (10.0, 0.75),
    (20.0, 0.0),
];

/// log10 a_T of the truth at a measured temperature.
fn log_shift(t: f64) -> f64 {
    SHIFTS
        .iter()
        .find(|(ts, _)| (ts - t).abs() < 1e-9)
        .map(|s| s.1)
        .expect("a tabulated temperature")
}

/// The stiff polymer (module doc).
fn stiff_polymer() -> Prony {
    LogNormalSpectrum {
        terms: 141,
        log_tau: (-12.0, 8.0),
        centre: -6.0,
        width: 3.5,
        floor: 0.005,
        e0: 1e6,
        e1: 9.8e9,
    }
    .prony()
}

fn data(seed: u64) -> Measurements {
    let temperatures: Vec<f64> = SHIFTS.iter().map(|s| s.0).collect();
    let speeds: Vec<f64> = (0..21)
        .map(|i| 1e-6 * 10f64.powf(0.25 * i as f64))
        .collect();
    set_with_shifts(
        stiff_polymer(),
        &temperatures,
        &speeds,
        log_shift,
        0.01,
        seed,
        true,
    )
}

fn params(kind: ShiftKind) -> rollfit_fit::ValidFitParams {
    let mut p = FitParams {
        anchor: Some(ScaleAnchor::ModulusAt {
            omega: 10.0,
            modulus: stiff_polymer().modulus(10.0).norm(),
        }),
        ..FitParams::default()
    };
    p.shift.kind = kind;
    p.shift.t_ref = Some(20.0);
    p.check(setup()).unwrap()
}

/// Every run of the replica's fits, free and auto (`SEED=n`, default 1):
/// where the evaluations go.
/// `cargo test --release -p rollfit-fit --test it verdict::probe -- --ignored --nocapture`
#[test]
#[ignore = "probe: run by hand"]
fn probe() {
    let seed = std::env::var("SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let set = data(seed);
    for kind in [ShiftKind::Free, ShiftKind::Auto] {
        let r = fit(&set, &params(kind)).unwrap();
        for run in &r.runs {
            eprintln!(
                "{kind:?}: {:<60} λ {:.3e} it {:>5} ev {:>5} V {:.6e} {}",
                run.stage,
                run.lambda,
                run.iterations,
                run.evaluations,
                run.objective,
                run.stop_reason
            );
        }
        eprintln!(
            "{kind:?}: {} evaluations, λ {:.3e}",
            r.evaluations, r.lambda.value
        );
    }
}

/// The replica is fitted and accepted with `shift = "free"` and with the
/// default settings: not "invalid" (E0 lies beyond the window and is
/// reported as an extrapolation with its bound), log10 a_T within 0.05
/// decade at every temperature, tan δ within 3 % RMS over the window, in
/// at most 600 evaluations (seed 1: 461 free, 508 auto; the counts are
/// deterministic).
#[test]
fn a_stiff_polymer_is_judged_where_the_data_are() {
    let truth = stiff_polymer();
    let set = data(1);
    for kind in [ShiftKind::Free, ShiftKind::Auto] {
        let r = fit(&set, &params(kind)).unwrap();
        let q = &r.fit_quality;
        let window = r.window;
        let low = truth.modulus(window.omega_min).re;
        let high = truth.modulus(window.omega_max).re;
        eprintln!(
            "{kind:?}: verdict {} ({:?}), window {:.2e} … {:.2e} rad/s (true E′ {low:.3e} … \
             {high:.3e} Pa), E0 {:.3e} Pa, E1 {:.3e} Pa, {} evaluations, {:.2} s",
            q.verdict,
            q.reasons,
            window.omega_min,
            window.omega_max,
            r.model.static_modulus,
            r.model.glassy_modulus,
            r.evaluations,
            r.wall_time_s
        );
        assert!(!q.is_invalid(), "{kind:?}: {:?}", q.reasons);
        assert!(q.is_good() && r.converged, "{kind:?}: {q:?}");
        let shift = r.shift.as_ref().expect("a temperature set");
        let mut worst = 0.0f64;
        for s in shift.log_shifts() {
            worst = worst.max((s.log_shift - log_shift(s.temperature)).abs());
        }
        let tan = tan_delta_rms(&r, &truth);
        eprintln!(
            "  worst log a_T {worst:.4} decade, tan δ {:.2} % RMS",
            100.0 * tan
        );
        assert!(worst <= 0.05, "{kind:?}: log a_T off by {worst}");
        assert!(
            r.evaluations <= 600,
            "{kind:?}: {} evaluations",
            r.evaluations
        );
        assert!(tan <= 0.03, "{kind:?}: tan δ {tan}");
        // The truth's E0 lies far below the window: the fit's E0 is an
        // extrapolation, reported with the bound the window gives, which
        // holds the truth.
        let e0 = r
            .extrapolated
            .iter()
            .find(|x| x.quantity == "E0")
            .expect("E0 is an extrapolation");
        assert!(e0.high.unwrap() >= truth.static_modulus(), "{e0:?}");
        assert!(e0.low.is_none(), "{e0:?}");
    }
}

/// `auto` on a lab set of the broad polymer (20 speeds, 3 % noise, seed
/// 15, anchored) whose one-curve route lands on a material with E1/E0
/// beyond double precision (E0 = E1 − ΣH rounds to zero): that route
/// fails and another answers, as `free` does, with the truth's shifts.
#[test]
fn auto_answers_when_one_route_leaves_double_precision() {
    use rollfit_testkit::broad_polymer::{lab_set, params, worst_shift_error};
    let data = lab_set(20, 0.03, 15);
    let temps: Vec<f64> = (0..5).map(|k| -20.0 + 20.0 * k as f64).collect();
    for kind in [ShiftKind::Auto, ShiftKind::Free] {
        let report = fit(&data, &params(kind, true)).unwrap();
        let worst = worst_shift_error(&report, &temps);
        eprintln!("{kind:?}: worst log a_T error {worst:.3}");
        assert!(worst <= 0.1, "{kind:?}: {worst}");
    }
}
