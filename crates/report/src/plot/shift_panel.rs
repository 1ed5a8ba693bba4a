//! The shift-factor panel of the master-curve pictures (`rollfit master`
//! on frequency sweeps and on relaxation isotherms, and the joint fit's
//! master curve): log10 a_T against T, one marker per isotherm in its
//! colour — filled with a ±1σ bar where the overlap measured the shift,
//! hollow at the applied value where it did not — and the shift law as a
//! line. The legend sits in a strip under the plot, never inside it, so
//! that it cannot cover a marker or an error bar however the shifts fall;
//! it names the law and its constants with their standard errors:
//!
//! - WLF: log10 a_T = −C1 (T − T_ref)/(C2 + T − T_ref);
//! - Arrhenius: log10 a_T = E_a/(R ln 10) (1/T − 1/T_ref), T in K;
//! - WLF–Arrhenius: WLF above the junction T_g, Arrhenius below,
//!   continuous at T_g;
//! - free: the measured shifts, linear in T between isotherms.
//!
//! (Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., 1980, ch. 11.)

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};
use rollfit_fit::master::{ShiftFactors, ShiftLaw};
use rollfit_io::fit_dir::ShiftSummary;

use super::axes::linear_range;
use super::isotherm_key::{celsius, draw_colour_key, text_style};
use super::parts::runs;
use super::{DrawResult, draw_shift_mesh, style};

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

/// What the shift panel draws.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ShiftPanel<'a> {
    /// The shift factor of each isotherm.
    pub shifts: &'a [ShiftMarker],
    /// The law's curve (T °C, log10 a_T), densely; empty when none.
    pub curve: &'a [(f64, f64)],
    /// The legend's lines naming the law and its constants ([`law_legend`]);
    /// empty: the curve is called "fitted shift curve".
    pub law: &'a [String],
}

/// The legend of the hollow markers.
const UNDETERMINED_LABEL: &str = "not determined (value applied)";
/// The legend of the filled markers.
const MEASURED_LABEL: &str = "measured, ±1σ";
/// The legend of an unnamed curve.
const UNNAMED_CURVE: &str = "fitted shift curve";
/// Height of a legend line, px.
const LINE_HEIGHT: i32 = 20;
/// Indent of a legend line's text after its key, px.
const TEXT_INDENT: i32 = 40;

