//! The isotherm colours of the master-curve pictures and their key: every
//! point is drawn in the colour of its isotherm's temperature on one
//! cold-to-warm scale (blue to red, [`style::cold_to_warm`]) from the
//! coldest to the warmest isotherm, so that the master curve, the van
//! Gurp–Palmen plot and the shift panel of one run colour an isotherm
//! alike. The key is a bar from the coldest to the warmest temperature
//! with a tick per isotherm, labelled at both ends and at T_ref.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::{DrawResult, format_tick, style};

/// Slices of the colour key's gradient bar.
const KEY_SLICES: i32 = 120;

/// The colour of an isotherm at `t` °C between the coldest and the warmest.
pub(crate) fn isotherm_colour(t: f64, coldest: f64, warmest: f64) -> RGBColor {
    if warmest > coldest {
        style::cold_to_warm((t - coldest) / (warmest - coldest))
    } else {
        style::cold_to_warm(0.5)
    }
}

/// Black sans-serif text of `size` px anchored at (`h`, `v`).
pub(crate) fn text_style(size: u32, h: HPos, v: VPos) -> TextStyle<'static> {
    ("sans-serif", size)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(h, v))
}

/// "20 °C".
pub(crate) fn celsius(t: f64) -> String {
    format!("{} °C", format_tick(t))
}

/// The key to the isotherm colours on `area` (at least about 330 px wide):
/// a bar from the coldest to the warmest of `isotherms` (°C, increasing)
/// with a tick per isotherm, labelled at both ends and at `t_ref`; one
/// swatch for a single isotherm.
pub(crate) fn draw_colour_key<DB>(
    area: &DrawingArea<DB, Shift>,
    isotherms: &[f64],
    t_ref: f64,
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
        let b =
            x0 + ((f64::from(i + 1) / f64::from(KEY_SLICES)) * f64::from(x1 - x0)).ceil() as i32;
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
    // T_ref below the bar, with a longer tick, kept inside the panel when
    // it lies outside the measured range.
    let x = at(t_ref);
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
        format!("T_ref = {}", celsius(t_ref)),
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
