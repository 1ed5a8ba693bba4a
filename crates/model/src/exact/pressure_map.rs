//! The pressure map of an exact steady rolling solution at one speed: the
//! pressure under the body and the outline of the contact, in the same form
//! for the cylinder and the sphere, so that `rollfit forward` can write and
//! draw it without knowing which body rolls ([`super::ExactRolling::pressure_map`]).
//!
//! Coordinates are those of the solutions: x from the body's axis, positive
//! in the rolling direction (the leading side), y across it (sphere only),
//! both in m; pressures in Pa.

use std::f64::consts::PI;

use super::{RollingSolution, SphereSolution};

/// Points of the cylinder's pressure profile: enough to draw the square-root
/// edges and the leading edge layer at the cylinder's default resolution
/// (the spacing next to an edge is about 2e-5 of the contact width).
pub const CYLINDER_PROFILE_POINTS: usize = 401;

/// The exact steady rolling contact at one speed, for writing and drawing.
#[derive(Debug, Clone, PartialEq)]
pub struct PressureMap {
    /// Rolling speed v, m/s.
    pub speed: f64,
    /// Friction coefficient μ = x̄/R of the same solution (the value
    /// [`super::ExactRolling::exact_friction`] gives at this speed).
    pub mu: f64,
    /// Estimated relative error of μ from the discretisation.
    pub error_estimate: f64,
    /// The Hertz contact size with the static modulus, m: radius r0 of the
    /// sphere, half-width a0 of the cylinder (the comparison the picture
    /// draws dashed, and its length unit).
    pub static_contact_size: f64,
    /// The load the contact carries: for the cylinder the prescribed f_N,
    /// N/m; for the sphere h² Σ p over the cells, N (the prescribed F to
    /// the tolerance of the solver, which holds the load as one of its
    /// equations).
    pub load: f64,
    /// The pressure and the outline.
    pub pressure: ContactPressure,
}

/// The pressure under the body and the outline of the contact.
#[derive(Debug, Clone, PartialEq)]
pub enum ContactPressure {
    /// The sphere: the boundary-element solution, a constant pressure on
    /// each square cell; h² Σ p = F (the load) up to rounding. These are
    /// the finer grid's pressures, while μ is extrapolated from two grids:
    /// the map's centroid differs from μR by the extrapolation step (about
    /// `error_estimate` relative).
    Cells {
        /// Cell side h, m.
        cell: f64,
        /// The cells in contact (p > 0): centre x, y (m) and pressure p (Pa).
        cells: Vec<(f64, f64, f64)>,
        /// Per row of cells in contact, in increasing y: y (m, the row's
        /// centre), the trailing edge x (m, where p² extrapolated from the
        /// row's last two cells vanishes) and the leading edge x (m).
        outline: Vec<(f64, f64, f64)>,
    },
    /// The cylinder (plane strain): p(x), the same at every y.
    Profile {
        /// (x, p) from the trailing to the leading edge, x in m, p in Pa,
        /// on Chebyshev–Lobatto points x = c − b cos(kπ/n), which crowd
        /// toward the square-root edges and the leading edge layer; p = 0
        /// at both ends.
        points: Vec<(f64, f64)>,
        /// Trailing edge a1, m (< 0).
        trailing_edge: f64,
        /// Leading edge a2, m (> 0).
        leading_edge: f64,
    },
}

impl PressureMap {
    /// The sphere's map from its solution; `static_radius` r0 (m).
    pub fn of_sphere(solution: &SphereSolution, static_radius: f64) -> Self {
        let mut outline = solution.outline.clone();
        outline.sort_by(|a, b| a.0.total_cmp(&b.0));
        let h2 = solution.cell * solution.cell;
        let load = h2 * solution.pressure_map.iter().map(|c| c.2).sum::<f64>();
        PressureMap {
            speed: solution.speed,
            mu: solution.mu,
            error_estimate: solution.error_estimate,
            static_contact_size: static_radius,
            load,
            pressure: ContactPressure::Cells {
                cell: solution.cell,
                cells: solution.pressure_map.clone(),
                outline,
            },
        }
    }

    /// The cylinder's map from its solution; `static_half_width` a0 (m),
    /// `load` f_N (N/m).
    pub fn of_cylinder(solution: &RollingSolution, static_half_width: f64, load: f64) -> Self {
        let (c, b) = (solution.center(), solution.half_width());
        let n = CYLINDER_PROFILE_POINTS - 1;
        let points = (0..=n)
            .map(|k| {
                if k == 0 {
                    (solution.trailing_edge, 0.0)
                } else if k == n {
                    (solution.leading_edge, 0.0)
                } else {
                    let x = c - b * (PI * k as f64 / n as f64).cos();
                    // The series may dip a rounding error below zero at an
                    // edge; a contact pressure is never tensile.
                    (x, solution.pressure(x).max(0.0))
                }
            })
            .collect();
        PressureMap {
            speed: solution.speed,
            mu: solution.mu,
            error_estimate: solution.error_estimate,
            static_contact_size: static_half_width,
            load,
            pressure: ContactPressure::Profile {
                points,
                trailing_edge: solution.trailing_edge,
                leading_edge: solution.leading_edge,
            },
        }
    }

