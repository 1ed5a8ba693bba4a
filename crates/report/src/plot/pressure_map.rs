//! The picture of an exact steady rolling contact at one speed (`rollfit
//! forward` with `[contact] size = "exact"`): the pressure under the body
//! and the contact's outline, against the static Hertz contact, dashed, in
//! units of the static contact size (r0 or a0) and the static Hertz peak
//! pressure p0, so that the asymmetry the material's memory causes reads
//! off directly (Persson 2010, Section 4: the pressure's centroid moves to
//! the leading side by x̄ = μR).
//!
//! The sphere's map is a colour map of p/p0 over its boundary-element
//! cells on axes of equal scale (a circle looks round), with the outline
//! in black and a colour bar; the cylinder's, whose pressure is the same
//! at every y, is the profile p(x)/p0.

use std::ops::Range;

use plotters::coord::Shift;
use plotters::prelude::*;
use rollfit_model::exact::{ContactPressure, PressureMap};

use super::forward_sweep::significant;
use super::parts::{dashed_key, legend_box, place_legend, plot_size};
use super::{DrawResult, Figure, SeriesLabelPosition, draw_legend, format_tick, style};

/// Width of the y label area and height of the x label area, px.
const Y_LABELS: u32 = 60;
const X_LABELS: u32 = 45;
/// Width of the sphere map's colour bar area at the right, px (labels
/// included).
const BAR_AREA: u32 = 140;
/// Colour levels of the sphere's map. Neighbouring cells of a row on one
/// level are drawn as one rectangle, which keeps the SVG small (at the
/// default 96 cells across a contact holds about 7000 cells); 64 levels are
/// finer than the eye tells apart on the ramp.
const LEVELS: f64 = 64.0;
/// Room around the contact and the Hertz circle, in static contact sizes.
const PAD: f64 = 0.15;
/// Points of the dashed Hertz circle or profile.
const HERTZ_POINTS: usize = 241;
/// The static Hertz contact: blue, apart from every colour of the pressure
/// ramp.
const HERTZ: RGBColor = RGBColor(31, 119, 180);
/// The exact profile of a cylinder, and the fill under it.
const PROFILE: RGBColor = style::FITTED;

/// The pressure map of one exact solution.
pub struct PressureMapFigure<'a> {
    /// The solution's pressure and outline.
    pub map: &'a PressureMap,
    /// What rolls where, for the title (e.g. the scene file and the
    /// temperature); the speed and μ are added.
    pub label: String,
}

impl PressureMapFigure<'_> {
    fn title(&self) -> String {
        format!(
            "{}, v = {:.3e} m/s, μ = {}",
            self.label,
            self.map.speed,
            significant(self.map.mu, 4)
        )
    }

    /// "r₀ = 1.23 mm" or "a₀ = …": the length unit of the axes.
    fn size_text(&self, symbol: &str) -> String {
        format!(
            "{symbol} = {} mm",
            significant(1e3 * self.map.static_contact_size, 3)
        )
    }

    /// "p₀ = 1.23e5 Pa": the pressure unit.
    fn pressure_text(&self) -> String {
        format!("p₀ = {:.3e} Pa", self.map.static_peak_pressure())
    }
}

impl Figure for PressureMapFigure<'_> {
    fn name(&self) -> &'static str {
        "pressure_map"
    }

    fn caption(&self) -> String {
        let v = self.map.speed;
        match self.map.pressure {
            ContactPressure::Cells { .. } => format!(
                "Pressure under the rolling sphere at v = {v:.3e} m/s, p/p₀ in colour ({}, the \
                 static Hertz peak), the exact contact outline (black) and the static Hertz \
                 circle ({}, dashed); the sphere rolls toward +x.",
                self.pressure_text(),
                self.size_text("r₀")
            ),
            ContactPressure::Profile { .. } => format!(
                "Pressure under the rolling cylinder at v = {v:.3e} m/s, p/p₀ ({}, the static \
                 Hertz peak), against the static Hertz pressure ({}, dashed); the cylinder \
                 rolls toward +x.",
                self.pressure_text(),
                self.size_text("a₀")
            ),
        }
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let area = root.titled(&self.title(), ("sans-serif", style::CAPTION))?;
        match &self.map.pressure {
            ContactPressure::Cells { cell, cells, .. } => self.draw_cells(&area, *cell, cells),
            ContactPressure::Profile { points, .. } => self.draw_profile(&area, points),
        }
    }
}

/// The top of the colour scale and of the profile's axis, p/p0: the map's
/// largest pressure (1 for a map without pressure).
fn pressure_top(map: &PressureMap) -> f64 {
    let top = map.max_pressure() / map.static_peak_pressure();
    if top.is_finite() && top > 0.0 {
        top
    } else {
        1.0
    }
}

