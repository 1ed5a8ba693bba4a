//! The friction coefficient μ(v), Persson (2010) Eqs. (11) and (17), and its
//! derivatives with respect to Prony parameters.
//!
//! Method (see [`crate::kernel::weights`] for the product integration and
//! [`crate::kernel::window`] for the treatment of the oscillatory tails):
//!
//!   μ(v) = C Σ_j Φ_j W(σ_j − ln v),
//!
//! on a uniform grid σ_j = σ₀ + jh in σ = ln(ω r(ω)). The grid is shared by
//! all speeds of a sweep, so the modulus is evaluated once per node, not once
//! per node and speed. The sum is truncated where a rigorous bound of the
//! remaining tail, κ Σ e^{pσ_j} W(σ_j − ln v) with κ ≥ Φ e^{−pσ} (for a Prony
//! series p = 1 and L(ω) ≤ L′(0) ω), falls below the tolerance.
//!
//! Derivatives: with g_p = ∂E*/∂p (1 for E1, −1/(1 + iωτ_k) for H_k),
//! ∂L/∂p = (1 − ν²) Im(g_p/E²), ∂ ln r/∂p = −(1/n) Re(g_p/E) and
//!
//!   ∂μ/∂p = C ∫ dσ (ds/dσ) [∂A/∂p k̃(σ − ln v) + A ∂σ/∂p k̃′(σ − ln v)],
//!
//! which the same grid integrates with W and W′.
//!
//! A film of thickness d under the cylinder multiplies L(ω) by 1/S(ωd/v),
//! on a finer grid step (`film_cylinder`); under the sphere the film factor
//! depends on the direction of q and makes the kernel a function of two
//! variables, integrated in `film_sphere`.

mod film_cylinder;
mod film_sphere;
mod grid;
mod knots;
mod setup;
mod table_error;

use num_complex::Complex64;

use crate::contact::Shape;
use crate::error::ModelError;
use crate::film::film_factor;
use crate::kernel::{KernelTable, STEPS, step_for_tolerance};
use crate::modulus::{Prony, ViscoelasticModulus};
use crate::scene::Scene;
use grid::{Grid, Node};
use setup::Setup;

/// μ at several speeds and its derivatives with respect to the Prony
/// parameters p = (E1, H_1, …, H_n).
#[derive(Debug, Clone, PartialEq)]
pub struct FrictionJacobian {
    /// μ(v_i).
    pub mu: Vec<f64>,
    /// ∂μ(v_i)/∂p_j, row-major: `jacobian[i * parameter_count + j]`, 1/Pa.
    pub jacobian: Vec<f64>,
    /// Number of parameters n + 1.
    pub parameter_count: usize,
    /// ∂μ(v_i)/∂ln v_i. By time–temperature superposition this is also
    /// ∂μ/∂ln a_T of a shifted curve μ(v a_T): scaling v by a is the same as
    /// scaling every τ_k by a, a material change with ∂E*/∂ln a = dE*/d ln ω
    /// and ∂E0/∂ln a = 0, so it is computed as one more column of the same
    /// pass.
    pub d_ln_speed: Vec<f64>,
}

/// The derivatives behind column q of a friction Jacobian: g = ∂E*/∂p_q
/// and ∂E0/∂p_q, for p = (E1, H_1..H_n) and then the time scale ln a (see
/// [`FrictionJacobian::d_ln_speed`]). `factors` holds 1/(1 + iωτ_k) at the
/// node, `log_slope` dE*/d ln ω there.
pub(crate) fn column_derivative(
    q: usize,
    factors: &[Complex64],
    log_slope: Complex64,
) -> (Complex64, f64) {
    if q == 0 {
        (Complex64::new(1.0, 0.0), 1.0)
    } else if q <= factors.len() {
        (-factors[q - 1], -1.0)
    } else {
        (log_slope, 0.0)
    }
}

fn check_speeds(speeds: &[f64]) -> Result<(), ModelError> {
    for (i, &v) in speeds.iter().enumerate() {
        if !(v.is_finite() && v > 0.0) {
            return Err(ModelError::parameter(
                &format!("v[{i}]"),
                v,
                "a rolling speed must be a finite number greater than zero",
            ));
        }
    }
    Ok(())
}

/// The nodes one speed uses: (node, W, W′).
type Stencil = Vec<(i64, f64, f64)>;

