//! Fits without a scale anchor: ten synthetic truths — broad and
//! narrow Havriliak–Negami rubbers and two-peak spectra, E0 from 1e5 to
//! 1e8 Pa, under a ball and a cylinder — sampled at 15 speeds over 4–5
//! decades with 3 % noise and no sigma column.

use rollfit_testkit::broad_polymer;
use rollfit_testkit::materials::hn_rubber;
use rollfit_testkit::rolling::{cylinder_setup, setup, sparse};

use rollfit_fit::{FitParams, FitReport, Measurements, RollingSetup, ScaleAnchor, fit};
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

/// 15 speeds of `truth` over `decades` from `v_min` under `s`, 3 % noise,
/// no sigma column.
fn lab_data(s: RollingSetup, truth: &Truth, v_min: f64, decades: f64, seed: u64) -> Measurements {
    match truth {
        Truth::Hn(m) => sparse(s, m.clone(), v_min, decades, 15, 0.03, seed),
        Truth::Prony(m) => sparse(s, m.clone(), v_min, decades, 15, 0.03, seed),
    }
}

/// The contact size (ball radius, cylinder half-width) of the static Hertz
/// contact at `e0` (Pa) over the body's radius.
fn static_contact_ratio(s: &RollingSetup, e0: f64) -> f64 {
    rollfit_fit::tau_grid::contact_size(s, e0) / s.geometry.radius
}

/// The target for unanchored fits: over the ten truths (two seeds
/// each), every fit reports its scale interval; where the scale is
/// undetermined (refused by the command line) the reason names the three
/// anchors; at least 90 % of the intervals contain the true E0; no fit's
/// E0 lies outside its own interval, and no fit that is not judged
/// "invalid" has a static contact above R/3. Measured: all 20 intervals
/// hold the truth, all undetermined (15 speeds at 3 % noise bound E0 from
/// above — a stiffer rubber cannot give the friction of the slowest speeds
/// — but not from below, down to the E0 where the contact reaches R/3);
/// `study_unanchored` prints the profiles.
#[test]
fn unanchored_fits_report_a_scale_interval_or_refuse() {
    let (mut reported, mut holding) = (0, 0);
    for (name, s, truth, v_min, decades) in truths() {
        let params = FitParams::default().check(s).unwrap();
        let e0_true = truth.modulus().static_modulus();
        for seed in 0..2 {
            let r = fit(&lab_data(s, &truth, v_min, decades, seed), &params).unwrap();
            let scale = r
                .scale
                .as_ref()
                .expect("an unanchored fit has a scale record");
            let inside =
                |x: f64| scale.low.is_none_or(|l| x >= l) && scale.high.is_none_or(|h| x <= h);
            let e0 = r.model.static_modulus;
            eprintln!(
                "{name} seed {seed}: {} [{:?}, {:?}] E0 {e0:.3e} truth {e0_true:.3e} verdict {}",
                scale.status, scale.low, scale.high, r.fit_quality.verdict
            );
            assert!(inside(e0), "{name} seed {seed}: E0 {e0} outside {scale:?}");
            if scale.is_undetermined() {
                for anchor in ["E0 = …", "E_at", "contact_radius"] {
                    assert!(scale.reason.contains(anchor), "{anchor}: {}", scale.reason);
                }
            }
            if !r.fit_quality.is_invalid() {
                let ratio = static_contact_ratio(&s, e0);
                assert!(
                    ratio <= 1.0 / 3.0 + 1e-9,
                    "{name} seed {seed}: a/R = {ratio}"
                );
            }
            reported += 1;
            if inside(e0_true) {
                holding += 1;
            }
        }
    }
    assert!(
        holding as f64 >= 0.9 * reported as f64,
        "{holding} of {reported} intervals hold the true E0"
    );
}

