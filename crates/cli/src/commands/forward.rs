//! `rollfit forward SCENE.toml [-o OUT.csv]`: μ(v) of a scene over its
//! `[sweep]` of speeds.

use std::path::PathBuf;

use anyhow::{Context, Result};
use rollfit_model::Shape;

use crate::output;
use crate::scene_file::{self, DynScene, ForwardSetup};

/// CSV columns, in order (DESIGN.md §4 fixes `v` and `mu`; the rest is ours):
/// speed v (m/s); friction coefficient μ; its low-speed asymptote (Eqs.
/// 18/19); static Hertz contact size r0 or a0 (m) and mean pressure p_a
/// (Pa), the same on every row; pressure-centroid shift x̄ = μR (m);
/// Greenwood–Tabor hysteresis fraction α that reproduces μ (Eq. 20).
pub const COLUMNS: [&str; 7] = [
    "v",
    "mu",
    "mu_low_speed",
    "contact_size_static",
    "mean_pressure_static",
    "centroid_shift",
    "gt_alpha",
];

/// Arguments of `rollfit forward`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scene file (TOML) with [geometry], [material] and [sweep].
    pub scene: PathBuf,
    /// Write the CSV here (atomically, creating missing folders) instead of
    /// to stdout.
    #[arg(short, long, value_name = "OUT.csv")]
    pub output: Option<PathBuf>,
}

/// Runs the command: reads the scene, computes μ(v), writes the CSV and a
/// one-line summary on stderr.
pub fn run(args: &Args) -> Result<()> {
    let path = &args.scene;
    if let Some(out) = &args.output {
        // Refuse an unusable output path before a possibly long computation.
        output::check_target(out)?;
    }
    let file = scene_file::load(path)?;
    let setup = file
        .forward_setup(path)
        .with_context(|| format!("scene file {}", path.display()))?;
    let mu = setup
        .scene
        .friction_sweep(&setup.speeds)
        .map_err(anyhow::Error::msg)
        .with_context(|| format!("computing μ(v) for scene file {}", path.display()))?;

    let bytes = output::csv_bytes(&COLUMNS, rows(&setup.scene, &setup.speeds, &mu))?;
    match &args.output {
        Some(out) => output::write_atomically(out, &bytes)?,
        None => output::write_stdout(&bytes)?,
    }
    eprintln!("{}", summary(&setup, &mu));
    Ok(())
}

fn rows<'a>(
    scene: &'a DynScene,
    speeds: &'a [f64],
    mu: &'a [f64],
) -> impl Iterator<Item = Vec<f64>> + 'a {
    let contact_size = scene.static_contact_size();
    let pressure = scene.static_mean_pressure();
    speeds.iter().zip(mu).map(move |(&v, &mu)| {
        vec![
            v,
            mu,
            scene.low_speed_asymptote(v),
            contact_size,
            pressure,
            scene.centroid_shift(mu),
            scene.greenwood_tabor_alpha(mu),
        ]
    })
}

/// One line for a person at a terminal: the scene's static contact and, when
/// the sweep brackets one, the friction maximum.
fn summary(setup: &ForwardSetup, mu: &[f64]) -> String {
    let scene = &setup.scene;
    let g = scene.geometry();
    let (shape, load_unit, size_name) = match g.shape {
        Shape::Sphere => ("sphere", "N", "r0"),
        Shape::Cylinder => ("cylinder", "N/m", "a0"),
    };
    let speeds = &setup.speeds;
    let mut line = format!("{shape} R = {} m, load {} {load_unit}", g.radius, g.load);
    if let Some(shift) = setup.shift {
        line += &format!(
            ", T = {} °C (log10 a_T = {:.4})",
            shift.temperature, shift.log10_a_t
        );
    }
    line += &format!(
        ": static contact {size_name} = {:.4e} m, mean pressure p_a = {:.4e} Pa; ",
        scene.static_contact_size(),
        scene.static_mean_pressure()
    );
    line += &peak_description(scene, speeds, mu);
    line
}

/// The friction maximum, refined between the sampled speeds around the
/// largest sampled μ. A largest μ at either end of the sweep means the
/// maximum (if any) lies outside it, which is said instead of a number.
fn peak_description(scene: &DynScene, speeds: &[f64], mu: &[f64]) -> String {
    let n = mu.len();
    let Some(i) = (0..n).max_by(|&a, &b| mu[a].total_cmp(&mu[b])) else {
        return "no speeds".into();
    };
    if n < 3 || i == 0 || i == n - 1 {
        let end = if i == 0 { "lowest" } else { "highest" };
        return format!(
            "no friction maximum inside the sweep (largest μ = {:.4e} at the {end} speed, v = {:.4e} m/s)",
            mu[i], speeds[i]
        );
    }
    match scene.friction_maximum(speeds[i - 1], speeds[i + 1]) {
        Ok(peak) => format!(
            "friction maximum μ = {:.4e} at v = {:.4e} m/s",
            peak.mu, peak.speed
        ),
        // The CSV is complete without it; the summary is a convenience.
        Err(e) => format!(
            "friction maximum near v = {:.4e} m/s (μ = {:.4e}), not refined: {e}",
            speeds[i], mu[i]
        ),
    }
}
