//! The fidelity ladder and `auto` (crates/model/src/ladder): the model-error
//! estimate of Eq. (11) bounds the error against the exact cylinder on
//! solids it was not calibrated on; `auto` meets the requested accuracy
//! against the most faithful rung, computed independently and tightly,
//! and chooses cheaper rungs where they suffice; films are neglected only
//! where that is safe; a sphere near its friction maximum is reported as
//! not meeting a tight accuracy instead of being claimed to.

use rollfit_testkit::materials::{Lcg, random_prony};
use rollfit_testkit::scenes::scene;

use rollfit_model::exact::{
    CreepCompliance, ExactSettings, RollingCylinder, RollingSphere, SphereSettings,
};
use rollfit_model::ladder::{MODEL_ERROR_FACTOR, Rung, dynamic_contact_size};
use rollfit_model::{
    ContactSize, HavriliakNegami, Prony, Scene, Shape, StandardLinearSolid, ViscoelasticModulus,
};

const RADIUS: f64 = 0.01;
const LOAD: f64 = 100.0;

fn sls(ratio: f64, tau: f64) -> Prony {
    StandardLinearSolid::new(1e6, ratio * 1e6, tau)
        .unwrap()
        .to_prony()
}

fn roller(material: Prony, film: Option<f64>) -> Scene<Prony> {
    scene(
        Shape::Cylinder,
        RADIUS,
        LOAD,
        0.5,
        film,
        ContactSize::Dynamic,
        material,
    )
}

/// μ of `scene` at `speeds` by Eq. (11)/(17) at tolerance 1e-10.
fn tight_sweep<M: ViscoelasticModulus + Clone>(scene: &Scene<M>, speeds: &[f64]) -> Vec<f64> {
    scene
        .clone()
        .with_tolerance(1e-10)
        .unwrap()
        .friction_sweep(speeds)
        .unwrap()
}

/// `count` log-spaced speeds from 10^lo to 10^hi m/s.
fn speeds(lo: f64, hi: f64, count: usize) -> Vec<f64> {
    (0..count)
        .map(|i| 10f64.powf(lo + (hi - lo) * i as f64 / (count - 1) as f64))
        .collect()
}

/// Speeds from 1e-4 a0/λ_max (λ_max the longest retardation time: the
/// slowest creep, which sets where the low-speed limit begins) up to
/// 1e3 a0/τ_min (τ_min the shortest relaxation time), 3 a decade.
fn natural_sweep(material: &Prony, a0: f64) -> Vec<f64> {
    sweep_from(1e-4, material, a0)
}

/// As [`natural_sweep`] from `lowest` a0/λ_max.
fn sweep_from(lowest: f64, material: &Prony, a0: f64) -> Vec<f64> {
    sweep_at(3.0, lowest, material, a0)
}

/// As [`sweep_from`] with `per_decade` speeds a decade.
fn sweep_at(per_decade: f64, lowest: f64, material: &Prony, a0: f64) -> Vec<f64> {
    let creep = CreepCompliance::from_prony(material);
    let lambda_max = creep.retardation_times.iter().copied().fold(0.0, f64::max);
    let tau_min = material
        .relaxation_times()
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    let (lo, hi) = (
        (lowest * a0 / lambda_max).log10(),
        (1e3 * a0 / tau_min).log10(),
    );
    speeds(lo, hi, ((hi - lo) * per_decade).ceil() as usize + 1)
}

/// The estimate K μR/b bounds the error of Eq. (11) on solids other than
/// those it was calibrated on (other E1/E0, other random spectra).
#[test]
fn model_error_estimate_bounds_eq11_on_other_solids() {
    let mut rng = Lcg(20261123);
    let mut solids: Vec<(String, Prony)> = [3.0, 30.0, 300.0, 3000.0]
        .iter()
        .map(|&r| (format!("SLS E1/E0 = {r}"), sls(r, 0.1)))
        .collect();
    for k in 0..5 {
        let terms = 4 + 2 * k;
        solids.push((
            format!("random Prony, {terms} terms"),
            random_prony(&mut rng, terms, -5.0, 0.9),
        ));
    }
    let mut worst_ratio = 0.0f64;
    for (name, material) in &solids {
        let cylinder = RollingCylinder::new(material, 0.5, RADIUS, LOAD).unwrap();
        let eq11 = roller(material.clone(), None).with_tolerance(1e-9).unwrap();
        let sweep = sweep_at(2.0, 1e-4, material, eq11.static_contact_size());
        let mu = eq11.friction_sweep(&sweep).unwrap();
        for (&v, &m) in sweep.iter().zip(&mu) {
            let exact = cylinder.solve(v).unwrap().mu;
            let error = (m / exact - 1.0).abs();
            let asymmetry = m * RADIUS / dynamic_contact_size(&eq11, v);
            // Where the exact solution's edge layers are not resolved (very
            // low speed) it is itself good to about 1e-4 only.
            let reference_error = if cylinder.resolves_edge_layers(v) {
                1e-6
            } else {
                1e-4
            };
            if cylinder.resolves_edge_layers(v) {
                worst_ratio = worst_ratio.max(error / asymmetry);
            }
            assert!(
                error <= MODEL_ERROR_FACTOR * asymmetry + reference_error,
                "{name}, v = {v:e}: Eq. (11) off by {error:.3e}, estimate {:.3e}",
                MODEL_ERROR_FACTOR * asymmetry
            );
        }
    }
    eprintln!("largest |error|/(μR/b) on the test solids: {worst_ratio:.3}");
}