/// The colour level (0 … LEVELS − 1) of p/p0 = `reduced` on a scale up to
/// `top`.
fn level(reduced: f64, top: f64) -> f64 {
    (reduced / top * LEVELS).floor().clamp(0.0, LEVELS - 1.0)
}

/// The colour of a level: the ramp at the level's middle.
fn level_colour(level: f64) -> RGBColor {
    style::pressure_ramp((level + 0.5) / LEVELS)
}

/// Ranges covering `x` and `y` with the same scale on both axes for a plot
/// of `plot` px (width, height): the shorter side is widened about its
/// middle.
fn equal_scale(x: Range<f64>, y: Range<f64>, plot: (u32, u32)) -> (Range<f64>, Range<f64>) {
    let (w, h) = (f64::from(plot.0), f64::from(plot.1));
    let scale = ((x.end - x.start) / w).max((y.end - y.start) / h);
    let around = |r: Range<f64>, pixels: f64| {
        let mid = 0.5 * (r.start + r.end);
        (mid - 0.5 * scale * pixels)..(mid + 0.5 * scale * pixels)
    };
    (around(x, w), around(y, h))
}

/// A rectangle of one colour level: lower-left and upper-right corners
/// (units of r0) and the level.
type LevelRect = ((f64, f64), (f64, f64), f64);

/// The cells of the sphere's map in units of r0 as rectangles
/// ((x0, y0), (x1, y1), level): each run of neighbouring cells of a row on
/// one colour level is one rectangle.
fn cell_runs(cells: &[(f64, f64, f64)], cell: f64, r0: f64, p0: f64, top: f64) -> Vec<LevelRect> {
    let h = cell / r0;
    // Cell centres lie on a grid of side h offset from the axis (the grid
    // is centred on the contact): the offset, from any cell, then rows and
    // columns as whole numbers of cells.
    let (dx, dy) = cells.first().map_or((0.0, 0.0), |&(x, y, _)| {
        ((x / cell).rem_euclid(1.0), (y / cell).rem_euclid(1.0))
    });
    let mut indexed: Vec<(i64, i64, f64)> = cells
        .iter()
        .map(|&(x, y, p)| {
            (
                (y / cell - dy).round() as i64,
                (x / cell - dx).round() as i64,
                level(p / p0, top),
            )
        })
        .collect();
    indexed.sort_by_key(|a| (a.0, a.1));
    let mut rects = Vec::new();
    let mut i = 0;
    while i < indexed.len() {
        let (row, first, lvl) = indexed[i];
        let mut last = first;
        while i + 1 < indexed.len()
            && indexed[i + 1].0 == row
            && indexed[i + 1].1 == last + 1
            && indexed[i + 1].2 == lvl
        {
            i += 1;
            last += 1;
        }
        let y = (row as f64 + dy) * h;
        let (x0, x1) = ((first as f64 + dx - 0.5) * h, (last as f64 + dx + 0.5) * h);
        rects.push(((x0, y - 0.5 * h), (x1, y + 0.5 * h), lvl));
        i += 1;
    }
    rects
}

/// The outline as one closed line in units of r0: the leading edges up
/// the rows, the trailing edges back down, closed half a cell (`cell`, m)
/// beyond the first and last rows, where their cells end.
fn outline_polygon(outline: &[(f64, f64, f64)], r0: f64, cell: f64) -> Vec<(f64, f64)> {
    let (Some(&(y_first, a_first, b_first)), Some(&(y_last, a_last, b_last))) =
        (outline.first(), outline.last())
    else {
        return Vec::new();
    };
    let half = 0.5 * cell;
    let mut line = vec![(b_first / r0, (y_first - half) / r0)];
    line.extend(outline.iter().map(|&(y, _, b)| (b / r0, y / r0)));
    line.push((b_last / r0, (y_last + half) / r0));
    line.push((a_last / r0, (y_last + half) / r0));
    line.extend(outline.iter().rev().map(|&(y, a, _)| (a / r0, y / r0)));
    line.push((a_first / r0, (y_first - half) / r0));
    line.push(line[0]);
    line
}

/// The legend's corner: where a box of `entries` short lines covers the
/// fewest of `points`.
fn legend_corner(
    points: &[(f64, f64)],
    x: &Range<f64>,
    y: &Range<f64>,
    plot: (u32, u32),
    entries: usize,
    longest: usize,
) -> SeriesLabelPosition {
    let weighted: Vec<((f64, f64), usize)> = points.iter().map(|&p| (p, 1)).collect();
    place_legend(&weighted, x, y, legend_box(plot, entries, longest)).corner
}

