//! The two-variable parts of the film sphere kernel, K(τ, λ) and A(τ, λ)
//! (τ = ln x, λ = ln δ), tabulated in rows of constant λ (see [`super`]).
//!
//! Rows lie on the global grid λ_i = i Δλ (Δλ = 1/32) and are built on
//! first use and kept for the process, per Poisson ratio and grid step; a
//! scene asks for the rows its range of δ = d/r(ω) needs. Along a row the
//! values sit on τ_m = m Δτ with Δτ = h/n close to 0.02 (n an integer,
//! so that every node of a speed has the same fractional position, as for
//! [`crate::kernel::weights`]). Values between rows and between points are
//! six-point Lagrange interpolants in λ and in τ (error measured in the
//! tests: below 1e-10 of the kernel's scale).
//!
//! K is kept from τ = −12 (below, K ∝ x² for every film to ~x: its
//! contribution to μ there is below e^{−36} of the total) to where the blend
//! has made it irrelevant; A from where the blend starts to where the
//! window has removed the oscillation.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use num_complex::Complex64;
use rayon::prelude::*;

use super::blend::blend_range;
use super::integrals::FilmKernel;
use crate::kernel::chebyshev::PiecewiseChebyshev;
use crate::kernel::weights::{STENCIL, STEPS};
use crate::kernel::{sphere, window};

/// Row spacing Δλ in ln δ.
pub const LAMBDA_SPACING: f64 = 1.0 / 32.0;
/// Lower end of the K rows in τ.
const FAR_BELOW: f64 = -12.0;
/// Target spacing of the values along a row.
const TAU_SPACING: f64 = 0.02;

/// One row: K and A at τ_m for one λ.
#[derive(Debug)]
struct Row {
    full: Vec<f64>,
    amplitude: Vec<Complex64>,
}

/// Where a row's values lie, the same for all rows of one grid step.
#[derive(Debug, Clone, Copy)]
struct Layout {
    /// Index into [`STEPS`] of the grid step.
    step_index: usize,
    /// Values per grid step h.
    per_step: i64,
    /// Δτ = h/per_step.
    spacing: f64,
    /// Grid index m of full[0] and amplitude[0].
    full_offset: i64,
    full_len: usize,
    amplitude_offset: i64,
    amplitude_len: usize,
}

impl Layout {
    fn new(step_index: usize) -> Layout {
        let step = STEPS[step_index];
        let per_step = ((step / TAU_SPACING).round() as i64).max(2);
        let spacing = step / per_step as f64;
        let reach = (STENCIL / 2) as f64 * step;
        let margin = 4.0 * spacing;
        let (blend_lo, blend_hi) = blend_range();
        let full_offset = (FAR_BELOW / spacing).floor() as i64;
        let full_end = ((blend_hi + reach + margin) / spacing).ceil() as i64;
        let amplitude_offset = ((blend_lo - reach - margin) / spacing).floor() as i64;
        let amplitude_end = ((window::smooth_above() + reach + margin) / spacing).ceil() as i64;
        Layout {
            step_index,
            per_step,
            spacing,
            full_offset,
            full_len: (full_end - full_offset + 1) as usize,
            amplitude_offset,
            amplitude_len: (amplitude_end - amplitude_offset + 1) as usize,
        }
    }

    /// Panel breaks of the K rows in τ: 1 wide below τ = −2, ¼ above.
    fn full_breaks(&self) -> Vec<f64> {
        let full_lo = self.full_offset as f64 * self.spacing;
        let full_hi = (self.full_offset + self.full_len as i64 - 1) as f64 * self.spacing;
        let mut breaks = vec![full_lo];
        let mut b = full_lo;
        while b + 1.0 < -2.0 {
            b += 1.0;
            breaks.push(b);
        }
        while b < full_hi {
            b = (b + 0.25).min(full_hi);
            breaks.push(b);
        }
        breaks
    }

