//! The boundary-element operator u = A p as a discrete convolution,
//! evaluated by FFT on a zero-padded grid (DC-FFT: Liu, Wang & Liu 2000).
//!
//! The grid is uniform, so u_i = Σ_k A(x_i − x_k, y_i − y_k) p_k is a
//! linear (not cyclic) convolution. Padding both the influence table and
//! the pressure to px × py with px ≥ 2nx − 1, py ≥ 2ny − 1 and placing
//! A(X, Y) at (X mod px, Y mod py) makes the cyclic convolution of the
//! padded arrays equal the linear one on the grid: offsets span
//! −(n − 1) … n − 1, 2n − 1 values, so no image overlaps. The padded sizes
//! are the smallest 5-smooth numbers (2^a 3^b 5^c) from 2n on: 2n itself
//! can hold a large prime (2·173 for the 144-cell grid), which the FFT
//! handles by Bluestein's algorithm at several times the cost. The
//! operator is not symmetric (the memory looks ahead only), which the FFT
//! does not care about.
//!
//! # References
//! - S. Liu, Q. Wang, G. Liu, "A versatile method of discrete convolution
//!   and FFT (DC-FFT) for contact analyses", Wear 243 (2000) 101–111.

use std::sync::Arc;

use num_complex::Complex64;
use rustfft::{Fft, FftPlanner};

/// A = (influence table), applied by FFT.
pub(crate) struct Convolution {
    nx: usize,
    ny: usize,
    /// Padded sizes: the 5-smooth numbers from 2nx, 2ny on.
    px: usize,
    py: usize,
    /// FFT of the padded table, transposed layout (index k·py + y), divided
    /// by px·py so that the inverse transform needs no scaling; only the
    /// columns k = 0 … px/2, which are all that real data need (see
    /// [`Self::apply`]).
    spectrum: Vec<Complex64>,
    forward_x: Arc<dyn Fft<f64>>,
    inverse_x: Arc<dyn Fft<f64>>,
    forward_y: Arc<dyn Fft<f64>>,
    inverse_y: Arc<dyn Fft<f64>>,
}

impl Convolution {
    /// The operator of an nx × ny grid whose influence of offset (X, Y)
    /// is `table(X, |Y|)`, X = −(nx − 1) … nx − 1.
    pub fn new(nx: usize, ny: usize, table: impl Fn(isize, usize) -> f64) -> Self {
        let (px, py) = (smooth_from(2 * nx), smooth_from(2 * ny));
        let mut planner = FftPlanner::new();
        let mut op = Convolution {
            nx,
            ny,
            px,
            py,
            spectrum: Vec::new(),
            forward_x: planner.plan_fft_forward(px),
            inverse_x: planner.plan_fft_inverse(px),
            forward_y: planner.plan_fft_forward(py),
            inverse_y: planner.plan_fft_inverse(py),
        };
        let mut padded = vec![Complex64::new(0.0, 0.0); px * py];
        for yi in 0..py {
            // Offsets 0 … n − 1 at the front, −(n − 1) … −1 at the back,
            // zeros between.
            let y = if yi < ny {
                yi as isize
            } else if yi + ny > py {
                yi as isize - py as isize
            } else {
                continue;
            };
            for xi in 0..px {
                let x = if xi < nx {
                    xi as isize
                } else if xi + nx > px {
                    xi as isize - px as isize
                } else {
                    continue;
                };
                padded[yi * px + xi] = Complex64::new(table(x, y.unsigned_abs()), 0.0);
            }
        }
        let scale = 1.0 / (px * py) as f64;
        let mut spectrum = op.transform(padded, py);
        spectrum.iter_mut().for_each(|z| *z *= scale);
        // Only the columns k = 0 … px/2 are used (see `apply`).
        spectrum.truncate((px / 2 + 1) * py);
        op.spectrum = spectrum;
        op
    }

    /// The 2-D FFT of a padded array (row-major, index y·px + x) whose rows
    /// at and beyond `rows` are zero; returned transposed (x·py + y).
    fn transform(&self, mut data: Vec<Complex64>, rows: usize) -> Vec<Complex64> {
        self.forward_x.process(&mut data[..rows * self.px]);
        let mut t = transpose(&data, self.px, self.py);
        self.forward_y.process(&mut t);
        t
    }

