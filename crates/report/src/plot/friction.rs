//! Picture 1: the measured μ(v) (error bars where σ is known) with the
//! fitted curve on log–log axes, and below it the relative residuals in
//! percent, 100 (μ_fit − μ_meas)/μ_meas — the `residual` column of mu.csv
//! (docs/user-guide.md, "Reports and DMA comparison") — with error bars ±100 σ/μ_meas where σ is
//! known. A temperature set gets one colour per temperature.
//!
//! The fitted curve is the model's μ(v) on a dense grid of speeds
//! ([`crate::fitted_friction`]) when the fit's scene could be read, else
//! mu.csv's fitted values at the measured speeds joined by straight lines
//! (the caption says which, and why). The title carries the fit's verdict,
//! so that the picture copied alone still says whether the fit describes
//! its data.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::{self, lg, log_axis, log_range};
use super::{DrawResult, Figure, draw_legend, draw_mesh, style};
use crate::fitted_friction::{DENSE_POINTS, FittedLine, temperature_groups};
use rollfit_io::fit_dir::{FitDir, FitSummary, FrictionRow};

/// μ(v) with residuals.
pub struct FrictionFigure<'a> {
    /// The fit.
    pub fit: &'a FitDir,
    /// The fitted line to draw.
    pub line: &'a FittedLine,
}

/// One temperature's fitted line as (log10 v, log10 μ) points.
pub type FittedSeries = (Option<f64>, Vec<(f64, f64)>);

/// "T = 20 °C", or the given label without a temperature.
pub(crate) fn temperature_label(t: Option<f64>, otherwise: &str) -> String {
    match t {
        Some(t) => format!("T = {} °C", super::format_tick(t)),
        None => otherwise.to_string(),
    }
}

/// "verdict: good" (or poor, invalid), or "no verdict" when fit.json has
/// no `fit_quality`: the words the picture's title adds.
pub fn verdict_phrase(summary: &FitSummary) -> String {
    match &summary.fit_quality {
        Some(q) => format!("verdict: {}", q.verdict),
        None => "no verdict in fit.json".into(),
    }
}

impl FrictionFigure<'_> {
    /// The fitted lines the picture draws, one per temperature in the
    /// order of [`temperature_groups`]: the dense curve where there is one
    /// for that temperature, else mu.csv's fitted μ at the measured speeds.
    pub fn fitted_series(&self) -> Vec<FittedSeries> {
        let points = |speeds: &mut dyn Iterator<Item = (f64, f64)>| -> Vec<(f64, f64)> {
            speeds
                .filter_map(|(v, mu)| Some((lg(v)?, lg(mu)?)))
                .collect()
        };
        temperature_groups(&self.fit.friction)
            .into_iter()
            .map(|(t, members)| {
                let dense = match self.line {
                    FittedLine::Dense(curves) => curves.iter().find(|c| c.temperature == t),
                    FittedLine::AtData { .. } => None,
                };
                let line = match dense {
                    Some(c) => {
                        points(&mut c.speeds.iter().copied().zip(c.friction.iter().copied()))
                    }
                    None => points(&mut members.iter().map(|r| (r.speed, r.mu_fit))),
                };
                (t, line)
            })
            .collect()
    }
}

impl Figure for FrictionFigure<'_> {
    fn name(&self) -> &'static str {
        "friction"
    }

    fn caption(&self) -> String {
        let line = match self.line {
            FittedLine::Dense(_) => {
                format!("the model's μ(v) on {DENSE_POINTS} speeds through the measured range")
            }
            FittedLine::AtData { why } => format!(
                "the fit's μ at the measured speeds joined by straight lines, for want of a dense \
                 curve: {why}"
            ),
        };
        let (points, lines) = if self.fit.is_temperature_set() {
            (
                "Measured μ(v) per temperature (points)",
                "the joint fit (lines)",
            )
        } else {
            (
                "Measured μ(v) (points, ±1σ bars where σ is known)",
                "the fit (line)",
            )
        };
        let kappa = match self
            .fit
            .summary
            .joint
            .as_ref()
            .and_then(|j| j.friction_factor.as_ref())
        {
            Some(k) => format!(
                "; the fit is κ times the model's μ, κ = {:.4} ± {:.4} fitted jointly with DMA data",
                k.value, k.sigma
            ),
            None => String::new(),
        };
        format!(
            "{points} and {lines}, {}; relative residuals (μ_fit − μ_meas)/μ_meas at the data below; {line}{kappa}.",
            verdict_phrase(&self.fit.summary)
        )
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
        let fitted = self.fitted_series();
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
            rows.iter()
                .flat_map(|r| {
                    [
                        r.mu_measured,
                        r.mu_fit,
                        r.mu_measured - r.sigma.unwrap_or(0.0),
                    ]
                })
                .chain(
                    fitted
                        .iter()
                        .flat_map(|(_, line)| line.iter().map(|p| 10f64.powf(p.1))),
                ),
            0.1,
            -3.0..0.0,
        );
        let (upper, lower) = root.split_vertically(530);

        let title = format!(
            "Rolling friction μ(v) — {}",
            verdict_phrase(&self.fit.summary)
        );
        let mut chart = ChartBuilder::on(&upper)
            .margin(12)
            .caption(title, ("sans-serif", style::CAPTION))
            .x_label_area_size(40)
            .y_label_area_size(75)
            .build_cartesian_2d(log_axis(x_range.clone()), log_axis(y_range.clone()))?;
        draw_mesh(&mut chart, "v (m/s)", "μ", true)?;

        for (i, ((t, members), (_, line))) in groups.iter().zip(&fitted).enumerate() {
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
            let line_colour = if several { c } else { style::FITTED };
            let series = chart.draw_series(LineSeries::new(
                line.iter().copied(),
                line_colour.stroke_width(2),
            ))?;
            if !several {
                series.label("fit").legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], line_colour.stroke_width(2))
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
