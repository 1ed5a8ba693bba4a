//! Laboratory-shaped data (issue 13): 10–20 speeds over 3–5 decades,
//! 2–5 % noise nobody wrote down, one scale anchor.

mod common;

use common::{
    band_coverage, cylinder_setup, hn_rubber, narrow_rubber, setup, sparse, window_errors,
};
use rollfit_fit::{FitParams, RollingSetup, ScaleAnchor, fit};
use rollfit_model::{HavriliakNegami, Scene, ViscoelasticModulus};

/// The window centre's frequency ω ≈ v/r for the middle speed.
fn centre_omega(setup: RollingSetup, truth: &HavriliakNegami, v_mid: f64) -> f64 {
    let scene = Scene::new(
        setup.geometry,
        setup.substrate,
        setup.contact,
        truth.clone(),
    )
    .unwrap();
    let _ = scene;
    let r = rollfit_fit::tau_grid::contact_size(&setup, truth.rubbery_modulus());
    v_mid / r
}

#[test]
#[ignore = "study"]
fn study_sparse() {
    let cases: Vec<(&str, RollingSetup, HavriliakNegami, f64)> = vec![
        ("broad sphere", setup(), hn_rubber(), 1e-6),
        ("narrow sphere", setup(), narrow_rubber(), 1e-5),
        ("broad cylinder", cylinder_setup(), hn_rubber(), 1e-6),
        ("narrow cylinder", cylinder_setup(), narrow_rubber(), 1e-5),
    ];
    let seeds: u64 = std::env::var("SEEDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    let only = std::env::var("CASE").ok();
    let lambda = std::env::var("LAMBDA")
        .ok()
        .and_then(|s| s.parse().ok())
        .map(rollfit_fit::Lambda::Fixed)
        .unwrap_or(rollfit_fit::Lambda::Auto);
    for (name, s, truth, v_min) in cases {
        if only.as_deref().is_some_and(|o| o != name) {
            continue;
        }
        let omega_a = centre_omega(s, &truth, v_min * 10f64.powf(2.5));
        for seed in 0..seeds {
            let count: usize = std::env::var("COUNT")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(15);
            let decades: f64 = std::env::var("DECADES")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(5.0);
            let noise: f64 = std::env::var("NOISE")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(0.03);
            let data = sparse(s, truth.clone(), v_min, decades, count, noise, seed);
            let params = FitParams {
                anchor: Some(ScaleAnchor::ModulusAt {
                    omega: omega_a,
                    modulus: truth.modulus(omega_a).norm(),
                }),
                lambda,
                ..FitParams::default()
            }
            .check(s)
            .unwrap();
            let report = fit(&data, &params).unwrap();
            let (t, e, n) = window_errors(&report, &truth);
            let (ct, ce) = band_coverage(&report, &truth, 2.0);
            eprintln!(
                "{name} seed {seed}: tan δ {t:.4} |E| {e:.4} ({n} pts) cover2σ {ct:.2}/{ce:.2} {} runs p {:.3} λ {:.2e} t {:.1} noise {:.4} terms {} {:.3} s",
                report.fit_quality.verdict,
                report.fit_quality.runs.map_or(f64::NAN, |r| r.p_value),
                report.lambda.value,
                report.effective_parameters,
                report.noise,
                report.terms.count,
                report.wall_time_s
            );
        }
    }
}

#[test]
#[ignore = "study"]
fn study_one() {
    let case = std::env::var("CASE").unwrap_or("narrow sphere".into());
    let (s, truth, v_min) = match case.as_str() {
        "narrow sphere" => (setup(), narrow_rubber(), 1e-5),
        "broad cylinder" => (cylinder_setup(), hn_rubber(), 1e-6),
        _ => (setup(), hn_rubber(), 1e-6),
    };
    let seed: u64 = std::env::var("SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    let omega_a = centre_omega(s, &truth, v_min * 10f64.powf(2.5));
    let data = sparse(s, truth.clone(), v_min, 5.0, 15, 0.03, seed);
    let scene = Scene::new(s.geometry, s.substrate, s.contact, truth.clone()).unwrap();
    let exact = scene.friction_sweep(data.speeds()).unwrap();
    let params = FitParams {
        anchor: Some(ScaleAnchor::ModulusAt {
            omega: omega_a,
            modulus: truth.modulus(omega_a).norm(),
        }),
        ..FitParams::default()
    }
    .check(s)
    .unwrap();
    let report = fit(&data, &params).unwrap();
    for i in 0..data.len() {
        eprintln!(
            "v {:.3e} mu {:.4e} exact {:.4e} fit {:.4e}",
            data.speeds()[i],
            data.friction()[i],
            exact[i],
            report.mu_fit[i]
        );
    }
    eprintln!(
        "window {:?} anchor ω {omega_a:.3e} E0 {:.3e} E1 {:.3e} warnings {:?}",
        report.window, report.model.static_modulus, report.model.glassy_modulus, report.warnings
    );
    for p in &report.lambda.path {
        eprintln!("path λ {:.2e} misfit {:.4e} t {:.2}", p[0], p[1], p[2]);
    }
    for p in &report.lambda.criterion {
        eprintln!("crit λ {:.2e} {:.3}", p[0], p[1]);
    }
    for r in &report.runs {
        eprintln!(
            "{} λ {:.2e} V {:.4e} ev {} {}",
            r.stage, r.lambda, r.objective, r.evaluations, r.stop_reason
        );
    }
    for p in report.curve.iter().step_by(5) {
        let x = truth.modulus(p.omega);
        eprintln!(
            "ω {:.2e} tanδ {:.4} ± {:.4} truth {:.4} |E| {:.3e} ± {:.2e} truth {:.3e}",
            p.omega,
            p.tan_delta,
            p.tan_delta_sigma,
            x.im / x.re,
            p.magnitude,
            p.magnitude_sigma,
            x.norm()
        );
    }
}

#[test]
#[ignore = "study"]
fn study_eval_cost() {
    use rollfit_model::Prony;
    let s = setup();
    let tau: Vec<f64> = (0..26).map(|k| 1e-9 * 10f64.powf(k as f64 * 0.5)).collect();
    let h: Vec<f64> = tau
        .iter()
        .map(|t| 1e7 * (-(t.log10() + 2.0).powi(2) / 8.0).exp())
        .collect();
    let e1 = 2e6 + h.iter().sum::<f64>();
    let p = Prony::new(e1, h, tau).unwrap();
    for tol in [1e-6, 1e-5, 1e-4] {
        let scene = Scene::new(s.geometry, s.substrate, s.contact, p.clone())
            .unwrap()
            .with_tolerance(tol)
            .unwrap();
        let speeds: Vec<f64> = (0..15)
            .map(|i| 1e-6 * 10f64.powf(5.0 * i as f64 / 14.0))
            .collect();
        let t0 = std::time::Instant::now();
        for _ in 0..200 {
            let _ = scene.friction_with_gradient(&speeds).unwrap();
        }
        let t1 = t0.elapsed().as_secs_f64() / 200.0;
        let t0 = std::time::Instant::now();
        for _ in 0..200 {
            let _ = scene.friction_sweep(&speeds).unwrap();
        }
        let t2 = t0.elapsed().as_secs_f64() / 200.0;
        eprintln!(
            "tol {tol:e}: with gradient {:.3} ms, μ only {:.3} ms",
            t1 * 1e3,
            t2 * 1e3
        );
    }
}
