//! The van Gurp–Palmen plot `rollfit master` draws next to the master
//! curve (vgp.png, vgp.svg): the phase angle
//!
//! δ = atan(E″/E′)  (degrees)
//!
//! of every measured point against its dynamic modulus
//!
//! |E*| = √(E′² + E″²)  (Pa, log axis),
//!
//! each isotherm in its temperature's colour (the master picture's) and
//! its points joined in order of |E*|. Neither coordinate involves the
//! frequency, so no shift enters: where time–temperature superposition
//! holds (a thermorheologically simple material) every isotherm lies on
//! one curve, and an isotherm that leaves the common curve shows where no
//! horizontal shift can superpose it — the test of superposition that
//! does not assume it. Vertical factors b_T, which divide E′ and E″ alike,
//! would move points along |E*|; the points are drawn as measured,
//! without them. The Prony series fitted to the master curve is drawn in
//! the same coordinates (black), the curve a simple material's isotherms
//! would follow.
//!
//! # References
//! - M. van Gurp, J. Palmen, "Time–temperature superposition for polymeric
//!   blends", Rheology Bulletin 67 (1998) 5–8.
//! - S. Trinkle, C. Friedrich, "Van Gurp–Palmen plot: a way to characterize
//!   polydispersity of linear polymers", Rheol. Acta 40 (2001) 322–328.

use std::ops::Range;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::axes::{lg, linear_range, log_axis, log_range};
use super::dma_master::MasterCurveFit;
use super::isotherm_key::{celsius, draw_colour_key, text_style};
use super::marker_density::drawn_points;
use super::master_frame;
use super::parts::{isotherms, legend_box, place_legend, plot_size, runs};
use super::{DrawResult, Figure, draw_legend, draw_mesh, style};

/// Height of the colour key, px.
const KEY_HEIGHT: u32 = 200;

/// One measured DMA point, as read (no shift, no vertical factor).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeasuredPoint {
    /// Storage modulus E′ (or G′), Pa.
    pub storage: f64,
    /// Loss modulus E″ (or G″), Pa.
    pub loss: f64,
    /// Temperature of the point's isotherm, °C.
    pub temperature: f64,
}

impl MeasuredPoint {
    /// (log10 |E*|, δ in degrees), None where E′ or E″ is not positive and
    /// finite.
    fn plane(&self) -> Option<(f64, f64)> {
        plane(self.storage, self.loss)
    }
}

/// (log10 |E*|, δ°) of E′ and E″, None where either is not positive and
/// finite.
fn plane(storage: f64, loss: f64) -> Option<(f64, f64)> {
    if !(storage > 0.0 && loss > 0.0 && storage.is_finite() && loss.is_finite()) {
        return None;
    }
    Some((lg(storage.hypot(loss))?, loss.atan2(storage).to_degrees()))
}

/// The van Gurp–Palmen plot of a run's isotherms.
pub struct VanGurpPalmenFigure<'a> {
    /// Every measured point.
    pub points: &'a [MeasuredPoint],
    /// The Prony series of the master curve (drawn as δ against |E*|);
    /// empty: none.
    pub fit: &'a MasterCurveFit,
    /// Reference temperature of the series, °C (the colour key marks it).
    pub t_ref: f64,
    /// "E" (Young's modulus) or "G" (shear modulus): what the labels say.
    pub modulus_symbol: &'static str,
}

impl VanGurpPalmenFigure<'_> {
    fn isotherms(&self) -> Vec<f64> {
        isotherms(self.points.iter().map(|p| p.temperature))
    }

    /// Each isotherm's points in the plane, in order of |E*|, with its
    /// temperature.
    fn isotherm_paths(&self) -> Vec<(f64, Vec<(f64, f64)>)> {
        let drawn = drawn_points(self.points, |p| p.temperature);
        self.isotherms()
            .into_iter()
            .map(|t| {
                let mut path: Vec<(f64, f64)> = drawn
                    .iter()
                    .filter(|p| p.temperature == t)
                    .filter_map(|p| p.plane())
                    .collect();
                path.sort_by(|a, b| a.0.total_cmp(&b.0));
                (t, path)
            })
            .collect()
    }

    /// The series' runs in the plane.
    fn series(&self) -> Vec<Vec<(f64, f64)>> {
        let fit = self.fit;
        runs((0..fit.omega.len()).map(|i| plane(*fit.storage.get(i)?, *fit.loss.get(i)?)))
    }
}

impl Figure for VanGurpPalmenFigure<'_> {
    fn name(&self) -> &'static str {
        "vgp"
    }

    fn caption(&self) -> String {
        let s = self.modulus_symbol;
        let n = self.isotherms().len();
        format!(
            "van Gurp–Palmen plot of {n} DMA isotherm{}: phase angle δ = atan({s}″/{s}′) against |{s}*|, as measured (no shift applied), coloured by temperature, with the master curve's Prony series (black); where time–temperature superposition holds the isotherms fall on one curve.",
            if n == 1 { "" } else { "s" }
        )
    }

    fn size(&self) -> (u32, u32) {
        (1100, 640)
    }

    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let isotherms = self.isotherms();
        let colour = master_frame::palette(&isotherms, self.t_ref);
        let (left, right) = root.split_horizontally(master_frame::LEFT_WIDTH);
        let (key_area, note_area) = right.split_vertically(KEY_HEIGHT);
        self.draw_plane(&left, &colour)?;
        draw_colour_key(&key_area, &isotherms, self.t_ref, &colour)?;
        self.draw_note(&note_area)
    }
}

