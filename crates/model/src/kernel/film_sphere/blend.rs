//! The universal product-integration weights of the film sphere kernel:
//! those of the blend 1 − χ between the full kernel and its split, and of
//! the windowed oscillation E = χ (1 − χ_w) e^{2ix} (see [`super`]).
//!
//! With B the cardinal function of the P-point local Lagrange interpolant
//! on the σ grid (as in [`crate::kernel::weights`]),
//!
//!   W_lo(τ) = h ∫ B(u) [1 − χ(τ + hu)] du,   W_osc(τ) = h ∫ B(u) E(τ + hu) du,
//!
//! and their τ-derivatives W′ = −∫ B′(u) F(τ + hu) du. Both are tabulated on
//! a fine uniform grid (h/32) where they are not constant: W_lo = h below
//! and 0 above its range, W_osc = 0 outside its. E oscillates up to
//! x ≈ 20 e^{1.5}, i.e. a phase change of 2x·h per cell: each cell of B is
//! cut into sub-panels of at most 2 radians, each integrated by 16-point
//! Gauss–Legendre.

use std::sync::OnceLock;

use num_complex::Complex64;

use crate::kernel::chebyshev::PiecewiseChebyshev;
use crate::kernel::quadrature::gauss_legendre_unit;
use crate::kernel::weights::{STENCIL, STEPS, cardinal, lagrange6};
use crate::kernel::{sphere, window};

/// Centre of the blend χ in τ = ln x: the kernel is split into its smooth
/// part and its oscillation above x ≈ 1.
pub const BLEND_CENTRE: f64 = 0.0;
/// Width of the blend in ln x (χ = ½ erfc((τ_b − τ)/w)).
pub const BLEND_WIDTH: f64 = 0.25;
/// χ is 0 or 1 to rounding beyond this many widths from its centre.
const SATURATION: f64 = 6.0;
/// Table points per grid step.
const SUBDIVISION: usize = 32;

/// χ(τ): 0 for x ≪ 1, 1 for x ≫ 1.
pub fn blend(tau: f64) -> f64 {
    0.5 * libm::erfc((BLEND_CENTRE - tau) / BLEND_WIDTH)
}

/// τ below which χ = 0 and above which χ = 1 (to rounding).
pub fn blend_range() -> (f64, f64) {
    (
        BLEND_CENTRE - SATURATION * BLEND_WIDTH,
        BLEND_CENTRE + SATURATION * BLEND_WIDTH,
    )
}

/// The half-space's smooth part N_h(τ) = 1/(3x²) + 4/(15x⁴) (the film's N
/// with its moments at their thick-film values 2/3 and 8/15), and its
/// τ-derivative: the profile the smooth factors of the film are measured
/// against (see [`BlendWeights`]).
#[inline]
pub fn half_space_smooth(tau: f64) -> (f64, f64) {
    half_space_smooth_at((-2.0 * tau).exp())
}

/// [`half_space_smooth`] from u = 1/x² = e^{−2τ} (which the sums update by
/// a factor per node instead of an exponential).
#[inline]
pub fn half_space_smooth_at(inverse_x2: f64) -> (f64, f64) {
    let (a, b) = (HALF_SPACE_SMOOTH[0].1, HALF_SPACE_SMOOTH[1].1);
    let (e2, e4) = (inverse_x2, inverse_x2 * inverse_x2);
    (a * e2 + b * e4, -2.0 * a * e2 - 4.0 * b * e4)
}

/// N_h = Σ a e^{cτ}: the pairs (c, a).
const HALF_SPACE_SMOOTH: [(f64, f64); 2] = [(-2.0, 1.0 / 3.0), (-4.0, 4.0 / 15.0)];

/// E(τ) N_h(τ), E = χ(τ)(1 − χ_w(τ)) e^{2i e^τ}.
fn windowed_oscillation(tau: f64) -> Complex64 {
    let x = tau.exp();
    Complex64::from_polar(
        blend(tau) * window::keep_oscillation(tau) * half_space_smooth(tau).0,
        2.0 * x,
    )
}

/// A weight and its τ-derivative, tabulated.
#[derive(Debug)]
struct Tabulated<T> {
    /// Index of the first value on the global grid τ = m·spacing.
    offset: i64,
    values: Vec<(T, T)>,
}

/// A tabulated weight at one node: below or above its table, or the
/// interpolated (W, W′).
enum Lookup<T> {
    Below,
    At((T, T)),
    Above,
}