/// A fitted material that breaks the model's assumptions where the data
/// determine it is judged "invalid" with the assumption and the numbers:
/// E0 pinned where the static contact of the 5 mm ball at 1 N exceeds R/3
/// (2e5 Pa: a = 0.48 R; the slowest speeds see the rubbery plateau). E0
/// pinned at 5 kPa, below any solid's, lies below the window, whose |E|
/// the fit keeps above 10 kPa: it judges nothing, and the fit is refused
/// as "poor" because it cannot follow the data.
#[test]
fn a_material_that_breaks_the_assumptions_is_invalid() {
    let s = setup();
    let data = sparse(s, hn_rubber(), 1e-6, 5.0, 15, 0.03, 0);
    let pinned = |e0: f64| {
        let params = FitParams {
            anchor: Some(ScaleAnchor::StaticModulus(e0)),
            ..FitParams::default()
        }
        .check(s)
        .unwrap();
        fit(&data, &params).unwrap()
    };
    let r: FitReport = pinned(2e5);
    let q = &r.fit_quality;
    assert!(q.is_invalid() && !q.is_good(), "{q:?}");
    assert!(
        q.reasons.iter().any(|x| x.contains("small contact")),
        "{:?}",
        q.reasons
    );
    let r: FitReport = pinned(5e3);
    let q = &r.fit_quality;
    assert!(q.is_poor() && !q.is_invalid(), "{q:?}");
    assert!(
        q.reasons.iter().all(|x| !x.contains("E0")),
        "{:?}",
        q.reasons
    );
}

/// The study of unanchored fits with the profile's numbers printed:
/// `cargo test --release -p rollfit-fit --test it unanchored::study_unanchored -- --ignored --nocapture`
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
            let data = lab_data(s, &truth, v_min, decades, seed);
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
            if std::env::var("PIN").is_ok() {
                let pinned = FitParams {
                    anchor: Some(rollfit_fit::ScaleAnchor::StaticModulus(
                        truth.modulus().static_modulus(),
                    )),
                    ..FitParams::default()
                }
                .check(s)
                .unwrap();
                let q = fit(&data, &pinned).unwrap();
                eprintln!(
                    "    anchored at the true E0: misfit {:.5} (unanchored {:.5}) noise {:.4} λ {:.2e}",
                    q.misfit, r.misfit, q.noise, q.lambda.value
                );
            }
            let sc = r.scale.as_ref().unwrap();
            let profile_evaluations: usize = r
                .runs
                .iter()
                .filter(|x| x.stage.starts_with("scale profile"))
                .map(|x| x.evaluations)
                .sum();
            eprintln!(
                "    profile evaluations {profile_evaluations} of {}: ×{:.2} the fit without it",
                r.evaluations,
                r.evaluations as f64 / (r.evaluations - profile_evaluations) as f64
            );
            let inside = sc.low.is_none_or(|l| e0 >= l) && sc.high.is_none_or(|h| e0 <= h);
            eprintln!(
                "    scale {} [{:?}, {:?}] truth inside {inside}; evaluations {}; verdict {} {:?}",
                sc.status,
                sc.low,
                sc.high,
                r.evaluations,
                r.fit_quality.verdict,
                r.fit_quality
                    .reasons
                    .iter()
                    .map(|x| x.chars().take(90).collect::<String>())
                    .collect::<Vec<_>>()
            );
            for p in &sc.profile {
                eprintln!("    E0 {:.3e}: Δχ² {:.2}", p[0], p[1]);
            }
        }
    }
}

/// What an unanchored fit must do when it writes a result that writes a result (its scale
/// determined, so that the command line writes it): at every point of the
/// determined window the true |E| lies within the reported 2σ, and the
/// reported |E| within ×1.5 of the truth. Returns (whether the result is
/// written, the fraction of points whose 2σ band holds the true |E|, the
/// largest ratio reported/true |E| either way).
fn held_out(report: &FitReport, truth: &dyn ViscoelasticModulus) -> (bool, f64, f64) {
    let written = report.scale.as_ref().is_none_or(|s| !s.is_undetermined());
    let (mut inside, mut ratio) = (0usize, 1.0f64);
    for p in &report.curve {
        let e = truth.modulus(p.omega).norm();
        inside += usize::from((p.magnitude - e).abs() <= 2.0 * p.magnitude_sigma);
        ratio = ratio.max((p.magnitude / e).max(e / p.magnitude));
    }
    (
        written,
        inside as f64 / report.curve.len().max(1) as f64,
        ratio,
    )
}

