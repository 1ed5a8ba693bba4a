//! Picture 5, for a temperature set (a fit with a shift): the master
//! friction curve, μ against the reduced speed v·a_T with every
//! temperature's points in its own colour on the one fitted curve, and the
//! shift itself, log10 a_T against T with ±1σ bars (hollow where the data
//! do not determine it) and the law's curve when the shift is WLF or
//! Arrhenius. (μ(v) per temperature with the fitted curves is picture 1, which
//! colours a set by temperature.)

use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::{lg, linear_range, log_axis, log_range};
use super::friction::temperature_label;
use super::{DrawResult, Figure, draw_legend, draw_mesh, draw_shift_mesh, format_tick, style};
use crate::fitted_friction::temperature_groups;
use rollfit_io::fit_dir::FitDir;

/// μ against v·a_T.
pub struct MasterFrictionFigure<'a> {
    /// The fit (with a shift).
    pub fit: &'a FitDir,
}

/// log10 a_T against T.
pub struct ShiftFigure<'a> {
    /// The fit (with a shift).
    pub fit: &'a FitDir,
}

impl Figure for MasterFrictionFigure<'_> {
    fn name(&self) -> &'static str {
        "master_friction"
    }

    fn caption(&self) -> String {
        let t_ref = self
            .fit
            .summary
            .shift
            .as_ref()
            .map_or(f64::NAN, |s| s.t_ref);
        format!(
            "Master friction curve at T_ref = {} °C: every temperature's μ against the reduced speed v·a_T (points) and the joint fit (line).",
            format_tick(t_ref)
        )
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let rows = &self.fit.friction;
        let reduced = |r: &rollfit_io::fit_dir::FrictionRow| r.reduced_speed.unwrap_or(r.speed);
        let x_range = log_range(rows.iter().map(reduced), 0.2, -8.0..0.0);
        let y_range = log_range(
            rows.iter().flat_map(|r| [r.mu_measured, r.mu_fit]),
            0.1,
            -3.0..0.0,
        );
        let mut chart = ChartBuilder::on(root)
            .margin(12)
            .caption(
                "Master friction curve μ(v·a_T)",
                ("sans-serif", style::CAPTION),
            )
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(log_axis(x_range), log_axis(y_range))?;
        draw_mesh(&mut chart, "v·a_T (m/s)", "μ", true)?;
        for (i, (t, members)) in temperature_groups(rows).iter().enumerate() {
            let c = style::SERIES[i % style::SERIES.len()];
            chart
                .draw_series(members.iter().filter_map(|r| {
                    lg(r.mu_measured).map(|y| Circle::new((reduced(r).log10(), y), 3, c.filled()))
                }))?
                .label(temperature_label(*t, "measured"))
                .legend(move |(x, y)| Circle::new((x + 10, y), 4, c.filled()));
        }
        let mut fitted: Vec<(f64, f64)> = rows
            .iter()
            .filter_map(|r| Some((lg(reduced(r))?, lg(r.mu_fit)?)))
            .collect();
        fitted.sort_by(|a, b| a.0.total_cmp(&b.0));
        chart
            .draw_series(LineSeries::new(fitted, BLACK.stroke_width(2)))?
            .label("joint fit")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
        draw_legend(&mut chart, SeriesLabelPosition::UpperLeft)?;
        Ok(())
    }
}

impl Figure for ShiftFigure<'_> {
    fn name(&self) -> &'static str {
        "shift"
    }

    fn caption(&self) -> String {
        match &self.fit.summary.shift {
            Some(s) => match (s.c1, s.c2) {
                (Some(c1), Some(c2)) => format!(
                    "Shift factors log10 a_T (points, ±1σ) and the fitted WLF curve: C1 = {c1:.4}, C2 = {c2:.2} K at T_ref = {} °C.",
                    format_tick(s.t_ref)
                ),
                _ => match (s.model.as_str(), s.activation_energy) {
                    ("arrhenius", Some(energy)) => format!(
                        "Shift factors log10 a_T (points, ±1σ) and the fitted Arrhenius curve: E_a = {energy:.4e} J/mol at T_ref = {} °C.",
                        format_tick(s.t_ref)
                    ),
                    _ => format!(
                        "Free shift factors log10 a_T (points, ±1σ; hollow: not determined by the data), T_ref = {} °C.",
                        format_tick(s.t_ref)
                    ),
                },
            },
            None => "No shift: not a temperature set.".into(),
        }
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let Some(shift) = &self.fit.summary.shift else {
            return Ok(());
        };
        let points = &shift.log_shift;
        let x_range = linear_range(points.iter().map(|p| p.temperature), 0.08);
        let law = match shift.model.as_str() {
            "wlf" => Some("WLF fit"),
            "arrhenius" => Some("Arrhenius fit"),
            _ => None,
        };
        let wlf_curve: Vec<(f64, f64)> = match law {
            Some(_) => (0..=200)
                .filter_map(|i| {
                    let t = x_range.start + (x_range.end - x_range.start) * f64::from(i) / 200.0;
                    shift.log_shift_at(t).map(|l| (t, l))
                })
                .collect(),
            _ => Vec::new(),
        };
        let y_range = linear_range(
            points
                .iter()
                .flat_map(|p| {
                    [
                        p.log_shift - p.log_shift_sigma,
                        p.log_shift + p.log_shift_sigma,
                    ]
                })
                .chain(wlf_curve.iter().map(|p| p.1)),
            0.08,
        );
        let mut chart = ChartBuilder::on(root)
            .margin(12)
            .caption("Time–temperature shift", ("sans-serif", style::CAPTION))
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(x_range, y_range)?;
        draw_shift_mesh(&mut chart, None)?;
        if !wlf_curve.is_empty() {
            chart
                .draw_series(LineSeries::new(wlf_curve, style::WLF.stroke_width(2)))?
                .label(law.unwrap_or("law"))
                .legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], style::WLF.stroke_width(2))
                });
        }
        for p in points.iter().filter(|p| p.log_shift_sigma > 0.0) {
            chart.draw_series(std::iter::once(ErrorBar::new_vertical(
                p.temperature,
                p.log_shift - p.log_shift_sigma,
                p.log_shift,
                p.log_shift + p.log_shift_sigma,
                BLACK.stroke_width(1),
                8,
            )))?;
        }
        let determined = |p: &&rollfit_io::fit_dir::LogShiftSummary| p.log_shift_sigma.is_finite();
        chart
            .draw_series(
                points.iter().filter(determined).map(|p| {
                    Circle::new((p.temperature, p.log_shift), 5, style::MEASURED.filled())
                }),
            )?
            .label("joint fit, per temperature")
            .legend(|(x, y)| Circle::new((x + 10, y), 5, style::MEASURED.filled()));
        if points.iter().any(|p| !p.log_shift_sigma.is_finite()) {
            chart
                .draw_series(
                    points
                        .iter()
                        .filter(|p| !p.log_shift_sigma.is_finite())
                        .map(|p| {
                            Circle::new(
                                (p.temperature, p.log_shift),
                                5,
                                style::MEASURED.stroke_width(2),
                            )
                        }),
                )?
                .label("not determined by the data")
                .legend(|(x, y)| Circle::new((x + 10, y), 5, style::MEASURED.stroke_width(2)));
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight)?;
        Ok(())
    }
}
