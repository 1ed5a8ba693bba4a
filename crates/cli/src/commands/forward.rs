//! `rollfit forward SCENE.toml [-o OUT.csv] [--noise REL [--seed N]]`: μ(v)
//! of a scene over its `[sweep]` of speeds, optionally as a synthetic
//! measurement with multiplicative Gaussian noise.
//!
//! Temperatures: `[sweep] temperature = T` evaluates the material shifted to
//! T (°C); a list, `temperature = [T1, T2, ..]`, makes a synthetic
//! temperature set: one block of rows per temperature, in the listed order,
//! each the full speed sweep at that temperature. Whenever `temperature` is
//! set, a column `T` (°C) is added as the last column.
//!
//! Noise: each μ_i is multiplied by (1 + REL·z_i), z_i independent standard
//! normal deviates, and reported with its standard deviation
//! σ_i = REL·μ_exact,i. The deviates come from one ChaCha8 stream seeded
//! with `seed_from_u64(N)` (rand_chacha) through rand_distr's
//! `StandardNormal`, drawn in row order over the whole file (for a
//! temperature set: the first temperature's sweep, then the next one's, ..):
//! a seed names one fixed data set, the same on every machine for the
//! versions pinned in Cargo.lock. The first block of a set therefore has the
//! noise of the single-temperature file with the same seed.

mod counted;
mod pressure_maps;
mod summary;

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use rollfit_io::columns::MU;
use rollfit_io::fit_dir::columns::{SIGMA, T, V};
use rollfit_io::{csv_text, output, table};
use rollfit_model::exact::ExactRolling;
use rollfit_model::ladder::AutoSweep;
use rollfit_model::plausibility;
use rollfit_model::{ModelError, Shape, ViscoelasticModulus};
use rollfit_report::plot::{
    self, Picture, forward_sweep::ForwardSweepFigure, forward_sweep::SweepCurve,
};

use crate::{progress, stdout};
use counted::Counted;
use indicatif::ProgressBar;
use rollfit_io::scene::{
    self as scene_file, DynScene, ForwardBlock, ForwardRung, ForwardSetup, MaterialKind, SceneFile,
};

/// CSV columns, in order (docs/ARCHITECTURE.md, "Contract", fixes `v` and `mu`; the rest is ours):
/// speed v (m/s); friction coefficient μ; its low-speed asymptote (Eqs.
/// 18/19); static Hertz contact size r0 or a0 (m) and mean pressure p_a
/// (Pa), the same on every row; pressure-centroid shift x̄ = μR (m);
/// Greenwood–Tabor hysteresis fraction α that reproduces μ (Eq. 20).
pub const COLUMNS: [&str; 7] = [
    V,
    MU,
    "mu_low_speed",
    "contact_size_static",
    "mean_pressure_static",
    "centroid_shift",
    "gt_alpha",
];

/// CSV columns with `--noise`: v; the noisy μ; its standard deviation σ;
/// the noiseless μ; then the columns after `mu` in [`COLUMNS`], computed
/// from the noiseless μ (they describe the model, not the measurement).
pub const NOISY_COLUMNS: [&str; 9] = [
    V,
    MU,
    SIGMA,
    "mu_exact",
    "mu_low_speed",
    "contact_size_static",
    "mean_pressure_static",
    "centroid_shift",
    "gt_alpha",
];

/// The column added last, after [`COLUMNS`] or [`NOISY_COLUMNS`], when
/// `[sweep]` sets a temperature: the temperature of the row, °C (the name
/// the fit's data reader takes a temperature set from).
pub const TEMPERATURE_COLUMN: &str = T;

