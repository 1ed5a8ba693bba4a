//! Picture 4: convergence. The best objective V found so far against the
//! number of objective evaluations, for every solver run of the fit (the λ
//! path, the refinement and each start), coloured by method. Runs at
//! different λ minimise different V, so their levels differ; what the
//! picture shows is how fast each run settles and which ones stalled.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::{lg, log_axis, log_range};
use super::{DrawResult, Figure, draw_legend, style};
use rollfit_io::fit_dir::{FitDir, RunSummary};

/// V against evaluations per run.
pub struct ConvergenceFigure<'a> {
    /// The fit.
    pub fit: &'a FitDir,
}

impl ConvergenceFigure<'_> {
    /// The runs with a history; a fit.json without per-run histories gives
    /// its final run's.
    fn runs(&self) -> Vec<RunSummary> {
        let summary = &self.fit.summary;
        let with_history: Vec<RunSummary> = summary
            .runs
            .iter()
            .filter(|r| !r.history.is_empty())
            .cloned()
            .collect();
        if !with_history.is_empty() || summary.history.is_empty() {
            return with_history;
        }
        vec![RunSummary {
            stage: "final run".into(),
            method: summary.method.clone(),
            objective: summary.objective,
            evaluations: summary.history.last().map_or(0, |p| p[0] as usize),
            converged: summary.converged,
            history: summary.history.clone(),
        }]
    }

    fn methods(&self) -> Vec<String> {
        let mut methods: Vec<String> = Vec::new();
        for r in self.runs() {
            if !methods.contains(&r.method) {
                methods.push(r.method);
            }
        }
        methods
    }
}

impl Figure for ConvergenceFigure<'_> {
    fn name(&self) -> &'static str {
        "convergence"
    }

    fn caption(&self) -> String {
        let runs = self.runs();
        format!(
            "Convergence: best objective V against evaluations for {} solver run{} ({}); the dashed line is the final V = {:.6e}.",
            runs.len(),
            if runs.len() == 1 { "" } else { "s" },
            self.methods().join(", "),
            self.fit.summary.objective
        )
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let runs = self.runs();
        let methods = self.methods();
        let max_evaluations = runs
            .iter()
            .flat_map(|r| r.history.iter().map(|p| p[0]))
            .fold(1.0f64, f64::max);
        let y_range = log_range(
            runs.iter()
                .flat_map(|r| r.history.iter().map(|p| p[1]))
                .chain([self.fit.summary.objective]),
            0.2,
            0.0..3.0,
        );
        let mut chart = ChartBuilder::on(root)
            .margin(12)
            .caption(
                "Convergence of the solver runs",
                ("sans-serif", style::CAPTION),
            )
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(0.0..max_evaluations * 1.03, log_axis(y_range.clone()))?;
        let log_label = |v: &f64| super::axes::decade_label(v);
        let plain_label = |v: &f64| super::format_tick(*v);
        chart
            .configure_mesh()
            .x_desc("objective evaluations")
            .y_desc("best V so far")
            .x_label_formatter(&plain_label)
            .y_label_formatter(&log_label)
            .label_style(("sans-serif", style::TICK_LABEL))
            .axis_desc_style(("sans-serif", style::AXIS_DESCRIPTION))
            .bold_line_style(RGBColor(200, 200, 200))
            .light_line_style(RGBColor(236, 236, 236))
            .x_max_light_lines(0)
            .draw()?;

        for (m, method) in methods.iter().enumerate() {
            let colour = style::SERIES[m % style::SERIES.len()];
            let members: Vec<&RunSummary> = runs.iter().filter(|r| &r.method == method).collect();
            for (i, run) in members.iter().enumerate() {
                // Staircase: V holds between improvements.
                let mut steps = Vec::new();
                for pair in run.history.windows(2) {
                    if let (Some(a), Some(b)) = (lg(pair[0][1]), lg(pair[1][1])) {
                        steps.push((pair[0][0], a));
                        steps.push((pair[1][0], a));
                        steps.push((pair[1][0], b));
                    }
                }
                if let [only] = run.history.as_slice()
                    && let Some(y) = lg(only[1])
                {
                    steps.push((only[0], y));
                }
                let series = chart.draw_series(LineSeries::new(steps, colour.stroke_width(2)))?;
                if i == 0 {
                    let label = format!(
                        "{method} ({} run{})",
                        members.len(),
                        if members.len() == 1 { "" } else { "s" }
                    );
                    series.label(label).legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                    });
                }
            }
        }
        if let Some(y) = lg(self.fit.summary.objective) {
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(0.0, y), (max_evaluations * 1.03, y)],
                    8,
                    5,
                    BLACK.stroke_width(1),
                ))?
                .label("final V")
                .legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(1))
                });
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight)?;
        Ok(())
    }
}
