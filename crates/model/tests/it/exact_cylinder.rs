//! The exact steady rolling cylinder (crates/model/src/exact): checks
//! against Hertz, the load, the creep compliance, the speed limits, grid
//! convergence and Persson's Eq. (11) (dynamic contact size); and the
//! graded mesh for stiff solids against the semi-analytic solution
//! written out below (`semi_analytic`).

use rollfit_testkit::{materials, scenes};

use std::f64::consts::PI;

use rollfit_model::exact::{
    CreepCompliance, ExactMethod, ExactSettings, GRADED_ERROR, GRADED_FLOOR, RollingCylinder,
};
use rollfit_model::{ContactSize, Prony, Shape, ViscoelasticModulus};
use rollfit_testkit::materials::{rippled_prony, sls};
use semi_analytic::Reference;

const RADIUS: f64 = 0.01;
const LOAD: f64 = 100.0;

/// A broad 15-term series, one term per decade from 1e-10 s.
fn broad_prony() -> Prony {
    rippled_prony(15, -10, 0.12)
}

fn cylinder(material: &Prony, terms: Option<usize>) -> RollingCylinder {
    let settings = ExactSettings {
        terms,
        ..ExactSettings::default()
    };
    RollingCylinder::with_settings(material, 0.5, RADIUS, LOAD, settings).unwrap()
}

/// 1/E*(ω) from the retardation spectrum equals 1/E*(ω) computed directly.
#[test]
fn creep_compliance_reproduces_the_modulus() {
    for material in [sls(10.0).to_prony(), sls(1e3).to_prony(), broad_prony()] {
        let creep = CreepCompliance::from_prony(&material);
        let e0 = material.static_modulus();
        assert!((creep.equilibrium() * e0 - 1.0).abs() < 1e-13);
        assert!(creep.strengths.iter().all(|&c| c > 0.0));
        let mut worst = 0.0f64;
        for i in 0..=400 {
            let omega = 10f64.powf(-14.0 + 0.07 * i as f64);
            let direct = 1.0 / material.modulus(omega);
            let err = (creep.complex_compliance(omega) - direct).norm() / direct.norm();
            worst = worst.max(err);
        }
        println!("{} terms: worst relative error {worst:.2e}", material.len());
        // E1/E0 = 1000 loses a little to cancellation in the direct 1/E*.
        assert!(worst < 5e-13, "{worst}");
    }
    // The standard linear solid's retardation time is the paper's τ.
    let creep = CreepCompliance::from_prony(&sls(10.0).to_prony());
    assert!((creep.retardation_times[0] - 1.0).abs() < 1e-14);
}

/// E1 = E0: Hertz pressure, symmetric edges, μ = 0.
#[test]
fn elastic_limit_is_hertz() {
    for material in [
        Prony::new(2e6, vec![], vec![]).unwrap(),
        sls(1.0).to_prony(),
    ] {
        let cyl = cylinder(&material, None);
        let a = cyl.static_half_width();
        for v in [1e-6, 1.0, 1e6] {
            let sol = cyl.solve(v).unwrap();
            assert!(sol.mu.abs() < 1e-10, "μ = {}", sol.mu);
            assert!((sol.leading_edge / a - 1.0).abs() < 1e-10);
            assert!((sol.trailing_edge / a + 1.0).abs() < 1e-10);
            let p0 = 2.0 * LOAD / (PI * a);
            for (x, p) in sol.pressure_profile(41) {
                let hertz = 2.0 * LOAD / (PI * a * a) * (a * a - x * x).max(0.0).sqrt();
                assert!((p - hertz).abs() < 1e-10 * p0, "x {x}: {p} vs {hertz}");
            }
        }
    }
}

/// ∫p dx = f_N and ∫x p dx = f_N x̄ by an independent quadrature; p ≥ 0.
#[test]
fn pressure_integrates_to_the_load() {
    for material in [sls(10.0).to_prony(), broad_prony()] {
        let cyl = cylinder(&material, None);
        let a0 = cyl.static_half_width();
        for x in [1e-2, 0.3, 1.0, 3.0, 30.0] {
            let sol = cyl.solve(x * a0).unwrap();
            // x = c − b cos θ: the integrand p b sin θ is smooth and
            // periodic, so the trapezoid rule in θ converges spectrally.
            let (c, b) = (sol.center(), sol.half_width());
            let n = 4000;
            let (mut load, mut moment) = (0.0, 0.0);
            for i in 1..n {
                let theta = PI * i as f64 / n as f64;
                let xi = c - b * theta.cos();
                let p = sol.pressure(xi);
                assert!(p >= -1e-9 * LOAD / a0, "p({xi}) = {p}");
                let w = b * theta.sin() * PI / n as f64;
                load += p * w;
                moment += p * xi * w;
            }
            assert!((load / LOAD - 1.0).abs() < 1e-10, "load {load}");
            assert!(
                (moment / LOAD - sol.centroid).abs() < 1e-10 * a0,
                "centroid {} vs {}",
                moment / LOAD,
                sol.centroid
            );
            assert!(sol.mu > 0.0);
        }
    }
}