/// Arguments of `rollfit forward`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scene file (TOML) with [geometry], [material] and [sweep].
    pub scene: PathBuf,
    /// Write the CSV here (atomically, creating missing folders) instead of
    /// to stdout, and its picture beside it: OUT.png and OUT.svg, μ(v) per
    /// temperature with the low-speed asymptote and the friction maximum.
    #[arg(short, long, value_name = "OUT.csv")]
    pub output: Option<PathBuf>,
    /// Make a synthetic measurement: multiply each μ by (1 + REL·z), z a
    /// standard normal deviate, and add the columns sigma (= REL·μ) and
    /// mu_exact. REL is relative, e.g. 0.01 for 1 % noise.
    #[arg(long, value_name = "REL", value_parser = parse_noise, allow_hyphen_values = true)]
    pub noise: Option<f64>,
    /// Seed of the noise generator (ChaCha8); the same seed gives the same
    /// file on every machine. Default 0. Needs --noise.
    #[arg(long, value_name = "N", requires = "noise", allow_hyphen_values = true)]
    pub seed: Option<u64>,
    /// Also write the exact contact's pressure map at this speed (m/s;
    /// repeatable), beside OUT.csv: OUT-pressure-map-v<V>.csv (x, y,
    /// pressure; a cylinder x, pressure), …-outline.csv (y, x_trailing,
    /// x_leading) and a picture. Needs -o and [contact] size = "exact" or
    /// "auto"; without it the map is written at the speed of the largest
    /// exact μ only.
    #[arg(
        long,
        value_name = "V",
        value_parser = pressure_maps::parse_speed,
        allow_hyphen_values = true,
        requires = "output"
    )]
    pub pressure_map: Vec<f64>,
}

/// `--noise`: a finite relative standard deviation greater than zero. Zero
/// would write σ = 0, which `rollfit fit` refuses (infinite weight): the
/// noiseless μ is what `forward` writes without --noise.
fn parse_noise(text: &str) -> Result<f64, String> {
    let rel: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("expected a number such as 0.01 (1 % noise), got {text:?}"))?;
    if rel.is_finite() && rel > 0.0 {
        Ok(rel)
    } else {
        Err(format!(
            "the relative noise must be a finite number greater than zero (0.01 = 1 %), got \
             {rel}; leave --noise out for the noiseless μ"
        ))
    }
}

/// Multiplicative Gaussian noise: (noisy μ, σ) for each noiseless μ, from
/// ChaCha8 seeded with `seed`, one standard normal deviate per μ in order.
pub fn add_noise(mu: &[f64], rel: f64, seed: u64) -> Vec<(f64, f64)> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    mu.iter()
        .map(|&m| {
            let z: f64 = StandardNormal.sample(&mut rng);
            (m * (1.0 + rel * z), rel * m)
        })
        .collect()
}

