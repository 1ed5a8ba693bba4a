//! Where the fitting methods hold and where they fail: each test asserts the behaviour docs/validation.md's "Where the methods
//! fail" documents — a bound, or a clear report — never a silent wrong
//! answer. Fixed seeds throughout; the figures printed with --nocapture are
//! the ones docs/validation.md quotes.

use rollfit_testkit::materials::hn_rubber;
use rollfit_testkit::rolling::{setup, synthetic, window_errors};

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Uniform};
use rayon::prelude::*;
use rollfit_fit::{
    FitParams, Lambda, Measurements, Method, ScaleAnchor, StartMaterial, TermRule, fit,
};
use rollfit_model::ViscoelasticModulus;

fn anchor() -> ScaleAnchor {
    ScaleAnchor::ModulusAt {
        omega: 10.0,
        modulus: hn_rubber().modulus(10.0).norm(),
    }
}

fn params() -> FitParams {
    FitParams {
        anchor: Some(anchor()),
        ..FitParams::default()
    }
}

/// Spread of the recovered tan δ over 10 noise seeds at 0.1, 1 and 5 %
/// noise, with the automatic λ (discrepancy principle) and with none
/// (λ = 0, non-negativity alone). Regularised, the RMS error grows about
/// linearly with the noise and stays a few times the noise; without
/// regularisation it is several times larger at every level, and the worst
/// seed much more so.
#[test]
fn tan_delta_spread_over_noise_seeds_with_and_without_regularisation() {
    let truth = hn_rubber();
    let mut table = Vec::new();
    for noise in [0.001, 0.01, 0.05] {
        for (name, lambda) in [("auto", Lambda::Auto), ("none", Lambda::Fixed(0.0))] {
            let valid = FitParams { lambda, ..params() }.check(setup()).unwrap();
            let errors: Vec<f64> = (0..10)
                .into_par_iter()
                .map(|seed| {
                    let report = fit(&synthetic(hn_rubber(), noise, seed), &valid).unwrap();
                    window_errors(&report, &truth).0
                })
                .collect();
            let mean = errors.iter().sum::<f64>() / errors.len() as f64;
            let worst = errors.iter().copied().fold(0.0, f64::max);
            eprintln!("noise {noise}: λ {name}: tan δ RMS error mean {mean:.4}, worst {worst:.4}");
            table.push((noise, name, mean, worst));
        }
    }
    let get = |noise: f64, name: &str| {
        table
            .iter()
            .find(|r| r.0 == noise && r.1 == name)
            .map(|r| (r.2, r.3))
            .unwrap()
    };
    for noise in [0.001, 0.01, 0.05] {
        let (mean, worst) = get(noise, "auto");
        // Regularised: a few times the noise.
        assert!(mean < 3.0 * noise + 0.002, "noise {noise}: mean {mean}");
        assert!(worst < 5.0 * noise + 0.004, "noise {noise}: worst {worst}");
        // Without: worse on average at every level (measured 5.5×, 2.3×,
        // 1.7× at 0.1, 1, 5 %).
        let (mean_none, _) = get(noise, "none");
        assert!(
            mean_none > 1.3 * mean,
            "noise {noise}: λ = 0 {mean_none} vs {mean}"
        );
    }
}

/// Ten starting materials (E0 log-uniform in 0.5 … 5 MPa, E1/E0 in
/// 100 … 10 000, seed 7), the same λ, one start each, 3000 evaluations per
/// run: Levenberg–Marquardt and L-BFGS converge from every start to the
/// same tan δ (measured 10 of 10 each; the test allows L-BFGS two misses);
/// Nelder–Mead (33 parameters) from none, its tan δ up to 77 % off —
/// reported as not converged, never as a result.
#[test]
fn nelder_mead_and_lbfgs_from_the_same_starts() {
    let truth = hn_rubber();
    let data = synthetic(hn_rubber(), 0.01, 0);
    let lambda = fit(&data, &params().check(setup()).unwrap())
        .unwrap()
        .lambda
        .value;
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let starts: Vec<StartMaterial> = (0..10)
        .map(|_| {
            let e0 = 10f64.powf(Uniform::new(5.7, 6.7).unwrap().sample(&mut rng));
            let ratio = 10f64.powf(Uniform::new(2.0, 4.0).unwrap().sample(&mut rng));
            StartMaterial {
                static_modulus: e0,
                glassy_modulus: e0 * ratio,
            }
        })
        .collect();
    for method in [
        Method::LevenbergMarquardt,
        Method::Lbfgs,
        Method::NelderMead,
    ] {
        let mut converged = 0;
        let mut errors = Vec::new();
        // The starts are independent fits: computed on every core.
        let reports: Vec<_> = starts
            .par_iter()
            .map(|start| {
                let valid = FitParams {
                    method,
                    lambda: Lambda::Fixed(lambda),
                    starts: 1,
                    max_evaluations: Some(3000),
                    start: Some(start.clone()),
                    ..params()
                }
                .check(setup())
                .unwrap();
                fit(&data, &valid).unwrap()
            })
            .collect();
        for report in reports {
            if report.converged {
                converged += 1;
            } else {
                assert!(
                    !report.stop_reason.starts_with("converged"),
                    "{}",
                    report.stop_reason
                );
            }
            errors.push(window_errors(&report, &truth).0);
        }
        let worst = errors.iter().copied().fold(0.0, f64::max);
        eprintln!(
            "{}: converged from {converged} of 10 starts; tan δ RMS error worst {worst:.4}",
            method.name()
        );
        match method {
            Method::LevenbergMarquardt => {
                assert_eq!(converged, 10);
                assert!(worst < 0.03);
            }
            Method::Lbfgs => assert!(converged >= 8, "L-BFGS converged {converged}/10"),
            Method::NelderMead => {
                assert!(converged <= 2, "Nelder–Mead converged {converged}/10");
                assert!(worst > 0.05, "Nelder–Mead's unconverged tan δ looks good?");
            }
        }
    }
}