    /// The peak pressure of the static Hertz contact, Pa: 3F/(2π r0²) for
    /// the sphere, 2f_N/(π a0) for the cylinder (the pressure unit of the
    /// picture).
    pub fn static_peak_pressure(&self) -> f64 {
        let size = self.static_contact_size;
        match self.pressure {
            ContactPressure::Cells { .. } => 1.5 * self.load / (PI * size * size),
            ContactPressure::Profile { .. } => 2.0 * self.load / (PI * size),
        }
    }

    /// The outline as (y, x_trailing, x_leading) rows, m: the sphere's per
    /// row of cells; for the cylinder one row at y = 0 (its edges are the
    /// same at every y).
    pub fn outline(&self) -> Vec<(f64, f64, f64)> {
        match &self.pressure {
            ContactPressure::Cells { outline, .. } => outline.clone(),
            ContactPressure::Profile {
                trailing_edge,
                leading_edge,
                ..
            } => vec![(0.0, *trailing_edge, *leading_edge)],
        }
    }

    /// The largest pressure of the map, Pa.
    pub fn max_pressure(&self) -> f64 {
        match &self.pressure {
            ContactPressure::Cells { cells, .. } => cells.iter().map(|c| c.2).fold(0.0, f64::max),
            ContactPressure::Profile { points, .. } => {
                points.iter().map(|p| p.1).fold(0.0, f64::max)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::StandardLinearSolid;
    use crate::exact::{ExactRolling, RollingCylinder, RollingSphere};

    /// The paper's Fig. 2 solid (E1/E0 = 10, τ = 1 s), ν = 0.
    fn prony() -> crate::Prony {
        StandardLinearSolid::new(1e6, 1e7, 1.0).unwrap().to_prony()
    }

    /// The cylinder's map is the solution exact_friction reports: the same
    /// μ and edges, a pressure that vanishes at the edges and integrates to
    /// the load (trapezoids on the Lobatto points: the square-root edges
    /// cost about 1e-4).
    #[test]
    fn cylinder_map_carries_the_load_between_its_edges() {
        let body = RollingCylinder::new(&prony(), 0.0, 0.01, 100.0).unwrap();
        let v = 3e-4;
        let map = body.pressure_map(v).unwrap();
        let friction = body.exact_friction(v).unwrap();
        assert_eq!(map.mu, friction.mu);
        let ContactPressure::Profile {
            points,
            trailing_edge,
            leading_edge,
        } = &map.pressure
        else {
            panic!("a cylinder has a profile");
        };
        assert_eq!(
            (*trailing_edge, *leading_edge),
            (friction.trailing_edge, friction.leading_edge)
        );
        assert_eq!(points.len(), CYLINDER_PROFILE_POINTS);
        assert_eq!(points[0], (*trailing_edge, 0.0));
        let integral: f64 = points
            .windows(2)
            .map(|w| 0.5 * (w[1].0 - w[0].0) * (w[0].1 + w[1].1))
            .sum();
        assert!((integral / 100.0 - 1.0).abs() < 1e-3, "∫p dx = {integral}");
        assert!(points.windows(2).all(|w| w[1].0 > w[0].0));
        assert_eq!(map.outline(), vec![(0.0, *trailing_edge, *leading_edge)]);
        assert!(map.max_pressure() > 0.5 * map.static_peak_pressure());
    }

    /// The sphere's map on a coarse grid: cells of side h whose pressures
    /// sum to the load, an outline row per row of cells, trailing < 0 <
    /// leading, and the μ of exact_friction.
    #[test]
    fn sphere_map_carries_the_load_inside_its_outline() {
        let body = RollingSphere::new(&prony(), 0.0, 0.01, 0.15)
            .unwrap()
            .with_cells(24);
        let v = 1e-3;
        let map = body.pressure_map(v).unwrap();
        assert_eq!(map.mu, body.exact_friction(v).unwrap().mu);
        let ContactPressure::Cells {
            cell,
            cells,
            outline,
        } = &map.pressure
        else {
            panic!("a sphere has cells");
        };
        let load = cell * cell * cells.iter().map(|c| c.2).sum::<f64>();
        assert!((load / 0.15 - 1.0).abs() < 1e-6, "h² Σ p = {load}");
        assert!(outline.windows(2).all(|w| w[1].0 > w[0].0));
        for &(y, trailing, leading) in outline {
            assert!(trailing < 0.0 && leading > 0.0, "row y = {y}");
        }
        for &(x, y, p) in cells {
            assert!(p > 0.0);
            let row = outline
                .iter()
                .find(|r| (r.0 - y).abs() < 0.5 * cell)
                .expect("every cell's row is in the outline");
            assert!(row.1 < x && x < row.2, "cell ({x}, {y}) outside its row");
        }
        let r0 = map.static_contact_size;
        assert!((0.5 * r0..2.0 * r0).contains(&(outline[outline.len() / 2].2)));
    }
}