/// `auto` against the exact cylinder (192 terms where the default 128 do
/// not resolve its edge layers): within the accuracy wherever it says so,
/// at every speed for solids whose layers the default resolves, and
/// cheaper rungs at the ends of the sweep.
#[test]
fn auto_meets_the_accuracy_against_the_exact_cylinder() {
    let mut rng = Lcg(7);
    let solids = [
        ("SLS 10", sls(10.0, 1.0), true),
        ("SLS 1000", sls(1000.0, 1.0), false),
        ("random Prony", random_prony(&mut rng, 6, -4.0, 0.5), true),
    ];
    for (name, material, all_met) in solids {
        let cylinder = RollingCylinder::new(&material, 0.5, RADIUS, LOAD).unwrap();
        let fine = RollingCylinder::with_settings(
            &material,
            0.5,
            RADIUS,
            LOAD,
            ExactSettings {
                max_terms: 192,
                ..ExactSettings::default()
            },
        )
        .unwrap();
        let s = roller(material.clone(), None);
        // From 1e-5 a0/τ_max: at ε = 1e-3 the slowest speeds are the
        // asymptote's (vτ/a0 = 1e-4 for the SLS).
        let sweep = sweep_from(1e-5, &material, s.static_contact_size());
        let reference: Vec<f64> = sweep.iter().map(|&v| fine.solve(v).unwrap().mu).collect();
        for accuracy in [1e-1, 1e-2, 1e-3] {
            let auto = s.friction_auto(&sweep, accuracy, Ok(&cylinder)).unwrap();
            let mut worst = 0.0f64;
            for i in 0..sweep.len() {
                let error = (auto.mu[i] / reference[i] - 1.0).abs();
                if auto.error_estimate[i] > accuracy {
                    // Said so: not claimed.
                    continue;
                }
                worst = worst.max(error);
                assert!(
                    error <= accuracy,
                    "{name}, accuracy {accuracy}: v = {:e} by {:?} off by {error:.2e}",
                    sweep[i],
                    auto.rungs[i]
                );
            }
            eprintln!(
                "{name}, accuracy {accuracy:.0e}: not met at {}",
                auto.unmet()
            );
            if all_met {
                assert_eq!(auto.unmet(), 0, "{name} {accuracy}");
            }
            assert!(auto.unmet() < sweep.len() / 4, "{name} {accuracy}");
            let count = |r: Rung| auto.rungs.iter().filter(|&&x| x == r).count();
            eprintln!(
                "{name}, accuracy {accuracy:.0e}: worst error {worst:.2e}; low-speed {}, \
                 dynamic {}, exact {} of {}",
                count(Rung::LowSpeed),
                count(Rung::Dynamic),
                count(Rung::Exact),
                sweep.len()
            );
            // The slowest speed needs no contact solve at any accuracy here
            // (Eq. (11) and the asymptote are exact as v → 0).
            assert_ne!(auto.rungs[0], Rung::Exact, "{name} {accuracy}");
            assert!(count(Rung::Exact) < sweep.len(), "{name} {accuracy}");
            if accuracy >= 1e-2 {
                assert!(count(Rung::LowSpeed) > 0, "{name} {accuracy}");
            }
        }
        // A loose accuracy needs fewer contact solves than a tight one.
        let loose = s.friction_auto(&sweep, 1e-1, Ok(&cylinder)).unwrap();
        let tight = s.friction_auto(&sweep, 1e-3, Ok(&cylinder)).unwrap();
        let exact_count = |a: &rollfit_model::ladder::AutoSweep| {
            a.rungs.iter().filter(|&&r| r == Rung::Exact).count()
        };
        assert!(exact_count(&loose) < exact_count(&tight), "{name}");
    }
}