/// Runs the command: reads the scene, computes μ(v) (at each temperature),
/// writes the CSV and a one-line summary on stderr.
pub fn run(args: &Args) -> Result<()> {
    let path = &args.scene;
    if let Some(out) = &args.output {
        // Refuse an unusable output path before a possibly long computation.
        output::check_target(out)?;
        // Never over a result folder's file (a fit's mu.csv).
        for path in [
            out.clone(),
            out.with_extension("png"),
            out.with_extension("svg"),
        ] {
            output::check_free_file(&path)?;
        }
    }
    let file = scene_file::load(path)?;
    let setup = file
        .forward_setup(path, &|note| eprintln!("note: {note}"))
        .with_context(|| format!("scene file {}", path.display()))?;
    pressure_maps::check_request(&setup, &args.pressure_map, path)?;
    let bar = sweep_bar(&setup);
    // μ of each block, in row order.
    let solved = setup
        .blocks
        .iter()
        .map(|block| {
            if let Some(s) = block.shift {
                bar.set_message(format!("T = {} °C", s.temperature));
            }
            solve_block(block, &setup.speeds, &bar)
                .map_err(|e| explain_table_error(&file, path, block, e))
                .with_context(|| {
                    let at = block
                        .shift
                        .map(|s| format!(" at T = {} °C", s.temperature))
                        .unwrap_or_default();
                    format!("computing μ(v){at} for scene file {}", path.display())
                })
        })
        .collect::<Result<Vec<_>>>();
    bar.finish_and_clear();
    let solved = solved?;
    let mu: Vec<Vec<f64>> = solved.iter().map(|s| s.mu.clone()).collect();
    let extra = Extra {
        edges: solved.iter().any(|s| s.edges.is_some()),
        error: solved.iter().any(|s| s.error.is_some()),
        auto: solved.iter().any(|s| s.auto.is_some()),
        table_error: solved.iter().any(|s| s.table_error.is_some()),
        temperature: setup.blocks.iter().any(|b| b.shift.is_some()),
    };
    let rows = setup
        .blocks
        .iter()
        .zip(&solved)
        .flat_map(|(block, solved)| rows(block, &setup.speeds, solved));
    let refuse = |e: rollfit_io::IoError| {
        anyhow::Error::from(e).context(format!(
            "scene file {}: the model gives a number that is not finite; check [geometry] \
             radius and load and the material's moduli for values far outside a rolling \
             contact",
            path.display()
        ))
    };
    let bytes = match args.noise {
        None => csv_text::csv_text_bytes(&header(&COLUMNS, extra), rows).map_err(refuse)?,
        Some(rel) => {
            // One stream over the whole file, in row order.
            let exact: Vec<f64> = mu.iter().flatten().copied().collect();
            let noisy = add_noise(&exact, rel, args.seed.unwrap_or(0));
            let negative = noisy.iter().filter(|(m, _)| *m <= 0.0).count();
            if negative > 0 {
                // Kept, not clipped: clipping would bias the data set; a
                // fit with relative weights needs to know, though.
                eprintln!(
                    "warning: {negative} of {} noisy μ values are zero or negative \
                     (with --noise {rel}, every deviate below -1/{rel} gives one)",
                    noisy.len()
                );
            }
            let rows = rows.zip(noisy).map(|(mut row, (m, sigma))| {
                // [v, mu_exact, rest.., (T)] → [v, mu, sigma, mu_exact, rest.., (T)]
                row.splice(1..1, [csv_text::number(m), csv_text::number(sigma)]);
                row
            });
            csv_text::csv_text_bytes(&header(&NOISY_COLUMNS, extra), rows).map_err(refuse)?
        }
    };
    let mut map_lines = Vec::new();
    match &args.output {
        Some(out) => {
            // Drawn, and the maps solved, before anything is written, so
            // that a failure leaves no CSV without its pictures and maps.
            let picture = picture(&setup, &mu, path)?;
            let maps = pressure_maps::solve(&setup, &solved, &args.pressure_map, out, path)?;
            output::write_atomically(out, &bytes)?;
            output::write_atomically(&out.with_extension("png"), &picture.png)?;
            output::write_atomically(&out.with_extension("svg"), picture.svg.as_bytes())?;
            map_lines = pressure_maps::write(&maps)?;
        }
        None => stdout::write_stdout(&bytes)?,
    }
    eprintln!("{}", summary::summary(&setup, &solved, &mu));
    for line in map_lines {
        eprintln!("{line}");
    }
    for line in plausibility_warnings(&setup, &mu) {
        eprintln!("warning: {line}");
    }
    Ok(())
}

/// A contact-map error of a "table" material with what a user can do
/// about it: the table lines that cause it (see
/// [`table::explain_contact_map`]); other errors pass unchanged.
fn explain_table_error(
    file: &SceneFile,
    scene: &Path,
    block: &ForwardBlock,
    e: anyhow::Error,
) -> anyhow::Error {
    // The model's error is kept as the anyhow error's own value
    // (`anyhow::Error::msg` in `solve_block`), so it is found by type.
    let Some(&ModelError::ContactMapNotIncreasing { omega, exponent }) =
        e.downcast_ref::<ModelError>()
    else {
        return e;
    };
    let message = format!("{e:#}");
    let Some(material) = file
        .material
        .as_ref()
        .filter(|m| m.model == MaterialKind::Table)
    else {
        return e;
    };
    let Ok((table_path, table)) = material.read_table(scene.parent().unwrap_or(Path::new("")))
    else {
        return e;
    };
    // The block's material is shifted, E_T(ω) = E_ref(ω a_T): the table's
    // own frequency is ω a_T.
    let omega = omega * block.shift.map_or(1.0, |s| 10f64.powf(s.log10_a_t));
    anyhow::anyhow!(
        "{message}\n{}",
        table::explain_contact_map(&table, &table_path, omega, exponent)
    )
}

