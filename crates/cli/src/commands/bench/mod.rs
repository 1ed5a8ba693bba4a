//! `rollfit bench [-o DIR]`: the speed–accuracy chart.
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

mod fit;
mod forward;

use std::path::PathBuf;

use anyhow::{Context, Result};
use rollfit_io::{csv_text, output};
use rollfit_report::plot::speed_accuracy::{CostPoint, SpeedAccuracyFigure};
use rollfit_report::plot::{Picture, SeriesLabelPosition, render};

use fit::fit_rows;
use forward::{Forward, forward_rows};

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
    let forward_chart = forward_chart(args, &forward)?;
    let fit_chart = fit_chart(args, &fits)?;

    let dir = &args.output;
    output::write_atomically(&dir.join("forward.csv"), forward_csv(&forward).as_bytes())?;
    output::write_atomically(&dir.join("fit.csv"), fit_csv(&fits).as_bytes())?;
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

/// Error of μ against time per μ, one series per rung, plus the dynamic
/// rung against itself computed tightly: the tolerance dial of the
/// paper's model seen apart from its model error.
fn forward_chart(args: &Args, forward: &Forward) -> Result<Picture> {
    let mut points: Vec<CostPoint> = forward
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
    points.extend(
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
    Ok(render(&SpeedAccuracyFigure {
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
        points: &points,
        legend: SeriesLabelPosition::LowerLeft,
    })?)
}

/// tan δ error against wall time, one series per method.
fn fit_chart(args: &Args, fits: &[FitRow]) -> Result<Picture> {
    let points: Vec<CostPoint> = fits
        .iter()
        .map(|r| CostPoint {
            series: r.method.to_string(),
            setting: r.budget.to_string(),
            cost: r.wall_time,
            error: r.tan_delta_rms,
            ok: r.converged,
        })
        .collect();
    Ok(render(&SpeedAccuracyFigure {
        name: "fit",
        title: "Fitting: tan δ error against wall time".into(),
        caption: format!(
            "RMS relative error of the recovered tan δ against the truth of {} over its window, against the fit's wall time, for each method from the same start at the same λ and each evaluation budget (labels); hollow: the run did not converge.",
            args.fit_data.display()
        ),
        cost_description: "wall time of the fit (s)",
        error_description: "RMS relative error of tan δ",
        points: &points,
        legend: SeriesLabelPosition::UpperRight,
    })?)
}

/// forward.csv: a comment line saying what the errors are against, then
/// one row per rung and setting.
fn forward_csv(forward: &Forward) -> String {
    let mut text = format!(
        "# errors against {}; {} speeds {:e} … {:e} m/s; times on this machine\n\
         rung,setting,time_per_mu_s,max_rel_error,rms_rel_error,numerical_rel_error\n",
        forward.reference,
        forward.speeds.len(),
        forward.speeds[0],
        forward.speeds[forward.speeds.len() - 1]
    );
    for r in &forward.rows {
        text.push_str(&format!(
            "{},{},{},{},{},{}\n",
            r.rung,
            r.setting,
            csv_text::number(r.time_per_mu),
            csv_text::number(r.max_error),
            csv_text::number(r.rms_error),
            csv_text::number(r.numerical_error)
        ));
    }
    text
}

/// fit.csv: one row per method and budget.
fn fit_csv(fits: &[FitRow]) -> String {
    let mut text = String::from(
        "method,max_evaluations,wall_time_s,evaluations,tan_delta_rms_rel,converged\n",
    );
    for r in fits {
        text.push_str(&format!(
            "{},{},{},{},{},{}\n",
            r.method,
            r.budget,
            csv_text::number(r.wall_time),
            r.evaluations,
            csv_text::number(r.tan_delta_rms),
            r.converged
        ));
    }
    text
}
