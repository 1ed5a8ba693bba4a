//! μ(v) for a modulus that is analytic only between knots (a tabulated
//! master curve): adaptive Gauss–Kronrod quadrature in s = ln ω, split at
//! the knots.
//!
//! The product integration of [`crate::kernel::weights`] interpolates
//! Φ(σ) by 10-point Lagrange polynomials on a uniform σ grid; its error
//! O((h/d)^P) needs Φ analytic in a strip. A table's interpolant is a
//! different function on every interval between its rows: ln E is only C¹
//! there (a jump of its second derivative), so Φ — which holds d ln|E|/d ln ω
//! through the dynamic contact map — has a jump in its first derivative, and
//! at the table's ends, where the interpolant meets the terminal power laws,
//! in Φ itself. Every stencil that straddles a knot then interpolates a kink,
//! and the error falls only like h² (about 1e-4 of μ at tolerance 1e-6).
//!
//! Here the integral is taken as written, in s, over pieces on which the
//! integrand is analytic:
//!
//!   μ(v) = C ∫ ds A(s) k̃(σ(s) − ln v) [1/S(ωd/v)],
//!
//! A = L/r^m, σ = s + ln r(e^s) (both from [`Setup::point`]: no Newton
//! iteration for the contact map is needed in s), k̃ the kernel with its
//! oscillation faded out far out (below) and S the
//! film factor under a cylinder. The first panels end at every knot and are
//! at most [`MAX_PANEL_WIDTH`] wide; the adaptive Gauss–Kronrod (7, 15)
//! rule of [`crate::kernel::gauss_kronrod`] bisects the panel with the
//! largest error until the summed bound |K − G| is below
//! [`TARGET_FRACTION`] × tolerance × μ. On each panel the integrand is
//! analytic, so the Kronrod value converges fast and the bound is
//! pessimistic.
//!
//! The range is σ − ln v ∈ [−T_lo, T_hi]; the tails beyond are bounded as in
//! [`super::grid`], with Φ = A ds/dσ ≤ κ e^{pσ} ([`Setup::tail_bound`]) and
//! |k̃(τ)| ≤ ½ e^{τ} below, ≤ ½ e^{−2τ} above:
//!
//!   tail_lo ≤ C κ v^p e^{−(1+p)T_lo}/(2(1 + p)),
//!   tail_hi ≤ C κ v^p e^{−(2−p)T_hi}/(2(2 − p)),
//!
//! and T is widened until both are below 1 % of the tolerance.
//!
//! The window. Beyond x ≈ 20 the kernel's oscillation has a period π/x in
//! ln x; the product integration drops it there (window centre X = 20),
//! which costs an exponentially small error for an analytic Φ. Against a Φ
//! that is analytic only between knots what the window drops is a sum of
//! boundary terms of integration by parts at the knots where x ≳ X:
//! O(jump of Φ′ · X⁻⁴) under the dynamic contact rule (Φ′ jumps at every
//! knot), measured at up to 4.5e-6 of μ with X = 20 for a table of 10 rows
//! a decade (tests/table_friction.rs). So the quadrature here keeps the
//! oscillation out to a centre that grows as the tolerance falls (see
//! [`window_centre`]), following it with the adaptive panels; the kernel is
//! [`WindowedKernel`], cheap at any x.
//!
//! # References
//! - R. Piessens et al., *QUADPACK*, Springer 1983 (adaptive Gauss–Kronrod).
//! - P.J. Davis, P. Rabinowitz, *Methods of Numerical Integration*, 2nd ed.,
//!   Academic Press 1984, §2.9 (integrands with known singular points:
//!   split the range there).

use std::cell::Cell;

use super::setup::{Point, Setup};
use crate::error::ModelError;
use crate::film::film_factor;
use crate::kernel::gauss_kronrod::{Failure, Targets, integrate};
use crate::kernel::window;
use crate::kernel::windowed::{MAX_CENTRE, WindowedKernel};
use crate::modulus::ViscoelasticModulus;
use crate::scene::Scene;

/// Widest first panel in s: the kernel varies on a scale of one in ln x.
const MAX_PANEL_WIDTH: f64 = 1.0;

/// The summed Kronrod error bound asked for, as a fraction of tolerance × μ.
const TARGET_FRACTION: f64 = 0.1;

/// Panels the adaptive rule may use per speed.
const MAX_PANELS: usize = 200_000;

/// Starting reach of the range below and above ln v, in σ.
const REACH: (f64, f64) = (40.0, 20.0);

/// Largest total reach in σ before the tails are declared unbounded.
const MAX_REACH: f64 = 2000.0;

/// μ at each of `speeds` (m/s) for a material with the given knots
/// (angular frequencies, rad/s, increasing).
pub(super) fn friction_sweep<M: ViscoelasticModulus>(
    scene: &Scene<M>,
    setup: &Setup,
    speeds: &[f64],
    knots: &[f64],
) -> Result<Vec<f64>, ModelError> {
    let knots: Vec<f64> = knots.iter().map(|w| w.ln()).collect();
    let film = scene
        .substrate()
        .film_thickness
        .map(|d| (d, scene.substrate().poisson));
    speeds
        .iter()
        .map(|&v| one_speed(scene, setup, &knots, film, v))
        .collect()
}

