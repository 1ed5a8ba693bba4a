//! The ladder of model fidelities, and `auto`: the cheapest rung that meets
//! a requested accuracy, chosen per speed.
//!
//! # The rungs, cheapest first
//!
//! 1. The low-speed asymptote, Eqs. (18)/(19) ([`crate::asymptotes`]): one
//!    power of v, exact as v → 0 only.
//! 2. Eq. (11)/(17) with the static contact size E_eff(0).
//! 3. Eq. (11)/(17) with the dynamic contact size |E_eff(ω)| (the paper's).
//! 4. The exact rolling body ([`crate::exact`]) on a half-space, Prony or
//!    standard-linear-solid modulus: the cylinder in milliseconds a speed,
//!    the sphere in about a second.
//!
//! and two dials: the quadrature tolerance of rungs 2–3, and, for a film,
//! whether it is computed or neglected (a half-space). What each costs and
//! how far it is from the next is measured by `rollfit bench` (examples/fits/bench).
//!
//! # `auto`
//!
//! The reference is the most faithful rung the scene has: the exact
//! cylinder or sphere where it applies, else Eq. (11)/(17) with the
//! dynamic contact size and the film. Given a relative accuracy ε against it, the error
//! budget is shared out as ε/10 to the quadrature (its tolerance), and 0.3 ε
//! each to neglecting the film, to the low-speed asymptote and to the model
//! error of Eq. (11), so that their sum stays below ε. Per speed of an
//! increasing sweep:
//!
//! - the asymptote serves the leading run of speeds where it lies within
//!   0.3 ε of the full model with the film (`low_speed`, by probes);
//! - elsewhere Eq. (11)/(17) with the dynamic size; a film is neglected
//!   where the rigorous bound of `film_bound` on its effect is below
//!   0.3 ε of the half-space μ, and computed elsewhere;
//! - the exact body replaces either where the model-error estimate of
//!   `model_error`, K μR/b, exceeds 0.3 ε and it applies (no film
//!   computed at that speed).
//!
//! Each speed gets an error estimate against the exact physics: the
//! quadrature tolerance, the film bound, the asymptote's probed deviation,
//! the model-error estimate K μR/b (measured against the exact cylinder
//! and the exact sphere, `model_error`), or the exact solution's own
//! estimate of its grid error ([`crate::exact::ExactFriction`]; where that
//! is no better than Eq. (11)/(17)'s, Eq. (11)/(17) is kept). Where the
//! estimate exceeds ε — a film near the friction maximum, where no exact
//! rung exists — the result says so rather than claiming the accuracy.
//!
//! The static contact size is never chosen: it costs what the dynamic one
//! costs (one quadrature on the same grid) and is never closer to the
//! exact cylinder (examples/fits/bench, tests/eq11_error_map.rs).
//!
//! # References
//! - B.N.J. Persson, Eur. Phys. J. E 33 (2010), Eqs. (11), (17)–(19).
//! - S.C. Hunter, J. Appl. Mech. 28 (1961) 611–617 (the exact cylinder).

mod film_bound;
mod low_speed;
mod model_error;

pub use model_error::{MODEL_ERROR_FACTOR, dynamic_contact_size, model_error_estimate};

use crate::contact::{ContactSize, Shape};
use crate::error::ModelError;
use crate::exact::{ExactRolling, RollingCylinder};
use crate::modulus::ViscoelasticModulus;
use crate::scene::{Scene, Substrate};
use film_bound::FilmBound;
use rayon::prelude::*;

/// Share of the accuracy given to the quadrature tolerance.
const QUADRATURE_SHARE: f64 = 0.1;
/// Share given to each of: neglecting a film, the low-speed asymptote, the
/// model error of Eq. (11).
const RUNG_SHARE: f64 = 0.3;

/// The rung `auto` chose at one speed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rung {
    /// The low-speed asymptote, Eqs. (18)/(19).
    LowSpeed,
    /// Eq. (11)/(17), dynamic contact size, half-space (a film, if the
    /// scene has one, neglected).
    Dynamic,
    /// Eq. (11)/(17), dynamic contact size, with the film.
    DynamicFilm,
    /// The exact rolling cylinder.
    Exact,
}