    /// The half-space kernel k_half = x² G(x) on the K rows' panels, shared
    /// by all rows of one step: G costs more than the film's integrals, and
    /// at a panel's own Chebyshev points the interpolant returns the values
    /// it was built from.
    fn half_space_kernel(&self) -> &'static PiecewiseChebyshev {
        static CELLS: [OnceLock<PiecewiseChebyshev>; STEPS.len()] =
            [const { OnceLock::new() }; STEPS.len()];
        CELLS[self.step_index].get_or_init(|| {
            PiecewiseChebyshev::new(self.full_breaks(), POINTS, |tau| {
                let x = tau.exp();
                x * x * sphere::g(x)
            })
        })
    }

    /// One row: K and A by quadrature at the nodes of piecewise Chebyshev
    /// interpolants in τ (panels of 1 below τ = −2, where K is smooth and
    /// ∝ x² at the bottom; ¼ above, where it carries e^{2ix} up to x ≈ 10;
    /// ½ for the non-oscillating A; 16 points each: measured below 1e-12 of
    /// the kernel's scale), sampled on the row's τ grid.
    fn build_row(&self, poisson: f64, lambda: f64) -> Row {
        let kernel = FilmKernel::new(poisson, lambda.exp());
        let breaks = self.full_breaks();
        let half_space = self.half_space_kernel();
        let full = PiecewiseChebyshev::new(breaks, POINTS, |tau| {
            kernel.full(tau.exp()) / half_space.eval(tau)
        });
        let amplitude_lo = self.amplitude_offset as f64 * self.spacing;
        let amplitude_hi =
            (self.amplitude_offset + self.amplitude_len as i64 - 1) as f64 * self.spacing;
        let panels = ((amplitude_hi - amplitude_lo) / 0.5).ceil() as usize;
        let breaks = (0..=panels)
            .map(|p| amplitude_lo + (amplitude_hi - amplitude_lo) * p as f64 / panels as f64)
            .collect();
        let [re, im] = PiecewiseChebyshev::new_many(breaks, POINTS, |tau| {
            let a = kernel.amplitude(tau.exp());
            [a.re, a.im]
        });
        Row {
            full: (0..self.full_len as i64)
                .map(|m| full.eval((self.full_offset + m) as f64 * self.spacing))
                .collect(),
            amplitude: (0..self.amplitude_len as i64)
                .map(|m| {
                    let tau = (self.amplitude_offset + m) as f64 * self.spacing;
                    Complex64::new(re.eval(tau), im.eval(tau))
                })
                .collect(),
        }
    }
}

/// Chebyshev points per panel of a row's interpolants.
const POINTS: usize = 16;

type RowKey = (u64, usize, i64);

fn cache() -> &'static Mutex<HashMap<RowKey, Arc<Row>>> {
    static CACHE: OnceLock<Mutex<HashMap<RowKey, Arc<Row>>>> = OnceLock::new();
    CACHE.get_or_init(|| Mutex::new(HashMap::new()))
}

/// Six-point Lagrange weights at fractional position f (nodes −2..3) and
/// their derivatives d/df: L_k = c_k Π_{m≠k} d_m with d_m = f − n_m, so
/// L_k′ = c_k Σ_{m≠k} Π_{l≠k,m} d_l, from prefix and suffix products
/// (no division, so f on a node is fine).
pub(crate) fn lagrange6_with_slope(f: f64) -> ([f64; 6], [f64; 6]) {
    // 1/Π_{m≠k}(n_k − n_m) for the nodes −2..3.
    const C: [f64; 6] = [
        -1.0 / 120.0,
        1.0 / 24.0,
        -1.0 / 12.0,
        1.0 / 12.0,
        -1.0 / 24.0,
        1.0 / 120.0,
    ];
    let d = [f + 2.0, f + 1.0, f, f - 1.0, f - 2.0, f - 3.0];
    // prefix[k] = Π_{m<k} d_m, suffix[k] = Π_{m>k} d_m, and their
    // derivatives (sums of the products with one factor left out).
    let (mut prefix, mut prefix_slope) = ([1.0; 6], [0.0; 6]);
    for k in 1..6 {
        prefix[k] = prefix[k - 1] * d[k - 1];
        prefix_slope[k] = prefix_slope[k - 1] * d[k - 1] + prefix[k - 1];
    }
    let (mut suffix, mut suffix_slope) = ([1.0; 6], [0.0; 6]);
    for k in (0..5).rev() {
        suffix[k] = suffix[k + 1] * d[k + 1];
        suffix_slope[k] = suffix_slope[k + 1] * d[k + 1] + suffix[k + 1];
    }
    let mut weights = [0.0; 6];
    let mut slopes = [0.0; 6];
    for k in 0..6 {
        weights[k] = C[k] * prefix[k] * suffix[k];
        slopes[k] = C[k] * (prefix_slope[k] * suffix[k] + prefix[k] * suffix_slope[k]);
    }
    (weights, slopes)
}