    /// u = A p for p on the nx × ny grid (index y·nx + x).
    ///
    /// p and u are real, so each row's spectrum is Hermitian, Z(−k) =
    /// conj Z(k): two rows a, b are transformed along x as one complex row
    /// a + ib and separated, A(k) = (Z(k) + conj Z(−k))/2, B(k) = (Z(k) −
    /// conj Z(−k))/2i; only the columns k = 0 … px/2 are transformed along
    /// y and multiplied; and two result rows come back from one inverse
    /// transform of U_a + iU_b, with the other columns conj U(px − k).
    /// Half the transforms of the complex product, the same result to
    /// rounding.
    pub fn apply(&self, p: &[f64], u: &mut [f64]) {
        let (nx, ny, px, py) = (self.nx, self.ny, self.px, self.py);
        let half = px / 2 + 1;
        let zero = Complex64::new(0.0, 0.0);
        // Columns k < half of the row spectra, transposed (k·py + y).
        let mut t = vec![zero; half * py];
        let mut row = vec![zero; px];
        for a in (0..ny).step_by(2) {
            let b = a + 1;
            row.iter_mut().for_each(|z| *z = zero);
            for x in 0..nx {
                let im = if b < ny { p[b * nx + x] } else { 0.0 };
                row[x] = Complex64::new(p[a * nx + x], im);
            }
            self.forward_x.process(&mut row);
            for k in 0..half {
                let (z, mirror) = (row[k], row[(px - k) % px].conj());
                t[k * py + a] = 0.5 * (z + mirror);
                if b < ny {
                    t[k * py + b] = Complex64::new(0.0, -0.5) * (z - mirror);
                }
            }
        }
        self.forward_y.process(&mut t);
        for (z, k) in t.iter_mut().zip(&self.spectrum) {
            *z *= k;
        }
        self.inverse_y.process(&mut t);
        for a in (0..ny).step_by(2) {
            let b = a + 1;
            let at = |k: usize, y: usize| if y < ny { t[k * py + y] } else { zero };
            for (k, z) in row.iter_mut().enumerate() {
                let (ua, ub) = if k < half {
                    (at(k, a), at(k, b))
                } else {
                    (at(px - k, a).conj(), at(px - k, b).conj())
                };
                *z = ua + Complex64::new(0.0, 1.0) * ub;
            }
            self.inverse_x.process(&mut row);
            for x in 0..nx {
                u[a * nx + x] = row[x].re;
                if b < ny {
                    u[b * nx + x] = row[x].im;
                }
            }
        }
    }
}

/// The smallest 5-smooth number (2^a 3^b 5^c) at least `n`: FFT lengths
/// without large prime factors.
fn smooth_from(n: usize) -> usize {
    let smooth = |mut m: usize| {
        for f in [2, 3, 5] {
            while m.is_multiple_of(f) {
                m /= f;
            }
        }
        m == 1
    };
    (n.max(1)..).find(|&m| smooth(m)).unwrap_or(n)
}

/// The transpose of a rows × cols array (row-major): cols × rows.
fn transpose(data: &[Complex64], cols: usize, rows: usize) -> Vec<Complex64> {
    let mut out = vec![Complex64::new(0.0, 0.0); data.len()];
    for r in 0..rows {
        for c in 0..cols {
            out[c * rows + r] = data[r * cols + c];
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The FFT product against the direct double sum, for a table with no
    /// symmetry in X.
    #[test]
    fn equals_the_direct_sum() {
        // Odd and even rows and padded lengths (15 × 10, 16 × 12, 64 × 30).
        for (nx, ny) in [(7, 5), (8, 6), (32, 15)] {
            equals_the_direct_sum_on(nx, ny);
        }
    }

    fn equals_the_direct_sum_on(nx: usize, ny: usize) {
        let table = |x: isize, y: usize| {
            1.0 / (1.0 + (x as f64 + 0.3).powi(2) + (y * y) as f64) + 0.1 * x as f64
        };
        let op = Convolution::new(nx, ny, table);
        let p: Vec<f64> = (0..nx * ny).map(|k| ((k * 37 % 11) as f64).sin()).collect();
        let mut u = vec![0.0; nx * ny];
        op.apply(&p, &mut u);
        for yi in 0..ny {
            for xi in 0..nx {
                let mut direct = 0.0;
                for yk in 0..ny {
                    for xk in 0..nx {
                        let (dx, dy) = (xi as isize - xk as isize, yi as isize - yk as isize);
                        direct += table(dx, dy.unsigned_abs()) * p[yk * nx + xk];
                    }
                }
                assert!(
                    (u[yi * nx + xi] - direct).abs() < 1e-12,
                    "{nx}×{ny}: {xi},{yi}"
                );
            }
        }
    }
}
