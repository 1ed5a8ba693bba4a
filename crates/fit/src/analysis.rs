//! What the data determine: the probed window, which relaxation times the
//! data constrain, the noise level, and 1σ bands on E′, E″ and tan δ.
//!
//! At the optimum θ̂ with residual Jacobian J (data rows J_d, penalty rows
//! √λ L), the Gauss–Newton curvature of V/2 is H = JᵀJ = J_dᵀJ_d + λLᵀL.
//!
//! - Influence trace: t = tr(H⁻¹ J_dᵀJ_d), the effective number of
//!   parameters the data fix (≤ free parameters; smaller with smoothing).
//! - Noise: s² = 1 when σ is measured (residuals are in units of σ). Else
//!   s² = RSS/ν from the data residuals at the optimum, with the residual
//!   degrees of freedom of a linear smoother ν = N − 2 tr A + tr AᵀA,
//!   A = J_d H⁺ J_dᵀ the influence matrix of the linearisation
//!   ([`residual_dof`]). For y = f + ε, E‖(I − A)ε‖² = σ² tr((I − A)ᵀ(I − A))
//!   = σ² ν, so RSS/ν is unbiased for the noise and errs on the wide side by
//!   the smoothing bias ‖(I − A)f‖²/ν. Every free parameter is counted
//!   where the data move it: each shift of a temperature set adds about one
//!   to tr A and tr AᵀA (the data alone fix it), a penalised strength less
//!   than one. The plain N − t (t = tr A) counts a penalised direction once
//!   where it takes 2a − a² ≥ a degrees of freedom from the residuals; on
//!   15 speeds it put the estimate's median 6–10 % under the noise. The
//!   marginal likelihood's own restricted estimate V̂/(N − m₀)
//!   ([`crate::regularization`]) chooses λ; it assumes the spectrum drawn
//!   from the smoothness prior, which a real material is not, and on those
//!   15 speeds it lay 8–10 % low as well.
//! - Covariance: C = s² H⁻¹ (the curvature of V at the optimum), via a
//!   pseudo-inverse so that directions the data and penalty leave flat show
//!   up as large, honest uncertainties instead of a failure.
//! - Determined terms: τ_k is determined when the data alone resolve its
//!   ln H_k: changing ln H_k by one (a factor e) moves the misfit by at least
//!   one noise unit, ‖J_d e_k‖² ≥ s², and 1/τ_k lies within a decade of the
//!   probed window.
//! - Window: the band v/r … 20 v/r (r the fitted dynamic contact size) over
//!   the data's speeds.
//! - Bands: σ_f(ω)² = ∇f C ∇fᵀ + b_f(ω)² for f = E′, E″, tan δ, |E|: the
//!   linearised variance plus the smoothing bias b_f. The curvature alone
//!   leaves out that the penalty pulls the curve toward a power law; the
//!   bias is estimated as the change of f when the smoothing is relaxed
//!   tenfold, b_f = |f(θ̂_{λ/10}) − f(θ̂_λ)|. For a penalty whose bias grows
//!   linearly in λ that is 0.9 times the bias at λ, plus the extra noise the
//!   weaker smoothing lets in (so it errs on the wide side). The
//!   alternative, f(10λ) − f(λ), measures nine times the bias.
//! - Determined window: the probed window is where the kernels of Eqs. (11)
//!   and (17) put weight; at its ends, μ(v) fixes E* only through a tail of
//!   that kernel and the deconvolution is poorly conditioned (on 15 speeds
//!   over 5 decades, tan δ at the top of the probed window is off by a
//!   factor of two, inside an honest band). The window reported is the
//!   stretch around the best-determined frequency where the 1σ band of
//!   tan δ stays within [`DETERMINED_RELATIVE_SIGMA`] of tan δ.
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

/// The relative 1σ of tan δ (bias included) up to which a frequency counts
/// as determined by the data: tan δ to ±10 %, so that the 2σ band is at
/// most ±20 %.
pub const DETERMINED_RELATIVE_SIGMA: f64 = 0.1;

/// The determined stretch of `curve` (indices `first..=last`): the
/// contiguous run around the point of smallest relative tan δ band where
/// that band is at most [`DETERMINED_RELATIVE_SIGMA`]; None when no point
/// qualifies.
pub(crate) fn determined_stretch(curve: &[ModulusPoint]) -> Option<(usize, usize)> {
    let relative = |p: &ModulusPoint| p.tan_delta_sigma / p.tan_delta.abs();
    let (best, _) = curve
        .iter()
        .enumerate()
        .filter(|(_, p)| relative(p).is_finite())
        .min_by(|a, b| relative(a.1).total_cmp(&relative(b.1)))?;
    if relative(&curve[best]) > DETERMINED_RELATIVE_SIGMA {
        return None;
    }
    let ok = |i: usize| relative(&curve[i]) <= DETERMINED_RELATIVE_SIGMA;
    let mut first = best;
    while first > 0 && ok(first - 1) {
        first -= 1;
    }
    let mut last = best;
    while last + 1 < curve.len() && ok(last + 1) {
        last += 1;
    }
    Some((first, last))
}

