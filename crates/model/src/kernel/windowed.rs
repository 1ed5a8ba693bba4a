//! The friction kernels k(ln x) with their oscillation faded out by a window
//! at a chosen centre X, as a cheap function of ln x on the whole line, for
//! quadratures that evaluate the kernel at arbitrary points (the
//! knot-splitting quadrature of a tabulated modulus) rather than through the
//! product-integration weights of [`super::weights`].
//!
//! As in [`super::window`], k = k_n + k_o with k_n smooth and
//! k_o = Re[e^{2ix} B(x)] oscillating, B non-oscillating:
//! B = (J₁ + iY₁)² e^{−2ix}/(2x) (cylinder, since J₁² − Y₁² = Re H₁²) and
//! B = −x² I(x) (sphere, G_o = −Re[e^{2ix} I], [`sphere::oscillatory_amplitude`]).
//! The windowed kernel is
//!
//!   k̃_X = k_n + ½ erfc((ln x − ln X)/w) k_o,   w = [`window::WINDOW_WIDTH`],
//!
//! equal to k where x ≤ X e^{−6w} and to k_n where x ≥ X e^{6w}. Against an
//! integrand analytic in a strip the dropped part is exponentially small
//! (see [`super::window`]); against one that is only piecewise analytic —
//! a kink of Φ at σ_k — it is a boundary term of integration by parts,
//! O(jump of Φ′ · x_k⁻⁴) for a cylinder, which is why the centre is a
//! parameter here (X = 20 in the product integration).
//!
//! Pieces, each exact to about 1e-13 relative where used:
//!
//! - ln x < −16: the small-x expansions, k = x/4 − x³/16 (cylinder) and
//!   k = x²[(1/9) ln(2/x) + c_f] (sphere, relative error O(x² ln x));
//! - −16 ≤ ln x ≤ ln 4: piecewise Chebyshev interpolation (degree 14) of k
//!   itself, on panels ½ wide below ln x = −1 and 1/16 wide above;
//! - ln x > ln 4: k_n in closed form (Hankel's expansion, G_n) plus the
//!   window times Re[e^{2ix} B], with B by piecewise Chebyshev in ln x
//!   (panels 1/8 wide) out to [`MAX_CENTRE`] e^{6w}.
//!
//! # References
//! - L.N. Trefethen, *Approximation Theory and Approximation Practice*,
//!   SIAM 2013, ch. 8 (Chebyshev interpolation of analytic functions).
//! - M. Abramowitz, I.A. Stegun, *Handbook of Mathematical Functions*,
//!   Dover 1965, §9.2 (Hankel's expansions of J₁ and Y₁).

use std::sync::OnceLock;

use num_complex::Complex64;

use super::chebyshev::PiecewiseChebyshev;
use super::{cylinder, sphere, window};
use crate::contact::Shape;

/// ln x below which the small-x expansion is used.
const SMALL_BELOW: f64 = -16.0;

/// ln x above which k is written as k_n + Re[e^{2ix} B].
const SPLIT_ABOVE: f64 = 1.386_294_361_119_890_6; // ln 4

/// The largest window centre X the tables of B cover.
pub(crate) const MAX_CENTRE: f64 = 500.0;

/// Beyond this many widths from its centre the window is 0 or 1 to rounding.
const SATURATION: f64 = 6.0;

/// k(ln x) and its oscillation amplitude for one shape.
pub(crate) struct WindowedKernel {
    shape: Shape,
    /// k on [SMALL_BELOW, SPLIT_ABOVE].
    near: PiecewiseChebyshev,
    /// Re B and Im B on [SPLIT_ABOVE, ln MAX_CENTRE + 6w].
    amplitude: (PiecewiseChebyshev, PiecewiseChebyshev),
    /// c_f of the sphere's G(x) = (1/9) ln(2/x) + c_f + O(x² ln x).
    sphere_constant: f64,
}

