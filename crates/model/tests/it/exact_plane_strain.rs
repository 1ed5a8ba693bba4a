//! The exact sphere's boundary elements in plane strain
//! (`RollingSphere::plane_strain`: one row of strips, log kernel, the
//! sphere's own memory recursion, contact set, load balance, three grids
//! and extrapolation) against the exact rolling cylinder
//! (`RollingCylinder`, Hunter 1961 by Chebyshev series and graded mesh: an
//! independent method, accurate to ~1e-8) — the check "the same
//! code in plane strain equals the exact cylinder"; and the elastic limits
//! (Hertz line contact) at both speed ends.

use std::f64::consts::PI;

use rollfit_model::Prony;
use rollfit_model::exact::{RollingCylinder, RollingSphere, SphereSettings};

const RADIUS: f64 = 0.01;
/// Load per unit length, N/m (Persson's Fig. 2 cylinder).
const LOAD: f64 = 100.0;

/// A standard linear solid E0 = 1 MPa, E1 = ratio · E0 with relaxation
/// time τ = 1 s (the exact solvers' convention: speeds as vτ/a0 with τ the
/// relaxation time).
fn relaxing(ratio: f64) -> Prony {
    Prony::new(ratio * 1e6, vec![(ratio - 1.0) * 1e6], vec![1.0]).unwrap()
}

fn strips(material: &Prony, poisson: f64, cells: usize) -> RollingSphere {
    let settings = SphereSettings {
        cells,
        ..SphereSettings::default()
    };
    RollingSphere::plane_strain(material, poisson, RADIUS, LOAD, settings).unwrap()
}

/// One comparison: the plane-strain boundary elements' μ, its own error
/// estimate, the exact cylinder's μ and its estimate.
struct Comparison {
    ratio: f64,
    poisson: f64,
    speed: f64,
    bem: f64,
    estimate: f64,
    /// μ of the finest of the three grids alone (no extrapolation).
    single: f64,
    exact: f64,
    exact_estimate: f64,
}

impl Comparison {
    fn new(ratio: f64, poisson: f64, speed_over_a0: f64, cells: usize) -> Self {
        let material = relaxing(ratio);
        let body = strips(&material, poisson, cells);
        let a0 = body.static_contact_radius();
        let speed = speed_over_a0 * a0;
        let bem = body.solve(speed).unwrap();
        let single = body.solve_single(speed, cells).unwrap();
        let cylinder = RollingCylinder::new(&material, poisson, RADIUS, LOAD).unwrap();
        assert!((cylinder.static_half_width() / a0 - 1.0).abs() < 1e-14);
        let exact = cylinder.solve_with_error_estimate(speed).unwrap();
        Comparison {
            ratio,
            poisson,
            speed: speed_over_a0,
            bem: bem.mu,
            estimate: bem.error_estimate,
            single: single.mu,
            exact: exact.mu,
            exact_estimate: exact.error_estimate,
        }
    }

    fn difference(&self) -> f64 {
        (self.bem / self.exact - 1.0).abs()
    }

    fn print(&self) {
        println!(
            "| {} | {} | {} | {:.6e} | {:.6e} | {:.1e} | {:.1e} | {:.2} | {:.1e} |",
            self.ratio,
            self.poisson,
            self.speed,
            self.exact * RADIUS,
            self.bem * RADIUS,
            self.difference(),
            self.estimate,
            self.difference() / self.estimate,
            (self.single / self.exact - 1.0).abs()
        );
    }
}

