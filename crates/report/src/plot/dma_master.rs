//! The picture `rollfit master` writes: DMA isotherms shifted by their
//! factors a_T onto one master curve at the reference temperature, with the
//! Prony series fitted to it. Top left, log E′ (filled circles) and log E″
//! (open triangles) against the reduced frequency ω a_T, every point in the
//! colour of its isotherm (cold blue to warm red), so that an isotherm that
//! does not join its neighbours shows at once, and the Prony E′ and E″ as
//! black solid and dashed lines; below it tan δ = E″/E′, the most sensitive
//! test of the superposition (it does not depend on a vertical shift), of
//! the points and of the Prony curve. At the right, log10 a_T against T per
//! isotherm with the law's curve, named with its constants in a legend
//! under the panel ([`super::shift_panel`]), and under it the key to the
//! colours: the coldest, the reference and the warmest temperature. A
//! single isotherm has nothing to shift: its panel says so. A verdict that
//! is not "good" is the picture's title ([`super::verdict_banner`]).
//! Shear data are drawn as G′ and G″, the moduli of the file (the caller
//! divides the Young's moduli by 2(1+ν) and says "G").

use std::ops::Range;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::{lg, log_axis, log_range};
use super::isotherm_key::celsius;
use super::marker_density::drawn_points;
use super::master_frame;
use super::parts::{
    ColouredPoint, dashed_key, draw_storage_loss, isotherms, legend_box, place_legend, plot_size,
    runs,
};
pub use super::shift_panel::ShiftMarker;
use super::shift_panel::ShiftPanel;
pub use super::verdict_banner::Verdict;
use super::{DrawResult, Figure, draw_legend, draw_mesh, style};

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
    /// The law's shift curve (T °C, log10 a_T), densely; empty when none.
    pub shift_curve: &'a [(f64, f64)],
    /// The legend's lines naming the law and its constants
    /// ([`super::shift_panel::law_legend`]); empty: "fitted shift curve".
    pub shift_law: &'a [String],
    /// "E" (Young's modulus) or "G" (shear modulus): what the axis labels say.
    pub modulus_symbol: &'static str,
    /// The verdict, in the title when it is not "good"; None: none given.
    pub verdict: Option<Verdict<'a>>,
}

impl DmaMasterFigure<'_> {
    /// The isotherms' temperatures, °C, increasing, each once.
    fn isotherms(&self) -> Vec<f64> {
        isotherms(self.points.iter().map(|p| p.temperature))
    }

    /// The shift panel's content.
    fn shift_panel(&self) -> ShiftPanel<'_> {
        ShiftPanel {
            shifts: self.shifts,
            curve: self.shift_curve,
            law: self.shift_law,
        }
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

impl Figure for DmaMasterFigure<'_> {
    fn name(&self) -> &'static str {
        "master"
    }

    fn caption(&self) -> String {
        let s = self.modulus_symbol;
        let n = self.isotherms().len();
        let shift = if self.shift_panel().has_shift() {
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
        master_frame::size(self.verdict.as_ref())
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let isotherms = self.isotherms();
        let colour = master_frame::palette(&isotherms, self.t_ref);
        let (upper, lower) = master_frame::draw(
            root,
            self.verdict.as_ref(),
            &self.shift_panel(),
            &isotherms,
            self.t_ref,
            &colour,
        )?;
        let curves = Curves::of(self, &colour);
        self.draw_moduli(&upper, &curves)?;
        self.draw_tan_delta(&lower, &curves)
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
