//! The picture of a `rollfit forward` sweep: the friction coefficient μ(v)
//! the model predicts, on log–log axes, one solid line per temperature
//! (cold blue to warm red, in order of T; a single sweep in the house
//! colour of a computed μ). Each curve carries its low-speed asymptote,
//! Eqs. (18)/(19) (μ ∝ v), as a thin dashed line of the same colour, so the
//! reader sees where the full model leaves the linear law, and its friction
//! maximum as a filled marker with its value, which is what a sweep is
//! usually run to find.

use std::ops::Range;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::axes::{LogAxis, lg, log_axis, log_range};
use super::parts::{Pixel, dashed_key, legend_box, place_legend, plot_size, runs};
use super::{DrawResult, Figure, draw_legend, draw_mesh, format_tick, style};

/// How far beyond a curve's own μ range its asymptote is drawn, as a
/// factor on its largest μ (and a divisor on its smallest): the straight
/// line μ ∝ v rises without bound, and drawn in full it would set the
/// y range and squash the curves.
const ASYMPTOTE_REACH: f64 = 3.0;
/// Decades added above the data when the maximum is labelled on the plot,
/// so that its label stays inside.
const LABEL_HEADROOM: f64 = 0.3;
/// How many line samples a maximum's marker counts as when the legend's
/// corner is chosen: a hidden maximum loses the picture's main result.
const MAXIMUM_WEIGHT: usize = 25;
/// Width of the y label area and height of the x label area, px.
const Y_LABELS: u32 = 75;
const X_LABELS: u32 = 45;
/// Radius of the maximum's marker, px.
const MAXIMUM_RADIUS: i32 = 6;

/// One μ(v) curve of a sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepCurve {
    /// Temperature, °C, when the sweep set one (legend "20 °C"); None for a
    /// single sweep at the reference state.
    pub temperature: Option<f64>,
    /// Speeds, m/s, increasing.
    pub speeds: Vec<f64>,
    /// Friction coefficient μ at each speed.
    pub mu: Vec<f64>,
    /// The low-speed asymptote μ_low(v) at each speed (Eqs. 18/19: μ ∝ v at
    /// low speed), same length.
    pub mu_low_speed: Vec<f64>,
    /// The friction maximum (v, μ) when it lies inside the sweep: v in m/s.
    pub maximum: Option<(f64, f64)>,
}

/// μ(v) of a forward sweep, with asymptotes and maxima.
pub struct ForwardSweepFigure<'a> {
    /// The curves, in any order (drawn and listed in order of temperature).
    pub curves: &'a [SweepCurve],
    /// The chart's title.
    pub title: String,
}

/// `x` to `digits` significant digits in fixed notation (0.0213, 1.50).
pub(crate) fn significant(x: f64, digits: i32) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let decimals = (digits - 1 - x.abs().log10().floor() as i32).max(0) as usize;
    format!("{x:.decimals$}")
}

/// "μ_max = 0.0213 at 3.2e-2 m/s".
fn maximum_text((v, mu): (f64, f64)) -> String {
    format!("μ_max = {} at {v:.1e} m/s", significant(mu, 3))
}

/// "20 °C", or "μ(v)" for a sweep at the reference state.
fn curve_name(t: Option<f64>) -> String {
    match t {
        Some(t) => format!("{} °C", format_tick(t)),
        None => "μ(v)".into(),
    }
}

/// One curve ready to draw: log10 coordinates, colour and name.
struct Prepared {
    colour: RGBColor,
    name: String,
    /// Runs of (log10 v, log10 μ).
    mu: Vec<Vec<(f64, f64)>>,
    /// Runs of (log10 v, log10 μ_low) within the curve's reach.
    asymptote: Vec<Vec<(f64, f64)>>,
    /// (log10 v, log10 μ) of the maximum, with its text.
    maximum: Option<((f64, f64), String)>,
}

