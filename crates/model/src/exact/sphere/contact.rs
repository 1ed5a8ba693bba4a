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
//! good start). The plane-strain strip ([`super::element`]) is the same
//! problem on one row (y = 0): h Σ p_i = W per unit length, pressures in
//! units of a/(R J), a the reference half-width. The gap that decides the
//! joins is that of the pressures
//! with their negative part removed, g⁺ = A max(p, 0) − δ + profile: with
//! a long memory a cell pulled (p < 0) lifts the whole strip of surface
//! behind it, which would otherwise pull in the next cell behind, and so
//! on — a front of spurious joins walking toward the trailing side one
//! cell per iteration (seen at E1/E0 = 100, vτ/r0 ≲ 0.01).
//!
//! A is not a P-matrix (it is not symmetric, and its memory part is
//! nearly a one-sided integration along x), so the discrete
//! complementarity problem need not have a solution, and the iteration
//! can cycle — in practice at cells of the contact's edge that the grid
//! cannot resolve, such as the glassy layer at the leading edge, whose
//! width vτ_relax can be far below a cell. Cycles are detected, the
//! iteration is bounded, and an unsettled solve returns the iterate with
//! the least complementarity defect, together with the defect's share of
//! μ (see [`defect`]), which the caller adds to the error estimate.
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
use super::element::Element;
use super::gmres::gmres;

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
    /// The boundary element (square cell, or strip with ny = 1).
    pub element: Element,
}

impl Grid {
    /// Centre of cell k = j·nx + i.
    pub fn centre(&self, k: usize) -> (f64, f64) {
        let (i, j) = (k % self.nx, k / self.nx);
        (self.x0 + i as f64 * self.h, self.y0 + j as f64 * self.h)
    }

