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

use super::{ExactSettings, PressureMap, RollingCylinder, RollingSphere, SphereSettings};

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
}

impl ExactRolling for RollingCylinder {
    fn shape(&self) -> Shape {
        Shape::Cylinder
    }

    fn static_contact_size(&self) -> f64 {
        self.static_half_width()
    }

    fn exact_friction(&self, v: f64) -> Result<ExactFriction, ModelError> {
        let solution = self.solve_with_error_estimate(v)?;
        Ok(ExactFriction {
            mu: solution.mu,
            error_estimate: solution.error_estimate,
            trailing_edge: solution.trailing_edge,
            leading_edge: solution.leading_edge,
        })
    }

    fn pressure_map(&self, v: f64) -> Result<PressureMap, ModelError> {
        let solution = self.solve_with_error_estimate(v)?;
        Ok(PressureMap::of_cylinder(
            &solution,
            self.static_half_width(),
            self.load,
        ))
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
        let solution = self.solve(v)?;
        let (trailing_edge, leading_edge) = solution.axis_edges();
        Ok(ExactFriction {
            mu: solution.mu,
            error_estimate: solution.error_estimate,
            trailing_edge,
            leading_edge,
        })
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