/// The plausibility checks of [`rollfit_model::plausibility`]: the scene's inputs, its
/// material at each temperature and the predicted μ, one message each
/// (warnings only: the exit status stays 0). A message the same at every
/// temperature is given once; others name their temperature.
fn plausibility_warnings(setup: &ForwardSetup, mu: &[Vec<f64>]) -> Vec<String> {
    let speeds = &setup.speeds;
    let mut lines: Vec<String> =
        plausibility::input_warnings(&setup.blocks[0].scene.rolling_setup(), speeds, None)
            .into_iter()
            .map(|w| w.message)
            .collect();
    let per_block: Vec<(Option<f64>, Vec<String>)> = setup
        .blocks
        .iter()
        .zip(mu)
        .map(|(block, mu)| {
            let scene = &block.scene;
            let material = scene.material();
            let e0 = material.static_modulus();
            // The glassy modulus: exact for a positive spectrum, else |E|
            // three decades above the modulus's structure.
            let e1 = material
                .relaxation_bound()
                .unwrap_or_else(|| material.modulus(1e3 * material.structure_range().1).norm());
            let rolling = scene.rolling_setup();
            let modulus = |omega: f64| material.modulus(omega);
            let mut w = plausibility::material_warnings(&rolling, speeds, &modulus, e0, e1, false);
            w.extend(plausibility::predicted_friction_warnings(
                &rolling, speeds, mu, e0, false,
            ));
            let messages = w.into_iter().map(|w| w.message).collect();
            (block.shift.map(|s| s.temperature), messages)
        })
        .collect();
    for (i, (temperature, messages)) in per_block.iter().enumerate() {
        for m in messages {
            if per_block.iter().all(|(_, other)| other.contains(m)) {
                if i == 0 {
                    lines.push(m.clone());
                }
            } else {
                lines.push(match temperature {
                    Some(t) => format!("at {t} °C: {m}"),
                    None => m.clone(),
                });
            }
        }
    }
    lines
}

/// Columns of the exact solution (`[contact] size = "exact"`): the contact
/// edges relative to the cylinder's axis, m (trailing < 0 < leading).
pub const EDGE_COLUMNS: [&str; 2] = ["contact_trailing_edge", "contact_leading_edge"];

/// Column of `[contact] size = "exact"` and `"auto"`: the estimated
/// relative error of μ (the exact solution's discretisation error; for
/// auto, against the exact physics, see crates/model/src/ladder).
pub const ERROR_COLUMN: &str = "error_estimate";

/// Column of a `table` material on the `"dynamic"` and `"static"` rungs:
/// the estimated relative error of μ that comes from interpolating between
/// the table's rows (`Scene::table_interpolation_error`: μ of the same rows
/// interpolated with higher-order slopes, compared). It adds to the
/// quadrature's tolerance.
pub const TABLE_ERROR_COLUMN: &str = "table_error_estimate";

/// Column of `[contact] size = "auto"`: the rung that gave μ
/// ("low-speed", "dynamic", "dynamic-film" or "exact").
pub const RUNG_COLUMN: &str = "rung";

/// (trailing, leading) contact edges per speed, m.
type Edges = Vec<[f64; 2]>;

/// μ of one block and what came with it.
struct Solved {
    mu: Vec<f64>,
    /// Contact edges of the exact solution.
    edges: Option<Edges>,
    /// Estimated relative error of each μ (exact or auto).
    error: Option<Vec<f64>>,
    /// What `auto` chose.
    auto: Option<AutoSweep>,
    /// Estimated relative error of each μ from a table's interpolation.
    table_error: Option<Vec<f64>>,
}

/// Which optional columns the file has.
#[derive(Clone, Copy)]
struct Extra {
    edges: bool,
    error: bool,
    auto: bool,
    table_error: bool,
    temperature: bool,
}