impl ShiftPanel<'_> {
    /// Whether there is a shift to show: at least two shift factors or a
    /// curve.
    pub(crate) fn has_shift(&self) -> bool {
        let measured = self
            .shifts
            .iter()
            .filter(|s| s.temperature.is_finite() && s.log_shift.is_finite())
            .count();
        measured >= 2
            || self
                .curve
                .iter()
                .any(|s| s.0.is_finite() && s.1.is_finite())
    }

    /// The legend's entries, top to bottom: the key and the text of each
    /// line (continuation lines of the law without a key).
    fn legend(&self, curve: bool, measured: bool, undetermined: bool) -> Vec<(Key, String)> {
        let mut lines = Vec::new();
        if curve {
            match self.law.split_first() {
                Some((first, rest)) => {
                    lines.push((Key::Line, first.clone()));
                    lines.extend(rest.iter().map(|l| (Key::None, l.clone())));
                }
                None => lines.push((Key::Line, UNNAMED_CURVE.to_string())),
            }
        } else if !self.law.is_empty() {
            // A law without a drawable curve (one isotherm, or a law that
            // diverges over the whole range) is still named.
            lines.extend(self.law.iter().map(|l| (Key::None, l.clone())));
        }
        if measured {
            lines.push((Key::Filled, MEASURED_LABEL.to_string()));
        }
        if undetermined {
            lines.push((Key::Hollow, UNDETERMINED_LABEL.to_string()));
        }
        lines
    }

    /// log10 a_T against T on `area`: the plot at the top, the legend in a
    /// strip under it.
    pub(crate) fn draw<DB>(
        &self,
        area: &DrawingArea<DB, Shift>,
        colour: &dyn Fn(f64) -> RGBColor,
        t_ref: f64,
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
        let bars: Vec<(f64, f64, f64)> = shown
            .iter()
            .filter(|s| s.determined && s.sigma.is_finite() && s.sigma > 0.0)
            .map(|s| (s.temperature, s.log_shift, s.sigma))
            .collect();
        let curve = runs(
            self.curve
                .iter()
                .map(|&(t, l)| (t.is_finite() && l.is_finite()).then_some((t, l))),
        );
        let legend = self.legend(
            !curve.is_empty(),
            !measured.is_empty(),
            !undetermined.is_empty(),
        );
        let (_, height) = area.dim_in_pixel();
        let strip = (LINE_HEIGHT * legend.len() as i32 + 20).min(height as i32 / 2);
        let (plot_area, legend_area) = area.split_vertically(height as i32 - strip);

        let x_range = linear_range(
            measured
                .iter()
                .chain(&undetermined)
                .chain(curve.iter().flatten())
                .map(|p| p.0)
                .chain([t_ref]),
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
        let mut chart = ChartBuilder::on(&plot_area)
            .margin(12)
            .caption("Shift factors a_T", ("sans-serif", style::CAPTION))
            .x_label_area_size(45)
            .y_label_area_size(60)
            .build_cartesian_2d(x_range, y_range)?;
        draw_shift_mesh(&mut chart, Some(6))?;
        for run in &curve {
            chart.draw_series(LineSeries::new(
                run.iter().copied(),
                style::WLF.stroke_width(2),
            ))?;
        }
        draw_bars(&mut chart, &bars)?;
        chart.draw_series(undetermined.iter().map(|&(t, l)| {
            EmptyElement::at((t, l))
                + Circle::new((0, 0), 5, WHITE.filled())
                + Circle::new((0, 0), 5, colour(t).stroke_width(2))
        }))?;
        chart.draw_series(measured.iter().map(|&(t, l)| {
            EmptyElement::at((t, l))
                + Circle::new((0, 0), 5, colour(t).filled())
                + Circle::new((0, 0), 5, BLACK.stroke_width(1))
        }))?;
        draw_legend_strip(&legend_area, &legend)
    }
}

/// The measured shifts' ±1σ bars, clipped to the axes: a bar of decades
/// on a poorly measured isotherm would otherwise flatten the plot.
fn draw_bars<'a, DB>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    bars: &[(f64, f64, f64)],
) -> DrawResult
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
{
    let (lo, hi) = (chart.y_range().start, chart.y_range().end);
    chart.draw_series(bars.iter().map(|&(t, l, sigma)| {
        ErrorBar::new_vertical(
            t,
            (l - sigma).max(lo),
            l,
            (l + sigma).min(hi),
            BLACK.stroke_width(1),
            8,
        )
    }))?;
    Ok(())
}

/// The key drawn before a legend line.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Key {
    /// The law's line.
    Line,
    /// A measured shift.
    Filled,
    /// An undetermined shift.
    Hollow,
    /// A continuation line.
    None,
}

