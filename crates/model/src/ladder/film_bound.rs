//! A rigorous bound on how much a film changes μ: when it is below the
//! share of the accuracy `auto` allows, the film is neglected and the
//! half-space formula used.
//!
//! The film divides L(ω) by S(qd) ≥ 1 (S: [`crate::film`]), so the
//! half-space μ exceeds the film's by
//!
//!   cylinder: Δ = (8 f_N/π) ∫₀^∞ dq L(qv) [1 − 1/S(qd)] J1²(qa)/(qa)²,
//!   sphere:   Δ = (9 F_N/(2π²)) ∫₀^∞ dq q [1 − 1/S(qd)] f(q r) ∫₀^{2π} dφ cos φ L(qv cos φ).
//!
//! With J1²(y)/y² ≤ ¼ and f(y) ≤ 1/9 (both maxima at y = 0), the angular
//! integral at most 4 L̂(qv), L̂(ω) = max_{ω′ ≤ ω} L(ω′) the rising
//! envelope of the loss compliance, and x = qd:
//!
//!   cylinder: Δ ≤ (2 f_N/(π d))  ∫₀^∞ L̂(xv/d) [1 − 1/S(x)] dx,
//!   sphere:   Δ ≤ (2 F_N/(π² d²)) ∫₀^∞ x L̂(xv/d) [1 − 1/S(x)] dx.
//!
//! The contact size drops out (it only enters through the form factors'
//! maxima), so the bound holds for either contact rule. Since 1 − 1/S
//! falls like e^{−2x}, only wavelengths longer than about the film
//! thickness count: at low speed the bound is of order (a/d)² (cylinder)
//! and (r/d)³ (sphere) of μ, but at speeds where v/d reaches the loss peak
//! while the contact probes the glassy side, the long waves the film
//! stiffens carry a share of μ that no thickness removes.
//!
//! The integral is evaluated on a logarithmic grid, 40 points a decade
//! from x = 1e-8 to 40 (1 − 1/S < 1e-30 beyond), by the trapezoid rule in
//! ln x, with the envelope taken over the samples and 10 % added for what
//! the samples and the rule miss; below 1e-8 the integrand is at most
//! x^m L̂(1e-8 v/d). About 350 modulus evaluations a speed.

use std::f64::consts::PI;

use crate::contact::Shape;
use crate::film::film_factor;
use crate::modulus::ViscoelasticModulus;
use crate::scene::Scene;

/// Points of the x grid per decade, and its ends.
const PER_DECADE: f64 = 40.0;
const X_MIN: f64 = 1e-8;
const X_MAX: f64 = 40.0;

/// Bounds on μ_half − μ_film for one scene (its film thickness d).
pub(super) struct FilmBound<'a, M> {
    scene: &'a Scene<M>,
    thickness: f64,
    /// (x, 1 − 1/S(x, ν)) on the grid, increasing x.
    deficit: Vec<(f64, f64)>,
}

impl<'a, M: ViscoelasticModulus> FilmBound<'a, M> {
    /// The bound for `scene` with a film of `thickness` (m).
    pub(super) fn new(scene: &'a Scene<M>, thickness: f64) -> Self {
        let nu = scene.substrate().poisson;
        let n = ((X_MAX / X_MIN).log10() * PER_DECADE).ceil() as usize;
        let step = (X_MAX / X_MIN).ln() / n as f64;
        let deficit = (0..=n)
            .map(|k| {
                let x = X_MIN * (step * k as f64).exp();
                (x, 1.0 - 1.0 / film_factor(x, nu))
            })
            .collect();
        FilmBound {
            scene,
            thickness,
            deficit,
        }
    }

    /// An upper bound on μ_half − μ_film (≥ 0) at speed `v` (m/s).
    pub(super) fn at(&self, v: f64) -> f64 {
        let d = self.thickness;
        let g = self.scene.geometry();
        let power = match g.shape {
            Shape::Cylinder => 1,
            Shape::Sphere => 2,
        };
        let factor = self.scene.plane_strain_factor();
        let loss = |omega: f64| {
            let e = self.scene.material().modulus(omega);
            factor * e.im / e.norm_sqr()
        };
        // x^power [1 − 1/S] L̂ with the envelope over the samples so far;
        // the trapezoid in ln x weighs each sample by x (dx = x d ln x).
        let mut envelope = loss(X_MIN * v / d).max(0.0);
        let below = envelope * X_MIN.powi(power) / f64::from(power);
        let step = (X_MAX / X_MIN).ln() / (self.deficit.len() - 1) as f64;
        let mut sum = 0.0;
        for (k, &(x, deficit)) in self.deficit.iter().enumerate() {
            envelope = envelope.max(loss(x * v / d));
            let weight = if k == 0 || k + 1 == self.deficit.len() {
                0.5
            } else {
                1.0
            };
            sum += weight * x.powi(power) * deficit * envelope;
        }
        let integral = 1.1 * (below + step * sum);
        match g.shape {
            Shape::Cylinder => 2.0 * g.load / (PI * d) * integral,
            Shape::Sphere => 2.0 * g.load / (PI * PI * d * d) * integral,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn film_factor_is_at_least_one_so_the_deficit_lies_in_zero_one() {
        for nu in [0.0, 0.25, 0.49, 0.5] {
            for i in 0..=4000 {
                let x = 1e-6 * 10f64.powf(i as f64 * 8.0 / 4000.0);
                let s = film_factor(x, nu);
                assert!(s >= 1.0, "S({x}, {nu}) = {s}");
            }
        }
    }

    /// The bound is never below the film's real effect (both computed
    /// tightly) for both shapes, thin and thick films, across the speeds.
    #[test]
    fn bound_exceeds_the_film_effect() {
        use crate::{ContactSize, Geometry, Prony, StandardLinearSolid, Substrate};
        let broad = Prony::new(4e7, vec![2e6, 5e6, 1e7, 2e7], vec![1e-4, 1e-2, 1.0, 1e2]).unwrap();
        let materials = [
            StandardLinearSolid::new(1e6, 1e7, 1.0).unwrap().to_prony(),
            broad,
        ];
        for material in materials {
            for (shape, load) in [(Shape::Cylinder, 100.0), (Shape::Sphere, 0.15)] {
                let scene = |film| {
                    Scene::new(
                        Geometry {
                            shape,
                            radius: 0.01,
                            load,
                        },
                        Substrate {
                            poisson: 0.5,
                            film_thickness: film,
                        },
                        ContactSize::Dynamic,
                        material.clone(),
                    )
                    .unwrap()
                    .with_tolerance(1e-7)
                    .unwrap()
                };
                let half = scene(None);
                let a0 = half.static_contact_size();
                for ratio in [0.3, 1.0, 10.0, 100.0] {
                    let d = ratio * a0;
                    let film = scene(Some(d));
                    let bound = FilmBound::new(&film, d);
                    for k in 0..=8 {
                        let v = a0 * 10f64.powf(-6.0 + k as f64);
                        let (h, f) = (half.friction(v).unwrap(), film.friction(v).unwrap());
                        let b = bound.at(v);
                        // 2e-7 h: the two μ's own tolerance.
                        assert!(
                            h - f <= b + 2e-7 * h,
                            "{shape:?} d = {ratio} a0, v = {v:e}: effect {:e} > bound {b:e}",
                            h - f
                        );
                        assert!(h - f >= -2e-7 * h, "{shape:?}: the film stiffens");
                    }
                }
            }
        }
    }
}