/// Low speed: Hertz with E0 and Eq. (11)'s low-speed asymptote, μ ∝ v;
/// high speed: Hertz with E1 and Eq. (11) itself (both perturbative limits
/// are exact to first order in the loss).
#[test]
fn speed_limits_agree_with_eq11() {
    for material in [sls(10.0).to_prony(), broad_prony()] {
        let cyl = cylinder(&material, None);
        let scene = scenes::scene(
            Shape::Cylinder,
            RADIUS,
            LOAD,
            0.5,
            None,
            ContactSize::Dynamic,
            material.clone(),
        );
        let a0 = cyl.static_half_width();
        let ag = cyl.glassy_half_width();
        let tau_max = material
            .relaxation_times()
            .iter()
            .cloned()
            .fold(0.0, f64::max);
        let tau_min = material
            .relaxation_times()
            .iter()
            .cloned()
            .fold(f64::INFINITY, f64::min);
        let slow = cyl.solve(1e-5 * a0 / tau_max).unwrap();
        let ratio = slow.mu / scene.low_speed_asymptote(slow.speed);
        println!(
            "{} terms: low speed μ/asymptote = {ratio:.8}",
            material.len()
        );
        assert!((ratio - 1.0).abs() < 5e-4, "{ratio}");
        let width = slow.half_width() / a0 - 1.0;
        println!("{} terms: low speed b/a0 − 1 = {width:.2e}", material.len());
        assert!(width.abs() < 1e-3, "{width}");
        let fast = cyl.solve(1e5 * ag / tau_min).unwrap();
        let ratio = fast.mu / scene.friction(fast.speed).unwrap();
        println!(
            "{} terms: high speed μ/Eq.(11) = {ratio:.8}",
            material.len()
        );
        assert!((ratio - 1.0).abs() < 1e-4, "{ratio}");
        assert!((fast.half_width() / ag - 1.0).abs() < 1e-4);
    }
}

/// Grid convergence of the default settings against N = 360, and the
/// observed order (error against N at a fixed speed).
#[test]
fn grid_convergence() {
    let material = sls(10.0).to_prony();
    let reference_cyl = cylinder(&material, Some(360));
    let default_cyl = cylinder(&material, None);
    let a0 = default_cyl.static_half_width();
    let mut worst = 0.0f64;
    for x in [1e-3, 1e-2, 0.1, 0.5, 1.0, 2.0, 10.0, 100.0] {
        let v = x * a0;
        let reference = reference_cyl.solve(v).unwrap();
        let start = std::time::Instant::now();
        let sol = default_cyl.solve(v).unwrap();
        let elapsed = start.elapsed();
        let err = (sol.mu / reference.mu - 1.0).abs();
        let edge = ((sol.leading_edge - reference.leading_edge).abs()
            + (sol.trailing_edge - reference.trailing_edge).abs())
            / a0;
        println!(
            "vτ/a0 {x:7.0e}: N = {:3}, μ rel. error {err:.1e}, edge error/a0 {edge:.1e}, {elapsed:?}",
            sol.coefficients.len()
        );
        worst = worst.max(err);
    }
    println!("worst relative error of μ at default settings: {worst:.1e}");
    assert!(worst < 1e-5, "{worst}");
    // Order: at vτ/a0 = 0.01 the error falls like exp(−κN).
    let v = 1e-2 * a0;
    let reference = reference_cyl.solve(v).unwrap();
    let mut previous: Option<(usize, f64)> = None;
    for n in [16, 24, 32, 48, 64, 96, 128] {
        let sol = cylinder(&material, Some(n)).solve(v).unwrap();
        let err = (sol.mu / reference.mu - 1.0).abs().max(1e-16);
        match previous {
            Some((m, e)) => println!(
                "N = {n:3}: error {err:.2e}, algebraic order {:.1}, exponential rate {:.3}/term",
                (e / err).ln() / (n as f64 / m as f64).ln(),
                (e / err).ln() / (n - m) as f64
            ),
            None => println!("N = {n:3}: error {err:.2e}"),
        }
        previous = Some((n, err));
    }
}

