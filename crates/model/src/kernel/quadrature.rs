//! Gauss–Legendre rules used to build the kernel tables (once, at first use).
//!
//! Written here rather than taken from `gauss-quad` because only fixed
//! low-order rules on [0, 1] are needed and they are computed once by the
//! classic Newton iteration on P_n (Golub–Welsch would be overkill).

/// Nodes and weights of the n-point Gauss–Legendre rule on [0, 1].
pub(crate) fn gauss_legendre_unit(n: usize) -> (Vec<f64>, Vec<f64>) {
    let mut nodes = vec![0.0; n];
    let mut weights = vec![0.0; n];
    for i in 0..n {
        // Tricomi's initial guess, then Newton on the three-term recurrence.
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 1 { x } else { p1 };
            let pm = if n == 1 { 1.0 } else { p0 };
            dp = n as f64 * (x * pn - pm) / (x * x - 1.0);
            let dx = pn / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        nodes[i] = 0.5 * (1.0 - x);
        weights[i] = 1.0 / ((1.0 - x * x) * dp * dp);
    }
    (nodes, weights)
}

/// ∫_a^b f by composite Gauss–Legendre with `panels` equal panels.
pub(crate) fn integrate<F: FnMut(f64) -> f64>(
    rule: &(Vec<f64>, Vec<f64>),
    a: f64,
    b: f64,
    panels: usize,
    mut f: F,
) -> f64 {
    let width = (b - a) / panels as f64;
    let mut sum = 0.0;
    for p in 0..panels {
        let start = a + p as f64 * width;
        for (x, w) in rule.0.iter().zip(&rule.1) {
            sum += w * f(start + x * width);
        }
    }
    sum * width
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrates_polynomials_exactly() {
        for n in [1, 4, 16, 24] {
            let rule = gauss_legendre_unit(n);
            let deg = 2 * n - 1;
            let got = integrate(&rule, 0.0, 1.0, 1, |x| x.powi(deg as i32));
            assert!(
                (got - 1.0 / (deg as f64 + 1.0)).abs() < 1e-14,
                "n={n}: {got}"
            );
        }
    }
}
