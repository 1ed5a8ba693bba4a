//! Picture 2: the recovered master curve. Above, E′ and E″ against ω
//! (log–log); below, tan δ against ω. The window the data determine is
//! shaded and the curve is drawn solid inside it and dashed outside, where
//! it is only the extrapolation of the Prony series; the 1σ bands of
//! modulus.csv are filled around the curves; DMA points (already shifted to
//! the fit's reference state) go on top when given.

use std::ops::Range;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::{lg, log_axis, log_range};
use super::{DrawResult, Figure, draw_legend, draw_mesh, style};
use num_complex::Complex64;
use rollfit_io::fit_dir::FitDir;

/// Decades drawn beyond each end of the window.
const OUTSIDE_DECADES: f64 = 2.0;
/// Points of the drawn curve.
const CURVE_POINTS: usize = 240;

/// A curve as (log10 x, log10 y) points.
type Curve = Vec<(f64, f64)>;

/// One DMA point at the reference state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DmaMarker {
    /// Reduced angular frequency ω·a_T, rad/s.
    pub omega: f64,
    /// E′, Pa (Young's).
    pub storage: f64,
    /// E″, Pa (Young's).
    pub loss: f64,
}

/// E′, E″ and tan δ against ω.
pub struct MasterCurveFigure<'a> {
    /// The fit.
    pub fit: &'a FitDir,
    /// DMA points at the reference state, if any.
    pub dma: &'a [DmaMarker],
}

struct Sample {
    lg_omega: f64,
    modulus: Complex64,
}

impl MasterCurveFigure<'_> {
    /// The log10 ω range drawn: the window plus the extrapolation, widened
    /// to the DMA points.
    fn omega_range(&self) -> Range<f64> {
        let w = self.fit.summary.window;
        let lo = w.omega_min.log10() - OUTSIDE_DECADES;
        let hi = w.omega_max.log10() + OUTSIDE_DECADES;
        let dma = self.dma.iter().filter_map(|p| lg(p.omega));
        let (lo, hi) = dma.fold((lo, hi), |(a, b), x| (a.min(x), b.max(x)));
        (lo - 0.1)..(hi + 0.1)
    }

    fn samples(&self, range: &Range<f64>) -> Vec<Sample> {
        (0..CURVE_POINTS)
            .map(|i| {
                let lg_omega =
                    range.start + (range.end - range.start) * i as f64 / (CURVE_POINTS - 1) as f64;
                Sample {
                    lg_omega,
                    modulus: self.fit.modulus_at(10f64.powf(lg_omega)),
                }
            })
            .collect()
    }

    /// The title: the reference temperature of a temperature set, and a
    /// scale the data leave undetermined (E′ and E″ then only up to a
    /// common factor), so that the picture copied alone says both.
    pub fn title(&self) -> String {
        let s = &self.fit.summary;
        let mut title = "Recovered master curve E*(ω)".to_string();
        if let Some(shift) = &s.shift {
            title += &format!(" at T_ref = {} °C", super::format_tick(shift.t_ref));
        }
        if s.anchor.is_none() && s.scale.as_ref().is_some_and(|c| !c.is_determined()) {
            title += " — scale undetermined";
        }
        title
    }

    fn in_window(&self, lg_omega: f64) -> bool {
        let w = self.fit.summary.window;
        lg_omega >= w.omega_min.log10() - 1e-9 && lg_omega <= w.omega_max.log10() + 1e-9
    }
}

/// Draws `curve` (x, y) solid inside the window and dashed outside.
fn draw_curve<DB>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<super::axes::LogAxis, super::axes::LogAxis>>,
    curve: &[(f64, f64)],
    inside: impl Fn(f64) -> bool,
    colour: RGBColor,
    label: &str,
) -> DrawResult
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    let solid: Vec<(f64, f64)> = curve.iter().copied().filter(|p| inside(p.0)).collect();
    let (below, above): (Curve, Curve) = curve
        .iter()
        .copied()
        .filter(|p| !inside(p.0))
        .partition(|p| solid.first().is_none_or(|s| p.0 < s.0));
    for part in [below, above] {
        if part.len() > 1 {
            chart.draw_series(DashedLineSeries::new(part, 6, 4, colour.stroke_width(1)))?;
        }
    }
    chart
        .draw_series(LineSeries::new(solid, colour.stroke_width(3)))?
        .label(label)
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(3)));
    Ok(())
}

/// Fills the band between `lower` and `upper` (x, y pairs on one x grid).
fn draw_band<DB>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<super::axes::LogAxis, super::axes::LogAxis>>,
    lower: &[(f64, f64)],
    upper: &[(f64, f64)],
    colour: RGBColor,
) -> DrawResult
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    if lower.len() < 2 {
        return Ok(());
    }
    let outline: Vec<(f64, f64)> = upper.iter().chain(lower.iter().rev()).copied().collect();
    chart.draw_series(std::iter::once(Polygon::new(
        outline,
        colour.mix(0.25).filled(),
    )))?;
    Ok(())
}

