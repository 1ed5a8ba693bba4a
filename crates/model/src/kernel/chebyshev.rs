//! Piecewise Chebyshev interpolation of a smooth function, used once to make
//! the sphere kernel (whose every value costs a quadrature) cheap while the
//! product-integration tables are built.

/// Piecewise Chebyshev interpolant on consecutive panels.
pub(crate) struct PiecewiseChebyshev {
    breaks: Vec<f64>,
    coefficients: Vec<Vec<f64>>,
}

impl PiecewiseChebyshev {
    /// Interpolates `f` at `n` Chebyshev points of each panel between
    /// consecutive `breaks` (increasing).
    pub(crate) fn new<F: Fn(f64) -> f64>(breaks: Vec<f64>, n: usize, f: F) -> Self {
        let [real] = Self::new_many(breaks, n, |x| [f(x)]);
        real
    }

    /// Interpolants of the M components of `f`, which is evaluated once per
    /// node for all of them (for a complex function: its real and imaginary
    /// parts).
    pub(crate) fn new_many<const M: usize, F: Fn(f64) -> [f64; M]>(
        breaks: Vec<f64>,
        n: usize,
        f: F,
    ) -> [Self; M] {
        let nodes: Vec<f64> = (0..n)
            .map(|j| (std::f64::consts::PI * (j as f64 + 0.5) / n as f64).cos())
            .collect();
        let mut coefficients: [Vec<Vec<f64>>; M] = std::array::from_fn(|_| Vec::new());
        for ab in breaks.windows(2) {
            let (a, b) = (ab[0], ab[1]);
            let values: Vec<[f64; M]> = nodes
                .iter()
                .map(|&t| f(0.5 * (a + b) + 0.5 * (b - a) * t))
                .collect();
            for (component, out) in coefficients.iter_mut().enumerate() {
                out.push(
                    (0..n)
                        .map(|k| {
                            let s: f64 = values
                                .iter()
                                .enumerate()
                                .map(|(j, v)| {
                                    v[component]
                                        * (std::f64::consts::PI * k as f64 * (j as f64 + 0.5)
                                            / n as f64)
                                            .cos()
                                })
                                .sum();
                            s * 2.0 / n as f64 * if k == 0 { 0.5 } else { 1.0 }
                        })
                        .collect(),
                );
            }
        }
        coefficients.map(|coefficients| PiecewiseChebyshev {
            breaks: breaks.clone(),
            coefficients,
        })
    }

    /// Lower and upper end of the interpolated interval.
    pub(crate) fn range(&self) -> (f64, f64) {
        (self.breaks[0], self.breaks[self.breaks.len() - 1])
    }

    /// Value at `x` inside the range (Clenshaw recurrence).
    pub(crate) fn eval(&self, x: f64) -> f64 {
        let idx = match self
            .breaks
            .binary_search_by(|b| b.partial_cmp(&x).expect("finite"))
        {
            Ok(i) => i.min(self.coefficients.len() - 1),
            Err(i) => i.saturating_sub(1).min(self.coefficients.len() - 1),
        };
        let (a, b) = (self.breaks[idx], self.breaks[idx + 1]);
        let t = (2.0 * x - a - b) / (b - a);
        let c = &self.coefficients[idx];
        let (mut b1, mut b2) = (0.0, 0.0);
        for &ck in c.iter().skip(1).rev() {
            let b0 = 2.0 * t * b1 - b2 + ck;
            b2 = b1;
            b1 = b0;
        }
        t * b1 - b2 + c[0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolates_smooth_function() {
        let breaks: Vec<f64> = (0..=20).map(|i| i as f64 * 0.25).collect();
        let p = PiecewiseChebyshev::new(breaks, 16, |x| (3.0 * x).sin() * (-x).exp());
        for i in 0..1000 {
            let x = i as f64 * 0.005;
            assert!((p.eval(x) - (3.0 * x).sin() * (-x).exp()).abs() < 1e-14);
        }
    }
}