/// Sums μ for one speed over the shared grid, extending it as needed.
fn one_speed<F: Fn(f64) -> (Complex64, Complex64)>(
    grid: &mut Grid<'_, F>,
    setup: &Setup,
    table: &KernelTable,
    tolerance: f64,
    v: f64,
    film: Option<(f64, f64)>,
    mut record: Option<&mut Stencil>,
) -> Result<f64, ModelError> {
    let h = table.step();
    let t = v.ln();
    let j0 = ((t - grid.origin()) / h).round() as i64;
    let eps = 0.02 * tolerance;
    let film_weight = |node: &Node| -> f64 {
        match film {
            Some((d, nu)) => 1.0 / film_factor(node.point.omega * d / v, nu),
            None => 1.0,
        }
    };
    let tau0 = grid.origin() + j0 as f64 * h - t;
    let cursor = table.cursor(tau0);
    let mut sum = 0.0;
    // March up from j0, then down from j0 − 1; each direction stops once the
    // bounded remaining tail (see [`Node`]) is negligible.
    for direction in [1i64, -1] {
        let mut j = if direction > 0 { j0 } else { j0 - 1 };
        loop {
            let node = grid.node(j)?;
            let (w, dw) = table.evaluate_at(&cursor, j - j0);
            let f = film_weight(&node);
            sum += node.phi * f * w;
            if let Some(r) = record.as_deref_mut() {
                r.push((j, w * f, dw * f));
            }
            let tau = tau0 + (j - j0) as f64 * h;
            if direction as f64 * tau > 2.0 {
                let bound = if direction > 0 {
                    node.up_bound
                } else {
                    node.down_bound
                };
                if bound * w.abs() <= eps * sum.abs() {
                    break;
                }
            }
            j += direction;
        }
    }
    Ok(setup.prefactor * sum)
}

impl<M: ViscoelasticModulus> Scene<M> {
    /// The friction coefficient μ at rolling speed `v` (m/s), to the scene's
    /// relative tolerance.
    pub fn friction(&self, v: f64) -> Result<f64, ModelError> {
        Ok(self.friction_sweep(&[v])?[0])
    }

    /// The kernel table, the σ-grid (started at the first speed) that all
    /// speeds of a sweep share, and the film (thickness, ν) under a
    /// cylinder, if any.
    #[allow(clippy::type_complexity)]
    fn shared_grid<'a>(
        &'a self,
        setup: &'a Setup,
        first_speed: f64,
    ) -> (
        &'static KernelTable,
        Grid<'a, impl Fn(f64) -> (Complex64, Complex64) + 'a>,
        Option<(f64, f64)>,
    ) {
        let film = self
            .substrate()
            .film_thickness
            .map(|d| (d, self.substrate().poisson));
        let table = match film {
            Some(_) => KernelTable::get_film_cylinder(film_cylinder::step_index(self.tolerance())),
            None => KernelTable::get(setup.shape, step_for_tolerance(self.tolerance())),
        };
        let material = self.material();
        let grid = Grid::new(
            setup,
            move |omega| material.modulus_and_log_slope(omega),
            first_speed.ln(),
            table.step(),
            self.tolerance(),
        );
        (table, grid, film)
    }

    /// The σ grid and the film kernel state of a sphere on a film of
    /// thickness `thickness` (m); the kernel rows are built for the contact
    /// radii between the glassy and the static one.
    fn film_sphere_grid<'a>(
        &'a self,
        setup: &'a Setup,
        first_speed: f64,
        thickness: f64,
    ) -> (
        Grid<'a, impl Fn(f64) -> (Complex64, Complex64) + 'a>,
        film_sphere::FilmSphere,
    ) {
        let step_index = step_for_tolerance(self.tolerance());
        let material = self.material();
        let grid = Grid::new(
            setup,
            move |omega| material.modulus_and_log_slope(omega),
            first_speed.ln(),
            STEPS[step_index],
            self.tolerance(),
        );
        let ln_size = |modulus: f64| (setup.ln_k - (modulus / setup.plane_strain).ln()) / setup.n;
        let ln_r0 = ln_size(setup.static_modulus);
        let ln_r_glassy = match setup.static_ln_size {
            Some(ln_r) => ln_r,
            None => {
                let (_, w_hi) = material.structure_range();
                ln_size(material.modulus(1e3 * w_hi).norm()).min(ln_r0)
            }
        };
        let film = film_sphere::FilmSphere::new(
            thickness,
            self.substrate().poisson,
            step_index,
            ln_r_glassy,
            ln_r0,
        );
        (grid, film)
    }

    /// μ at each of `speeds` (m/s), sharing the modulus evaluations.
    pub fn friction_sweep(&self, speeds: &[f64]) -> Result<Vec<f64>, ModelError> {
        check_speeds(speeds)?;
        if speeds.is_empty() {
            return Ok(Vec::new());
        }
        let setup = Setup::new(self)?;
        if let (Shape::Sphere, Some(d)) = (setup.shape, self.substrate().film_thickness) {
            let (mut grid, mut film) = self.film_sphere_grid(&setup, speeds[0], d);
            return speeds
                .iter()
                .map(|&v| {
                    film_sphere::one_speed(&mut grid, &setup, &mut film, self.tolerance(), v, None)
                })
                .collect();
        }
        // A modulus with knots (a table) is integrated piece by piece.
        let knots = self.material().knots();
        if !knots.is_empty() {
            return knots::friction_sweep(self, &setup, speeds, &knots);
        }
        let (table, mut grid, film) = self.shared_grid(&setup, speeds[0]);
        speeds
            .iter()
            .map(|&v| one_speed(&mut grid, &setup, table, self.tolerance(), v, film, None))
            .collect()
    }
}

