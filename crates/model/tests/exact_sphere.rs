//! The exact steady rolling sphere (crates/model/src/exact/sphere).

use std::f64::consts::PI;
use std::time::Instant;

use rollfit_model::exact::{RollingSphere, SphereSettings};
use rollfit_model::{Prony, StandardLinearSolid};

const RADIUS: f64 = 0.01;
const LOAD: f64 = 0.15;

fn sls(ratio: f64) -> Prony {
    StandardLinearSolid::new(1e6, ratio * 1e6, 1.0).unwrap().to_prony()
}

fn sphere(material: &Prony, cells: usize) -> RollingSphere {
    let settings = SphereSettings { cells, ..SphereSettings::default() };
    RollingSphere::with_settings(material, 0.0, RADIUS, LOAD, settings).unwrap()
}

#[test]
#[ignore]
fn convergence_study() {
    let m = sls(10.0);
    let r0 = sphere(&m, 20).static_contact_radius();
    for vt in [0.01, 0.1] {
        for cells in [16, 20, 24, 28, 32, 40, 48, 56, 64, 80, 96, 112, 128] {
            let sol = sphere(&m, cells).solve(vt * r0).unwrap();
            println!("vt {vt} cells {cells} mu {:.7e} it {} area {:.5e}", sol.mu * RADIUS / r0 / vt, sol.iterations, sol.area / (PI * r0 * r0));
        }
    }
    let s8 = sphere(&m, 48);
    let s16 = RollingSphere::with_settings(&m, 0.0, RADIUS, LOAD, SphereSettings { cells: 48, quadrature_order: 16 }).unwrap();
    for vt in [0.01, 1.0] {
        println!("order 8 vs 16 at vt {vt}: {:.9e} {:.9e}", s8.solve(vt * r0).unwrap().mu, s16.solve(vt * r0).unwrap().mu);
    }
}

#[test]
#[ignore]
fn study() {
    let elastic = Prony::new(1e6, vec![], vec![]).unwrap();
    for cells in [20, 40, 80] {
        let s = sphere(&elastic, cells);
        let r0 = s.static_contact_radius();
        let t = Instant::now();
        let sol = s.solve(1.0).unwrap();
        let hertz_delta = r0 * r0 / RADIUS;
        let hertz_p0 = 3.0 * LOAD / (2.0 * PI * r0 * r0);
        println!(
            "elastic cells {cells}: mu {:.2e} delta {:.3e} area {:.3e} pmax {:.3e} iters {} {:.2?}",
            sol.mu,
            sol.approach / hertz_delta - 1.0,
            sol.area / (PI * r0 * r0) - 1.0,
            sol.max_pressure / hertz_p0 - 1.0,
            sol.iterations,
            t.elapsed()
        );
    }
    for ratio in [10.0, 100.0] {
        let m = sls(ratio);
        let r0 = sphere(&m, 20).static_contact_radius();
        for vt in [0.01, 1.0, 100.0] {
            let v = vt * r0 / 1.0;
            let mut line = format!("E1/E0 {ratio} vτ/r0 {vt}:");
            for cells in [16, 24, 32, 48, 64, 96] {
                let t = Instant::now();
                let sol = sphere(&m, cells).solve(v).unwrap();
                line += &format!(" [{cells}: {:.6e} {:.0?} it{}]", sol.mu * RADIUS / r0, t.elapsed(), sol.iterations);
            }
            println!("{line}");
        }
    }
}

#[test]
#[ignore]
fn cost_study() {
    let m = sls(10.0);
    let r0 = sphere(&m, 20).static_contact_radius();
    for vt in [0.01, 1.0] {
        let t = Instant::now();
        let sol = sphere(&m, 96).solve(vt * r0).unwrap();
        println!("vt {vt}: {:.6e} ± {:.1e} in {:.2?}", sol.mu * RADIUS / r0 / vt, sol.error_estimate, t.elapsed());
    }
}
