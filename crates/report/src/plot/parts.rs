//! Small parts shared by the forward-sweep, DMA-master and joint pictures:
//! lines broken where a value cannot be drawn, a dashed legend key, the
//! choice of the legend's corner, and isotherms' E′ and E″ markers in their
//! temperature's colour.

use std::ops::Range;

use plotters::element::ComposedElement;
use plotters::prelude::*;

use super::axes::LogAxis;
use super::{DrawResult, SeriesLabelPosition, style};

/// A pixel position, plotters' backend coordinate.
pub(crate) type Pixel = (i32, i32);

/// The runs of consecutive points that a log–log plot can show: a point
/// that is missing (None) ends a run, so a line is broken there instead of
/// being drawn across the gap.
pub(crate) fn runs(points: impl IntoIterator<Item = Option<(f64, f64)>>) -> Vec<Vec<(f64, f64)>> {
    let mut runs = Vec::new();
    let mut current = Vec::new();
    for p in points {
        match p {
            Some(p) => current.push(p),
            None if !current.is_empty() => runs.push(std::mem::take(&mut current)),
            None => {}
        }
    }
    if !current.is_empty() {
        runs.push(current);
    }
    runs
}

/// A legend key of three dashes, as [`dashed_key`] builds it.
pub(crate) type DashedKey<DB> = ComposedElement<
    Pixel,
    DB,
    PathElement<Pixel>,
    ComposedElement<Pixel, DB, PathElement<Pixel>, PathElement<Pixel>>,
>;

/// A dashed line as a legend key at (x, y), the pixel position plotters
/// gives a legend entry; `width` px thick.
pub(crate) fn dashed_key<DB: DrawingBackend>(
    (x, y): Pixel,
    colour: RGBColor,
    width: u32,
) -> DashedKey<DB> {
    EmptyElement::at((x, y))
        + PathElement::new(vec![(0, 0), (6, 0)], colour.stroke_width(width))
        + PathElement::new(vec![(10, 0), (16, 0)], colour.stroke_width(width))
        + PathElement::new(vec![(20, 0), (24, 0)], colour.stroke_width(width))
}

/// Mean width of a legend character at [`super::style::LEGEND`] px, to
/// size the legend box before plotters draws it.
const LEGEND_CHAR_WIDTH: f64 = 7.5;

/// The size of a legend box as fractions of a plot of `plot` px (width,
/// height), about: its key and margins, `longest` characters of label, 22
/// px a line for `entries` lines and the frame.
pub(crate) fn legend_box(plot: (u32, u32), entries: usize, longest: usize) -> (f64, f64) {
    let width = 45.0 + LEGEND_CHAR_WIDTH * longest as f64;
    let height = 22.0 * entries as f64 + 16.0;
    (
        width / f64::from(plot.0.max(1)),
        height / f64::from(plot.1.max(1)),
    )
}

/// The plot area of a chart built in the house style on an area of
/// `area` px (width, height): the chart's margin of 12 px all round, the
/// label areas (`y_labels` px wide at the left, `x_labels` px high below)
/// and the caption's line when there is one. Needed before the chart is
/// built, to choose its y range.
pub(crate) fn plot_size(
    area: (u32, u32),
    y_labels: u32,
    x_labels: u32,
    caption: bool,
) -> (u32, u32) {
    let caption = if caption {
        super::style::CAPTION + 16
    } else {
        0
    };
    (
        area.0.saturating_sub(y_labels + 24).max(1),
        area.1.saturating_sub(x_labels + 24 + caption).max(1),
    )
}

/// Where a chart's legend goes, and the y range that leaves room for it.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct LegendPlace {
    /// The legend's corner.
    pub corner: SeriesLabelPosition,
    /// The y range to build the chart with: the given one, or raised.
    pub y: Range<f64>,
}

