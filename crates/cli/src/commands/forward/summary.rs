//! The summary `rollfit forward` prints on stderr: the scene's static
//! contact, the temperatures, the friction maximum of each sweep, and what
//! the exact solution or `auto` did.

use rollfit_io::scene::{self as scene_file, DynScene, ForwardRung, ForwardSetup};
use rollfit_model::Shape;

use super::Solved;

/// The exact sphere's estimated error above which `forward` warns.
const SPHERE_NOTE_ERROR: f64 = 1e-3;

/// One line for a person at a terminal: the scene's static contact (the
/// same at every temperature: a shift leaves the static modulus alone), the
/// temperatures and, where the sweep brackets one, the friction maximum at
/// each.
pub(super) fn summary(setup: &ForwardSetup, solved: &[Solved], mu: &[Vec<f64>]) -> String {
    let mut line = summary_line(setup, mu);
    let shape = setup.blocks[0].scene.geometry().shape;
    for (block, solved) in setup.blocks.iter().zip(solved) {
        let at = block
            .shift
            .map(|s| format!("at {} °C: ", s.temperature))
            .unwrap_or_default();
        if let Some(auto) = &solved.auto {
            line += &format!("\n{at}{}", auto.description(&setup.speeds, shape));
        }
        if let (ForwardRung::Exact(_), Some(error), rollfit_model::Shape::Sphere) =
            (&block.rung, &solved.error, shape)
        {
            let worst = error.iter().copied().fold(0.0, f64::max);
            let above = error.iter().filter(|&&e| e > SPHERE_NOTE_ERROR).count();
            if above > 0 {
                line += &format!(
                    "\nwarning: {at}the exact sphere's estimated error (the size of its \
                     grid-extrapolation step) exceeds {SPHERE_NOTE_ERROR:.0e} at {above} of {} \
                     speeds, up to {worst:.1e} (column error_estimate): at low speed the \
                     material's memory is shorter than a boundary-element cell",
                    error.len()
                );
            }
        } else if let (ForwardRung::Exact(_), Some(error)) = (&block.rung, &solved.error) {
            let unresolved: Vec<usize> = (0..error.len())
                .filter(|&i| error[i] > rollfit_model::exact::RESOLVED_ERROR)
                .collect();
            if let (Some(&first), Some(&last)) = (unresolved.first(), unresolved.last()) {
                let worst = unresolved.iter().map(|&i| error[i]).fold(0.0, f64::max);
                line += &format!(
                    "\nwarning: {at}the exact solution does not resolve the pressure's edge \
                     layers at {} of {} speeds (v = {:.3e} … {:.3e} m/s: low speed, or large \
                     E1/E0 below the friction maximum); estimated error there up to {worst:.1e} \
                     (column error_estimate)",
                    unresolved.len(),
                    error.len(),
                    setup.speeds[first],
                    setup.speeds[last]
                );
            }
        }
        if let Some(error) = &solved.table_error {
            let worst = error.iter().copied().fold(0.0, f64::max);
            line += &format!(
                "\n{at}the table's interpolation between its rows: μ estimated to err by up to \
                 {worst:.1e} relative (column table_error_estimate), beside the quadrature's \
                 tolerance {:.0e}",
                block.scene.tolerance()
            );
        }
        if matches!(block.rung, ForwardRung::LowSpeed) {
            line += &format!(
                "\n{at}μ is the low-speed asymptote (Eqs. 18/19) at every speed: exact as v → 0 \
                 only (use size = \"auto\" to use it only where it is accurate)"
            );
            break;
        }
    }
    line
}

/// The first line of the summary.
fn summary_line(setup: &ForwardSetup, mu: &[Vec<f64>]) -> String {
    let first = &setup.blocks[0].scene;
    let g = first.geometry();
    let (shape, load_unit, size_name) = match g.shape {
        Shape::Sphere => ("sphere", "N", "r0"),
        Shape::Cylinder => ("cylinder", "N/m", "a0"),
    };
    let speeds = &setup.speeds;
    let mut line = format!("{shape} R = {} m, load {} {load_unit}", g.radius, g.load);
    let shifts: Vec<_> = setup.blocks.iter().filter_map(|b| b.shift).collect();
    // The vertical factors, where the scene has any (b_T = 1 says nothing).
    let vertical = shifts.iter().any(|s| s.log10_b_t != 0.0);
    let list = |f: &dyn Fn(&scene_file::ShiftApplied) -> String| {
        shifts.iter().map(f).collect::<Vec<_>>().join(", ")
    };
    let factors = || {
        // + 0.0: WLF gives −0 at T_ref, which would print as "-0.0000".
        let mut text = format!(
            "log10 a_T = {}",
            list(&|s| format!("{:.4}", s.log10_a_t + 0.0))
        );
        if vertical {
            text += &format!(
                "; log10 b_T = {}",
                list(&|s| format!("{:.4}", s.log10_b_t + 0.0))
            );
        }
        text
    };
    match shifts.as_slice() {
        [] => {}
        [shift] => {
            line += &format!(", T = {} °C ({})", shift.temperature, factors());
        }
        many => {
            line += &format!(
                ", temperature set of {} temperatures T = {} °C ({}), {} speeds each, {} rows",
                many.len(),
                list(&|s| s.temperature.to_string()),
                factors(),
                speeds.len(),
                many.len() * speeds.len()
            );
        }
    }
    line += &format!(
        ": static contact {size_name} = {:.4e} m, mean pressure p_a = {:.4e} Pa; ",
        first.static_contact_size(),
        first.static_mean_pressure()
    );
    if setup
        .blocks
        .iter()
        .any(|b| !matches!(b.rung, ForwardRung::Paper))
    {
        // The exact solution, auto and the asymptote are not refined
        // between samples (a contact solve a μ, a mix of rungs, no
        // maximum); the summary gives the largest sampled value.
        let peaks: Vec<String> = setup
            .blocks
            .iter()
            .zip(mu)
            .map(|(block, mu)| {
                let at = block
                    .shift
                    .map(|s| format!("at {} °C ", s.temperature))
                    .unwrap_or_default();
                let i = (0..mu.len())
                    .max_by(|&a, &b| mu[a].total_cmp(&mu[b]))
                    .unwrap_or(0);
                let rung = match block.rung {
                    ForwardRung::Exact(_) => "exact solution: ",
                    ForwardRung::Auto { .. } => "auto: ",
                    ForwardRung::LowSpeed => "low-speed asymptote: ",
                    ForwardRung::Paper => "",
                };
                format!(
                    "{at}{rung}largest sampled μ = {:.4e} at v = {:.4e} m/s",
                    mu[i], speeds[i]
                )
            })
            .collect();
        line += &peaks.join("; ");
    } else if let [block] = setup.blocks.as_slice() {
        line += &peak_description(&block.scene, speeds, &mu[0]);
    } else {
        let peaks: Vec<String> = setup
            .blocks
            .iter()
            .zip(mu)
            .map(|(block, mu)| {
                let t = block.shift.map_or(f64::NAN, |s| s.temperature);
                format!("at {t} °C {}", peak_description(&block.scene, speeds, mu))
            })
            .collect();
        line += &peaks.join("; ");
    }
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
