//! Restarted GMRES for the non-symmetric contact systems of the exact
//! sphere.
//!
//! Written here because no maintained Rust crate offers a matrix-free
//! Krylov solver for an operator given as a closure (nalgebra and argmin
//! have none); the method is the textbook one: Arnoldi with modified
//! Gram–Schmidt, the Hessenberg least-squares problem reduced by Givens
//! rotations, restarts every `restart` steps.
//!
//! # References
//! - Y. Saad, M.H. Schultz, "GMRES: a generalized minimal residual algorithm
//!   for solving nonsymmetric linear systems", SIAM J. Sci. Stat. Comput. 7
//!   (1986) 856–869.
//! - Y. Saad, *Iterative Methods for Sparse Linear Systems*, 2nd ed., SIAM
//!   2003, §6.5.

/// What one GMRES solve did.
#[derive(Debug, Clone, Copy)]
pub(crate) struct KrylovOutcome {
    /// Operator applications.
    pub applications: usize,
    /// Final residual norm relative to the right-hand side's.
    pub relative_residual: f64,
}

/// Solves A x = b to a relative residual `tolerance`, starting from the
/// given `x`, with at most `max_applications` operator applications.
pub(crate) fn gmres(
    apply: &mut dyn FnMut(&[f64], &mut [f64]),
    b: &[f64],
    x: &mut [f64],
    restart: usize,
    tolerance: f64,
    max_applications: usize,
) -> KrylovOutcome {
    let n = b.len();
    let b_norm = norm(b).max(f64::MIN_POSITIVE);
    let mut applications = 0;
    let mut r = vec![0.0; n];
    let mut w = vec![0.0; n];
    loop {
        apply(x, &mut w);
        applications += 1;
        for i in 0..n {
            r[i] = b[i] - w[i];
        }
        let beta = norm(&r);
        if beta <= tolerance * b_norm || applications >= max_applications {
            return KrylovOutcome {
                applications,
                relative_residual: beta / b_norm,
            };
        }
        let mut basis: Vec<Vec<f64>> = vec![r.iter().map(|v| v / beta).collect()];
        let mut h: Vec<Vec<f64>> = Vec::new();
        let (mut cs, mut sn): (Vec<f64>, Vec<f64>) = (Vec::new(), Vec::new());
        let mut g = vec![beta];
        let mut steps = 0;
        while steps < restart && applications < max_applications {
            apply(&basis[steps], &mut w);
            applications += 1;
            let mut column = vec![0.0; steps + 2];
            for (j, v) in basis.iter().enumerate() {
                let hij = dot(&w, v);
                column[j] = hij;
                for (wi, vi) in w.iter_mut().zip(v) {
                    *wi -= hij * vi;
                }
            }
            let next = norm(&w);
            column[steps + 1] = next;
            // Earlier rotations, then a new one to zero the subdiagonal.
            for j in 0..steps {
                let t = cs[j] * column[j] + sn[j] * column[j + 1];
                column[j + 1] = -sn[j] * column[j] + cs[j] * column[j + 1];
                column[j] = t;
            }
            let d = column[steps].hypot(column[steps + 1]);
            let (c, s) = if d == 0.0 {
                (1.0, 0.0)
            } else {
                (column[steps] / d, column[steps + 1] / d)
            };
            column[steps] = d;
            column[steps + 1] = 0.0;
            cs.push(c);
            sn.push(s);
            g.push(-s * g[steps]);
            g[steps] *= c;
            h.push(column);
            steps += 1;
            if g[steps].abs() <= tolerance * b_norm || next == 0.0 {
                break;
            }
            basis.push(w.iter().map(|v| v / next).collect());
        }
        // Back substitution for the Krylov coefficients.
        let mut y = vec![0.0; steps];
        for i in (0..steps).rev() {
            let mut s = g[i];
            for (j, yj) in y.iter().enumerate().skip(i + 1) {
                s -= h[j][i] * yj;
            }
            y[i] = s / h[i][i];
        }
        for (yj, v) in y.iter().zip(&basis) {
            for (xi, vi) in x.iter_mut().zip(v) {
                *xi += yj * vi;
            }
        }
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A non-symmetric, diagonally dominant system, checked by its
    /// residual computed directly.
    #[test]
    fn solves_a_nonsymmetric_system() {
        let n = 40;
        let a = |i: usize, j: usize| {
            if i == j {
                4.0 + (i as f64).sin()
            } else {
                1.0 / (1.0 + (i as f64 - j as f64 + 0.5).abs().powf(1.5))
                    * if j > i { 1.3 } else { 0.4 }
            }
        };
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).cos()).collect();
        let mut apply = |x: &[f64], out: &mut [f64]| {
            for (i, o) in out.iter_mut().enumerate() {
                *o = (0..n).map(|j| a(i, j) * x[j]).sum();
            }
        };
        let mut x = vec![0.0; n];
        let outcome = gmres(&mut apply, &b, &mut x, 10, 1e-12, 1000);
        assert!(outcome.relative_residual < 1e-12, "{outcome:?}");
        let mut check = vec![0.0; n];
        apply(&x, &mut check);
        for i in 0..n {
            assert!((check[i] - b[i]).abs() < 1e-10);
        }
    }
}
