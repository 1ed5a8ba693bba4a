//! The exact steady rolling of a rigid sphere on a linear viscoelastic
//! half-space (frictionless, quasi-static, constant ν): the reference that
//! Persson's Eq. (17) approximates.
//!
//! # Formulation
//!
//! The sphere (radius R, load F) rolls at speed v in +x; x is measured from
//! its axis. With the effective creep compliance
//! J_eff(t) = (1 − ν²) J(t), J(t) = J0 + Σ_j c_j (1 − e^{−t/λ_j})
//! ([`super::CreepCompliance`]), the surface displacement in the frame of
//! the sphere is
//!
//!   u(x, y) = (1/π) ∫∫ p(s, t) [J0 K(x − s, y − t) + ∫_0^∞ J̇(τ) K(x − s + vτ, y − t) dτ] ds dt,
//!
//! K = 1/ρ (Boussinesq, with the history of the material point now at
//! (x, y), which was at (x + vτ, y) a time τ ago). Contact: u = δ − (x² + y²)/(2R)
//! where p > 0, u ≥ δ − (x² + y²)/(2R) elsewhere, ∫∫ p = F. The contact
//! area is not a circle and not centred on the axis; it is found with the
//! pressure.
//!
//! # Method
//!
//! Boundary elements: piecewise-constant pressure on a uniform grid of
//! square cells, collocation at the cell centres. The influence
//! coefficients are the exact cell integrals of the elastic kernel
//! ([`cell`]) and their memory integrals ([`memory`]: an exact recursion
//! along the rolling direction, product-integrated, tabulated once per
//! grid). The operator is a discrete convolution applied by FFT with zero
//! padding ([`convolution`]); the contact set, pressures and approach come
//! from a primal–dual active-set iteration with GMRES for the
//! non-symmetric linear systems ([`contact`]). The grid's side is a fixed
//! fraction of the contact radius estimated at that speed, so the
//! discretisation error is the same at every speed.
//!
//! Each speed is solved on three grids (N, ⅔N, 4/9 N cells across the
//! expected contact diameter), μ extrapolated in h² from the two finer
//! and its error estimated from the three ([`RollingSphere::solve`]).
//! Where the active-set iteration does not settle from the Hertz start
//! (stiff solids at low speed), the coarsest grid is reached by
//! continuation from higher speeds; where it cycles on a grid the iterate
//! of least complementarity defect is kept and its defect charged to the
//! error estimate ([`contact`]).
//! A solve may instead start each grid from an earlier solve's on the
//! same grid (a fit's next sweep at the same speed; [`warm`],
//! [`RollingSphere::solve_from`]), with the same answer.
//!
//! Outputs: μ = x̄/R from the pressure centroid (Persson 2010, Section 4),
//! the approach, the contact outline and the pressure map. As a check, μ
//! from the dissipated power, P/(vF) = (1/F) ∫ d²q/(2π)² (2|q_x|/|q|)
//! J''(|q_x| v) |p̂(q)|², which uses the cell pressures and the material's
//! loss compliance but none of the influence coefficients, agrees with
//! x̄/R to 2e-3 on the 96-cell grid (tests/exact_sphere_dissipation.rs).
//!
//! # Plane-strain check
//!
//! [`RollingSphere::plane_strain`] runs the same code on a cylinder (load
//! W per unit length): one row of strips ([`element`]) whose influence is
//! the plane-strain kernel C(x) = −(2/π) ∫ ln|x − ξ| dξ over the strip
//! ([`strip`]) instead of the square cell's Boussinesq integral, with the
//! memory recursion, convolution, contact set, load balance h Σ p_i = W,
//! three grids and extrapolation unchanged. The log kernel does not decay;
//! its additive constant only shifts the approach (see [`memory`]). Against
//! the exact cylinder ([`super::RollingCylinder`], an independent method
//! accurate to ~1e-8; tests/exact_plane_strain.rs, standard linear solids
//! E1/E0 = 10 and 100, vτ/a0 = 0.01 … 100): the finest grid alone converges
//! to it (≤ 4e-5 at 486 strips); at the default 96 strips μ agrees to
//! 1e-5 … 2e-3 up to vτ/a0 = 10 and to 2e-2 at vτ/a0 = 100 (μ small against
//! the contact edges' jitter on the grid), within 2.1 times the error
//! estimate. There the grid error is jitter, not a smooth h² term: the
//! finest grid alone is closer to the exact μ than the h² extrapolation in
//! 24 of 36 cases at 96 strips (E1/E0 = 2 … 1000), 33 of 36 at 216.
//!
//! # References
//! - S.C. Hunter, J. Appl. Mech. 28 (1961) 611–617 (the cylinder).
//! - G. Carbone, C. Putignano, J. Mech. Phys. Solids 61 (2013) 1822–1834.
//! - C. Putignano, L. Afferrante, G. Carbone, G. Demelio, "A new efficient
//!   numerical method for contact mechanics of rough surfaces", Int. J.
//!   Solids Struct. 49 (2012) 338–343.
//! - K.L. Johnson, *Contact Mechanics*, Cambridge 1985, §3.9, §7.6.
//! - B.N.J. Persson, Eur. Phys. J. E 33 (2010) 327–333, Eq. (17).

