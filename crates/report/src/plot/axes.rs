//! Logarithmic axes: quantities spanning decades are plotted as their
//! log10 on a linear axis whose labelled ticks sit on whole decades and read
//! 10ⁿ, with light lines at 2…9 × 10ⁿ when few decades are shown. Doing the
//! log ourselves (rather than plotters' log coordinate) gives decade ticks
//! at any span and keeps shading, bands and markers in one coordinate.

use std::ops::Range;

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};
use plotters::coord::types::RangedCoordf64;

/// A log10 axis: a linear coordinate in log10 of the quantity with its own
/// tick positions. (plotters' `with_key_points` wrapper would do, but it
/// loses the value formatter that the mesh needs for f64 axes.)
#[derive(Clone)]
pub struct LogAxis {
    inner: RangedCoordf64,
    decades: Vec<f64>,
    minor: Vec<f64>,
}

impl LogAxis {
    /// The labelled ticks (log10 values).
    pub fn bold_points(&self) -> &[f64] {
        &self.decades
    }

    /// The unlabelled light ticks (log10 values).
    pub fn light_points(&self) -> &[f64] {
        &self.minor
    }
}

impl Ranged for LogAxis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.inner.map(value, limit)
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.minor.clone()
        } else {
            self.decades.clone()
        }
    }

    fn range(&self) -> Range<f64> {
        self.inner.range()
    }
}

/// The log10 range covering `values` (positive ones only), padded by
/// `pad` decades each side; `fallback` when there is none.
pub fn log_range(
    values: impl IntoIterator<Item = f64>,
    pad: f64,
    fallback: Range<f64>,
) -> Range<f64> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values {
        if v > 0.0 && v.is_finite() {
            lo = lo.min(v.log10());
            hi = hi.max(v.log10());
        }
    }
    if !lo.is_finite() {
        return fallback;
    }
    if hi - lo < 0.5 {
        let mid = 0.5 * (lo + hi);
        lo = mid - 0.25;
        hi = mid + 0.25;
    }
    (lo - pad)..(hi + pad)
}

/// A linear range covering `values`, padded by `pad` of its span.
pub fn linear_range(values: impl IntoIterator<Item = f64>, pad: f64) -> Range<f64> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values {
        if v.is_finite() {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    if !lo.is_finite() {
        return -1.0..1.0;
    }
    let span = if hi > lo { hi - lo } else { lo.abs().max(1.0) };
    (lo - pad * span)..(hi + pad * span)
}

/// The axis for a log10 range: bold ticks on decades (every 1, 2, 3 … so
/// that at most about 9 are labelled; also at 2 and 5 × 10ⁿ when fewer
/// than 2.5 decades are shown, so a short axis still has numbers), light
/// ones at 2…9 × 10ⁿ when at most 6 decades are shown.
pub fn log_axis(range: Range<f64>) -> LogAxis {
    let span = range.end - range.start;
    let step = (span / 9.0).ceil().max(1.0) as i32;
    let first = range.start.floor() as i32;
    let last = range.end.ceil() as i32;
    let mantissas: &[f64] = if span < 2.5 { &[1.0, 2.0, 5.0] } else { &[1.0] };
    let decades: Vec<f64> = (first..=last)
        .filter(|d| d.rem_euclid(step) == 0)
        .flat_map(|d| mantissas.iter().map(move |m| f64::from(d) + m.log10()))
        .filter(|x| range.contains(x))
        .collect();
    let mut minor = Vec::new();
    if span <= 6.0 {
        for d in (range.start.floor() as i32)..=(range.end.ceil() as i32) {
            for k in 2..=9 {
                let x = f64::from(d) + f64::from(k).log10();
                if range.contains(&x) {
                    minor.push(x);
                }
            }
        }
    }
    LogAxis {
        inner: RangedCoordf64::from(range),
        decades,
        minor,
    }
}

/// "10ⁿ" for a whole decade n, "m×10ⁿ" for m × 10ⁿ with a whole
/// mantissa m (the 2 and 5 ticks of short axes); plain digits where they
/// are shorter (0.2, 5, 20).
pub fn decade_label(log10: &f64) -> String {
    let n = log10.floor();
    let mantissa = 10f64.powf(log10 - n);
    let whole = mantissa.round();
    if (mantissa - whole).abs() > 1e-6 {
        return format!("{:.3e}", 10f64.powf(*log10));
    }
    let (m, n) = if whole >= 10.0 {
        (1.0, n + 1.0)
    } else {
        (whole, n)
    };
    if m == 1.0 {
        return if n == 0.0 {
            "1".into()
        } else {
            format!("10{}", superscript(n as i64))
        };
    }
    if (-1.0..=1.0).contains(&n) {
        return super::format_tick(m * 10f64.powf(n));
    }
    format!("{m}×10{}", superscript(n as i64))
}

fn superscript(n: i64) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let mut s = String::new();
    if n < 0 {
        s.push('⁻');
    }
    for c in n.unsigned_abs().to_string().chars() {
        s.push(DIGITS[c.to_digit(10).unwrap_or(0) as usize]);
    }
    s
}

/// log10 of a positive value; non-positive values (which a log axis cannot
/// show) give None.
pub fn lg(v: f64) -> Option<f64> {
    (v > 0.0 && v.is_finite()).then(|| v.log10())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decades_are_labelled_with_superscripts() {
        assert_eq!(decade_label(&-12.0), "10⁻¹²");
        assert_eq!(decade_label(&0.0), "1");
        assert_eq!(decade_label(&3.0), "10³");
        assert_eq!(decade_label(&2f64.log10()), "2");
        assert_eq!(decade_label(&(5f64.log10() - 3.0)), "5×10⁻³");
        assert_eq!(decade_label(&(2f64.log10() - 1.0)), "0.2");
    }

    #[test]
    fn ticks_sit_on_decades_and_thin_out_over_wide_spans() {
        let axis = log_axis(-8.3..0.2);
        assert_eq!(
            axis.bold_points(),
            &[-8.0, -7.0, -6.0, -5.0, -4.0, -3.0, -2.0, -1.0, 0.0]
        );
        let wide = log_axis(-10.0..10.0);
        assert!(wide.bold_points().iter().all(|d| d.rem_euclid(3.0) == 0.0));
        assert!(wide.light_points().is_empty());
        let narrow = log_axis(-0.5..1.5);
        assert!(
            narrow
                .light_points()
                .iter()
                .any(|&x| (x - 2f64.log10()).abs() < 1e-12)
        );
    }
}
