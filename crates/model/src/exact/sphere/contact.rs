//! The unilateral contact problem on the grid: which cells touch, their
//! pressures and the approach, for a prescribed load.
//!
//! In units of the reference contact radius r (lengths), r²/R
//! (displacements) and r/(R J) (pressures, J the reference compliance),
//! the discrete problem is: find the contact set 𝒜, pressures p ≥ 0 and
//! the approach δ with
//!
//!   (A p)_i = δ − (x_i² + y_i²)/2   for i ∈ 𝒜,   p_i = 0 outside,
//!   h² Σ p_i = F,
//!   g_i = (A p)_i − δ + (x_i² + y_i²)/2 ≥ 0 outside 𝒜,
//!
//! x measured from the sphere's axis. For a fixed 𝒜 this is one linear
//! system, bordered by the load row, solved by GMRES (A is not symmetric).
//! The set is then corrected — cells with p < 0 leave, cells that
//! penetrate (g < 0) join — and the system solved again from the previous
//! pressures, until the set stops changing (a primal–dual active-set
//! iteration, which for contact problems converges in a few steps from a
//! good start).
//!
//! # References
//! - M. Hintermüller, K. Ito, K. Kunisch, "The primal-dual active set
//!   strategy as a semismooth Newton method", SIAM J. Optim. 13 (2003)
//!   865–888.
//! - I.A. Polonsky, L.M. Keer, "A numerical method for solving rough contact
//!   problems based on the multi-level multi-summation and conjugate
//!   gradient techniques", Wear 231 (1999) 206–219 (the same problem with a
//!   symmetric operator).

use super::convolution::Convolution;
use super::gmres::gmres;
use crate::error::ModelError;

/// The grid, in units of the reference contact radius.
pub(crate) struct Grid {
    /// Cells along x and y.
    pub nx: usize,
    pub ny: usize,
    /// Cell side.
    pub h: f64,
    /// x of the first cell centre (from the axis).
    pub x0: f64,
    /// y of the first cell centre.
    pub y0: f64,
}

impl Grid {
    /// Centre of cell k = j·nx + i.
    pub fn centre(&self, k: usize) -> (f64, f64) {
        let (i, j) = (k % self.nx, k / self.nx);
        (self.x0 + i as f64 * self.h, self.y0 + j as f64 * self.h)
    }

    /// Whether cell k lies on the grid's border.
    fn on_border(&self, k: usize) -> bool {
        let (i, j) = (k % self.nx, k / self.nx);
        i == 0 || j == 0 || i + 1 == self.nx || j + 1 == self.ny
    }
}

/// The solved contact on the grid.
pub(crate) struct GridContact {
    /// Pressure of each cell (zero outside the contact).
    pub pressure: Vec<f64>,
    /// Approach δ.
    pub approach: f64,
    /// Active-set iterations.
    pub iterations: usize,
    /// Operator applications in all.
    pub applications: usize,
}

/// Why a grid solve did not give a contact.
pub(crate) enum GridFailure {
    /// The contact reached the grid's border: a larger grid is needed.
    TooSmall,
    /// A model error (no convergence).
    Model(ModelError),
}

/// Relative residual of the final linear solve.
const KRYLOV_TOLERANCE: f64 = 1e-11;
/// Relative residual while the contact set is still changing: the set only
/// needs the signs of p and g, and each solve starts from the last.
const LOOSE_TOLERANCE: f64 = 1e-6;
/// Active-set corrections allowed before giving up.
const MAX_SET_ITERATIONS: usize = 80;

/// Solves the contact for load `load` on `grid` with operator `operator`,
/// starting from the set `start` (cells flagged true) and pressures
/// `guess`.
pub(crate) fn solve_contact(
    grid: &Grid,
    operator: &Convolution,
    load: f64,
    start: Vec<bool>,
    guess: &[f64],
    speed: f64,
) -> Result<GridContact, GridFailure> {
    let cells = grid.nx * grid.ny;
    let profile: Vec<f64> = (0..cells)
        .map(|k| {
            let (x, y) = grid.centre(k);
            0.5 * (x * x + y * y)
        })
        .collect();
    let h2 = grid.h * grid.h;
    let mut active = start;
    let mut pressure = guess.to_vec();
    let mut approach = 0.0;
    let mut applications = 0;
    let mut full = vec![0.0; cells];
    let mut u = vec![0.0; cells];
    let mut tolerance = LOOSE_TOLERANCE;
    for iteration in 1..=MAX_SET_ITERATIONS {
        let index: Vec<usize> = (0..cells).filter(|&k| active[k]).collect();
        if index.is_empty() {
            return Err(GridFailure::Model(ModelError::ExactSphereNotConverged {
                speed,
            }));
        }
        let n = index.len();
        let mut z: Vec<f64> = index.iter().map(|&k| pressure[k].max(0.0)).collect();
        z.push(approach);
        let mut rhs: Vec<f64> = index.iter().map(|&k| -profile[k]).collect();
        rhs.push(load);
        let mut apply = |z: &[f64], out: &mut [f64]| {
            full.iter_mut().for_each(|v| *v = 0.0);
            for (&k, &p) in index.iter().zip(z) {
                full[k] = p;
            }
            operator.apply(&full, &mut u);
            for (o, &k) in out.iter_mut().zip(&index) {
                *o = u[k] - z[n];
            }
            out[n] = h2 * z[..n].iter().sum::<f64>();
        };
        let outcome = gmres(&mut apply, &rhs, &mut z, 80, tolerance, 20_000);
        applications += outcome.applications;
        if outcome.relative_residual > 1e3 * tolerance {
            return Err(GridFailure::Model(ModelError::ExactSphereNotConverged {
                speed,
            }));
        }
        pressure.iter_mut().for_each(|v| *v = 0.0);
        for (&k, &p) in index.iter().zip(&z) {
            pressure[k] = p;
        }
        approach = z[n];
        operator.apply(&pressure, &mut u);
        // Cells in the set stay while pressed; others join where the
        // surface would penetrate the sphere (gap u − δ + profile < 0).
        let next: Vec<bool> = (0..cells)
            .map(|k| {
                if active[k] {
                    pressure[k] > 0.0
                } else {
                    u[k] - approach + profile[k] < 0.0
                }
            })
            .collect();
        if next == active && tolerance > KRYLOV_TOLERANCE {
            // The set has settled: solve once more to full accuracy and
            // check it again.
            tolerance = KRYLOV_TOLERANCE;
            continue;
        }
        if next == active {
            if (0..cells).any(|k| active[k] && grid.on_border(k)) {
                return Err(GridFailure::TooSmall);
            }
            return Ok(GridContact {
                pressure,
                approach,
                iterations: iteration,
                applications,
            });
        }
        active = next;
    }
    Err(GridFailure::Model(ModelError::ExactSphereNotConverged {
        speed,
    }))
}
