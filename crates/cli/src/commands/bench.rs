//! `rollfit bench [-o DIR]`: the speed–accuracy chart (issue 6).
//!
//! Forward model: for the scene (default data/paper-fig2-cylinder.toml, the
//! paper's standard linear solid E1/E0 = 10 under a cylinder), every rung of
//! the model ladder — the low-speed asymptote (Eqs. 18/19), the static and
//! the dynamic contact size (Eq. 11, the paper), the exact cylinder, and
//! `auto` at a dial of requested accuracies — at each quadrature
//! tolerance of the dial, timed per μ and compared over the scene's sweep
//! with the reference: the dynamic rung at tolerance 1e-11, i.e. the
//! paper's theory computed to rounding (the asymptote only at speeds two
//! decades and more below the friction maximum, where it is meant to hold). The error of the static rung and of
//! the asymptote against it is their model error relative to the paper; the
//! error of the dynamic rung is the quadrature's alone.
//!
//! Fitting: on the bundled example (data/hn-rubber.toml, hn-rubber.csv,
//! truth in its [material]), each method — Levenberg–Marquardt, L-BFGS,
//! Nelder–Mead — from the same neutral start at the same λ (the one the
//! default fit chooses), one start, with a dial of evaluation budgets; the
//! error is the RMS relative error of the recovered tan δ against the
//! truth over the window shrunk by half a decade at each end.
//!
//! Writes DIR/forward.csv, DIR/fit.csv and the charts DIR/forward.{png,svg}
//! and DIR/fit.{png,svg} (default DIR: fits/bench). Timings are wall time
//! of this process on this machine; the CSVs say which.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context, Result, anyhow};
use rollfit_fit::{Lambda, Method};
use rollfit_io::{csv_text, output};
use rollfit_model::exact::{ExactSettings, RollingCylinder};
use rollfit_model::{ContactSize, Prony, Scene, ViscoelasticModulus};
use rollfit_report::plot::speed_accuracy::{CostPoint, SpeedAccuracyFigure};
use rollfit_report::plot::{SeriesLabelPosition, render};

use crate::{data_file, scene_file};

/// Arguments of `rollfit bench`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Folder for forward.csv, fit.csv and the charts.
    #[arg(short, long, value_name = "DIR", default_value = "fits/bench")]
    pub output: PathBuf,
    /// Scene of the forward-model chart (its [sweep] gives the speeds).
    #[arg(
        long,
        value_name = "SCENE",
        default_value = "data/paper-fig2-cylinder.toml"
    )]
    pub forward_scene: PathBuf,
    /// Scene of the fitting chart; its [material] is the truth.
    #[arg(long, value_name = "SCENE", default_value = "data/hn-rubber.toml")]
    pub fit_scene: PathBuf,
    /// Data of the fitting chart.
    #[arg(long, value_name = "DATA", default_value = "data/hn-rubber.csv")]
    pub fit_data: PathBuf,
    /// Fewer settings and shorter timings (for tests).
    #[arg(long)]
    pub quick: bool,
}

/// Quadrature tolerances of the dial.
const TOLERANCES: [f64; 6] = [1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-8];
/// Chebyshev terms of the exact rung's dial (None: the automatic choice).
const TERMS: [Option<usize>; 6] = [Some(12), Some(16), Some(24), Some(32), Some(48), None];
/// Requested accuracies of the auto rung.
const ACCURACIES: [f64; 5] = [1e-1, 3e-2, 1e-2, 3e-3, 1e-3];
/// The reference's tolerance.
const REFERENCE_TOLERANCE: f64 = 1e-11;
/// Evaluation budgets of the fitting dial (per solver run).
const BUDGETS: [usize; 6] = [100, 300, 1000, 3000, 10_000, 20_000];

/// The settings swept, and how long each is timed.
struct Dials<'a> {
    /// Quadrature tolerances of Eq. (11)/(17).
    tolerances: &'a [f64],
    /// Chebyshev terms of the exact rung (None: automatic).
    terms: &'a [Option<usize>],
    /// Requested accuracies of auto.
    accuracies: &'a [f64],
    /// Evaluation budgets of the fitting chart.
    budgets: &'a [usize],
    /// At most this many speeds of the forward scene.
    max_speeds: usize,
    /// Seconds each timing runs at least.
    min_time: f64,
}

