//! Picture 1: the measured μ(v) (error bars where σ is known) with the
//! fitted curve on log–log axes, and below it the relative residuals in
//! percent, 100 (μ_fit − μ_meas)/μ_meas — the `residual` column of mu.csv
//! (README, "Fit results") — with error bars ±100 σ/μ_meas where σ is
//! known. A temperature set gets one colour per temperature.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::{self, lg, log_axis, log_range};
use super::{DrawResult, Figure, draw_legend, draw_mesh, style};
use rollfit_io::fit_dir::{FitDir, FrictionRow};

/// μ(v) with residuals.
pub struct FrictionFigure<'a> {
    /// The fit.
    pub fit: &'a FitDir,
}

/// Rows of mu.csv grouped by temperature (one group without a T column),
/// in the file's order of first appearance, each sorted by speed.
pub(crate) fn temperature_groups(rows: &[FrictionRow]) -> Vec<(Option<f64>, Vec<FrictionRow>)> {
    let mut groups: Vec<(Option<f64>, Vec<FrictionRow>)> = Vec::new();
    for row in rows {
        match groups.iter_mut().find(|(t, _)| *t == row.temperature) {
            Some((_, members)) => members.push(*row),
            None => groups.push((row.temperature, vec![*row])),
        }
    }
    for (_, members) in &mut groups {
        members.sort_by(|a, b| a.speed.total_cmp(&b.speed));
    }
    groups
}

/// "T = 20 °C", or the given label without a temperature.
pub(crate) fn temperature_label(t: Option<f64>, otherwise: &str) -> String {
    match t {
        Some(t) => format!("T = {} °C", super::format_tick(t)),
        None => otherwise.to_string(),
    }
}

impl Figure for FrictionFigure<'_> {
    fn name(&self) -> &'static str {
        "friction"
    }

    fn caption(&self) -> String {
        if self.fit.is_temperature_set() {
            "Measured μ(v) per temperature (points) and the joint fit (lines); relative residuals (μ_fit − μ_meas)/μ_meas below.".into()
        } else {
            "Measured μ(v) (points, ±1σ bars where σ is known) and the fit (line); relative residuals (μ_fit − μ_meas)/μ_meas below.".into()
        }
    }

    fn size(&self) -> (u32, u32) {
        (900, 760)
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let rows = &self.fit.friction;
        let groups = temperature_groups(rows);
        let several = groups.len() > 1;
        let colour = |i: usize| {
            if several {
                style::SERIES[i % style::SERIES.len()]
            } else {
                style::MEASURED
            }
        };

        let x_range = log_range(rows.iter().map(|r| r.speed), 0.2, -6.0..0.0);
        let y_range = log_range(
            rows.iter().flat_map(|r| {
                [
                    r.mu_measured,
                    r.mu_fit,
                    r.mu_measured - r.sigma.unwrap_or(0.0),
                ]
            }),
            0.1,
            -3.0..0.0,
        );
        let (upper, lower) = root.split_vertically(530);

        let mut chart = ChartBuilder::on(&upper)
            .margin(12)
            .caption("Rolling friction μ(v)", ("sans-serif", style::CAPTION))
            .x_label_area_size(40)
            .y_label_area_size(75)
            .build_cartesian_2d(log_axis(x_range.clone()), log_axis(y_range.clone()))?;
        draw_mesh(&mut chart, "v (m/s)", "μ", true)?;

        for (i, (t, members)) in groups.iter().enumerate() {
            let c = colour(i);
            for r in members {
                if let (Some(s), Some(y)) = (r.sigma, lg(r.mu_measured)) {
                    let x = r.speed.log10();
                    let lo = lg(r.mu_measured - s).unwrap_or(y_range.start);
                    let hi = lg(r.mu_measured + s).unwrap_or(y);
                    chart.draw_series(std::iter::once(PathElement::new(
                        vec![(x, lo.max(y_range.start)), (x, hi)],
                        c.stroke_width(1),
                    )))?;
                }
            }
            let label = temperature_label(*t, "measured");
            chart
                .draw_series(members.iter().filter_map(|r| {
                    lg(r.mu_measured)
                        .map(|y| Circle::new((r.speed.log10(), y), 3, c.stroke_width(1)))
                }))?
                .label(label)
                .legend(move |(x, y)| Circle::new((x + 10, y), 4, c.stroke_width(1)));
            let line = if several { c } else { style::FITTED };
            let series = chart.draw_series(LineSeries::new(
                members
                    .iter()
                    .filter_map(|r| lg(r.mu_fit).map(|y| (r.speed.log10(), y))),
                line.stroke_width(2),
            ))?;
            if !several {
                series.label("fit").legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], line.stroke_width(2))
                });
            }
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperLeft)?;

        // The convention of mu.csv's `residual` column, in percent.
        let residual = |r: &FrictionRow| 100.0 * (r.mu_fit - r.mu_measured) / r.mu_measured;
        let bar = |r: &FrictionRow| r.sigma.map_or(0.0, |s| 100.0 * s / r.mu_measured);
        let y_residual = axes::linear_range(
            rows.iter()
                .flat_map(|r| [residual(r) - bar(r), residual(r) + bar(r)]),
            0.08,
        );
        let mut chart = ChartBuilder::on(&lower)
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(log_axis(x_range.clone()), y_residual)?;
        draw_mesh(&mut chart, "v (m/s)", "(μ_fit − μ_meas)/μ_meas (%)", false)?;
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(x_range.start, 0.0), (x_range.end, 0.0)],
            BLACK.stroke_width(1),
        )))?;
        for (i, (_, members)) in groups.iter().enumerate() {
            let c = colour(i);
            for r in members.iter().filter(|r| r.sigma.is_some()) {
                let (x, y, b) = (r.speed.log10(), residual(r), bar(r));
                chart.draw_series(std::iter::once(PathElement::new(
                    vec![(x, y - b), (x, y + b)],
                    c.stroke_width(1),
                )))?;
            }
            chart.draw_series(
                members
                    .iter()
                    .map(|r| Circle::new((r.speed.log10(), residual(r)), 3, c.filled())),
            )?;
        }
        Ok(())
    }
}
