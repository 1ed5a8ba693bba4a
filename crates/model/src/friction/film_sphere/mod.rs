//! μ(v) of a sphere rolling on a viscoelastic film of thickness d bonded to
//! a rigid base, and its derivatives with respect to Prony parameters: the
//! product integration of [`super`] with the film kernel of
//! [`crate::kernel::film_sphere`].
//!
//! # Formula
//!
//! The film divides L(ω) by S(qd) in Eq. (17). With ω = q v cos φ and
//! u = 1/cos φ, as for the half-space ([`crate::kernel::sphere`]),
//!
//!   μ = C ∫ ds A(s) K(σ(s) − ln v, λ(s)),   C = 18 F_N/π²,
//!   K(τ, λ) = x² ∫₁^∞ f(xu)/S(xuδ) du/√(u² − 1),   x = e^τ, δ = e^λ,
//!
//! with σ = ln(ω r(ω)), λ = ln(d/r(ω)) (r the Hertz contact radius, dynamic
//! or static rule, m) and A = L/r² as in [`super`]. The kernel depends on the
//! speed only through τ = σ − ln v, like the half-space kernel; its second
//! argument λ belongs to the node (constant for the static rule).
//!
//! # Method
//!
//! K is split (see [`crate::kernel::film_sphere`]) as
//!
//!   K̃ = (1 − χ(τ)) K + χ(τ) N + Re[A(τ, λ) E(τ)],   E = χ (1 − χ_w) e^{2ix},
//!
//! with χ a smooth step at x ≈ 1, N and A smooth (non-oscillating) in both
//! variables and χ_w the window of [`crate::kernel::window`] (the same
//! exponentially small change as for the half-space). On the σ grid,
//!
//!   μ ≈ C Σ_j Φ_j [K_j W_lo(τ_j) + N_j (h − W_lo(τ_j)) + Re(A_j W_osc(τ_j))],
//!
//! where W_lo and W_osc are universal product-integration weights of 1 − χ
//! and E, and K_j, N_j, A_j are the smooth factors at the node (K and A
//! interpolated from rows of constant λ, N from the moments M₄, M₆). What is
//! interpolated across the stencil is Φ·K, Φ·N and Φ·A — smooth functions of
//! σ even where λ varies with σ — so the product rule keeps its order.
//! Derivatives with respect to a material parameter p move σ and λ together
//! (∂σ/∂p = −∂λ/∂p = ∂ ln r/∂p), i.e. they need ∂K/∂ln x at fixed z = x δ:
//! D = ∂_τ − ∂_λ applied to the same split, with the weights' derivatives for
//! the factors that move with τ.
//!
//! The sums are truncated like the half-space's: below τ = −2 the film
//! kernel falls at least like e^{τ} (like x² in fact, for every film), so
//! the node's own weight bounds the rest; above the window the weight is
//! h N ≤ h x² G_n (1/S ≤ 1), and the half-space bound applies to that.
//!
//! # References
//! - B.N.J. Persson, "Rolling friction for hard cylinder and sphere on
//!   viscoelastic solid", Eur. Phys. J. E 33 (2010) 327–333, Eq. (17).
//! - P.J. Davis, P. Rabinowitz, *Methods of Numerical Integration*, 2nd ed.,
//!   Academic Press 1984, §2.10 (product integration).

use std::sync::Arc;

use num_complex::Complex64;

use super::Stencil;
use super::grid::{Grid, Node};
use super::setup::Setup;
use crate::contact::Shape;
use crate::error::ModelError;
use crate::kernel::film_sphere::blend::{BlendCursor, BlendWeights, half_space_smooth_at};
use crate::kernel::film_sphere::moments::SmoothMoments;
use crate::kernel::film_sphere::rows::{FilmRows, RowCursor, RowStencil};
use crate::kernel::weights::{KernelCursor, KernelTable, STENCIL, STEPS};
use crate::kernel::window;

/// The film kernel state of one sweep: rows, weights and the nodes' places
/// between rows.
pub(super) struct FilmSphere {
    poisson: f64,
    step_index: usize,
    step: f64,
    ln_thickness: f64,
    rows: FilmRows,
    lambda_range: (f64, f64),
    blend: &'static BlendWeights,
    half_space: &'static KernelTable,
    moments: Arc<SmoothMoments>,
    /// Row stencils of nodes j ≥ 0 and j < 0 (j = −1 first).
    up: Vec<(f64, RowStencil)>,
    down: Vec<(f64, RowStencil)>,
}