impl PressureMapFigure<'_> {
    /// The sphere: colour map, outline, Hertz circle, axis and colour bar.
    fn draw_cells<DB>(
        &self,
        area: &DrawingArea<DB, Shift>,
        cell: f64,
        cells: &[(f64, f64, f64)],
    ) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let map = self.map;
        let (r0, p0) = (map.static_contact_size, map.static_peak_pressure());
        let top = pressure_top(map);
        let outline = map.outline();
        let (width, _) = area.dim_in_pixel();
        let (main, bar) = area.split_horizontally(width.saturating_sub(BAR_AREA));
        let plot = plot_size(main.dim_in_pixel(), Y_LABELS, X_LABELS, false);

        let polygon = outline_polygon(&outline, r0, cell);
        let half_cell = 0.5 * cell / r0;
        let extent = |values: &mut dyn Iterator<Item = f64>| {
            values.fold((-1.0f64, 1.0f64), |(lo, hi), v| (lo.min(v), hi.max(v)))
        };
        let (x_lo, x_hi) = extent(&mut polygon.iter().map(|p| p.0));
        let (y_lo, y_hi) = extent(
            &mut polygon
                .iter()
                .flat_map(|p| [p.1 - half_cell, p.1 + half_cell]),
        );
        let (x_range, y_range) =
            equal_scale((x_lo - PAD)..(x_hi + PAD), (y_lo - PAD)..(y_hi + PAD), plot);
        let circle: Vec<(f64, f64)> = (0..HERTZ_POINTS)
            .map(|k| {
                let phi = std::f64::consts::TAU * k as f64 / (HERTZ_POINTS - 1) as f64;
                (phi.cos(), phi.sin())
            })
            .collect();
        let corner = legend_corner(
            &[polygon.as_slice(), circle.as_slice()].concat(),
            &x_range,
            &y_range,
            plot,
            3,
            "sphere's axis".len(),
        );

        let mut chart = ChartBuilder::on(&main)
            .margin(12)
            .x_label_area_size(X_LABELS)
            .y_label_area_size(Y_LABELS)
            .build_cartesian_2d(x_range, y_range)?;
        let tick = |v: &f64| format_tick(*v);
        chart
            .configure_mesh()
            .x_desc(format!(
                "x / r₀, rolling direction → ({}, static Hertz)",
                self.size_text("r₀")
            ))
            .y_desc("y / r₀")
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .label_style(("sans-serif", style::TICK_LABEL))
            .axis_desc_style(("sans-serif", style::AXIS_DESCRIPTION))
            .bold_line_style(RGBColor(220, 220, 220))
            .max_light_lines(0)
            .draw()?;
        chart.draw_series(
            cell_runs(cells, cell, r0, p0, top)
                .into_iter()
                .map(|(a, b, lvl)| Rectangle::new([a, b], level_colour(lvl).filled())),
        )?;
        chart
            .draw_series(DashedLineSeries::new(circle, 8, 5, HERTZ.stroke_width(2)))?
            .label("static Hertz")
            .legend(|at| dashed_key(at, HERTZ, 2));
        chart
            .draw_series(LineSeries::new(polygon, BLACK.stroke_width(2)))?
            .label("exact outline")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
        chart
            .draw_series(std::iter::once(Cross::new(
                (0.0, 0.0),
                6,
                BLACK.stroke_width(1),
            )))?
            .label("sphere's axis")
            .legend(|(x, y)| Cross::new((x + 10, y), 6, BLACK.stroke_width(1)));
        draw_legend(&mut chart, corner)?;
        colour_bar(&bar, top, &self.pressure_text())
    }

    /// The cylinder: p(x)/p0 against x/a0 with the static Hertz profile.
    fn draw_profile<DB>(&self, area: &DrawingArea<DB, Shift>, points: &[(f64, f64)]) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let map = self.map;
        let (a0, p0) = (map.static_contact_size, map.static_peak_pressure());
        let top = pressure_top(map).max(1.0);
        let profile: Vec<(f64, f64)> = points.iter().map(|&(x, p)| (x / a0, p / p0)).collect();
        let hertz: Vec<(f64, f64)> = (0..HERTZ_POINTS)
            .map(|k| {
                let xi = -(std::f64::consts::PI * k as f64 / (HERTZ_POINTS - 1) as f64).cos();
                (xi, (1.0 - xi * xi).max(0.0).sqrt())
            })
            .collect();
        let (x_lo, x_hi) = profile
            .iter()
            .fold((-1.0f64, 1.0f64), |(lo, hi), p| (lo.min(p.0), hi.max(p.0)));
        let x_range = (x_lo - PAD)..(x_hi + PAD);
        let y_range = 0.0..1.15 * top;
        let plot = plot_size(area.dim_in_pixel(), Y_LABELS, X_LABELS, false);
        let corner = legend_corner(
            &[profile.as_slice(), hertz.as_slice()].concat(),
            &x_range,
            &y_range,
            plot,
            3,
            "cylinder's axis".len(),
        );

        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .x_label_area_size(X_LABELS)
            .y_label_area_size(Y_LABELS)
            .build_cartesian_2d(x_range, y_range.clone())?;
        let tick = |v: &f64| format_tick(*v);
        chart
            .configure_mesh()
            .x_desc(format!(
                "x / a₀, rolling direction → ({}, static Hertz)",
                self.size_text("a₀")
            ))
            .y_desc(format!("p / p₀ ({})", self.pressure_text()))
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .label_style(("sans-serif", style::TICK_LABEL))
            .axis_desc_style(("sans-serif", style::AXIS_DESCRIPTION))
            .bold_line_style(RGBColor(220, 220, 220))
            .max_light_lines(0)
            .draw()?;
        chart.draw_series(AreaSeries::new(
            profile.iter().copied(),
            0.0,
            style::pressure_ramp(0.3).mix(0.6).filled(),
        ))?;
        chart
            .draw_series(DashedLineSeries::new(hertz, 8, 5, HERTZ.stroke_width(2)))?
            .label("static Hertz")
            .legend(|at| dashed_key(at, HERTZ, 2));
        chart
            .draw_series(LineSeries::new(profile, PROFILE.stroke_width(2)))?
            .label("exact pressure")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], PROFILE.stroke_width(2)));
        chart
            .draw_series(DashedLineSeries::new(
                [(0.0, y_range.start), (0.0, y_range.end)],
                3,
                3,
                BLACK.stroke_width(1),
            ))?
            .label("cylinder's axis")
            .legend(|at| dashed_key(at, BLACK, 1));
        draw_legend(&mut chart, corner)?;
        Ok(())
    }
}