/// One row of forward.csv.
struct ForwardRow {
    rung: &'static str,
    /// The dial: a quadrature tolerance or a number of Chebyshev terms.
    setting: String,
    time_per_mu: f64,
    /// Against the reference (model and numerical error together).
    max_error: f64,
    rms_error: f64,
    /// Against the same rung computed tightly: the numerical error alone.
    numerical_error: f64,
}

/// One row of fit.csv.
struct FitRow {
    method: &'static str,
    budget: usize,
    wall_time: f64,
    evaluations: usize,
    tan_delta_rms: f64,
    converged: bool,
}

/// Runs the command.
pub fn run(args: &Args) -> Result<()> {
    let quick_terms = [Some(16), None];
    let dials = if args.quick {
        Dials {
            tolerances: &TOLERANCES[..2],
            terms: &quick_terms,
            accuracies: &ACCURACIES[..1],
            budgets: &BUDGETS[..2],
            max_speeds: 7,
            min_time: 0.005,
        }
    } else {
        Dials {
            tolerances: &TOLERANCES,
            terms: &TERMS,
            accuracies: &ACCURACIES,
            budgets: &BUDGETS,
            max_speeds: 31,
            min_time: 0.2,
        }
    };
    let forward = forward_rows(&args.forward_scene, &dials)
        .with_context(|| format!("scene file {}", args.forward_scene.display()))?;
    let fits = fit_rows(&args.fit_scene, &args.fit_data, dials.budgets)?;

    let mut forward_points: Vec<CostPoint> = forward
        .rows
        .iter()
        .map(|r| CostPoint {
            series: r.rung.to_string(),
            setting: r.setting.clone(),
            cost: r.time_per_mu,
            error: r.max_error,
            ok: true,
        })
        .collect();
    // The tolerance dial of the paper's model, seen apart from its model
    // error: the dynamic rung against itself computed tightly.
    forward_points.extend(
        forward
            .rows
            .iter()
            .filter(|r| r.rung == "dynamic")
            .map(|r| CostPoint {
                series: "dynamic, quadrature error alone".into(),
                setting: r.setting.clone(),
                cost: r.time_per_mu,
                error: r.numerical_error,
                ok: true,
            }),
    );
    let fit_points: Vec<CostPoint> = fits
        .iter()
        .map(|r| CostPoint {
            series: r.method.to_string(),
            setting: r.budget.to_string(),
            cost: r.wall_time,
            error: r.tan_delta_rms,
            ok: r.converged,
        })
        .collect();
    let forward_chart = render(&SpeedAccuracyFigure {
        name: "forward",
        title: "Forward model: error against time per μ".into(),
        caption: format!(
            "Largest relative error of μ at {} speeds of {} ({:.3e} … {:.3e} m/s) against {}, against the time per μ, for each rung of the model ladder and each setting (labels: quadrature tolerance, or Chebyshev terms of the exact solution).",
            forward.speeds.len(),
            args.forward_scene.display(),
            forward.speeds[0],
            forward.speeds[forward.speeds.len() - 1],
            forward.reference
        ),
        cost_description: "time per μ (s)",
        error_description: "largest relative error of μ",
        points: &forward_points,
        legend: SeriesLabelPosition::LowerLeft,
    })?;
    let fit_chart = render(&SpeedAccuracyFigure {
        name: "fit",
        title: "Fitting: tan δ error against wall time".into(),
        caption: format!(
            "RMS relative error of the recovered tan δ against the truth of {} over its window, against the fit's wall time, for each method from the same start at the same λ and each evaluation budget (labels); hollow: the run did not converge.",
            args.fit_data.display()
        ),
        cost_description: "wall time of the fit (s)",
        error_description: "RMS relative error of tan δ",
        points: &fit_points,
        legend: SeriesLabelPosition::UpperRight,
    })?;

    let mut forward_text = format!(
        "# errors against {}; {} speeds {:e} … {:e} m/s; times on this machine\n\
         rung,setting,time_per_mu_s,max_rel_error,rms_rel_error,numerical_rel_error\n",
        forward.reference,
        forward.speeds.len(),
        forward.speeds[0],
        forward.speeds[forward.speeds.len() - 1]
    );
    for r in &forward.rows {
        forward_text.push_str(&format!(
            "{},{},{},{},{},{}\n",
            r.rung,
            r.setting,
            csv_text::number(r.time_per_mu),
            csv_text::number(r.max_error),
            csv_text::number(r.rms_error),
            csv_text::number(r.numerical_error)
        ));
    }
    let mut fit_text = String::from(
        "method,max_evaluations,wall_time_s,evaluations,tan_delta_rms_rel,converged\n",
    );
    for r in &fits {
        fit_text.push_str(&format!(
            "{},{},{},{},{},{}\n",
            r.method,
            r.budget,
            csv_text::number(r.wall_time),
            r.evaluations,
            csv_text::number(r.tan_delta_rms),
            r.converged
        ));
    }
    let dir = &args.output;
    output::write_atomically(&dir.join("forward.csv"), forward_text.as_bytes())?;
    output::write_atomically(&dir.join("fit.csv"), fit_text.as_bytes())?;
    for p in [&forward_chart, &fit_chart] {
        output::write_atomically(&dir.join(format!("{}.png", p.name)), &p.png)?;
        output::write_atomically(&dir.join(format!("{}.svg", p.name)), p.svg.as_bytes())?;
    }
    eprintln!(
        "wrote {} (forward.csv, fit.csv, forward.png/svg, fit.png/svg)",
        dir.display()
    );
    Ok(())
}

