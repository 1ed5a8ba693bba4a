//! Warm starts of the exact solves (`ExactRolling::
//! exact_friction_from`): a solve started from where a solve at the same
//! speed ended for a nearby modulus — as a fit's refits change it — gives
//! the cold solve's μ and error estimate, with fewer iterations.

use rollfit_model::exact::{ExactRolling, RollingCylinder, RollingSphere, SphereSettings};
use rollfit_model::{Prony, StandardLinearSolid};

/// A 9-term series, E0 = 2 MPa, E1 = 200 MPa, relaxation times 1e-6 …
/// 1e2 s with a log-normal bump of strengths; `perturbed` changes each
/// strength and time by a few 1e-3, as one refit of a fit changes its
/// modulus.
fn series(perturbed: bool) -> Prony {
    let tau: Vec<f64> = (0..9).map(|k| 10f64.powf(-6.0 + k as f64)).collect();
    let w: Vec<f64> = tau
        .iter()
        .map(|t| (-0.5 * ((t.log10() + 2.0) / 2.0).powi(2)).exp() + 0.05)
        .collect();
    let total: f64 = w.iter().sum();
    let wobble = |k: usize, size: f64| {
        if perturbed {
            1.0 + size * (1.7 * k as f64).sin()
        } else {
            1.0
        }
    };
    let h = w
        .iter()
        .enumerate()
        .map(|(k, x)| 198e6 * x / total * wobble(k, 3e-3))
        .collect();
    let tau = tau.iter().enumerate().map(|(k, t)| t * wobble(k + 3, 2e-3));
    Prony::new(200e6, h, tau.collect()).unwrap()
}

/// The cylinder on the graded mesh (this series' glassy time is below
/// what 128 Chebyshev terms resolve at these speeds) and in Chebyshev
/// collocation (an SLS near its maximum): from the root of the
/// unperturbed series, the perturbed series' μ and estimate equal the
/// cold solve's to the secant's tolerance; without the estimate, then
/// with it deferred, they are the warm solve's.
#[test]
fn a_warm_cylinder_solve_equals_the_cold_one() {
    let cases: [(Prony, Prony, f64); 2] = [
        (series(false), series(true), 0.005),
        (
            StandardLinearSolid::new(1e6, 1e7, 1.0).unwrap().to_prony(),
            StandardLinearSolid::new(1.002e6, 0.997e7, 1.001)
                .unwrap()
                .to_prony(),
            0.01,
        ),
    ];
    for (before, after, radius) in cases {
        let a = RollingCylinder::new(&before, 0.5, radius, 1000.0).unwrap();
        let b = RollingCylinder::new(&after, 0.5, radius, 1000.0).unwrap();
        for v in [1e-7, 1e-5, 1e-3, 1e-1] {
            let (_, start) = a.exact_friction_from(v, None).unwrap();
            let cold = b.exact_friction(v).unwrap();
            let (warm, _) = b.exact_friction_from(v, Some(&start)).unwrap();
            let moved = (a.exact_friction(v).unwrap().mu / cold.mu - 1.0).abs();
            assert!(moved > 1e-6, "v {v}: the perturbation moved μ by {moved:e}");
            assert!(
                (warm.mu / cold.mu - 1.0).abs() < 1e-9,
                "v {v}: warm {warm:?} cold {cold:?}"
            );
            // The estimate left out and made afterwards is the same number.
            let (unestimated, end) = b.exact_friction_unestimated_from(v, Some(&start)).unwrap();
            let deferred = b.deferred_estimate(v, &end).unwrap();
            assert_eq!(unestimated.mu, warm.mu, "v {v}");
            assert_eq!(
                deferred.unwrap_or(unestimated.error_estimate),
                warm.error_estimate,
                "v {v}"
            );
            let estimates = (warm.error_estimate, cold.error_estimate);
            assert!(
                (estimates.0 - estimates.1).abs() <= 1e-9 + 1e-3 * estimates.1,
                "v {v}: {estimates:?}"
            );
        }
    }
}

/// The sphere (R = 1 cm, 0.15 N, 48 cells so the test stays short) of a
/// standard linear solid E1/E0 = 10 at vτ/r0 ≈ 0.1, 1 and 10, and the
/// series above: from each grid's solution for the unperturbed modulus
/// the perturbed one's μ and estimate equal the cold solve's to the
/// Krylov tolerance, with fewer operator applications on the finest grid.
#[test]
fn a_warm_sphere_solve_equals_the_cold_one() {
    let settings = SphereSettings {
        cells: 48,
        ..SphereSettings::default()
    };
    let sphere = |p: &Prony| RollingSphere::with_settings(p, 0.0, 0.01, 0.15, settings).unwrap();
    let sls = |e0: f64, e1: f64, tau: f64| StandardLinearSolid::new(e0, e1, tau).unwrap();
    let cases = [
        (
            sls(1e6, 1e7, 1.0).to_prony(),
            sls(1.002e6, 0.997e7, 1.001).to_prony(),
            [1e-4, 1e-3, 1e-2],
        ),
        (series(false), series(true), [1e-5, 1e-3, 1e-1]),
    ];
    let (mut warm_applications, mut cold_applications) = (0, 0);
    for (before, after, speeds) in cases {
        let (a, b) = (sphere(&before), sphere(&after));
        for v in speeds {
            let (was, start) = a.solve_from(v, None).unwrap();
            let cold = b.solve(v).unwrap();
            let (warm, _) = b.solve_from(v, Some(&start)).unwrap();
            let moved = (was.mu / cold.mu - 1.0).abs();
            assert!(moved > 1e-5, "v {v}: the perturbation moved μ by {moved:e}");
            assert!(
                (warm.mu / cold.mu - 1.0).abs() < 1e-8,
                "v {v}: warm μ {} cold {} (was {})",
                warm.mu,
                cold.mu,
                was.mu
            );
            assert!(
                (warm.error_estimate - cold.error_estimate).abs() <= 1e-6,
                "v {v}: {} against {}",
                warm.error_estimate,
                cold.error_estimate
            );
            assert_eq!(warm.pressure_map.len(), cold.pressure_map.len(), "v {v}");
            warm_applications += warm.operator_applications;
            cold_applications += cold.operator_applications;
        }
    }
    eprintln!(
        "operator applications, finest grid: warm {warm_applications}, cold {cold_applications}"
    );
    assert!(
        warm_applications < cold_applications,
        "warm {warm_applications} against cold {cold_applications}"
    );
}
