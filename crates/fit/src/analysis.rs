//! What the data determine: the probed window, which relaxation times the
//! data constrain, the noise level, and 1σ bands on E′, E″ and tan δ.
//!
//! At the optimum θ̂ with residual Jacobian J (data rows J_d, penalty rows
//! √λ L), the Gauss–Newton curvature of V/2 is H = JᵀJ = J_dᵀJ_d + λLᵀL.
//!
//! - Influence trace: t = tr(H⁻¹ J_dᵀJ_d), the effective number of
//!   parameters the data fix (≤ free parameters; smaller with smoothing).
//! - Noise: s² = 1 when σ is measured (residuals are in units of σ), else
//!   s² = misfit/(N − t), the residual variance of a relative-error model.
//! - Covariance: C = s² H⁻¹ (the curvature of V at the optimum), via a
//!   pseudo-inverse so that directions the data and penalty leave flat show
//!   up as large, honest uncertainties instead of a failure.
//! - Determined terms: τ_k is determined when the data alone resolve its
//!   ln H_k: changing ln H_k by one (a factor e) moves the misfit by at least
//!   one noise unit, ‖J_d e_k‖² ≥ s², and 1/τ_k lies within a decade of the
//!   probed window.
//! - Window: the band v/r … 20 v/r (r the fitted dynamic contact size) over
//!   the data's speeds.
//! - Bands: σ_f(ω)² = ∇f C ∇fᵀ for f = E′, E″, tan δ, |E| (linearised).
//!
//! # References
//! - P.C. Hansen, *Rank-Deficient and Discrete Ill-Posed Problems*, SIAM
//!   1998, §7 (influence matrix, GCV).
//! - W.H. Press et al., *Numerical Recipes*, 3rd ed., §15.5 (covariance
//!   from the curvature matrix).

use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;
use rollfit_model::{Prony, ViscoelasticModulus};

use crate::parametrization::{Mapped, Parametrization, one_minus_debye};
use crate::params::RollingSetup;
use crate::tau_grid::contact_size;

/// Curvature-based statistics at an optimum.
#[derive(Debug, Clone)]
pub(crate) struct Curvature {
    /// C = s² H⁺.
    pub covariance: DMatrix<f64>,
    /// tr(H⁺ J_dᵀJ_d).
    pub effective_parameters: f64,
    /// s².
    pub noise_variance: f64,
    /// ‖J_d e_k‖² per free parameter.
    pub sensitivity: Vec<f64>,
}

/// Pseudo-inverse of a symmetric positive semi-definite matrix, dropping
/// eigenvalues below 1e-12 of the largest.
fn pseudo_inverse(h: &DMatrix<f64>) -> DMatrix<f64> {
    let eig = h.clone().symmetric_eigen();
    let largest = eig.eigenvalues.iter().fold(0.0f64, |m, &v| m.max(v.abs()));
    let cutoff = 1e-12 * largest;
    let inv: DVector<f64> = eig
        .eigenvalues
        .map(|v| if v > cutoff { 1.0 / v } else { 0.0 });
    &eig.eigenvectors * DMatrix::from_diagonal(&inv) * eig.eigenvectors.transpose()
}

/// Statistics from the full residual Jacobian `jacobian` whose first
/// `data_count` rows are data residuals and whose last row is the E1_max
/// bound.
pub(crate) fn curvature(
    jacobian: &DMatrix<f64>,
    data_count: usize,
    misfit: f64,
    sigma_known: bool,
) -> Curvature {
    // The last row is the E1_max bound: a guard against runaway steps, not
    // information about the material, so it does not narrow the band.
    let informative = jacobian.rows(0, jacobian.nrows() - 1);
    let h = informative.transpose() * informative;
    let jd = jacobian.rows(0, data_count);
    let hd = jd.transpose() * jd;
    let h_inv = pseudo_inverse(&h);
    let effective_parameters = (&h_inv * &hd).trace();
    let dof = (data_count as f64 - effective_parameters).max(1.0);
    let noise_variance = if sigma_known { 1.0 } else { misfit / dof };
    let sensitivity = (0..jacobian.ncols()).map(|k| hd[(k, k)]).collect();
    Curvature {
        covariance: h_inv * noise_variance,
        effective_parameters,
        noise_variance,
        sensitivity,
    }
}

