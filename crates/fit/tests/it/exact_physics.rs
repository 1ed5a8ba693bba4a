//! `physics = "exact"`: fits against the exact rolling contact
//! by defect correction, measured on synthetic data of a broad rubber
//! (E1/E0 = 1000, a smooth 200-term spectrum) under a 5 mm cylinder at
//! 1000 N/m, 41 speeds over 8 decades centred on the friction maximum,
//! anchored with the known E0.
//!
//! Three fits per noise level and seed (the same noise draws on both data
//! sets):
//! - data of Eq. (11) fitted with Eq. (11): the reference, where the model
//!   is right;
//! - data of the exact contact fitted with Eq. (11): the model error the
//!   exact physics removes;
//! - data of the exact contact fitted with `physics = "exact"`: must come
//!   within 1.5 times the reference's RMS errors of tan δ and |E| (over the
//!   determined window shrunk by half a decade at each end, as
//!   tests/recovery.rs measures).
//!
//! The full study (more seeds, a table):
//! `cargo test --release -p rollfit-fit --test it -- --ignored --nocapture exact_physics::study`

use rollfit_testkit::materials::rubber_200;
use rollfit_testkit::rolling;
use rollfit_testkit::rolling::{
    BothPhysics, exact_and_approximate, exact_cylinder_setup, setup, window_errors, with_noise,
};

use rayon::prelude::*;
use std::sync::OnceLock;

use rollfit_fit::{FitParams, FitReport, Physics, RollingSetup, ScaleAnchor, fit};
use rollfit_model::Prony;

/// The target: the exact-physics fit's RMS errors within this factor of
/// the reference's.
const TARGET_FACTOR: f64 = 1.5;

/// (speeds, μ of Eq. (11), μ exact) of the broad rubber under the
/// cylinder, computed once per test binary (about 5 s on two cores).
fn cylinder_data() -> &'static BothPhysics {
    static DATA: OnceLock<BothPhysics> = OnceLock::new();
    DATA.get_or_init(|| exact_and_approximate(exact_cylinder_setup(), &rubber_200(), 1e-6).unwrap())
}

fn anchored(setup: RollingSetup, physics: Physics) -> rollfit_fit::ValidFitParams {
    FitParams {
        anchor: Some(ScaleAnchor::StaticModulus(2e6)),
        physics,
        ..FitParams::default()
    }
    .check(setup)
    .unwrap()
}

/// RMS errors of tan δ and |E| of one fit against the truth.
#[derive(Debug, Clone, Copy)]
struct Errors {
    tan_delta: f64,
    modulus: f64,
}

fn errors(report: &FitReport, truth: &Prony) -> Errors {
    let (tan_delta, modulus, n) = window_errors(report, truth);
    assert!(n > 20, "window too small: {n} points");
    Errors { tan_delta, modulus }
}

/// The three fits of one noise level and seed.
struct Case {
    noise: f64,
    seed: u64,
    reference: Errors,
    uncorrected: Errors,
    corrected: Errors,
    exact: FitReport,
}

fn case(setup: RollingSetup, data: &BothPhysics, noise: f64, seed: u64) -> Case {
    let truth = rubber_200();
    let (speeds, approximate, exact) = (&data.speeds, &data.approximate, &data.exact);
    let approximate_params = anchored(setup, Physics::Approximate);
    let reference = fit(
        &with_noise(speeds, approximate, noise, seed),
        &approximate_params,
    )
    .unwrap();
    let measured = with_noise(speeds, exact, noise, seed);
    let uncorrected = fit(&measured, &approximate_params).unwrap();
    let corrected = fit(&measured, &anchored(setup, Physics::Exact)).unwrap();
    Case {
        noise,
        seed,
        reference: errors(&reference, &truth),
        uncorrected: errors(&uncorrected, &truth),
        corrected: errors(&corrected, &truth),
        exact: corrected,
    }
}

fn print_header() {
    eprintln!(
        "| σ | seed | Eq.11 data, approximate: tan δ / |E| | exact data, approximate | \
         exact data, exact | refits | exact solves | max |r−1| | converged | wall s |"
    );
    eprintln!("|---|---|---|---|---|---|---|---|---|---|");
}

fn print_row(c: &Case) {
    let p = c.exact.physics.as_ref().unwrap();
    let pct = |e: Errors| format!("{:.2} % / {:.2} %", 100.0 * e.tan_delta, 100.0 * e.modulus);
    eprintln!(
        "| {} % | {} | {} | {} | {} | {} | {} | {:.2} % | {} | {:.1} |",
        100.0 * c.noise,
        c.seed,
        pct(c.reference),
        pct(c.uncorrected),
        pct(c.corrected),
        p.iterations,
        p.exact_solves,
        100.0 * p.max_correction,
        p.converged,
        c.exact.wall_time_s
    );
}

