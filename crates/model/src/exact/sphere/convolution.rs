//! The boundary-element operator u = A p as a discrete convolution,
//! evaluated by FFT on a zero-padded grid (DC-FFT: Liu, Wang & Liu 2000).
//!
//! The grid is uniform, so u_i = Σ_k A(x_i − x_k, y_i − y_k) p_k is a
//! linear (not cyclic) convolution. Padding both the influence table and
//! the pressure to 2nx × 2ny and placing A(X, Y) at (X mod 2nx, Y mod 2ny)
//! makes the cyclic convolution of the padded arrays equal the linear one
//! on the grid: offsets span −(n − 1) … n − 1, fewer than 2n, so no image
//! overlaps. The operator is not symmetric (the memory looks ahead only),
//! which the FFT does not care about.
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
    /// Padded sizes 2nx, 2ny.
    px: usize,
    py: usize,
    /// FFT of the padded table, transposed layout (index x·py + y), divided
    /// by px·py so that the inverse transform needs no scaling.
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
        let (px, py) = (2 * nx, 2 * ny);
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
            let y = if yi < ny {
                yi as isize
            } else if yi > ny {
                yi as isize - py as isize
            } else {
                continue;
            };
            for xi in 0..px {
                let x = if xi < nx {
                    xi as isize
                } else if xi > nx {
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
    pub fn apply(&self, p: &[f64], u: &mut [f64]) {
        let (nx, ny, px, py) = (self.nx, self.ny, self.px, self.py);
        let mut data = vec![Complex64::new(0.0, 0.0); px * py];
        for y in 0..ny {
            for x in 0..nx {
                data[y * px + x].re = p[y * nx + x];
            }
        }
        let mut t = self.transform(data, ny);
        for (z, k) in t.iter_mut().zip(&self.spectrum) {
            *z *= k;
        }
        self.inverse_y.process(&mut t);
        // Only the first ny rows of the result are on the grid.
        let mut rows = transpose_rows(&t, py, px, ny);
        self.inverse_x.process(&mut rows);
        for y in 0..ny {
            for x in 0..nx {
                u[y * nx + x] = rows[y * px + x].re;
            }
        }
    }
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

/// The first `keep` columns of a (rows × cols, row-major) array, transposed
/// to keep × rows.
fn transpose_rows(data: &[Complex64], cols: usize, rows: usize, keep: usize) -> Vec<Complex64> {
    let mut out = vec![Complex64::new(0.0, 0.0); keep * rows];
    for r in 0..rows {
        for c in 0..keep {
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
        let (nx, ny) = (7, 5);
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
                assert!((u[yi * nx + xi] - direct).abs() < 1e-12, "{xi},{yi}");
            }
        }
    }
}
