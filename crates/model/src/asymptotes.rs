//! Quantities derived from μ(v): the low-speed asymptote, Greenwood–Tabor's
//! hysteresis-loss fraction α, the pressure-centroid shift and the friction
//! maximum.
//!
//! Low speed, Persson (2010) Eqs. (18)/(19) and the cylinder analogue: as
//! v → 0 only frequencies ω ≲ v/a0 → 0 matter, where the contact has its
//! static size and the loss compliance follows its low-frequency power law
//! L(ω) ≈ λ ω^p, λ = (1 − ν²) ℓ/E0², with E″ ≈ ℓ ω^p (p = 1, ℓ = lim E″/ω
//! for a solid with a longest relaxation time; p = α < 1 for a
//! Havriliak–Negami solid). Substituting x = ω r0/v in the sphere's
//! frequency integral (see [`crate::kernel::sphere`]) and y = q a0 in Eq. (11):
//!
//!   sphere:   μ → (18/π) M_s(p) p_a λ (v/r0)^p,  M_s(p) = ∫₀^∞ x^{1+p} G(x) dx,
//!   cylinder: μ → (16/π) M_c(p) p_a λ (v/a0)^p,  M_c(p) = ∫₀^∞ y^{p−2} J1²(y) dy,
//!
//! with p_a the static mean pressure (F_N/(πr0²), f_N/(2a0)). Both Mellin
//! transforms have closed forms. For the sphere, G(x) = ∫₁^∞ f(xu) du/√(u²−1)
//! and y = xu separate the integral into
//!
//!   M_s(p) = ∫₁^∞ u^{−p−2} du/√(u² − 1) × ∫₀^∞ y^{1+p} f(y) dy
//!          = (√π/2) Γ(1 + p/2)/Γ(3/2 + p/2) × ∫₀^∞ y^{p−1} j1(y)² dy,
//!
//! (u = 1/t turns the first factor into a Beta integral; y² f(y) = j1(y)², the
//! spherical Bessel function) and, with j1(y)² = (π/(2y)) J_{3/2}(y)², both
//! Bessel integrals are the Weber–Schafheitlin case
//!
//!   ∫₀^∞ t^{−λ} J_ν(t)² dt = Γ(λ) Γ(ν + (1 − λ)/2) / (2^λ Γ((1 + λ)/2)² Γ(ν + (1 + λ)/2)),
//!
//! valid for 0 < λ < 2ν + 1: λ = 2 − p with ν = 3/2 (sphere) or ν = 1
//! (cylinder). At p = 1 this is Eq. (18): M_s(1) = (π/4)(π/6) = π²/24, so
//! (18/π) M_s = 9I/2 = 3π/4 with the paper's I = π/6, and M_c(1) = 1/2 gives
//! the cylinder's 8/π; λ then equals L′(0) and μ ∝ v. For p < 1, μ ∝ v^p.
//!
//! The next-order terms are smaller by a factor of order (v τ/r0)^p for a
//! material whose structure starts near 1/τ: with p = ½ the asymptote is
//! approached only slowly.
//!
//! Greenwood–Tabor, Eqs. (20)–(21): rolling resistance is a fraction α of the
//! elastic work done ahead of the contact centre, μ = (3/16) α r0/R for a
//! sphere and μ = (2/(3π)) α a0/R for a cylinder; the α that reproduces μ is
//! reported. For a standard linear solid at low speed α → (16/3) tan δ(v/r0)
//! (sphere).
//!
//! Pressure centroid, Section 4: the moment of the asymmetric pressure
//! equals the friction moment, x̄ = μR.
//!
//! # References
//! - J.A. Greenwood, D. Tabor, "The friction of hard sliders on lubricated
//!   rubber: the importance of deformation losses", Proc. Phys. Soc. 71 (1958).
//! - B.N.J. Persson, Eur. Phys. J. E 33 (2010), Sections 3–4.
//! - G.N. Watson, *A Treatise on the Theory of Bessel Functions*, 2nd ed.,
//!   Cambridge 1944, §13.41 (the Weber–Schafheitlin integral).

use std::f64::consts::PI;

use crate::contact::Shape;
use crate::error::ModelError;
use crate::modulus::ViscoelasticModulus;
use crate::scene::Scene;

