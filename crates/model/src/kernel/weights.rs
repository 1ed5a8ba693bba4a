//! Product-integration weights for the friction integrals.
//!
//! Both friction coefficients have the form (see [`super`])
//!
//!   μ(v) = C ∫ dσ Φ(σ) k̃(σ − ln v),
//!
//! with σ = ln(ω a(ω)) the logarithm of "contact size × frequency" (a speed),
//! Φ a smooth function of the material and k̃ a universal kernel. The material
//! is sampled on a uniform grid σ_j = σ₀ + jh and interpolated by local
//! Lagrange polynomials of P points (P even, the P grid values nearest each
//! cell). Writing that interpolant as Φ_I(σ) = Σ_j Φ_j B((σ − σ_j)/h) with the
//! cardinal function B, the integral becomes
//!
//!   μ ≈ C Σ_j Φ_j W(σ_j − ln v),   W(τ) = h ∫ B(u) k̃(τ + hu) du,
//!
//! where W depends on nothing but the kernel — so it is tabulated once, finely
//! in τ, and the kernel's oscillation is integrated exactly instead of being
//! sampled. The error is that of interpolating Φ (analytic in a strip of
//! half-width ≈ π/2 in ln ω for Prony series), O((h/d)^P). Derivatives of μ
//! with respect to a material parameter p need ∫ Ψ k̃′, which the same
//! machinery gives with W′(τ) = −∫ B′(u) k̃(τ + hu) du.
//!
//! Outside the tabulated τ range W follows in closed form from the kernel's
//! asymptotes (powers of x and x² ln x integrate against B in closed form
//! through the moments β(c) = h∫B(u)e^{cu}du).
//!
//! # References
//! - P.J. Davis, P. Rabinowitz, *Methods of Numerical Integration*, 2nd ed.,
//!   Academic Press 1984, §2.10 (product integration).

use std::sync::OnceLock;

use super::chebyshev::PiecewiseChebyshev;
use super::quadrature::gauss_legendre_unit;
use super::{cylinder, sphere, window};
use crate::contact::Shape;

/// Number of grid points of the local Lagrange interpolant.
pub const STENCIL: usize = 10;
/// Table points per grid step.
const SUBDIVISION: usize = 32;
/// Grid steps h available, coarse to fine; [`step_for_tolerance`] picks one
/// of the first six for a half-space. The last two serve only a film under
/// a cylinder, whose factor 1/S narrows the strip of analyticity of the
/// integrand (`friction::film_cylinder`).
pub const STEPS: [f64; 8] = [0.4, 0.28, 0.2, 0.14, 0.1, 0.07, 0.05, 0.035];

/// Six-point Lagrange weights at fractional position f ∈ [0, 1) for nodes
/// −2..3.
#[inline]
pub(crate) fn lagrange6(f: f64) -> [f64; 6] {
    let (fm2, fm1, f0, f1, f2, f3) = (f + 2.0, f + 1.0, f, f - 1.0, f - 2.0, f - 3.0);
    [
        -(fm1 * f0 * f1 * f2 * f3) / 120.0,
        (fm2 * f0 * f1 * f2 * f3) / 24.0,
        -(fm2 * fm1 * f1 * f2 * f3) / 12.0,
        (fm2 * fm1 * f0 * f2 * f3) / 12.0,
        -(fm2 * fm1 * f0 * f1 * f3) / 24.0,
        (fm2 * fm1 * f0 * f1 * f2) / 120.0,
    ]
}

/// Index into [`STEPS`] for a requested relative tolerance of μ.
///
/// Calibrated against the reference values (tests/reference_values.rs) with
/// a margin of about 20: the worst reference case (dynamic cylinder,
/// E1/E0 = 10, just below the friction peak) has relative errors 1.5e-5,
/// 1.0e-6, 4.5e-8 and 2.2e-9 at h = 0.28, 0.2, 0.14 and 0.1 — the error of
/// interpolating an analytic Φ falls like (h/d)^P.
pub fn step_for_tolerance(tolerance: f64) -> usize {
    const LIMITS: [f64; 6] = [1e-3, 1e-4, 1e-5, 1e-7, 1e-9, 0.0];
    LIMITS
        .iter()
        .position(|&limit| tolerance >= limit)
        .unwrap_or(LIMITS.len() - 1)
}

