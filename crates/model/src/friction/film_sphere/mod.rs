//! μ(v) of a sphere rolling on a viscoelastic film of thickness d bonded to
//! a rigid base, and its derivatives with respect to Prony parameters.
//!
//! # Formula
//!
//! The film divides L(ω) by S(qd) in Eq. (17) (S: [`crate::film`]).
//! Substituting ω = q v cos φ and cosh t = 1/cos φ as for the half-space
//! ([`crate::kernel::sphere`]):
//!
//!   μ_film = C/v² ∫₀^∞ dω ω L(ω) G_film(x, z),   C = 18 F_N/π²,
//!   G_film(x, z) = ∫₀^∞ f(x cosh t)/S(z cosh t) dt,
//!
//! with x = ω r(ω)/v and z = ω d/v (dimensionless), r(ω) the Hertz contact
//! radius (dynamic or static rule, m), L the loss compliance (1/Pa) and f
//! the Hertz form factor. Writing G_film = G − D
//! ([`crate::kernel::film_sphere`]):
//!
//!   μ_film = μ_half − Δ,   Δ = C ∫ ds (ω/v)² L(ω) D(x, z),   s = ln ω.
//!
//! # Method
//!
//! μ_half is the half-space μ of the same scene, from the product
//! integration of [`super`]: it owns the part that is hard to integrate, the
//! kernel's oscillation that decays only like x^{−9/2} against the
//! material, which that method retires with its window. Δ is what the film
//! changes: a double integral with a non-negative integrand over a bounded
//! domain — D = 0 for z ≥ Z = 24, so s ≤ ln(Zv/d) — whose low-frequency
//! tail falls like e^{(2+p)s}|s| (L ≤ κω^p). It is computed by nested
//! adaptive Gauss–Kronrod (7, 15) quadrature ([`crate::kernel::gauss_kronrod`]):
//! outer in s, inner in t for D at each outer node, so the modulus is
//! evaluated only at outer nodes. Integrating G_film directly instead would
//! bring the oscillating tail back into a new quadrature.
//!
//! # Error control
//!
//! With θ ≤ μ_film/μ_half, the absolute error E = tol·θ·μ_half ≤ tol·μ_film
//! is shared out ([`SHARES`]):
//! - 0.8 E to μ_half, computed at relative tolerance 0.8·tol·θ;
//! - 0.08 E to the inner integrals: each D to relative accuracy 0.08·tol·θ,
//!   which moves Δ by at most 0.08·tol·θ·Δ ≤ 0.08 E (non-negative
//!   integrand, Δ ≤ μ_half), and 0.03 E to absolute floors of that accuracy
//!   where D is negligible;
//! - 0.08 E to the outer quadrature (summed |K − G| bounds, which overstate
//!   the error of the Kronrod sums);
//! - 0.01 E to the truncated low-frequency tail, bounded rigorously by
//!   ∫_{−∞}^{s_lo} (ω/v)² L D ds ≤ κ/(9v²) e^{(2+p)s_lo}[(A − s_lo)/(2+p) +
//!   1/(2+p)²] with A = ln(2Zv/d), from f ≤ 1/9, w ≤ 1 and acosh(Z/z) ≤
//!   ln(2Z/z); κ = L′(0) and p = 1 for a positive relaxation spectrum,
//!   else sampled as for the half-space tail.
//!
//! θ starts at ½. If the result shows μ_film < θ μ_half, θ is set just below
//! the observed ratio (less the error allowed so far) and μ recomputed. The
//! subtraction amplifies the half-space error by μ_half/μ_film, and the
//! half-space μ is relied on only down to [`HALF_SPACE_ACCURACY`] = 1e-8
//! (its measured floor is ~4e-9 at low speed), so the request must satisfy
//! 0.8·tol·θ ≥ 1e-8: μ_film/μ_half ≥ 1.25·10⁻⁸/tol (1.25 % at the default
//! tol = 10⁻⁶), and tol ≥ 1.25·10⁻⁸ for any film. Otherwise an error is
//! returned, not a number. μ_film/μ_half drops for films thin compared with
//! the contact: measured 2–8 % at d = r0/10 and 0.4–4 % at r0/20 for speeds
//! across the loss peak (3- and 15-term Prony series).
//!
//! Measured (tests/film_sphere.rs): against a brute-force nested
//! integration the results agree to better than 6e-8 at the default
//! tolerance, and against the tightest admissible tolerance the errors stay
//! below 1 % of the requested tolerance (1e-3 … 1e-6).
//!
//! # Supported films and cost
//!
//! D's integrand oscillates over y = x cosh t up to Z r/d, so the inner and
//! outer integrals each need ~2 r/d panels for d ≪ r: the work grows like
//! (r0/d)². Measured per speed (3- and 15-term Prony series, default
//! tolerance, one core): d/r0 ≥ 1: 0.1–1 ms; 0.3: 3 ms; 0.1: 9–12 ms;
//! 0.05: 16–35 ms. Supported at the default tolerance: d/r0 ≳ 0.1 at every
//! speed (oracle-checked from 0.1 to 1000); thinner films wherever
//! μ_film/μ_half ≥ 1.25 %, refused elsewhere. More than [`MAX_EVALUATIONS`]
//! integrand evaluations (d/r0 ≲ 0.02) are refused too.
//!
//! # References
//! - B.N.J. Persson, "Rolling friction for hard cylinder and sphere on
//!   viscoelastic solid", Eur. Phys. J. E 33 (2010) 327–333, Eq. (17).
//! - R. Piessens, E. de Doncker-Kapenga, C.W. Überhuber, D.K. Kahaner,
//!   *QUADPACK*, Springer 1983 (Gauss–Kronrod rules, globally adaptive
//!   bisection).
//! - P.J. Davis, P. Rabinowitz, *Methods of Numerical Integration*, 2nd ed.,
//!   Academic Press 1984 (product rules and nested quadrature).