fn header() {
    println!(
        "| E1/E0 | ν | vτ/a0 | μR (exact cylinder), m | μR (plane-strain BEM), m | difference | BEM estimate | difference/estimate | finest grid alone |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
}

/// The plane-strain boundary elements (96 strips across the expected
/// contact width, the sphere's default) against the exact cylinder, for
/// E1/E0 = 10 and 100 (ν = 0) over vτ/a0 = 0.01 … 100 and for ν = 0.5 at
/// E1/E0 = 10. Measured: differences 1.2e-5 … 2.1e-2 (≤ 2.1e-3 for
/// vτ/a0 ≤ 10; the 2.1e-2 is E1/E0 = 100 at vτ/a0 = 100, where μ is small
/// against the grid's jitter of the contact edges), within the BEM's own
/// estimate in 10 of the 12 cases and at most 2.04 times it. The test
/// holds the difference to the estimate's calibrated band — the sphere's
/// estimate is 0.3 … 5 times its error (BENCHMARKS.md), so the error may
/// reach 3 times the estimate — plus the cylinder's own estimate (≤ 1e-6
/// here). ν enters only through (1 − ν²) J: the ν = 0.5 rows equal the
/// ν = 0 ones relatively.
#[test]
fn plane_strain_matches_exact_cylinder() {
    header();
    let mut cases = Vec::new();
    for ratio in [10.0, 100.0] {
        for speed in [0.01, 0.1, 1.0, 10.0, 100.0] {
            cases.push(Comparison::new(ratio, 0.0, speed, 96));
        }
    }
    for speed in [0.1, 10.0] {
        cases.push(Comparison::new(10.0, 0.5, speed, 96));
    }
    for case in &cases {
        case.print();
    }
    for case in &cases {
        assert!(
            case.difference() <= 3.0 * case.estimate + case.exact_estimate,
            "E1/E0 {}, ν {}, vτ/a0 {}: difference {:.2e}, estimate {:.2e}",
            case.ratio,
            case.poisson,
            case.speed,
            case.difference(),
            case.estimate
        );
    }
}

/// On a fine grid of 486 strips the finest grid alone (no extrapolation)
/// converges to the exact cylinder: the memory recursion with the log
/// kernel, the load balance and the contact set are right, not merely
/// consistent with their own estimate. Measured: at most 3.9e-5 over
/// E1/E0 = 10, 100 and vτ/a0 = 0.01 … 100 (at 96 strips up to 5.2e-3).
#[test]
fn fine_grid_converges_to_exact_cylinder() {
    for ratio in [10.0, 100.0] {
        let material = relaxing(ratio);
        let cylinder = RollingCylinder::new(&material, 0.0, RADIUS, LOAD).unwrap();
        let body = strips(&material, 0.0, 486);
        let a0 = body.static_contact_radius();
        for speed in [0.01, 0.1, 1.0, 10.0, 100.0] {
            let exact = cylinder.solve_with_error_estimate(speed * a0).unwrap();
            let single = body.solve_single(speed * a0, 486).unwrap();
            let error = (single.mu / exact.mu - 1.0).abs();
            println!("E1/E0 {ratio}, vτ/a0 {speed}: {error:.1e}");
            assert!(error < 1e-4, "E1/E0 {ratio}, vτ/a0 {speed}: {error:.2e}");
        }
    }
}

/// An elastic solid, and a standard linear solid far below and far above
/// its relaxation, give μ ≈ 0 and the Hertz line contact: half-width
/// a = √(4WR J/π) from the contact's edges (within a quarter strip; they
/// are extrapolated within one, measured 0.12 strip), the largest strip
/// pressure equal to Hertz p0 √(1 − x²/a²) at its centre x (measured to
/// 2e-6), and the load h Σ p = W to rounding.
#[test]
fn elastic_limits_are_hertz_line_contact() {
    let elastic = Prony::new(1e6, vec![], vec![]).unwrap();
    let stiff = relaxing(10.0);
    // (material, speed, compliance the contact sees)
    for (material, v, j) in [
        (&elastic, 1e-3, 1e-6),
        (&stiff, 1e-12, 1e-6),
        (&stiff, 1e6, 1e-7),
    ] {
        let sol = strips(material, 0.0, 96).solve_single(v, 96).unwrap();
        let a = (4.0 * LOAD * RADIUS * j / PI).sqrt();
        let p0 = 2.0 * LOAD / (PI * a);
        let (trailing, leading) = sol.axis_edges();
        let quarter_strip = 0.25 * sol.cell / a;
        let (x_peak, _, p_peak) = sol
            .pressure_map
            .iter()
            .copied()
            .max_by(|a, b| a.2.total_cmp(&b.2))
            .unwrap();
        let hertz_peak = p0 * (1.0 - (x_peak / a).powi(2)).sqrt();
        let load: f64 = sol.pressure_map.iter().map(|(_, _, p)| p * sol.cell).sum();
        println!(
            "v {v:e}: μ {:.1e}, edges {:.1e} {:.1e} (quarter strip {quarter_strip:.1e}), peak {:.1e}, load {:.1e}",
            sol.mu,
            -trailing / a - 1.0,
            leading / a - 1.0,
            p_peak / hertz_peak - 1.0,
            load / LOAD - 1.0
        );
        assert!(sol.mu.abs() < 1e-6, "v = {v}: μ = {}", sol.mu);
        assert!((-trailing / a - 1.0).abs() < quarter_strip, "v = {v}");
        assert!((leading / a - 1.0).abs() < quarter_strip, "v = {v}");
        assert_eq!(p_peak, sol.max_pressure);
        assert!((p_peak / hertz_peak - 1.0).abs() < 1e-4, "v = {v}");
        assert!((load / LOAD - 1.0).abs() < 1e-10, "v = {v}");
    }
}

/// The larger table: E1/E0 = 2, 10, 100, 1000, ν = 0 and 0.5, vτ/a0 =
/// 0.01 … 100 in half decades, 96 and 144 strips. Prints the table the
/// docs/validation.md quotes; asserts nothing beyond the solves succeeding.
///
/// `cargo test --release -p rollfit-model --test it exact_plane_strain:: -- --ignored --nocapture`
#[test]
#[ignore]
fn plane_strain_table() {
    header();
    for cells in [96, 144, 216] {
        println!("{cells} strips");
        for poisson in [0.0, 0.5] {
            for ratio in [2.0, 10.0, 100.0, 1000.0] {
                for k in -4..=4 {
                    let speed = 10f64.powf(0.5 * k as f64);
                    Comparison::new(ratio, poisson, speed, cells).print();
                }
            }
        }
    }
}
