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
