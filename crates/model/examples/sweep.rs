//! μ(v) of a steel ball (R = 1 cm, 1 N) on a standard linear solid
//! (E0 = 1 MPa, E1 = 100 MPa, τ = 10 ms, ν = ½), the paper's dynamic
//! contact size: the speed, μ, its low-speed asymptote, and the friction
//! maximum. Run with `cargo run --release --example sweep -p rollfit-model`.

use rollfit_model::{
    ContactSize, Geometry, ModelError, Scene, Shape, StandardLinearSolid, Substrate,
};

fn main() -> Result<(), ModelError> {
    let scene = Scene::new(
        Geometry {
            shape: Shape::Sphere,
            radius: 0.01,
            load: 1.0,
        },
        Substrate {
            poisson: 0.5,
            film_thickness: None,
        },
        ContactSize::Dynamic,
        StandardLinearSolid::new(1e6, 1e8, 1e-2)?,
    )?;
    let speeds: Vec<f64> = (0..=16)
        .map(|k| 10f64.powf(-6.0 + 0.5 * k as f64))
        .collect();
    let mu = scene.friction_sweep(&speeds)?;
    println!("{:>12} {:>12} {:>12}", "v (m/s)", "mu", "mu_low");
    for (v, m) in speeds.iter().zip(&mu) {
        println!(
            "{v:12.3e} {m:12.5e} {:12.5e}",
            scene.low_speed_asymptote(*v)
        );
    }
    let peak = scene.friction_maximum(speeds[0], speeds[speeds.len() - 1])?;
    println!(
        "friction maximum μ = {:.5e} at v = {:.3e} m/s",
        peak.mu, peak.speed
    );
    Ok(())
}