impl Rung {
    /// The name written to output files.
    pub fn name(self) -> &'static str {
        match self {
            Rung::LowSpeed => "low-speed",
            Rung::Dynamic => "dynamic",
            Rung::DynamicFilm => "dynamic-film",
            Rung::Exact => "exact",
        }
    }

    /// A phrase for people.
    fn description(self, shape: Shape) -> &'static str {
        match (self, shape) {
            (Rung::LowSpeed, _) => "the low-speed asymptote (Eqs. 18/19)",
            (Rung::Dynamic, Shape::Cylinder) => "Eq. (11), dynamic contact size",
            (Rung::Dynamic, Shape::Sphere) => "Eq. (17), dynamic contact size",
            (Rung::DynamicFilm, Shape::Cylinder) => "Eq. (11) with the film",
            (Rung::DynamicFilm, Shape::Sphere) => "Eq. (17) with the film",
            (Rung::Exact, Shape::Cylinder) => "the exact rolling cylinder",
            (Rung::Exact, Shape::Sphere) => "the exact rolling sphere",
        }
    }
}

/// μ(v) by `auto`, with what it chose and why.
#[derive(Debug, Clone, PartialEq)]
pub struct AutoSweep {
    /// μ at each speed.
    pub mu: Vec<f64>,
    /// The rung used at each speed.
    pub rungs: Vec<Rung>,
    /// Estimated relative error of each μ against the exact physics (see
    /// the module documentation).
    pub error_estimate: Vec<f64>,
    /// The requested relative accuracy ε.
    pub accuracy: f64,
    /// Quadrature tolerance used for Eq. (11)/(17).
    pub tolerance: f64,
    /// Why the exact cylinder is not available, if it is not.
    pub exact_unavailable: Option<String>,
    /// The film's thickness (m) and the largest bound on its effect where
    /// it was neglected, if the scene has a film.
    pub film: Option<(f64, Option<f64>)>,
}

impl AutoSweep {
    /// The relative accuracy of μ the exact rung's body was discretised for
    /// ([`ExactRolling::with_accuracy`]): its share of the requested
    /// accuracy. A pressure map drawn beside the sweep uses the same body,
    /// so that its μ is the sweep's.
    pub fn exact_accuracy(&self) -> f64 {
        RUNG_SHARE * self.accuracy
    }

    /// Number of speeds whose error estimate exceeds the accuracy.
    pub fn unmet(&self) -> usize {
        self.error_estimate
            .iter()
            .filter(|&&e| e > self.accuracy)
            .count()
    }

    /// What was chosen, in one paragraph, for `speeds` (m/s) of a `shape`.
    pub fn description(&self, speeds: &[f64], shape: Shape) -> String {
        let mut parts = Vec::new();
        for rung in [
            Rung::LowSpeed,
            Rung::Dynamic,
            Rung::DynamicFilm,
            Rung::Exact,
        ] {
            let at: Vec<f64> = speeds
                .iter()
                .zip(&self.rungs)
                .filter(|(_, r)| **r == rung)
                .map(|(v, _)| *v)
                .collect();
            if let (Some(lo), Some(hi)) = (at.first(), at.last()) {
                let range = if at.len() == 1 {
                    format!("v = {lo:.3e} m/s")
                } else {
                    format!("v = {lo:.3e} … {hi:.3e} m/s")
                };
                parts.push(format!(
                    "{} at {} speed{} ({range})",
                    rung.description(shape),
                    at.len(),
                    if at.len() == 1 { "" } else { "s" }
                ));
            }
        }
        let reference = match &self.exact_unavailable {
            None => match shape {
                Shape::Cylinder => "the exact rolling cylinder".to_string(),
                Shape::Sphere => "the exact rolling sphere".to_string(),
            },
            Some(why) => format!(
                "{} with the dynamic contact size (no exact rung: {why})",
                match shape {
                    Shape::Cylinder => "Eq. (11)",
                    Shape::Sphere => "Eq. (17)",
                }
            ),
        };
        let mut text = format!(
            "auto, accuracy {:.0e} against {reference}: {}; quadrature tolerance {:.0e}",
            self.accuracy,
            parts.join(", "),
            self.tolerance
        );
        if let Some((d, neglected)) = self.film {
            match neglected {
                Some(bound) => {
                    text += &format!(
                        "; the film (d = {d:e} m) neglected where its effect is below {:.1e} \
                     (largest bound {bound:.1e})",
                        RUNG_SHARE * self.accuracy
                    )
                }
                None => text += &format!("; the film (d = {d:e} m) computed at every speed"),
            }
        }
        let worst = self.error_estimate.iter().copied().fold(0.0, f64::max);
        let unmet = self.unmet();
        if unmet == 0 {
            text += &format!("; estimated error ≤ {worst:.1e} at every speed");
        } else {
            text += &format!(
                "; NOT MET at {unmet} of {} speeds: estimated error up to {worst:.1e}",
                speeds.len()
            );
            if self.exact_unavailable.is_some() {
                text += " (the model error of Eq. (11)/(17) near the friction maximum, estimated \
                         as 0.4 μR/b; only the exact solution on a half-space goes further)";
            }
        }
        text
    }
}