/// The held-out target on unanchored laboratory-shaped sets
/// (3 % noise, no sigma column): the broad real-curve replica of
/// `broad_polymer::` (5 temperatures × 15 speeds, kinked shifts,
/// `shift = "auto"`) and the Havriliak–Negami truths above, SEEDS seeds
/// each (CASE selects):
/// `SEEDS=10 cargo test --release -p rollfit-fit --test it unanchored::study_held_out -- --ignored --nocapture`
#[test]
#[ignore = "study: run by hand"]
fn study_held_out() {
    let seeds: u64 = std::env::var("SEEDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(5);
    let only = std::env::var("CASE").ok();
    let polymer = broad_polymer::truth();
    let mut runs = vec![HeldOut {
        name: "broad polymer".into(),
        data: Box::new(|seed| broad_polymer::lab_set(15, 0.03, seed)),
        params: broad_polymer::params(rollfit_fit::ShiftKind::Auto, false),
        truth: Truth::Prony(polymer),
    }];
    for (name, s, truth, v_min, decades) in truths() {
        if !name.starts_with("HN") {
            continue;
        }
        let t = truth.clone();
        runs.push(HeldOut {
            name: name.into(),
            data: Box::new(move |seed| lab_data(s, &t, v_min, decades, seed)),
            params: FitParams::default().check(s).unwrap(),
            truth,
        });
    }
    let (mut written, mut failed) = (0, Vec::new());
    for run in &runs {
        let name = &run.name;
        if only.as_deref().is_some_and(|o| !name.contains(o)) {
            continue;
        }
        for seed in 0..seeds {
            let r = fit(&(run.data)(seed), &run.params).unwrap();
            let (w, inside, ratio) = held_out(&r, run.truth.modulus());
            let sc = r.scale.as_ref().unwrap();
            eprintln!(
                "{name} seed {seed}: scale {} [{:?}, {:?}] E0 {:.3e} (truth {:.3e}); 2σ holds \
                 the true |E| at {inside:.2} of {} points; |E| within ×{ratio:.3}; verdict {}",
                sc.status,
                sc.low,
                sc.high,
                r.model.static_modulus,
                run.truth.modulus().static_modulus(),
                r.curve.len(),
                r.fit_quality.verdict
            );
            if w {
                for p in &sc.profile {
                    eprintln!("    E0 {:.3e}: Δχ² {:.2}", p[0], p[1]);
                }
                written += 1;
                if inside < 1.0 || ratio > 1.5 {
                    failed.push(format!("{name} seed {seed}"));
                }
            }
        }
    }
    eprintln!("{written} results written; the target missed in {failed:?}");
}

/// An unanchored case of [`study_held_out`]: its name, data for a seed,
/// settings and truth.
struct HeldOut {
    name: String,
    data: Box<dyn Fn(u64) -> Measurements>,
    params: rollfit_fit::ValidFitParams,
    truth: Truth,
}

/// A scale profile that stays flat just above Δχ² = 4 down to the model's
/// range (the broad replica, seed 6: about 4.8 from 6e5 to 2e7 Pa with its
/// minimum at the top of the range) does not determine the scale: such a
/// crossing excluded the true E0 in each of the three fits it wrote. The
/// fit is written only when the scale is determined, so this one is not.
#[test]
fn a_plateau_just_over_two_sigma_does_not_determine_the_scale() {
    let data = broad_polymer::lab_set(15, 0.03, 6);
    let params = broad_polymer::params(rollfit_fit::ShiftKind::Auto, false);
    let r = fit(&data, &params).unwrap();
    let scale = r.scale.as_ref().unwrap();
    assert_eq!(scale.status, "undetermined", "{scale:?}");
    assert!(scale.low.is_none(), "{scale:?}");
}