mod cell;
mod contact;
mod convolution;
mod element;
mod gmres;
mod memory;
mod strip;
mod table_cache;
mod warm;

use crate::contact::hertz_contact_size;
use crate::error::{ModelError, require_positive};
use crate::modulus::Prony;

use super::CreepCompliance;
use contact::{Grid, GridFailure, solve_contact};
use convolution::Convolution;
use element::Element;
use table_cache::cell_table;
pub use warm::SphereStart;

/// Discretisation settings of the exact sphere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereSettings {
    /// Cells across the estimated contact diameter.
    pub cells: usize,
    /// Gauss–Legendre nodes per half cell of the memory integrals.
    pub quadrature_order: usize,
}

impl SphereSettings {
    /// The cells for a relative accuracy `accuracy` of μ, from the
    /// measured true errors (against the extrapolation of 144 and 216
    /// cells; standard linear solids E1/E0 = 10 and 100, vτ/r0 = 0.01 …
    /// 10): at most 1.2e-3 with 64 cells, 1.4e-4 with 96 and 1.4e-4 with
    /// 144. The error does not fall like a power of h — the jitter of the
    /// contact set on the grid dominates — so the rule is the measured
    /// one: 96 cells for 1e-3 and a factor 1.5 per decade,
    /// N = 96 · 1.5^{log10(1e-3/ε)}, between 30 and 330 and a multiple of
    /// 3 (the coarser grids have ⅔ and 4/9 of it).
    pub fn for_accuracy(accuracy: f64) -> Self {
        let cells = (96.0 * 1.5f64.powf((1e-3 / accuracy).log10())).clamp(30.0, 330.0);
        SphereSettings {
            cells: (cells / 3.0).ceil() as usize * 3,
            ..SphereSettings::default()
        }
    }
}

impl Default for SphereSettings {
    fn default() -> Self {
        SphereSettings {
            cells: 96,
            quadrature_order: 8,
        }
    }
}

/// A rigid sphere rolling on a viscoelastic half-space.
#[derive(Debug, Clone)]
pub struct RollingSphere {
    compliance: CreepCompliance,
    radius: f64,
    /// Load F, N (plane strain: W per unit length, N/m).
    load: f64,
    settings: SphereSettings,
    /// Square cells (the sphere) or strips (the plane-strain check).
    element: Element,
}