impl<T> Tabulated<T>
where
    T: Copy + std::ops::Mul<f64, Output = T> + std::ops::Add<Output = T>,
{
    /// (W, W′) at τ₀ + kh by six-point Lagrange interpolation, or where the
    /// node lies outside the table.
    #[inline]
    fn lookup(&self, cursor: &BlendCursor, k: i64) -> Lookup<T> {
        let i = cursor.index0 + k * SUBDIVISION as i64 - self.offset;
        if i < 2 {
            return Lookup::Below;
        }
        if i + 4 > self.values.len() as i64 {
            return Lookup::Above;
        }
        let values = &self.values[(i - 2) as usize..(i + 4) as usize];
        let c = &cursor.weights;
        let (mut w, mut dw) = (values[0].0 * c[0], values[0].1 * c[0]);
        for (v, c) in values[1..].iter().zip(&c[1..]) {
            w = w + v.0 * *c;
            dw = dw + v.1 * *c;
        }
        Lookup::At((w, dw))
    }
}

/// W_lo, W_K, W_N, W_osc and their derivatives for one grid step.
///
/// The smooth factors N and A of the film grow like x⁻⁴ below x ≈ 1, where
/// χN and Re(A E) nearly cancel; interpolating Φ·N and Φ·A across a stencil
/// there loses the rule's order (about 1e-6 of μ at vτ/r0 = 1000 at the
/// default step, 1e-3 at the coarsest). So the weights carry the
/// half-space's N_h, exactly integrated, and the nodes the bounded ratios
/// N/N_h ∈ [0, 1] and A/N_h:
///
///   W_N = h ∫ B χ N_h,   W_osc = h ∫ B E N_h,
///
/// the same way W_K carries k_half against the ratio R = K/k_half.
#[derive(Debug)]
pub struct BlendWeights {
    step: f64,
    spacing: f64,
    low: Tabulated<f64>,
    full: Tabulated<f64>,
    smooth: Tabulated<f64>,
    /// h ∫ B(u) e^{c h u} du for the exponents c of [`HALF_SPACE_SMOOTH`]:
    /// W_N above its table, where χ = 1.
    smooth_far: [f64; 2],
    oscillation: Tabulated<Complex64>,
}

/// Interpolation state for τ₀ + kh, k integer: every such point has the same
/// fractional position on a table of spacing h/`SUBDIVISION`.
#[derive(Debug, Clone, Copy)]
pub struct BlendCursor {
    index0: i64,
    weights: [f64; 6],
}