use std::f64::consts::PI;

use num_complex::Complex64;

mod deficit;

use super::FrictionJacobian;
use super::setup::Setup;
use crate::error::ModelError;
use crate::kernel::film_sphere::deficit_and_slope;
use crate::kernel::gauss_kronrod::for_each_node;
use crate::modulus::{Prony, ViscoelasticModulus};
use crate::scene::{Scene, Substrate};
use deficit::{Deficit, DeficitIntegral};

/// The accuracy the half-space μ is relied on for: no tighter tolerance is
/// requested of it. Measured against a brute-force integration and the
/// reference values (3- and 15-term Prony series, standard linear solid),
/// the half-space sphere μ is systematically 3.7–4.9e-9 low at speeds with
/// vτ/r0 ≲ 0.01 whatever tolerance is asked for (1e-10 included), and
/// within 3e-10 at higher speeds; this is twice the worst of that.
pub const HALF_SPACE_ACCURACY: f64 = 1e-8;

/// Panel budget of one inner integral D: about 2 r/d initial panels are
/// needed, so this is not what limits the film thickness
/// ([`MAX_EVALUATIONS`] is); it guards against a runaway refinement.
pub const MAX_INNER_PANELS: usize = 20_000;

/// Panel budget of the outer integral over s = ln ω.
const MAX_OUTER_PANELS: usize = 4_000;

/// Integrand evaluations (of f·w, ~50 ns each) allowed for one μ: about a
/// quarter of a second. The work grows like (r0/d)²; films thin enough to
/// exhaust this are also refused for their small μ_film/μ_half at most
/// speeds (see the module docs).
pub const MAX_EVALUATIONS: usize = 5_000_000;

/// Largest initial outer panel width in s.
const MAX_OUTER_WIDTH: f64 = 1.0;

/// A borrowed modulus, so that the half-space scene can share the film
/// scene's material without cloning it (M need not be Clone). A trait
/// object, not `&M`: `Scene<Borrowed>` is then one type whatever M is, which
/// keeps the generic friction code from instantiating itself without end.
struct Borrowed<'a>(&'a dyn ViscoelasticModulus);

