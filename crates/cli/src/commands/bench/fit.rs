//! The fitting chart of `rollfit bench`: each method from the same start at
//! the same λ with a dial of evaluation budgets, the recovered tan δ
//! against the truth (see the parent module).

use std::path::Path;
use std::time::Instant;

use anyhow::{Context, Result, anyhow};
use rollfit_fit::{Lambda, Method};
use rollfit_model::{Prony, ViscoelasticModulus};

use super::FitRow;
use rollfit_io::data::read as read_data;

use rollfit_io::scene as scene_file;

pub(super) fn fit_rows(
    scene_path: &Path,
    data_path: &Path,
    budgets: &[usize],
) -> Result<Vec<FitRow>> {
    let context = || format!("scene file {}", scene_path.display());
    let file = scene_file::load(scene_path)?;
    let base = scene_path.parent().unwrap_or(Path::new(""));
    let truth = file
        .material
        .as_ref()
        .context("the fitting chart needs the truth in the scene's [material]")
        .with_context(context)?
        .build(base, &|note| eprintln!("note: {note}"))
        .with_context(context)?;
    let (setup, params) = file.fit_setup().with_context(context)?;
    let data = read_data(data_path)?
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