/// Large E1/E0: the edge layer is as thin as v times the relaxation time
/// τE0/E1, not the retardation time τ (the rule before 2026-11-23 used τ
/// and was 6 % off at E1/E0 = 1000, vτ/a0 = 0.3, while calling itself
/// converged). Where the default settings say they resolve the layers, μ
/// agrees with N = 192 to 1e-5 (measured ≤ 3.6e-7); where they do not, they
/// say so.
#[test]
fn grid_convergence_at_large_ratios() {
    let mut rng = materials::Lcg(99);
    let solids = [
        ("SLS 100", sls(100.0).to_prony()),
        ("SLS 1000", sls(1000.0).to_prony()),
        ("SLS 1e4", sls(1e4).to_prony()),
        (
            "random Prony",
            materials::random_prony(&mut rng, 6, -3.0, 0.5),
        ),
    ];
    for (name, material) in solids {
        let default_cyl = cylinder(&material, None);
        let reference_cyl = cylinder(&material, Some(192));
        let a0 = default_cyl.static_half_width();
        let (mut worst, mut resolved, mut unresolved) = (0.0f64, 0, 0);
        for k in 0..=12 {
            let v = a0 * 10f64.powf(-3.0 + 0.5 * k as f64);
            if !default_cyl.resolves_edge_layers(v) {
                unresolved += 1;
                continue;
            }
            resolved += 1;
            let err =
                (default_cyl.solve(v).unwrap().mu / reference_cyl.solve(v).unwrap().mu - 1.0).abs();
            worst = worst.max(err);
        }
        println!("{name}: {resolved} speeds resolved (worst error {worst:.1e}), {unresolved} not");
        assert!(worst < 1e-5, "{name}: {worst}");
        assert!(resolved >= 4, "{name}");
    }
    // The speeds where the old rule was wrong are now flagged.
    let stiff = sls(1000.0).to_prony();
    let cyl = cylinder(&stiff, None);
    let a0 = cyl.static_half_width();
    for x in [0.03, 0.1, 0.3] {
        assert!(!cyl.resolves_edge_layers(x * a0), "vτ/a0 = {x}");
    }
}

/// A coarser layer resolution C (fewer terms, for `auto` at a loose
/// accuracy) stays within the error it claims, against 192 terms.
#[test]
fn coarser_resolutions_meet_their_claimed_error() {
    let mut rng = materials::Lcg(5);
    let solids = [
        ("SLS 2", sls(2.0).to_prony()),
        ("SLS 10", sls(10.0).to_prony()),
        ("SLS 1000", sls(1000.0).to_prony()),
        (
            "random Prony",
            materials::random_prony(&mut rng, 5, -3.0, 0.5),
        ),
    ];
    for (name, material) in solids {
        let reference_cyl = cylinder(&material, Some(192));
        let a0 = reference_cyl.static_half_width();
        let speeds: Vec<f64> = (0..=10)
            .map(|k| a0 * 10f64.powf(-2.0 + 0.5 * k as f64))
            .collect();
        let reference: Vec<f64> = speeds
            .iter()
            .map(|&v| reference_cyl.solve(v).unwrap().mu)
            .collect();
        for resolution in [1.5, 2.0, 3.0] {
            let coarse = cylinder(&material, None).with_layer_resolution(resolution);
            let claimed = coarse.settings().resolved_error();
            let mut worst = 0.0f64;
            for (&v, &r) in speeds.iter().zip(&reference) {
                let sol = coarse.solve(v).unwrap();
                if !sol.resolved {
                    continue;
                }
                assert_eq!(sol.error_estimate, claimed);
                worst = worst.max((sol.mu / r - 1.0).abs());
            }
            println!("{name}, C = {resolution}: worst {worst:.1e}, claimed {claimed:.1e}");
            assert!(
                worst <= claimed,
                "{name}, C = {resolution}: {worst:e} > {claimed:e}"
            );
        }
    }
}