/// The window as a shaded rectangle over the whole height.
fn shade_window<DB>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<super::axes::LogAxis, super::axes::LogAxis>>,
    fit: &FitDir,
    y: &Range<f64>,
    with_label: bool,
) -> DrawResult
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    let w = fit.summary.window;
    let series = chart.draw_series(std::iter::once(Rectangle::new(
        [(w.omega_min.log10(), y.start), (w.omega_max.log10(), y.end)],
        style::WINDOW.filled(),
    )))?;
    if with_label {
        series
            .label("window the data determine")
            .legend(|(x, y)| Rectangle::new([(x, y - 6), (x + 20, y + 6)], style::WINDOW.filled()));
    }
    Ok(())
}

impl Figure for MasterCurveFigure<'_> {
    fn name(&self) -> &'static str {
        "master_curve"
    }

    fn caption(&self) -> String {
        let w = self.fit.summary.window;
        let mut text = format!(
            "Recovered master curve: E′, E″ (top) and tan δ (bottom); the shaded window {:.3e}–{:.3e} rad/s is what the data determine (solid), outside is extrapolation (dashed); bands are ±1σ",
            w.omega_min, w.omega_max
        );
        if !self.dma.is_empty() {
            text.push_str(&format!("; {} DMA points on top", self.dma.len()));
        }
        if let Some(shift) = &self.fit.summary.shift {
            text.push_str(&format!(
                " (reference temperature {} °C)",
                super::format_tick(shift.t_ref)
            ));
        }
        if let Some(scale) = self
            .fit
            .summary
            .scale
            .as_ref()
            .filter(|c| !c.is_determined())
        {
            text.push_str(&format!(
                "; the data do not determine the modulus scale (scale {}): E′ and E″ are known only up to a common factor",
                scale.status
            ));
        }
        text + "."
    }

    fn size(&self) -> (u32, u32) {
        (900, 820)
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let x_range = self.omega_range();
        let panels = self.panels(&x_range);
        let (upper_area, lower_area) = root.split_vertically(470);
        self.draw_moduli(&upper_area, &panels, &x_range)?;
        self.draw_tan_delta(&lower_area, &panels, &x_range)
    }
}

/// What the two panels draw, as (log10 ω, log10 value): the fitted curves,
/// their 1σ bands (lower, upper) and the DMA points inside the ω range.
struct Panels {
    storage: Curve,
    loss: Curve,
    tan_delta: Curve,
    storage_band: (Curve, Curve),
    loss_band: (Curve, Curve),
    tan_band: (Curve, Curve),
    dma_storage: Curve,
    dma_loss: Curve,
    dma_tan: Curve,
}

/// A value of a modulus.csv row and its 1σ, if any.
type WithSigma = dyn Fn(&rollfit_io::fit_dir::ModulusRow) -> (f64, Option<f64>);