impl<M: ViscoelasticModulus> Scene<M> {
    /// μ at each of `speeds` (m/s, strictly increasing) by the cheapest
    /// rung that meets the relative `accuracy` (1e-8 … 0.5), per speed
    /// (module documentation). `exact` is this scene's exact rolling
    /// cylinder when the scene has one (cylinder, Prony modulus), else
    /// `Err` with the reason. The scene's own tolerance and contact rule
    /// are not used: auto sets the tolerance to accuracy/10 and uses the
    /// dynamic contact size.
    pub fn friction_auto(
        &self,
        speeds: &[f64],
        accuracy: f64,
        exact: Result<&RollingCylinder, String>,
    ) -> Result<AutoSweep, ModelError> {
        self.friction_auto_with(speeds, accuracy, exact.map(|c| c as &dyn ExactRolling))
    }

    /// As [`Self::friction_auto`] with any exact rolling body (the cylinder
    /// or the sphere, [`crate::exact::exact_body`]).
    pub fn friction_auto_with(
        &self,
        speeds: &[f64],
        accuracy: f64,
        exact: Result<&dyn ExactRolling, String>,
    ) -> Result<AutoSweep, ModelError> {
        check_auto_request(speeds, accuracy)?;
        let exact = self.matching_exact(exact)?;
        let tolerance = (QUADRATURE_SHARE * accuracy).clamp(1e-12, 1e-2);
        let budget = RUNG_SHARE * accuracy;
        let at = |film: Option<f64>| {
            Scene::new(
                *self.geometry(),
                Substrate {
                    film_thickness: film,
                    ..*self.substrate()
                },
                ContactSize::Dynamic,
                self.material(),
            )?
            .with_tolerance(tolerance)
        };
        let film = self.substrate().film_thickness;
        let full = at(film)?;
        let half_space = at(None)?;
        let rungs = LadderRuns {
            full: &full,
            half_space: &half_space,
            film,
            speeds,
            budget,
            tolerance,
        };
        let (mut sweep, neglected_bound) = rungs.asymptote_and_dynamic()?;
        if let Ok(body) = &exact {
            rungs.exact_where_needed(*body, &mut sweep)?;
        } else {
            rungs.add_model_error(&mut sweep);
        }
        Ok(AutoSweep {
            mu: sweep.mu,
            rungs: sweep.rungs,
            error_estimate: sweep.estimate,
            accuracy,
            tolerance,
            exact_unavailable: exact.err(),
            film: film.map(|d| (d, neglected_bound)),
        })
    }

    /// The caller's exact body, checked to be this scene's; `Err` with
    /// the reason when there is none.
    fn matching_exact<'c>(
        &self,
        exact: Result<&'c dyn ExactRolling, String>,
    ) -> Result<Result<&'c dyn ExactRolling, String>, ModelError> {
        Ok(match exact {
            Ok(body) if body.shape() == self.geometry().shape => {
                let size = self.static_contact_size();
                if (body.static_contact_size() / size - 1.0).abs() > 1e-8 {
                    return Err(ModelError::ExactCylinderMismatch {
                        exact: body.static_contact_size(),
                        scene: size,
                    });
                }
                Ok(body)
            }
            Ok(_) => Err("the exact solution is for another body".to_string()),
            Err(why) => Err(why),
        })
    }
}

/// Refuses an accuracy outside 1e-8 … 0.5 and speeds that do not increase.
fn check_auto_request(speeds: &[f64], accuracy: f64) -> Result<(), ModelError> {
    if !(accuracy.is_finite() && (1e-8..=0.5).contains(&accuracy)) {
        return Err(ModelError::parameter(
            "accuracy",
            accuracy,
            "must lie between 1e-8 and 0.5",
        ));
    }
    for (i, w) in speeds.windows(2).enumerate() {
        if w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater) {
            return Err(ModelError::table(
                "speeds",
                format!(
                    "auto needs strictly increasing speeds; v[{}] = {} follows {}",
                    i + 1,
                    w[1],
                    w[0]
                ),
            ));
        }
    }
    Ok(())
}

/// μ, rung and error estimate per speed, as the rungs fill them in.
struct PartialSweep {
    mu: Vec<f64>,
    rungs: Vec<Rung>,
    estimate: Vec<f64>,
    /// The bound on a neglected film's effect, relative (0 where the film
    /// is computed or absent).
    film_effect: Vec<f64>,
}

/// What every rung of one `friction_auto` call shares.
struct LadderRuns<'a, M: ViscoelasticModulus> {
    /// The scene with its film (if any), dynamic contact, auto's tolerance.
    full: &'a Scene<&'a M>,
    /// The same on a half-space.
    half_space: &'a Scene<&'a M>,
    film: Option<f64>,
    speeds: &'a [f64],
    /// The share of the accuracy each rung's approximation may use.
    budget: f64,
    tolerance: f64,
}