/// The friction maximum of μ(v).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionPeak {
    /// Speed of the maximum, m/s.
    pub speed: f64,
    /// μ at the maximum.
    pub mu: f64,
}

/// Γ(x) for the positive arguments of the Mellin constants.
fn gamma(x: f64) -> f64 {
    libm::tgamma(x)
}

/// ∫₀^∞ t^{−λ} J_ν(t)² dt for 0 < λ < 2ν + 1 (Weber–Schafheitlin).
fn bessel_square_mellin(lambda: f64, nu: f64) -> f64 {
    let half = 0.5 * (1.0 + lambda);
    gamma(lambda) * gamma(nu + 0.5 * (1.0 - lambda))
        / (2f64.powf(lambda) * gamma(half) * gamma(half) * gamma(nu + half))
}

/// M_s(p) = ∫₀^∞ x^{1+p} G(x) dx of the sphere kernel, 0 < p < 2.
fn sphere_mellin(p: f64) -> f64 {
    let angular = 0.5 * PI.sqrt() * gamma(1.0 + 0.5 * p) / gamma(1.5 + 0.5 * p);
    let radial = 0.5 * PI * bessel_square_mellin(2.0 - p, 1.5);
    angular * radial
}

/// M_c(p) = ∫₀^∞ y^{p−2} J1(y)² dy of the cylinder kernel, 0 < p < 2.
fn cylinder_mellin(p: f64) -> f64 {
    bessel_square_mellin(2.0 - p, 1.0)
}

/// The dimensionless factor c(p) of the low-speed asymptote
/// μ → c(p) p_a λ (v/d0)^p (d0 = r0 or a0, see the module documentation):
/// (18/π) M_s(p) for a sphere, (16/π) M_c(p) for a cylinder; 3π/4 and 8/π
/// at p = 1 (Eqs. 18/19), returned exactly there.
pub fn low_speed_factor(shape: Shape, p: f64) -> f64 {
    match (shape, p == 1.0) {
        (Shape::Sphere, true) => 0.75 * PI,
        (Shape::Cylinder, true) => 8.0 / PI,
        (Shape::Sphere, false) => 18.0 / PI * sphere_mellin(p),
        (Shape::Cylinder, false) => 16.0 / PI * cylinder_mellin(p),
    }
}

impl<M: ViscoelasticModulus> Scene<M> {
    /// L′(0) = dL/dω at ω = 0 (1/(Pa·rad/s)), L = −Im 1/E_eff; infinite
    /// when the loss vanishes more slowly than ω (see
    /// [`Self::low_frequency_loss_compliance`]).
    pub fn loss_compliance_slope_at_zero(&self) -> f64 {
        let e0 = self.material().static_modulus();
        self.plane_strain_factor() * self.material().loss_slope_at_zero() / (e0 * e0)
    }

    /// The low-frequency power law of the loss compliance, L(ω) ≈ λ ω^p:
    /// returns (λ in 1/(Pa·s^p), p), λ = (1 − ν²) ℓ/E0² with E″ ≈ ℓ ω^p.
    /// For p = 1, λ = L′(0).
    pub fn low_frequency_loss_compliance(&self) -> (f64, f64) {
        let material = self.material();
        let e0 = material.static_modulus();
        let lambda =
            self.plane_strain_factor() * material.low_frequency_loss_coefficient() / (e0 * e0);
        (lambda, material.loss_exponent_at_zero())
    }

    /// Low-speed asymptote of μ at speed `v` (m/s): Eqs. (18)/(19) for a
    /// loss linear in ω, μ → c(p) p_a λ (v/d0)^p in general (module
    /// documentation; d0 the static contact size r0 or a0, m).
    pub fn low_speed_asymptote(&self, v: f64) -> f64 {
        let size = self.static_contact_size();
        let (lambda, p) = self.low_frequency_loss_compliance();
        let factor = low_speed_factor(self.geometry().shape, p);
        factor * self.static_mean_pressure() * lambda * (v / size).powf(p)
    }