impl ViscoelasticModulus for Borrowed<'_> {
    // Every method is forwarded, defaulted ones included: a default here
    // would silently replace the material's own answer.
    fn modulus(&self, omega: f64) -> Complex64 {
        self.0.modulus(omega)
    }
    fn modulus_and_log_slope(&self, omega: f64) -> (Complex64, Complex64) {
        self.0.modulus_and_log_slope(omega)
    }
    fn static_modulus(&self) -> f64 {
        self.0.static_modulus()
    }
    fn loss_slope_at_zero(&self) -> f64 {
        self.0.loss_slope_at_zero()
    }
    fn loss_exponent_at_zero(&self) -> f64 {
        self.0.loss_exponent_at_zero()
    }
    fn low_frequency_loss_coefficient(&self) -> f64 {
        self.0.low_frequency_loss_coefficient()
    }
    fn structure_range(&self) -> (f64, f64) {
        self.0.structure_range()
    }
    fn relaxation_bound(&self) -> Option<f64> {
        self.0.relaxation_bound()
    }
}

/// The half-space scene of `scene` (same geometry, contact rule, material
/// and Poisson ratio, no film) at relative tolerance `tolerance`.
fn half_space_scene<M: ViscoelasticModulus>(
    scene: &Scene<M>,
    tolerance: f64,
) -> Result<Scene<Borrowed<'_>>, ModelError> {
    Scene::new(
        *scene.geometry(),
        Substrate {
            film_thickness: None,
            ..*scene.substrate()
        },
        scene.contact(),
        Borrowed(scene.material()),
    )?
    .with_tolerance(tolerance)
}

/// κ and p with L(ω) ≤ κ ω^p for all ω.
fn loss_bound<M: ViscoelasticModulus>(scene: &Scene<M>) -> Result<(f64, f64), ModelError> {
    let material = scene.material();
    let plane_strain = scene.plane_strain_factor();
    let e0 = material.static_modulus();
    let p = material.loss_exponent_at_zero();
    if !(p > 0.0 && p <= 1.0) {
        return Err(ModelError::LossExponentOutOfRange { exponent: p });
    }
    let kappa = match material.relaxation_bound() {
        // A positive relaxation spectrum makes L(ω)/ω non-increasing, so
        // L ≤ L′(0) ω exactly.
        Some(_) if p == 1.0 => plane_strain * material.loss_slope_at_zero() / (e0 * e0),
        // Otherwise sample L/ω^p across the structure and six decades
        // beyond, with the same 1.5 margin as the half-space tail bound.
        _ => {
            let (w_lo, w_hi) = material.structure_range();
            if !(w_lo > 0.0 && w_hi >= w_lo && w_hi.is_finite()) {
                return Err(ModelError::UnusableFrequencyRange {
                    low: w_lo,
                    high: w_hi,
                });
            }
            let decades = (w_hi / w_lo).log10() + 6.0;
            let count = (decades * 20.0).ceil() as usize + 1;
            let mut sup = 0.0f64;
            for i in 0..count {
                let omega = w_lo * 1e-3 * 10f64.powf(i as f64 / 20.0);
                let l = -plane_strain * (1.0 / material.modulus(omega)).im;
                sup = sup.max(l / omega.powf(p));
            }
            1.5 * sup
        }
    };
    if !(kappa.is_finite() && kappa >= 0.0) {
        return Err(ModelError::LossComplianceUnbounded);
    }
    Ok((kappa, p))
}

/// Shares of the absolute error allowed in μ_film, see the module docs.
/// Δ's shares are in the units of [`Deficit::integral`] (Δ/C).
#[derive(Debug, Clone, Copy)]
struct Budget {
    /// Truncated low-frequency tail of Δ.
    tail: f64,
    /// Summed |K − G| bounds of the outer quadrature.
    outer: f64,
    /// Relative accuracy of each D.
    inner_relative: f64,
    /// Effect on Δ of the absolute floors of the D accuracy.
    inner_floor: f64,
}

/// Fractions of the absolute error E = tol·θ·μ_half: half-space, outer
/// quadrature, low-frequency tail, inner relative, inner floors. The
/// half-space gets the largest share because its accuracy has a floor
/// ([`HALF_SPACE_ACCURACY`]); Δ converges spectrally and tightening it is
/// cheap.
const SHARES: [f64; 5] = [0.8, 0.08, 0.01, 0.08, 0.03];

/// The result for one speed.
struct Solution {
    mu: f64,
    /// Relative tolerance the half-space μ was computed with.
    half_tolerance: f64,
    budget: Budget,
    deficit: DeficitIntegral,
}

