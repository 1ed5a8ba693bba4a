//! The pictures of a fit, each drawn once per backend: PNG (rasterised with
//! the embedded DejaVu Sans, so no system font is needed) and SVG (text as
//! `<text>` elements in the generic "sans-serif" family, which every viewer
//! has).
//!
//! Every picture is a [`Figure`]: it knows its file stem, its size and how
//! to draw itself on any plotters backend, so the PNG and the SVG cannot
//! differ in content. Logarithmic quantities are plotted as their log10 on
//! linear axes whose ticks sit on whole decades and are labelled 10ⁿ (see
//! [`axes`]).

pub mod axes;
pub mod convergence;
pub mod dma_master;
pub mod forward_sweep;
pub mod friction;
mod isotherm_key;
pub mod joint_master;
pub mod joint_residuals;
mod marker_density;
pub mod master_curve;
mod master_frame;
mod parts;
pub mod pressure_map;
pub mod relaxation_master;
pub mod shift_panel;
pub mod spectrum;
pub mod speed_accuracy;
pub mod style;
pub mod temperature_set;
pub mod van_gurp_palmen;
pub mod verdict_banner;

use std::error::Error;
use std::sync::Once;

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use crate::error::ReportError;

/// Legend corners, for callers that place a chart's legend.
pub use plotters::chart::SeriesLabelPosition;

/// What a figure's drawing returns: plotters' errors differ per backend.
pub type DrawResult = Result<(), Box<dyn Error>>;

/// A picture that can draw itself on any backend.
pub trait Figure {
    /// File stem: the picture is written as `<name>.png` and `<name>.svg`.
    fn name(&self) -> &'static str;
    /// One-line description, used as the HTML caption.
    fn caption(&self) -> String;
    /// Width and height, pixels.
    fn size(&self) -> (u32, u32) {
        (900, 620)
    }
    /// Draws the picture on `root` (already filled white).
    fn draw<DB>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static;
}

/// A rendered picture.
#[derive(Debug, Clone)]
pub struct Picture {
    /// File stem.
    pub name: &'static str,
    /// One-line description.
    pub caption: String,
    /// Width and height, pixels.
    pub size: (u32, u32),
    /// The PNG file's bytes.
    pub png: Vec<u8>,
    /// The SVG document.
    pub svg: String,
}

/// Renders `figure` to PNG and SVG.
pub fn render(figure: &impl Figure) -> Result<Picture, ReportError> {
    register_fonts();
    let name = figure.name();
    let fail = |message: String| ReportError::Plot {
        name: name.to_string(),
        message,
    };
    let (width, height) = figure.size();

    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| fail(e.to_string()))?;
        figure.draw(&root).map_err(|e| fail(e.to_string()))?;
        root.present().map_err(|e| fail(e.to_string()))?;
    }

    let mut pixels = vec![0u8; width as usize * height as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| fail(e.to_string()))?;
        figure.draw(&root).map_err(|e| fail(e.to_string()))?;
        root.present().map_err(|e| fail(e.to_string()))?;
    }
    let png = encode_png(&pixels, width, height).map_err(|e| fail(e.to_string()))?;

    Ok(Picture {
        name,
        caption: figure.caption(),
        size: (width, height),
        png,
        svg,
    })
}

fn encode_png(rgb: &[u8], width: u32, height: u32) -> Result<Vec<u8>, png::EncodingError> {
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, width, height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        // The default deflate level with Paeth filtering: about 8 ms a
        // picture and a fifth of the fast level's size (20–40 kB instead of
        // 100–200 kB), which keeps the committed examples small.
        encoder.set_compression(png::Compression::Default);
        encoder.set_filter(png::FilterType::Paeth);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(rgb)?;
    }
    Ok(bytes)
}

/// Registers the embedded DejaVu Sans as plotters' "sans-serif" once per
/// process: without a registered font the bitmap backend cannot draw text
/// on a machine without system fonts (docs/ARCHITECTURE.md, "Crates").
fn register_fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        for (style, bytes) in [
            (FontStyle::Normal, dejavu::sans::regular()),
            (FontStyle::Bold, dejavu::sans::bold()),
            (FontStyle::Italic, dejavu::sans::oblique()),
        ] {
            // The bytes are a valid TrueType font compiled into the binary;
            // a failure here would be a broken build, caught by every test.
            if plotters::style::register_font("sans-serif", style, bytes).is_err() {
                panic!("the embedded DejaVu Sans font could not be parsed");
            }
        }
    });
}

