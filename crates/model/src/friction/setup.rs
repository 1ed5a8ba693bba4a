//! Scene constants of the friction integrals, and the per-frequency material
//! function Φ of the product integration (see [`crate::kernel::weights`]).
//!
//! With n = 3 (sphere) or 2 (cylinder), m = n − 1, the contact size
//! r(ω) = (K/|E_eff(ω)|)^{1/n} (K = 3F_N R/4 or 4 f_N R/π; |E_eff(0)| for
//! the static rule), σ(s) = s + ln r(e^s) and L = −Im 1/E_eff:
//!
//!   μ(v) = C ∫ ds A(s) k(σ(s) − ln v),   A = L/r^m,
//!   C = 18 F_N/π² (sphere, Eq. 17) or 8 f_N/π (cylinder, Eq. 11).
//!
//! In σ the integrand is Φ(σ) = A·ds/dσ with ds/dσ = 1/(1 − (1/n) d ln|E|/ds).

use std::f64::consts::PI;

use num_complex::Complex64;

use crate::contact::{ContactSize, Shape};
use crate::error::ModelError;
use crate::modulus::ViscoelasticModulus;
use crate::scene::Scene;

/// Scene constants needed at every node.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Setup {
    pub shape: Shape,
    /// 1 − ν².
    pub plane_strain: f64,
    /// ln(1 − ν²).
    pub ln_plane_strain: f64,
    /// ln K in r^n = K/|E_eff|.
    pub ln_k: f64,
    /// n.
    pub n: f64,
    /// m = n − 1.
    pub m: f64,
    /// Prefactor C.
    pub prefactor: f64,
    /// ln r0 (static contact size) when the static rule applies.
    pub static_ln_size: Option<f64>,
    /// Static modulus E(0), Pa.
    pub static_modulus: f64,
    /// Upper bound κ ≥ Φ(σ) e^{−pσ}, used to bound the truncated tails.
    pub tail_bound: f64,
    /// p of [`crate::modulus::ViscoelasticModulus::loss_exponent_at_zero`].
    pub tail_exponent: f64,
    /// For a positive relaxation spectrum, the constants (c₁, c₂) of the
    /// local bounds on Φ above a node j, see [`Setup::upper_tail_bound`].
    pub local_bounds: Option<(f64, f64)>,
}

/// One evaluation of the integrand's material part at s = ln ω.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Point {
    /// σ(s).
    pub sigma: f64,
    /// dσ/ds.
    pub dsigma_ds: f64,
    /// A = L/r^m.
    pub a: f64,
    /// 1/E (Young's), 1/Pa.
    pub inv_e: Complex64,
    /// r^m.
    pub size_m: f64,
    /// ω = e^s, rad/s.
    pub omega: f64,
    /// E′(ω), Pa.
    pub storage: f64,
}