/// A sphere whose exact rung is unavailable (as for a modulus that is no
/// Prony series): `auto` meets the accuracy against Eq. (17) computed
/// tightly, and near the friction maximum says that a tight accuracy is
/// not met (the model error of Eq. (17) itself).
#[test]
fn auto_for_a_sphere_is_honest_about_eq17() {
    let material = sls(10.0, 1.0);
    let s = scene(
        Shape::Sphere,
        RADIUS,
        0.15,
        0.5,
        None,
        ContactSize::Dynamic,
        material.clone(),
    );
    let sweep = natural_sweep(&material, s.static_contact_size());
    let tight = tight_sweep(&s, &sweep);
    for accuracy in [1e-1, 1e-2, 1e-3] {
        let auto = s
            .friction_auto(
                &sweep,
                accuracy,
                Err("no exact solution for a sphere".into()),
            )
            .unwrap();
        for i in 0..sweep.len() {
            let error = (auto.mu[i] / tight[i] - 1.0).abs();
            assert!(
                error <= accuracy,
                "accuracy {accuracy}: v = {:e} off Eq. (17) by {error:.2e}",
                sweep[i]
            );
        }
        assert!(auto.rungs.iter().all(|&r| r != Rung::Exact));
    }
    let auto = s
        .friction_auto(&sweep, 1e-3, Err("no exact solution for a sphere".into()))
        .unwrap();
    assert!(auto.unmet() > 0);
    let text = auto.description(&sweep, Shape::Sphere);
    assert!(text.contains("NOT MET"), "{text}");
    eprintln!("{text}");
}

/// Films: a thick one is neglected where its bound allows, and then its
/// real effect is within the share of the accuracy; a thin one is
/// computed. Either way μ is within the accuracy of the film model.
#[test]
fn auto_neglects_a_film_only_where_it_does_not_matter() {
    let material = sls(10.0, 1.0);
    let half_space = roller(material.clone(), None)
        .with_tolerance(1e-10)
        .unwrap();
    let a0 = half_space.static_contact_size();
    let cylinder = RollingCylinder::new(&material, 0.5, RADIUS, LOAD).unwrap();
    let accuracy = 1e-2;
    let sweep = natural_sweep(&material, a0);
    let half = half_space.friction_sweep(&sweep).unwrap();
    for (ratio, mostly_neglected) in [(1e3, true), (1.0, false)] {
        let d = ratio * a0;
        let s = roller(material.clone(), Some(d));
        let film_model = tight_sweep(&s, &sweep);
        let auto = s.friction_auto(&sweep, accuracy, Ok(&cylinder)).unwrap();
        let computed = auto
            .rungs
            .iter()
            .filter(|&&r| r == Rung::DynamicFilm)
            .count();
        eprintln!(
            "d = {ratio} a0: film computed at {computed} of {} speeds",
            sweep.len()
        );
        for i in 0..sweep.len() {
            // The bound is within a factor of 10 of the film's real effect:
            // where that is below a tenth of its share, the film is neglected.
            let effect = 1.0 - film_model[i] / half[i];
            if effect <= 0.03 * accuracy && auto.rungs[i] != Rung::LowSpeed {
                assert_ne!(
                    auto.rungs[i],
                    Rung::DynamicFilm,
                    "d = {ratio} a0, v = {:e}: effect {effect:.1e}",
                    sweep[i]
                );
            }
        }
        if mostly_neglected {
            assert!(
                computed < sweep.len() / 2,
                "d = {ratio} a0: {:?}",
                auto.rungs
            );
        } else {
            assert!(
                computed > sweep.len() / 2,
                "d = {ratio} a0: {:?}",
                auto.rungs
            );
        }
        for i in 0..sweep.len() {
            if matches!(auto.rungs[i], Rung::Dynamic | Rung::Exact) {
                let effect = 1.0 - film_model[i] / half[i];
                assert!(
                    effect <= 0.3 * accuracy,
                    "d = {ratio} a0, v = {:e}: film neglected but changes μ by {effect:.2e}",
                    sweep[i]
                );
            }
            // Against the film model (the film has no exact rung); where
            // auto used the exact cylinder, Eq. (11)'s own error comes in.
            let error = (auto.mu[i] / film_model[i] - 1.0).abs();
            let allowed = if auto.rungs[i] == Rung::Exact {
                accuracy + MODEL_ERROR_FACTOR * film_model[i] * RADIUS / a0
            } else {
                accuracy
            };
            assert!(
                error <= allowed,
                "d = {ratio} a0, v = {:e} by {:?}: off by {error:.2e}",
                sweep[i],
                auto.rungs[i]
            );
        }
    }
}

