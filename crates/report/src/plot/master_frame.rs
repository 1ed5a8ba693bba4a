//! The frame the two master-curve pictures share (frequency sweeps,
//! [`super::dma_master`], and relaxation isotherms,
//! [`super::relaxation_master`]): a verdict that is not "good" as a banner
//! across the top ([`super::verdict_banner`]), the shift panel above the
//! isotherm colour key in a right column ([`super::shift_panel`]), and a
//! left column of two panels that each picture fills with its own curves.
//! Every isotherm has one colour in all of them
//! ([`super::isotherm_key`]).

use std::error::Error;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::isotherm_key::isotherm_colour;
use super::shift_panel::{ShiftPanel, draw_shift_column};
use super::verdict_banner::Verdict;

/// Width of the left column, px.
pub(crate) const LEFT_WIDTH: u32 = 740;
/// Height of the upper left panel and of the shift panel, px.
pub(crate) const TOP_HEIGHT: u32 = 520;

/// The picture's size: 1100 × 800 px and the banner's height.
pub(crate) fn size(verdict: Option<&Verdict>) -> (u32, u32) {
    (1100, 800 + Verdict::height(verdict))
}

/// The colour of each isotherm of `isotherms` (°C, increasing): cold to
/// warm from the first to the last; `t_ref`'s colour when there are none.
pub(crate) fn palette(isotherms: &[f64], t_ref: f64) -> impl Fn(f64) -> RGBColor + use<> {
    let coldest = isotherms.first().copied().unwrap_or(t_ref);
    let warmest = isotherms.last().copied().unwrap_or(t_ref);
    move |t: f64| isotherm_colour(t, coldest, warmest)
}

/// The two panels of the left column (upper, lower).
pub(crate) type LeftPanels<DB> = (DrawingArea<DB, Shift>, DrawingArea<DB, Shift>);

/// Draws the banner and the right column on `root` and returns the left
/// column's two panels for the picture's own curves.
pub(crate) fn draw<DB>(
    root: &DrawingArea<DB, Shift>,
    verdict: Option<&Verdict>,
    panel: &ShiftPanel,
    isotherms: &[f64],
    t_ref: f64,
    colour: &dyn Fn(f64) -> RGBColor,
) -> Result<LeftPanels<DB>, Box<dyn Error>>
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    let (banner, root) = root.split_vertically(Verdict::height(verdict));
    if let Some(verdict) = verdict {
        verdict.draw(&banner)?;
    }
    let (left, right) = root.split_horizontally(LEFT_WIDTH);
    draw_shift_column(&right, TOP_HEIGHT, panel, isotherms, t_ref, colour)?;
    Ok(left.split_vertically(TOP_HEIGHT))
}
