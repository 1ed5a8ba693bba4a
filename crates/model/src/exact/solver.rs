//! The steady rolling contact: Gauss–Chebyshev collocation with unknown
//! edges (see the module documentation of [`super`]).

use std::f64::consts::PI;

use super::creep::CreepCompliance;
use super::kernel::MemoryQuadrature;
use crate::error::ModelError;

/// The collocation system at given edges: the coefficients α_n of the
/// pressure, and the consistency residual (the tilt c0 the surface would
/// need for a pressure bounded at both edges) and the load residual.
pub(crate) struct Collocation {
    pub(crate) alpha: Vec<f64>,
    pub(crate) tilt: f64,
    pub(crate) load_error: f64,
}

/// Solves the dense system `a x = rhs` (n × n, row-major) by Gaussian
/// elimination with partial pivoting; `None` if singular.
fn solve_dense(mut a: Vec<f64>, mut rhs: Vec<f64>, n: usize) -> Option<Vec<f64>> {
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
            rhs.swap(pivot, col);
        }
        let d = a[col * n + col];
        for row in col + 1..n {
            let f = a[row * n + col] / d;
            if f != 0.0 {
                for k in col..n {
                    a[row * n + k] -= f * a[col * n + k];
                }
                rhs[row] -= f * rhs[col];
            }
        }
    }
    for row in (0..n).rev() {
        let mut s = rhs[row];
        for k in row + 1..n {
            s -= a[row * n + k] * rhs[k];
        }
        rhs[row] = s / a[row * n + row];
    }
    Some(rhs)
}

/// Builds and solves the collocation system for centre `c` and half-width
/// `b` (m): N basis functions, N + 1 collocation points at the zeros of
/// T_{N+1}, and the tilt c0 as the (N+1)-th unknown.
#[allow(clippy::too_many_arguments)]
pub(crate) fn collocate(
    compliance: &CreepCompliance,
    quadrature: &MemoryQuadrature,
    speed: f64,
    radius: f64,
    load: f64,
    terms: usize,
    c: f64,
    b: f64,
) -> Option<Collocation> {
    let n = terms;
    let m = n + 1;
    let points: Vec<f64> = (0..m)
        .map(|k| (PI * (2 * k + 1) as f64 / (2 * m) as f64).cos())
        .collect();
    let mut a = vec![0.0; m * m];
    // Instantaneous part J0 T_{n+1}(t_k) and the tilt column.
    for (k, &t) in points.iter().enumerate() {
        let (mut prev, mut cur) = (1.0, t);
        for col in 0..n {
            a[k * m + col] = compliance.instantaneous * cur;
            let next = 2.0 * t * cur - prev;
            prev = cur;
            cur = next;
        }
        a[k * m + n] = 1.0;
    }
    // Memory terms.
    let mut outer = vec![0.0; n];
    let mut inner = vec![0.0; n];
    for (&cj, &lambda) in compliance
        .strengths
        .iter()
        .zip(&compliance.retardation_times)
    {
        let beta = b / (speed * lambda);
        quadrature.outer(beta, &mut outer);
        for (k, &t) in points.iter().enumerate() {
            quadrature.inner(beta, t, &mut inner);
            let e = (-beta * (1.0 - t)).exp();
            for col in 0..n {
                a[k * m + col] += cj * (inner[col] + e * outer[col]);
            }
        }
    }
    let rhs: Vec<f64> = points
        .iter()
        .map(|&t| (c + b * t) / (2.0 * b * radius))
        .collect();
    let x = solve_dense(a, rhs, m)?;
    let alpha = x[..n].to_vec();
    let tilt = 2.0 * radius * x[n];
    let load_error = PI * b * b * alpha[0] / (2.0 * load) - 1.0;
    Some(Collocation {
        alpha,
        tilt,
        load_error,
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
    let eval = |c: f64, b: f64| -> Result<Collocation, ModelError> {
        collocate(compliance, quadrature, speed, radius, load, terms, c, b).ok_or_else(|| {
            ModelError::Evaluation(format!(
                "exact rolling cylinder: singular collocation system at v = {speed} m/s"
            ))
        })
    };
    let (mut c, mut b) = (0.0, b_guess);
    let mut current = eval(c, b)?;
    for iteration in 1..=60 {
        let h = 1e-7 * b;
        let dc = eval(c + h, b)?;
        let db = eval(c, b + h)?;
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
        current = eval(c, b)?;
        if step_c.abs().max(step_b.abs()) <= tolerance * b {
            return Ok((c, b, current, iteration));
        }
    }
    Err(ModelError::Evaluation(format!(
        "exact rolling cylinder: the contact edges did not converge at v = {speed} m/s"
    )))
}