/// Closed-form W(τ) outside the table: Σ a e^{cτ}(b₀ + b₁ τ) terms.
#[derive(Debug, Clone)]
struct FarField {
    /// (coefficient, rate c, moment β(c), first moment β₁(c), log coefficient)
    /// for k ≈ Σ coefficient·e^{cσ}(1 + log_coefficient·σ).
    terms: Vec<(f64, f64, f64, f64, f64)>,
}

impl FarField {
    fn value(&self, tau: f64) -> (f64, f64) {
        let mut w = 0.0;
        let mut dw = 0.0;
        for &(a, c, beta, beta1, l) in &self.terms {
            // W = a e^{cτ}[(1 + lτ)β + l β₁]
            let e = a * (c * tau).exp();
            let inner = (1.0 + l * tau) * beta + l * beta1;
            w += e * inner;
            dw += e * (c * inner + l * beta);
        }
        (w, dw)
    }
}

/// Tabulated W(τ), W′(τ) for one shape and one grid step.
#[derive(Debug)]
pub struct KernelTable {
    step: f64,
    tau_lo: f64,
    delta: f64,
    w: Vec<f64>,
    dw: Vec<f64>,
    low: FarField,
    high: FarField,
}

/// Cardinal function B(u) of P-point local Lagrange interpolation on the
/// integers, and its derivative.
pub(crate) fn cardinal(u: f64) -> (f64, f64) {
    let half = (STENCIL / 2) as i64;
    let cell = u.floor() as i64;
    let first = cell - half + 1;
    let last = cell + half;
    if first > 0 || last < 0 {
        return (0.0, 0.0);
    }
    let mut value = 1.0;
    let mut denom = 1.0;
    for i in first..=last {
        if i != 0 {
            value *= u - i as f64;
            denom *= -(i as f64);
        }
    }
    let mut derivative = 0.0;
    for m in first..=last {
        if m == 0 {
            continue;
        }
        let mut prod = 1.0;
        for i in first..=last {
            if i != 0 && i != m {
                prod *= u - i as f64;
            }
        }
        derivative += prod;
    }
    (value / denom, derivative / denom)
}

/// h∫B(u) e^{cu} du and h∫B(u)(hu) e^{cu} du.
fn moments(step: f64, c: f64) -> (f64, f64) {
    let rule = gauss_legendre_unit(24);
    let half = (STENCIL / 2) as i64;
    let (mut m0, mut m1) = (0.0, 0.0);
    for cell in -half..half {
        for (t, wt) in rule.0.iter().zip(&rule.1) {
            let u = cell as f64 + t;
            let b = cardinal(u).0;
            m0 += wt * b * (c * step * u).exp();
            m1 += wt * b * step * u * (c * step * u).exp();
        }
    }
    (step * m0, step * m1)
}

/// The kernel with its oscillation retired by the window centred at
/// `centre`.
fn windowed(shape: Shape, ln_x: f64, centre: f64) -> f64 {
    let x = ln_x.exp();
    let keep = window::keep_oscillation_at(ln_x, centre);
    match shape {
        Shape::Sphere => {
            if ln_x < window::exact_below_at(centre) {
                x * x * sphere::g(x)
            } else {
                x * x * (sphere::smooth_part(x) + keep * sphere::oscillatory_part(x))
            }
        }
        Shape::Cylinder => {
            if ln_x < window::exact_below_at(centre) {
                cylinder::kernel(x)
            } else {
                cylinder::smooth_part(x) + keep * cylinder::oscillatory_part(x)
            }
        }
    }
}