impl MasterCurveFigure<'_> {
    fn panels(&self, x_range: &Range<f64>) -> Panels {
        let samples = self.samples(x_range);
        let curve = |value: &dyn Fn(Complex64) -> f64| -> Curve {
            samples
                .iter()
                .filter_map(|s| lg(value(s.modulus)).map(|y| (s.lg_omega, y)))
                .collect()
        };
        let dma = |value: &dyn Fn(&DmaMarker) -> f64| -> Curve {
            self.dma
                .iter()
                .filter_map(|p| Some((lg(p.omega)?, lg(value(p))?)))
                .filter(|p| x_range.contains(&p.0))
                .collect()
        };
        Panels {
            storage: curve(&|e| e.re),
            loss: curve(&|e| e.im),
            tan_delta: curve(&|e| e.im / e.re),
            storage_band: self.band(&|r| (r.storage, r.storage_sigma)),
            loss_band: self.band(&|r| (r.loss, r.loss_sigma)),
            tan_band: self.band(&|r| (r.tan_delta, r.tan_delta_sigma)),
            dma_storage: dma(&|p| p.storage),
            dma_loss: dma(&|p| p.loss),
            dma_tan: dma(&|p| p.loss / p.storage),
        }
    }

    /// (lower, upper) edges of the 1σ band of a modulus.csv quantity.
    fn band(&self, value: &WithSigma) -> (Curve, Curve) {
        let mut lower = Vec::new();
        let mut upper = Vec::new();
        for r in &self.fit.modulus {
            let (v, s) = value(r);
            if let Some(s) = s
                && let Some(hi) = lg(v + s.abs())
            {
                let x = r.omega.log10();
                upper.push((x, hi));
                lower.push((x, lg(v - s.abs()).unwrap_or(f64::NEG_INFINITY)));
            }
        }
        (lower, upper)
    }

    /// E′ and E″ with their bands, and the DMA points.
    fn draw_moduli<DB>(
        &self,
        area: &DrawingArea<DB, Shift>,
        panels: &Panels,
        x_range: &Range<f64>,
    ) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let y_moduli = log_range(
            panels
                .storage
                .iter()
                .chain(&panels.loss)
                .chain(&panels.dma_storage)
                .chain(&panels.dma_loss)
                .map(|p| 10f64.powf(p.1)),
            0.15,
            4.0..9.0,
        );
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .caption(self.title(), ("sans-serif", style::CAPTION))
            .x_label_area_size(40)
            .y_label_area_size(75)
            .build_cartesian_2d(log_axis(x_range.clone()), log_axis(y_moduli.clone()))?;
        shade_window(&mut chart, self.fit, &y_moduli, true)?;
        draw_mesh(&mut chart, "ω (rad/s)", "E′, E″ (Pa)", true)?;
        let (lower, upper) = clip(&panels.storage_band, &y_moduli);
        draw_band(&mut chart, &lower, &upper, style::STORAGE)?;
        let (lower, upper) = clip(&panels.loss_band, &y_moduli);
        draw_band(&mut chart, &lower, &upper, style::LOSS)?;
        let inside = |x: f64| self.in_window(x);
        draw_curve(
            &mut chart,
            &panels.storage,
            inside,
            style::STORAGE,
            "E′ (storage)",
        )?;
        draw_curve(&mut chart, &panels.loss, inside, style::LOSS, "E″ (loss)")?;
        if !panels.dma_storage.is_empty() {
            draw_dma_squares(&mut chart, &panels.dma_storage, style::STORAGE, "DMA E′")?;
            chart
                .draw_series(panels.dma_loss.iter().map(|&p| {
                    EmptyElement::at(p)
                        + TriangleMarker::new((0, 0), 6, style::LOSS.filled())
                        + TriangleMarker::new((0, 0), 6, style::DMA.stroke_width(1))
                }))?
                .label("DMA E″")
                .legend(|(x, y)| {
                    EmptyElement::at((x + 10, y))
                        + TriangleMarker::new((0, 0), 6, style::LOSS.filled())
                        + TriangleMarker::new((0, 0), 6, style::DMA.stroke_width(1))
                });
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperLeft)
    }

    /// tan δ with its band, and the DMA points.
    fn draw_tan_delta<DB>(
        &self,
        area: &DrawingArea<DB, Shift>,
        panels: &Panels,
        x_range: &Range<f64>,
    ) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let y_tan = log_range(
            panels
                .tan_delta
                .iter()
                .chain(&panels.dma_tan)
                .map(|p| 10f64.powf(p.1)),
            0.15,
            -2.0..0.0,
        );
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(log_axis(x_range.clone()), log_axis(y_tan.clone()))?;
        shade_window(&mut chart, self.fit, &y_tan, false)?;
        draw_mesh(&mut chart, "ω (rad/s)", "tan δ", true)?;
        let (lower, upper) = clip(&panels.tan_band, &y_tan);
        draw_band(&mut chart, &lower, &upper, style::TAN_DELTA)?;
        draw_curve(
            &mut chart,
            &panels.tan_delta,
            |x: f64| self.in_window(x),
            style::TAN_DELTA,
            "tan δ = E″/E′",
        )?;
        if !panels.dma_tan.is_empty() {
            draw_dma_squares(&mut chart, &panels.dma_tan, style::TAN_DELTA, "DMA tan δ")?;
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperLeft)
    }
}

/// A band's edges clipped to the y range, so that the filled polygon stays
/// inside the plot.
fn clip(band: &(Curve, Curve), y: &Range<f64>) -> (Curve, Curve) {
    let (lower, upper) = band;
    let lower = lower.iter().map(|&(x, v)| (x, v.max(y.start))).collect();
    let upper = upper.iter().map(|&(x, v)| (x, v.min(y.end))).collect();
    (lower, upper)
}

/// DMA points as squares filled in the quantity's colour.
fn draw_dma_squares<'a, DB>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<super::axes::LogAxis, super::axes::LogAxis>>,
    points: &[(f64, f64)],
    colour: RGBColor,
    label: &str,
) -> DrawResult
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
{
    chart
        .draw_series(points.iter().map(|&p| {
            EmptyElement::at(p)
                + Rectangle::new([(-4, -4), (4, 4)], colour.filled())
                + Rectangle::new([(-4, -4), (4, 4)], style::DMA.stroke_width(1))
        }))?
        .label(label)
        .legend(move |(x, y)| {
            EmptyElement::at((x + 10, y))
                + Rectangle::new([(-4, -4), (4, 4)], colour.filled())
                + Rectangle::new([(-4, -4), (4, 4)], style::DMA.stroke_width(1))
        });
    Ok(())
}