/// μ_film = μ_half − Δ at speed `v` with the θ iteration of the module docs.
fn solve<M: ViscoelasticModulus>(
    scene: &Scene<M>,
    deficit: &Deficit<'_, M>,
) -> Result<Solution, ModelError> {
    let v = deficit.v;
    let tolerance = scene.tolerance();
    let prefactor = 18.0 * scene.geometry().load / (PI * PI);
    let (kappa, p) = loss_bound(scene)?;
    let [
        half_share,
        outer_share,
        tail_share,
        inner_share,
        floor_share,
    ] = SHARES;
    // θ: assumed lower bound of μ_film/μ_half (see the module docs); the
    // half-space share of the error, half_share·tol·θ·μ_half, must not be
    // below what the half-space delivers.
    let theta_min = HALF_SPACE_ACCURACY / (half_share * tolerance);
    let refuse = |ratio: f64| ModelError::FilmToleranceUnreachable {
        tolerance,
        speed: v,
        ratio,
        thickness_in_radii: deficit.d / deficit.r0,
        half_space_accuracy: HALF_SPACE_ACCURACY,
        ratio_needed: theta_min,
    };
    if theta_min > 1.0 {
        return Err(ModelError::FilmToleranceTooTight {
            tolerance,
            half_space_accuracy: HALF_SPACE_ACCURACY,
            loosest: HALF_SPACE_ACCURACY / half_share,
        });
    }
    let mut theta = theta_min.max(0.5);
    for _ in 0..8 {
        let half_tolerance = half_share * tolerance * theta;
        let half_tolerance = half_tolerance.min(1e-2);
        let mu_half = half_space_scene(scene, half_tolerance)?.friction(v)?;
        if mu_half.is_nan() || mu_half <= 0.0 {
            // 0 ≤ μ_film ≤ μ_half: nothing to subtract from (e.g. a purely
            // elastic solid). A negative or NaN μ_half is not a friction
            // coefficient.
            return if mu_half == 0.0 {
                Ok(Solution {
                    mu: 0.0,
                    half_tolerance,
                    budget: Budget {
                        tail: 0.0,
                        outer: 0.0,
                        inner_relative: 0.0,
                        inner_floor: 0.0,
                    },
                    deficit: DeficitIntegral {
                        value: 0.0,
                        panels: Vec::new(),
                        span: 0.0,
                    },
                })
            } else {
                Err(ModelError::FilmHalfSpaceInvalid { mu_half, speed: v })
            };
        }
        // E/C in the units of the Δ integral.
        let allowed = tolerance * theta * mu_half / prefactor;
        let budget = Budget {
            tail: tail_share * allowed,
            outer: outer_share * allowed,
            // Δ ≤ μ_half, so a relative error ρ of every D moves Δ by ≤ ρ μ_half.
            inner_relative: inner_share * tolerance * theta,
            inner_floor: floor_share * allowed,
        };
        let integral = deficit.integral(kappa, p, &budget)?;
        let mu = mu_half - prefactor * integral.value;
        if !mu.is_finite() {
            return Err(ModelError::FilmNotFinite {
                what: "μ is",
                speed: v,
            });
        }
        if mu >= theta * mu_half {
            return Ok(Solution {
                mu,
                half_tolerance,
                budget,
                deficit: integral,
            });
        }
        // The film removes more than assumed: the true ratio is at least
        // the estimate less the error just allowed (tol·θ); aim 10 % lower
        // and repeat, unless that is below what the half-space supports. A
        // non-positive μ can only come from the error allowed.
        let ratio = mu / mu_half;
        theta = 0.9 * (ratio - tolerance * theta);
        if theta < theta_min {
            return Err(refuse(ratio));
        }
    }
    Err(ModelError::FilmNotSettled { speed: v })
}

/// μ of a sphere rolling at speed `v` (m/s) on a film of thickness
/// `thickness` (m), to the scene's relative tolerance.
pub(super) fn friction<M: ViscoelasticModulus>(
    scene: &Scene<M>,
    _setup: &Setup,
    v: f64,
    thickness: f64,
) -> Result<f64, ModelError> {
    Ok(solve(scene, &Deficit::new(scene, v, thickness))?.mu)
}

