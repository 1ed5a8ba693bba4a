//! The steady rolling contact: Gauss–Chebyshev collocation with unknown
//! edges (see the module documentation of [`super`]).

use std::f64::consts::PI;

use super::creep::CreepCompliance;
use super::kernel::{CollocationGrid, MemoryQuadrature};
use crate::error::ModelError;

/// The collocation system at given edges: the coefficients α_n of the
/// pressure, and the consistency residual (the tilt c0 the surface would
/// need for a pressure bounded at both edges) and the load residual.
pub(crate) struct Collocation {
    pub(crate) alpha: Vec<f64>,
    pub(crate) tilt: f64,
    pub(crate) load_error: f64,
}

/// The LU factors of a dense n × n matrix (row-major; L below the
/// diagonal with unit diagonal, U on and above) and the row swaps of
/// partial pivoting.
pub(crate) struct Factors {
    lu: Vec<f64>,
    pivots: Vec<usize>,
    n: usize,
}

impl Factors {
    /// Gaussian elimination with partial pivoting; `None` if singular.
    pub(crate) fn new(mut a: Vec<f64>, n: usize) -> Option<Self> {
        let mut pivots = Vec::with_capacity(n);
        for col in 0..n {
            let pivot =
                (col..n).max_by(|&i, &j| a[i * n + col].abs().total_cmp(&a[j * n + col].abs()))?;
            if a[pivot * n + col] == 0.0 {
                return None;
            }
            if pivot != col {
                for k in 0..n {
                    a.swap(pivot * n + k, col * n + k);
                }
            }
            pivots.push(pivot);
            let d = a[col * n + col];
            // Rows below the pivot row, as slices (the loop vectorises).
            let (top, bottom) = a.split_at_mut((col + 1) * n);
            let pivot_row = &top[col * n + col + 1..(col + 1) * n];
            for row in bottom.chunks_exact_mut(n) {
                let f = row[col] / d;
                row[col] = f;
                if f != 0.0 {
                    row[col + 1..]
                        .iter_mut()
                        .zip(pivot_row)
                        .for_each(|(x, p)| *x -= f * p);
                }
            }
        }
        Some(Factors { lu: a, pivots, n })
    }

    /// The solution x of a x = rhs.
    pub(crate) fn solve(&self, mut rhs: Vec<f64>) -> Vec<f64> {
        let (a, n) = (&self.lu, self.n);
        // The swaps moved whole rows, multipliers included: apply them all
        // before the forward substitution.
        for (col, &pivot) in self.pivots.iter().enumerate() {
            rhs.swap(pivot, col);
        }
        for col in 0..n {
            for row in col + 1..n {
                rhs[row] -= a[row * n + col] * rhs[col];
            }
        }
        for row in (0..n).rev() {
            let mut s = rhs[row];
            for k in row + 1..n {
                s -= a[row * n + k] * rhs[k];
            }
            rhs[row] = s / a[row * n + row];
        }
        rhs
    }
}

/// The collocation system at half-width b, factorised. The centre c enters
/// only the right-hand side (the memory integrals depend on b/v alone), so
/// one factorisation serves every c, Newton's c-derivative included.
struct System<'a> {
    grid: &'a CollocationGrid,
    factors: Factors,
    b: f64,
    radius: f64,
    load: f64,
}

impl System<'_> {
    /// The pressure coefficients and residuals for centre `c` (m).
    fn collocate(&self, c: f64) -> Collocation {
        let (b, radius) = (self.b, self.radius);
        let rhs: Vec<f64> = self
            .grid
            .points()
            .iter()
            .map(|&t| (c + b * t) / (2.0 * b * radius))
            .collect();
        let x = self.factors.solve(rhs);
        let n = x.len() - 1;
        let alpha = x[..n].to_vec();
        let tilt = 2.0 * radius * x[n];
        let load_error = PI * b * b * alpha[0] / (2.0 * self.load) - 1.0;
        Collocation {
            alpha,
            tilt,
            load_error,
        }
    }
}