/// Σ w_b v_b over six values.
#[inline(always)]
fn dot<T>(weights: &[f64; 6], values: &[T]) -> T
where
    T: Copy + std::ops::Mul<f64, Output = T> + std::ops::Add<Output = T>,
{
    let mut sum = values[0] * weights[0];
    for (v, w) in values[1..6].iter().zip(&weights[1..]) {
        sum = sum + *v * *w;
    }
    sum
}

/// The rows one scene needs: λ from `lambda_lo` to `lambda_hi`.
#[derive(Debug, Clone)]
pub struct FilmRows {
    layout: Layout,
    /// Row index i of rows[0].
    first: i64,
    rows: Vec<Arc<Row>>,
}

/// A node's place between rows: the first of six rows, their weights and
/// the weights' λ-derivatives.
#[derive(Debug, Clone, Copy)]
pub struct RowStencil {
    first: usize,
    weights: [f64; 6],
    slopes: [f64; 6],
}

/// The fractional position of a speed's nodes along the rows.
#[derive(Debug, Clone, Copy)]
pub struct RowCursor {
    index0: i64,
    weights: [f64; 6],
    slopes: [f64; 6],
}

/// K or A and their partial derivatives in τ and λ at one node.
#[derive(Debug, Clone, Copy)]
pub struct Interpolated<T> {
    pub value: T,
    pub d_tau: T,
    pub d_lambda: T,
}

impl FilmRows {
    /// The rows for ν = `poisson`, grid step `STEPS[step_index]` and
    /// λ = ln(d/r) ∈ [`lambda_lo`, `lambda_hi`], building missing rows (in
    /// parallel).
    pub fn new(poisson: f64, step_index: usize, lambda_lo: f64, lambda_hi: f64) -> FilmRows {
        let layout = Layout::new(step_index);
        let first = (lambda_lo / LAMBDA_SPACING).floor() as i64 - 2;
        let last = (lambda_hi / LAMBDA_SPACING).floor() as i64 + 3;
        let key = |i: i64| (poisson.to_bits(), step_index, i);
        let missing: Vec<i64> = {
            let cache = cache().lock().expect("film row cache");
            (first..=last)
                .filter(|&i| !cache.contains_key(&key(i)))
                .collect()
        };
        let built: Vec<(i64, Arc<Row>)> = missing
            .par_iter()
            .map(|&i| {
                (
                    i,
                    Arc::new(layout.build_row(poisson, i as f64 * LAMBDA_SPACING)),
                )
            })
            .collect();
        let mut cache = cache().lock().expect("film row cache");
        for (i, row) in built {
            cache.entry(key(i)).or_insert(row);
        }
        let rows = (first..=last)
            .map(|i| Arc::clone(&cache[&key(i)]))
            .collect();
        FilmRows {
            layout,
            first,
            rows,
        }
    }

    /// The stencil of a node at λ (inside the range asked for).
    pub fn stencil(&self, lambda: f64) -> RowStencil {
        let q = lambda / LAMBDA_SPACING;
        let i = q.floor();
        let (weights, slopes) = lagrange6_with_slope(q - i);
        let first = (i as i64 - 2 - self.first).clamp(0, self.rows.len() as i64 - 6) as usize;
        RowStencil {
            first,
            weights,
            slopes: slopes.map(|s| s / LAMBDA_SPACING),
        }
    }

    /// Prepares evaluations at τ₀ + kh.
    pub fn cursor(&self, tau0: f64) -> RowCursor {
        let q = tau0 / self.layout.spacing;
        let i = q.floor();
        let (weights, slopes) = lagrange6_with_slope(q - i);
        RowCursor {
            index0: i as i64,
            weights,
            slopes: slopes.map(|s| s / self.layout.spacing),
        }
    }