/// The colour bar of the sphere's map: the levels from 0 to `top` (p/p0),
/// labelled at the left, `unit` naming p0.
fn colour_bar<DB>(area: &DrawingArea<DB, Shift>, top: f64, unit: &str) -> DrawResult
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .margin_left(0)
        .x_label_area_size(X_LABELS)
        .y_label_area_size(80)
        .build_cartesian_2d(0.0..1.0, 0.0..top)?;
    let tick = |v: &f64| format_tick(*v);
    chart
        .configure_mesh()
        .disable_x_mesh()
        .disable_y_mesh()
        .x_labels(0)
        .y_desc(format!("p / p₀ ({unit})"))
        .y_label_formatter(&tick)
        .label_style(("sans-serif", style::TICK_LABEL))
        .axis_desc_style(("sans-serif", style::TICK_LABEL))
        .draw()?;
    chart.draw_series((0..LEVELS as usize).map(|k| {
        let lvl = k as f64;
        Rectangle::new(
            [(0.0, top * lvl / LEVELS), (1.0, top * (lvl + 1.0) / LEVELS)],
            level_colour(lvl).filled(),
        )
    }))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_scale_widens_the_shorter_side() {
        let (x, y) = equal_scale(-1.0..1.0, -1.0..1.0, (400, 200));
        assert_eq!(y, -1.0..1.0);
        assert_eq!(x, -2.0..2.0);
    }

    /// Neighbouring cells on one level merge; a gap or another level
    /// starts a new rectangle.
    #[test]
    fn cells_of_a_row_on_one_level_are_one_rectangle() {
        let h = 0.1;
        let cells = [
            (0.05, 0.05, 1.0),
            (0.15, 0.05, 1.0),
            (0.25, 0.05, 100.0),
            (0.45, 0.05, 100.0),
            (0.05, 0.15, 1.0),
        ];
        let rects = cell_runs(&cells, h, 1.0, 100.0, 1.0);
        // Half-integer centres (an even grid) either side of the axis
        // stay neighbours.
        let even = [(-0.05, 0.0, 1.0), (0.05, 0.0, 1.0)];
        assert_eq!(cell_runs(&even, h, 1.0, 100.0, 1.0).len(), 1);
        assert_eq!(rects.len(), 4, "{rects:?}");
        let (a, b, lvl) = rects[0];
        assert!((a.0 - 0.0).abs() < 1e-12 && (b.0 - 0.2).abs() < 1e-12);
        assert!((a.1 - 0.0).abs() < 1e-12 && (b.1 - 0.1).abs() < 1e-12);
        assert_eq!(lvl, 0.0);
        assert_eq!(rects[1].2, LEVELS - 1.0);
    }

    #[test]
    fn the_outline_closes_on_itself() {
        let line = outline_polygon(&[(-1.0, -2.0, 3.0), (1.0, -2.5, 2.5)], 1.0, 0.5);
        assert_eq!(line.first(), line.last());
        assert_eq!(line[0], (3.0, -1.25));
        assert_eq!(line[1], (3.0, -1.0));
        assert_eq!(line[4], (-2.5, 1.25));
        assert_eq!(line[5], (-2.5, 1.0));
        assert!(outline_polygon(&[], 1.0, 0.5).is_empty());
    }
}