/// The legend in its own strip, framed as the house style frames legends.
fn draw_legend_strip<DB>(area: &DrawingArea<DB, Shift>, lines: &[(Key, String)]) -> DrawResult
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    if lines.is_empty() {
        return Ok(());
    }
    let (w, _) = area.dim_in_pixel();
    let (x0, y0) = (14, 4);
    let bottom = y0 + LINE_HEIGHT * lines.len() as i32 + 10;
    area.draw(&Rectangle::new(
        [(x0, y0), (w as i32 - 14, bottom)],
        RGBColor(160, 160, 160).stroke_width(1),
    ))?;
    let text = text_style(style::LEGEND, HPos::Left, VPos::Center);
    for (i, (key, line)) in lines.iter().enumerate() {
        let y = y0 + 5 + LINE_HEIGHT * i as i32 + LINE_HEIGHT / 2;
        let x = x0 + 10;
        match key {
            Key::Line => area.draw(&PathElement::new(
                vec![(x, y), (x + 22, y)],
                style::WLF.stroke_width(2),
            ))?,
            Key::Filled => {
                area.draw(&Circle::new((x + 11, y), 5, style::MEASURED.filled()))?;
                area.draw(&Circle::new((x + 11, y), 5, BLACK.stroke_width(1)))?;
            }
            Key::Hollow => {
                area.draw(&Circle::new((x + 11, y), 5, WHITE.filled()))?;
                area.draw(&Circle::new(
                    (x + 11, y),
                    5,
                    style::MEASURED.stroke_width(2),
                ))?;
            }
            Key::None => {}
        }
        area.draw(&Text::new(
            line.clone(),
            (x0 + TEXT_INDENT, y),
            text.clone(),
        ))?;
    }
    Ok(())
}

/// The legend's lines naming the law `shift` applies and its constants
/// with their standard errors (two significant digits), e.g.
/// "WLF, T_ref = 20 °C" then "C1 = 8.86 ± 0.12, C2 = 101.6 ± 2.1 K"; for
/// free shifts what is drawn instead of a law. Empty for `auto` (never an
/// applied law).
pub fn law_legend(shift: &ShiftFactors) -> Vec<String> {
    let reference = format!("T_ref = {}", celsius(shift.t_ref));
    match shift.law {
        ShiftLaw::Wlf => shift.wlf.map_or_else(Vec::new, |w| {
            wlf_legend(&reference, (w.c1, w.c1_sigma), (w.c2, w.c2_sigma))
        }),
        ShiftLaw::Arrhenius => shift.arrhenius.map_or_else(Vec::new, |a| {
            arrhenius_legend(&reference, (a.activation_energy, a.activation_energy_sigma))
        }),
        ShiftLaw::WlfArrhenius => shift.wlf_arrhenius.map_or_else(Vec::new, |w| {
            vec![
                format!("WLF–Arrhenius, {reference}:"),
                format!(
                    "C1 = {}, C2 = {} K",
                    with_sigma(w.c1, w.sigma[0]),
                    with_sigma(w.c2, w.sigma[1])
                ),
                format!("above T_g = {}; below,", celsius(w.t_junction)),
                format!(
                    "E_a = {} kJ/mol",
                    with_sigma(w.activation_energy / 1e3, w.sigma[2] / 1e3)
                ),
            ]
        }),
        ShiftLaw::Free => vec![
            format!("free (measured), {reference}:"),
            "linear in T between isotherms".to_string(),
        ],
        ShiftLaw::Auto => Vec::new(),
    }
}

/// The legend of a fit's shift law as fit.json records it (WLF or
/// Arrhenius with their constants; free shifts, measured); empty for a
/// law fit.json does not name.
pub fn fitted_law_legend(shift: &ShiftSummary) -> Vec<String> {
    let reference = format!("T_ref = {}", celsius(shift.t_ref));
    let sigma = |s: Option<f64>| s.unwrap_or(f64::NAN);
    match (
        shift.model.as_str(),
        shift.c1,
        shift.c2,
        shift.activation_energy,
    ) {
        ("wlf", Some(c1), Some(c2), _) => wlf_legend(
            &reference,
            (c1, sigma(shift.c1_sigma)),
            (c2, sigma(shift.c2_sigma)),
        ),
        ("arrhenius", _, _, Some(ea)) => {
            arrhenius_legend(&reference, (ea, sigma(shift.activation_energy_sigma)))
        }
        ("free", ..) => vec![
            format!("free (measured), {reference}:"),
            "linear in T between temperatures".to_string(),
        ],
        _ => Vec::new(),
    }
}