/// Times `f` (one call evaluates `count` μ) until at least `min_time` has
/// passed; seconds per μ.
fn time_per_mu(count: usize, min_time: f64, mut f: impl FnMut() -> Result<()>) -> Result<f64> {
    let started = Instant::now();
    let mut calls = 0usize;
    loop {
        f()?;
        calls += 1;
        let elapsed = started.elapsed().as_secs_f64();
        if elapsed >= min_time {
            return Ok(elapsed / (calls * count) as f64);
        }
    }
}

fn errors(values: &[f64], reference: &[f64]) -> (f64, f64) {
    let relative: Vec<f64> = values
        .iter()
        .zip(reference)
        .map(|(v, r)| ((v - r) / r).abs())
        .collect();
    let max = relative.iter().copied().fold(0.0, f64::max);
    let rms = (relative.iter().map(|e| e * e).sum::<f64>() / relative.len() as f64).sqrt();
    (max, rms)
}

/// The forward chart's measurements and what they were compared with.
struct Forward {
    rows: Vec<ForwardRow>,
    /// What the errors are relative to.
    reference: String,
    /// Speeds compared, m/s.
    speeds: Vec<f64>,
}

fn forward_rows(path: &Path, dials: &Dials<'_>) -> Result<Forward> {
    let Dials {
        tolerances,
        terms,
        accuracies,
        max_speeds,
        min_time,
        ..
    } = *dials;
    let file = scene_file::load(path)?;
    let section = file
        .material
        .as_ref()
        .context("bench needs a [material] section")?;
    let base = path.parent().unwrap_or(Path::new(""));
    let material: Arc<dyn ViscoelasticModulus> = Arc::from(section.build(base)?);
    let sweep = file
        .sweep
        .as_ref()
        .context("bench needs a [sweep] section")?
        .speeds()?;
    let setup = file.rolling_setup();
    let scene =
        |contact: ContactSize, tolerance: f64| -> Result<Scene<Arc<dyn ViscoelasticModulus>>> {
            Scene::new(
                setup.geometry,
                setup.substrate,
                contact,
                Arc::clone(&material),
            )
            .and_then(|s| s.with_tolerance(tolerance))
            .map_err(|e| anyhow!("{e}"))
        };
    let paper = scene(ContactSize::Dynamic, REFERENCE_TOLERANCE)?
        .friction_sweep(&sweep)
        .map_err(|e| anyhow!("{e}"))?;
    let peak = paper
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map_or(0, |(i, _)| i);
    let v_peak = sweep[peak];

    // With the exact solution (cylinder, half-space, SLS or Prony) the
    // errors are against it, from three decades below the friction maximum
    // up (lower, its edge layers need more terms than the reference has);
    // otherwise against the paper's theory at a tight tolerance.
    let exact_material = file.exact_material(section, base, None);
    let (speeds, reference, reference_name, prony) = match exact_material {
        Ok(prony) => {
            let kept: Vec<f64> = sweep
                .iter()
                .copied()
                .filter(|&v| v >= v_peak * 1e-3)
                .collect();
            let speeds = thin(&kept, max_speeds);
            let settings = ExactSettings {
                terms: Some(REFERENCE_TERMS),
                max_terms: REFERENCE_TERMS,
                ..ExactSettings::default()
            };
            let cylinder = file.exact_cylinder_with(&prony, settings)?;
            let reference = exact_sweep(&cylinder, &speeds)?;
            (
                speeds,
                reference,
                format!("the exact rolling cylinder with {REFERENCE_TERMS} Chebyshev terms"),
                Some(prony),
            )
        }
        Err(why) => {
            let speeds = thin(&sweep, max_speeds);
            let reference = scene(ContactSize::Dynamic, REFERENCE_TOLERANCE)?
                .friction_sweep(&speeds)
                .map_err(|e| anyhow!("{e}"))?;
            (
                speeds,
                reference,
                format!(
                    "Eq. (11) with the dynamic contact size at tolerance {REFERENCE_TOLERANCE:.0e} \
                     (no exact rung: {why:#})"
                ),
                None,
            )
        }
    };

    let mut rows = Vec::new();
    // The asymptote is a low-speed law (μ ∝ v^p grows without bound): its
    // error is measured where it is meant to hold, two decades and more
    // below the speed of the friction maximum.
    let low: Vec<usize> = (0..speeds.len())
        .filter(|&i| speeds[i] <= v_peak / 100.0)
        .collect();
    if !low.is_empty() {
        let asymptotic = scene(ContactSize::Static, tolerances[0])?;
        let low_speeds: Vec<f64> = low.iter().map(|&i| speeds[i]).collect();
        let mut values = Vec::new();
        let time = time_per_mu(low_speeds.len(), min_time, || {
            values = low_speeds
                .iter()
                .map(|&v| asymptotic.low_speed_asymptote(v))
                .collect();
            Ok(())
        })?;
        let low_reference: Vec<f64> = low.iter().map(|&i| reference[i]).collect();
        let (max_error, rms_error) = errors(&values, &low_reference);
        rows.push(ForwardRow {
            rung: "asymptote",
            setting: "v ≤ v_peak/100".into(),
            time_per_mu: time,
            max_error,
            rms_error,
            numerical_error: f64::NAN,
        });
    }
    for (rung, contact) in [
        ("static", ContactSize::Static),
        ("dynamic", ContactSize::Dynamic),
    ] {
        let tight = scene(contact, REFERENCE_TOLERANCE)?
            .friction_sweep(&speeds)
            .map_err(|e| anyhow!("{e}"))?;
        for &tolerance in tolerances {
            let s = scene(contact, tolerance)?;
            let mut values = Vec::new();
            let time = time_per_mu(speeds.len(), min_time, || {
                values = s.friction_sweep(&speeds).map_err(|e| anyhow!("{e}"))?;
                Ok(())
            })?;
            let (max_error, rms_error) = errors(&values, &reference);
            rows.push(ForwardRow {
                rung,
                setting: format!("{tolerance:.0e}"),
                time_per_mu: time,
                max_error,
                rms_error,
                numerical_error: errors(&values, &tight).0,
            });
        }
    }
    if let Some(prony) = &prony {
        for &n in terms {
            let settings = ExactSettings {
                terms: n,
                ..ExactSettings::default()
            };
            let cylinder = file.exact_cylinder_with(prony, settings)?;
            let mut values = Vec::new();
            // One speed after another: the time of one contact solve.
            let time = time_per_mu(speeds.len(), min_time, || {
                values = speeds
                    .iter()
                    .map(|&v| cylinder.solve(v).map(|s| s.mu))
                    .collect::<Result<Vec<f64>, _>>()
                    .map_err(|e| anyhow!("{e}"))?;
                Ok(())
            })?;
            let (max_error, rms_error) = errors(&values, &reference);
            rows.push(ForwardRow {
                rung: "exact",
                setting: n.map_or_else(|| "N auto".to_string(), |n| format!("N = {n}")),
                time_per_mu: time,
                max_error,
                rms_error,
                numerical_error: max_error,
            });
        }
    }
    // auto: the cheapest rung per speed for each requested accuracy, timed
    // on one thread (its contact solves would otherwise share the cores,
    // which the other rungs' timings do not).
    let exact_for_auto = match &prony {
        Some(p) => Ok(file.exact_cylinder_with(p, ExactSettings::default())?),
        None => Err("no exact rung for this scene".to_string()),
    };
    let one_thread = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .context("cannot start a one-thread pool")?;
    let auto_scene = scene(ContactSize::Dynamic, tolerances[0])?;
    for &accuracy in accuracies {
        let mut values = Vec::new();
        let time = one_thread.install(|| {
            time_per_mu(speeds.len(), min_time, || {
                values = auto_scene
                    .friction_auto(
                        &speeds,
                        accuracy,
                        exact_for_auto.as_ref().map_err(Clone::clone),
                    )
                    .map_err(|e| anyhow!("{e}"))?
                    .mu;
                Ok(())
            })
        })?;
        let (max_error, rms_error) = errors(&values, &reference);
        rows.push(ForwardRow {
            rung: "auto",
            setting: format!("ε = {accuracy:.0e}"),
            time_per_mu: time,
            max_error,
            rms_error,
            numerical_error: f64::NAN,
        });
    }
    Ok(Forward {
        rows,
        reference: reference_name,
        speeds,
    })
}