/// What a case must show: the corrected fit within the target of the
/// reference, having converged.
fn check(c: &Case) -> Vec<String> {
    let mut failures = Vec::new();
    let p = c.exact.physics.as_ref().unwrap();
    let within = |corrected: f64, reference: f64| corrected <= TARGET_FACTOR * reference;
    if !within(c.corrected.tan_delta, c.reference.tan_delta)
        || !within(c.corrected.modulus, c.reference.modulus)
    {
        failures.push(format!(
            "σ {} seed {}: corrected {:?} not within {TARGET_FACTOR} × reference {:?}",
            c.noise, c.seed, c.corrected, c.reference
        ));
    }
    if !p.converged || !c.exact.converged {
        failures.push(format!(
            "σ {} seed {}: not converged ({p:?}, {})",
            c.noise, c.seed, c.exact.stop_reason
        ));
    }
    failures
}

/// Whether the case can tell a correction from none: the approximate fit
/// of the exact data is outside the target. (At 1 % noise some seeds'
/// reference errors are as large as the model error, 6 % and more, and
/// then it is not; the fast test uses a seed where it is.)
fn discriminates(c: &Case) -> Option<String> {
    (c.uncorrected.tan_delta <= TARGET_FACTOR * c.reference.tan_delta).then(|| {
        format!(
            "σ {} seed {}: the approximate fit of exact data is already within the target \
             ({:?} against {:?}): the test cannot tell a correction from none",
            c.noise, c.seed, c.uncorrected, c.reference
        )
    })
}