/// Widens the bands of `point` by the smoothing bias: the difference to the
/// less smoothed material `other` at the same ω, added in quadrature.
pub(crate) fn add_bias(point: &mut ModulusPoint, other: Complex64) {
    let add = |sigma: &mut f64, bias: f64| *sigma = sigma.hypot(bias);
    add(&mut point.storage_sigma, other.re - point.storage);
    add(&mut point.loss_sigma, other.im - point.loss);
    add(
        &mut point.tan_delta_sigma,
        other.im / other.re - point.tan_delta,
    );
    add(&mut point.magnitude_sigma, other.norm() - point.magnitude);
}

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
    /// ln det H over the eigenvalues the pseudo-inverse keeps (for the
    /// marginal likelihood of [`crate::regularization`]).
    pub log_det: f64,
}

/// Pseudo-inverse of a symmetric positive semi-definite matrix, dropping
/// eigenvalues below 1e-12 of the largest, and the log-determinant over the
/// eigenvalues kept.
pub(crate) fn pseudo_inverse(h: &DMatrix<f64>) -> (DMatrix<f64>, f64) {
    let eig = h.clone().symmetric_eigen();
    let largest = eig.eigenvalues.iter().fold(0.0f64, |m, &v| m.max(v.abs()));
    let cutoff = 1e-12 * largest;
    let log_det = eig
        .eigenvalues
        .iter()
        .filter(|&&v| v > cutoff)
        .map(|v| v.ln())
        .sum();
    let inv: DVector<f64> = eig
        .eigenvalues
        .map(|v| if v > cutoff { 1.0 / v } else { 0.0 });
    (
        &eig.eigenvectors * DMatrix::from_diagonal(&inv) * eig.eigenvectors.transpose(),
        log_det,
    )
}

/// Statistics from the full residual Jacobian `jacobian` whose first
/// `data_count` rows are data residuals and whose last row is the E1_max
/// bound; the noise variance s² is `noise_variance` when known (1 for a
/// measured σ, or an estimate made elsewhere), else misfit/(N − t) from
/// the data residuals' `misfit`.
pub(crate) fn curvature(
    jacobian: &DMatrix<f64>,
    data_count: usize,
    misfit: f64,
    noise_variance: Option<f64>,
) -> Curvature {
    // The last row is the E1_max bound: a guard against runaway steps, not
    // information about the material, so it does not narrow the band.
    let informative = jacobian.rows(0, jacobian.nrows() - 1);
    let h = informative.transpose() * informative;
    let jd = jacobian.rows(0, data_count);
    let hd = jd.transpose() * jd;
    let (h_inv, log_det) = pseudo_inverse(&h);
    let effective_parameters = (&h_inv * &hd).trace();
    let dof = (data_count as f64 - effective_parameters).max(1.0);
    let noise_variance = noise_variance.unwrap_or(misfit / dof);
    let sensitivity = (0..jacobian.ncols()).map(|k| hd[(k, k)]).collect();
    Curvature {
        covariance: h_inv * noise_variance,
        effective_parameters,
        noise_variance,
        sensitivity,
        log_det,
    }
}

/// The residual degrees of freedom ν = N − 2 tr A + tr AᵀA (module doc) of
/// the full residual Jacobian `jacobian` whose first `data_count` rows are
/// data residuals and whose last row is the E1_max bound (left out, as in
/// [`curvature`]); at least 1.
pub(crate) fn residual_dof(jacobian: &DMatrix<f64>, data_count: usize) -> f64 {
    let informative = jacobian.rows(0, jacobian.nrows() - 1);
    let h = informative.transpose() * informative;
    let jd = jacobian.rows(0, data_count);
    let (h_inv, _) = pseudo_inverse(&h);
    let influence = jd * h_inv * jd.transpose();
    let trace = influence.trace();
    let squares = influence.norm_squared();
    (data_count as f64 - 2.0 * trace + squares).max(1.0)
}

/// E*(ω) (Pa) of the material `mapped` on relaxation times `tau`,
/// E0 + Σ H_k (1 − D_k(ω)), summed from E0 up: a material whose E1/E0 is
/// beyond what E0 = E1 − ΣH holds in double precision has its E* all the
/// same.
pub(crate) fn modulus_of(mapped: &Mapped, tau: &[f64], omega: f64) -> Complex64 {
    mapped
        .strengths
        .iter()
        .zip(tau)
        .fold(Complex64::new(mapped.static_modulus, 0.0), |e, (h, &t)| {
            e + h * one_minus_debye(omega, t)
        })
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

impl ModulusPoint {
    /// The numbers in modulus.csv's column order: ω, E′, E″, tan δ, |E*|
    /// and their 1σ in the same order.
    pub fn values(&self) -> [f64; 9] {
        [
            self.omega,
            self.storage,
            self.loss,
            self.tan_delta,
            self.magnitude,
            self.storage_sigma,
            self.loss_sigma,
            self.tan_delta_sigma,
            self.magnitude_sigma,
        ]
    }
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