/// The steady rolling contact of the sphere at one speed.
#[derive(Debug, Clone, PartialEq)]
pub struct SphereSolution {
    /// Rolling speed v, m/s.
    pub speed: f64,
    /// Friction coefficient μ = x̄/R.
    pub mu: f64,
    /// Pressure centroid x̄ from the axis, m (> 0: leading side).
    pub centroid: f64,
    /// Approach δ, m (plane strain, where the absolute approach is
    /// undefined: less the displacement that the whole load, as a line
    /// load, causes one grid length ahead of it).
    pub approach: f64,
    /// Contact area, m² (plane strain: the contact width, m).
    pub area: f64,
    /// Largest cell pressure, Pa.
    pub max_pressure: f64,
    /// Cell side, m.
    pub cell: f64,
    /// Cell centres x (from the axis), y, m, and pressures, Pa, of the
    /// cells in contact.
    pub pressure_map: Vec<(f64, f64, f64)>,
    /// Per row of cells in contact: y, trailing edge x, leading edge x, m.
    pub outline: Vec<(f64, f64, f64)>,
    /// Active-set iterations.
    pub iterations: usize,
    /// Applications of the boundary-element operator (FFT pairs).
    pub operator_applications: usize,
    /// Estimated relative error of μ (NaN where not estimated).
    pub error_estimate: f64,
    /// Relative error of μ that the complementarity defect of the grid
    /// solution may cause: 0 when the contact set settled, positive when
    /// the active-set iteration cycled and the least-defect iterate was
    /// taken (see the contact module).
    pub set_defect: f64,
}

impl SphereSolution {
    /// The trailing and leading contact edges on the rolling axis (the row
    /// of cells nearest y = 0), m from the sphere's axis.
    pub fn axis_edges(&self) -> (f64, f64) {
        self.outline
            .iter()
            .min_by(|a, b| a.0.abs().total_cmp(&b.0.abs()))
            .map_or((f64::NAN, f64::NAN), |&(_, a, b)| (a, b))
    }
}

impl RollingSphere {
    /// A sphere of radius `radius` (m) under load `load` (N) on a solid with
    /// Prony modulus `modulus` (Young's, Pa) and Poisson ratio `poisson`.
    pub fn new(modulus: &Prony, poisson: f64, radius: f64, load: f64) -> Result<Self, ModelError> {
        Self::with_settings(modulus, poisson, radius, load, SphereSettings::default())
    }

    /// As [`Self::new`] with explicit settings.
    pub fn with_settings(
        modulus: &Prony,
        poisson: f64,
        radius: f64,
        load: f64,
        settings: SphereSettings,
    ) -> Result<Self, ModelError> {
        Self::with_element(modulus, poisson, radius, load, settings, Element::Square)
    }

    /// The same boundary elements in plane strain: a rigid cylinder of
    /// radius `radius` (m) under a load `load_per_length` (N/m), solved as
    /// a one-row grid of strips whose influence is the plane-strain kernel
    /// −(2/π) ln|x| instead of Boussinesq's 1/ρ (module documentation,
    /// "Plane-strain check"). It exists to check the sphere's machinery —
    /// memory recursion, contact set, load balance, grids, extrapolation —
    /// against [`super::RollingCylinder`]; the cylinder itself is better
    /// solved there. `area` of its solutions is the contact width (m).
    pub fn plane_strain(
        modulus: &Prony,
        poisson: f64,
        radius: f64,
        load_per_length: f64,
        settings: SphereSettings,
    ) -> Result<Self, ModelError> {
        Self::with_element(
            modulus,
            poisson,
            radius,
            load_per_length,
            settings,
            Element::Strip,
        )
    }

    /// The body of either element: `load` in N (square cells) or N/m
    /// (strips).
    fn with_element(
        modulus: &Prony,
        poisson: f64,
        radius: f64,
        load: f64,
        settings: SphereSettings,
        element: Element,
    ) -> Result<Self, ModelError> {
        super::check_body(poisson, radius, load)?;
        if settings.cells < 8 || settings.quadrature_order < 4 {
            return Err(ModelError::ExactTooCoarse);
        }
        Ok(RollingSphere {
            compliance: CreepCompliance::from_prony(modulus).scaled(1.0 - poisson * poisson),
            radius,
            load,
            settings,
            element,
        })
    }

    /// The same sphere with `cells` across the contact diameter.
    pub fn with_cells(&self, cells: usize) -> Self {
        let mut sphere = self.clone();
        sphere.settings.cells = cells.max(8);
        sphere
    }

    /// The settings.
    pub fn settings(&self) -> &SphereSettings {
        &self.settings
    }

    /// Hertz radius r0 (m) with the static effective modulus (plane
    /// strain: the half-width a0).
    pub fn static_contact_radius(&self) -> f64 {
        hertz_contact_size(
            self.element.shape(),
            self.radius,
            self.load,
            1.0 / self.compliance.equilibrium(),
        )
    }

