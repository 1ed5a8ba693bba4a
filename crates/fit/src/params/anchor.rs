//! The scale anchors of a fit reduced to a known |E| at one frequency,
//! and the range of the moduli a fit's settings give.

use std::f64::consts::PI;

use rollfit_model::{ContactSize, Shape};

use super::{ModulusAnchor, RollingSetup, ScaleAnchor, positive};
use crate::error::FitError;

/// Accepted moduli of the fit's bound and anchors (`E1_max`, `E0`,
/// `E_at.E`), Pa: 1 kPa, a decade below the softest rubber
/// (`rollfit_model::plausibility::MIN_RUBBER_MODULUS`), to 1 TPa, diamond's Young's modulus and
/// ten times the stiffest glassy polymer (`rollfit_model::plausibility::MAX_GLASSY_MODULUS`).
/// Outside, the fit's numbers leave the floating-point range before any
/// check can name the key (`E1_max = 1e-300`: "effective_parameters =
/// NaN").
pub const MODULUS_SETTING_RANGE: (f64, f64) = (1e3, 1e12);

/// `value` of `key` within [`MODULUS_SETTING_RANGE`].
pub(super) fn modulus(key: &str, value: f64) -> Result<f64, FitError> {
    let value = positive(key, value)?;
    let (lo, hi) = MODULUS_SETTING_RANGE;
    if (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(FitError::setting(
            key,
            format!(
                "{value:e} Pa must lie between {lo:e} and {hi:e} Pa (a decade below the softest \
                 rubber, and diamond's modulus): is it in Pa?"
            ),
        ))
    }
}

/// The scale anchor as a known |E| at one frequency, which must lie below
/// E1_max.
pub(super) fn reduce_anchor(
    anchor: ScaleAnchor,
    setup: &RollingSetup,
    e1_max: f64,
) -> Result<ModulusAnchor, FitError> {
    let a = match anchor {
        ScaleAnchor::StaticModulus(e0) => {
            let e0 = modulus("E0", e0)?;
            ModulusAnchor {
                omega: 0.0,
                modulus: e0,
                source: "E0",
            }
        }
        ScaleAnchor::ModulusAt { omega, modulus } => ModulusAnchor {
            omega: positive("E_at.omega", omega)?,
            modulus: self::modulus("E_at.E", modulus)?,
            source: "E_at",
        },
        ScaleAnchor::ContactRadius { speed, radius } => contact_anchor(speed, radius, setup)?,
    };
    // A contact radius implies a modulus through Hertz: the same range.
    modulus(a.source, a.modulus)?;
    if a.modulus >= e1_max {
        return Err(FitError::setting(
            a.source,
            format!(
                "the anchored modulus {:e} Pa is not below E1_max = {e1_max:e} Pa",
                a.modulus
            ),
        ));
    }
    Ok(a)
}

/// |E| from a contact radius `radius` measured at rolling speed `speed`:
/// Hertz inverted for |E_eff|.
fn contact_anchor(
    speed: f64,
    radius: f64,
    setup: &RollingSetup,
) -> Result<ModulusAnchor, FitError> {
    let speed = positive("contact_radius.v", speed)?;
    let radius = positive("contact_radius.r", radius)?;
    let g = setup.geometry;
    if radius >= g.radius {
        return Err(FitError::setting(
            "contact_radius.r",
            format!(
                "{radius} m is not smaller than the body's radius {} m: \
                 Hertz contact does not apply",
                g.radius
            ),
        ));
    }
    let nu = setup.substrate.poisson;
    let plane_strain = 1.0 - nu * nu;
    // Invert Hertz for |E_eff| at the contact's own frequency
    // ω = v/r (the centre of the band v/r … 20 v/r it probes).
    let e_eff = match g.shape {
        Shape::Sphere => 0.75 * g.load * g.radius / radius.powi(3),
        Shape::Cylinder => 4.0 * g.load * g.radius / (PI * radius * radius),
    };
    let omega = match setup.contact {
        ContactSize::Dynamic => speed / radius,
        ContactSize::Static => 0.0,
    };
    Ok(ModulusAnchor {
        omega,
        modulus: e_eff * plane_strain,
        source: "contact_radius",
    })
}
