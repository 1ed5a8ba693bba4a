//! The residuals of a joint fit of DMA and rolling data, each
//! part in units of its own σ, so that where one part pulls against the
//! other shows as a run of points beyond ±2. Above, the DMA points'
//! ln(E_fit/E_meas)/σ_DMA for E′ (filled circles) and E″ (open triangles)
//! against the reduced frequency ω a_T, coloured by isotherm temperature as
//! in `joint_master`; below, the rolling rows' (μ_fit − μ_meas)/σ against
//! the reduced speed v·a_T, one colour per temperature as in `friction`.
//! These are the residuals fit.json's `joint.residual_ranges` averages
//! over decades (its rolling ranges are on the contact frequency v a_T/r,
//! which needs the scene's contact size; the reduced speed is what mu.csv
//! holds).
//!
//! σ of a rolling row is the joint fit's: the relative σ it estimated
//! (`joint.sigma.rolling`) times μ_meas, else the row's measured σ; a row
//! with neither is not drawn.

use std::ops::Range;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use super::axes::{LogAxis, lg, linear_range, log_axis, log_range};
use super::friction::temperature_label;
use super::isotherm_key::{celsius, isotherm_colour};
use super::parts::{
    ColouredPoint, dashed_key, draw_storage_loss, isotherms, legend_box, place_legend, plot_size,
};
use super::{DrawResult, Figure, draw_legend, draw_mesh, style};
use crate::fitted_friction::temperature_groups;
use rollfit_fit::JointRecord;
use rollfit_io::fit_dir::{FitDir, FrictionRow};

/// A residual beyond this many σ is a miss; the panels draw it as lines.
pub const MISS_SIGMA: f64 = 2.0;
/// Height of the DMA panel, px.
const UPPER_HEIGHT: u32 = 430;

/// DMA and rolling residuals in σ units.
pub struct JointResidualsFigure<'a> {
    /// The fit (mu.csv's rows).
    pub fit: &'a FitDir,
    /// fit.json's `joint`.
    pub joint: &'a JointRecord,
}

/// One temperature's rolling residuals: °C (None without a T column) and
/// (log10 v·a_T, residual in σ) of its rows.
pub type TemperatureResiduals = (Option<f64>, Vec<(f64, f64)>);

/// A residual panel's chart: log10 x against the residual in σ.
type ResidualChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<LogAxis, RangedCoordf64>>;

/// (log10 x, residual in σ, colour) of each point.
type Residuals = Vec<ColouredPoint>;

impl Figure for JointResidualsFigure<'_> {
    fn name(&self) -> &'static str {
        "joint_residuals"
    }

    fn caption(&self) -> String {
        format!(
            "Residuals of the joint fit in units of each part's σ: above, the DMA points' ln(E_fit/E_meas)/σ (σ = {:.3} % of E, {}) for E′ (filled) and E″ (open) against ω a_T, coloured by isotherm temperature; below, the rolling rows' (μ_fit − μ_meas)/σ against v·a_T, one colour per temperature. Dashed lines at ±{MISS_SIGMA}σ: a run beyond them is where the parts disagree.",
            100.0 * self.joint.sigma.dma,
            self.joint.sigma.dma_source,
        )
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let (upper, lower) = root.split_vertically(UPPER_HEIGHT);
        self.draw_dma(&upper)?;
        self.draw_rolling(&lower)
    }

    // Taller than the default: two panels of residuals, each with its own
    // caption and axes.
    fn size(&self) -> (u32, u32) {
        (900, 840)
    }
}

impl JointResidualsFigure<'_> {
    /// The isotherms' temperatures, °C, increasing, each once.
    fn isotherms(&self) -> Vec<f64> {
        isotherms(self.joint.dma.iter().map(|p| p.temperature))
    }

    /// ln(E′_fit/E′) / σ and ln(E″_fit/E″) / σ of every DMA point at its
    /// reduced frequency.
    pub fn dma_residuals(&self) -> (Residuals, Residuals) {
        let isotherms = self.isotherms();
        let coldest = isotherms.first().copied().unwrap_or(0.0);
        let warmest = isotherms.last().copied().unwrap_or(0.0);
        let sigma = self.joint.sigma.dma;
        let (mut storage, mut loss) = (Vec::new(), Vec::new());
        for p in &self.joint.dma {
            let Some(x) = lg(p.reduced_omega) else {
                continue;
            };
            let colour = isotherm_colour(p.temperature, coldest, warmest);
            let r1 = (p.storage_fit / p.storage).ln() / sigma;
            let r2 = (p.loss_fit / p.loss).ln() / sigma;
            if r1.is_finite() {
                storage.push((x, r1, colour));
            }
            if r2.is_finite() {
                loss.push((x, r2, colour));
            }
        }
        (storage, loss)
    }

    /// (μ_fit − μ_meas)/σ of the rolling rows at log10 v·a_T, per
    /// temperature in the order of [`temperature_groups`].
    pub fn rolling_residuals(&self) -> Vec<TemperatureResiduals> {
        let sigma = |r: &FrictionRow| {
            self.joint
                .sigma
                .rolling
                .map(|s| s * r.mu_measured)
                .or(r.sigma)
        };
        temperature_groups(&self.fit.friction)
            .into_iter()
            .map(|(t, rows)| {
                let points = rows
                    .iter()
                    .filter_map(|r| {
                        let x = lg(r.reduced_speed.unwrap_or(r.speed))?;
                        let residual = (r.mu_fit - r.mu_measured) / sigma(r)?;
                        residual.is_finite().then_some((x, residual))
                    })
                    .collect();
                (t, points)
            })
            .collect()
    }
}