/// The corner where a legend box of `box_size` (width, height as fractions
/// of the plot) covers none of `points` (x, y in chart coordinates, each
/// with a weight: a marker that must stay visible weighs more than one
/// sample of a line), or the least of them. Legends sit inside the plot in
/// the house style; this puts them where the data are not. When every
/// corner would hide data the y range is raised by the box's height and the
/// legend goes to the upper left, over an empty strip: a little less
/// resolution is better than a hidden curve. Ties go to the upper left,
/// then upper right, lower left, lower right.
pub(crate) fn place_legend(
    points: &[((f64, f64), usize)],
    x: &Range<f64>,
    y: &Range<f64>,
    box_size: (f64, f64),
) -> LegendPlace {
    // (right, upper) of each corner, in the order of preference.
    let corners = [(false, true), (true, true), (false, false), (true, false)];
    let mut covered = [0usize; 4];
    let span = |r: &Range<f64>| (r.end - r.start).max(f64::MIN_POSITIVE);
    for &((px, py), weight) in points {
        let fx = (px - x.start) / span(x);
        let fy = (py - y.start) / span(y);
        if !(fx.is_finite() && fy.is_finite()) {
            continue;
        }
        for (k, &(right, upper)) in corners.iter().enumerate() {
            let in_x = if right {
                fx >= 1.0 - box_size.0
            } else {
                fx <= box_size.0
            };
            let in_y = if upper {
                fy >= 1.0 - box_size.1
            } else {
                fy <= box_size.1
            };
            if in_x && in_y {
                covered[k] += weight;
            }
        }
    }
    let best = (0..4).min_by_key(|&k| (covered[k], k)).unwrap_or(0);
    if covered[best] == 0 {
        let corner = match best {
            1 => SeriesLabelPosition::UpperRight,
            2 => SeriesLabelPosition::LowerLeft,
            3 => SeriesLabelPosition::LowerRight,
            _ => SeriesLabelPosition::UpperLeft,
        };
        return LegendPlace {
            corner,
            y: y.clone(),
        };
    }
    // Raise the top so that the box's height is above every point; never
    // by more than the data's own height.
    let h = box_size.1.clamp(0.0, 0.5);
    LegendPlace {
        corner: SeriesLabelPosition::UpperLeft,
        y: y.start..(y.end + span(y) * h / (1.0 - h)),
    }
}

/// The temperatures of `points`, °C, increasing, each once (non-finite
/// ones left out): the isotherms.
pub(crate) fn isotherms(points: impl Iterator<Item = f64>) -> Vec<f64> {
    let mut ts: Vec<f64> = points.filter(|t| t.is_finite()).collect();
    ts.sort_by(f64::total_cmp);
    ts.dedup();
    ts
}

/// (log10 x, y, colour) of a point drawn in its isotherm's colour.
pub(crate) type ColouredPoint = (f64, f64, RGBColor);

/// E′ as filled circles and E″ as open triangles, each point in its
/// isotherm's colour, with their legend `labels` (E′, E″) keyed in the
/// measured colour: the markers of the DMA master curve, wherever its
/// points are drawn.
pub(crate) fn draw_storage_loss<'a, DB, Y>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<LogAxis, Y>>,
    storage: &[ColouredPoint],
    loss: &[ColouredPoint],
    labels: (String, String),
) -> DrawResult
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
    Y: Ranged<ValueType = f64>,
{
    chart
        .draw_series(
            storage
                .iter()
                .map(|&(x, y, c)| Circle::new((x, y), 3, c.filled())),
        )?
        .label(labels.0)
        .legend(|(x, y)| Circle::new((x + 10, y), 4, style::MEASURED.filled()));
    chart
        .draw_series(
            loss.iter()
                .map(|&(x, y, c)| TriangleMarker::new((x, y), 5, c.stroke_width(1))),
        )?
        .label(labels.1)
        .legend(|(x, y)| TriangleMarker::new((x + 10, y), 5, style::MEASURED.stroke_width(1)));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_break_at_missing_points() {
        let r = runs([
            None,
            Some((0.0, 1.0)),
            Some((1.0, 2.0)),
            None,
            None,
            Some((3.0, 4.0)),
        ]);
        assert_eq!(r, vec![vec![(0.0, 1.0), (1.0, 2.0)], vec![(3.0, 4.0)]]);
        assert!(runs([None, None]).is_empty());
    }

    #[test]
    fn the_legend_goes_where_the_data_are_not() {
        let range = 0.0..1.0;
        let place = |points: &[(f64, f64)]| {
            let weighted: Vec<_> = points.iter().map(|&p| (p, 1)).collect();
            place_legend(&weighted, &range, &range, (0.4, 0.3))
        };
        assert_eq!(place(&[]).corner, SeriesLabelPosition::UpperLeft);
        let p = place(&[(0.1, 0.9), (0.9, 0.1)]);
        assert_eq!(p.corner, SeriesLabelPosition::UpperRight);
        assert_eq!(p.y, range);
        let p = place(&[(0.1, 0.9), (0.9, 0.9), (0.9, 0.1)]);
        assert_eq!(p.corner, SeriesLabelPosition::LowerLeft);
        // Every corner taken: the top is raised so that the upper 30 % of
        // the new range is above the data.
        let p = place(&[(0.1, 0.9), (0.9, 0.9), (0.1, 0.1), (0.9, 0.1)]);
        assert_eq!(p.corner, SeriesLabelPosition::UpperLeft);
        let top = 0.9 / p.y.end;
        assert!(
            (p.y.end - 1.0 / 0.7).abs() < 1e-12 && top < 0.7,
            "{:?}",
            p.y
        );
    }

    #[test]
    fn a_chart_plot_is_its_area_less_labels_margins_and_caption() {
        assert_eq!(plot_size((900, 620), 75, 45, false), (801, 551));
        let with_caption = plot_size((900, 620), 75, 45, true);
        assert_eq!(with_caption.1, 551 - super::super::style::CAPTION - 16);
        assert_eq!(plot_size((10, 10), 75, 45, true), (1, 1));
    }
}
