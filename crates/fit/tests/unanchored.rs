//! Fits without a scale anchor (issue 32): ten synthetic truths — broad and
//! narrow Havriliak–Negami rubbers and two-peak spectra, E0 from 1e5 to
//! 1e8 Pa, under a ball and a cylinder — sampled at 15 speeds over 4–5
//! decades with 3 % noise and no sigma column.

mod common;

use common::{cylinder_setup, setup, sparse};
use rollfit_fit::{FitParams, RollingSetup, fit};
use rollfit_model::{HavriliakNegami, Prony, Shape, ViscoelasticModulus};

/// A truth the fit does not know the form of.
#[derive(Clone)]
enum Truth {
    Hn(HavriliakNegami),
    Prony(Prony),
}

impl Truth {
    fn modulus(&self) -> &dyn ViscoelasticModulus {
        match self {
            Truth::Hn(m) => m,
            Truth::Prony(m) => m,
        }
    }
}

/// Two relaxation processes: log-normal bumps at τ_a and τ_b (1.5 decades
/// wide) holding 70 % and 30 % of E1 − E0, on a floor.
fn two_peak(e0: f64, e1: f64, tau_a: f64, tau_b: f64) -> Prony {
    let n = 160;
    let tau: Vec<f64> = (0..n)
        .map(|k| 10f64.powf(-12.0 + 18.0 * k as f64 / (n - 1) as f64))
        .collect();
    let bump = |t: f64, c: f64| (-0.5 * ((t.log10() - c.log10()) / 1.5).powi(2)).exp();
    let w: Vec<f64> = tau
        .iter()
        .map(|&t| 0.7 * bump(t, tau_a) + 0.3 * bump(t, tau_b) + 1e-3)
        .collect();
    let total: f64 = w.iter().sum();
    let h = w.iter().map(|x| (e1 - e0) * x / total).collect();
    Prony::new(e1, h, tau).unwrap()
}

/// `base` with the radius and load set so that the rubbery contact is
/// a/R = 0.08 at E0 `e0`.
fn scaled(base: RollingSetup, e0: f64) -> RollingSetup {
    let mut s = base;
    let e_eff = e0 / (1.0 - 0.25);
    let a = 0.08 * s.geometry.radius;
    s.geometry.load = match s.geometry.shape {
        Shape::Sphere => a.powi(3) * e_eff / (0.75 * s.geometry.radius),
        Shape::Cylinder => a * a * std::f64::consts::PI * e_eff / (4.0 * s.geometry.radius),
    };
    s
}

/// (name, set-up, truth, slowest speed, decades).
fn truths() -> Vec<(&'static str, RollingSetup, Truth, f64, f64)> {
    let hn = |e0: f64, e1: f64, tau: f64, a: f64, b: f64| {
        Truth::Hn(HavriliakNegami::new(e0, e1, tau, a, b).unwrap())
    };
    // The slowest speed puts the contact frequency v/a of the rubbery
    // contact at `omega_lo`: v = ω a.
    let at = |s: RollingSetup, omega_lo: f64| omega_lo * 0.08 * s.geometry.radius;
    let ball = setup();
    let cyl = cylinder_setup();
    let mut v = Vec::new();
    for (name, base, truth, e0, omega_lo, decades) in [
        (
            "HN broad 1e5 ball",
            ball,
            hn(1e5, 1e8, 1e-3, 0.55, 0.4),
            1e5,
            1e-1,
            5.0,
        ),
        (
            "HN broad 1e6 cylinder",
            cyl,
            hn(1e6, 1e9, 1e-3, 0.55, 0.4),
            1e6,
            1e-1,
            5.0,
        ),
        (
            "HN narrow 1e7 ball",
            ball,
            hn(1e7, 3e9, 1e-4, 0.7, 0.25),
            1e7,
            1e1,
            4.0,
        ),
        (
            "HN narrow 1e8 cylinder",
            cyl,
            hn(1e8, 4e9, 1e-4, 0.7, 0.25),
            1e8,
            1e1,
            4.0,
        ),
        (
            "HN 1.2e6 issue ball",
            ball,
            hn(1.2e6, 1.8e9, 1e-2, 0.5, 0.45),
            1.2e6,
            1e-2,
            5.0,
        ),
        (
            "two-peak 1e5 cylinder",
            cyl,
            Truth::Prony(two_peak(1e5, 1e8, 1e-3, 1.0)),
            1e5,
            1e-2,
            5.0,
        ),
        (
            "two-peak 1e6 ball",
            ball,
            Truth::Prony(two_peak(1e6, 1e9, 1e-4, 1e-1)),
            1e6,
            1e-1,
            5.0,
        ),
        (
            "two-peak 1e7 cylinder",
            cyl,
            Truth::Prony(two_peak(1e7, 2e9, 1e-4, 1e-1)),
            1e7,
            1e0,
            4.5,
        ),
        (
            "two-peak 1e8 ball",
            ball,
            Truth::Prony(two_peak(1e8, 3e9, 1e-5, 1e-2)),
            1e8,
            1e1,
            4.5,
        ),
        (
            "HN broad 3e6 ball",
            ball,
            hn(3e6, 2e9, 1e-3, 0.55, 0.4),
            3e6,
            1e0,
            4.0,
        ),
    ] {
        let s = scaled(base, e0);
        v.push((name, s, truth, at(s, omega_lo), decades));
    }
    v
}

/// The study of unanchored fits with the profile's numbers printed:
/// `cargo test --release -p rollfit-fit --test unanchored study_unanchored -- --ignored --nocapture`
/// (SEEDS, CASE in the environment).
#[test]
#[ignore = "study: run by hand"]
fn study_unanchored() {
    let seeds: u64 = std::env::var("SEEDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let only = std::env::var("CASE").ok();
    for (name, s, truth, v_min, decades) in truths() {
        if only.as_deref().is_some_and(|o| !name.contains(o)) {
            continue;
        }
        let params = FitParams::default().check(s).unwrap();
        for seed in 0..seeds {
            let data = match &truth {
                Truth::Hn(m) => sparse(s, m.clone(), v_min, decades, 15, 0.03, seed),
                Truth::Prony(m) => sparse(s, m.clone(), v_min, decades, 15, 0.03, seed),
            };
            let r = fit(&data, &params).unwrap();
            let e0 = truth.modulus().static_modulus();
            eprintln!(
                "{name} seed {seed}: E0 fit {:.3e} truth {e0:.3e} ratio {:.3} noise {:.4} {} runs p {:.3} {:.3} s",
                r.model.static_modulus,
                r.model.static_modulus / e0,
                r.noise,
                r.fit_quality.verdict,
                r.fit_quality.runs.map_or(f64::NAN, |x| x.p_value),
                r.wall_time_s
            );
            for p in &r.scale_profile {
                eprintln!(
                    "    ×{:.2}: Δχ² {:.2} λ {:.1e}",
                    p[0],
                    (p[1] - r.misfit) / (r.noise * r.noise),
                    p[2]
                );
            }
        }
    }
}
