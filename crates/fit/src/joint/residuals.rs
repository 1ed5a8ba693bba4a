//! The DMA part of a joint fit's objective: every isotherm point a
//! measurement of the master curve at its reduced frequency.
//!
//! A point (T, ω, E′, E″) gives two residuals,
//!
//!   r′ = [ln(b_T E′_fit(ω a_T)) − ln E′]/σ,   r″ = [ln(b_T E″_fit(ω a_T)) − ln E″]/σ,
//!
//! σ the relative standard deviation of the DMA moduli (a DMA's scatter is
//! a fraction of the modulus, as `crate::master::prony_fit` weighs it), a_T
//! the joint shift at T and b_T the known vertical factor (1 without). With
//! p = (E0, H_1..H_n) and w_k = ω a_T τ_k the Prony series of Eq. (B2) gives
//!
//!   E′ = E0 + Σ H_k w_k²/(1 + w_k²),   E″ = Σ H_k w_k/(1 + w_k²),
//!   ∂E′/∂H_k = w_k²/(1 + w_k²),  ∂E″/∂H_k = w_k/(1 + w_k²),  ∂E′/∂E0 = 1,
//!   ∂E′/∂ln ω = Σ H_k 2w_k²/(1 + w_k²)²,  ∂E″/∂ln ω = Σ H_k w_k(1 − w_k²)/(1 + w_k²)²,
//!
//! and the shift's columns follow from ∂ln ω_red/∂θ_s = ∂ln a_T/∂θ_s. The
//! gradient in p is pulled back to θ by the parametrisation, exactly as the
//! rolling rows' ([`crate::objective`]).

use std::f64::consts::LN_10;

use nalgebra::{DMatrix, DVector};
use rollfit_model::VerticalShift;

use crate::error::FitError;
use crate::master::reach::REDUCED_RANGE;
use crate::parametrization::{Mapped, Parametrization};
use crate::shift::{ShiftParam, index_of};

use crate::dma_rows::DmaRows;

/// The DMA rows of a joint objective, ready for evaluation.
#[derive(Debug, Clone)]
pub(crate) struct DmaBlock {
    /// Index of each point's temperature among the shift's (0 without a
    /// shift).
    temp_index: Vec<usize>,
    /// Isotherm temperature of each point, °C.
    temperature: Vec<f64>,
    /// Measured ω, rad/s.
    omega: Vec<f64>,
    ln_storage: Vec<f64>,
    ln_loss: Vec<f64>,
    /// ln b_T of each point (0 without vertical factors).
    ln_vertical: Vec<f64>,
    /// Relative σ of E′ and E″.
    sigma: f64,
}

/// The joint curve at the DMA points.
#[derive(Debug, Clone)]
pub(crate) struct DmaValues {
    /// ω a_T, rad/s.
    pub reduced_omega: Vec<f64>,
    /// b_T E′_fit, Pa.
    pub storage: Vec<f64>,
    /// b_T E″_fit, Pa.
    pub loss: Vec<f64>,
}

impl DmaBlock {
    /// The block for `rows` under `shift` (None: every point at T_ref),
    /// weighted by the relative `sigma`, with the known vertical factors.
    pub(crate) fn new(
        rows: &DmaRows,
        shift: Option<&ShiftParam>,
        sigma: f64,
        vertical: Option<&VerticalShift>,
    ) -> Result<DmaBlock, FitError> {
        let mut block = DmaBlock {
            temp_index: Vec::new(),
            temperature: Vec::new(),
            omega: Vec::new(),
            ln_storage: Vec::new(),
            ln_loss: Vec::new(),
            ln_vertical: Vec::new(),
            sigma,
        };
        for (t, w, e1, e2) in rows.points() {
            let j = match shift {
                Some(s) => index_of(s.temperatures(), t).ok_or(FitError::Internal(
                    "a DMA temperature is missing from the joint shift",
                ))?,
                None => 0,
            };
            let ln_b = match vertical {
                Some(v) => LN_10 * v.log10_factor(t)?,
                None => 0.0,
            };
            block.temp_index.push(j);
            block.temperature.push(t);
            block.omega.push(w);
            block.ln_storage.push(e1.ln());
            block.ln_loss.push(e2.ln());
            block.ln_vertical.push(ln_b);
        }
        Ok(block)
    }

    /// Number of points (residual rows: twice as many).
    pub(crate) fn points(&self) -> usize {
        self.omega.len()
    }

    /// The point indices grouped by isotherm, each in ascending ω: the runs
    /// test's order.
    pub(crate) fn isotherm_groups(&self) -> Vec<Vec<usize>> {
        let mut temps: Vec<f64> = self.temperature.clone();
        temps.sort_by(f64::total_cmp);
        temps.dedup();
        temps
            .iter()
            .map(|&t| {
                let mut g: Vec<usize> = (0..self.points())
                    .filter(|&i| self.temperature[i] == t)
                    .collect();
                g.sort_by(|&a, &b| self.omega[a].total_cmp(&self.omega[b]));
                g
            })
            .collect()
    }

    /// ln a_T of each point and ∂ln a_T/∂θ_s, from the shift's values at
    /// its temperatures.
    fn point_shifts(&self, shift: Option<(&ShiftParam, &[f64])>) -> (Vec<f64>, Vec<Vec<f64>>) {
        match shift {
            None => (vec![0.0; self.points()], vec![Vec::new(); self.points()]),
            Some((s, theta)) => {
                let (values, grads) = s.log_shifts(theta);
                self.temp_index
                    .iter()
                    .map(|&j| {
                        (
                            LN_10 * values[j],
                            grads[j].iter().map(|g| LN_10 * g).collect(),
                        )
                    })
                    .unzip()
            }
        }
    }

