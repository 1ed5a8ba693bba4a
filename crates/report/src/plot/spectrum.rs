//! Picture 3: the relaxation spectrum, H_k against τ_k (log–log). Terms
//! the data determine are filled, with their 1σ from the curvature of V
//! (H_k·e^{±σ(ln H_k)}); the others are hollow grey: they only extend E*
//! outside the window and are not results. The τ range 1/ω_max … 1/ω_min
//! that the window corresponds to is shaded.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::{lg, log_axis, log_range};
use super::{DrawResult, Figure, draw_legend, draw_mesh, style};
use rollfit_io::fit_dir::FitDir;

/// H_k against τ_k.
pub struct SpectrumFigure<'a> {
    /// The fit.
    pub fit: &'a FitDir,
}

impl SpectrumFigure<'_> {
    fn determined(&self, k: usize) -> bool {
        self.fit
            .summary
            .model
            .determined
            .get(k)
            .copied()
            .unwrap_or(true)
    }
}

impl Figure for SpectrumFigure<'_> {
    fn name(&self) -> &'static str {
        "spectrum"
    }

    fn caption(&self) -> String {
        let model = &self.fit.summary.model;
        let undetermined = (0..model.tau.len())
            .filter(|&k| !self.determined(k))
            .count();
        format!(
            "Relaxation spectrum: {} terms H_k at τ_k, {} of them not determined by the data (hollow, grey); bars are ±1σ; the shaded τ range corresponds to the window.",
            model.tau.len(),
            undetermined
        )
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let model = &self.fit.summary.model;
        let sigma = |k: usize| {
            model
                .ln_strength_sigma
                .get(k)
                .copied()
                .filter(|s| s.is_finite())
        };
        let w = self.fit.summary.window;
        let x_range = log_range(
            model
                .tau
                .iter()
                .copied()
                .chain([1.0 / w.omega_max, 1.0 / w.omega_min]),
            0.3,
            -6.0..0.0,
        );
        let y_range = log_range(
            model.strengths.iter().enumerate().flat_map(|(k, &h)| {
                let s = sigma(k)
                    .filter(|_| self.determined(k))
                    .unwrap_or(0.0)
                    .min(3.0);
                [h * (-s).exp(), h * s.exp()]
            }),
            0.2,
            4.0..9.0,
        );
        let mut chart = ChartBuilder::on(root)
            .margin(12)
            .caption("Relaxation spectrum", ("sans-serif", style::CAPTION))
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(log_axis(x_range.clone()), log_axis(y_range.clone()))?;
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [
                    (-w.omega_max.log10(), y_range.start),
                    (-w.omega_min.log10(), y_range.end),
                ],
                style::WINDOW.filled(),
            )))?
            .label("τ range of the window, 1/ω")
            .legend(|(x, y)| Rectangle::new([(x, y - 6), (x + 20, y + 6)], style::WINDOW.filled()));
        draw_mesh(&mut chart, "τ_k (s)", "H_k (Pa)", true)?;

        let points: Vec<(usize, f64, f64)> = model
            .tau
            .iter()
            .zip(&model.strengths)
            .enumerate()
            .filter_map(|(k, (&t, &h))| Some((k, lg(t)?, lg(h)?)))
            .collect();
        for &(k, x, y) in points.iter().filter(|p| self.determined(p.0)) {
            if let Some(s) = sigma(k) {
                let half = s / std::f64::consts::LN_10;
                chart.draw_series(std::iter::once(PathElement::new(
                    vec![
                        (x, (y - half).max(y_range.start)),
                        (x, (y + half).min(y_range.end)),
                    ],
                    style::STORAGE.stroke_width(1),
                )))?;
            }
        }
        chart.draw_series(LineSeries::new(
            points.iter().map(|p| (p.1, p.2)),
            RGBColor(190, 190, 190).stroke_width(1),
        ))?;
        chart
            .draw_series(
                points
                    .iter()
                    .filter(|p| self.determined(p.0))
                    .map(|p| Circle::new((p.1, p.2), 5, style::STORAGE.filled())),
            )?
            .label("determined by the data")
            .legend(|(x, y)| Circle::new((x + 10, y), 5, style::STORAGE.filled()));
        if points.iter().any(|p| !self.determined(p.0)) {
            chart
                .draw_series(
                    points
                        .iter()
                        .filter(|p| !self.determined(p.0))
                        .map(|p| Circle::new((p.1, p.2), 5, style::UNDETERMINED.stroke_width(2))),
                )?
                .label("not determined (extrapolation only)")
                .legend(|(x, y)| Circle::new((x + 10, y), 5, style::UNDETERMINED.stroke_width(2)));
        }
        draw_legend(&mut chart, SeriesLabelPosition::LowerLeft)?;
        Ok(())
    }
}