    /// The Greenwood–Tabor hysteresis-loss fraction α that reproduces `mu`
    /// with the static contact size.
    pub fn greenwood_tabor_alpha(&self, mu: f64) -> f64 {
        let ratio = self.static_contact_size() / self.geometry().radius;
        match self.geometry().shape {
            Shape::Sphere => mu / (3.0 / 16.0 * ratio),
            Shape::Cylinder => mu / (2.0 / (3.0 * PI) * ratio),
        }
    }

    /// Pressure-centroid shift x̄ = μR (m).
    pub fn centroid_shift(&self, mu: f64) -> f64 {
        mu * self.geometry().radius
    }

    /// The global maximum of μ(v) for v in [v_min, v_max] (m/s): a sweep of
    /// 20 points per decade, then golden-section refinement in ln v around
    /// the largest sample (to 1e-6 in ln v). A maximum at an end of the
    /// interval is reported as such (the peak may lie outside).
    pub fn friction_maximum(&self, v_min: f64, v_max: f64) -> Result<FrictionPeak, ModelError> {
        if !(v_min > 0.0 && v_max > v_min && v_max.is_finite()) {
            return Err(ModelError::InvalidSpeedRange { v_min, v_max });
        }
        let (lo, hi) = (v_min.ln(), v_max.ln());
        let count = (((hi - lo) / 10f64.ln() * 20.0).ceil() as usize).max(2) + 1;
        let grid: Vec<f64> = (0..count)
            .map(|i| (lo + (hi - lo) * i as f64 / (count - 1) as f64).exp())
            .collect();
        let mu = self.friction_sweep(&grid)?;
        let best = mu
            .iter()
            .enumerate()
            .fold(0, |b, (i, &m)| if m > mu[b] { i } else { b });
        if best == 0 || best == count - 1 {
            return Ok(FrictionPeak {
                speed: grid[best],
                mu: mu[best],
            });
        }
        let (mut a, mut b) = (grid[best - 1].ln(), grid[best + 1].ln());
        let ratio = 0.5 * (5f64.sqrt() - 1.0);
        let mut c = b - ratio * (b - a);
        let mut d = a + ratio * (b - a);
        let mut fc = self.friction(c.exp())?;
        let mut fd = self.friction(d.exp())?;
        while b - a > 1e-6 {
            if fc > fd {
                b = d;
                d = c;
                fd = fc;
                c = b - ratio * (b - a);
                fc = self.friction(c.exp())?;
            } else {
                a = c;
                c = d;
                fc = fd;
                d = a + ratio * (b - a);
                fd = self.friction(d.exp())?;
            }
        }
        let speed = (0.5 * (a + b)).exp();
        Ok(FrictionPeak {
            speed,
            mu: self.friction(speed)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::ContactSize;
    use crate::kernel::quadrature::{gauss_legendre_unit, integrate};
    use crate::kernel::sphere;
    use crate::modulus::HavriliakNegami;
    use crate::scene::{Geometry, Substrate};

    #[test]
    fn mellin_constants_reproduce_equations_18_and_19_at_p_one() {
        assert!((sphere_mellin(1.0) - PI * PI / 24.0).abs() < 1e-15);
        assert!((cylinder_mellin(1.0) - 0.5).abs() < 1e-15);
        assert!((18.0 / PI * sphere_mellin(1.0) / (0.75 * PI) - 1.0).abs() < 1e-14);
        assert!((16.0 / PI * cylinder_mellin(1.0) / (8.0 / PI) - 1.0).abs() < 1e-14);
        // The p = 1 shortcut joins the general formula continuously.
        for shape in [Shape::Sphere, Shape::Cylinder] {
            let near = low_speed_factor(shape, 1.0 - 1e-9);
            assert!((near / low_speed_factor(shape, 1.0) - 1.0).abs() < 1e-8);
        }
    }

    /// M_s(p) = ∫₀^∞ x^{1+p} G(x) dx by brute force: Gauss–Legendre in ln x
    /// below x = 1, in x (panels of width ½, resolving the oscillation)
    /// up to X, and the smooth asymptote G ≈ 1/(3x⁴) + 4/(15x⁶) beyond.
    fn sphere_mellin_by_quadrature(p: f64) -> f64 {
        let rule = gauss_legendre_unit(16);
        let low = integrate(&rule, -40.0, 0.0, 200, |t| {
            let x = t.exp();
            x.powf(2.0 + p) * sphere::g(x)
        });
        let x_max = 400.0;
        let mid = integrate(&rule, 1.0, x_max, 800, |x| x.powf(1.0 + p) * sphere::g(x));
        let tail = x_max.powf(p - 2.0) / (3.0 * (2.0 - p))
            + 4.0 * x_max.powf(p - 4.0) / (15.0 * (4.0 - p));
        low + mid + tail
    }

    /// M_c(p) = ∫₀^∞ y^{p−2} J1(y)² dy by brute force, with the averaged
    /// tail J1² ≈ 1/(πy) beyond Y.
    fn cylinder_mellin_by_quadrature(p: f64) -> f64 {
        let rule = gauss_legendre_unit(16);
        let f = |y: f64| y.powf(p - 2.0) * libm::j1(y).powi(2);
        let low = integrate(&rule, -40.0, 0.0, 200, |t| t.exp() * f(t.exp()));
        let y_max = 4000.0;
        let mid = integrate(&rule, 1.0, y_max, 8000, f);
        low + mid + y_max.powf(p - 2.0) / (PI * (2.0 - p))
    }

    #[test]
    fn mellin_constants_match_brute_force_quadrature() {
        for p in [0.2, 0.5, 0.75, 1.0] {
            let s = sphere_mellin_by_quadrature(p);
            assert!(
                (sphere_mellin(p) / s - 1.0).abs() < 1e-6,
                "sphere p = {p}: {} vs {s}",
                sphere_mellin(p)
            );
            let c = cylinder_mellin_by_quadrature(p);
            assert!(
                (cylinder_mellin(p) / c - 1.0).abs() < 1e-6,
                "cylinder p = {p}: {} vs {c}",
                cylinder_mellin(p)
            );
        }
    }

    fn hn_scene(shape: Shape) -> Scene<HavriliakNegami> {
        let load = match shape {
            Shape::Sphere => 0.15,
            Shape::Cylinder => 100.0,
        };
        Scene::new(
            Geometry {
                shape,
                radius: 0.01,
                load,
            },
            Substrate {
                poisson: 0.5,
                film_thickness: None,
            },
            ContactSize::Dynamic,
            HavriliakNegami::new(1e6, 1e7, 1.0, 0.5, 0.5).unwrap(),
        )
        .unwrap()
        .with_tolerance(1e-9)
        .unwrap()
    }

    /// For E″ ∝ ω^½ (Havriliak–Negami, α = ½), μ(v) approaches the
    /// generalised asymptote with a relative deviation that itself falls
    /// like (vτ/d0)^½: a factor 10 per 100 in speed.
    #[test]
    fn havriliak_negami_friction_approaches_its_power_law_asymptote() {
        for shape in [Shape::Sphere, Shape::Cylinder] {
            let s = hn_scene(shape);
            let d0 = s.static_contact_size();
            let deviation = |scaled: f64| {
                let v = scaled * d0;
                s.friction(v).unwrap() / s.low_speed_asymptote(v) - 1.0
            };
            let (a, b, c) = (deviation(1e-6), deviation(1e-8), deviation(1e-10));
            assert!(c.abs() < 1e-4, "{shape:?}: deviation {c} at vτ/d0 = 1e-10");
            for (hi, lo) in [(a, b), (b, c)] {
                let ratio = hi / lo;
                assert!(
                    (ratio - 10.0).abs() < 0.5,
                    "{shape:?}: {hi} / {lo} = {ratio}"
                );
            }
        }
    }

    #[test]
    fn power_law_loss_compliance_sets_the_asymptote() {
        let hn = hn_scene(Shape::Sphere);
        let (lambda, p) = hn.low_frequency_loss_compliance();
        assert_eq!(p, 0.5);
        // ℓ = (E1 − E0) β sin(π/4) τ^½, λ = (1 − ν²) ℓ/E0².
        let expected = 0.75 * 9e6 * 0.5 * (0.25 * PI).sin() / 1e12;
        assert!((lambda / expected - 1.0).abs() < 1e-14);
        assert!(hn.loss_compliance_slope_at_zero().is_infinite());
        let ratio = hn.low_speed_asymptote(4e-6) / hn.low_speed_asymptote(1e-6);
        assert!((ratio - 2.0).abs() < 1e-12);
    }
}