/// What a residual panel shows besides its points.
struct Panel<'s> {
    title: &'s str,
    x_description: &'s str,
    y_description: &'s str,
    /// log10 of the x range.
    x_range: Range<f64>,
    /// The points, (log10 x, residual), for the legend's corner.
    points: Vec<(f64, f64)>,
    /// Legend entries besides ±2σ, and the longest one's characters.
    entries: usize,
    longest: usize,
}

/// The chart of a residual panel in the house style, with its mesh, the
/// zero line and the dashed ±2σ lines, its y range covering the residuals
/// and the lines and leaving room for the legend; and the legend's corner.
fn residual_chart<'a, DB>(
    area: &'a DrawingArea<DB, Shift>,
    panel: &Panel<'_>,
) -> Result<(ResidualChart<'a, DB>, SeriesLabelPosition), Box<dyn std::error::Error>>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    // The ±2σ lines always show, half a σ inside the axes.
    let lines = [-MISS_SIGMA - 0.5, MISS_SIGMA + 0.5];
    let y_range = linear_range(panel.points.iter().map(|p| p.1).chain(lines), 0.08);
    let samples: Vec<((f64, f64), usize)> = panel.points.iter().map(|&p| (p, 1)).collect();
    let box_size = legend_box(
        plot_size(area.dim_in_pixel(), 60, 45, true),
        1 + panel.entries,
        panel.longest,
    );
    let legend = place_legend(&samples, &panel.x_range, &y_range, box_size);
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .caption(panel.title, ("sans-serif", style::CAPTION))
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(log_axis(panel.x_range.clone()), legend.y)?;
    draw_mesh(&mut chart, panel.x_description, panel.y_description, false)?;
    let x = &panel.x_range;
    chart.draw_series(std::iter::once(PathElement::new(
        vec![(x.start, 0.0), (x.end, 0.0)],
        BLACK.stroke_width(1),
    )))?;
    let grey = style::UNDETERMINED;
    for (i, level) in [MISS_SIGMA, -MISS_SIGMA].into_iter().enumerate() {
        let series = chart.draw_series(DashedLineSeries::new(
            vec![(x.start, level), (x.end, level)],
            6,
            4,
            grey.stroke_width(1),
        ))?;
        if i == 0 {
            series
                .label(format!("±{MISS_SIGMA}σ"))
                .legend(move |at| dashed_key(at, grey, 1));
        }
    }
    Ok((chart, legend.corner))
}

impl JointResidualsFigure<'_> {
    /// The DMA panel: E′ and E″ residuals coloured by isotherm, and the two
    /// ends of the colour ramp as a key.
    fn draw_dma<DB>(&self, area: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let (storage, loss) = self.dma_residuals();
        let ends: Vec<(String, RGBColor)> = match self.isotherms().as_slice() {
            [] => Vec::new(),
            [t] => vec![(celsius(*t), style::cold_to_warm(0.5))],
            [first, .., last] => vec![
                (
                    format!("{} (coldest)", celsius(*first)),
                    style::cold_to_warm(0.0),
                ),
                (
                    format!("{} (warmest)", celsius(*last)),
                    style::cold_to_warm(1.0),
                ),
            ],
        };
        let labels = (
            "E′: ln(E′_fit/E′)/σ, per isotherm".to_string(),
            "E″: ln(E″_fit/E″)/σ, per isotherm".to_string(),
        );
        let panel = Panel {
            title: "Joint fit residuals: DMA (σ units)",
            x_description: "reduced frequency ω a_T (rad/s)",
            y_description: "ln(E_fit/E_meas)/σ",
            x_range: log_range(storage.iter().map(|p| 10f64.powf(p.0)), 0.2, -2.0..3.0),
            points: storage.iter().chain(&loss).map(|p| (p.0, p.1)).collect(),
            entries: 2 + ends.len(),
            longest: labels.0.chars().count(),
        };
        let (mut chart, corner) = residual_chart(area, &panel)?;
        draw_storage_loss(&mut chart, &storage, &loss, labels)?;
        for (label, colour) in ends {
            chart
                .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())?
                .label(label)
                .legend(move |(x, y)| Circle::new((x + 10, y), 5, colour.filled()));
        }
        draw_legend(&mut chart, corner)
    }

    /// The rolling panel: one colour per temperature.
    fn draw_rolling<DB>(&self, area: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let groups = self.rolling_residuals();
        let points: Vec<(f64, f64)> = groups.iter().flat_map(|g| g.1.iter().copied()).collect();
        let labels: Vec<String> = groups
            .iter()
            .map(|(t, _)| temperature_label(*t, "rolling rows"))
            .collect();
        let panel = Panel {
            title: "Joint fit residuals: rolling friction (σ units)",
            x_description: "reduced speed v·a_T (m/s)",
            y_description: "(μ_fit − μ_meas)/σ",
            x_range: log_range(points.iter().map(|p| 10f64.powf(p.0)), 0.2, -6.0..0.0),
            points,
            entries: groups.len(),
            longest: labels.iter().map(|l| l.chars().count()).max().unwrap_or(4),
        };
        let (mut chart, corner) = residual_chart(area, &panel)?;
        let several = groups.len() > 1;
        for (i, ((_, points), label)) in groups.iter().zip(labels).enumerate() {
            // The colours of friction.png, temperature for temperature.
            let c = if several {
                style::SERIES[i % style::SERIES.len()]
            } else {
                style::MEASURED
            };
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, 3, c.filled())))?
                .label(label)
                .legend(move |(x, y)| Circle::new((x + 10, y), 4, c.filled()));
        }
        draw_legend(&mut chart, corner)
    }
}