    /// R = K/k_half at τ₀ + kh for a node with stencil `node`, with its
    /// partial derivatives if `slopes`. Below the table R is continued as a
    /// constant.
    #[inline]
    pub fn full(
        &self,
        cursor: &RowCursor,
        k: i64,
        node: &RowStencil,
        slopes: bool,
    ) -> Interpolated<f64> {
        let layout = &self.layout;
        let i = cursor.index0 + k * layout.per_step - layout.full_offset;
        if i < 2 {
            // R continued as a constant (its contribution there is below
            // e^{−36} of μ).
            let rows = &self.rows[node.first..node.first + 6];
            let value: f64 = rows
                .iter()
                .zip(&node.weights)
                .map(|(r, w)| w * r.full[0])
                .sum();
            let d_lambda: f64 = if slopes {
                rows.iter()
                    .zip(&node.slopes)
                    .map(|(r, w)| w * r.full[0])
                    .sum()
            } else {
                0.0
            };
            return Interpolated {
                value,
                d_tau: 0.0,
                d_lambda,
            };
        }
        let i = (i as usize - 2).min(layout.full_len - 6);
        self.interpolate(|row| &row.full[i..i + 6], cursor, node, slopes)
    }

    /// A at τ₀ + kh (inside its table), as [`FilmRows::full`].
    #[inline]
    pub fn amplitude(
        &self,
        cursor: &RowCursor,
        k: i64,
        node: &RowStencil,
        slopes: bool,
    ) -> Interpolated<Complex64> {
        let layout = &self.layout;
        let i = cursor.index0 + k * layout.per_step - layout.amplitude_offset;
        let i = (i.max(2) as usize - 2).min(layout.amplitude_len - 6);
        self.interpolate(|row| &row.amplitude[i..i + 6], cursor, node, slopes)
    }

