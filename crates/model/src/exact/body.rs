//! One interface over the exact steady rolling solutions: the cylinder
//! (plane strain, [`super::RollingCylinder`]) and the sphere
//! ([`super::RollingSphere`]). The fit's defect correction, `auto`'s exact
//! rung and `rollfit forward` ask "μ at this speed, and how sure are you"
//! without caring which body rolls.
//!
//! See docs/ARCHITECTURE.md, "Where each equation lives".

use crate::contact::Shape;
use crate::error::ModelError;
use crate::modulus::Prony;

use super::sphere::SphereStart;
use super::{
    ExactSettings, GRADED_ERROR, GRADED_FLOOR, GRADED_SAFETY, GradedStart, PressureMap,
    RollingCylinder, RollingSolution, RollingSphere, SphereSettings,
};

/// The exact steady rolling contact at one speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExactFriction {
    /// Rolling friction coefficient μ = x̄/R (dimensionless).
    pub mu: f64,
    /// Estimated relative error of μ from the discretisation.
    pub error_estimate: f64,
    /// Trailing contact edge on the rolling axis (y = 0), m from the
    /// body's axis (< 0).
    pub trailing_edge: f64,
    /// Leading contact edge on the rolling axis, m (> 0).
    pub leading_edge: f64,
}

/// A rigid body rolling steadily on a linear viscoelastic half-space,
/// solved without the approximations of Eqs. (11)/(17).
pub trait ExactRolling: Send + Sync {
    /// Which body rolls.
    fn shape(&self) -> Shape;

    /// The Hertz contact size with the static modulus (half-width a0 or
    /// radius r0), m: identifies the scene the body was built for.
    fn static_contact_size(&self) -> f64;

    /// μ at speed `v` (m/s) with its error estimate and the contact edges.
    fn exact_friction(&self, v: f64) -> Result<ExactFriction, ModelError>;

    /// The contact at speed `v` (m/s): the pressure (Pa) under the body and
    /// the contact's outline, x (m) from the body's axis, + in the rolling
    /// direction, from the same solution as [`Self::exact_friction`] (the
    /// same μ and error estimate). See [`PressureMap`].
    fn pressure_map(&self, v: f64) -> Result<PressureMap, ModelError>;

    /// The same body discretised for a relative accuracy of μ (explicit
    /// discretisations chosen by the caller are kept).
    fn with_accuracy(&self, accuracy: f64) -> Box<dyn ExactRolling>;

    /// As [`Self::exact_friction`], the iterations started from `start`,
    /// where a solve at the same speed ended for a nearby modulus (the
    /// last sweep of a fit), and with where this one ended. A start only
    /// saves iterations: the answer is that of [`Self::exact_friction`] to
    /// the solver's own tolerances (see [`ExactStart`]). Bodies without a
    /// warm start solve cold.
    fn exact_friction_from(
        &self,
        v: f64,
        _start: Option<&ExactStart>,
    ) -> Result<(ExactFriction, ExactStart), ModelError> {
        Ok((self.exact_friction(v)?, ExactStart(Start::Cold)))
    }

    /// As [`Self::exact_friction_from`], but where the body's error
    /// estimate costs a solve of its own (the cylinder's graded mesh: a
    /// q + 2 mesh, about half the cost), that solve is left out: the
    /// estimate is NaN, and [`Self::deferred_estimate`] with the start
    /// returned gives it later, the same number. A caller that learns only
    /// afterwards which solves it reports (a fit's last sweep) pays for
    /// those estimates alone.
    fn exact_friction_unestimated_from(
        &self,
        v: f64,
        start: Option<&ExactStart>,
    ) -> Result<(ExactFriction, ExactStart), ModelError> {
        self.exact_friction_from(v, start)
    }

    /// The error estimate left out by [`Self::exact_friction_unestimated_from`]
    /// at speed `v` (the same `v`), from the start it returned: None where
    /// that solve's estimate came with it.
    fn deferred_estimate(&self, _v: f64, _end: &ExactStart) -> Result<Option<f64>, ModelError> {
        Ok(None)
    }
}