    /// The contact radius expected at speed v: Hertz with the compliance
    /// after the contact time 2r/v, iterated.
    fn expected_radius(&self, v: f64) -> f64 {
        let mut r = self.static_contact_radius();
        for _ in 0..4 {
            let j = self.compliance.at(2.0 * r / v);
            r = hertz_contact_size(self.element.shape(), self.radius, self.load, 1.0 / j);
        }
        r
    }

    /// The steady rolling contact at speed `v` (m/s), on three grids of
    /// N₃ = ⌈⅔N₂⌉, N₂ = ⌈⅔N₁⌉ and N₁ (the settings') cells, each solve
    /// started from the previous one.
    ///
    /// μ is Richardson-extrapolated from the two finer grids, with the
    /// formal order 2 of piecewise-constant collocation where the memory
    /// is resolved: μ₁₂ = (r²μ₁ − μ₂)/(r² − 1), r = N₁/N₂ = 1.5. Its
    /// error is estimated from the difference to the extrapolation of the
    /// two coarser grids: if what the extrapolation leaves is C h³, the
    /// error of μ₁₂ is |μ₁₂ − μ₂₃|/(r³ − 1) (the usual Richardson estimate
    /// of the next order). Where the memory vλ_j of retardation terms is
    /// shorter than a cell the error falls only like h (measured: order
    /// 0.9 at vτ/r0 = 1e-5, E1/E0 = 10), the two extrapolations hardly
    /// differ, and that share of the creep is charged instead the error
    /// μ₁₂ has under first order, (μ₁ − μ₂)(1/(r − 1) − 1/(r² − 1)). The
    /// complementarity defects of unsettled grid solutions (0 where the
    /// sets settled) are added.
    ///
    /// Measured against the extrapolation of 144 and 216 cells (E1/E0 =
    /// 10 and 100, vτ/r0 = 0.01 … 100, 96 cells): the estimate is 0.3 …
    /// 5 times the error (BENCHMARKS.md); the step μ₁₂ − μ₁ alone is no
    /// estimate: it is up to 10 times pessimistic at moderate speeds and 2
    /// times optimistic at vτ/r0 = 1e-5.
    pub fn solve(&self, v: f64) -> Result<SphereSolution, ModelError> {
        Ok(self.solve_from(v, None)?.0)
    }

    /// The cells of the three grids of [`Self::solve`], finest first.
    fn grid_cells(&self) -> [usize; 3] {
        let n1 = self.settings.cells;
        let n2 = (2 * n1).div_ceil(3).max(8);
        let n3 = (2 * n2).div_ceil(3).max(8);
        [n1, n2, n3]
    }

    /// μ of [`Self::solve`] from the three grid solutions `[g1, g2, g3]`
    /// (finest first) at speed `v` on the `scale` (m), with its error
    /// estimate: g1 with the extrapolated μ.
    fn extrapolated(&self, v: f64, scale: f64, grids: [SphereSolution; 3]) -> SphereSolution {
        let [mut g1, g2, g3] = grids;
        let [n1, n2, n3] = self.grid_cells();
        let (mu12, defect12) = extrapolate(&g1, &g2, n1, n2);
        let (mu23, _) = extrapolate(&g2, &g3, n2, n3);
        // The error estimate (see above): next-order Richardson, at least
        // the first-order error for the creep whose memory is shorter
        // than a cell.
        let cell = 2.0 * scale / n1 as f64;
        let unresolved = self.unresolved_share(v, cell);
        let r = n1 as f64 / n2 as f64;
        let first_order = (g1.mu - g2.mu) * (1.0 / (r - 1.0) - 1.0 / (r * r - 1.0));
        let remainder = (mu12 - mu23).abs() / (r.powi(3) - 1.0);
        let grid_error = remainder.max(unresolved * first_order.abs());
        // (An elastic solid has μ = 0 on every grid, and no error.)
        let relative = if grid_error == 0.0 {
            0.0
        } else {
            grid_error / mu12.abs()
        };
        g1.error_estimate = relative + defect12;
        g1.set_defect = g1.set_defect.max(g2.set_defect).max(g3.set_defect);
        g1.mu = mu12;
        g1.centroid = mu12 * self.radius;
        g1
    }