/// Chebyshev terms of the exact reference.
const REFERENCE_TERMS: usize = 160;

/// At most `count` of `speeds`, evenly spread over the list (ends kept).
fn thin(speeds: &[f64], count: usize) -> Vec<f64> {
    if speeds.len() <= count || count < 2 {
        return speeds.to_vec();
    }
    (0..count)
        .map(|i| speeds[i * (speeds.len() - 1) / (count - 1)])
        .collect()
}

/// μ of the exact solution at every speed (in parallel).
fn exact_sweep(cylinder: &RollingCylinder, speeds: &[f64]) -> Result<Vec<f64>> {
    use rayon::prelude::*;
    speeds
        .par_iter()
        .map(|&v| cylinder.solve(v).map(|s| s.mu))
        .collect::<Result<Vec<f64>, _>>()
        .map_err(|e| anyhow!("exact reference: {e}"))
}

fn fit_rows(scene_path: &Path, data_path: &Path, budgets: &[usize]) -> Result<Vec<FitRow>> {
    let context = || format!("scene file {}", scene_path.display());
    let file = scene_file::load(scene_path)?;
    let base = scene_path.parent().unwrap_or(Path::new(""));
    let truth = file
        .material
        .as_ref()
        .context("the fitting chart needs the truth in the scene's [material]")
        .with_context(context)?
        .build(base)
        .with_context(context)?;
    let (setup, params) = file.fit_setup().with_context(context)?;
    let data = data_file::read(data_path)?
        .measurements()
        .with_context(|| format!("data file {}", data_path.display()))?;
    let fit = |method: Method, lambda: Lambda, starts: usize, budget: Option<usize>| {
        let mut p = params.clone();
        p.method = method;
        p.lambda = lambda;
        p.starts = starts;
        p.max_evaluations = budget;
        let valid = p.check(setup).map_err(|e| anyhow!("{e}"))?;
        rollfit_fit::fit(&data, &valid).map_err(|e| anyhow!("{e}"))
    };
    // λ of the default fit, so that every method minimises the same V.
    let default = fit(params.method, params.lambda, params.starts, None)?;
    let lambda = Lambda::Fixed(default.lambda.value);

    let mut rows: Vec<FitRow> = Vec::new();
    for method in [
        Method::LevenbergMarquardt,
        Method::Lbfgs,
        Method::NelderMead,
    ] {
        for &budget in budgets {
            // A run that ended before its budget gives the same fit with
            // any larger one.
            if rows
                .last()
                .is_some_and(|r| r.method == method.name() && r.evaluations < r.budget)
            {
                continue;
            }
            let started = Instant::now();
            let report = fit(method, lambda, 1, Some(budget))?;
            let wall_time = started.elapsed().as_secs_f64();
            let model = Prony::new(
                report.model.glassy_modulus,
                report.model.strengths.clone(),
                report.model.tau.clone(),
            )
            .map_err(|e| anyhow!("{e}"))?;
            rows.push(FitRow {
                method: method.name(),
                budget,
                wall_time,
                evaluations: report.evaluations,
                tan_delta_rms: tan_delta_error(&model, truth.as_ref(), report.window),
                converged: report.converged,
            });
        }
    }
    Ok(rows)
}

/// RMS relative error of tan δ over the window shrunk by half a decade at
/// each end (where the data fix the curve), 100 log-spaced frequencies.
fn tan_delta_error(
    fit: &Prony,
    truth: &dyn ViscoelasticModulus,
    window: rollfit_fit::report::Window,
) -> f64 {
    let (lo, hi) = (
        window.omega_min.log10() + 0.5,
        window.omega_max.log10() - 0.5,
    );
    let n = 100;
    let sum: f64 = (0..n)
        .map(|i| {
            let omega = 10f64.powf(lo + (hi - lo) * i as f64 / (n - 1) as f64);
            let (f, t) = (fit.modulus(omega), truth.modulus(omega));
            let (tf, tt) = (f.im / f.re, t.im / t.re);
            ((tf - tt) / tt).powi(2)
        })
        .sum();
    (sum / n as f64).sqrt()
}