/// Where an exact solve ended, to start the next solve at the same speed
/// for a nearby modulus from:
///
/// - the cylinder: the contact half-width, the root that its secant (graded
///   mesh) or Newton's method (Chebyshev) finds. Both iterate until the
///   step in ln b is at most the tolerance (1e-12), so a start changes the
///   answer by no more than that; from the last refit's root, a few 1e-4
///   off, the q mesh's secant takes its small first step of a root start.
/// - the sphere: each grid's contact set and pressures
///   ([`RollingSphere::solve_from`]); the active-set iteration settles on
///   the same set as from the cold start wherever the discrete contact
///   problem has one solution, and a warm solve that does not settle is
///   done again cold.
#[derive(Debug, Clone)]
pub struct ExactStart(Start);

#[derive(Debug, Clone)]
enum Start {
    Cold,
    HalfWidth(f64),
    /// A graded-mesh solve without its estimate: the q mesh's root and μ.
    Unestimated {
        half_width: f64,
        mu: f64,
    },
    Sphere(Box<SphereStart>),
}

impl Start {
    /// The half-width of a cylinder's start.
    fn half_width(&self) -> Option<f64> {
        match self {
            Start::HalfWidth(b) | Start::Unestimated { half_width: b, .. } => Some(*b),
            Start::Cold | Start::Sphere(_) => None,
        }
    }
}

impl ExactRolling for RollingCylinder {
    fn shape(&self) -> Shape {
        Shape::Cylinder
    }

    fn static_contact_size(&self) -> f64 {
        self.static_half_width()
    }

    fn exact_friction(&self, v: f64) -> Result<ExactFriction, ModelError> {
        Ok(cylinder_friction(&self.solve_with_error_estimate(v)?))
    }

    fn pressure_map(&self, v: f64) -> Result<PressureMap, ModelError> {
        let solution = self.solve_with_error_estimate(v)?;
        Ok(PressureMap::of_cylinder(
            &solution,
            self.static_half_width(),
            self.load,
        ))
    }

    fn exact_friction_from(
        &self,
        v: f64,
        start: Option<&ExactStart>,
    ) -> Result<(ExactFriction, ExactStart), ModelError> {
        let half_width = start.and_then(|s| s.0.half_width());
        let solution = self.solve_with_error_estimate_from(v, half_width)?;
        let end = ExactStart(Start::HalfWidth(solution.half_width()));
        Ok((cylinder_friction(&solution), end))
    }

    fn exact_friction_unestimated_from(
        &self,
        v: f64,
        start: Option<&ExactStart>,
    ) -> Result<(ExactFriction, ExactStart), ModelError> {
        let d = self.discretisation(v);
        if d.resolved {
            // The Chebyshev solve's estimate is its calibrated claim.
            return self.exact_friction_from(v, start);
        }
        crate::error::require_positive("v", v)?;
        let graded = match start.and_then(|s| s.0.half_width()) {
            Some(b) => GradedStart::Root(b),
            None => GradedStart::Guess(d.half_width),
        };
        let q = self.settings().panel_nodes;
        let solution = self.solve_graded(v, d.terms, q, graded)?;
        let end = Start::Unestimated {
            half_width: solution.half_width(),
            mu: solution.mu,
        };
        let mut friction = cylinder_friction(&solution);
        friction.error_estimate = f64::NAN;
        Ok((friction, ExactStart(end)))
    }

    fn deferred_estimate(&self, v: f64, end: &ExactStart) -> Result<Option<f64>, ModelError> {
        let Start::Unestimated { half_width, mu } = end.0 else {
            return Ok(None);
        };
        let terms = self.discretisation(v).terms;
        Ok(Some(self.graded_estimate(v, terms, (mu, half_width))))
    }

    fn with_accuracy(&self, accuracy: f64) -> Box<dyn ExactRolling> {
        if self.settings().terms.is_some() {
            Box::new(self.clone())
        } else {
            Box::new(self.with_layer_resolution(ExactSettings::resolution_for(accuracy)))
        }
    }
}

impl ExactRolling for RollingSphere {
    fn shape(&self) -> Shape {
        Shape::Sphere
    }

    fn static_contact_size(&self) -> f64 {
        self.static_contact_radius()
    }

    fn exact_friction(&self, v: f64) -> Result<ExactFriction, ModelError> {
        Ok(sphere_friction(&self.solve(v)?))
    }