/// A non-Prony modulus has no exact rung; auto still works against Eq. (11).
#[test]
fn auto_with_a_havriliak_negami_solid() {
    let material = HavriliakNegami::new(2e6, 1e9, 1e-3, 0.6, 0.4).unwrap();
    let s = scene(
        Shape::Cylinder,
        RADIUS,
        LOAD,
        0.5,
        None,
        ContactSize::Dynamic,
        material,
    );
    let sweep = speeds(-12.0, 2.0, 29);
    let tight = tight_sweep(&s, &sweep);
    let auto = s
        .friction_auto(&sweep, 1e-2, Err("not a Prony series".into()))
        .unwrap();
    for i in 0..sweep.len() {
        assert!(
            (auto.mu[i] / tight[i] - 1.0).abs() <= 1e-2,
            "v = {:e}",
            sweep[i]
        );
    }
    let text = auto.description(&sweep, Shape::Cylinder);
    assert!(text.contains("not a Prony series"), "{text}");
}

#[test]
fn bad_requests_are_refused() {
    let material = sls(10.0, 1.0);
    let s = roller(material.clone(), None);
    let cylinder = RollingCylinder::new(&material, 0.5, RADIUS, LOAD).unwrap();
    for accuracy in [0.0, -1e-3, f64::NAN, 0.9, 1e-9] {
        let e = s
            .friction_auto(&[1e-3], accuracy, Ok(&cylinder))
            .unwrap_err();
        assert!(e.to_string().contains("accuracy"), "{e}");
    }
    let e = s
        .friction_auto(&[1e-3, 1e-4], 1e-2, Ok(&cylinder))
        .unwrap_err();
    assert!(e.to_string().contains("increasing"), "{e}");
    // Another cylinder's exact solution is not this scene's.
    let other = RollingCylinder::new(&material, 0.5, 2.0 * RADIUS, LOAD).unwrap();
    assert!(s.friction_auto(&[1e-3], 1e-2, Ok(&other)).is_err());
    // Modulus use is by reference: the scene's material is untouched.
    assert_eq!(s.material().static_modulus(), 1e6);
}

/// Extremes: E1/E0 = 1e4 from 1e-12 to 1e6 natural speeds a0/τ.
/// Every μ is finite and positive with a finite estimate; the slowest
/// speeds are the asymptote's; where even the exact cylinder cannot be
/// resolved (the stiff solid near its maximum) the result says NOT MET
/// rather than claiming the accuracy.
#[test]
fn auto_at_the_extremes_is_finite_and_says_what_it_cannot_meet() {
    let material = sls(1e4, 1.0);
    let cylinder = RollingCylinder::new(&material, 0.5, RADIUS, LOAD).unwrap();
    let s = roller(material, None);
    let a0 = s.static_contact_size();
    let sweep: Vec<f64> = (0..=18).map(|k| a0 * 10f64.powi(k - 12)).collect();
    let auto = s.friction_auto(&sweep, 1e-3, Ok(&cylinder)).unwrap();
    for ((v, mu), estimate) in sweep.iter().zip(&auto.mu).zip(&auto.error_estimate) {
        assert!(mu.is_finite() && *mu > 0.0, "v = {v:e}");
        assert!(estimate.is_finite(), "v = {v:e}");
    }
    assert_eq!(auto.rungs[0], Rung::LowSpeed);
    let text = auto.description(&sweep, Shape::Cylinder);
    eprintln!("{text}");
    assert_eq!(text.contains("NOT MET"), auto.unmet() > 0, "{text}");
}

/// A ball on the solids of the Eq. (17) error map of docs/validation.md.
fn ball(material: Prony, poisson: f64) -> Scene<Prony> {
    scene(
        Shape::Sphere,
        RADIUS,
        1.0,
        poisson,
        None,
        ContactSize::Dynamic,
        material,
    )
}