/// "WLF, T_ref = …:" and its constants (value, 1σ), C2 in K.
fn wlf_legend(reference: &str, c1: (f64, f64), c2: (f64, f64)) -> Vec<String> {
    vec![
        format!("WLF, {reference}:"),
        format!(
            "C1 = {}, C2 = {} K",
            with_sigma(c1.0, c1.1),
            with_sigma(c2.0, c2.1)
        ),
    ]
}

/// "Arrhenius, T_ref = …:" and E_a (value, 1σ, J/mol) in kJ/mol.
fn arrhenius_legend(reference: &str, activation_energy: (f64, f64)) -> Vec<String> {
    vec![
        format!("Arrhenius, {reference}:"),
        format!(
            "E_a = {} kJ/mol",
            with_sigma(activation_energy.0 / 1e3, activation_energy.1 / 1e3)
        ),
    ]
}

/// "8.86 ± 0.12": the value to the decimals of its standard error's two
/// significant digits; a value too large or small for fixed decimals
/// (|x| ≥ 10⁵ or < 10⁻³) in scientific form; "± ?" where the error is not
/// defined.
fn with_sigma(value: f64, sigma: f64) -> String {
    let scientific = value != 0.0 && !(1e-3..1e5).contains(&value.abs());
    if scientific {
        return if sigma.is_finite() {
            format!("{value:.3e} ± {sigma:.1e}")
        } else {
            format!("{value:.3e} ± ?")
        };
    }
    if !sigma.is_finite() {
        return format!("{} ± ?", significant(value, 4));
    }
    if sigma == 0.0 {
        return format!("{} ± 0", significant(value, 4));
    }
    let decimals = (1 - sigma.abs().log10().floor() as i32).clamp(0, 6) as usize;
    format!("{value:.decimals$} ± {sigma:.decimals$}")
}

/// `value` to `digits` significant digits in fixed notation.
fn significant(value: f64, digits: i32) -> String {
    let magnitude = if value == 0.0 {
        0
    } else {
        value.abs().log10().floor() as i32
    };
    let decimals = (digits - 1 - magnitude).clamp(0, 8) as usize;
    format!("{value:.decimals$}")
}

/// The right column of the master-curve pictures: the shift panel (or,
/// without shifts, the note saying why) above the key to the isotherm
/// colours; `top` px for the panel.
pub(crate) fn draw_shift_column<DB>(
    area: &DrawingArea<DB, Shift>,
    top: u32,
    panel: &ShiftPanel,
    isotherms: &[f64],
    t_ref: f64,
    colour: &dyn Fn(f64) -> RGBColor,
) -> DrawResult
where
    DB: DrawingBackend,
    DB::ErrorType: 'static,
{
    let (shift_area, key_area) = area.split_vertically(top);
    if panel.has_shift() {
        panel.draw(&shift_area, colour, t_ref)?;
    } else {
        draw_no_shift_note(&shift_area, isotherms)?;
    }
    draw_colour_key(&key_area, isotherms, t_ref, colour)
}

/// A note in place of the shift panel, so that the empty corner is not
/// mistaken for a failed drawing.
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
    let style = text_style(style::LEGEND + 2, HPos::Center, VPos::Top);
    for (i, line) in note.iter().enumerate() {
        area.draw(&Text::new(
            line.clone(),
            (w as i32 / 2, 200 + 24 * i as i32),
            style.clone(),
        ))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_constant_keeps_the_decimals_of_its_error() {
        assert_eq!(with_sigma(8.8612, 0.1234), "8.86 ± 0.12");
        assert_eq!(with_sigma(101.63, 2.14), "101.6 ± 2.1");
        assert_eq!(with_sigma(152.3, 12.0), "152 ± 12");
        assert_eq!(with_sigma(1.9e11, 3.0e10), "1.900e11 ± 3.0e10");
        assert_eq!(with_sigma(17.25, f64::NAN), "17.25 ± ?");
        assert_eq!(with_sigma(17.25, 0.0), "17.25 ± 0");
    }
}