/// The mesh of a chart whose axes are both [`axes::LogAxis`] or a log x and
/// a linear y: labels, descriptions and light grid in the house style.
pub(crate) fn draw_mesh<DB, Y>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<axes::LogAxis, Y>>,
    x_description: &str,
    y_description: &str,
    y_log: bool,
) -> DrawResult
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
    Y: plotters::coord::ranged1d::Ranged<ValueType = f64>
        + plotters::coord::ranged1d::ValueFormatter<f64>,
{
    let log_label = |v: &f64| axes::decade_label(v);
    let plain_label = |v: &f64| format_tick(*v);
    let mut mesh = chart.configure_mesh();
    mesh.x_desc(x_description)
        .y_desc(y_description)
        .x_label_formatter(&log_label)
        .label_style(("sans-serif", style::TICK_LABEL))
        .axis_desc_style(("sans-serif", style::AXIS_DESCRIPTION))
        .bold_line_style(RGBColor(200, 200, 200))
        .light_line_style(RGBColor(236, 236, 236));
    if y_log {
        mesh.y_label_formatter(&log_label);
    } else {
        // A linear y axis gets plotters' own ticks but no light lines: on a
        // small residual panel they would fill it.
        mesh.y_label_formatter(&plain_label).y_max_light_lines(0);
    }
    mesh.draw()?;
    Ok(())
}

/// The mesh of a shift-factor chart, log10 a_T against T on linear axes,
/// in the house style; `x_labels` caps the temperature ticks (None:
/// plotters' own count).
pub(crate) fn draw_shift_mesh<DB>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    x_labels: Option<usize>,
) -> DrawResult
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    let plain_label = |v: &f64| format_tick(*v);
    let mut mesh = chart.configure_mesh();
    mesh.x_desc("T (°C)")
        .y_desc("log₁₀ a_T")
        .x_label_formatter(&plain_label)
        .y_label_formatter(&plain_label);
    if let Some(n) = x_labels {
        mesh.x_labels(n);
    }
    mesh.label_style(("sans-serif", style::TICK_LABEL))
        .axis_desc_style(("sans-serif", style::AXIS_DESCRIPTION))
        .bold_line_style(RGBColor(200, 200, 200))
        .light_line_style(RGBColor(236, 236, 236))
        .max_light_lines(0)
        .draw()?;
    Ok(())
}

/// A tick label for a linear axis: no trailing zeros, no "-0".
pub(crate) fn format_tick(v: f64) -> String {
    let v = if v.abs() < 1e-12 { 0.0 } else { v };
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

/// The legend box in the house style.
pub(crate) fn draw_legend<'a, DB, X, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    position: SeriesLabelPosition,
) -> DrawResult
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
    X: plotters::coord::ranged1d::Ranged,
    Y: plotters::coord::ranged1d::Ranged,
{
    chart
        .configure_series_labels()
        .position(position)
        .label_font(("sans-serif", style::LEGEND))
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(160, 160, 160))
        .draw()?;
    Ok(())
}

/// The pictures of a joint fit of DMA and rolling data, which the page
/// shows in their own section.
pub const JOINT_PICTURES: [&str; 2] = ["joint_master", "joint_residuals"];

/// Every picture of a fit, in reading order: friction, master curve,
/// spectrum, convergence, for a temperature set the master friction
/// curve and the shift, and for a joint fit with DMA data the joint master
/// curve and the residuals of both parts ([`JOINT_PICTURES`]). `dma` holds DMA points at the reference state;
/// `line` is the fitted μ(v) friction.png draws
/// ([`crate::fitted_friction::FittedLine::of`]).
pub fn pictures(
    fit: &rollfit_io::FitDir,
    dma: &[master_curve::DmaMarker],
    line: &crate::fitted_friction::FittedLine,
) -> Result<Vec<Picture>, ReportError> {
    let mut pictures = vec![
        render(&friction::FrictionFigure { fit, line })?,
        render(&master_curve::MasterCurveFigure { fit, dma })?,
        render(&spectrum::SpectrumFigure { fit })?,
        render(&convergence::ConvergenceFigure { fit })?,
    ];
    if fit.is_temperature_set() {
        pictures.push(render(&temperature_set::MasterFrictionFigure { fit })?);
        pictures.push(render(&temperature_set::ShiftFigure { fit })?);
    }
    if let Some(joint) = &fit.summary.joint {
        pictures.push(render(&joint_master::JointMasterFigure::of(fit, joint))?);
        pictures.push(render(&joint_residuals::JointResidualsFigure {
            fit,
            joint,
        })?);
    }
    Ok(pictures)
}
