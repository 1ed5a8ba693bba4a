//! Colours, markers and text sizes shared by all pictures, so that one
//! quantity looks the same everywhere (E′ always blue, E″ always red, …).
//! Tests find series in the PNGs by these colours.

use plotters::style::RGBColor;

/// Measured μ and its error bars.
pub const MEASURED: RGBColor = RGBColor(40, 40, 40);
/// The fitted μ(v).
pub const FITTED: RGBColor = RGBColor(214, 39, 40);
/// E′ (storage modulus).
pub const STORAGE: RGBColor = RGBColor(31, 119, 180);
/// E″ (loss modulus).
pub const LOSS: RGBColor = RGBColor(214, 39, 40);
/// tan δ.
pub const TAN_DELTA: RGBColor = RGBColor(44, 160, 44);
/// DMA points.
pub const DMA: RGBColor = RGBColor(0, 0, 0);
/// The window the data determine (background shading).
pub const WINDOW: RGBColor = RGBColor(255, 236, 179);
/// Terms or regions the data do not determine.
pub const UNDETERMINED: RGBColor = RGBColor(150, 150, 150);
/// The WLF curve of a temperature set.
pub const WLF: RGBColor = RGBColor(31, 119, 180);
/// A verdict that is not "good", in a picture's title.
pub const VERDICT: RGBColor = RGBColor(180, 20, 20);

/// One colour per temperature or per method: a qualitative palette
/// (Tableau 10) whose neighbours are easy to tell apart.
pub const SERIES: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// Caption size, px.
pub const CAPTION: u32 = 22;
/// Axis description size, px.
pub const AXIS_DESCRIPTION: u32 = 18;
/// Tick label size, px.
pub const TICK_LABEL: u32 = 15;
/// Legend size, px.
pub const LEGEND: u32 = 15;

/// Stops of [`cold_to_warm`], evenly spaced from cold to warm. No stop is
/// pale: every temperature's line and markers must stand out on white, so
/// the ramp runs through green and orange rather than through white.
const COLD_TO_WARM: [RGBColor; 5] = [
    RGBColor(49, 54, 149),
    RGBColor(33, 144, 200),
    RGBColor(60, 160, 80),
    RGBColor(240, 130, 30),
    RGBColor(200, 30, 40),
];

/// The colour of a temperature: `fraction` 0 is the coldest (deep blue),
/// 1 the warmest (red), linear in RGB between the stops. Values outside
/// [0, 1] are clamped; NaN gives the middle colour.
pub fn cold_to_warm(fraction: f64) -> RGBColor {
    let f = if fraction.is_nan() {
        0.5
    } else {
        fraction.clamp(0.0, 1.0)
    };
    ramp(&COLD_TO_WARM, f)
}

/// Stops of [`pressure_ramp`], from no pressure to the peak: light yellow
/// through orange to dark red (ColorBrewer YlOrRd). Low pressures are
/// pale, so that the black contact outline, where the pressure falls to
/// zero, stands out, and the blue of the static Hertz comparison stays
/// apart from every stop.
const PRESSURE_RAMP: [RGBColor; 5] = [
    RGBColor(255, 255, 204),
    RGBColor(254, 217, 118),
    RGBColor(253, 141, 60),
    RGBColor(227, 26, 28),
    RGBColor(128, 0, 38),
];

/// The colour of a contact pressure: `fraction` of the colour scale's top,
/// 0 pale yellow, 1 dark red, linear in RGB between the stops; clamped to
/// [0, 1], NaN gives 0.
pub fn pressure_ramp(fraction: f64) -> RGBColor {
    let f = if fraction.is_nan() {
        0.0
    } else {
        fraction.clamp(0.0, 1.0)
    };
    ramp(&PRESSURE_RAMP, f)
}

/// Linear interpolation in RGB between evenly spaced `stops`, `f` in [0, 1].
fn ramp(stops: &[RGBColor], f: f64) -> RGBColor {
    let scaled = f * (stops.len() - 1) as f64;
    let i = (scaled.floor() as usize).min(stops.len() - 2);
    let t = scaled - i as f64;
    let (a, b) = (stops[i], stops[i + 1]);
    let mix = |x: u8, y: u8| (f64::from(x) + t * (f64::from(y) - f64::from(x))).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_temperature_ramp_runs_from_blue_to_red_through_its_stops() {
        assert_eq!(cold_to_warm(0.0), COLD_TO_WARM[0]);
        assert_eq!(cold_to_warm(0.5), COLD_TO_WARM[2]);
        assert_eq!(cold_to_warm(1.0), COLD_TO_WARM[4]);
        assert_eq!(cold_to_warm(-3.0), COLD_TO_WARM[0]);
        assert_eq!(cold_to_warm(7.0), COLD_TO_WARM[4]);
        assert_eq!(cold_to_warm(f64::NAN), COLD_TO_WARM[2]);
        let cold = cold_to_warm(0.0);
        let warm = cold_to_warm(1.0);
        assert!(cold.2 > cold.0 && warm.0 > warm.2);
        // Halfway between two stops is their mean.
        let between = cold_to_warm(0.125);
        assert_eq!(between, RGBColor(41, 99, 175));
    }

    #[test]
    fn the_pressure_ramp_runs_from_pale_to_dark() {
        assert_eq!(pressure_ramp(0.0), PRESSURE_RAMP[0]);
        assert_eq!(pressure_ramp(1.0), PRESSURE_RAMP[4]);
        assert_eq!(pressure_ramp(f64::NAN), PRESSURE_RAMP[0]);
        assert_eq!(pressure_ramp(2.0), PRESSURE_RAMP[4]);
        let brightness = |c: RGBColor| u32::from(c.0) + u32::from(c.1) + u32::from(c.2);
        assert!((1..=10).all(|k| {
            brightness(pressure_ramp(f64::from(k) / 10.0))
                < brightness(pressure_ramp(f64::from(k - 1) / 10.0))
        }));
    }
}