/// Standard linear solid, E1/E0 = 10: one maximum of μR/a0 against vτ/a0,
/// slightly above and at a slightly higher speed than Eq. (11)'s.
#[test]
fn sls_maximum_against_eq11() {
    let s = sls(10.0);
    let material = s.to_prony();
    let cyl = cylinder(&material, None);
    let a0 = cyl.static_half_width();
    let scale = RADIUS / a0;
    let exact = |x: f64| cyl.solve(x * a0 / s.tau()).unwrap().mu * scale;
    // One maximum: the sampled curve rises, then falls.
    let xs: Vec<f64> = (0..=60)
        .map(|i| 10f64.powf(-3.0 + 0.1 * i as f64))
        .collect();
    let mus: Vec<f64> = xs.iter().map(|&x| exact(x)).collect();
    let turns = mus
        .windows(3)
        .filter(|w| (w[1] - w[0]).signum() != (w[2] - w[1]).signum())
        .count();
    assert_eq!(turns, 1, "{mus:?}");
    // Golden-section refinement in ln x.
    let k = mus
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .unwrap()
        .0;
    let (mut lo, mut hi) = (xs[k - 1].ln(), xs[k + 1].ln());
    let g = 0.5 * (5f64.sqrt() - 1.0);
    while hi - lo > 1e-7 {
        let (m1, m2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if exact(m1.exp()) > exact(m2.exp()) {
            hi = m2;
        } else {
            lo = m1;
        }
    }
    let x_exact = (0.5 * (lo + hi)).exp();
    let mu_exact = exact(x_exact);
    let scene = scenes::scene(
        Shape::Cylinder,
        RADIUS,
        LOAD,
        0.5,
        None,
        ContactSize::Dynamic,
        s.clone(),
    );
    let peak = scene
        .friction_maximum(1e-3 * a0 / s.tau(), 1e3 * a0 / s.tau())
        .unwrap();
    let x11 = peak.speed * s.tau() / a0;
    let mu11 = peak.mu * scale;
    println!(
        "exact maximum μR/a0 = {mu_exact:.6} at vτ/a0 = {x_exact:.5}; \
         Eq. (11) (dynamic) {mu11:.6} at {x11:.5}: ratio {:.4}, speed ratio {:.4}",
        mu_exact / mu11,
        x_exact / x11
    );
    assert!(mu_exact > mu11 && mu_exact < 1.05 * mu11);
    assert!(x_exact > x11 && x_exact < 3.0 * x11);
}

/// Stiff standard linear solids below the friction maximum and at
/// low speed, where 128 Chebyshev terms leave the edge layers (v τE0/E1
/// wide) unresolved — μ was off by up to 5.4 % at E1/E0 = 1e4, vτ/a0 = 0.3,
/// and by 2.8 % at 0.1 while claiming 1.3 % — now on the graded mesh,
/// against the semi-analytic solution. Measured: ≤ 6e-8 (solve's claim
/// GRADED_ERROR = 1e-7); the a-posteriori estimate 1.9 … 2.1 times the
/// error, or the floor 1e-10 where the error is below it.
#[test]
fn stiff_solids_match_the_semi_analytic_solution() {
    for ratio in [1e3, 1e4] {
        let material = sls(ratio).to_prony();
        let cyl = cylinder(&material, None);
        let reference = Reference::new(&material, 0.5, RADIUS, LOAD);
        let a0 = cyl.static_half_width();
        let mut graded = 0;
        // τ = 1 s: v = x a0 is vτ/a0 = x.
        for x in [1e-4, 1e-3, 1e-2, 0.03, 0.1, 0.3, 1.0] {
            let plain = cyl.solve(x * a0).unwrap();
            let estimated = cyl.solve_with_error_estimate(x * a0).unwrap();
            assert_eq!(
                plain.mu, estimated.mu,
                "the estimate changes only the claim"
            );
            let exact = reference.mu(x * a0, plain.half_width());
            let error = (plain.mu / exact - 1.0).abs();
            let claimed = estimated.error_estimate;
            println!(
                "E1/E0 = {ratio:.0e}, vτ/a0 = {x:.0e}: μ = {:.10e}, exact {exact:.10e}, \
                 error {error:.1e}, claimed {:.0e} / {claimed:.1e} ({:?})",
                plain.mu, plain.error_estimate, plain.method
            );
            assert!(error <= plain.error_estimate, "vτ/a0 = {x}: {error:e}");
            if let ExactMethod::GradedMesh { .. } = plain.method {
                graded += 1;
                assert!(error < GRADED_ERROR, "vτ/a0 = {x}: {error:e}");
                assert!(
                    claimed >= error / 3.0 && claimed <= 3.0 * error.max(GRADED_FLOOR),
                    "vτ/a0 = {x}: claimed {claimed:e}, error {error:e}"
                );
            }
        }
        assert!(graded >= 6, "E1/E0 = {ratio}: the graded mesh was not used");
    }
}

/// The semi-analytic reference itself against Eq. (18)'s linear term
/// (exact at first order in tan δ): at vτ/a0 = 1e-6 … 1e-4 (E1/E0 = 1e4)
/// μ/asymptote − 1 = −0.50 vτ/a0 (measured −5.03e-7, −5.01e-6, −5.00e-5:
/// the next order is linear in v). The graded mesh follows it; the 128
/// Chebyshev terms it replaces gave −1.1e-4 at 1e-4 and −5e-7 at 1e-5.
#[test]
fn stiff_low_speed_approaches_the_asymptote() {
    let material = sls(1e4);
    let prony = material.to_prony();
    let cyl = cylinder(&prony, None);
    let reference = Reference::new(&prony, 0.5, RADIUS, LOAD);
    let scene = scenes::scene(
        Shape::Cylinder,
        RADIUS,
        LOAD,
        0.5,
        None,
        ContactSize::Dynamic,
        material,
    );
    let a0 = cyl.static_half_width();
    for x in [1e-6, 1e-5, 1e-4] {
        let asymptote = scene.low_speed_asymptote(x * a0);
        let solution = cyl.solve(x * a0).unwrap();
        let exact = reference.mu(x * a0, solution.half_width());
        let (r_exact, r_mesh) = (exact / asymptote - 1.0, solution.mu / asymptote - 1.0);
        println!("vτ/a0 = {x:.0e}: reference/asymptote − 1 = {r_exact:.3e}, mesh {r_mesh:.3e}");
        assert!((r_exact / (-0.5 * x) - 1.0).abs() < 0.02, "{r_exact:e}");
        assert!((r_mesh / (-0.5 * x) - 1.0).abs() < 0.02, "{r_mesh:e}");
    }
}

/// Three relaxation times (1e-6, 1e-3, 1 s; E1/E0 = 1e4): the graded mesh
/// against the semi-analytic solution with three exponentials (its
/// Cauchy-like system is well conditioned up to vτ_max/a0 ≈ 0.1; measured
/// ≤ 1.7e-12).
#[test]
fn three_term_solid_matches_the_semi_analytic_solution() {
    let material = Prony::new(1e10, vec![3e9, 3e9, 4e9 - 1e6], vec![1e-6, 1e-3, 1.0]).unwrap();
    let cyl = cylinder(&material, None);
    let reference = Reference::new(&material, 0.5, RADIUS, LOAD);
    let a0 = cyl.static_half_width();
    for x in [1e-4, 1e-3, 1e-2, 0.1] {
        let solution = cyl.solve(x * a0).unwrap();
        let exact = reference.mu(x * a0, solution.half_width());
        let error = (solution.mu / exact - 1.0).abs();
        println!(
            "vτ_max/a0 = {x:.0e}: μ = {:.10e}, error {error:.1e}",
            solution.mu
        );
        assert!(matches!(solution.method, ExactMethod::GradedMesh { .. }));
        assert!(error < GRADED_ERROR, "vτ_max/a0 = {x}: {error:e}");
    }
}

/// Where the Chebyshev series resolves the layers, the graded mesh (forced
/// by `max_terms` = 24) gives the same μ: two independent discretisations.
/// Measured: μ ≤ 1.9e-8 apart (the Chebyshev side's error: q = 8 and 12
/// agree to 3e-12 at the random Prony's speeds).
#[test]
fn graded_mesh_agrees_with_chebyshev_where_both_resolve() {
    let mut rng = materials::Lcg(42);
    for (name, material) in [
        ("SLS 10", sls(10.0).to_prony()),
        ("SLS 1000", sls(1000.0).to_prony()),
        (
            "random Prony",
            materials::random_prony(&mut rng, 5, -3.0, 0.5),
        ),
    ] {
        let chebyshev = cylinder(&material, None);
        let graded = RollingCylinder::with_settings(
            &material,
            0.5,
            RADIUS,
            LOAD,
            ExactSettings {
                max_terms: 24,
                ..ExactSettings::default()
            },
        )
        .unwrap();
        let a0 = chebyshev.static_half_width();
        let mut compared = 0;
        for k in 0..=10 {
            let v = a0 * 10f64.powf(-2.0 + 0.5 * k as f64);
            if !chebyshev.resolves_edge_layers(v) || graded.resolves_edge_layers(v) {
                continue;
            }
            compared += 1;
            let (a, b) = (chebyshev.solve(v).unwrap(), graded.solve(v).unwrap());
            let difference = (a.mu / b.mu - 1.0).abs();
            let width = (a.half_width() / b.half_width() - 1.0).abs();
            println!(
                "{name}, v/a0 = {:.1e} s⁻¹: μ differs by {difference:.1e}, b by {width:.1e}",
                v / a0
            );
            assert!(difference < 1e-7, "{name}, v = {v:e}: {difference:e}");
            // The default Chebyshev terms place the edges less well than they
            // give μ (here 1.0e-6 off where 256 terms and the mesh agree to
            // 1e-13).
            assert!(width < 5e-6, "{name}, v = {v:e}: {width:e}");
        }
        assert!(compared >= 2, "{name}");
    }
}

/// The pressure on the graded mesh (the inversion of F there, not the
/// truncated series): non-negative, carrying the load and the centroid
/// (trapezoid in θ on 20000 points; measured ≤ 3e-10).
#[test]
fn graded_pressure_carries_the_load() {
    let material = sls(1e4).to_prony();
    let cyl = cylinder(&material, None);
    let a0 = cyl.static_half_width();
    for x in [1e-3, 0.3] {
        let sol = cyl.solve(x * a0).unwrap();
        assert!(matches!(sol.method, ExactMethod::GradedMesh { .. }));
        let (c, b) = (sol.center(), sol.half_width());
        let n = 20000;
        let (mut load, mut moment) = (0.0, 0.0);
        for i in 1..n {
            let theta = PI * i as f64 / n as f64;
            let xi = c - b * theta.cos();
            let p = sol.pressure(xi);
            assert!(p >= 0.0, "p({xi}) = {p}");
            let w = b * theta.sin() * PI / n as f64;
            load += p * w;
            moment += p * xi * w;
        }
        println!(
            "vτ/a0 = {x}: load error {:.1e}, centroid error/a0 {:.1e}",
            load / LOAD - 1.0,
            (moment / LOAD - sol.centroid) / a0
        );
        assert!((load / LOAD - 1.0).abs() < 1e-8);
        assert!((moment / LOAD - sol.centroid).abs() < 1e-8 * a0);
        assert_eq!(sol.pressure(sol.leading_edge), 0.0);
    }
}
/// The semi-analytic solution for a Prony modulus (module documentation of
/// `rollfit_model::exact`, "Thin edge layers"): inside the contact the
/// Hilbert transform of the pressure is F(t) = A t + Σ_k C_k ψ_k(t),
/// ψ_k = e^{−κ_k(1 − t)} − e^{−κ_k} I_0(κ_k), one exponential per
/// relaxation time (κ_k = b/(vτ_k)). Put into the equation, the t-terms give
/// A = 1/(2R J_eff(∞)), the constant terms the centre, and the terms
/// e^{−β_j(1 − t)} one condition per retardation time:
///
///   Σ_k C_k [W_jk − β_j/(β_j − κ_k)] = −A D_j,
///
/// W_jk = (1/π) ∫_0^π e^{−κ_k(1 − cos φ)} G_j(φ) dφ, G_j(φ) = β_j ∫_0^∞
/// e^{−β_j x} √(x(x + 2))/(x + 1 − cos φ) dx (the memory of ψ_k's
/// continuation outside the contact), D_j = −β_j ∫_0^∞ e^{−β_j x}
/// √(x(x + 2)) dx. Then α_0 = A + 2 Σ C_k e^{−κ_k} I_1(κ_k), α_1 =
/// 2 Σ C_k e^{−κ_k} I_2(κ_k), and the load fixes b. Only one- and
/// two-dimensional quadratures (Gauss–Legendre on panels doubling away from
/// the scales 1/√κ, 1/√β and the Lorentzian's width): independent of the
/// mesh, the Chebyshev series and the memory kernels of the crate. Well
/// conditioned for a few relaxation times; for many closely spaced ones
/// (or high speed, κ ≪ 1) the Cauchy-like matrix is not.
mod semi_analytic {
    use rollfit_model::Prony;
    use rollfit_model::exact::CreepCompliance;
    use std::f64::consts::PI;

    /// The 16-point Gauss–Legendre rule on [0, 1].
    fn rule() -> &'static (Vec<f64>, Vec<f64>) {
        static RULE: std::sync::OnceLock<(Vec<f64>, Vec<f64>)> = std::sync::OnceLock::new();
        RULE.get_or_init(|| {
            let n = 16;
            let (mut x, mut w) = (vec![0.0; n], vec![0.0; n]);
            for i in 0..n {
                let mut z = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
                for _ in 0..100 {
                    let (mut p0, mut p1) = (1.0, z);
                    for k in 2..=n {
                        let p2 = ((2 * k - 1) as f64 * z * p1 - (k - 1) as f64 * p0) / k as f64;
                        p0 = p1;
                        p1 = p2;
                    }
                    let dp = n as f64 * (z * p1 - p0) / (z * z - 1.0);
                    let dz = p1 / dp;
                    z -= dz;
                    if dz.abs() < 1e-16 {
                        x[i] = 0.5 * (1.0 - z);
                        w[i] = 1.0 / ((1.0 - z * z) * dp * dp);
                        break;
                    }
                }
            }
            (x, w)
        })
    }

    /// ∫_0^end f on panels doubling from `scale`/16 (one panel below).
    fn doubling(f: impl Fn(f64) -> f64, scale: f64, end: f64) -> f64 {
        let (x, w) = rule();
        let mut edges = vec![0.0];
        let mut e = (scale / 16.0).min(end);
        while e < end {
            edges.push(e);
            e *= 2.0;
        }
        edges.push(end);
        let mut sum = 0.0;
        for pair in edges.windows(2) {
            let h = pair[1] - pair[0];
            for (xi, wi) in x.iter().zip(w) {
                sum += h * wi * f(pair[0] + h * xi);
            }
        }
        sum
    }

    /// (1/π) ∫_0^π e^{−κ(1 − cos φ)} g(φ) dφ, breaks from min(1/√κ, `scale`).
    fn layer(kappa: f64, scale: f64, g: impl Fn(f64) -> f64) -> f64 {
        let end = if kappa > 20.0 {
            2.0 * (20.0 / kappa).sqrt().asin()
        } else {
            PI
        };
        let f = |phi: f64| (-2.0 * kappa * (0.5 * phi).sin().powi(2)).exp() * g(phi);
        doubling(f, (1.0 / kappa.sqrt()).min(scale), end) / PI
    }

    /// G(φ) in w = √x.
    fn outer_kernel(beta: f64, phi: f64) -> f64 {
        let d = 2.0 * (0.5 * phi).sin().powi(2);
        let f = |w: f64| {
            let x = w * w;
            2.0 * beta * w * (-beta * x).exp() * w * (x + 2.0).sqrt() / (x + d)
        };
        let scale = if d > 0.0 {
            d.sqrt().min(1.0 / beta.sqrt())
        } else {
            1.0 / beta.sqrt()
        };
        doubling(f, scale, (40.0 / beta).sqrt())
    }

    pub struct Reference {
        instantaneous: f64,
        strengths: Vec<f64>,
        retardation: Vec<f64>,
        relaxation: Vec<f64>,
        radius: f64,
        load: f64,
    }

    impl Reference {
        pub fn new(modulus: &Prony, poisson: f64, radius: f64, load: f64) -> Self {
            let creep = CreepCompliance::from_prony(modulus).scaled(1.0 - poisson * poisson);
            Reference {
                instantaneous: creep.instantaneous,
                strengths: creep.strengths.clone(),
                retardation: creep.retardation_times.clone(),
                relaxation: modulus.relaxation_times().to_vec(),
                radius,
                load,
            }
        }

        /// (centre, α_0, α_1) at half-width b.
        fn at(&self, v: f64, b: f64) -> (f64, f64, f64) {
            let n = self.strengths.len();
            let beta: Vec<f64> = self.retardation.iter().map(|l| b / (v * l)).collect();
            let kappa: Vec<f64> = self.relaxation.iter().map(|t| b / (v * t)).collect();
            let equilibrium = self.instantaneous + self.strengths.iter().sum::<f64>();
            let a = 1.0 / (2.0 * self.radius * equilibrium);
            let mut matrix = vec![0.0; n * n];
            let mut rhs = vec![0.0; n];
            for j in 0..n {
                let bj = beta[j];
                let d = doubling(
                    |w: f64| {
                        let x = w * w;
                        2.0 * bj * w * (-bj * x).exp() * w * (x + 2.0).sqrt()
                    },
                    1.0 / bj.sqrt(),
                    (40.0 / bj).sqrt(),
                );
                rhs[j] = a * d;
                for k in 0..n {
                    let w = layer(kappa[k], 1.0 / bj.sqrt(), |phi| outer_kernel(bj, phi));
                    matrix[j * n + k] = w - bj / (bj - kappa[k]);
                }
            }
            let c = solve(matrix, rhs, n);
            let (mut alpha0, mut alpha1) = (a, 0.0);
            let mut g0: f64 = self
                .strengths
                .iter()
                .zip(&beta)
                .map(|(s, b)| s * a / b)
                .sum();
            for k in 0..n {
                let bessel = |m: f64| layer(kappa[k], 1.0, |phi| (m * phi).cos());
                alpha0 += 2.0 * c[k] * bessel(1.0);
                alpha1 += 2.0 * c[k] * bessel(2.0);
                g0 -= c[k] * bessel(0.0) * equilibrium;
            }
            (2.0 * b * self.radius * g0, alpha0, alpha1)
        }

        /// μ at speed v (m/s), the secant on ln b started at `guess` (m).
        pub fn mu(&self, v: f64, guess: f64) -> f64 {
            let log_load = |x: f64| {
                let b = x.exp();
                (0.5 * PI * b * b * self.at(v, b).1 / self.load).ln()
            };
            let (mut x0, mut x1) = (guess.ln(), guess.ln() + 1e-3);
            let (mut f0, mut f1) = (log_load(x0), log_load(x1));
            for _ in 0..50 {
                let x2 = x1 - f1 * (x1 - x0) / (f1 - f0);
                (x0, f0) = (x1, f1);
                x1 = x2;
                f1 = log_load(x1);
                if (x1 - x0).abs() < 1e-13 {
                    break;
                }
            }
            let b = x1.exp();
            let (c, _, alpha1) = self.at(v, b);
            (c + PI * b * b * b * alpha1 / (4.0 * self.load)) / self.radius
        }
    }

    /// Gaussian elimination with partial pivoting.
    fn solve(mut a: Vec<f64>, mut r: Vec<f64>, n: usize) -> Vec<f64> {
        for col in 0..n {
            let p = (col..n)
                .max_by(|&i, &j| a[i * n + col].abs().total_cmp(&a[j * n + col].abs()))
                .unwrap();
            for k in 0..n {
                a.swap(p * n + k, col * n + k);
            }
            r.swap(p, col);
            for row in col + 1..n {
                let f = a[row * n + col] / a[col * n + col];
                for k in col..n {
                    a[row * n + k] -= f * a[col * n + k];
                }
                r[row] -= f * r[col];
            }
        }
        let mut x = vec![0.0; n];
        for row in (0..n).rev() {
            let s: f64 = (row + 1..n).map(|k| a[row * n + k] * x[k]).sum();
            x[row] = (r[row] - s) / a[row * n + row];
        }
        x
    }
}