/// Builds and factorises the collocation system for half-width `b` (m): N
/// basis functions, N + 1 collocation points at the zeros of T_{N+1}, and
/// the tilt c0 as the (N+1)-th unknown; `memory` is the memory part of the
/// matrix ([k·N + n], see [`CollocationGrid::memory_matrix`]).
fn system<'a>(
    grid: &'a CollocationGrid,
    instantaneous: f64,
    memory: &[f64],
    radius: f64,
    load: f64,
    b: f64,
) -> Option<System<'a>> {
    let points = grid.points();
    let m = points.len();
    let n = m - 1;
    let mut a = vec![0.0; m * m];
    // Instantaneous part J0 T_{n+1}(t_k), the memory, and the tilt column.
    for (k, &t) in points.iter().enumerate() {
        let (mut prev, mut cur) = (1.0, t);
        for col in 0..n {
            a[k * m + col] = instantaneous * cur + memory[k * n + col];
            let next = 2.0 * t * cur - prev;
            prev = cur;
            cur = next;
        }
        a[k * m + n] = 1.0;
    }
    Some(System {
        grid,
        factors: Factors::new(a, m)?,
        b,
        radius,
        load,
    })
}

/// Newton's method on (c, b) for tilt = 0 and the load; returns
/// (c, b, collocation, iterations).
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve_edges(
    compliance: &CreepCompliance,
    quadrature: &MemoryQuadrature,
    speed: f64,
    radius: f64,
    load: f64,
    terms: usize,
    b_guess: f64,
    tolerance: f64,
) -> Result<(f64, f64, Collocation, usize), ModelError> {
    let grid = CollocationGrid::new(terms);
    let memory = |b: f64| grid.memory_matrix(quadrature, compliance, b / speed);
    solve_edges_with(
        &grid,
        compliance.instantaneous,
        &memory,
        speed,
        radius,
        load,
        b_guess,
        tolerance,
    )
}

/// As [`solve_edges`] with the memory part of the matrix at half-width b
/// from `memory(b)`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve_edges_with(
    grid: &CollocationGrid,
    instantaneous: f64,
    memory: &dyn Fn(f64) -> Vec<f64>,
    speed: f64,
    radius: f64,
    load: f64,
    b_guess: f64,
    tolerance: f64,
) -> Result<(f64, f64, Collocation, usize), ModelError> {
    let build = |b: f64| -> Result<System, ModelError> {
        system(grid, instantaneous, &memory(b), radius, load, b)
            .ok_or(ModelError::ExactSingularSystem { speed })
    };
    let (mut c, mut b) = (0.0, b_guess);
    let mut at_b = build(b)?;
    let mut current = at_b.collocate(c);
    for iteration in 1..=60 {
        let h = 1e-7 * b;
        let dc = at_b.collocate(c + h);
        let db = build(b + h)?.collocate(c);
        let j11 = (dc.tilt - current.tilt) / h;
        let j21 = (dc.load_error - current.load_error) / h;
        let j12 = (db.tilt - current.tilt) / h;
        let j22 = (db.load_error - current.load_error) / h;
        let det = j11 * j22 - j12 * j21;
        if !(det.is_finite() && det != 0.0) {
            break;
        }
        let step_c = -(j22 * current.tilt - j12 * current.load_error) / det;
        let mut step_b = -(-j21 * current.tilt + j11 * current.load_error) / det;
        let mut step_c = step_c;
        // Keep the half-width positive and the step moderate.
        let limit = 0.5 * b;
        let scale = (step_c.abs().max(step_b.abs()) / limit).max(1.0);
        step_c /= scale;
        step_b /= scale;
        c += step_c;
        b += step_b;
        at_b = build(b)?;
        current = at_b.collocate(c);
        if step_c.abs().max(step_b.abs()) <= tolerance * b {
            return Ok((c, b, current, iteration));
        }
    }
    Err(ModelError::ExactEdgesNotConverged { speed })
}