/// λ = ln(d/r) of a node.
fn node_lambda(ln_thickness: f64, node: &Node) -> f64 {
    ln_thickness - (node.point.sigma - node.s)
}

impl FilmSphere {
    /// For film thickness `thickness` (m), Poisson ratio `poisson`, grid step
    /// `STEPS[step_index]` and contact radii between exp(`ln_r_lo`) and
    /// exp(`ln_r_hi`) (the rows for that range are built at once; nodes
    /// outside it extend it).
    pub(super) fn new(
        thickness: f64,
        poisson: f64,
        step_index: usize,
        ln_r_lo: f64,
        ln_r_hi: f64,
    ) -> FilmSphere {
        let ln_thickness = thickness.ln();
        let lambda_range = (ln_thickness - ln_r_hi, ln_thickness - ln_r_lo);
        FilmSphere {
            poisson,
            step_index,
            step: STEPS[step_index],
            ln_thickness,
            rows: FilmRows::new(poisson, step_index, lambda_range.0, lambda_range.1),
            lambda_range,
            blend: BlendWeights::get(step_index),
            half_space: KernelTable::get(Shape::Sphere, step_index),
            moments: SmoothMoments::get(poisson),
            up: Vec::new(),
            down: Vec::new(),
        }
    }

    /// Makes sure node j has its (λ, row stencil), extending the rows if λ
    /// is new.
    fn node_stencil<F: Fn(f64) -> (Complex64, Complex64)>(
        &mut self,
        grid: &mut Grid<'_, F>,
        j: i64,
    ) -> Result<(), ModelError> {
        let (list, index) = if j >= 0 {
            (&self.up, j as usize)
        } else {
            (&self.down, (-j - 1) as usize)
        };
        if index < list.len() {
            return Ok(());
        }
        loop {
            let (next, len) = if j >= 0 {
                (self.up.len() as i64, self.up.len())
            } else {
                (-(self.down.len() as i64) - 1, self.down.len())
            };
            let node = grid.node(next)?;
            let lambda = node_lambda(self.ln_thickness, &node);
            if lambda < self.lambda_range.0 || lambda > self.lambda_range.1 {
                self.lambda_range = (
                    self.lambda_range.0.min(lambda),
                    self.lambda_range.1.max(lambda),
                );
                self.rows = FilmRows::new(
                    self.poisson,
                    self.step_index,
                    self.lambda_range.0,
                    self.lambda_range.1,
                );
                // Earlier stencils index the old rows: recompute them.
                self.up.clear();
                self.down.clear();
                return self.node_stencil(grid, j);
            }
            let entry = (lambda, self.rows.stencil(lambda));
            if j >= 0 {
                self.up.push(entry);
            } else {
                self.down.push(entry);
            }
            if len == index {
                return Ok(());
            }
        }
    }

    /// (λ, row stencil) of node j, after [`Self::node_stencil`].
    #[inline]
    fn stencil_of(&self, j: i64) -> &(f64, RowStencil) {
        if j >= 0 {
            &self.up[j as usize]
        } else {
            &self.down[(-j - 1) as usize]
        }
    }

