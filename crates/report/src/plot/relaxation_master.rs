//! The picture `rollfit master` draws for stress-relaxation isotherms
//! (master.png, master.svg): the isotherms E(t) shifted to the reduced
//! time t_r = t/a_T at the reference temperature, every point in its
//! isotherm's colour (cold blue to warm red, as the frequency-sweep
//! master picture colours them), with the Prony series
//! E(t_r) = E0 + Σ_k H_k exp(−t_r/τ_k) fitted to them as a black line.
//! Below it the misfit of each point, log10 E/E_Prony in decades: E(t)
//! has no second component to test superposition with (tan δ for a
//! frequency sweep), so an isotherm that does not join its neighbours
//! shows as a band of its colour off zero. At the right the shift factors
//! with the law and its constants ([`super::shift_panel`]) and the key to
//! the colours; a verdict that is not "good" is the picture's title
//! ([`super::verdict_banner`]). Shear data (G(t)) are drawn as G. Creep
//! isotherms are drawn the same way as their compliance D(t) (or shear
//! J(t)), 1/Pa, with the series' exact creep compliance as the line.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::axes::{lg, linear_range, log_axis, log_range};
use super::isotherm_key::celsius;
use super::marker_density::drawn_points;
use super::master_frame;
use super::parts::{isotherms, legend_box, place_legend, plot_size, runs};
use super::shift_panel::{ShiftMarker, ShiftPanel};
use super::verdict_banner::Verdict;
use super::{DrawResult, Figure, draw_legend, draw_mesh, style};

/// The least half-height of the misfit panel, decades: the log misfit of
/// 2 % scatter (0.009), the low end of what relaxation instruments give.
const MIN_MISFIT_AXIS: f64 = 0.01;

/// One relaxation point after shifting.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShiftedRelaxation {
    /// Reduced time t/a_T, s.
    pub reduced_time: f64,
    /// Relaxation modulus E(t) (or G(t)), divided by b_T, Pa; or creep
    /// compliance D(t) (or J(t)) times b_T, 1/Pa.
    pub modulus: f64,
    /// The fitted series at the point's reduced time, Pa (1/Pa).
    pub fitted: f64,
    /// Temperature of the point's isotherm, °C.
    pub temperature: f64,
}

/// Shifted relaxation isotherms, the Prony series and the shift factors.
pub struct RelaxationMasterFigure<'a> {
    /// The shifted points of every isotherm.
    pub points: &'a [ShiftedRelaxation],
    /// The Prony series (t_r s, E Pa), densely over the points' reduced
    /// times.
    pub series: &'a [(f64, f64)],
    /// Reference temperature, °C.
    pub t_ref: f64,
    /// The shift factor of each isotherm.
    pub shifts: &'a [ShiftMarker],
    /// The law's shift curve (T °C, log10 a_T), densely; empty when none.
    pub shift_curve: &'a [(f64, f64)],
    /// The legend's lines naming the law and its constants.
    pub shift_law: &'a [String],
    /// "E" (Young's modulus) or "G" (shear modulus); "D" (tensile) or
    /// "J" (shear) of a creep compliance.
    pub modulus_symbol: &'static str,
    /// Creep isotherms: the values are compliances, 1/Pa.
    pub creep: bool,
    /// The verdict, in the title when it is not "good".
    pub verdict: Option<Verdict<'a>>,
}

impl RelaxationMasterFigure<'_> {
    /// The title's word and the unit of the values.
    fn words(&self) -> (&'static str, &'static str) {
        if self.creep {
            ("Creep", "1/Pa")
        } else {
            ("Relaxation", "Pa")
        }
    }

    fn isotherms(&self) -> Vec<f64> {
        isotherms(self.points.iter().map(|p| p.temperature))
    }

    fn shift_panel(&self) -> ShiftPanel<'_> {
        ShiftPanel {
            shifts: self.shifts,
            curve: self.shift_curve,
            law: self.shift_law,
        }
    }
}

impl Figure for RelaxationMasterFigure<'_> {
    fn name(&self) -> &'static str {
        "master"
    }

    fn caption(&self) -> String {
        let s = self.modulus_symbol;
        let n = self.isotherms().len();
        format!(
            "{} master curve from {n} isotherm{} at T_ref = {}: {s}(t/a_T) coloured by temperature with the fitted Prony series (black), each point's misfit log10 {s}/{s}_Prony below, the shift factors at the right.",
            self.words().0,
            if n == 1 { "" } else { "s" },
            celsius(self.t_ref)
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
        let drawn = drawn_points(self.points, |p| p.temperature);
        let x_range = log_range(
            drawn
                .iter()
                .map(|p| p.reduced_time)
                .chain(self.series.iter().map(|s| s.0)),
            0.2,
            -2.0..3.0,
        );
        self.draw_modulus(&upper, &drawn, &x_range, &colour)?;
        self.draw_misfit(&lower, &drawn, &x_range, &colour)
    }
}

