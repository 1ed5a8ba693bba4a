//! Recovery of known moduli from synthetic rolling data (fixed seeds).
//!
//! The truth of the bundled example (data/hn-rubber.toml): a broad
//! Havriliak–Negami rubber, E0 = 2 MPa, E1 = 2 GPa, τ = 1 ms, α = 0.55,
//! β = 0.4, under a 5 mm steel ball at 1 N, 41 speeds over 8 decades.

use rollfit_testkit::materials::hn_rubber;
use rollfit_testkit::rolling::{setup, synthetic, window_errors};
use rollfit_testkit::{materials, rolling};

use rayon::prelude::*;
use rollfit_fit::{FitParams, FitReport, ScaleAnchor, fit};
use rollfit_model::ViscoelasticModulus;

/// RMS relative errors of tan δ and |E| against `truth` over the reported
/// window shrunk by half a decade at each end.
fn errors<M: ViscoelasticModulus>(report: &FitReport, truth: &M) -> (f64, f64) {
    let (t, e, n) = window_errors(report, truth);
    assert!(n > 20, "window too small: {n} points");
    (t, e)
}

fn anchored(anchor: ScaleAnchor) -> rollfit_fit::ValidFitParams {
    FitParams {
        anchor: Some(anchor),
        ..FitParams::default()
    }
    .check(setup())
    .unwrap()
}