impl<M: ViscoelasticModulus> LadderRuns<'_, M> {
    /// Steps 1 and 2: the asymptote's run at the low speeds, against the
    /// full model; Eq. (11)/(17) above it, with the film where it matters.
    /// Also returns the largest bound of a neglected film's effect.
    fn asymptote_and_dynamic(&self) -> Result<(PartialSweep, Option<f64>), ModelError> {
        let (full, speeds, budget, tolerance) =
            (self.full, self.speeds, self.budget, self.tolerance);
        let (low, low_deviation) = low_speed::asymptote_run(full, speeds, budget)?;
        let mut sweep = PartialSweep {
            mu: speeds[..low]
                .iter()
                .map(|&v| full.low_speed_asymptote(v))
                .collect(),
            rungs: vec![Rung::LowSpeed; low],
            estimate: vec![low_deviation; low],
            film_effect: vec![0.0; low],
        };
        let rest = &speeds[low..];
        let bound = self.film.map(|d| FilmBound::new(full, d));
        let half = self.half_space.friction_sweep(rest)?;
        let mut film_speeds = Vec::new();
        let mut neglected_bound: Option<f64> = None;
        for (j, &v) in rest.iter().enumerate() {
            let relative = bound.as_ref().map_or(0.0, |b| b.at(v) / half[j]);
            if relative <= budget {
                if bound.is_some() {
                    neglected_bound = Some(neglected_bound.unwrap_or(0.0).max(relative));
                }
                sweep.mu.push(half[j]);
                sweep.rungs.push(Rung::Dynamic);
                sweep.estimate.push(tolerance + relative);
                sweep.film_effect.push(relative);
            } else {
                film_speeds.push(low + j);
                sweep.mu.push(f64::NAN);
                sweep.rungs.push(Rung::DynamicFilm);
                sweep.estimate.push(tolerance);
                sweep.film_effect.push(0.0);
            }
        }
        if !film_speeds.is_empty() {
            let v: Vec<f64> = film_speeds.iter().map(|&i| speeds[i]).collect();
            for (&i, m) in film_speeds.iter().zip(full.friction_sweep(&v)?) {
                sweep.mu[i] = m;
            }
        }
        Ok((sweep, neglected_bound))
    }

    /// The model error of Eq. (11)/(17) at each speed, added to the
    /// estimates; returns it.
    fn add_model_error(&self, sweep: &mut PartialSweep) -> Vec<f64> {
        let indicator: Vec<f64> = (0..self.speeds.len())
            .map(|i| model_error_estimate(self.half_space, self.speeds[i], sweep.mu[i]))
            .collect();
        for (estimate, e) in sweep.estimate.iter_mut().zip(&indicator) {
            *estimate += e;
        }
        indicator
    }

    /// Step 3: the model error of Eq. (11), and the exact cylinder where it
    /// is too large and applies (no film computed there).
    fn exact_where_needed(
        &self,
        body: &dyn ExactRolling,
        sweep: &mut PartialSweep,
    ) -> Result<(), ModelError> {
        // The exact cylinder is a half-space: with a film it may replace
        // only the speeds where the film was neglected by its bound.
        let film = self.film;
        let exact_applies = |rung: Rung| match rung {
            Rung::Dynamic => true,
            Rung::LowSpeed => film.is_none(),
            Rung::DynamicFilm | Rung::Exact => false,
        };
        let indicator = self.add_model_error(sweep);
        let exact_speeds: Vec<usize> = (0..self.speeds.len())
            .filter(|&i| exact_applies(sweep.rungs[i]) && indicator[i] > self.budget)
            .collect();
        if exact_speeds.is_empty() {
            return Ok(());
        }
        // As fine a discretisation as the model-error share needs, and no
        // finer (unless the caller chose it explicitly).
        let body = body.with_accuracy(self.budget);
        // Milliseconds (cylinder) to a second (sphere) a speed: worth the
        // threads.
        let solved = exact_speeds
            .par_iter()
            .map(|&i| body.exact_friction(self.speeds[i]))
            .collect::<Result<Vec<_>, ModelError>>()?;
        for (&i, solution) in exact_speeds.iter().zip(solved) {
            // What the film adds where it was neglected stays.
            let error = solution.error_estimate + sweep.film_effect[i];
            // Where its edge layers are thin the exact solution may be no
            // better than Eq. (11): keep the better estimate.
            if error < sweep.estimate[i] {
                sweep.mu[i] = solution.mu;
                sweep.rungs[i] = Rung::Exact;
                sweep.estimate[i] = error;
            }
        }
        Ok(())
    }
}
