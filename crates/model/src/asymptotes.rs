//! Quantities derived from μ(v): the low-speed asymptote, Greenwood–Tabor's
//! hysteresis-loss fraction α, the pressure-centroid shift and the friction
//! maximum.
//!
//! Low speed, Persson (2010) Eqs. (18)/(19) and the cylinder analogue: as
//! v → 0 only frequencies ω ≪ v/a0 matter, where L(ω) ≈ L′(0) ω and the
//! contact has its static size, so
//!
//!   sphere:   μ → (9I/2) p_a L′(0) v/r0,  I = π/6 (9I/2 = 3π/4),
//!   cylinder: μ → (8/π) p_a L′(0) v/a0,
//!
//! with p_a the static mean pressure and L′(0) = (1 − ν²) lim E″/(ω E0²).
//! (For the sphere ∫₀^∞ x²G(x)dx = π²/24 fixes I; for the cylinder
//! ∫₀^∞ J1²(y)/y dy = 1/2 gives the 8/π.)
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

impl<M: ViscoelasticModulus> Scene<M> {
    /// L′(0) = dL/dω at ω = 0 (1/(Pa·rad/s)), L = −Im 1/E_eff.
    pub fn loss_compliance_slope_at_zero(&self) -> f64 {
        let e0 = self.material().static_modulus();
        self.plane_strain_factor() * self.material().loss_slope_at_zero() / (e0 * e0)
    }

    /// Low-speed asymptote of μ at speed `v` (m/s), Eqs. (18)/(19).
    pub fn low_speed_asymptote(&self, v: f64) -> f64 {
        let size = self.static_contact_size();
        let factor = match self.geometry().shape {
            Shape::Sphere => 0.75 * PI,
            Shape::Cylinder => 8.0 / PI,
        };
        factor * self.static_mean_pressure() * self.loss_compliance_slope_at_zero() * v / size
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
            return Err(ModelError::Evaluation(format!(
                "friction maximum: need 0 < v_min < v_max, got [{v_min}, {v_max}]"
            )));
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