/// The fast comparison: σ = 0.1 % and 1 %, one seed each.
#[test]
fn exact_physics_removes_the_model_error_of_eq_11() {
    let data = cylinder_data();
    print_header();
    let mut failures = Vec::new();
    // The two noise levels are independent fits: computed on every core.
    let cases: Vec<Case> = [(0.001, 1), (0.01, 1)]
        .into_par_iter()
        .map(|(noise, seed)| case(exact_cylinder_setup(), data, noise, seed))
        .collect();
    for c in cases {
        print_row(&c);
        let p = c.exact.physics.as_ref().unwrap();
        assert_eq!(p.correction.len(), c.exact.mu_fit.len());
        // Adaptive sweeps: every fourth of the 41 speeds and the last at
        // least, never all of them.
        let sweeps = 1 + p.iterations;
        assert!(
            p.exact_solves >= 11 * sweeps && p.exact_solves < 41 * sweeps,
            "{p:?}"
        );
        failures.extend(check(&c));
        failures.extend(discriminates(&c));
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The study behind BENCHMARKS.md's exact-physics table: σ = 0.1 % (3 seeds) and 1 %
/// (5 seeds).
#[test]
#[ignore = "study, about 3 minutes: --ignored --nocapture exact_physics::study"]
fn study() {
    let data = cylinder_data();
    print_header();
    let mut failures = Vec::new();
    let mut cases = Vec::new();
    for (noise, seeds) in [(0.001, 0..3), (0.01, 0..5)] {
        for seed in seeds {
            let c = case(exact_cylinder_setup(), data, noise, seed);
            print_row(&c);
            failures.extend(check(&c));
            cases.push(c);
        }
    }
    for noise in [0.001, 0.01] {
        let of: Vec<&Case> = cases.iter().filter(|c| c.noise == noise).collect();
        let rms = |f: &dyn Fn(&Case) -> f64| {
            (of.iter().map(|c| f(c).powi(2)).sum::<f64>() / of.len() as f64).sqrt()
        };
        eprintln!(
            "σ = {} %, RMS over {} seeds: Eq.11 data/approximate {:.2} % / {:.2} %; exact \
             data/approximate {:.2} % / {:.2} %; exact data/exact {:.2} % / {:.2} %",
            100.0 * noise,
            of.len(),
            100.0 * rms(&|c| c.reference.tan_delta),
            100.0 * rms(&|c| c.reference.modulus),
            100.0 * rms(&|c| c.uncorrected.tan_delta),
            100.0 * rms(&|c| c.uncorrected.modulus),
            100.0 * rms(&|c| c.corrected.tan_delta),
            100.0 * rms(&|c| c.corrected.modulus),
        );
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The same comparison for a 5 mm ball at 1 N, σ = 0.1 % and 1 %. The
/// truth is the exact sphere at accuracy 1e-4 (a tenth of the smaller
/// noise; 1e-6 would need grids five times finer). For this rubber
/// Eq. (17) is within about 2 % of the exact sphere, so the uncorrected
/// fit may already be within the target at 1 %: only the target and the
/// convergence are checked, not that the case discriminates. The sphere's
/// sweeps solve at some speeds only and interpolate r to the others
/// (`exact_physics`, "Accuracy and cost"): the reported correction is
/// also checked against r solved at every speed at the reported modulus,
/// to within the accuracy asked plus that reference solve's own error
/// estimate (at the lowest speeds the sphere estimates 1e-4 … 2.5e-4 at
/// 144 cells, and its r jitters from speed to speed by that much, which
/// a correction interpolated there smooths out). About six minutes on
/// two cores:
/// `cargo test --release -p rollfit-fit --test it -- --ignored --nocapture exact_physics::sphere`
#[test]
#[ignore = "study, about six minutes: --ignored --nocapture exact_physics::sphere"]
fn exact_physics_for_a_sphere() {
    let data = exact_and_approximate(setup(), &rubber_200(), 1e-4).unwrap();
    print_header();
    let mut failures = Vec::new();
    for (noise, seed) in [(0.001, 1), (0.01, 1)] {
        let c = case(setup(), &data, noise, seed);
        print_row(&c);
        failures.extend(check(&c));
        let p = c.exact.physics.as_ref().unwrap();
        let off = correction_error(&c.exact, &data.speeds);
        let worst = off.iter().max_by(|a, b| a.0.total_cmp(&b.0)).unwrap();
        let beyond = off
            .iter()
            .filter(|(d, estimate)| *d > p.accuracy + estimate)
            .count();
        eprintln!(
            "σ = {} %: the reported r against r solved at all {} speeds: max |Δ ln r| = {:.1e} \
             (that solve's estimate {:.1e}; accuracy {:.1e}, {} exact solves in the fit)",
            100.0 * noise,
            data.speeds.len(),
            worst.0,
            worst.1,
            p.accuracy,
            p.exact_solves
        );
        if beyond > 0 {
            failures.push(format!(
                "σ {noise}: the reported correction is off from a full sweep by more than the \
                 accuracy {:.1e} plus the full sweep's own error estimate at {beyond} speeds",
                p.accuracy
            ));
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// Per speed, |ln(r_i/r̂_i)| of the reported correction r̂ against r solved
/// at every speed at the reported modulus (the exact sphere at the
/// accuracy the fit asked, over Eq. (17)), and that solve's own error
/// estimate; with the fit's rule for the exact material: strengths below
/// 1e-12 E1 left out, the largest kept, E0 kept.
fn correction_error(report: &FitReport, speeds: &[f64]) -> Vec<(f64, f64)> {
    use rollfit_model::Scene;
    use rollfit_model::exact::exact_body;

    let p = report.physics.as_ref().unwrap();
    let m = &report.model;
    let largest = m.strengths.iter().copied().fold(0.0, f64::max);
    let (mut strengths, mut tau, mut dropped) = (vec![], vec![], 0.0);
    for (&h, &t) in m.strengths.iter().zip(&m.tau) {
        if h >= 1e-12 * m.glassy_modulus || h == largest {
            strengths.push(h);
            tau.push(t);
        } else {
            dropped += h;
        }
    }
    let prony = Prony::new(m.glassy_modulus - dropped, strengths, tau).unwrap();
    let s = setup();
    let g = s.geometry;
    let body = exact_body(
        g.shape,
        &prony,
        s.substrate.poisson,
        g.radius,
        g.load,
        p.accuracy,
    )
    .unwrap();
    let exact: Vec<(f64, f64)> = speeds
        .par_iter()
        .map(|&v| {
            let x = body.exact_friction(v).unwrap();
            (x.mu, x.error_estimate)
        })
        .collect();
    let approximate = Scene::new(g, s.substrate, s.contact, prony)
        .unwrap()
        .friction_sweep(speeds)
        .unwrap();
    exact
        .iter()
        .zip(&approximate)
        .zip(&p.correction)
        .map(|((x, a), r)| ((x.0 / a / r).ln().abs(), x.1))
        .collect()
}

/// A temperature set (three temperatures, 15 speeds each, WLF truth) with
/// `physics = "exact"`: the correction of each row is the exact contact of
/// the master curve shifted to the row's temperature (`Prony::shifted`
/// with the fitted log10 a_T) at the row's own speed, over Eq. (11) there;
/// mu_fit is the approximate μ times it. (The data come from Eq. (11) to
/// keep the test short: what is checked is where r is taken.)
#[test]
fn a_temperature_set_is_corrected_at_each_rows_shifted_modulus() {
    use rollfit_fit::{Measurements, ShiftSettings};
    use rollfit_model::Scene;
    use rollfit_model::exact::exact_body;

    let s = exact_cylinder_setup();
    let truth = rubber_200();
    let scene = Scene::new(s.geometry, s.substrate, s.contact, truth.clone()).unwrap();
    let (mut v, mut mu, mut temps) = (vec![], vec![], vec![]);
    for t in [0.0, 20.0, 40.0] {
        for i in 0..15 {
            let speed = 1e-9 * 10f64.powf(5.0 * i as f64 / 14.0);
            let a = 10f64.powf(rolling::wlf_truth(t));
            v.push(speed);
            mu.push(scene.friction(speed * a).unwrap());
            temps.push(t);
        }
    }
    let sigma = mu.iter().map(|m| 0.003 * m).collect();
    let data = Measurements::new(v.clone(), mu, Some(sigma), Some(temps.clone())).unwrap();
    let params = FitParams {
        anchor: Some(ScaleAnchor::StaticModulus(2e6)),
        physics: Physics::Exact,
        shift: ShiftSettings {
            t_ref: Some(20.0),
            cross_check: false,
            ..ShiftSettings::default()
        },
        ..FitParams::default()
    }
    .check(s)
    .unwrap();
    let report = fit(&data, &params).unwrap();
    let p = report.physics.as_ref().unwrap();
    eprintln!("{p:?} in {:.1} s", report.wall_time_s);
    assert!(p.converged, "{p:?}");
    assert_eq!(p.correction.len(), v.len());
    let m = &report.model;
    let master = Prony::new(m.glassy_modulus, m.strengths.clone(), m.tau.clone()).unwrap();
    let shift = report.shift.as_ref().unwrap();
    for i in [0, 7, 14, 22, 30, 44] {
        let log_a = shift.log_shift_at(temps[i]).unwrap();
        let at_t = master.shifted(log_a).unwrap();
        let g = s.geometry;
        let body = exact_body(
            g.shape,
            &at_t,
            s.substrate.poisson,
            g.radius,
            g.load,
            p.accuracy,
        )
        .unwrap();
        let exact = body.exact_friction(v[i]).unwrap().mu;
        let approximate = Scene::new(g, s.substrate, s.contact, at_t)
            .unwrap()
            .friction(v[i])
            .unwrap();
        let r = exact / approximate;
        let (corrected, fitted) = (p.correction[i], report.mu_fit[i]);
        // Within the accuracy asked: the adaptive sweep interpolates r
        // between the speeds it solved at (within half the accuracy), and
        // r itself changes by percents across the set's reduced speeds, so
        // a correction taken at the wrong modulus or speed is far outside.
        assert!(
            (corrected / r - 1.0).abs() < p.accuracy,
            "row {i}: r = {corrected} against {r} at the shifted modulus"
        );
        assert!(
            (fitted / exact - 1.0).abs() < p.accuracy,
            "row {i}: mu_fit {fitted} against the exact {exact}"
        );
    }
}

/// Where Eq. (11) is the exact μ to the accuracy asked (a cylinder four
/// decades and more below the friction maximum of a standard linear solid:
/// r − 1 about 1e-9 against the 1e-3 asked at 1 % noise), the approximate
/// fit is the answer: no refit, one exact sweep, converged.
#[test]
fn no_refit_where_eq_11_is_already_exact() {
    use rollfit_fit::{Lambda, Measurements};
    use rollfit_model::{Scene, StandardLinearSolid};

    let s = exact_cylinder_setup();
    let truth = StandardLinearSolid::new(2e6, 2e7, 1e-2).unwrap();
    let scene = Scene::new(s.geometry, s.substrate, s.contact, truth).unwrap();
    let speeds: Vec<f64> = (0..9).map(|k| 1e-7 * 10f64.powf(0.25 * k as f64)).collect();
    let mu = scene.friction_sweep(&speeds).unwrap();
    let sigma = mu.iter().map(|m| 0.01 * m).collect();
    let data = Measurements::new(speeds, mu, Some(sigma), None).unwrap();
    let params = FitParams {
        anchor: Some(ScaleAnchor::StaticModulus(2e6)),
        physics: Physics::Exact,
        lambda: Lambda::Fixed(1.0),
        starts: 1,
        ..FitParams::default()
    }
    .check(s)
    .unwrap();
    let report = fit(&data, &params).unwrap();
    let p = report.physics.as_ref().unwrap();
    eprintln!("{p:?}");
    assert_eq!((p.iterations, p.exact_solves), (0, 9), "{p:?}");
    assert!(p.converged && p.max_correction <= p.accuracy, "{p:?}");
    assert_eq!(p.last_change, p.max_correction);
}