/// The model-error estimate K μR/b against the exact sphere: the largest
/// |μ_Eq.17/μ_exact − 1|/(μR/b) over standard linear solids E1/E0 = 2,
/// 10, 100, 1000 (ν = 0: with a constant ν both models see E only
/// through E/(1 − ν²), and ν = ½ measured the same ratios), at 2 speeds a
/// decade over six decades
/// around the friction maximum; cells where the exact sphere's own error
/// estimate is not below a tenth of the model error are left out of the
/// supremum (they measure the exact sphere, not Eq. (17)). Prints the
/// table the module documentation of `ladder::model_error` quotes.
///
/// `cargo test --release -p rollfit-model --test it -- --ignored --nocapture ladder::eq17_model_error_factor`
#[test]
#[ignore = "study, about 11 minutes"]
fn eq17_model_error_factor() {
    let mut worst = (0.0f64, String::new());
    let poisson = 0.0;
    for ratio in [2.0, 10.0, 100.0, 1000.0] {
        let material = sls(ratio, 1.0);
        let eq17 = ball(material.clone(), poisson)
            .with_tolerance(1e-9)
            .unwrap();
        let body = RollingSphere::with_settings(
            &material,
            poisson,
            RADIUS,
            1.0,
            SphereSettings::for_accuracy(1e-3),
        )
        .unwrap();
        let r0 = body.static_contact_radius();
        let probe = speeds((1e-4 * r0).log10(), (1e4 * r0).log10(), 81);
        let mu = eq17.friction_sweep(&probe).unwrap();
        let peak = probe[(0..mu.len())
            .max_by(|&a, &b| mu[a].total_cmp(&mu[b]))
            .unwrap()];
        let sweep = speeds((peak * 1e-3).log10(), (peak * 1e3).log10(), 13);
        let mu = eq17.friction_sweep(&sweep).unwrap();
        let mut row_worst = 0.0f64;
        for (&v, &m) in sweep.iter().zip(&mu) {
            let exact = body.solve(v).unwrap();
            let error = (m / exact.mu - 1.0).abs();
            let asymmetry = m * RADIUS / dynamic_contact_size(&eq17, v);
            let factor = error / asymmetry;
            let resolved = exact.error_estimate < 0.1 * error;
            println!(
                "ν = {poisson}, E1/E0 = {ratio}, vτ/r0 = {:.2e}: error {error:.2e}, μR/b {asymmetry:.2e}, \
                     ratio {factor:.3}, exact's estimate {:.1e}{}",
                v / r0,
                exact.error_estimate,
                if resolved { "" } else { " (not counted)" }
            );
            if resolved {
                row_worst = row_worst.max(factor);
                if factor > worst.0 {
                    worst = (
                        factor,
                        format!("ν = {poisson}, E1/E0 = {ratio}, vτ/r0 = {:.2e}", v / r0),
                    );
                }
            }
        }
        println!("ν = {poisson}, E1/E0 = {ratio}: largest ratio {row_worst:.3}");
    }
    println!("largest |error|/(μR/b): {:.3} at {}", worst.0, worst.1);
}

/// `auto` for a ball against the exact sphere: within the accuracy
/// wherever it claims it (measured against the exact sphere on a finer
/// grid, up to that reference's own estimate), the exact rung only where
/// Eq. (17)'s estimated model error needs it.
#[test]
fn auto_meets_the_accuracy_against_the_exact_sphere() {
    let material = sls(10.0, 1.0);
    let s = ball(material.clone(), 0.5);
    let cheap = RollingSphere::with_settings(
        &material,
        0.5,
        RADIUS,
        1.0,
        SphereSettings::for_accuracy(1e-2),
    )
    .unwrap();
    let fine = cheap.with_cells(SphereSettings::for_accuracy(1e-3).cells);
    // One speed a decade over the whole curve: 1e-4 a0/λ … 1e3 a0/τ.
    let sweep = sweep_at(1.0, 1e-4, &material, s.static_contact_size());
    let mut reference: Vec<Option<(f64, f64)>> = vec![None; sweep.len()];
    for accuracy in [1e-1, 3e-2] {
        let auto = s.friction_auto_with(&sweep, accuracy, Ok(&cheap)).unwrap();
        assert_eq!(auto.unmet(), 0, "accuracy {accuracy}");
        for i in 0..sweep.len() {
            let (exact, its_error) = *reference[i].get_or_insert_with(|| {
                let solution = fine.solve(sweep[i]).unwrap();
                (solution.mu, solution.error_estimate)
            });
            let error = (auto.mu[i] / exact - 1.0).abs();
            assert!(
                error <= accuracy + its_error,
                "accuracy {accuracy}: v = {:e} by {:?} off the exact sphere by {error:.2e}",
                sweep[i],
                auto.rungs[i]
            );
        }
        let exact = auto.rungs.iter().filter(|&&r| r == Rung::Exact).count();
        eprintln!(
            "ball, accuracy {accuracy:.0e}: exact sphere at {exact} of {} speeds",
            sweep.len()
        );
        assert!(exact < sweep.len(), "accuracy {accuracy}");
        assert_ne!(auto.rungs[0], Rung::Exact, "accuracy {accuracy}");
    }
}