/// The bar of a sweep's exact solves: the speeds of its `exact` blocks,
/// and the solves `auto` makes as it decides on them; hidden when no block
/// solves the exact contact (the other rungs take milliseconds).
fn sweep_bar(setup: &ForwardSetup) -> ProgressBar {
    let exact = |rung: &ForwardRung| match rung {
        ForwardRung::Exact(_) => Some(true),
        ForwardRung::Auto { exact: Ok(_), .. } => Some(false),
        _ => None,
    };
    let rungs: Vec<bool> = setup.blocks.iter().filter_map(|b| exact(&b.rung)).collect();
    if rungs.is_empty() {
        return ProgressBar::hidden();
    }
    let planned = rungs.iter().filter(|e| **e).count() * setup.speeds.len();
    progress::bar(Some(planned as u64), "exact solves")
}

/// μ at every speed of one block by its rung; `bar` counts exact solves.
fn solve_block(block: &ForwardBlock, speeds: &[f64], bar: &ProgressBar) -> Result<Solved> {
    let mu_only = |mu| Solved {
        mu,
        edges: None,
        error: None,
        auto: None,
        table_error: None,
    };
    match &block.rung {
        ForwardRung::Paper => {
            let mu = block
                .scene
                .friction_sweep(speeds)
                .map_err(anyhow::Error::msg)?;
            let table_error = block
                .scene
                .table_interpolation_error(speeds, &mu)
                .map_err(anyhow::Error::msg)?;
            Ok(Solved {
                table_error,
                ..mu_only(mu)
            })
        }
        ForwardRung::LowSpeed => Ok(mu_only(
            speeds
                .iter()
                .map(|&v| block.scene.low_speed_asymptote(v))
                .collect(),
        )),
        ForwardRung::Auto { accuracy, exact } => {
            let counted = exact
                .as_ref()
                .map(|b| Counted::new(b.as_ref(), bar.clone()))
                .map_err(Clone::clone);
            let auto = block
                .scene
                .friction_auto_with(
                    speeds,
                    *accuracy,
                    counted
                        .as_ref()
                        .map(|c| c as &dyn ExactRolling)
                        .map_err(Clone::clone),
                )
                .map_err(anyhow::Error::msg)?;
            Ok(Solved {
                mu: auto.mu.clone(),
                edges: None,
                error: Some(auto.error_estimate.clone()),
                auto: Some(auto),
                table_error: None,
            })
        }
        ForwardRung::Exact(body) => {
            // Milliseconds (cylinder) to a second (sphere) a speed: in
            // parallel.
            use rayon::prelude::*;
            let solutions = speeds
                .par_iter()
                .map(|&v| {
                    let solved = body.exact_friction(v);
                    bar.inc(1);
                    solved
                })
                .collect::<Result<Vec<_>, _>>()
                .map_err(anyhow::Error::msg)?;
            Ok(Solved {
                mu: solutions.iter().map(|s| s.mu).collect(),
                edges: Some(
                    solutions
                        .iter()
                        .map(|s| [s.trailing_edge, s.leading_edge])
                        .collect(),
                ),
                error: Some(solutions.iter().map(|s| s.error_estimate).collect()),
                auto: None,
                table_error: None,
            })
        }
    }
}