    /// Whether cell k lies on the grid's border (a strip grid's one row
    /// has its border at its ends only).
    fn on_border(&self, k: usize) -> bool {
        let (i, j) = (k % self.nx, k / self.nx);
        let row_end = self.element != Element::Strip && (j == 0 || j + 1 == self.ny);
        i == 0 || i + 1 == self.nx || row_end
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
    /// Relative error of μ the complementarity defect may cause: 0 when
    /// the set settled, else [`defect`] of the returned iterate.
    pub defect: f64,
}

/// Why a grid solve did not give a contact.
pub(crate) enum GridFailure {
    /// The contact reached the grid's border: a larger grid is needed.
    TooSmall,
    /// A linear solve failed or no contact was left.
    NotConverged,
}

/// Relative residual of the final linear solve.
const KRYLOV_TOLERANCE: f64 = 1e-11;
/// Relative residual while the contact set is still changing: the set only
/// needs the signs of p and g, and each solve starts from the last.
const LOOSE_TOLERANCE: f64 = 1e-6;

/// Solves the contact for load `load` on `grid` with operator `operator`,
/// starting from the set `start` (cells flagged true) and pressures
/// `guess`, within `max_iterations` set corrections.
///
/// A set met twice is a cycle of the iteration. Met while the systems are
/// solved loosely, the signs that moved the set may be noise of the loose
/// solve: the tolerance is tightened and the iteration goes on. Met with
/// tight solves, it is a true cycle: the iteration stops, as it does when
/// the budget is spent, and the iterate of least defect is returned with
/// its defect.
pub(crate) fn solve_contact(
    grid: &Grid,
    operator: &Convolution,
    load: f64,
    start: Vec<bool>,
    guess: &[f64],
    max_iterations: usize,
) -> Result<GridContact, GridFailure> {
    let cells = grid.nx * grid.ny;
    let profile: Vec<f64> = (0..cells)
        .map(|k| {
            let (x, y) = grid.centre(k);
            0.5 * (x * x + y * y)
        })
        .collect();
    let diagonal = self_influence(grid, operator);
    let mut active = start;
    let mut pressure = guess.to_vec();
    let mut approach = 0.0;
    let mut applications = 0;
    let mut u = vec![0.0; cells];
    let mut tolerance = LOOSE_TOLERANCE;
    let mut seen = std::collections::HashSet::new();
    let mut best: Option<GridContact> = None;
    for iteration in 1..=max_iterations {
        let (used, ok) = solve_on_set(
            grid,
            operator,
            load,
            &profile,
            &active,
            (&mut pressure, &mut approach),
            tolerance,
        )?;
        applications += used;
        if !ok {
            return Err(GridFailure::NotConverged);
        }
        let clipped: Vec<f64> = pressure.iter().map(|p| p.max(0.0)).collect();
        operator.apply(&clipped, &mut u);
        let gap: Vec<f64> = (0..cells).map(|k| u[k] - approach + profile[k]).collect();
        // Cells in the set stay unless pulled (p < 0; p = 0 satisfies
        // complementarity); others join where the surface would penetrate
        // the sphere (g⁺ < 0).
        let next: Vec<bool> = (0..cells)
            .map(|k| {
                if active[k] {
                    pressure[k] >= 0.0
                } else {
                    gap[k] < 0.0
                }
            })
            .collect();
        let settled = next == active;
        if settled && tolerance > KRYLOV_TOLERANCE {
            // Solve once more to full accuracy and check the set again.
            tolerance = KRYLOV_TOLERANCE;
            continue;
        }
        let share = if settled {
            0.0
        } else {
            defect(grid, &pressure, &gap, &active, diagonal)
        };
        if settled || best.as_ref().is_none_or(|b| share < b.defect) {
            if (0..cells).any(|k| active[k] && grid.on_border(k)) {
                return Err(GridFailure::TooSmall);
            }
            best = Some(GridContact {
                pressure: clipped,
                approach,
                iterations: iteration,
                applications,
                defect: share,
            });
        }
        if settled {
            break;
        }
        if !seen.insert((tolerance.to_bits(), fingerprint(&next))) {
            if tolerance > KRYLOV_TOLERANCE {
                tolerance = KRYLOV_TOLERANCE;
            } else {
                break;
            }
        }
        active = next;
    }
    let mut result = best.ok_or(GridFailure::NotConverged)?;
    result.applications = applications;
    Ok(result)
}

/// Solves the bordered system of the set `active` by GMRES from the
/// current pressures and approach, which it overwrites; returns the
/// operator applications and whether the solve reached its tolerance.
fn solve_on_set(
    grid: &Grid,
    operator: &Convolution,
    load: f64,
    profile: &[f64],
    active: &[bool],
    (pressure, approach): (&mut [f64], &mut f64),
    tolerance: f64,
) -> Result<(usize, bool), GridFailure> {
    let cells = active.len();
    let measure = grid.element.measure(grid.h);
    let index: Vec<usize> = (0..cells).filter(|&k| active[k]).collect();
    if index.is_empty() {
        return Err(GridFailure::NotConverged);
    }
    let n = index.len();
    let mut z: Vec<f64> = index.iter().map(|&k| pressure[k].max(0.0)).collect();
    z.push(*approach);
    let mut rhs: Vec<f64> = index.iter().map(|&k| -profile[k]).collect();
    rhs.push(load);
    let mut full = vec![0.0; cells];
    let mut u = vec![0.0; cells];
    let mut apply = |z: &[f64], out: &mut [f64]| {
        full.iter_mut().for_each(|v| *v = 0.0);
        for (&k, &p) in index.iter().zip(z) {
            full[k] = p;
        }
        operator.apply(&full, &mut u);
        for (o, &k) in out.iter_mut().zip(&index) {
            *o = u[k] - z[n];
        }
        out[n] = measure * z[..n].iter().sum::<f64>();
    };
    let outcome = gmres(&mut apply, &rhs, &mut z, 80, tolerance, 20_000);
    pressure.iter_mut().for_each(|v| *v = 0.0);
    for (&k, &p) in index.iter().zip(&z) {
        pressure[k] = p;
    }
    *approach = z[n];
    Ok((
        outcome.applications,
        outcome.relative_residual <= 1e3 * tolerance,
    ))
}

/// The influence of a cell's pressure on its own displacement (the same
/// for every cell: the operator is a convolution).
fn self_influence(grid: &Grid, operator: &Convolution) -> f64 {
    let cells = grid.nx * grid.ny;
    let centre = (grid.ny / 2) * grid.nx + grid.nx / 2;
    let mut unit = vec![0.0; cells];
    unit[centre] = 1.0;
    let mut u = vec![0.0; cells];
    operator.apply(&unit, &mut u);
    u[centre]
}

/// The relative error of μ = x̄/R that the complementarity defect of an
/// iterate may cause: the pressure changes that would remove it — −p at
/// pulled cells of the set, −g/a at penetrating cells outside it (the
/// pressure that presses a cell back to the sphere by its own
/// influence a) — each moving the centroid by δp (x − x̄)/Σp, summed in
/// absolute value and divided by |x̄|:
///
///   d = Σ |δp_k| |x_k − x̄| / (|x̄| Σ p).
fn defect(grid: &Grid, pressure: &[f64], gap: &[f64], active: &[bool], diagonal: f64) -> f64 {
    let positive = |k: usize| pressure[k].max(0.0);
    let total: f64 = (0..pressure.len()).map(positive).sum();
    let moment: f64 = (0..pressure.len())
        .map(|k| positive(k) * grid.centre(k).0)
        .sum();
    let centroid = moment / total;
    let shift: f64 = (0..pressure.len())
        .map(|k| {
            let change = if active[k] {
                (-pressure[k]).max(0.0)
            } else {
                (-gap[k]).max(0.0) / diagonal
            };
            change * (grid.centre(k).0 - centroid).abs()
        })
        .sum();
    shift / (total * centroid.abs())
}

/// A hash of a contact set (collisions only make a cycle be declared a
/// step early or late).
fn fingerprint(set: &[bool]) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    set.hash(&mut hasher);
    hasher.finish()
}
