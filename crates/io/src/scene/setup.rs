//! `[geometry]`, `[substrate]` and `[contact]`: the rolling set-up.

use rollfit_fit::RollingSetup;
use rollfit_model::{ContactSize, Geometry, Shape, Substrate};
use serde::Deserialize;

use crate::error::IoError;

use super::SceneFile;
use super::values::Real;

/// Default Poisson's ratio (incompressible rubber).
pub const DEFAULT_POISSON: f64 = 0.5;
/// Shape names as written in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ShapeName {
    /// A ball; `load` is a force, N.
    Sphere,
    /// A roller; `load` is a force per length, N/m.
    Cylinder,
}

/// `[geometry]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GeometrySection {
    /// "sphere" or "cylinder".
    pub shape: ShapeName,
    /// Radius R of the rolling body, m.
    pub radius: Real,
    /// F_N in N (sphere) or f_N in N/m (cylinder).
    pub load: Real,
}

/// `[substrate]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SubstrateSection {
    /// Poisson's ratio ν of the viscoelastic solid (default ½).
    pub poisson: Option<Real>,
    /// Film thickness d, m, for a film on a rigid base; absent = half-space.
    pub thickness: Option<Real>,
}

/// The rungs of the model ladder as written in the file (`[contact] size`;
/// the contract, docs/ARCHITECTURE.md, "Contract", names "dynamic" and
/// "static", the rest extend it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ContactName {
    /// |E_eff(ω)| at the local frequency.
    Dynamic,
    /// E_eff(0) for every frequency.
    Static,
    /// The exact steady rolling contact (cylinder on a half-space, standard
    /// linear solid or Prony series; forward only): the reference Eq. (11)
    /// approximates.
    Exact,
    /// The low-speed asymptote, Eqs. (18)/(19) (forward only).
    #[serde(rename = "low-speed")]
    LowSpeed,
    /// The cheapest rung that meets `[contact] accuracy`, per speed
    /// (forward only; crates/model/src/ladder).
    Auto,
}

/// Default `[contact] accuracy` of `size = "auto"`.
pub const DEFAULT_ACCURACY: f64 = 1e-3;

/// `[contact]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSection {
    /// "dynamic" (default), "static", "exact", "low-speed" or "auto".
    pub size: Option<ContactName>,
    /// Relative accuracy of μ that `size = "auto"` must meet (default 1e-3).
    pub accuracy: Option<Real>,
}

impl ContactSection {
    /// `accuracy` belongs to `size = "auto"`.
    pub(super) fn check(&self) -> Result<(), IoError> {
        if let Some(Real(accuracy)) = self.accuracy {
            if self.size != Some(ContactName::Auto) {
                return Err(err!(
                    "[contact]: accuracy = {accuracy} is the target of size = \"auto\"; add size = \"auto\" \
         or remove accuracy"
                ));
            }
            if !(1e-8..=0.5).contains(&accuracy) {
                return Err(err!(
                    "[contact]: accuracy = {accuracy} must lie between 1e-8 and 0.5 (relative)"
                ));
            }
        }
        Ok(())
    }
}

impl SceneFile {
    /// The body, substrate and contact rule of `[geometry]`, `[substrate]` and
    /// `[contact]` (values unchecked: `Scene::new` checks them).
    pub fn rolling_setup(&self) -> RollingSetup {
        RollingSetup {
            geometry: Geometry {
                shape: match self.geometry.shape {
                    ShapeName::Sphere => Shape::Sphere,
                    ShapeName::Cylinder => Shape::Cylinder,
                },
                radius: self.geometry.radius.0,
                load: self.geometry.load.0,
            },
            substrate: Substrate {
                poisson: self.substrate.poisson.map_or(DEFAULT_POISSON, |r| r.0),
                film_thickness: self.substrate.thickness.map(|r| r.0),
            },
            // The exact solution has no contact-size rule; the columns
            // forward writes beside its μ (asymptote, static contact) come
            // from the paper's model with the dynamic size.
            contact: match self.contact.size {
                None
                | Some(ContactName::Dynamic)
                | Some(ContactName::Exact)
                | Some(ContactName::LowSpeed)
                | Some(ContactName::Auto) => ContactSize::Dynamic,
                Some(ContactName::Static) => ContactSize::Static,
            },
        }
    }
}