impl BlendWeights {
    /// The weights for grid step `STEPS[index]`, built on first use.
    pub fn get(index: usize) -> &'static BlendWeights {
        static CELLS: [OnceLock<BlendWeights>; STEPS.len()] =
            [const { OnceLock::new() }; STEPS.len()];
        CELLS[index].get_or_init(|| BlendWeights::build(STEPS[index]))
    }

    fn build(step: f64) -> BlendWeights {
        let spacing = step / SUBDIVISION as f64;
        let reach = (STENCIL / 2) as f64 * step;
        let (blend_lo, blend_hi) = blend_range();
        let margin = 4.0 * spacing;
        let rule = gauss_legendre_unit(16);
        let half = (STENCIL / 2) as i64;
        // h ∫ B F and −∫ B′ F over the stencil, each cell cut so that F's
        // phase moves at most 2 radians per sub-panel.
        let integrate = |tau: f64, f: &dyn Fn(f64) -> Complex64| -> (Complex64, Complex64) {
            let mut w = Complex64::new(0.0, 0.0);
            let mut dw = Complex64::new(0.0, 0.0);
            for cell in -half..half {
                let x_top = (tau + step * (cell + 1) as f64).exp();
                let pieces = ((2.0 * x_top * step / 2.0).ceil() as usize).max(1);
                let width = 1.0 / pieces as f64;
                for piece in 0..pieces {
                    for (t, wt) in rule.0.iter().zip(&rule.1) {
                        let u = cell as f64 + (piece as f64 + t) * width;
                        let (b, db) = cardinal(u);
                        let value = f(tau + step * u);
                        w += wt * width * b * value;
                        dw += wt * width * db * value;
                    }
                }
            }
            (step * w, -dw)
        };
        // Tables on the grid τ = m·spacing, so that one cursor serves all.
        let low_offset = ((blend_lo - reach - margin) / spacing).floor() as i64;
        let count = ((blend_hi + reach + margin) / spacing).ceil() as i64 - low_offset + 1;
        let low = Tabulated {
            offset: low_offset,
            values: (0..count)
                .map(|m| {
                    let (w, dw) = integrate((low_offset + m) as f64 * spacing, &|s| {
                        Complex64::new(1.0 - blend(s), 0.0)
                    });
                    (w.re, dw.re)
                })
                .collect(),
        };
        // W_K: the weights of (1 − χ) k_half, k_half = x² G(x) the
        // half-space kernel, which multiplies the smooth ratio
        // R = K/k_half at the nodes (see [`super`]).
        // G is evaluated at the quadrature points of every table entry (some
        // 10⁵ points): through a Chebyshev interpolant of k_half on panels
        // of ¼ (16 points, x ≤ 7 there; accurate to rounding, as the rows'
        // ratio R), as G itself would cost seconds. Above the blend 1 − χ
        // is below 1e-17 and the integrand is dropped.
        let (tau_lo, tau_hi) = (blend_lo - 2.0 * reach - 1.0, blend_hi);
        let panels = ((tau_hi - tau_lo) / 0.25).ceil() as usize;
        let breaks = (0..=panels)
            .map(|p| tau_lo + (tau_hi - tau_lo) * p as f64 / panels as f64)
            .collect();
        let half_space = PiecewiseChebyshev::new(breaks, 16, |s| {
            let x = s.exp();
            x * x * sphere::g(x)
        });
        let full = Tabulated {
            offset: low_offset,
            values: (0..count)
                .map(|m| {
                    let (w, dw) = integrate((low_offset + m) as f64 * spacing, &|s| {
                        if s >= tau_hi {
                            return Complex64::new(0.0, 0.0);
                        }
                        Complex64::new((1.0 - blend(s)) * half_space.eval(s), 0.0)
                    });
                    (w.re, dw.re)
                })
                .collect(),
        };
        // W_N: the weights of χ N_h, which multiply N/N_h at the nodes.
        let smooth = Tabulated {
            offset: low_offset,
            values: (0..count)
                .map(|m| {
                    let (w, dw) = integrate((low_offset + m) as f64 * spacing, &|s| {
                        Complex64::new(blend(s) * half_space_smooth(s).0, 0.0)
                    });
                    (w.re, dw.re)
                })
                .collect(),
        };
        let smooth_far = HALF_SPACE_SMOOTH
            .map(|(c, _)| integrate(0.0, &|s| Complex64::new((c * s).exp(), 0.0)).0.re);
        let osc_offset = low_offset;
        let count =
            ((window::smooth_above() + reach + margin) / spacing).ceil() as i64 - osc_offset + 1;
        let oscillation = Tabulated {
            offset: osc_offset,
            values: (0..count)
                .map(|m| integrate((osc_offset + m) as f64 * spacing, &windowed_oscillation))
                .collect(),
        };
        BlendWeights {
            step,
            spacing,
            low,
            full,
            smooth,
            smooth_far,
            oscillation,
        }
    }

    /// Prepares evaluations at τ₀ + kh.
    #[inline]
    pub fn cursor(&self, tau0: f64) -> BlendCursor {
        let q = tau0 / self.spacing;
        let i = q.floor();
        BlendCursor {
            index0: i as i64,
            weights: lagrange6(q - i),
        }
    }

    /// (W_lo, W_lo′) at τ₀ + kh.
    #[inline]
    pub fn low(&self, cursor: &BlendCursor, k: i64) -> (f64, f64) {
        match self.low.lookup(cursor, k) {
            Lookup::Below => (self.step, 0.0),
            Lookup::At(w) => w,
            Lookup::Above => (0.0, 0.0),
        }
    }

    /// (W_K, W_K′) at τ₀ + kh, or `None` below the table (where W_K is the
    /// half-space's product weight).
    #[inline]
    pub fn full(&self, cursor: &BlendCursor, k: i64) -> Option<(f64, f64)> {
        match self.full.lookup(cursor, k) {
            Lookup::Below => None,
            Lookup::At(w) => Some(w),
            Lookup::Above => Some((0.0, 0.0)),
        }
    }

    /// (W_N, W_N′) at τ₀ + kh, where 1/x² = `inverse_x2`.
    #[inline]
    pub fn smooth(&self, cursor: &BlendCursor, k: i64, inverse_x2: f64) -> (f64, f64) {
        match self.smooth.lookup(cursor, k) {
            Lookup::Below => (0.0, 0.0),
            Lookup::At(w) => w,
            Lookup::Above => {
                // Σ a e^{cτ} m_c with c = −2, −4.
                let (c2, c4) = (HALF_SPACE_SMOOTH[0].0, HALF_SPACE_SMOOTH[1].0);
                let t2 = HALF_SPACE_SMOOTH[0].1 * inverse_x2 * self.smooth_far[0];
                let t4 = HALF_SPACE_SMOOTH[1].1 * inverse_x2 * inverse_x2 * self.smooth_far[1];
                (t2 + t4, c2 * t2 + c4 * t4)
            }
        }
    }

    /// (W_osc, W_osc′) at τ₀ + kh.
    #[inline]
    pub fn oscillation(&self, cursor: &BlendCursor, k: i64) -> Option<(Complex64, Complex64)> {
        match self.oscillation.lookup(cursor, k) {
            Lookup::At(w) => Some(w),
            Lookup::Below | Lookup::Above => None,
        }
    }
}