/// μ at one speed.
fn one_speed<M: ViscoelasticModulus>(
    scene: &Scene<M>,
    setup: &Setup,
    knots: &[f64],
    film: Option<(f64, f64)>,
    v: f64,
) -> Result<f64, ModelError> {
    let material = scene.material();
    let kernel = WindowedKernel::get(setup.shape);
    let tolerance = scene.tolerance();
    let ln_centre = window_centre(tolerance).ln();
    let ln_v = v.ln();
    // The first failure seen inside the integrand; the integrand then
    // returns NaN, which stops the quadrature.
    let fault: Cell<Option<ModelError>> = Cell::new(None);
    let point = |s: f64| {
        let omega = s.exp();
        let (e, slope) = material.modulus_and_log_slope(omega);
        setup.point(s, omega, e, slope)
    };
    let integrand = |s: f64| -> [f64; 1] {
        let p = point(s);
        if setup.static_ln_size.is_none() && !(p.dsigma_ds > 0.0 && p.sigma.is_finite()) {
            fault.set(Some(ModelError::ContactMapNotIncreasing {
                omega: p.omega,
                exponent: setup.n,
            }));
            return [f64::NAN];
        }
        let f = match film {
            Some((d, nu)) => 1.0 / film_factor(p.omega * d / v, nu),
            None => 1.0,
        };
        [p.a * f * kernel.eval(p.sigma - ln_v, ln_centre)]
    };
    // ∫ over [a, b] in s, first panels ending at every knot between; the
    // target is relative to this piece's value, or absolute (for the tails
    // added later, against the sum so far).
    let piece = |a: f64, b: f64, absolute: f64| -> Result<f64, ModelError> {
        let mut breaks = vec![a];
        for &k in knots.iter().filter(|&&k| k > a && k < b) {
            push_subdivided(&mut breaks, k);
        }
        push_subdivided(&mut breaks, b);
        let targets = Targets {
            absolute: [absolute],
            relative: if absolute > 0.0 {
                0.0
            } else {
                TARGET_FRACTION * tolerance
            },
        };
        match integrate(&integrand, &breaks, targets, MAX_PANELS) {
            Ok(integral) => Ok(integral.value[0]),
            Err(Failure::NotFinite { .. }) => {
                Err(fault.take().unwrap_or(ModelError::TooManyQuadratureNodes))
            }
            Err(_) => Err(ModelError::TooManyQuadratureNodes),
        }
    };
    let p = setup.tail_exponent;
    let tail_scale = setup.prefactor * setup.tail_bound * (p * ln_v).exp() * 0.5;
    let (mut reach_lo, mut reach_hi) = REACH;
    let mut s_lo = range_end(&point, setup, ln_v - reach_lo, -1.0);
    let mut s_hi = range_end(&point, setup, ln_v + reach_hi, 1.0);
    let mut sum = piece(s_lo, s_hi, 0.0)?;
    // Widen the range, a piece at a time, until the bounded tails beyond it
    // are below 1 % of the tolerance.
    loop {
        let mu = setup.prefactor * sum;
        let tail_lo = tail_scale * (-(1.0 + p) * reach_lo).exp() / (1.0 + p);
        let tail_hi = tail_scale * (-(2.0 - p) * reach_hi).exp() / (2.0 - p);
        let allowed = 0.01 * tolerance * mu.abs();
        if tail_lo <= allowed && tail_hi <= allowed {
            return Ok(mu);
        }
        if reach_lo + reach_hi > MAX_REACH {
            return Err(ModelError::TooManyQuadratureNodes);
        }
        let absolute = TARGET_FRACTION * tolerance * sum.abs();
        if tail_lo > allowed {
            reach_lo *= 1.5;
            let end = range_end(&point, setup, ln_v - reach_lo, -1.0);
            sum += piece(end, s_lo, absolute)?;
            s_lo = end;
        }
        if tail_hi > allowed {
            reach_hi *= 1.5;
            let end = range_end(&point, setup, ln_v + reach_hi, 1.0);
            sum += piece(s_hi, end, absolute)?;
            s_hi = end;
        }
    }
}

/// The centre X of the window that fades the kernel's oscillation out, for
/// a requested relative tolerance: X = 20 (the product integration's) at
/// 1e-4 and above, growing like tolerance^{−1/4} below — what the window
/// drops at a kink of Φ falls like X⁻⁴ — up to [`MAX_CENTRE`].
fn window_centre(tolerance: f64) -> f64 {
    (window::WINDOW_CENTRE * (1e-4 / tolerance).powf(0.25)).clamp(window::WINDOW_CENTRE, MAX_CENTRE)
}

/// Appends `end` to `breaks`, with equal steps between if the gap from the
/// last break is wider than [`MAX_PANEL_WIDTH`].
fn push_subdivided(breaks: &mut Vec<f64>, end: f64) {
    let start = *breaks.last().expect("starts with the lower end");
    let pieces = ((end - start) / MAX_PANEL_WIDTH).ceil().max(1.0) as usize;
    for i in 1..pieces {
        breaks.push(start + (end - start) * i as f64 / pieces as f64);
    }
    breaks.push(end);
}

/// An s beyond which σ(s) passes `target` (`outward` = −1: σ(s) ≤ target;
/// +1: σ(s) ≥ target). σ − s = ln r varies slowly and dσ/ds lies between
/// (n − 1)/n and about 1 where the map is increasing, so steps
/// s += target − σ(s) settle s to 0.01; one unit more in σ is a margin
/// that costs a negligible stretch of integrand.
fn range_end<F: Fn(f64) -> Point>(point: &F, setup: &Setup, target: f64, outward: f64) -> f64 {
    if let Some(ln_r0) = setup.static_ln_size {
        return target - ln_r0 + outward;
    }
    let mut s = target;
    for _ in 0..50 {
        let sigma = point(s).sigma;
        if !sigma.is_finite() {
            break;
        }
        let miss = target - sigma;
        s += miss;
        if miss.abs() < 0.01 {
            break;
        }
    }
    s + outward
}