    /// The share of the creep compliance Σ c_j whose memory vλ_j is
    /// shorter than `cell` (m) at speed `v`.
    fn unresolved_share(&self, v: f64, cell: f64) -> f64 {
        let c = &self.compliance;
        let total: f64 = c.strengths.iter().sum();
        let short: f64 = c
            .strengths
            .iter()
            .zip(&c.retardation_times)
            .filter(|(_, lambda)| v * **lambda < cell)
            .map(|(s, _)| s)
            .sum();
        if total > 0.0 { short / total } else { 0.0 }
    }

    /// The contact at speed v on a grid of `cells`, by continuation in the
    /// speed where the active-set iteration does not settle from Hertz.
    ///
    /// The primal–dual active-set iteration is a semismooth Newton method
    /// (Hintermüller, Ito & Kunisch 2003): it converges fast from a start
    /// near the answer but may cycle from a far one. At low speed on a
    /// stiff solid (E1/E0 ≳ 100) the contact is a crescent on the leading
    /// side with a glassy edge layer, far from the centred Hertz circle,
    /// and the iteration wanders. The speed is then raised by
    /// [`CONTINUATION_STEP`] (toward the glassy limit, where the contact
    /// is the elastic Hertz one and the iteration settles) until it
    /// settles, and the solution carried back down step by step, each
    /// solve started from the previous one.
    fn solve_continued(
        &self,
        v: f64,
        cells: usize,
        depth: usize,
    ) -> Result<(SphereSolution, (f64, f64)), ModelError> {
        let scale = self.expected_radius(v);
        let cold = self.solve_growing(v, scale, cells, (1.35, 1.2), None);
        let unsettled = match &cold {
            Ok((solution, _)) => solution.set_defect > 0.0,
            Err(ModelError::ExactSphereNotConverged { .. }) => true,
            Err(_) => false,
        };
        if !unsettled || depth >= MAX_CONTINUATION {
            return cold;
        }
        let (previous, extent) = self.solve_continued(v * CONTINUATION_STEP, cells, depth + 1)?;
        let warm = self.solve_growing(v, scale, cells, extent, Some(&previous));
        // Keep the warm solve unless it failed or settled no better.
        match (cold, warm) {
            (Ok(cold), Ok(warm)) if cold.0.set_defect < warm.0.set_defect => Ok(cold),
            (Ok(cold), Err(_)) => Ok(cold),
            (_, warm) => warm,
        }
    }

    /// The contact on one grid of `cells` across the expected diameter
    /// (no extrapolation; `error_estimate` NaN).
    pub fn solve_single(&self, v: f64, cells: usize) -> Result<SphereSolution, ModelError> {
        require_positive("v", v)?;
        let scale = self.expected_radius(v);
        Ok(self
            .solve_growing(v, scale, cells.max(8), (1.35, 1.2), None)?
            .0)
    }

    /// [`Self::solve_on`], with the grid enlarged while the contact
    /// reaches its border; also returns the extent used.
    fn solve_growing(
        &self,
        v: f64,
        scale: f64,
        cells: usize,
        mut extent: (f64, f64),
        start: Option<&SphereSolution>,
    ) -> Result<(SphereSolution, (f64, f64)), ModelError> {
        loop {
            match self.solve_on(v, scale, cells, extent, start) {
                Err(GridFailure::TooSmall) if extent.0 < 4.0 => {
                    extent = (extent.0 * 1.3, extent.1 * 1.3);
                }
                Err(GridFailure::TooSmall) => {
                    return Err(ModelError::ExactSphereNotConverged { speed: v });
                }
                Err(GridFailure::NotConverged) => {
                    return Err(ModelError::ExactSphereNotConverged { speed: v });
                }
                Ok(solution) => return Ok((solution, extent)),
            }
        }
    }