impl KernelTable {
    /// The table for `shape` and grid step `STEPS[index]`, built on first use.
    pub fn get(shape: Shape, index: usize) -> &'static KernelTable {
        static SPHERE: [OnceLock<KernelTable>; STEPS.len()] =
            [const { OnceLock::new() }; STEPS.len()];
        static CYLINDER: [OnceLock<KernelTable>; STEPS.len()] =
            [const { OnceLock::new() }; STEPS.len()];
        let cells = match shape {
            Shape::Sphere => &SPHERE,
            Shape::Cylinder => &CYLINDER,
        };
        cells[index].get_or_init(|| KernelTable::build(shape, STEPS[index], window::WINDOW_CENTRE))
    }

    /// The cylinder's table for grid step `STEPS[index]` for a cylinder on a
    /// film, built on first use: with the window at
    /// [`window::FILM_WINDOW_CENTRE`] on steps h ≤ 0.07, which resolve the
    /// kernel's oscillation that far; on coarser steps the default table,
    /// whose window costs a film at most about 6e-7 (measured,
    /// `friction::film_cylinder`), below the tolerances ≥ 1e-5 those steps
    /// serve a film.
    pub fn get_film_cylinder(index: usize) -> &'static KernelTable {
        static CYLINDER: [OnceLock<KernelTable>; STEPS.len()] =
            [const { OnceLock::new() }; STEPS.len()];
        if STEPS[index] > 0.07 {
            return KernelTable::get(Shape::Cylinder, index);
        }
        CYLINDER[index].get_or_init(|| {
            KernelTable::build(Shape::Cylinder, STEPS[index], window::FILM_WINDOW_CENTRE)
        })
    }

    fn build(shape: Shape, step: f64, centre: f64) -> KernelTable {
        let reach = (STENCIL / 2) as f64 * step;
        // τ range of the table: below it the small-x expansion of k is exact
        // to rounding, above it the windowed kernel is k_n and k_n's
        // expansion is exact to rounding.
        let (tau_lo, tau_hi) = match shape {
            Shape::Sphere => (-16.0, window::smooth_above_at(centre) + reach + 0.5),
            Shape::Cylinder => (-16.0, 8.0 + reach),
        };
        let smooth_top = window::smooth_above_at(centre);
        debug_assert!(smooth_top < tau_hi - reach);
        let lo = tau_lo - reach - 0.1;
        let mut breaks = Vec::new();
        let mut b = lo;
        while b < -1.0 {
            breaks.push(b);
            b += 0.5;
        }
        b = -1.0;
        // Panels of 1/16 in ln x hold at most 1.8 periods of k_o (period
        // π/x) up to the default window's top; beyond it (a film's wider
        // window) they shrink like 1/x to hold as many.
        let default_top = window::smooth_above();
        while b < smooth_top {
            breaks.push(b);
            b += if b < default_top {
                1.0 / 16.0
            } else {
                (default_top - b).exp() / 16.0
            };
        }
        breaks.push(smooth_top);
        let fast = PiecewiseChebyshev::new(breaks, 14, |s| windowed(shape, s, centre));
        let (cheb_lo, cheb_hi) = fast.range();
        let kernel = |s: f64| -> f64 {
            if s <= cheb_hi && s >= cheb_lo {
                fast.eval(s)
            } else if s > cheb_hi {
                let x = s.exp();
                match shape {
                    Shape::Sphere => x * x * sphere::smooth_part(x),
                    Shape::Cylinder => cylinder::smooth_part(x),
                }
            } else {
                windowed(shape, s, centre)
            }
        };

        let delta = step / SUBDIVISION as f64;
        let count = ((tau_hi - tau_lo) / delta).ceil() as usize + 1;
        let rule = gauss_legendre_unit(24);
        let half = (STENCIL / 2) as i64;
        let mut basis = Vec::new();
        for cell in -half..half {
            for (t, wt) in rule.0.iter().zip(&rule.1) {
                let u = cell as f64 + t;
                let (b, db) = cardinal(u);
                basis.push((u, wt * b, wt * db));
            }
        }
        let mut w = Vec::with_capacity(count);
        let mut dw = Vec::with_capacity(count);
        for m in 0..count {
            let tau = tau_lo + m as f64 * delta;
            let (mut sw, mut sdw) = (0.0, 0.0);
            for &(u, b, db) in &basis {
                let k = kernel(tau + step * u);
                sw += b * k;
                sdw += db * k;
            }
            w.push(step * sw);
            dw.push(-sdw);
        }

        let term = |a: f64, c: f64, l: f64| {
            let (beta, beta1) = moments(step, c);
            (a, c, beta, beta1, l)
        };
        let (low, high) = match shape {
            Shape::Sphere => {
                // G(x) = (1/9) ln(2/x) + c_f for small x.
                let x = 1e-9f64;
                let c_f = sphere::g(x) - (2.0 / x).ln() / 9.0;
                let a = 2f64.ln() / 9.0 + c_f;
                (
                    FarField {
                        terms: vec![term(a, 2.0, -1.0 / (9.0 * a))],
                    },
                    FarField {
                        terms: vec![term(1.0 / 3.0, -2.0, 0.0), term(4.0 / 15.0, -4.0, 0.0)],
                    },
                )
            }
            Shape::Cylinder => (
                FarField {
                    terms: vec![term(0.25, 1.0, 0.0), term(-1.0 / 16.0, 3.0, 0.0)],
                },
                FarField {
                    terms: vec![
                        term(1.0 / std::f64::consts::PI, -2.0, 0.0),
                        term(0.375 / std::f64::consts::PI, -4.0, 0.0),
                        term(-45.0 / 128.0 / std::f64::consts::PI, -6.0, 0.0),
                    ],
                },
            ),
        };
        KernelTable {
            step,
            tau_lo,
            delta,
            w,
            dw,
            low,
            high,
        }
    }

    /// Grid step h in σ.
    pub fn step(&self) -> f64 {
        self.step
    }

    /// W(τ) and W′(τ).
    #[inline]
    pub fn evaluate(&self, tau: f64) -> (f64, f64) {
        self.evaluate_at(&self.cursor(tau), 0)
    }

    /// Prepares evaluations at τ₀ + kh for integer k. Every such point lies at
    /// the same fractional position between table points (the table spacing
    /// is h/`SUBDIVISION`), so the six interpolation weights are computed
    /// once for all of them.
    #[inline]
    pub fn cursor(&self, tau0: f64) -> KernelCursor {
        let q = (tau0 - self.tau_lo) / self.delta;
        let i = q.floor();
        KernelCursor {
            tau0,
            index0: i as i64,
            weights: lagrange6(q - i),
        }
    }

    /// W and W′ at τ₀ + kh, τ₀ from `cursor`.
    #[inline]
    pub fn evaluate_at(&self, cursor: &KernelCursor, k: i64) -> (f64, f64) {
        let i = cursor.index0 + k * SUBDIVISION as i64;
        let n = self.w.len() as i64;
        if i < 2 {
            return self.low.value(cursor.tau0 + k as f64 * self.step);
        }
        if i > n - 4 {
            return self.high.value(cursor.tau0 + k as f64 * self.step);
        }
        let i = i as usize - 2;
        let (w, dw) = (&self.w[i..i + 6], &self.dw[i..i + 6]);
        let c = &cursor.weights;
        let mut value = 0.0;
        let mut slope = 0.0;
        for k in 0..6 {
            value += c[k] * w[k];
            slope += c[k] * dw[k];
        }
        (value, slope)
    }
}