/// `columns`, then the edge, error, auto, table-error and temperature
/// columns the file has.
fn header(columns: &[&'static str], extra: Extra) -> Vec<&'static str> {
    let mut header = columns.to_vec();
    if extra.edges {
        header.extend(EDGE_COLUMNS);
    }
    if extra.error {
        header.push(ERROR_COLUMN);
    }
    if extra.auto {
        header.push(RUNG_COLUMN);
    }
    if extra.table_error {
        header.push(TABLE_ERROR_COLUMN);
    }
    if extra.temperature {
        header.push(TEMPERATURE_COLUMN);
    }
    header
}

/// The rows of one block: the columns of [`COLUMNS`], the block's extra
/// columns, then its temperature if it has one.
fn rows<'a>(
    block: &'a ForwardBlock,
    speeds: &'a [f64],
    solved: &'a Solved,
) -> impl Iterator<Item = Vec<String>> + 'a {
    let scene = &block.scene;
    let contact_size = scene.static_contact_size();
    let pressure = scene.static_mean_pressure();
    let temperature = block.shift.map(|s| s.temperature);
    speeds
        .iter()
        .zip(&solved.mu)
        .enumerate()
        .map(move |(i, (&v, &mu))| {
            let mut row = vec![
                v,
                mu,
                scene.low_speed_asymptote(v),
                contact_size,
                pressure,
                scene.centroid_shift(mu),
                scene.greenwood_tabor_alpha(mu),
            ];
            if let Some(edges) = &solved.edges {
                row.extend(edges[i]);
            }
            if let Some(error) = &solved.error {
                row.push(error[i]);
            }
            let mut row: Vec<String> = row.into_iter().map(csv_text::number).collect();
            if let Some(auto) = &solved.auto {
                row.push(auto.rungs[i].name().to_string());
            }
            if let Some(error) = &solved.table_error {
                row.push(csv_text::number(error[i]));
            }
            row.extend(temperature.map(csv_text::number));
            row
        })
}

/// The picture of the sweep written beside the CSV: μ(v) per temperature
/// with its low-speed asymptote and friction maximum.
fn picture(setup: &ForwardSetup, mu: &[Vec<f64>], scene_path: &Path) -> Result<Picture> {
    let curves: Vec<SweepCurve> = setup
        .blocks
        .iter()
        .zip(mu)
        .map(|(block, mu)| SweepCurve {
            temperature: block.shift.map(|s| s.temperature),
            speeds: setup.speeds.clone(),
            mu: mu.clone(),
            mu_low_speed: setup
                .speeds
                .iter()
                .map(|&v| block.scene.low_speed_asymptote(v))
                .collect(),
            maximum: friction_maximum(&block.scene, &setup.speeds, mu).map(|(v, m, _)| (v, m)),
        })
        .collect();
    let g = setup.blocks[0].scene.geometry();
    let (shape, unit) = match g.shape {
        Shape::Sphere => ("sphere", "N"),
        Shape::Cylinder => ("cylinder", "N/m"),
    };
    let title = format!(
        "{}: {shape} R = {} m, load {} {unit}",
        scene_path
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned()),
        g.radius,
        g.load
    );
    plot::render(&ForwardSweepFigure {
        curves: &curves,
        title,
    })
    .map_err(|e| anyhow::anyhow!("{e}"))
}

/// The friction maximum inside the sweep as (v, μ, refined): refined
/// between the sampled speeds around the largest sampled μ, or that sample
/// when refining fails; None when the largest μ is at either end.
fn friction_maximum(scene: &DynScene, speeds: &[f64], mu: &[f64]) -> Option<(f64, f64, bool)> {
    let n = mu.len();
    let i = (0..n).max_by(|&a, &b| mu[a].total_cmp(&mu[b]))?;
    if n < 3 || i == 0 || i == n - 1 {
        return None;
    }
    Some(match scene.friction_maximum(speeds[i - 1], speeds[i + 1]) {
        Ok(peak) => (peak.speed, peak.mu, true),
        Err(_) => (speeds[i], mu[i], false),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_is_reproducible_and_relative() {
        let mu = [1e-3, 2e-2, 5e-1];
        let a = add_noise(&mu, 0.01, 7);
        assert_eq!(a, add_noise(&mu, 0.01, 7));
        assert_ne!(a, add_noise(&mu, 0.01, 8));
        for ((m, sigma), exact) in a.iter().zip(mu) {
            assert_eq!(*sigma, 0.01 * exact);
            assert!((m / exact - 1.0).abs() < 0.1);
        }
        let none = add_noise(&mu, 0.0, 3);
        assert!(none.iter().zip(mu).all(|(&(m, s), e)| m == e && s == 0.0));
    }

    #[test]
    fn noise_level_is_checked() {
        assert_eq!(parse_noise("0.01"), Ok(0.01));
        assert!(parse_noise("0").is_err());
        for bad in ["-0.01", "nan", "inf", "1%", ""] {
            assert!(parse_noise(bad).is_err(), "{bad}");
        }
    }
}