    fn exact_friction_from(
        &self,
        v: f64,
        start: Option<&ExactStart>,
    ) -> Result<(ExactFriction, ExactStart), ModelError> {
        let previous = match start {
            Some(ExactStart(Start::Sphere(s))) => Some(s.as_ref()),
            _ => None,
        };
        let (solution, end) = self.solve_from(v, previous)?;
        let end = ExactStart(Start::Sphere(Box::new(end)));
        Ok((sphere_friction(&solution), end))
    }

    fn pressure_map(&self, v: f64) -> Result<PressureMap, ModelError> {
        let solution = self.solve(v)?;
        Ok(PressureMap::of_sphere(
            &solution,
            self.static_contact_radius(),
        ))
    }

    fn with_accuracy(&self, accuracy: f64) -> Box<dyn ExactRolling> {
        Box::new(self.with_cells(SphereSettings::for_accuracy(accuracy).cells))
    }
}

fn cylinder_friction(solution: &super::RollingSolution) -> ExactFriction {
    ExactFriction {
        mu: solution.mu,
        error_estimate: solution.error_estimate,
        trailing_edge: solution.trailing_edge,
        leading_edge: solution.leading_edge,
    }
}

fn sphere_friction(solution: &super::SphereSolution) -> ExactFriction {
    let (trailing_edge, leading_edge) = solution.axis_edges();
    ExactFriction {
        mu: solution.mu,
        error_estimate: solution.error_estimate,
        trailing_edge,
        leading_edge,
    }
}

impl RollingCylinder {
    /// The graded-mesh solve of [`Self::solve_with_error_estimate`], its
    /// q mesh's secant started at `start`.
    pub(super) fn graded_with_estimate(
        &self,
        v: f64,
        terms: usize,
        start: GradedStart,
    ) -> Result<RollingSolution, ModelError> {
        let q = self.settings().panel_nodes;
        let mut solution = self.solve_graded(v, terms, q, start)?;
        solution.error_estimate =
            self.graded_estimate(v, terms, (solution.mu, solution.half_width()));
        Ok(solution)
    }

    /// The a-posteriori estimate of a q-mesh solution (μ, half-width b in
    /// m) at speed `v`: the q + 2 mesh's secant started at its root.
    pub(super) fn graded_estimate(&self, v: f64, terms: usize, (mu, b): (f64, f64)) -> f64 {
        let q = self.settings().panel_nodes;
        match self.solve_graded(v, terms, q + 2, GradedStart::Root(b)) {
            Ok(finer) => (GRADED_SAFETY * (mu / finer.mu - 1.0).abs()).max(GRADED_FLOOR),
            // No estimate without the finer mesh: the calibrated claim.
            Err(_) => GRADED_ERROR,
        }
    }

    /// [`Self::solve_with_error_estimate`], the q mesh's secant (or the
    /// Chebyshev Newton iteration) started from `half_width` (m) where
    /// given: the root of an earlier solve at this speed for a nearby
    /// modulus ([`ExactStart`]).
    fn solve_with_error_estimate_from(
        &self,
        v: f64,
        half_width: Option<f64>,
    ) -> Result<super::RollingSolution, ModelError> {
        let Some(b) = half_width else {
            return self.solve_with_error_estimate(v);
        };
        crate::error::require_positive("v", v)?;
        let mut d = self.discretisation(v);
        if d.resolved {
            d.half_width = b;
            return self.solve_discretised(v, &d);
        }
        self.graded_with_estimate(v, d.terms, GradedStart::Root(b))
    }
}

/// The exact rolling body of `shape` (radius m, load N or N/m) on a
/// half-space with Prony modulus `modulus` (Young's, Pa) and Poisson ratio
/// `poisson`, discretised for a relative accuracy `accuracy` of μ.
pub fn exact_body(
    shape: Shape,
    modulus: &Prony,
    poisson: f64,
    radius: f64,
    load: f64,
    accuracy: f64,
) -> Result<Box<dyn ExactRolling>, ModelError> {
    Ok(match shape {
        Shape::Cylinder => {
            RollingCylinder::new(modulus, poisson, radius, load)?.with_accuracy(accuracy)
        }
        Shape::Sphere => RollingSphere::with_settings(
            modulus,
            poisson,
            radius,
            load,
            SphereSettings::for_accuracy(accuracy),
        )?
        .with_accuracy(accuracy),
    })
}