impl WindowedKernel {
    /// The kernel of `shape`, built on first use.
    pub(crate) fn get(shape: Shape) -> &'static WindowedKernel {
        static SPHERE: OnceLock<WindowedKernel> = OnceLock::new();
        static CYLINDER: OnceLock<WindowedKernel> = OnceLock::new();
        let cell = match shape {
            Shape::Sphere => &SPHERE,
            Shape::Cylinder => &CYLINDER,
        };
        cell.get_or_init(|| WindowedKernel::build(shape))
    }

    fn build(shape: Shape) -> WindowedKernel {
        let mut breaks = Vec::new();
        let mut b = SMALL_BELOW;
        while b < -1.0 {
            breaks.push(b);
            b += 0.5;
        }
        b = -1.0;
        while b < SPLIT_ABOVE {
            breaks.push(b);
            b += 1.0 / 16.0;
        }
        breaks.push(SPLIT_ABOVE);
        let near = PiecewiseChebyshev::new(breaks, 14, |s| exact(shape, s.exp()));
        let top = MAX_CENTRE.ln() + SATURATION * window::WINDOW_WIDTH;
        let pieces = ((top - SPLIT_ABOVE) * 8.0).ceil() as usize;
        let breaks: Vec<f64> = (0..=pieces)
            .map(|i| SPLIT_ABOVE + (top - SPLIT_ABOVE) * i as f64 / pieces as f64)
            .collect();
        let amplitude = (
            PiecewiseChebyshev::new(breaks.clone(), 14, |s| amplitude(shape, s.exp()).re),
            PiecewiseChebyshev::new(breaks, 14, |s| amplitude(shape, s.exp()).im),
        );
        let x = 1e-9f64;
        WindowedKernel {
            shape,
            near,
            amplitude,
            sphere_constant: sphere::g(x) - (2.0 / x).ln() / 9.0,
        }
    }

    /// k̃_X at ln x for the window centre ln X = `ln_centre`
    /// (ln X ≤ ln [`MAX_CENTRE`]).
    #[inline]
    pub(crate) fn eval(&self, ln_x: f64, ln_centre: f64) -> f64 {
        if ln_x < SMALL_BELOW {
            let x = ln_x.exp();
            return match self.shape {
                Shape::Sphere => x * x * ((2.0f64.ln() - ln_x) / 9.0 + self.sphere_constant),
                Shape::Cylinder => x * (0.25 - x * x / 16.0),
            };
        }
        if ln_x <= SPLIT_ABOVE {
            return self.near.eval(ln_x);
        }
        let x = ln_x.exp();
        let smooth = match self.shape {
            Shape::Sphere => x * x * sphere::smooth_part(x),
            Shape::Cylinder => cylinder::smooth_part(x),
        };
        let z = (ln_x - ln_centre) / window::WINDOW_WIDTH;
        if z >= SATURATION {
            return smooth;
        }
        let keep = 0.5 * libm::erfc(z);
        let (b_re, b_im) = (self.amplitude.0.eval(ln_x), self.amplitude.1.eval(ln_x));
        let (sin, cos) = (2.0 * x).sin_cos();
        smooth + keep * (b_re * cos - b_im * sin)
    }
}

/// k(x) evaluated directly.
fn exact(shape: Shape, x: f64) -> f64 {
    match shape {
        Shape::Sphere => x * x * sphere::g(x),
        Shape::Cylinder => cylinder::kernel(x),
    }
}

/// B(x) with k_o = Re[e^{2ix} B(x)], x > 2.
fn amplitude(shape: Shape, x: f64) -> Complex64 {
    match shape {
        Shape::Sphere => -x * x * sphere::oscillatory_amplitude(x),
        Shape::Cylinder => {
            let h = Complex64::new(libm::j1(x), libm::y1(x));
            h * h * Complex64::new(0.0, -2.0 * x).exp() / (2.0 * x)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Against the direct evaluation of k_n + window · k_o on a fine grid
    /// crossing every piece and join, at the product integration's centre
    /// and at the largest.
    #[test]
    fn matches_the_direct_kernel() {
        for shape in [Shape::Sphere, Shape::Cylinder] {
            let k = WindowedKernel::get(shape);
            for centre in [window::WINDOW_CENTRE, MAX_CENTRE] {
                let direct = |ln_x: f64| {
                    let x = ln_x.exp();
                    if ln_x <= SPLIT_ABOVE {
                        return exact(shape, x);
                    }
                    let keep = 0.5 * libm::erfc((ln_x - centre.ln()) / window::WINDOW_WIDTH);
                    match shape {
                        Shape::Sphere => {
                            x * x * (sphere::smooth_part(x) + keep * sphere::oscillatory_part(x))
                        }
                        Shape::Cylinder => {
                            cylinder::smooth_part(x) + keep * cylinder::oscillatory_part(x)
                        }
                    }
                };
                let mut worst = 0.0f64;
                let mut ln_x = -20.0;
                while ln_x < 9.0 {
                    // The kernel touches zero at the zeros of J₁ (and the
                    // sphere's near them): measure against its size nearby.
                    let scale = [-0.1, 0.0, 0.1]
                        .iter()
                        .map(|d| direct(ln_x + d).abs())
                        .fold(0.0, f64::max);
                    worst = worst.max((k.eval(ln_x, centre.ln()) - direct(ln_x)).abs() / scale);
                    ln_x += 0.00737;
                }
                assert!(worst < 1e-11, "{shape:?} X = {centre}: {worst:e}");
            }
        }
    }
}
