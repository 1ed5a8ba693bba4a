//! The picture `rollfit master` writes: DMA isotherms shifted by their
//! factors a_T onto one master curve at the reference temperature, with the
//! Prony series fitted to it. Top left, log E′ (filled circles) and log E″
//! (open triangles) against the reduced frequency ω a_T, every point in the
//! colour of its isotherm (cold blue to warm red), so that an isotherm that
//! does not join its neighbours shows at once, and the Prony E′ and E″ as
//! black solid and dashed lines; below it tan δ = E″/E′, the most sensitive
//! test of the superposition (it does not depend on a vertical shift), of
//! the points and of the Prony curve. At the right, log10 a_T against T per
//! isotherm with the fitted shift curve (WLF or Arrhenius), and under it
//! the key to the colours: the coldest, the reference and the warmest
//! temperature. A single isotherm has nothing to shift: its panel says so.

use std::ops::Range;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::axes::{lg, linear_range, log_axis, log_range};
use super::marker_density::drawn_points;
use super::parts::{
    ColouredPoint, dashed_key, draw_storage_loss, isotherms, legend_box, place_legend, plot_size,
    runs,
};
use super::{DrawResult, Figure, draw_legend, draw_mesh, draw_shift_mesh, format_tick, style};

/// Width of the left column (master curve and tan δ), px.
const LEFT_WIDTH: u32 = 740;
/// Height of the master curve panel and of the shift panel, px.
const TOP_HEIGHT: u32 = 520;
/// Slices of the colour key's gradient bar.
const KEY_SLICES: i32 = 120;

/// One DMA point after shifting.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShiftedPoint {
    /// Reduced angular frequency ω a_T, rad/s.
    pub reduced_omega: f64,
    /// Storage modulus E′ (or G′), Pa.
    pub storage: f64,
    /// Loss modulus E″ (or G″), Pa.
    pub loss: f64,
    /// Temperature of the point's isotherm, °C.
    pub temperature: f64,
}

/// The Prony curve fitted to the master curve, sampled densely.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct MasterCurveFit {
    /// Angular frequency, rad/s, increasing.
    pub omega: Vec<f64>,
    /// Storage modulus at each ω, Pa.
    pub storage: Vec<f64>,
    /// Loss modulus at each ω, Pa.
    pub loss: Vec<f64>,
}

/// One isotherm's shift factor as the picture shows it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShiftMarker {
    /// Temperature, °C.
    pub temperature: f64,
    /// log10 a_T: the measured one where `determined`, else the value
    /// applied (the law's).
    pub log_shift: f64,
    /// 1σ of a measured shift, decades (an error bar where finite and
    /// positive).
    pub sigma: f64,
    /// Whether the data determine the shift; an undetermined one is drawn
    /// hollow at the law's value.
    pub determined: bool,
}

/// Shifted DMA isotherms, the Prony fit and the shift factors.
pub struct DmaMasterFigure<'a> {
    /// The shifted points of every isotherm.
    pub points: &'a [ShiftedPoint],
    /// The fitted Prony curve.
    pub fit: &'a MasterCurveFit,
    /// Reference temperature, °C.
    pub t_ref: f64,
    /// The shift factor of each isotherm.
    pub shifts: &'a [ShiftMarker],
    /// The fitted shift curve (T °C, log10 a_T), densely (WLF/Arrhenius);
    /// empty when none.
    pub shift_curve: &'a [(f64, f64)],
    /// "E" (Young's modulus) or "G" (shear modulus): what the axis labels say.
    pub modulus_symbol: &'static str,
}