/// μ at each of `speeds` (m/s) on a film of thickness `thickness` (m), and
/// ∂μ/∂(E1, H_1..H_n) (1/Pa).
///
/// ∂μ_film/∂p = ∂μ_half/∂p − ∂Δ/∂p. The first comes from the half-space
/// product integration at the tolerance μ_half was computed with; the
/// second differentiates Δ under the integral sign — only L and, through x,
/// the contact radius depend on p (z = ωd/v does not):
///
///   ∂Δ/∂p = C ∫ ds (ω/v)² [∂L/∂p · D + L · x∂D/∂x · ∂ln r/∂p],
///
/// with ∂L/∂p = (1 − ν²) Im(g_p/E²), ∂ln r/∂p = −(1/3) Re(g_p/E) (dynamic)
/// or −(1/3) ∂E0/∂p / E0 (static), g_p = ∂E*/∂p, and x∂D/∂x = ∫ y f′(y) w dt
/// ([`crate::kernel::film_sphere`]). It is summed with the Kronrod nodes of
/// the final outer panels of μ's own quadrature, with D and x∂D/∂x to the
/// same relative accuracy as D was for μ.
pub(super) fn friction_with_gradient(
    scene: &Scene<Prony>,
    speeds: &[f64],
    thickness: f64,
) -> Result<FrictionJacobian, ModelError> {
    let prony = scene.material();
    let np = prony.parameter_count();
    let prefactor = 18.0 * scene.geometry().load / (PI * PI);
    let e0 = prony.static_modulus();
    let mut mu = Vec::with_capacity(speeds.len());
    let mut jacobian = Vec::with_capacity(speeds.len() * np);
    let mut d_ln_speed = Vec::with_capacity(speeds.len());
    let mut factors = vec![Complex64::new(0.0, 0.0); prony.len()];
    let mut scratch = Vec::new();
    for &v in speeds {
        let deficit = Deficit::new(scene, v, thickness);
        let solution = solve(scene, &deficit)?;
        let half = Scene::new(
            *scene.geometry(),
            Substrate {
                film_thickness: None,
                ..*scene.substrate()
            },
            scene.contact(),
            prony.clone(),
        )?
        .with_tolerance(solution.half_tolerance)?
        .friction_with_gradient(&[v])?;
        let mut row = half.jacobian;
        // The parameters, then the time scale (see FrictionJacobian).
        row.push(half.d_ln_speed[0]);
        let mut d_delta = vec![0.0; np + 1];
        let mut failure = None;
        let budget = solution.budget;
        let span = solution.deficit.span;
        for_each_node(&solution.deficit.panels, |s, weight| {
            if failure.is_some() {
                return;
            }
            let (e, _) = prony.evaluate_with_factors(s.exp(), &mut factors);
            let (_, log_slope) = prony.modulus_and_log_slope(s.exp());
            let (x, z, omega_over_v_sq, loss) = deficit.point(s, e);
            let floor = budget.inner_floor / (span * omega_over_v_sq * loss);
            let dd = match deficit_and_slope(
                x,
                z,
                deficit.poisson,
                budget.inner_relative,
                floor,
                MAX_INNER_PANELS,
                &mut scratch,
            ) {
                Ok(dd) => dd.value,
                Err(e) => {
                    failure = Some(e);
                    return;
                }
            };
            let inv_e = 1.0 / e;
            let inv_e2 = inv_e * inv_e;
            for (q, out) in d_delta.iter_mut().enumerate() {
                let (g, de0) = super::column_derivative(q, &factors, log_slope);
                let d_loss = deficit.plane_strain * (g * inv_e2).im;
                let d_ln_r = match deficit.static_size {
                    Some(_) => -de0 / (3.0 * e0),
                    None => -(g * inv_e).re / 3.0,
                };
                *out += weight * omega_over_v_sq * (d_loss * dd[0] + loss * dd[1] * d_ln_r);
            }
        });
        if failure.is_some() {
            return Err(deficit.too_thin());
        }
        for (r, dd) in row.iter_mut().zip(&d_delta) {
            *r -= prefactor * dd;
        }
        if row.iter().any(|r| !r.is_finite()) {
            return Err(ModelError::FilmNotFinite {
                what: "the derivatives of μ are",
                speed: v,
            });
        }
        mu.push(solution.mu);
        jacobian.extend_from_slice(&row[..np]);
        d_ln_speed.push(row[np]);
    }
    Ok(FrictionJacobian {
        mu,
        jacobian,
        parameter_count: np,
        d_ln_speed,
    })
}
