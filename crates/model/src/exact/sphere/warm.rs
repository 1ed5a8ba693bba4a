//! Warm starts of the exact sphere: a fit's defect correction
//! solves the same speeds again and again for a modulus that changes a
//! little from one refit to the next (the correction r by 1e-3 … 1e-5), so
//! each grid's active-set iteration is started from the contact set and
//! pressures where the last solve at that speed ended on the same grid,
//! rather than from the next coarser grid (or, for the coarsest, from
//! Hertz and perhaps a continuation in the speed).
//!
//! The answer does not move with the start where the discrete contact
//! problem has one solution: the iteration stops only when the set is
//! settled and the system on it is solved to the final Krylov tolerance,
//! and the grid (its cells and extent) is chosen as in the cold solve —
//! the coarsest from the first extent, each finer from its coarser one's,
//! each enlarged while the contact reaches its border. A warm solve that
//! does not settle (a cycling set, where the cold solve would keep the
//! least-defect iterate or continue from higher speeds) or fails is done
//! again cold, so the answer there is the cold one.

use crate::error::{ModelError, require_positive};

use super::{RollingSphere, SphereSolution};

/// The grid solutions of one speed, to start the next solve at that speed
/// from ([`RollingSphere::solve_from`]).
#[derive(Debug, Clone)]
pub struct SphereStart {
    /// (cells across the contact diameter, the solution on that grid).
    grids: Vec<(usize, SphereSolution)>,
}

impl SphereStart {
    /// The solution on the grid of `cells`, if one was kept.
    fn on(&self, cells: usize) -> Option<&SphereSolution> {
        self.grids.iter().find(|(c, _)| *c == cells).map(|(_, g)| g)
    }
}

/// The extent (in units of the scale, along x and y) the cold solve
/// starts the coarsest grid at.
const FIRST_EXTENT: (f64, f64) = (1.35, 1.2);

type GridSolve = Result<(SphereSolution, (f64, f64)), ModelError>;

impl RollingSphere {
    /// [`Self::solve`], each grid started from `start`'s solution on a grid
    /// of the same cells where it has one (a solve at the same speed for a
    /// nearby modulus, possibly at another accuracy: the 96- and 64-cell
    /// grids of accuracy 1e-3 are the two coarser of 1e-4), and where this
    /// solve ended. See the module doc for why the answer is the cold one.
    pub fn solve_from(
        &self,
        v: f64,
        start: Option<&SphereStart>,
    ) -> Result<(SphereSolution, SphereStart), ModelError> {
        require_positive("v", v)?;
        let [n1, n2, n3] = self.grid_cells();
        let scale = self.expected_radius(v);
        let earlier = |cells: usize| start.and_then(|s| s.on(cells));
        let (g3, extent) = self.warm_or_cold(v, scale, n3, FIRST_EXTENT, earlier(n3), || {
            self.solve_continued(v, n3, 0)
        })?;
        let (g2, extent) = self.warm_or_cold(v, scale, n2, extent, earlier(n2), || {
            self.solve_growing(v, scale, n2, extent, Some(&g3))
        })?;
        let (g1, _) = self.warm_or_cold(v, scale, n1, extent, earlier(n1), || {
            self.solve_growing(v, scale, n1, extent, Some(&g2))
        })?;
        let end = SphereStart {
            grids: vec![(n1, g1.clone()), (n2, g2.clone()), (n3, g3.clone())],
        };
        Ok((self.extrapolated(v, scale, [g1, g2, g3]), end))
    }

    /// The grid of `cells` from `extent` on, started from `previous` (the
    /// same grid's solution for a nearby modulus) where given and kept if
    /// its set settled; otherwise `cold`.
    fn warm_or_cold(
        &self,
        v: f64,
        scale: f64,
        cells: usize,
        extent: (f64, f64),
        previous: Option<&SphereSolution>,
        cold: impl FnOnce() -> GridSolve,
    ) -> GridSolve {
        if let Some(previous) = previous
            && let Ok(warm) = self.solve_growing(v, scale, cells, extent, Some(previous))
            && warm.0.set_defect == 0.0
        {
            return Ok(warm);
        }
        cold()
    }
}