impl ForwardSweepFigure<'_> {
    /// The curves in order of temperature (a curve without one first, one
    /// with a non-finite temperature last).
    fn ordered(&self) -> Vec<&SweepCurve> {
        let mut curves: Vec<&SweepCurve> = self.curves.iter().collect();
        let key = |c: &SweepCurve| match c.temperature {
            None => f64::NEG_INFINITY,
            Some(t) if t.is_nan() => f64::INFINITY,
            Some(t) => t,
        };
        curves.sort_by(|a, b| key(a).total_cmp(&key(b)));
        curves
    }

    /// One colour per curve, in the order of [`Self::ordered`]: the house
    /// colour for a single curve, the cold-to-warm ramp by temperature when
    /// every curve has one, otherwise the qualitative palette.
    fn colours(curves: &[&SweepCurve]) -> Vec<RGBColor> {
        if curves.len() == 1 {
            return vec![style::FITTED];
        }
        let temperatures: Option<Vec<f64>> = curves
            .iter()
            .map(|c| c.temperature.filter(|t| t.is_finite()))
            .collect();
        match temperatures {
            Some(ts) => {
                let (lo, hi) = ts
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &t| {
                        (a.min(t), b.max(t))
                    });
                ts.iter()
                    .enumerate()
                    .map(|(i, &t)| {
                        // Equal temperatures (a repeated sweep) still get
                        // apart colours, by position.
                        let f = if hi > lo {
                            (t - lo) / (hi - lo)
                        } else {
                            i as f64 / (ts.len() - 1).max(1) as f64
                        };
                        style::cold_to_warm(f)
                    })
                    .collect()
            }
            None => (0..curves.len())
                .map(|i| style::SERIES[i % style::SERIES.len()])
                .collect(),
        }
    }

    fn prepare(&self) -> Vec<Prepared> {
        let curves = self.ordered();
        let colours = Self::colours(&curves);
        let several = curves.len() > 1;
        curves
            .iter()
            .zip(colours)
            .map(|(c, colour)| {
                let point = |i: usize, values: &[f64]| -> Option<(f64, f64)> {
                    Some((lg(*c.speeds.get(i)?)?, lg(*values.get(i)?)?))
                };
                let n = c.speeds.len();
                let mu = runs((0..n).map(|i| point(i, &c.mu)));
                let (lo, hi) = mu
                    .iter()
                    .flatten()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                        (a.min(p.1), b.max(p.1))
                    });
                let reach = ASYMPTOTE_REACH.log10();
                let asymptote = runs((0..n).map(|i| {
                    point(i, &c.mu_low_speed).filter(|p| p.1 >= lo - reach && p.1 <= hi + reach)
                }));
                let maximum = c.maximum.and_then(|(v, m)| {
                    let at = (lg(v)?, lg(m)?);
                    Some((at, maximum_text((v, m))))
                });
                let mut name = curve_name(c.temperature);
                if several && let Some((_, text)) = &maximum {
                    // Several labels on the plot would overlap: the
                    // numbers go into the legend instead.
                    name = format!("{name}: {text}");
                }
                Prepared {
                    colour,
                    name,
                    mu,
                    asymptote,
                    maximum,
                }
            })
            .collect()
    }
}

/// Where the single curve's maximum label goes: above the marker, and
/// kept inside the plot at either end of the speed axis. Returns the text
/// style (with its anchor) and the pixel offset from the marker.
fn maximum_label_place(at_x: f64, x_range: &Range<f64>) -> (TextStyle<'static>, Pixel) {
    let f = (at_x - x_range.start) / (x_range.end - x_range.start);
    let (h, dx) = if f < 0.25 {
        (HPos::Left, -MAXIMUM_RADIUS)
    } else if f > 0.75 {
        (HPos::Right, MAXIMUM_RADIUS)
    } else {
        (HPos::Center, 0)
    };
    let font = ("sans-serif", style::LEGEND)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(h, VPos::Bottom));
    (font, (dx, -MAXIMUM_RADIUS - 4))
}