impl DmaMasterFigure<'_> {
    /// The isotherms' temperatures, °C, increasing, each once.
    fn isotherms(&self) -> Vec<f64> {
        isotherms(self.points.iter().map(|p| p.temperature))
    }

    /// Whether there is a shift to show: at least two shift factors or a
    /// fitted curve.
    fn has_shift(&self) -> bool {
        let measured = self
            .shifts
            .iter()
            .filter(|s| s.temperature.is_finite() && s.log_shift.is_finite())
            .count();
        measured >= 2
            || self
                .shift_curve
                .iter()
                .any(|s| s.0.is_finite() && s.1.is_finite())
    }

    fn modulus_name(&self) -> &'static str {
        if self.modulus_symbol == "G" {
            "shear modulus"
        } else {
            "Young's modulus"
        }
    }

    /// The Prony curve's runs of (log10 ω, log10 value).
    fn fit_runs(&self, value: impl Fn(usize) -> Option<f64>) -> Vec<Vec<(f64, f64)>> {
        runs((0..self.fit.omega.len()).map(|i| Some((lg(self.fit.omega[i])?, lg(value(i)?)?))))
    }
}

/// The colour of an isotherm at `t` °C between the coldest and the warmest.
pub(crate) fn isotherm_colour(t: f64, coldest: f64, warmest: f64) -> RGBColor {
    if warmest > coldest {
        style::cold_to_warm((t - coldest) / (warmest - coldest))
    } else {
        style::cold_to_warm(0.5)
    }
}

fn text_style(size: u32, h: HPos, v: VPos) -> TextStyle<'static> {
    ("sans-serif", size)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(h, v))
}

/// "20 °C".
pub(crate) fn celsius(t: f64) -> String {
    format!("{} °C", format_tick(t))
}

impl Figure for DmaMasterFigure<'_> {
    fn name(&self) -> &'static str {
        "master"
    }

    fn caption(&self) -> String {
        let s = self.modulus_symbol;
        let n = self.isotherms().len();
        let shift = if self.has_shift() {
            "; right, the shift factors log10 a_T per isotherm and the fitted shift curve"
        } else {
            "; a single isotherm, so nothing was shifted"
        };
        format!(
            "Master curve of the {} from {n} DMA isotherm{} at T_ref = {}: {s}′ (filled) and {s}″ (open) coloured by temperature with the fitted Prony curve (black), tan δ = {s}″/{s}′ below{shift}.",
            self.modulus_name(),
            if n == 1 { "" } else { "s" },
            celsius(self.t_ref),
        )
    }

    fn size(&self) -> (u32, u32) {
        (1100, 800)
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let isotherms = self.isotherms();
        let coldest = isotherms.first().copied().unwrap_or(self.t_ref);
        let warmest = isotherms.last().copied().unwrap_or(self.t_ref);
        let colour = |t: f64| isotherm_colour(t, coldest, warmest);
        let (left, right) = root.split_horizontally(LEFT_WIDTH);
        let (upper, lower) = left.split_vertically(TOP_HEIGHT);
        let (shift_area, key_area) = right.split_vertically(TOP_HEIGHT);

        let curves = Curves::of(self, &colour);
        self.draw_moduli(&upper, &curves)?;
        self.draw_tan_delta(&lower, &curves)?;
        if self.has_shift() {
            self.draw_shift(&shift_area, &colour)?;
        } else {
            draw_no_shift_note(&shift_area, &isotherms)?;
        }
        self.draw_colour_key(&key_area, &isotherms, &colour)?;
        Ok(())
    }
}

/// (log10 ω a_T, log10 value, colour) of the measured points.
type ColouredPoints = Vec<ColouredPoint>;

/// What the two left panels draw, in log10 coordinates, and their shared
/// frequency axis.
struct Curves {
    storage: ColouredPoints,
    loss: ColouredPoints,
    tan_delta: ColouredPoints,
    fit_storage: Vec<Vec<(f64, f64)>>,
    fit_loss: Vec<Vec<(f64, f64)>>,
    fit_tan: Vec<Vec<(f64, f64)>>,
    x_range: Range<f64>,
    x_description: String,
}

