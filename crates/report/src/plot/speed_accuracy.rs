//! The speed–accuracy chart of `rollfit bench`: error against cost, one
//! series per method or model rung, each point one setting (a quadrature
//! tolerance, an evaluation budget), both axes logarithmic. The lower left
//! is better; a series that turns up as it moves right has hit an error
//! its setting cannot remove (the model's own error, or a stalled solver).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::{lg, log_axis, log_range};
use super::{DrawResult, Figure, draw_legend, draw_mesh, style};

/// One measured setting.
#[derive(Debug, Clone, PartialEq)]
pub struct CostPoint {
    /// The series (method or rung) it belongs to.
    pub series: String,
    /// The setting, written next to the point ("1e-4", "1000").
    pub setting: String,
    /// Cost: seconds (per μ, or per fit).
    pub cost: f64,
    /// Error (relative); non-positive errors are drawn at the bottom edge.
    pub error: f64,
    /// Whether the run behind the point reached its goal (a converged fit);
    /// others are drawn hollow.
    pub ok: bool,
}

/// Error against cost.
pub struct SpeedAccuracyFigure<'a> {
    /// File stem.
    pub name: &'static str,
    /// Title drawn on the picture.
    pub title: String,
    /// Caption for the HTML page and README.
    pub caption: String,
    /// x axis description (with unit).
    pub cost_description: &'a str,
    /// y axis description.
    pub error_description: &'a str,
    /// The points, in series order.
    pub points: &'a [CostPoint],
    /// Where the legend goes (a corner the points leave free).
    pub legend: SeriesLabelPosition,
}

impl SpeedAccuracyFigure<'_> {
    fn series(&self) -> Vec<&str> {
        let mut names: Vec<&str> = Vec::new();
        for p in self.points {
            if !names.contains(&p.series.as_str()) {
                names.push(&p.series);
            }
        }
        names
    }
}

impl Figure for SpeedAccuracyFigure<'_> {
    fn name(&self) -> &'static str {
        self.name
    }

    fn caption(&self) -> String {
        self.caption.clone()
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let x_range = log_range(self.points.iter().map(|p| p.cost), 0.3, -6.0..0.0);
        let y_range = log_range(
            self.points.iter().map(|p| p.error).filter(|e| *e > 0.0),
            0.4,
            -8.0..0.0,
        );
        let mut chart = ChartBuilder::on(root)
            .margin(12)
            .caption(&self.title, ("sans-serif", style::CAPTION))
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(log_axis(x_range), log_axis(y_range.clone()))?;
        draw_mesh(
            &mut chart,
            self.cost_description,
            self.error_description,
            true,
        )?;
        for (i, name) in self.series().into_iter().enumerate() {
            let colour = style::SERIES[i % style::SERIES.len()];
            let mut members: Vec<(f64, f64, &CostPoint)> = self
                .points
                .iter()
                .filter(|p| p.series == name)
                .filter_map(|p| Some((lg(p.cost)?, lg(p.error).unwrap_or(y_range.start), p)))
                .collect();
            members.sort_by(|a, b| a.0.total_cmp(&b.0));
            chart.draw_series(LineSeries::new(
                members.iter().map(|m| (m.0, m.1)),
                colour.stroke_width(1),
            ))?;
            chart
                .draw_series(members.iter().map(|m| {
                    let style = if m.2.ok {
                        colour.filled()
                    } else {
                        colour.stroke_width(2)
                    };
                    Circle::new((m.0, m.1), 5, style)
                }))?
                .label(name)
                .legend(move |(x, y)| Circle::new((x + 10, y), 5, colour.filled()));
            // Labels alternate above and below their points, so neighbours
            // at nearly the same cost stay readable.
            chart.draw_series(members.iter().enumerate().map(|(k, m)| {
                EmptyElement::at((m.0, m.1))
                    + Text::new(
                        m.2.setting.clone(),
                        (7, if k % 2 == 0 { -16 } else { 5 }),
                        ("sans-serif", 12).into_font().color(&RGBColor(90, 90, 90)),
                    )
            }))?;
        }
        draw_legend(&mut chart, self.legend.clone())?;
        Ok(())
    }
}
