//! The window that retires the kernels' fast oscillation.
//!
//! Both kernels are k = k_n + k_o with k_n smooth and k_o = Re[A(x) e^{2ix}]
//! oscillating ever faster in ln x. Against a material function Φ(ln x) that
//! is analytic in a strip |Im ln x| < d (true of every Prony series and of the
//! Hertz contact map), the integral of χ·k_o — with χ a smooth step from 0 to
//! 1 around x = X0 — is exponentially small, O(e^{−2 X0 sin d′}) for d′ < d:
//! the contour can be shifted into the half plane where e^{2ix} decays. So the
//! quadrature uses the windowed kernel
//!
//!   k̃ = k_n + (1 − χ) k_o,
//!
//! identical to k for x ≲ X0/4 and to the non-oscillating k_n for x ≳ 4 X0.
//! χ(ln x) = ½ erfc((ln X0 − ln x)/w) is entire, so it adds no singularity.

/// Centre X0 of the window (in x = ω a/v).
pub const WINDOW_CENTRE: f64 = 20.0;
/// Centre X0 of the window under a cylinder on a film, on grids of step
/// h ≤ 0.07. The film factor 1/S(ωd/v) has poles at x = x*·a/d with
/// arg x* ≥ 0.94 and |x*| ≈ 3.1 (`friction::film_cylinder`); where such a
/// pole lies near X0 = 20 the window, which grows like e^{(θ/w)²} a distance
/// θ off the real ln x axis, no longer makes the dropped part small. At 40
/// the residue's factor e^{−2 Im x} outweighs that growth for every a/d,
/// while the kept oscillation (frequency 2x in ln x) still stops short of
/// the grid's own frequency 2π/h (x ≈ π/h = 45 at h = 0.07), where the
/// interpolation error of the grid would resonate with it (at X0 = 80 and
/// h = 0.05: 1.3e-8).
pub const FILM_WINDOW_CENTRE: f64 = 40.0;
/// Width w of the window in ln x.
pub const WINDOW_WIDTH: f64 = 0.25;
/// Beyond this many widths from the centre the window is 0 or 1 to rounding.
const SATURATION: f64 = 6.0;

/// The part of the window, 1 − χ, that keeps k_o: 1 below, 0 above.
pub fn keep_oscillation(ln_x: f64) -> f64 {
    keep_oscillation_at(ln_x, WINDOW_CENTRE)
}

/// ln x above which k̃ = k_n to rounding.
pub fn smooth_above() -> f64 {
    smooth_above_at(WINDOW_CENTRE)
}

/// [`keep_oscillation`] of a window centred at `centre` (X0).
pub fn keep_oscillation_at(ln_x: f64, centre: f64) -> f64 {
    0.5 * libm::erfc((ln_x - centre.ln()) / WINDOW_WIDTH)
}

/// ln x below which k̃ = k to rounding, for a window centred at `centre`
/// (X0).
pub fn exact_below_at(centre: f64) -> f64 {
    centre.ln() - SATURATION * WINDOW_WIDTH
}

/// [`smooth_above`] of a window centred at `centre` (X0).
pub fn smooth_above_at(centre: f64) -> f64 {
    centre.ln() + SATURATION * WINDOW_WIDTH
}