impl Figure for ForwardSweepFigure<'_> {
    fn name(&self) -> &'static str {
        "forward"
    }

    fn caption(&self) -> String {
        if self.curves.is_empty() {
            return "No curves: the forward sweep gave no μ(v).".into();
        }
        let curves = self.ordered();
        let temperatures: Vec<String> = curves
            .iter()
            .filter_map(|c| c.temperature.map(|t| format!("{} °C", format_tick(t))))
            .collect();
        let what = match curves.len() {
            1 => "μ(v) of the forward sweep (solid)".to_string(),
            n if temperatures.len() == n => format!(
                "μ(v) of the forward sweep at {} (solid, cold blue to warm red)",
                temperatures.join(", ")
            ),
            n => format!("μ(v) of the forward sweep, {n} curves (solid)"),
        };
        let maximum = match (curves.as_slice(), curves.first().and_then(|c| c.maximum)) {
            ([_], Some(m)) => format!(" and the friction maximum, {}", maximum_text(m)),
            ([_], None) => " (no friction maximum inside the sweep)".into(),
            _ => " and each friction maximum (filled markers, values in the legend)".into(),
        };
        format!("{what}, the low-speed asymptote μ ∝ v (Eqs. 18/19, dashed){maximum}.")
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let prepared = self.prepare();
        let layout = Layout::of(&prepared, root.dim_in_pixel());
        let mut chart = ChartBuilder::on(root)
            .margin(12)
            .caption(&self.title, ("sans-serif", style::CAPTION))
            .x_label_area_size(X_LABELS)
            .y_label_area_size(Y_LABELS)
            .build_cartesian_2d(
                log_axis(layout.x_range.clone()),
                log_axis(layout.y_range.clone()),
            )?;
        draw_mesh(
            &mut chart,
            "rolling speed v (m/s)",
            "friction coefficient μ",
            true,
        )?;
        draw_curves(&mut chart, &prepared, layout.has_asymptote)?;
        draw_maxima(&mut chart, &layout, prepared.len() > 1)?;
        draw_legend(&mut chart, layout.legend_corner)?;
        Ok(())
    }
}

/// The axes' ranges, the maxima that can be drawn and where the legend goes.
struct Layout<'a> {
    x_range: Range<f64>,
    y_range: Range<f64>,
    /// (colour, (log10 v, log10 μ), text) of each maximum inside the sweep.
    maxima: Vec<(RGBColor, (f64, f64), &'a str)>,
    /// One curve with a maximum: its text is written beside it.
    labelled_on_plot: bool,
    has_asymptote: bool,
    legend_corner: SeriesLabelPosition,
}

impl<'a> Layout<'a> {
    fn of(prepared: &'a [Prepared], pixels: (u32, u32)) -> Self {
        let several = prepared.len() > 1;
        let all_points = || {
            prepared
                .iter()
                .flat_map(|p| p.mu.iter().chain(&p.asymptote).flatten())
                .copied()
        };
        let x_range = log_range(all_points().map(|p| 10f64.powf(p.0)), 0.2, -6.0..0.0);
        let mut y_range = log_range(
            all_points()
                .map(|p| p.1)
                .chain(
                    prepared
                        .iter()
                        .filter_map(|p| p.maximum.as_ref().map(|m| m.0.1)),
                )
                .map(|y| 10f64.powf(y)),
            0.1,
            -3.0..0.0,
        );
        // The maxima that can be drawn: inside the sweep's speeds.
        let maxima: Vec<(RGBColor, (f64, f64), &str)> = prepared
            .iter()
            .filter_map(|p| {
                p.maximum
                    .as_ref()
                    .map(|(at, text)| (p.colour, *at, text.as_str()))
            })
            .filter(|(_, at, _)| x_range.contains(&at.0) && y_range.contains(&at.1))
            .collect();
        let labelled_on_plot = !several && !maxima.is_empty();
        if labelled_on_plot {
            y_range.end += LABEL_HEADROOM;
        }
        let has_asymptote = prepared
            .iter()
            .any(|p| p.asymptote.iter().any(|r| r.len() > 1));

        // The legend goes where it hides nothing (or least): the maxima,
        // and the label above the single one, weigh as much as a stretch of
        // line.
        let entries = prepared.iter().filter(|p| !p.mu.is_empty()).count()
            + usize::from(has_asymptote)
            + usize::from(!maxima.is_empty());
        let longest = prepared
            .iter()
            .map(|p| p.name.chars().count())
            .chain(["low-speed asymptote (Eqs. 18/19)".len()])
            .max()
            .unwrap_or(0);
        let box_size = legend_box(
            plot_size(pixels, Y_LABELS, X_LABELS, true),
            entries,
            longest,
        );
        let weighted: Vec<((f64, f64), usize)> = all_points()
            .map(|p| (p, 1))
            .chain(maxima.iter().map(|m| (m.1, MAXIMUM_WEIGHT)))
            .collect();
        let legend = place_legend(&weighted, &x_range, &y_range, box_size);
        Layout {
            x_range,
            y_range: legend.y,
            maxima,
            labelled_on_plot,
            has_asymptote,
            legend_corner: legend.corner,
        }
    }
}