/// The recovery target: tan δ and |E| within 3 % RMS at 1 % noise for
/// each of 10 seeds with one anchor, within 1.5 % at 0.1 %. Met with the
/// bundled example's anchor (|E| at 10 rad/s, data/hn-rubber.toml) at both
/// noise levels, and with the static modulus E0 at 0.1 % noise; E0 at 1 %
/// noise is `static_modulus_anchor_at_one_percent_noise` below.
#[test]
fn anchored_recovery_meets_the_target_for_ten_seeds() {
    let truth = hn_rubber();
    let e_at = truth.modulus(10.0).norm();
    let mut failures = Vec::new();
    for (noise, bound) in [(0.01, 0.03), (0.001, 0.015)] {
        for seed in 0..10 {
            let mut anchors = vec![ScaleAnchor::ModulusAt {
                omega: 10.0,
                modulus: e_at,
            }];
            if noise < 0.01 {
                anchors.push(ScaleAnchor::StaticModulus(2e6));
            }
            for anchor in anchors {
                let report = fit(&synthetic(hn_rubber(), noise, seed), &anchored(anchor)).unwrap();
                let (t, e) = errors(&report, &truth);
                eprintln!("noise {noise} seed {seed} {anchor:?}: tan δ {t:.4} |E| {e:.4}");
                if t > bound || e > bound {
                    failures.push((noise, seed, anchor, t, e));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures:?}");
}

/// The static modulus alone is a weak anchor for the top of this window, a
/// property of the data rather than of the solver: |E| there is E0 plus
/// the whole rise through the transition (|E(10 rad/s)| = 31 E0 on this
/// rubber), and the data fix that rise only through the loss compliance,
/// whose integral must be right to a fraction of a per cent. Refitting with
/// E0 moved by the 1–2 % that an `E_at`-anchored fit returns moves |E| at the
/// top by 10–20 %; at 0.3 % noise the error is a third of that at 1 %
/// (linear in the noise, not a bias). Measured on 10 seeds at 1 % noise:
/// tan δ within 3 % RMS except seed 0 (4.6 %); |E| within 3 % for 6 seeds and
/// 3.5–6.5 % for seeds 0, 1, 7, 9. This test holds that line (tan δ ≤ 5 %,
/// |E| ≤ 7 %, and at least 6 of 10 seeds within the 3 % target) so a
/// regression shows; the 3 % target for every seed is not met with E0.
#[test]
fn static_modulus_anchor_at_one_percent_noise() {
    let truth = hn_rubber();
    let mut within = 0;
    for seed in 0..10 {
        let report = fit(
            &synthetic(hn_rubber(), 0.01, seed),
            &anchored(ScaleAnchor::StaticModulus(2e6)),
        )
        .unwrap();
        let (t, e) = errors(&report, &truth);
        eprintln!("seed {seed}: tan δ {t:.4} |E| {e:.4}");
        assert!(t <= 0.05 && e <= 0.07, "seed {seed}: tan δ {t}, |E| {e}");
        if t <= 0.03 && e <= 0.03 {
            within += 1;
        }
    }
    assert!(within >= 6, "{within} of 10 seeds within 3 %");
}

/// What the anchored fit achieves today on three seeds at 1 % noise: the
/// noise floor is reached and tan δ, the quantity rolling data fix best,
/// comes back within 3 %.
#[test]
fn anchored_fit_reaches_the_noise_floor_and_recovers_tan_delta() {
    let truth = hn_rubber();
    for seed in 1..4 {
        let report = fit(
            &synthetic(hn_rubber(), 0.01, seed),
            &anchored(ScaleAnchor::StaticModulus(2e6)),
        )
        .unwrap();
        let (t, e) = errors(&report, &truth);
        eprintln!(
            "seed {seed}: tan δ {t:.4} |E| {e:.4} χ²/N {:.3} λ {:e} {:.3} s",
            report.misfit_per_point, report.lambda.value, report.wall_time_s
        );
        assert!(report.converged, "{}", report.stop_reason);
        assert!((0.7..1.3).contains(&report.misfit_per_point));
        assert!(t <= 0.03, "tan δ {t}");
        assert!(e <= 0.05, "|E| {e}");
    }
}

/// The three methods on the same anchored problem at the λ the default
/// chose, from the same neutral start: time, evaluations, how each ended and
/// the recovered accuracy. A measurement (BENCHMARKS.md), not a
/// pass/fail target (Nelder–Mead is not expected to converge in 31
/// dimensions).
#[test]
#[ignore = "measurement: run with --ignored --nocapture"]
fn methods_compared_on_the_bundled_rubber() {
    use rollfit_fit::{Lambda, Method};
    let truth = hn_rubber();
    let data = synthetic(hn_rubber(), 0.01, 1);
    let reference = fit(&data, &anchored(ScaleAnchor::StaticModulus(2e6))).unwrap();
    for method in [
        Method::LevenbergMarquardt,
        Method::Lbfgs,
        Method::NelderMead,
    ] {
        let params = FitParams {
            anchor: Some(ScaleAnchor::StaticModulus(2e6)),
            method,
            lambda: Lambda::Fixed(reference.lambda.value),
            starts: 1,
            ..FitParams::default()
        }
        .check(setup())
        .unwrap();
        let report = fit(&data, &params).unwrap();
        let (t, e) = errors(&report, &truth);
        eprintln!(
            "{:<20} {:>7.2} s {:>6} evaluations, χ²/N {:.3}, V {:.2}, tan δ {t:.4}, |E| {e:.4}: {}",
            method.name(),
            report.wall_time_s,
            report.evaluations,
            report.misfit_per_point,
            report.objective,
            report.stop_reason
        );
    }
}

/// A 15-term Prony series with relaxation times inside the probed window
/// (one per decade, 1e-5 … 1e9 s ↔ ω 1e-9 … 1e5 rad/s, smooth bell-shaped
/// spectrum).
fn prony15() -> rollfit_model::Prony {
    let tau: Vec<f64> = (0..15).map(|k| 10f64.powi(k - 5)).collect();
    let h: Vec<f64> = (0..15)
        .map(|k| 4e7 * (-(((k as f64) - 4.0) / 3.0).powi(2)).exp() + 2e5)
        .collect();
    let e1 = 2e6 + h.iter().sum::<f64>();
    rollfit_model::Prony::new(e1, h, tau).unwrap()
}

/// Self-consistency: data made from a 15-term Prony series are fitted back
/// to the noise floor (χ²/N ≈ 1) from the neutral start by the default
/// method, for five seeds; L-BFGS runs on the same problems and how often it
/// stops short of convergence is reported.
#[test]
fn prony_data_are_fitted_back_to_the_noise_floor() {
    use rollfit_fit::Method;
    let mut lbfgs_stalls = 0;
    // The seeds are independent: each seed's two fits (L-BFGS at the
    // main fit's λ) on every core, printed and asserted in order.
    let fits: Vec<_> = (0..5u64)
        .into_par_iter()
        .map(|seed| {
            let data = synthetic(prony15(), 0.01, 100 + seed);
            let report = fit(&data, &anchored(ScaleAnchor::StaticModulus(2e6))).unwrap();
            let lbfgs = FitParams {
                anchor: Some(ScaleAnchor::StaticModulus(2e6)),
                method: Method::Lbfgs,
                lambda: rollfit_fit::Lambda::Fixed(report.lambda.value),
                starts: 1,
                ..FitParams::default()
            }
            .check(setup())
            .unwrap();
            let r = fit(&data, &lbfgs).unwrap();
            (seed, report, r)
        })
        .collect();
    for (seed, report, r) in fits {
        eprintln!(
            "seed {seed}: χ²/N {:.3} λ {:.3e} converged {} ({} evaluations, {:.3} s)",
            report.misfit_per_point,
            report.lambda.value,
            report.converged,
            report.evaluations,
            report.wall_time_s
        );
        for r in &report.runs {
            eprintln!(
                "    {} λ={:.2e} V={:.2} ev={} {}",
                r.stage, r.lambda, r.objective, r.evaluations, r.stop_reason
            );
        }
        assert!(report.converged, "{}", report.stop_reason);
        assert!(
            (0.6..1.4).contains(&report.misfit_per_point),
            "χ²/N = {}",
            report.misfit_per_point
        );
        eprintln!(
            "  L-BFGS: χ²/N {:.3} converged {} ({}), {:.2} s",
            r.misfit_per_point, r.converged, r.stop_reason, r.wall_time_s
        );
        if !r.converged || r.misfit_per_point > 1.4 {
            lbfgs_stalls += 1;
        }
    }
    eprintln!("L-BFGS stopped short in {lbfgs_stalls} of 5 seeds");
}

/// Without an anchor the fit measures how well the data fix the
/// scale: for each of 6 seeds of the bundled example (41 speeds, 1 % noise,
/// σ measured) the 2σ interval of its scale profile contains the true E0,
/// the fit's E0 lies inside its own interval, the warnings say what the
/// profile found (naming the anchors where the scale is undetermined), and
/// the 1σ band of |E|, widened by the profile, covers the truth over most
/// of the probed window. Measured: the data bound E0 from above at
/// 2.1–2.2 MPa (truth 2 MPa); below, the profile stays flat down to the
/// 0.61 MPa at which the static contact reaches R/3, so the interval spans
/// a factor 3.5–3.7, within the factor 9 that counts as determined.
#[test]
fn unanchored_fit_reports_a_scale_interval_that_holds_the_truth() {
    let truth = hn_rubber();
    let mut total = 0.0;
    for seed in 0..6 {
        let params = FitParams::default().check(setup()).unwrap();
        let report = fit(&synthetic(hn_rubber(), 0.01, seed), &params).unwrap();
        let scale = report
            .scale
            .as_ref()
            .expect("an unanchored fit has a scale record");
        let note = report
            .warnings
            .iter()
            .find(|w| w.contains("no scale anchor"))
            .expect("the warnings say what the profile found");
        assert!(
            !scale.is_undetermined() || note.contains("contact_radius"),
            "{note}"
        );
        let e0 = report.model.static_modulus;
        let inside = |x: f64| scale.low.is_none_or(|l| x >= l) && scale.high.is_none_or(|h| x <= h);
        assert!(inside(e0), "seed {seed}: E0 {e0} outside {scale:?}");
        assert!(inside(2e6), "seed {seed}: the truth outside {scale:?}");
        let covered = report
            .curve
            .iter()
            .filter(|p| (p.magnitude - truth.modulus(p.omega).norm()).abs() <= p.magnitude_sigma)
            .count() as f64
            / report.curve.len() as f64;
        eprintln!(
            "seed {seed}: {} interval {:?} … {:?}, E0 {e0:.3e}; |E| inside 1σ over {covered:.2}",
            scale.status, scale.low, scale.high
        );
        total += covered;
    }
    assert!(total / 6.0 >= 0.8, "mean coverage {}", total / 6.0);
}

/// A second truth, not in data/: a rubber with a narrower, more symmetric
/// transition (HN α = 0.7, β = 0.25, E1/E0 = 300, τ = 10 µs) under a
/// 10 mm cylinder at 200 N/m, anchored by one |E| in the window.
#[test]
fn second_truth_under_a_cylinder_is_recovered() {
    use rollfit_fit::Measurements;
    use rollfit_model::Scene;
    let truth = materials::narrow_rubber();
    let setup = rolling::cylinder_setup();
    let scene = Scene::new(
        setup.geometry,
        setup.substrate,
        setup.contact,
        truth.clone(),
    )
    .unwrap();
    let speeds: Vec<f64> = (0..41).map(|i| 1e-9 * 10f64.powf(i as f64 * 0.2)).collect();
    let exact = scene.friction_sweep(&speeds).unwrap();
    // Deterministic ±1 % noise from a fixed LCG, no extra crates needed.
    let mut state = 77u64;
    let noisy: Vec<f64> = exact
        .iter()
        .map(|m| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let u = (state >> 11) as f64 / (1u64 << 53) as f64;
            m * (1.0 + 0.01 * (2.0 * u - 1.0) * 3f64.sqrt())
        })
        .collect();
    let sigma = exact.iter().map(|m| 0.01 * m).collect();
    let data = Measurements::new(speeds, noisy, Some(sigma), None).unwrap();
    let params = FitParams {
        anchor: Some(ScaleAnchor::ModulusAt {
            omega: 100.0,
            modulus: truth.modulus(100.0).norm(),
        }),
        ..FitParams::default()
    }
    .check(setup)
    .unwrap();
    let report = fit(&data, &params).unwrap();
    let (t, e) = errors(&report, &truth);
    eprintln!(
        "cylinder truth: tan δ {t:.4}, |E| {e:.4}, χ²/N {:.3}, {:.3} s",
        report.misfit_per_point, report.wall_time_s
    );
    assert!(report.converged);
    assert!(t <= 0.03 && e <= 0.03, "tan δ {t}, |E| {e}");
}

/// The same data, settings and seed give the same fit, bit for bit.
#[test]
fn fits_are_deterministic_for_a_seed() {
    let data = synthetic(hn_rubber(), 0.01, 4);
    let params = FitParams {
        anchor: Some(ScaleAnchor::StaticModulus(2e6)),
        seed: 17,
        ..FitParams::default()
    }
    .check(setup())
    .unwrap();
    let a = fit(&data, &params).unwrap();
    let b = fit(&data, &params).unwrap();
    assert_eq!(a.model, b.model);
    assert_eq!(a.lambda, b.lambda);
    assert_eq!(a.mu_fit, b.mu_fit);
    assert_eq!(a.objective, b.objective);
}

/// `terms = "auto"` compares the densities that fit in the data by the
/// corrected Akaike criterion and says which it chose.
#[test]
fn automatic_term_count_reports_its_choice() {
    use rollfit_fit::TermRule;
    let data = synthetic(hn_rubber(), 0.01, 5);
    let params = FitParams {
        anchor: Some(ScaleAnchor::StaticModulus(2e6)),
        terms: TermRule::Auto,
        ..FitParams::default()
    }
    .check(setup())
    .unwrap();
    let report = fit(&data, &params).unwrap();
    assert_eq!(report.terms.rule, "aicc");
    assert!(!report.terms.candidates.is_empty());
    let best = report
        .terms
        .candidates
        .iter()
        .min_by(|a, b| a[1].total_cmp(&b[1]))
        .unwrap();
    eprintln!(
        "AICc candidates {:?}; chose {:.2} per decade",
        report.terms.candidates, report.terms.per_decade
    );
    assert!((report.terms.per_decade - best[0]).abs() < 0.1);
}