    /// The contact at speed v on a grid of cell side 2·scale/cells covering
    /// |x| ≤ extent.0·scale, |y| ≤ extent.1·scale, started from `start`
    /// (a coarser solution) or from Hertz.
    fn solve_on(
        &self,
        v: f64,
        scale: f64,
        cells: usize,
        extent: (f64, f64),
        start: Option<&SphereSolution>,
    ) -> Result<SphereSolution, GridFailure> {
        let j_ref = self.compliance.equilibrium();
        let h = 2.0 / cells as f64;
        let nx = (2.0 * extent.0 / h).ceil() as usize;
        let ny = match self.element {
            Element::Square => (2.0 * extent.1 / h).ceil() as usize,
            Element::Strip => 1,
        };
        let grid = Grid {
            nx,
            ny,
            h,
            x0: -0.5 * (nx - 1) as f64 * h,
            y0: -0.5 * (ny - 1) as f64 * h,
            element: self.element,
        };
        let table = cell_table(nx, ny, self.settings.quadrature_order, self.element);
        let width = table.width();
        let mut influence: Vec<f64> = table
            .elastic
            .iter()
            .map(|c| self.compliance.instantaneous / j_ref * c)
            .collect();
        for (c, lambda) in self
            .compliance
            .strengths
            .iter()
            .zip(&self.compliance.retardation_times)
        {
            let ell = v * lambda / (h * scale);
            let weight = c / j_ref;
            for (a, m) in influence.iter_mut().zip(table.memory(ell)) {
                *a += weight * m;
            }
        }
        let operator = Convolution::new(nx, ny, |x, y| {
            h * influence[y * width + (x + nx as isize - 1) as usize]
        });
        // F R J / r³ (sphere), W R J / a² (strip).
        let load = self.load * self.radius * j_ref / (scale * self.element.measure(scale));
        let guess: Vec<f64> = match start {
            Some(coarse) => {
                let lookup = CoarseLookup::new(coarse, scale);
                (0..nx * ny)
                    .map(|k| {
                        let (x, y) = grid.centre(k);
                        lookup.at(x, y) / (scale / (self.radius * j_ref))
                    })
                    .collect()
            }
            None => {
                let p0 = self.element.hertz_peak(load);
                (0..nx * ny)
                    .map(|k| {
                        let (x, y) = grid.centre(k);
                        p0 * (1.0 - x * x - y * y).max(0.0).sqrt()
                    })
                    .collect()
            }
        };
        let active: Vec<bool> = guess.iter().map(|&p| p > 0.0).collect();
        let solved = solve_contact(&grid, &operator, load, active, &guess, SET_BUDGET)?;
        Ok(self.dimensional(v, scale, &grid, solved))
    }

    /// The grid solution in SI units.
    fn dimensional(
        &self,
        v: f64,
        scale: f64,
        grid: &Grid,
        solved: contact::GridContact,
    ) -> SphereSolution {
        let j_ref = self.compliance.equilibrium();
        let pressure_unit = scale / (self.radius * j_ref);
        let total: f64 = solved.pressure.iter().sum();
        let moment: f64 = solved
            .pressure
            .iter()
            .enumerate()
            .map(|(k, p)| grid.centre(k).0 * p)
            .sum();
        let centroid = scale * moment / total;
        let mut pressure_map = Vec::new();
        for (k, &p) in solved.pressure.iter().enumerate() {
            if p > 0.0 {
                let (x, y) = grid.centre(k);
                pressure_map.push((x * scale, y * scale, p * pressure_unit));
            }
        }
        let outline = outline(grid, &solved.pressure)
            .into_iter()
            .map(|(y, a, b)| (y * scale, a * scale, b * scale))
            .collect();
        let cells_in_contact = pressure_map.len();
        SphereSolution {
            speed: v,
            mu: centroid / self.radius,
            centroid,
            approach: solved.approach * scale * scale / self.radius,
            area: cells_in_contact as f64 * self.element.measure(grid.h * scale),
            max_pressure: solved.pressure.iter().copied().fold(0.0, f64::max) * pressure_unit,
            cell: grid.h * scale,
            pressure_map,
            outline,
            iterations: solved.iterations,
            operator_applications: solved.applications,
            error_estimate: f64::NAN,
            set_defect: solved.defect,
        }
    }
}