impl Curves {
    fn of(figure: &DmaMasterFigure, colour: &dyn Fn(f64) -> RGBColor) -> Self {
        let drawn = drawn_points(figure.points, |p| p.temperature);
        let points = |value: &dyn Fn(&ShiftedPoint) -> f64| -> ColouredPoints {
            drawn
                .iter()
                .filter_map(|p| Some((lg(p.reduced_omega)?, lg(value(p))?, colour(p.temperature))))
                .collect()
        };
        let storage = points(&|p| p.storage);
        let loss = points(&|p| p.loss);
        let tan_delta = points(&|p| p.loss / p.storage);
        let fit = figure.fit;
        let fit_storage = figure.fit_runs(|i| fit.storage.get(i).copied());
        let fit_loss = figure.fit_runs(|i| fit.loss.get(i).copied());
        let fit_tan = figure.fit_runs(|i| Some(fit.loss.get(i)? / fit.storage.get(i)?));
        let x_range = log_range(
            storage
                .iter()
                .chain(&loss)
                .map(|p| p.0)
                .chain(fit_storage.iter().chain(&fit_loss).flatten().map(|p| p.0))
                .map(|x| 10f64.powf(x)),
            0.2,
            -2.0..3.0,
        );
        Curves {
            storage,
            loss,
            tan_delta,
            fit_storage,
            fit_loss,
            fit_tan,
            x_range,
            x_description: format!(
                "reduced frequency ω a_T (rad/s), T_ref = {}",
                celsius(figure.t_ref)
            ),
        }
    }
}

impl DmaMasterFigure<'_> {
    /// E′ and E″ of the isotherms with the Prony curves on top.
    fn draw_moduli<DB>(&self, area: &DrawingArea<DB, Shift>, curves: &Curves) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let s = self.modulus_symbol;
        let (storage, loss) = (&curves.storage, &curves.loss);
        let (fit_storage, fit_loss) = (&curves.fit_storage, &curves.fit_loss);
        let y_moduli = log_range(
            storage
                .iter()
                .chain(loss)
                .map(|p| p.1)
                .chain(fit_storage.iter().chain(fit_loss).flatten().map(|p| p.1))
                .map(|y| 10f64.powf(y)),
            0.15,
            4.0..9.0,
        );
        let storage_label = format!("{s}′ (storage), per isotherm");
        let loss_label = format!("{s}″ (loss), per isotherm");
        let samples: Vec<((f64, f64), usize)> = storage
            .iter()
            .chain(loss)
            .map(|p| ((p.0, p.1), 1))
            .chain(
                fit_storage
                    .iter()
                    .chain(fit_loss)
                    .flatten()
                    .map(|&p| (p, 1)),
            )
            .collect();
        let box_size = legend_box(
            plot_size(area.dim_in_pixel(), 75, 45, true),
            4,
            storage_label.chars().count(),
        );
        let legend = place_legend(&samples, &curves.x_range, &y_moduli, box_size);
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .caption(
                format!(
                    "Master curve of the DMA isotherms at T_ref = {}",
                    celsius(self.t_ref)
                ),
                ("sans-serif", style::CAPTION),
            )
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(log_axis(curves.x_range.clone()), log_axis(legend.y))?;
        draw_mesh(
            &mut chart,
            &curves.x_description,
            &format!("{s}′, {s}″ (Pa)"),
            true,
        )?;
        draw_storage_loss(&mut chart, storage, loss, (storage_label, loss_label))?;
        // The Prony curves on top of the points: they are what the points
        // are judged against.
        for (i, run) in fit_storage.iter().enumerate() {
            let series =
                chart.draw_series(LineSeries::new(run.iter().copied(), BLACK.stroke_width(2)))?;
            if i == 0 {
                series.label(format!("Prony {s}′")).legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 24, y)], BLACK.stroke_width(2))
                });
            }
        }
        for (i, run) in fit_loss.iter().enumerate() {
            let series = chart.draw_series(DashedLineSeries::new(
                run.iter().copied(),
                8,
                5,
                BLACK.stroke_width(2),
            ))?;
            if i == 0 {
                series
                    .label(format!("Prony {s}″"))
                    .legend(|at| dashed_key(at, BLACK, 2));
            }
        }
        draw_legend(&mut chart, legend.corner)
    }

    /// tan δ of the isotherms with the Prony curve.
    fn draw_tan_delta<DB>(&self, area: &DrawingArea<DB, Shift>, curves: &Curves) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let s = self.modulus_symbol;
        let (tan_delta, fit_tan) = (&curves.tan_delta, &curves.fit_tan);
        let y_tan = log_range(
            tan_delta
                .iter()
                .map(|p| p.1)
                .chain(fit_tan.iter().flatten().map(|p| p.1))
                .map(|y| 10f64.powf(y)),
            0.15,
            -2.0..0.0,
        );
        let tan_label = format!("tan δ = {s}″/{s}′, per isotherm");
        let samples: Vec<((f64, f64), usize)> = tan_delta
            .iter()
            .map(|p| ((p.0, p.1), 1))
            .chain(fit_tan.iter().flatten().map(|&p| (p, 1)))
            .collect();
        let box_size = legend_box(
            plot_size(area.dim_in_pixel(), 75, 45, false),
            2,
            tan_label.chars().count(),
        );
        let legend = place_legend(&samples, &curves.x_range, &y_tan, box_size);
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(log_axis(curves.x_range.clone()), log_axis(legend.y))?;
        draw_mesh(&mut chart, &curves.x_description, "tan δ", true)?;
        chart
            .draw_series(
                tan_delta
                    .iter()
                    .map(|&(x, y, c)| Circle::new((x, y), 3, c.filled())),
            )?
            .label(tan_label)
            .legend(|(x, y)| Circle::new((x + 10, y), 4, style::MEASURED.filled()));
        for (i, run) in fit_tan.iter().enumerate() {
            let series =
                chart.draw_series(LineSeries::new(run.iter().copied(), BLACK.stroke_width(2)))?;
            if i == 0 {
                series.label("Prony tan δ").legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 24, y)], BLACK.stroke_width(2))
                });
            }
        }
        draw_legend(&mut chart, legend.corner)
    }
}