impl Scene<Prony> {
    /// μ at each of `speeds` and ∂μ/∂(E1, H_1..H_n), computed in one pass over
    /// a shared grid (for a film under a sphere: per speed, by the film
    /// correction of the `film_sphere` module).
    pub fn friction_with_gradient(&self, speeds: &[f64]) -> Result<FrictionJacobian, ModelError> {
        check_speeds(speeds)?;
        let prony = self.material();
        let np = prony.parameter_count();
        if speeds.is_empty() {
            return Ok(FrictionJacobian {
                mu: Vec::new(),
                jacobian: Vec::new(),
                parameter_count: np,
                d_ln_speed: Vec::new(),
            });
        }
        let setup = Setup::new(self)?;
        let mut stencils = Vec::with_capacity(speeds.len());
        let mut mu = Vec::with_capacity(speeds.len());
        if let (Shape::Sphere, Some(d)) = (setup.shape, self.substrate().film_thickness) {
            let (mut grid, mut film) = self.film_sphere_grid(&setup, speeds[0], d);
            for &v in speeds {
                let mut stencil = Stencil::new();
                mu.push(film_sphere::one_speed(
                    &mut grid,
                    &setup,
                    &mut film,
                    self.tolerance(),
                    v,
                    Some(&mut stencil),
                )?);
                stencils.push(stencil);
            }
            return jacobian(&mut grid, &setup, prony, mu, &stencils);
        }
        let (table, mut grid, film) = self.shared_grid(&setup, speeds[0]);
        for &v in speeds {
            let mut stencil = Stencil::new();
            mu.push(one_speed(
                &mut grid,
                &setup,
                table,
                self.tolerance(),
                v,
                film,
                Some(&mut stencil),
            )?);
            stencils.push(stencil);
        }
        jacobian(&mut grid, &setup, prony, mu, &stencils)
    }
}

/// ∂μ/∂p for every speed from the stencils (node, W, W′) its sum used:
/// ∂μ/∂p = C Σ_j (ds/dσ)_j [∂A/∂p W + A ∂σ/∂p W′] (see the module docs).
fn jacobian<F: Fn(f64) -> (Complex64, Complex64)>(
    grid: &mut Grid<'_, F>,
    setup: &Setup,
    prony: &Prony,
    mu: Vec<f64>,
    stencils: &[Stencil],
) -> Result<FrictionJacobian, ModelError> {
    let np = prony.parameter_count();
    let speeds = &mu;
    // Per-node derivative data: (ds/dσ)·∂A/∂p and (ds/dσ)·A·∂σ/∂p.
    let (j_min, j_max) = stencils
        .iter()
        .flatten()
        .fold((i64::MAX, i64::MIN), |(lo, hi), &(j, _, _)| {
            (lo.min(j), hi.max(j))
        });
    let span = (j_max - j_min + 1) as usize;
    // Columns: the n + 1 parameters, then the time scale (ln a).
    let nq = np + 1;
    let mut d_a = vec![0.0; span * nq];
    let mut d_sigma = vec![0.0; span * nq];
    let mut factors = vec![Complex64::new(0.0, 0.0); prony.len()];
    let e0 = setup.static_modulus;
    let n = setup.n;
    let m = setup.m;
    for (idx, j) in (j_min..=j_max).enumerate() {
        let node = grid.node(j)?;
        let omega = node.point.omega;
        let _ = prony.evaluate_with_factors(omega, &mut factors);
        let (_, log_slope) = prony.modulus_and_log_slope(omega);
        let p = node.point;
        let inv2 = p.inv_e * p.inv_e;
        let ds_dsigma = 1.0 / p.dsigma_ds;
        let row_a = &mut d_a[idx * nq..(idx + 1) * nq];
        let row_s = &mut d_sigma[idx * nq..(idx + 1) * nq];
        for q in 0..nq {
            let (g, de0) = column_derivative(q, &factors, log_slope);
            let d_loss = setup.plane_strain * (g * inv2).im;
            let d_ln_r = match setup.static_ln_size {
                Some(_) => -de0 / (n * e0),
                None => -(g * p.inv_e).re / n,
            };
            row_a[q] = ds_dsigma * (d_loss / p.size_m - m * p.a * d_ln_r);
            row_s[q] = ds_dsigma * p.a * d_ln_r;
        }
    }
    let mut wide = vec![0.0; speeds.len() * nq];
    for (i, stencil) in stencils.iter().enumerate() {
        let row = &mut wide[i * nq..(i + 1) * nq];
        for &(j, w, dw) in stencil {
            let idx = (j - j_min) as usize;
            let a = &d_a[idx * nq..(idx + 1) * nq];
            let s = &d_sigma[idx * nq..(idx + 1) * nq];
            for q in 0..nq {
                row[q] += a[q] * w + s[q] * dw;
            }
        }
        for value in row.iter_mut() {
            *value *= setup.prefactor;
        }
    }
    let mut jacobian = Vec::with_capacity(speeds.len() * np);
    let mut d_ln_speed = Vec::with_capacity(speeds.len());
    for row in wide.chunks_exact(nq) {
        jacobian.extend_from_slice(&row[..np]);
        d_ln_speed.push(row[np]);
    }
    Ok(FrictionJacobian {
        mu,
        jacobian,
        parameter_count: np,
        d_ln_speed,
    })
}