/// μ of the bundled truth at `count` speeds log-spaced over `v_min … v_max`
/// with 1 % noise (seed 3), σ known.
fn narrow_data(v_min: f64, v_max: f64, count: usize) -> Measurements {
    use rand_distr::Normal;
    use rollfit_model::Scene;
    let s = setup();
    let scene = Scene::new(s.geometry, s.substrate, s.contact, hn_rubber()).unwrap();
    let speeds: Vec<f64> = (0..count)
        .map(|i| v_min * (v_max / v_min).powf(i as f64 / (count - 1) as f64))
        .collect();
    let mu = scene.friction_sweep(&speeds).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let normal = Normal::new(0.0, 1.0).unwrap();
    let noisy = mu
        .iter()
        .map(|m| m * (1.0 + 0.01 * normal.sample(&mut rng)))
        .collect();
    let sigma = mu.iter().map(|m| 0.01 * m).collect();
    Measurements::new(speeds, noisy, Some(sigma), None).unwrap()
}

/// Data over one and a half decades of speed under a τ grid of 24 decades:
/// most terms are marked undetermined, the window is the narrow band the
/// data probe, and the curve reported (modulus.csv) stays inside it — the
/// other terms are not printed as results. Fewer points than terms is
/// normal under the smoothness penalty; fewer than four distinct speeds is
/// refused, saying so.
#[test]
fn a_narrow_window_leaves_most_terms_undetermined() {
    let tau: Vec<f64> = (0..25).map(|k| 1e-12 * 10f64.powi(k)).collect();
    let valid = FitParams {
        terms: TermRule::Explicit(tau.clone()),
        ..params()
    }
    .check(setup())
    .unwrap();

    let too_few = Measurements::new(vec![1e-5, 3e-5, 1e-4], vec![0.1; 3], None, None)
        .unwrap_err()
        .to_string();
    assert!(too_few.contains("distinct speed"), "{too_few}");
    let fewer_points_than_terms = fit(&narrow_data(1e-5, 3e-4, 8), &valid).unwrap();
    assert!(fewer_points_than_terms.converged);

    let data = narrow_data(1e-5, 3e-4, 31);
    let report = fit(&data, &valid).unwrap();
    let determined = report.model.determined.iter().filter(|d| **d).count();
    let window = report.window;
    eprintln!(
        "31 points over 1.5 decades of speed: window {:.3e} … {:.3e} rad/s, {determined} of {} terms determined",
        window.omega_min,
        window.omega_max,
        tau.len()
    );
    assert!(determined <= tau.len() / 2, "{determined} determined");
    assert!(
        report.warnings.iter().any(|w| w.contains("not determined")),
        "{:?}",
        report.warnings
    );
    // Determined terms lie inside the window (in 1/τ) or next to it.
    for (k, &t) in tau.iter().enumerate() {
        if report.model.determined[k] {
            assert!(
                1.0 / t > window.omega_min / 10.0 && 1.0 / t < window.omega_max * 10.0,
                "τ = {t} s determined but far outside the window"
            );
        }
    }
    assert!(window.omega_max / window.omega_min < 1e6, "window too wide");
    assert!(
        report.curve.iter().all(|p| {
            p.omega >= window.omega_min * 0.999 && p.omega <= window.omega_max * 1.001
        })
    );
}