/// The pressure of a coarser solution at any point, by the cell that holds
/// it: cell centres lie on multiples of half a cell side, so twice the
/// coordinate in cell sides, rounded, names a cell.
struct CoarseLookup {
    cells: std::collections::HashMap<(i64, i64), f64>,
    /// Coarse cell side in units of the scale.
    h: f64,
    /// Parities of the doubled centre coordinates.
    parity: (i64, i64),
}

impl CoarseLookup {
    fn new(coarse: &SphereSolution, scale: f64) -> Self {
        let h = coarse.cell / scale;
        let key = |x: f64, y: f64| {
            (
                (2.0 * x / scale / h).round() as i64,
                (2.0 * y / scale / h).round() as i64,
            )
        };
        let cells: std::collections::HashMap<_, _> = coarse
            .pressure_map
            .iter()
            .map(|&(x, y, p)| (key(x, y), p))
            .collect();
        let parity = cells
            .keys()
            .next()
            .map_or((0, 0), |&(a, b)| (a.rem_euclid(2), b.rem_euclid(2)));
        CoarseLookup { cells, h, parity }
    }

    /// The coarse pressure (Pa) at (x, y) in units of the scale.
    fn at(&self, x: f64, y: f64) -> f64 {
        let nearest = |t: f64, parity: i64| {
            ((t / self.h * 2.0 - parity as f64) / 2.0).round() as i64 * 2 + parity
        };
        let key = (nearest(x, self.parity.0), nearest(y, self.parity.1));
        self.cells.get(&key).copied().unwrap_or(0.0)
    }
}

/// Active-set corrections allowed on one grid: from a good start the
/// iteration settles in a handful (measured: 4–10), so a solve that has
/// not settled after this many is wandering and is better restarted by
/// continuation than continued.
const SET_BUDGET: usize = 30;

/// The factor between consecutive speeds of the continuation.
const CONTINUATION_STEP: f64 = 2.0;

/// Continuation steps allowed: 2^20 ≈ 1e6 in speed, from the lowest
/// speeds of interest (vτ/r0 ~ 1e-5) past the friction maximum.
const MAX_CONTINUATION: usize = 20;

/// μ extrapolated in h² from a fine and a coarse grid solution of `fine`
/// and `coarse` cells, and the share of it the grids' complementarity
/// defects may cause (each weighted as the extrapolation weights μ).
fn extrapolate(
    fine: &SphereSolution,
    coarse: &SphereSolution,
    fine_cells: usize,
    coarse_cells: usize,
) -> (f64, f64) {
    let r2 = (fine_cells as f64 / coarse_cells as f64).powi(2);
    let mu = (r2 * fine.mu - coarse.mu) / (r2 - 1.0);
    let defect = (r2 * fine.set_defect + coarse.set_defect) / (r2 - 1.0);
    (mu, defect)
}

/// Per row with cells in contact: y and the trailing and leading edges,
/// where p² — linear in the distance to a square-root edge — extrapolated
/// from the last two cells of the row reaches zero (within one cell).
fn outline(grid: &Grid, pressure: &[f64]) -> Vec<(f64, f64, f64)> {
    let mut rows = Vec::new();
    for j in 0..grid.ny {
        let row = &pressure[j * grid.nx..(j + 1) * grid.nx];
        let (Some(first), Some(last)) = (
            row.iter().position(|&p| p > 0.0),
            row.iter().rposition(|&p| p > 0.0),
        ) else {
            continue;
        };
        let x = |i: usize| grid.x0 + i as f64 * grid.h;
        let edge = |outer: usize, inner: usize, sign: f64| {
            let (a, b) = (row[outer].powi(2), row[inner].max(0.0).powi(2));
            let step = if b > a { a / (b - a) } else { 0.5 };
            x(outer) + sign * grid.h * step.min(1.0)
        };
        let trailing = if last > first {
            edge(first, first + 1, -1.0)
        } else {
            x(first) - 0.5 * grid.h
        };
        let leading = if last > first {
            edge(last, last - 1, 1.0)
        } else {
            x(last) + 0.5 * grid.h
        };
        rows.push((grid.y0 + j as f64 * grid.h, trailing, leading));
    }
    rows
}