/// The stiff-solid study (slow, `cargo test --release -p rollfit-model --test it -- --ignored --nocapture exact_cylinder::stiff_study`): standard linear
/// solids E1/E0 = 1e3 and 1e4 and a broad series (nine relaxation times
/// 1e-8 … 1 s, E1/E0 = 1e4) from vτ/a0 = 1e-4 to 1e2 (τ = 1 s, the SLS's
/// retardation time and the series' longest relaxation time): μ, the
/// reference (semi-analytic; for the series above vτ/a0 = 0.1, where its
/// system is ill-conditioned, 256 Chebyshev terms), the error, the claimed
/// error of `solve_with_error_estimate` and its time; and what the 128
/// Chebyshev terms the graded mesh replaces gave and claimed (ten times the
/// change from 96 terms).
#[test]
#[ignore]
fn stiff_study() {
    let weights: Vec<f64> = (0..9)
        .map(|k| (1.0 + 0.3 * (0.7 * k as f64).sin()) * 10f64.powf(0.25 * k as f64))
        .collect();
    let total: f64 = weights.iter().sum();
    let broad = Prony::new(
        1e10,
        weights.iter().map(|w| (1e10 - 1e6) * w / total).collect(),
        (0..9).map(|k| 10f64.powi(k - 8)).collect(),
    )
    .unwrap();
    println!(
        "| material | vτ/a0 | μ | reference | error | claimed | ms | method | N = 128: error | claimed |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for (name, material) in [
        ("SLS 1e3", sls(1e3).to_prony()),
        ("SLS 1e4", sls(1e4).to_prony()),
        ("broad 1e4", broad),
    ] {
        let cyl = cylinder(&material, None);
        let old = cylinder(&material, Some(128));
        let old_coarse = cylinder(&material, Some(96));
        let fine = cylinder(&material, Some(256));
        let reference = Reference::new(&material, 0.5, RADIUS, LOAD);
        let a0 = cyl.static_half_width();
        for k in 0..=12 {
            let x = 10f64.powf(-4.0 + 0.5 * k as f64);
            let v = x * a0;
            let start = std::time::Instant::now();
            let s = cyl.solve_with_error_estimate(v).unwrap();
            let ms = start.elapsed().as_secs_f64() * 1e3;
            let semi = name.starts_with("SLS") || x <= 0.1;
            let exact = if semi {
                reference.mu(v, s.half_width())
            } else {
                fine.solve(v).unwrap().mu
            };
            let error = (s.mu / exact - 1.0).abs();
            let (old_error, old_claim) = if s.method == ExactMethod::Chebyshev {
                (error, s.error_estimate)
            } else {
                let o = old.solve(v).unwrap().mu;
                let change = (o / old_coarse.solve(v).unwrap().mu - 1.0).abs();
                ((o / exact - 1.0).abs(), (10.0 * change).max(1e-5))
            };
            let method = match s.method {
                ExactMethod::Chebyshev => format!("Chebyshev {}", s.coefficients.len()),
                ExactMethod::GradedMesh { nodes } => format!("mesh {nodes}"),
            };
            println!(
                "| {name} | {x:.1e} | {:.9e} | {exact:.9e}{} | {error:.1e} | {:.1e} | {ms:.1} | {method} | {old_error:.1e} | {old_claim:.1e} |",
                s.mu,
                if semi { "" } else { " (N = 256)" },
                s.error_estimate
            );
        }
    }
}