impl Setup {
    pub(crate) fn new<M: ViscoelasticModulus>(scene: &Scene<M>) -> Result<Self, ModelError> {
        let g = scene.geometry();
        let shape = g.shape;
        let n = shape.contact_exponent();
        let (k, prefactor) = match shape {
            Shape::Sphere => (0.75 * g.load * g.radius, 18.0 * g.load / (PI * PI)),
            Shape::Cylinder => (4.0 * g.load * g.radius / PI, 8.0 * g.load / PI),
        };
        let plane_strain = scene.plane_strain_factor();
        let material = scene.material();
        let static_modulus = material.static_modulus();
        let static_ln_size = match scene.contact() {
            ContactSize::Static => Some((k.ln() - (static_modulus / plane_strain).ln()) / n),
            ContactSize::Dynamic => None,
        };
        let (w_lo, w_hi) = material.structure_range();
        if !(w_lo > 0.0 && w_hi >= w_lo && w_hi.is_finite()) {
            return Err(ModelError::UnusableFrequencyRange {
                low: w_lo,
                high: w_hi,
            });
        }
        // Bound of L(ω)/ω^p and of 1/r^{m+p} over all ω (p = the exponent of
        // the low-frequency loss, 1 for a solid with bounded relaxation
        // times), by sampling 20 points per decade across (and beyond) the
        // structure: for Prony series L(ω) ≤ L′(0)ω holds exactly (positive
        // retardation spectrum); the sampling covers other moduli.
        let p = material.loss_exponent_at_zero();
        if !(p > 0.0 && p <= 1.0) {
            return Err(ModelError::LossExponentOutOfRange { exponent: p });
        }
        let (sup_l_over_power, max_abs_e) = match material.relaxation_bound() {
            Some(e1) if p == 1.0 => (
                plane_strain * material.loss_slope_at_zero() / (static_modulus * static_modulus),
                e1,
            ),
            _ => {
                let mut sup_l_over_power = 0.0f64;
                let mut max_abs_e = static_modulus;
                let decades = (w_hi / w_lo).log10() + 6.0;
                let count = (decades * 20.0).ceil() as usize + 1;
                for i in 0..count {
                    let omega = w_lo * 1e-3 * 10f64.powf(i as f64 / 20.0);
                    let e = material.modulus(omega);
                    let l = -plane_strain * (1.0 / e).im;
                    sup_l_over_power = sup_l_over_power.max(l / omega.powf(p));
                    max_abs_e = max_abs_e.max(e.norm());
                }
                (1.5 * sup_l_over_power, max_abs_e)
            }
        };
        if !(sup_l_over_power.is_finite() && max_abs_e.is_finite()) {
            return Err(ModelError::LossComplianceUnbounded);
        }
        let m = n - 1.0;
        let ln_r_min = match static_ln_size {
            Some(ln_r0) => ln_r0,
            None => (k.ln() - (max_abs_e / plane_strain).ln()) / n,
        };
        // Φ = A ds/dσ ≤ (L/ω^p)·ω^p/r^m·n/(n−1), and ω = e^σ/r.
        let tail_bound = sup_l_over_power * (-(m + p) * ln_r_min).exp() * n / (n - 1.0);
        Ok(Setup {
            shape,
            plane_strain,
            ln_plane_strain: plane_strain.ln(),
            ln_k: k.ln(),
            n,
            m,
            prefactor,
            static_ln_size,
            static_modulus,
            tail_bound,
            tail_exponent: p,
            local_bounds: material.relaxation_bound().map(|_| {
                let ds_dsigma_max = n / (n - 1.0);
                (
                    (-(m + 1.0) * ln_r_min).exp() * ds_dsigma_max,
                    plane_strain * (-m * ln_r_min).exp() * ds_dsigma_max,
                )
            }),
        })
    }

    /// For a positive relaxation spectrum, bounds on Φ(σ) for σ ≥ σ_j from
    /// node j's own material state: (κ_j, B_j) with Φ ≤ κ_j e^{σ} and
    /// Φ ≤ B_j. `None` when only the global bound Φ ≤ κe^{pσ} holds.
    ///
    /// For a positive relaxation spectrum the loss compliance is a sum of
    /// Debye terms, so L(ω)/ω does not increase with ω, and E′ does not
    /// decrease; with r ≥ r_min and ds/dσ ≤ n/(n − 1), for ω ≥ ω_j
    ///
    ///   Φ ≤ (L_j/ω_j) ω r^{−m} n/(n−1) ≤ c₁ (L_j/ω_j) e^{σ},
    ///   Φ ≤ (1 − ν²)/(E′_j r^m) · n/(n−1) ≤ c₂/E′_j.
    ///
    /// The first is far tighter than the global bound once the node has
    /// passed relaxation times (L/ω has dropped); the second lets the
    /// kernel's e^{−2τ} decay act without a growing factor.
    #[inline]
    pub(crate) fn upper_tail_bound(&self, point: &Point) -> Option<(f64, f64)> {
        self.local_bounds.map(|(c1, c2)| {
            let loss = point.a * point.size_m;
            (
                (c1 * loss / point.omega).min(self.tail_bound),
                c2 / point.storage,
            )
        })
    }

    /// Evaluates the material part at s = ln ω (ω = e^s passed in, rad/s)
    /// from E* and dE*/d ln ω.
    #[inline]
    pub(crate) fn point(&self, s: f64, omega: f64, e: Complex64, e_slope: Complex64) -> Point {
        let norm_sqr = e.norm_sqr();
        let inv_e = e.conj() / norm_sqr;
        let loss_compliance = -self.plane_strain * inv_e.im;
        let (ln_r, dsigma_ds) = match self.static_ln_size {
            Some(ln_r0) => (ln_r0, 1.0),
            None => {
                // ln|E_eff| = ½ ln|E|² − ln(1 − ν²), without hypot's cost.
                let ln_abs_e_eff = 0.5 * norm_sqr.ln() - self.ln_plane_strain;
                let dln_e = (e_slope * inv_e).re;
                ((self.ln_k - ln_abs_e_eff) / self.n, 1.0 - dln_e / self.n)
            }
        };
        let size_m = (self.m * ln_r).exp();
        Point {
            sigma: s + ln_r,
            dsigma_ds,
            a: loss_compliance / size_m,
            inv_e,
            size_m,
            omega,
            storage: e.re,
        }
    }
}
