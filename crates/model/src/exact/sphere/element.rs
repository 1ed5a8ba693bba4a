//! The boundary element of the grid: a square cell of the sphere's contact
//! (three dimensions, Boussinesq kernel 1/ρ, [`super::cell`]) or a strip of
//! a cylinder's contact (plane strain, kernel −ln|x|, [`super::strip`]).
//!
//! Everything else — the memory recursion, the convolution, the contact
//! set, the load balance, the three grids and the extrapolation — is the
//! same code for both: the strip problem is the square-cell one on a grid
//! of one row (ny = 1), with the load balance h Σ p_i = W (load per unit
//! length) in place of h² Σ p_i = F. The strip exists so that the sphere's
//! machinery can be checked against the exact rolling cylinder
//! ([`super::super::RollingCylinder`], an independent method).
//!
//! # References
//! - K.L. Johnson, *Contact Mechanics*, Cambridge 1985, §2.2, §3.9, §4.2
//!   (Hertz: line contact p0 = 2W/(πa), point contact p0 = 3F/(2πr²)).

use crate::contact::Shape;

use super::cell::unit_cell_potential;
use super::strip::unit_strip_potential;

/// The boundary element.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Element {
    /// A square cell of side h: the sphere.
    Square,
    /// A strip of width h, infinitely long in y: the cylinder in plane
    /// strain.
    Strip,
}

impl Element {
    /// The body whose contact this element discretises (for the Hertz
    /// contact sizes).
    pub fn shape(self) -> Shape {
        match self {
            Element::Square => Shape::Sphere,
            Element::Strip => Shape::Cylinder,
        }
    }

    /// The displacement at offset (x, y) (element sides) under a unit
    /// pressure on the unit element, in units of the effective compliance
    /// and the side (the strip has y = 0 only).
    pub fn potential(self, x: f64, y: f64) -> f64 {
        match self {
            Element::Square => unit_cell_potential(x, y),
            Element::Strip => unit_strip_potential(x),
        }
    }

    /// The element's measure for side `h`: its area h² (m² for h in m), or
    /// for the strip its width h per unit length.
    pub fn measure(self, h: f64) -> f64 {
        match self {
            Element::Square => h * h,
            Element::Strip => h,
        }
    }

    /// The Hertz peak pressure of the load `load`, in units where the
    /// contact radius (half-width) is 1: 3F/(2π) for the sphere, 2W/π for
    /// the cylinder.
    pub fn hertz_peak(self, load: f64) -> f64 {
        match self {
            Element::Square => 1.5 * load / std::f64::consts::PI,
            Element::Strip => 2.0 * load / std::f64::consts::PI,
        }
    }
}