/// The shift panel left blank but for the reason, so that the empty corner
/// is not mistaken for a failed drawing.
fn draw_no_shift_note<DB>(area: &DrawingArea<DB, Shift>, isotherms: &[f64]) -> DrawResult
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    let (w, _) = area.dim_in_pixel();
    let note = match isotherms {
        [t] => vec![
            format!("Single isotherm ({}):", celsius(*t)),
            "nothing was shifted, so there".into(),
            "are no shift factors to show.".into(),
        ],
        _ => vec![
            "No shift factors given:".into(),
            "the shift panel is empty.".into(),
        ],
    };
    for (i, line) in note.iter().enumerate() {
        area.draw(&Text::new(
            line.clone(),
            (w as i32 / 2, 200 + 24 * i as i32),
            text_style(style::LEGEND + 2, HPos::Center, VPos::Top),
        ))?;
    }
    Ok(())
}

/// The measured shifts' ±1σ bars (clipped to the axes) and the
/// undetermined isotherms as hollow markers in their colour.
fn draw_bars_and_undetermined<'a, DB>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    bars: &[(f64, f64, f64)],
    undetermined: &[(f64, f64)],
    colour: &dyn Fn(f64) -> RGBColor,
) -> DrawResult
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
{
    let (lo, hi) = (chart.y_range().start, chart.y_range().end);
    for &(t, l, sigma) in bars {
        chart.draw_series(std::iter::once(ErrorBar::new_vertical(
            t,
            (l - sigma).max(lo),
            l,
            (l + sigma).min(hi),
            BLACK.stroke_width(1),
            8,
        )))?;
    }
    if !undetermined.is_empty() {
        chart
            .draw_series(undetermined.iter().map(|&(t, l)| {
                EmptyElement::at((t, l))
                    + Circle::new((0, 0), 5, WHITE.filled())
                    + Circle::new((0, 0), 5, colour(t).stroke_width(2))
            }))?
            .label(UNDETERMINED_LABEL)
            .legend(|(x, y)| {
                EmptyElement::at((x + 10, y))
                    + Circle::new((0, 0), 5, WHITE.filled())
                    + Circle::new((0, 0), 5, style::MEASURED.stroke_width(2))
            });
    }
    Ok(())
}

