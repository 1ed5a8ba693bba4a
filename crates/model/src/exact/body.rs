//! One interface over the exact steady rolling solutions: the cylinder
//! (plane strain, [`super::RollingCylinder`]) and the sphere. The fit's
//! defect correction and `auto`'s exact rung ask "μ at this speed, and how
//! sure are you" without caring which body rolls.
//!
//! See docs/ARCHITECTURE.md, "Where each equation lives".

use crate::contact::Shape;
use crate::error::ModelError;
use crate::modulus::Prony;

use super::{ExactSettings, RollingCylinder};

/// μ of the exact steady rolling contact at one speed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExactFriction {
    /// Rolling friction coefficient μ = x̄/R (dimensionless).
    pub mu: f64,
    /// Estimated relative error of μ from the discretisation.
    pub error_estimate: f64,
}

/// A rigid body rolling steadily on a linear viscoelastic half-space,
/// solved without the approximations of Eqs. (11)/(17).
pub trait ExactRolling: Send + Sync {
    /// Which body rolls.
    fn shape(&self) -> Shape;

    /// μ at speed `v` (m/s) with its error estimate.
    fn exact_friction(&self, v: f64) -> Result<ExactFriction, ModelError>;
}

impl ExactRolling for RollingCylinder {
    fn shape(&self) -> Shape {
        Shape::Cylinder
    }

    fn exact_friction(&self, v: f64) -> Result<ExactFriction, ModelError> {
        let solution = self.solve_with_error_estimate(v)?;
        Ok(ExactFriction {
            mu: solution.mu,
            error_estimate: solution.error_estimate,
        })
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
    match shape {
        Shape::Cylinder => {
            let cylinder = RollingCylinder::new(modulus, poisson, radius, load)?
                .with_layer_resolution(ExactSettings::resolution_for(accuracy));
            Ok(Box::new(cylinder))
        }
        Shape::Sphere => Err(ModelError::ExactNotAvailable {
            why: "there is no exact solution for a sphere yet",
        }),
    }
}