    /// The product-integration weight of node `k` steps from the cursors'
    /// origin, and (if `slopes`) the weight of D K̃.
    #[inline]
    fn weight(
        &self,
        Cursors {
            blend: blend_cursor,
            half_space: half_cursor,
            rows: row_cursor,
        }: &Cursors,
        k: i64,
        (tau, inverse_x2): (f64, f64),
        (lambda, stencil): &(f64, RowStencil),
        slopes: bool,
    ) -> (f64, f64) {
        let (w_low, dw_low) = self.blend.low(blend_cursor, k);
        let mut w = 0.0;
        let mut dw = 0.0;
        if w_low != 0.0 || dw_low != 0.0 {
            // K = R k_half: the weights carry k_half (the half-space's own
            // below the blend), the rows the smooth ratio R.
            let (w_full, dw_full) = self
                .blend
                .full(blend_cursor, k)
                .unwrap_or_else(|| self.half_space.evaluate_at(half_cursor, k));
            let ratio = self.rows.full(row_cursor, k, stencil, slopes);
            w += ratio.value * w_full;
            dw += ratio.value * dw_full + (ratio.d_tau - ratio.d_lambda) * w_full;
        }
        let (w_smooth, dw_smooth) = self.blend.smooth(blend_cursor, k, inverse_x2);
        let oscillation = self.blend.oscillation(blend_cursor, k);
        if w_smooth != 0.0 || dw_smooth != 0.0 || oscillation.is_some() {
            // The nodes carry N/N_h and A/N_h (see [`BlendWeights`]).
            let (n_half, dn_half) = half_space_smooth_at(inverse_x2);
            if w_smooth != 0.0 || dw_smooth != 0.0 {
                let [m4, m6] = self.moments.at(tau + *lambda);
                let (c4, c6) = (2.0 / 3.0, 8.0 / 15.0);
                // N/N_h = (m₆ + m₄x²)/(c₆ + c₄x²), written in u = 1/x².
                let u = inverse_x2;
                let den = c6 * u + c4;
                let ratio = (m6 * u + m4) / den;
                // D(N/N_h): the moments are constant at fixed z.
                let d_ratio = 2.0 * u * (m4 * c6 - c4 * m6) / (den * den);
                w += ratio * w_smooth;
                dw += ratio * dw_smooth + d_ratio * w_smooth;
            }
            if let Some((w_osc, dw_osc)) = oscillation {
                let a = self.rows.amplitude(row_cursor, k, stencil, slopes);
                let ratio = a.value / n_half;
                w += (ratio * w_osc).re;
                if slopes {
                    let d_ratio = (a.d_tau - a.d_lambda - ratio * dn_half) / n_half;
                    dw += (d_ratio * w_osc + ratio * dw_osc).re;
                }
            }
        }
        (w, dw)
    }
}

/// The fractional positions of one speed's nodes on the tables: all its
/// nodes τ₀ + kh share them.
struct Cursors {
    blend: BlendCursor,
    half_space: KernelCursor,
    rows: RowCursor,
}

/// Sums μ for one speed over the shared grid, extending it as needed (the
/// film counterpart of [`super::one_speed`]).
pub(super) fn one_speed<F: Fn(f64) -> (Complex64, Complex64)>(
    grid: &mut Grid<'_, F>,
    setup: &Setup,
    film: &mut FilmSphere,
    tolerance: f64,
    v: f64,
    mut record: Option<&mut Stencil>,
) -> Result<f64, ModelError> {
    let h = film.step;
    let t = v.ln();
    let j0 = ((t - grid.origin()) / h).round() as i64;
    let eps = 0.02 * tolerance;
    let tau0 = grid.origin() + j0 as f64 * h - t;
    let cursors = Cursors {
        blend: film.blend.cursor(tau0),
        half_space: film.half_space.cursor(tau0),
        rows: film.rows.cursor(tau0),
    };
    let slopes = record.is_some();
    // Above this τ the weight is h N: the window and blend are done.
    let up_start = window::smooth_above() + (STENCIL / 2) as f64 * h + 0.2;
    let mut sum = 0.0;
    for direction in [1i64, -1] {
        let mut j = if direction > 0 { j0 } else { j0 - 1 };
        // 1/x² = e^{−2τ}, updated by a factor per node.
        let factor = (-2.0 * direction as f64 * h).exp();
        let mut inverse_x2 = (-2.0 * (tau0 + (j - j0) as f64 * h)).exp();
        loop {
            let node = grid.node(j)?;
            film.node_stencil(grid, j)?;
            let stencil = film.stencil_of(j);
            let k = j - j0;
            let tau = tau0 + k as f64 * h;
            let (w, dw) = film.weight(&cursors, k, (tau, inverse_x2), stencil, slopes);
            sum += node.phi * w;
            if let Some(r) = record.as_deref_mut() {
                r.push((j, w, dw));
            }
            let stop = if direction > 0 {
                tau > up_start && {
                    let u = inverse_x2;
                    let bound_weight = h * (u / 3.0 + 4.0 * u * u / 15.0);
                    node.up_bound * bound_weight <= eps * sum.abs()
                }
            } else {
                tau < -2.0 && node.down_bound * w.abs() <= eps * sum.abs()
            };
            if stop {
                break;
            }
            j += direction;
            inverse_x2 *= factor;
        }
    }
    if !sum.is_finite() {
        return Err(ModelError::FilmNotFinite {
            what: "μ is",
            speed: v,
        });
    }
    Ok(setup.prefactor * sum)
}