/// The probed window [ω_min, ω_max] (rad/s) of speeds `speeds` on `prony`:
/// ω_min solves ω r(ω) = v_min, ω_max is 20 times the ω solving
/// ω r(ω) = v_max, with r the dynamic (or static) contact size.
pub(crate) fn probed_window(setup: &RollingSetup, prony: &Prony, speeds: (f64, f64)) -> (f64, f64) {
    let dynamic = matches!(setup.contact, rollfit_model::ContactSize::Dynamic);
    let size_at = |omega: f64| {
        let e = if dynamic {
            prony.modulus(omega).norm()
        } else {
            prony.static_modulus()
        };
        contact_size(setup, e)
    };
    // ω r(ω) is increasing; a fixed-point iteration on ω = v/r(ω) converges
    // because r varies like |E|^(−1/3) or slower.
    let solve = |v: f64| {
        let mut omega = v / size_at(0.0);
        for _ in 0..50 {
            let next = v / size_at(omega);
            if ((next - omega) / omega).abs() < 1e-10 {
                return next;
            }
            omega = next;
        }
        omega
    };
    (solve(speeds.0), 20.0 * solve(speeds.1))
}

/// One row of the recovered master curve with 1σ uncertainties.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModulusPoint {
    /// Angular frequency, rad/s.
    pub omega: f64,
    /// E′, Pa.
    pub storage: f64,
    /// E″, Pa.
    pub loss: f64,
    /// tan δ.
    pub tan_delta: f64,
    /// |E*|, Pa.
    pub magnitude: f64,
    /// 1σ of E′, Pa.
    pub storage_sigma: f64,
    /// 1σ of E″, Pa.
    pub loss_sigma: f64,
    /// 1σ of tan δ.
    pub tan_delta_sigma: f64,
    /// 1σ of |E*|, Pa.
    pub magnitude_sigma: f64,
}

/// E*(ω) on the fitted series with its linearised 1σ band.
pub(crate) fn modulus_point(
    param: &Parametrization,
    mapped: &Mapped,
    covariance: &DMatrix<f64>,
    omega: f64,
) -> ModulusPoint {
    let n = param.terms();
    let mut e = Complex64::new(mapped.static_modulus, 0.0);
    let mut grad_p = vec![Complex64::new(1.0, 0.0)];
    for (k, &tau) in param.tau().iter().enumerate() {
        let part = one_minus_debye(omega, tau);
        e += mapped.strengths[k] * part;
        grad_p.push(part);
    }
    let free = param.free_count();
    let pull = |g: &[f64]| {
        let mut out = vec![0.0; free];
        param.pullback(mapped, g, &mut out);
        DVector::from_vec(out)
    };
    let re: Vec<f64> = grad_p.iter().map(|z| z.re).collect();
    let im: Vec<f64> = grad_p.iter().map(|z| z.im).collect();
    let g_storage = pull(&re);
    let g_loss = pull(&im);
    let tan_delta = e.im / e.re;
    let g_tan = (&g_loss - &g_storage * tan_delta) / e.re;
    let magnitude = e.norm();
    let g_mag = (&g_storage * e.re + &g_loss * e.im) / magnitude;
    let sd = |g: &DVector<f64>| (g.transpose() * covariance * g)[(0, 0)].max(0.0).sqrt();
    debug_assert_eq!(re.len(), n + 1);
    ModulusPoint {
        omega,
        storage: e.re,
        loss: e.im,
        tan_delta,
        magnitude,
        storage_sigma: sd(&g_storage),
        loss_sigma: sd(&g_loss),
        tan_delta_sigma: sd(&g_tan),
        magnitude_sigma: sd(&g_mag),
    }
}