impl RelaxationMasterFigure<'_> {
    fn x_description(&self) -> String {
        format!("reduced time t/a_T (s), T_ref = {}", celsius(self.t_ref))
    }

    /// log E against log t/a_T: the points and the series.
    fn draw_modulus<DB>(
        &self,
        area: &DrawingArea<DB, Shift>,
        drawn: &[&ShiftedRelaxation],
        x_range: &std::ops::Range<f64>,
        colour: &dyn Fn(f64) -> RGBColor,
    ) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let s = self.modulus_symbol;
        let points: Vec<(f64, f64, RGBColor)> = drawn
            .iter()
            .filter_map(|p| Some((lg(p.reduced_time)?, lg(p.modulus)?, colour(p.temperature))))
            .collect();
        let series = runs(self.series.iter().map(|&(t, e)| Some((lg(t)?, lg(e)?))));
        let y_range = log_range(
            points
                .iter()
                .map(|p| p.1)
                .chain(series.iter().flatten().map(|p| p.1))
                .map(|y| 10f64.powf(y)),
            0.15,
            4.0..9.0,
        );
        let points_label = format!("{s}(t/a_T), per isotherm");
        let samples: Vec<((f64, f64), usize)> = points
            .iter()
            .map(|p| ((p.0, p.1), 1))
            .chain(series.iter().flatten().map(|&p| (p, 1)))
            .collect();
        let box_size = legend_box(
            plot_size(area.dim_in_pixel(), 75, 45, true),
            2,
            points_label.chars().count(),
        );
        let legend = place_legend(&samples, x_range, &y_range, box_size);
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .caption(
                format!(
                    "{} master curve at T_ref = {}",
                    self.words().0,
                    celsius(self.t_ref)
                ),
                ("sans-serif", style::CAPTION),
            )
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(log_axis(x_range.clone()), log_axis(legend.y))?;
        draw_mesh(
            &mut chart,
            &self.x_description(),
            &format!("{s}(t) ({})", self.words().1),
            true,
        )?;
        chart
            .draw_series(
                points
                    .iter()
                    .map(|&(x, y, c)| Circle::new((x, y), 3, c.filled())),
            )?
            .label(points_label)
            .legend(|(x, y)| Circle::new((x + 10, y), 4, style::MEASURED.filled()));
        for (i, run) in series.iter().enumerate() {
            let line =
                chart.draw_series(LineSeries::new(run.iter().copied(), BLACK.stroke_width(2)))?;
            if i == 0 {
                line.label(format!("Prony {s}(t)")).legend(|(x, y)| {
                    PathElement::new(vec![(x, y), (x + 24, y)], BLACK.stroke_width(2))
                });
            }
        }
        draw_legend(&mut chart, legend.corner)
    }

    /// log10 E/E_Prony of each point, decades, with the zero line.
    fn draw_misfit<DB>(
        &self,
        area: &DrawingArea<DB, Shift>,
        drawn: &[&ShiftedRelaxation],
        x_range: &std::ops::Range<f64>,
        colour: &dyn Fn(f64) -> RGBColor,
    ) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let s = self.modulus_symbol;
        let misfits: Vec<(f64, f64, RGBColor)> = drawn
            .iter()
            .filter_map(|p| {
                let d = lg(p.modulus)? - lg(p.fitted)?;
                Some((lg(p.reduced_time)?, d, colour(p.temperature)))
            })
            .collect();
        // At least ±MIN_MISFIT_AXIS: a series within the scatter of real
        // data shows as flat, not as noise magnified to fill the panel.
        let y_range = linear_range(
            misfits
                .iter()
                .map(|p| p.1)
                .chain([-MIN_MISFIT_AXIS, MIN_MISFIT_AXIS]),
            0.15,
        );
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(75)
            .build_cartesian_2d(log_axis(x_range.clone()), y_range)?;
        draw_mesh(
            &mut chart,
            &self.x_description(),
            &format!("log₁₀ {s}/{s}_Prony"),
            false,
        )?;
        chart.draw_series(LineSeries::new(
            [(x_range.start, 0.0), (x_range.end, 0.0)],
            BLACK.stroke_width(2),
        ))?;
        chart.draw_series(
            misfits
                .iter()
                .map(|&(x, y, c)| Circle::new((x, y), 3, c.filled())),
        )?;
        Ok(())
    }
}