/// The chart of μ against v, both axes logarithmic.
type SweepChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<LogAxis, LogAxis>>;

/// The asymptotes, then the curves on top where they meet, and one legend
/// entry for all asymptotes: in the curve's colour when there is one curve,
/// neutral when each curve has its own.
fn draw_curves<'a, DB>(
    chart: &mut SweepChart<'a, DB>,
    prepared: &[Prepared],
    has_asymptote: bool,
) -> DrawResult
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
{
    for p in prepared {
        for run in p.asymptote.iter().filter(|r| r.len() > 1) {
            chart.draw_series(DashedLineSeries::new(
                run.iter().copied(),
                6,
                4,
                p.colour.stroke_width(1),
            ))?;
        }
    }
    for p in prepared {
        let colour = p.colour;
        for (i, run) in p.mu.iter().enumerate() {
            let series =
                chart.draw_series(LineSeries::new(run.iter().copied(), colour.stroke_width(2)))?;
            if i == 0 {
                series.label(p.name.clone()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                });
            }
        }
    }
    if has_asymptote {
        let key = if prepared.len() > 1 {
            style::MEASURED
        } else {
            prepared[0].colour
        };
        chart
            .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())?
            .label("low-speed asymptote (Eqs. 18/19)")
            .legend(move |at| dashed_key(at, key, 1));
    }
    Ok(())
}

/// The friction maxima as filled circles, with the value written beside a
/// single one.
fn draw_maxima<'a, DB>(chart: &mut SweepChart<'a, DB>, layout: &Layout, several: bool) -> DrawResult
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
{
    let maxima = &layout.maxima;
    if maxima.is_empty() {
        return Ok(());
    }
    let key = if several {
        style::MEASURED
    } else {
        maxima[0].0
    };
    chart
        .draw_series(maxima.iter().map(|&(c, at, _)| {
            EmptyElement::at(at)
                + Circle::new((0, 0), MAXIMUM_RADIUS, c.filled())
                + Circle::new((0, 0), MAXIMUM_RADIUS, BLACK.stroke_width(1))
        }))?
        .label("friction maximum")
        .legend(move |(x, y)| {
            EmptyElement::at((x + 10, y))
                + Circle::new((0, 0), MAXIMUM_RADIUS, key.filled())
                + Circle::new((0, 0), MAXIMUM_RADIUS, BLACK.stroke_width(1))
        });
    if layout.labelled_on_plot {
        let (_, at, text) = maxima[0];
        let (font, offset) = maximum_label_place(at.0, &layout.x_range);
        chart.draw_series(std::iter::once(
            EmptyElement::at(at) + Text::new(text.to_string(), offset, font),
        ))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_maximum_reads_with_three_significant_digits() {
        assert_eq!(
            maximum_text((0.0316, 0.021_34)),
            "μ_max = 0.0213 at 3.2e-2 m/s"
        );
        assert_eq!(significant(1.5, 3), "1.50");
        assert_eq!(significant(f64::NAN, 3), "NaN");
    }
}