    /// The joint curve at every point: reduced ω and b_T E*(ω a_T).
    pub(crate) fn values(
        &self,
        m: &Mapped,
        tau: &[f64],
        shift: Option<(&ShiftParam, &[f64])>,
    ) -> DmaValues {
        let (ln_a, _) = self.point_shifts(shift);
        let mut out = DmaValues {
            reduced_omega: Vec::with_capacity(self.points()),
            storage: Vec::with_capacity(self.points()),
            loss: Vec::with_capacity(self.points()),
        };
        for (i, shift) in ln_a.iter().enumerate() {
            let w = self.omega[i] * shift.exp();
            let (e1, e2) = moduli(m, tau, w);
            let b = self.ln_vertical[i].exp();
            out.reduced_omega.push(w);
            out.storage.push(b * e1);
            out.loss.push(b * e2);
        }
        out
    }

    /// Writes the 2N residuals from row `row0` on (E′ then E″ of each point)
    /// and, when given, their Jacobian (material columns first, the shift's
    /// from `n_material`); returns Σ r². `kappa_column`: a column whose
    /// entries stay zero (κ does not touch the DMA rows).
    pub(crate) fn fill(
        &self,
        param: &Parametrization,
        m: &Mapped,
        shift: Option<(&ShiftParam, &[f64])>,
        residuals: &mut DVector<f64>,
        jacobian: Option<&mut DMatrix<f64>>,
        row0: usize,
    ) -> Result<f64, FitError> {
        let (ln_a, grads) = self.point_shifts(shift);
        let tau = param.tau();
        let n = tau.len();
        let n_material = param.free_count();
        let mut misfit = 0.0;
        let mut jac = jacobian;
        let mut grad_p = vec![0.0; n + 1];
        let mut grad_theta = vec![0.0; n_material];
        for i in 0..self.points() {
            let w = self.omega[i] * ln_a[i].exp();
            if !(REDUCED_RANGE.0..=REDUCED_RANGE.1).contains(&w) {
                return Err(shift.map_or(
                    FitError::setting("shift", "a DMA frequency left the floating-point range"),
                    |(s, theta)| s.beyond_range(theta),
                ));
            }
            let (e1, e2) = moduli(m, tau, w);
            let r1 = (e1.ln() + self.ln_vertical[i] - self.ln_storage[i]) / self.sigma;
            let r2 = (e2.ln() + self.ln_vertical[i] - self.ln_loss[i]) / self.sigma;
            let (row1, row2) = (row0 + 2 * i, row0 + 2 * i + 1);
            residuals[row1] = r1;
            residuals[row2] = r2;
            misfit += r1 * r1 + r2 * r2;
            let Some(jac) = jac.as_deref_mut() else {
                continue;
            };
            let (mut d1_ln_w, mut d2_ln_w) = (0.0, 0.0);
            let scale1 = 1.0 / (e1 * self.sigma);
            let scale2 = 1.0 / (e2 * self.sigma);
            // E′ row: ∂/∂E0 = 1, ∂/∂H_k = x²/(1 + x²).
            grad_p[0] = scale1;
            for k in 0..n {
                let x = w * tau[k];
                let d = 1.0 / (1.0 + x * x);
                grad_p[k + 1] = x * x * d * scale1;
                d1_ln_w += m.strengths[k] * 2.0 * x * x * d * d;
                d2_ln_w += m.strengths[k] * x * (1.0 - x * x) * d * d;
            }
            param.pullback(m, &grad_p, &mut grad_theta);
            for (j, g) in grad_theta.iter().enumerate() {
                jac[(row1, j)] = *g;
            }
            grad_p[0] = 0.0;
            for k in 0..n {
                let x = w * tau[k];
                grad_p[k + 1] = x / (1.0 + x * x) * scale2;
            }
            param.pullback(m, &grad_p, &mut grad_theta);
            for (j, g) in grad_theta.iter().enumerate() {
                jac[(row2, j)] = *g;
            }
            for (k, d) in grads[i].iter().enumerate() {
                jac[(row1, n_material + k)] = d1_ln_w * scale1 * d;
                jac[(row2, n_material + k)] = d2_ln_w * scale2 * d;
            }
        }
        Ok(misfit)
    }
}

/// E′ and E″ of the Prony series (E0, H) on `tau` at ω, Pa.
fn moduli(m: &Mapped, tau: &[f64], omega: f64) -> (f64, f64) {
    moduli_at(m.static_modulus, &m.strengths, tau, omega)
}

/// E′ and E″ (Pa) at ω (rad/s) of the Prony series with static modulus
/// `static_modulus` and strengths `strengths` (Pa) at `tau` (s).
pub(crate) fn moduli_at(
    static_modulus: f64,
    strengths: &[f64],
    tau: &[f64],
    omega: f64,
) -> (f64, f64) {
    let mut e1 = static_modulus;
    let mut e2 = 0.0;
    for (h, t) in strengths.iter().zip(tau) {
        let x = omega * t;
        let d = 1.0 / (1.0 + x * x);
        e1 += h * x * x * d;
        e2 += h * x * d;
    }
    (e1, e2)
}