/// Shared interpolation state for W at τ₀ + kh, see [`KernelTable::cursor`].
#[derive(Debug, Clone, Copy)]
pub struct KernelCursor {
    tau0: f64,
    index0: i64,
    weights: [f64; 6],
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cardinal_function_interpolates() {
        assert!((cardinal(0.0).0 - 1.0).abs() < 1e-15);
        for k in 1..6 {
            assert!(cardinal(k as f64).0.abs() < 1e-15);
            assert!(cardinal(-(k as f64)).0.abs() < 1e-15);
        }
        // Symmetric, and reproduces polynomials: Σ_j B(u − j) j² = u².
        for &u in &[0.3, 1.7, -2.2] {
            assert!((cardinal(u).0 - cardinal(-u).0).abs() < 1e-14);
            let s: f64 = (-20..=20)
                .map(|j| cardinal(u - j as f64).0 * (j * j) as f64)
                .sum();
            assert!((s - u * u).abs() < 1e-11);
        }
    }

    #[test]
    fn far_field_joins_table() {
        for (shape, index) in [
            (Shape::Sphere, 2),
            (Shape::Cylinder, 2),
            (Shape::Cylinder, STEPS.len() - 1),
        ] {
            let t = KernelTable::get(shape, index);
            let edge_lo = t.tau_lo + 2.5 * t.delta;
            let (a, da) = t.low.value(edge_lo);
            let (b, db) = t.evaluate(edge_lo);
            assert!(((a - b) / a).abs() < 1e-9, "{shape:?} low {a} {b}");
            assert!(((da - db) / da).abs() < 1e-7, "{shape:?} low' {da} {db}");
            let n = t.w.len();
            let edge_hi = t.tau_lo + (n as f64 - 4.5) * t.delta;
            let (a, da) = t.high.value(edge_hi);
            let (b, db) = t.evaluate(edge_hi);
            assert!(((a - b) / a).abs() < 1e-9, "{shape:?} high {a} {b}");
            assert!(((da - db) / da).abs() < 1e-7, "{shape:?} high' {da} {db}");
        }
    }
}