    /// Six-by-six Lagrange interpolation: the six values `along` picks from
    /// each of the node's six rows, combined in τ with the cursor's weights
    /// and in λ with the node's, with the partial derivatives if `slopes`.
    #[inline(always)]
    fn interpolate<'r, T, F>(
        &'r self,
        along: F,
        cursor: &RowCursor,
        node: &RowStencil,
        slopes: bool,
    ) -> Interpolated<T>
    where
        T: Copy + Default + std::ops::Mul<f64, Output = T> + std::ops::Add<Output = T> + 'r,
        F: Fn(&'r Row) -> &'r [T],
    {
        let rows = &self.rows[node.first..node.first + 6];
        let mut in_tau = [T::default(); 6];
        let mut in_tau_slope = [T::default(); 6];
        for (a, row) in rows.iter().enumerate() {
            let values = along(row);
            in_tau[a] = dot(&cursor.weights, values);
            if slopes {
                in_tau_slope[a] = dot(&cursor.slopes, values);
            }
        }
        let value = dot(&node.weights, &in_tau);
        let (d_tau, d_lambda) = if slopes {
            (
                dot(&node.weights, &in_tau_slope),
                dot(&node.slopes, &in_tau),
            )
        } else {
            (T::default(), T::default())
        };
        Interpolated {
            value,
            d_tau,
            d_lambda,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The prefix-product weights and slopes against the Lagrange basis
    /// written out term by term, and the weights against `lagrange6`.
    #[test]
    fn lagrange_slopes_match_the_basis_written_out() {
        let nodes = [-2.0, -1.0, 0.0, 1.0, 2.0, 3.0];
        for f in [0.0, 0.13, 0.5, 0.999, 1.0, -2.0, 3.0] {
            let (w, dw) = lagrange6_with_slope(f);
            let plain = crate::kernel::weights::lagrange6(f);
            for k in 0..6 {
                let others = || (0..6).filter(move |&m| m != k);
                let denom: f64 = others().map(|m| nodes[k] - nodes[m]).product();
                let value: f64 = others().map(|m| f - nodes[m]).product::<f64>() / denom;
                let slope: f64 = others()
                    .map(|m| {
                        others()
                            .filter(|&l| l != m)
                            .map(|l| f - nodes[l])
                            .product::<f64>()
                    })
                    .sum::<f64>()
                    / denom;
                assert!((w[k] - value).abs() < 1e-14, "f={f} k={k}");
                assert!((w[k] - plain[k]).abs() < 1e-14, "f={f} k={k}");
                assert!(
                    (dw[k] - slope).abs() < 1e-13,
                    "f={f} k={k}: {} {slope}",
                    dw[k]
                );
            }
        }
    }

    /// Interpolated K and A against direct evaluation between rows and
    /// between points. What matters is the error of what a node contributes,
    /// K·W_lo and Re(A·W_osc), against the scale of the kernel (its largest
    /// K·W_lo + h N along the row): the rows are not meant to be accurate
    /// where the blend has switched them off.
    #[test]
    fn interpolation_between_rows_and_points_is_accurate() {
        use super::super::blend::BlendWeights;
        for nu in [0.49, 0.5] {
            for (lo, hi) in [
                ((1e-3f64).ln(), (2e-3f64).ln()),
                (-0.4, 0.3),
                ((8.0f64).ln(), (12.0f64).ln()),
            ] {
                for step_index in [0, 3, 5] {
                    let h = STEPS[step_index];
                    let rows = FilmRows::new(nu, step_index, lo, hi);
                    let blend = BlendWeights::get(step_index);
                    let mut worst = 0.0f64;
                    for s in 0..5 {
                        let lambda = lo + (hi - lo) * (s as f64 + 0.31) / 5.0;
                        let kernel = FilmKernel::new(nu, lambda.exp());
                        let node = rows.stencil(lambda);
                        let tau0 = 0.0123;
                        let cursor = rows.cursor(tau0);
                        let blend_cursor = blend.cursor(tau0);
                        let mut scale = 0.0f64;
                        let mut error = 0.0f64;
                        for k in (-13.0 / h) as i64..=(7.0 / h) as i64 {
                            let tau = tau0 + k as f64 * h;
                            let x = tau.exp();
                            let (w_low, _) = blend.low(&blend_cursor, k);
                            if w_low != 0.0 && tau > FAR_BELOW {
                                let got = rows.full(&cursor, k, &node, false).value
                                    * x
                                    * x
                                    * sphere::g(x);
                                let want = kernel.full(x);
                                if ((got - want) * w_low).abs() > 1e-12 {
                                    eprintln!("  K τ={tau:.3} {:e} {want:e}", (got - want) * w_low);
                                }
                                error = error.max(((got - want) * w_low).abs());
                                scale = scale.max((want * w_low).abs());
                            }
                            if w_low < h {
                                scale = scale.max(kernel.smooth(x) * (h - w_low));
                            }
                            if let Some((w_osc, _)) = blend.oscillation(&blend_cursor, k) {
                                // W_osc carries N_h (`BlendWeights`).
                                let w_osc = w_osc / super::super::blend::half_space_smooth(tau).0;
                                let got = rows.amplitude(&cursor, k, &node, false).value;
                                let want = kernel.amplitude(x);
                                if ((got - want) * w_osc).re.abs() > 1e-12 {
                                    eprintln!(
                                        "  A τ={tau:.3} {:e} {want:e}",
                                        ((got - want) * w_osc).re
                                    );
                                }
                                error = error.max(((got - want) * w_osc).re.abs());
                            }
                        }
                        worst = worst.max(error / scale);
                    }
                    // Far below what the step is used for (the tolerance of
                    // `step_for_tolerance`).
                    let allowed = [5e-5, 5e-6, 5e-7, 5e-9, 2e-9, 2e-9][step_index];
                    eprintln!("ν={nu} λ∈[{lo:.3},{hi:.3}] h={h}: {worst:e}");
                    assert!(worst < allowed, "ν={nu} λ∈[{lo},{hi}] h={h}: {worst:e}");
                }
            }
        }
    }
}
#[cfg(test)]
mod timing {
    use super::*;
    #[test]
    #[ignore]
    fn row_build_time() {
        for (nu, lo) in [(0.5, (1e-3f64).ln()), (0.49, -0.3), (0.5, 2.0)] {
            let t = std::time::Instant::now();
            let _ = FilmRows::new(nu, 3, lo, lo + 0.7);
            eprintln!("ν={nu} λ from {lo:.2}: {:?}", t.elapsed());
        }
    }
}