/// The legend of the hollow markers.
const UNDETERMINED_LABEL: &str = "not determined (value applied)";

impl DmaMasterFigure<'_> {
    /// log10 a_T against T: the measured factors as markers in their
    /// isotherm's colour, the fitted shift curve as a line.
    fn draw_shift<DB>(
        &self,
        area: &DrawingArea<DB, Shift>,
        colour: &dyn Fn(f64) -> RGBColor,
    ) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let shown: Vec<ShiftMarker> = self
            .shifts
            .iter()
            .copied()
            .filter(|s| s.temperature.is_finite() && s.log_shift.is_finite())
            .collect();
        let measured: Vec<(f64, f64)> = shown
            .iter()
            .filter(|s| s.determined)
            .map(|s| (s.temperature, s.log_shift))
            .collect();
        let undetermined: Vec<(f64, f64)> = shown
            .iter()
            .filter(|s| !s.determined)
            .map(|s| (s.temperature, s.log_shift))
            .collect();
        // Error bars, drawn only where they fit in the axes: a bar of
        // decades on a well-measured isotherm would flatten the plot.
        let bars: Vec<(f64, f64, f64)> = shown
            .iter()
            .filter(|s| s.determined && s.sigma.is_finite() && s.sigma > 0.0)
            .map(|s| (s.temperature, s.log_shift, s.sigma))
            .collect();
        let curve = runs(
            self.shift_curve
                .iter()
                .map(|&(t, l)| (t.is_finite() && l.is_finite()).then_some((t, l))),
        );
        let x_range = linear_range(
            measured
                .iter()
                .chain(&undetermined)
                .chain(curve.iter().flatten())
                .map(|p| p.0)
                .chain([self.t_ref]),
            0.08,
        );
        let y_range = linear_range(
            measured
                .iter()
                .chain(&undetermined)
                .chain(curve.iter().flatten())
                .map(|p| p.1)
                .chain([0.0]),
            0.08,
        );
        // Markers weigh more than samples of the line.
        let samples: Vec<((f64, f64), usize)> = curve
            .iter()
            .flatten()
            .map(|&p| (p, 1))
            .chain(measured.iter().chain(&undetermined).map(|&p| (p, 10)))
            .collect();
        let box_size = legend_box(
            plot_size(area.dim_in_pixel(), 60, 45, true),
            2 + usize::from(!undetermined.is_empty()),
            UNDETERMINED_LABEL.len(),
        );
        let legend = place_legend(&samples, &x_range, &y_range, box_size);
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .caption("Shift factors a_T", ("sans-serif", style::CAPTION))
            .x_label_area_size(45)
            .y_label_area_size(60)
            .build_cartesian_2d(x_range, legend.y)?;
        draw_shift_mesh(&mut chart, Some(6))?;
        for (i, run) in curve.iter().enumerate() {
            let series = chart.draw_series(LineSeries::new(
                run.iter().copied(),
                style::WLF.stroke_width(2),
            ))?;
            if i == 0 {
                series.label("fitted shift curve").legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], style::WLF.stroke_width(2))
                });
            }
        }
        draw_bars_and_undetermined(&mut chart, &bars, &undetermined, colour)?;
        if !measured.is_empty() {
            chart
                .draw_series(measured.iter().map(|&(t, l)| {
                    EmptyElement::at((t, l))
                        + Circle::new((0, 0), 5, colour(t).filled())
                        + Circle::new((0, 0), 5, BLACK.stroke_width(1))
                }))?
                .label("measured, ±1σ")
                .legend(|(x, y)| {
                    EmptyElement::at((x + 10, y))
                        + Circle::new((0, 0), 5, style::MEASURED.filled())
                        + Circle::new((0, 0), 5, BLACK.stroke_width(1))
                });
        }
        draw_legend(&mut chart, legend.corner)?;
        Ok(())
    }

    /// The key to the isotherm colours: a bar from the coldest to the
    /// warmest temperature with a tick per isotherm, labelled at both ends
    /// and at T_ref.
    fn draw_colour_key<DB>(
        &self,
        area: &DrawingArea<DB, Shift>,
        isotherms: &[f64],
        colour: &dyn Fn(f64) -> RGBColor,
    ) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let (w, _) = area.dim_in_pixel();
        let w = w as i32;
        area.draw(&Text::new(
            "Isotherm colours",
            (w / 2, 30),
            text_style(style::AXIS_DESCRIPTION, HPos::Center, VPos::Top),
        ))?;
        let (x0, x1, y0, y1) = (30, w - 30, 100, 122);
        let label = text_style(style::LEGEND, HPos::Center, VPos::Top);
        let (coldest, warmest) = match isotherms {
            [] => return Ok(()),
            [t] => {
                // One isotherm: one swatch, no bar.
                area.draw(&Rectangle::new(
                    [(w / 2 - 30, y0), (w / 2 + 30, y1)],
                    colour(*t).filled(),
                ))?;
                area.draw(&Text::new(
                    format!("the one isotherm, {}", celsius(*t)),
                    (w / 2, y1 + 12),
                    label,
                ))?;
                return Ok(());
            }
            [first, .., last] => (*first, *last),
        };
        let at = |t: f64| {
            let f = ((t - coldest) / (warmest - coldest)).clamp(0.0, 1.0);
            x0 + (f * f64::from(x1 - x0)).round() as i32
        };
        for i in 0..KEY_SLICES {
            let f = f64::from(i) / f64::from(KEY_SLICES);
            let a = x0 + (f * f64::from(x1 - x0)).floor() as i32;
            let b = x0
                + ((f64::from(i + 1) / f64::from(KEY_SLICES)) * f64::from(x1 - x0)).ceil() as i32;
            area.draw(&Rectangle::new(
                [(a, y0), (b, y1)],
                style::cold_to_warm(f + 0.5 / f64::from(KEY_SLICES)).filled(),
            ))?;
        }
        area.draw(&Rectangle::new([(x0, y0), (x1, y1)], BLACK.stroke_width(1)))?;
        for &t in isotherms {
            let x = at(t);
            area.draw(&PathElement::new(
                vec![(x, y1), (x, y1 + 6)],
                BLACK.stroke_width(1),
            ))?;
        }
        area.draw(&Text::new(
            format!("{} (coldest)", celsius(coldest)),
            (x0, y0 - 6),
            text_style(style::LEGEND, HPos::Left, VPos::Bottom),
        ))?;
        area.draw(&Text::new(
            format!("{} (warmest)", celsius(warmest)),
            (x1, y0 - 6),
            text_style(style::LEGEND, HPos::Right, VPos::Bottom),
        ))?;
        // T_ref below the bar, with a longer tick, kept inside the panel
        // when it lies outside the measured range.
        let x = at(self.t_ref);
        area.draw(&PathElement::new(
            vec![(x, y0 - 2), (x, y1 + 14)],
            BLACK.stroke_width(2),
        ))?;
        let h = if x < x0 + 60 {
            HPos::Left
        } else if x > x1 - 60 {
            HPos::Right
        } else {
            HPos::Center
        };
        area.draw(&Text::new(
            format!("T_ref = {}", celsius(self.t_ref)),
            (x, y1 + 18),
            text_style(style::LEGEND, h, VPos::Top),
        ))?;
        area.draw(&Text::new(
            format!("{} isotherms, one tick each", isotherms.len()),
            (w / 2, y1 + 48),
            text_style(style::TICK_LABEL, HPos::Center, VPos::Top),
        ))?;
        Ok(())
    }
}