impl VanGurpPalmenFigure<'_> {
    /// δ against log10 |E*|: the isotherms and the series.
    fn draw_plane<DB>(
        &self,
        area: &DrawingArea<DB, Shift>,
        colour: &dyn Fn(f64) -> RGBColor,
    ) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let s = self.modulus_symbol;
        let paths = self.isotherm_paths();
        let series = self.series();
        let all = || {
            paths
                .iter()
                .flat_map(|(_, p)| p.iter())
                .chain(series.iter().flatten())
        };
        let x_range = log_range(all().map(|p| 10f64.powf(p.0)), 0.1, 5.0..9.0);
        let y_range = degrees_range(all().map(|p| p.1));
        let points_label = "per isotherm, as measured";
        let samples: Vec<((f64, f64), usize)> = all().map(|&p| (p, 1)).collect();
        let box_size = legend_box(
            plot_size(area.dim_in_pixel(), 65, 45, true),
            2,
            points_label.chars().count(),
        );
        let legend = place_legend(&samples, &x_range, &y_range, box_size);
        let mut chart = ChartBuilder::on(area)
            .margin(12)
            .caption(
                "van Gurp–Palmen plot (no shift applied)",
                ("sans-serif", style::CAPTION),
            )
            .x_label_area_size(45)
            .y_label_area_size(65)
            .build_cartesian_2d(log_axis(x_range), legend.y)?;
        draw_mesh(
            &mut chart,
            &format!("|{s}*| = √({s}′² + {s}″²) (Pa)"),
            "phase angle δ (°)",
            false,
        )?;
        for (t, path) in &paths {
            let c = colour(*t);
            chart.draw_series(LineSeries::new(path.iter().copied(), c.stroke_width(1)))?;
        }
        chart
            .draw_series(paths.iter().flat_map(|(t, path)| {
                let c = colour(*t);
                path.iter().map(move |&p| Circle::new(p, 3, c.filled()))
            }))?
            .label(points_label)
            .legend(|(x, y)| Circle::new((x + 10, y), 4, style::MEASURED.filled()));
        for (i, run) in series.iter().enumerate() {
            let line =
                chart.draw_series(LineSeries::new(run.iter().copied(), BLACK.stroke_width(2)))?;
            if i == 0 {
                line.label(format!("Prony series at T_ref = {}", celsius(self.t_ref)))
                    .legend(|(x, y)| {
                        PathElement::new(vec![(x, y), (x + 24, y)], BLACK.stroke_width(2))
                    });
            }
        }
        draw_legend(&mut chart, legend.corner)
    }

    /// How to read the plot, under the colour key.
    fn draw_note<DB>(&self, area: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let s = self.modulus_symbol;
        let lines = [
            "Frequency is not an axis of this plot,".to_string(),
            "so no shift enters: every isotherm is".to_string(),
            format!("drawn as measured (δ and |{s}*| alone)."),
            String::new(),
            "Where time–temperature superposition".to_string(),
            "holds, the isotherms fall on one curve.".to_string(),
            "An isotherm off the common curve is".to_string(),
            "thermorheologically complex there: no".to_string(),
            "horizontal shift superposes it.".to_string(),
        ];
        let style = text_style(style::LEGEND, HPos::Left, VPos::Top);
        for (i, line) in lines.iter().enumerate() {
            area.draw(&Text::new(
                line.clone(),
                (30, 20 + 22 * i as i32),
                style.clone(),
            ))?;
        }
        Ok(())
    }
}

/// The phase-angle axis: the data's range padded, within 0…90°.
fn degrees_range(values: impl Iterator<Item = f64>) -> Range<f64> {
    let range = linear_range(values, 0.06);
    let (lo, hi) = (range.start.max(0.0), range.end.min(90.0));
    if hi > lo { lo..hi } else { 0.0..90.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plane_is_the_phase_angle_against_the_dynamic_modulus() {
        // E′ = E″: δ = 45°, |E*| = √2 E′.
        let (x, d) = plane(1e6, 1e6).unwrap();
        assert!((d - 45.0).abs() < 1e-12);
        assert!((x - (2e12f64).sqrt().log10()).abs() < 1e-12);
        // tan δ = √3: 60°.
        let (_, d) = plane(1.0, 3f64.sqrt()).unwrap();
        assert!((d - 60.0).abs() < 1e-9);
        assert!(plane(0.0, 1.0).is_none() && plane(1.0, -1.0).is_none());
        assert!(plane(f64::NAN, 1.0).is_none());
    }
}
