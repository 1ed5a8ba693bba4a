//! The exact steady rolling of a rigid cylinder on a viscoelastic half-space
//! (plane strain, frictionless, non-adhesive): the reference that Persson's
//! Eq. (11) approximates.
//!
//! # Formulation
//!
//! The cylinder (radius R, load f_N per unit length) rolls at speed v in the
//! +x direction; x is measured from its axis, so the leading edge is at
//! x = a2 > 0 and the trailing one at a1 < 0. The solid's effective creep
//! compliance is J_eff(t) = (1 − ν²) J(t) with, for a Prony series
//! ([`CreepCompliance`]), J(t) = 1/E1 + Σ_j c_j (1 − e^{−t/λ_j}). In the
//! frame moving with the cylinder the surface displacement into the solid
//! is u(x) = ∫ G(x − s) p(s) ds with
//!
//!   G(x) = J_eff(0) G0(x) + ∫_0^∞ J̇_eff(t) G0(x + vt) dt,  G0(x) = −(2/π) ln|x|
//!
//! (Hunter 1961; Johnson §7.6): the material point now at x was at x + vt a
//! time t ago. Inside the contact u = δ − x²/(2R); its derivative removes
//! the approach δ:
//!
//!   (2/π) [J_eff(0) PV∫ p(s) ds/(x − s) + Σ_j c_j (1/ℓ_j) ∫_0^∞ e^{−ξ/ℓ_j} H(x + ξ) dξ] = x/R,
//!
//! with ℓ_j = vλ_j and H(y) = PV∫ p(s) ds/(y − s). Non-adhesive contact
//! means p → 0 at both edges (p ≥ 0 inside, gap ≥ 0 outside follow for the
//! solution with edges chosen this way).
//!
//! # Method
//!
//! Gauss–Chebyshev collocation with unknown edges (Erdogan & Gupta 1972):
//! x = c + bt, p = b √(1 − t²) Σ_{n<N} α_n U_n(t), for which H is known in
//! closed form inside and outside the contact; the memory integrals of the
//! basis reduce to smooth one-dimensional integrals (see `kernel.rs`,
//! which sums them over the retardation times in closed-form series where
//! the memory is much shorter or much longer than the contact, so that a
//! 200-term Prony series costs about 0.2 s per speed instead of 15 s). The
//! equation is collocated at the N + 1 zeros of T_{N+1} with one extra
//! unknown, a tilt c0 added to the right-hand side: a pressure bounded at
//! both edges exists only where c0 = 0. Newton's method on (c, b) then
//! solves c0 = 0 and (π/2) b² α_0 = f_N (the matrix depends on b alone, so
//! the c-derivative reuses its factorisation). The solution φ(t) is analytic on
//! [−1, 1], but the memory puts boundary layers at the edges: the material
//! entering the contact stays near its glassy compliance for the glassy
//! time t_g = J(0)/J̇(0) (for a standard linear solid the relaxation time
//! τE0/E1, far shorter than the retardation time τ when E1/E0 is large),
//! so the layers have relative width δ = v t_g/b. Chebyshev series resolve
//! them with N ∝ δ^{−1/2} and then converge exponentially; the default
//! chooses N = ⌈3.5 δ^{−1/2}⌉ in [24, 128] (see
//! [`ExactSettings::automatic_terms`]), which gives μ to about 1e-6. Where
//! that N would exceed `max_terms` — very low speed, and for large E1/E0
//! up to about a decade below the friction maximum (E1/E0 = 1000:
//! vτ/a0 ≲ 0.5) — the series cannot resolve the layers (at N = 128 μ was
//! off by up to 5 % for E1/E0 = 1e4, and beyond N ≈ 200 the dense
//! collocation loses accuracy), and the graded mesh below takes over.
//!
//! # Thin edge layers
//!
//! Write F(t) = H(c + bt)/(bπ) for the Hilbert transform of the pressure
//! inside the contact (F = Σ α_n T_{n+1}). The equation is then of the
//! second kind in F:
//!
//!   J_eff(0) F + Σ_j c_j \[V_j F + e^{−β_j(1 − t)} O_j\[F\]\] = (c + bt)/(2bR),
//!   V_j F(t) = β_j ∫_t^1 e^{−β_j(s − t)} F(s) ds,  β_j = b/(vλ_j),
//!
//! a Volterra operator from the leading edge plus, for each term, the
//! memory of the material's path outside the contact, O_j\[F\] =
//! β_j ∫_1^∞ e^{−β_j(s − 1)} F_out(s) ds, where the bounded continuation is
//! F_out(s) = (√(s² − 1)/π) ∫ F(τ) dτ/(√(1 − τ²)(s − τ)) (the pressure is
//! bounded at both edges iff ∫ F dτ/√(1 − τ²) = 0). Applying Π_j(1 − ℓ_j
//! d/dx) shows what the layers are: inside the contact
//!
//!   F(t) = A t + B + Σ_k C_k e^{−κ_k(1 − t)},  κ_k = b/(vτ_k),
//!
//! one exponential for each relaxation time τ_k of the modulus (the zeros
//! of J̃(s) = J(0) + Σ_j c_j/(1 + sλ_j) lie at s = −1/τ_k): the layers are
//! v τ_k wide, the thinnest v τ_min, and sit at the leading edge only
//! (in the pressure they become √-shaped edge layers of relative width
//! δ_k = vτ_k/b, hence N ∝ δ^{−1/2} above). F itself is smooth in t, so it
//! is collocated at Gauss–Legendre nodes on panels graded geometrically
//! from the leading edge, in u = 1 − t: the first 0.1 vτ_min/b wide, each
//! next 2.5 times wider up to 0.5 (`cylinder_mesh.rs`); with q = 8 nodes
//! per panel (`panel_nodes`) that is 100 … 300 nodes. The Volterra
//! integrals are stepped from node to node on the panels' Lagrange basis,
//! and where a memory is short against a panel they are the terminating
//! series Σ_k (−1/β_j)^k P^{(k)} of the panel's polynomial P, summed over
//! all such terms at once (`cylinder_graded.rs`): a 200-term Prony series
//! costs about 0.1 … 0.2 s per speed. For F in hand the centre follows
//! from the consistency condition (c enters the right-hand side only) and
//! b from the load by the secant method; α_0 and α_1 are integrals of F
//! against T_1, T_2. μ agrees with the semi-analytic solution of a
//! standard linear solid (A, B, C from three conditions; tests) to ≤ 6e-8
//! for E1/E0 = 2 … 1e5 down to vτ/a0 = 1e-5, at 3 … 5 ms per speed (about
//! twice that with the a-posteriori error estimate).
//!
//! Outputs: the load ∫p = (π/2) b² α_0 and the centroid
//! x̄ = c + π b³ α_1/(4 f_N) are exact for the discrete pressure;
//! μ = x̄/R (Persson 2010, Section 4: the moment of the pressure equals the
//! rolling-resistance moment), positive for a pressure shifted to the
//! leading side.
//!
//! # References
//! - S.C. Hunter, "The rolling contact of a rigid cylinder with a
//!   viscoelastic half space", J. Appl. Mech. 28 (1961) 611–617.
//! - G. Carbone, C. Putignano, "A novel methodology to predict sliding and
//!   rolling friction of viscoelastic materials: theory and experiments",
//!   J. Mech. Phys. Solids 61 (2013) 1822–1834.
//! - K.L. Johnson, *Contact Mechanics*, Cambridge 1985, §2.7 (inversion of
//!   the singular integral equation), §6 and §7.6 (rolling on viscoelastic
//!   solids).
//! - F. Erdogan, G.D. Gupta, "On the numerical solution of singular integral
//!   equations", Q. Appl. Math. 29 (1972) 525–534.
//! - F.G. Tricomi, *Integral Equations*, Interscience 1957, ch. IV (the
//!   finite Hilbert transform, its bounded inversion and the Cauchy
//!   integral off the interval).
//! - H. Brunner, *Collocation Methods for Volterra Integral and Related
//!   Functional Equations*, Cambridge 2004, ch. 2 (piecewise polynomial
//!   collocation of second-kind Volterra equations).
//! - J.-P. Berrut, L.N. Trefethen, "Barycentric Lagrange interpolation",
//!   SIAM Rev. 46 (2004) 501–517.
//! - B.N.J. Persson, Eur. Phys. J. E 33 (2010) 327–333, Eq. (11).

mod body;
mod creep;
mod cylinder_graded;
mod cylinder_mesh;
mod cylinder_pressure;
mod kernel;
mod pressure_map;
mod solver;
mod sphere;

pub use body::{ExactFriction, ExactRolling, ExactStart, exact_body};
pub use creep::{CreepCompliance, NEGLIGIBLE_SHARE};
pub use pressure_map::{CYLINDER_PROFILE_POINTS, ContactPressure, PressureMap};
pub use sphere::{RollingSphere, SphereSettings, SphereSolution};

use std::f64::consts::PI;

use crate::contact::{Shape, hertz_contact_size};
use crate::error::{ModelError, require_positive};
use crate::modulus::Prony;
use cylinder_graded::{GradedContact, GradedSolution};
use cylinder_pressure::PressureProfile;
use kernel::MemoryQuadrature;
use std::sync::Arc;

/// Discretisation settings of the exact solution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExactSettings {
    /// Number N of Chebyshev terms of the pressure; `None` chooses it from
    /// the speed (see [`ExactSettings::automatic_terms`]).
    pub terms: Option<usize>,
    /// Upper bound of the automatic N; where the layers need more terms,
    /// the graded mesh is used instead.
    pub max_terms: usize,
    /// C in the automatic N = ⌈C δ^{−1/2}⌉, from 1.5 to 3.5; the grid error
    /// it buys where N is not capped is [`ExactSettings::resolved_error`].
    pub layer_resolution: f64,
    /// Gauss–Legendre nodes per panel of the memory integrals.
    pub quadrature_order: usize,
    /// Relative convergence tolerance of the contact edges.
    pub tolerance: f64,
    /// Gauss nodes q per panel of the graded mesh, used where the automatic
    /// N would exceed `max_terms` (see the module documentation, "Thin edge
    /// layers"): q = 8 gives μ to better than 1e-7 (the error estimate
    /// compares with q + 2).
    pub panel_nodes: usize,
}

impl ExactSettings {
    /// The default C: μ to about 1e-6 where N is not capped.
    pub const LAYER_RESOLUTION: f64 = 3.5;

    /// The error of μ claimed for a layer resolution C where N is not
    /// capped: 1e-3·e^{−4(C − 1.5)}, at least 1e-5. Measured against 192
    /// terms (standard linear solids E1/E0 = 2 … 1000, random Prony
    /// series; tests/exact_cylinder.rs): ≤ 5.7e-4 at C = 1.5, ≤ 6e-5 at 2,
    /// ≤ 3e-7 at 3 and ≤ 3.6e-7 at 3.5.
    pub fn resolved_error(&self) -> f64 {
        (1e-3 * (-4.0 * (self.layer_resolution - 1.5)).exp()).max(RESOLVED_ERROR)
    }

    /// The layer resolution C whose claimed error is at most `error`
    /// (clamped to the calibrated 1.5 … 3.5).
    pub fn resolution_for(error: f64) -> f64 {
        (1.5 + (1e-3 / error).ln() / 4.0).clamp(1.5, Self::LAYER_RESOLUTION)
    }

    /// The automatic number of terms for a layer length ℓ = v t_g (t_g the
    /// glassy time, see [`RollingCylinder::resolves_edge_layers`]) and
    /// contact half-width b: the pressure has boundary layers of relative
    /// width δ = ℓ/b at the edges, which Chebyshev series resolve with
    /// N ∝ δ^{−1/2}; N = ⌈C δ^{−1/2}⌉ clamped to [24, `max_terms`]. Also
    /// returns whether that N resolves the layers, i.e. was not held at
    /// `max_terms`.
    pub fn automatic_terms(&self, layer_length: f64, half_width: f64) -> (usize, bool) {
        let delta = layer_length / half_width;
        let n = (self.layer_resolution / delta.sqrt()).ceil();
        if n.is_finite() {
            let cap = self.max_terms.max(24);
            ((n as usize).clamp(24, cap), n <= cap as f64)
        } else {
            (24, true)
        }
    }
}

/// How one speed is discretised.
struct Discretisation {
    /// Starting half-width of Newton's method, m.
    half_width: f64,
    /// Chebyshev terms.
    terms: usize,
    /// Whether they resolve the edge layers (explicit terms count as such).
    resolved: bool,
}

/// Where the secant for the half-width on the graded mesh starts.
#[derive(Debug, Clone, Copy)]
enum GradedStart {
    /// A Hertz estimate, m.
    Guess(f64),
    /// The root on another mesh, m.
    Root(f64),
}

impl Default for ExactSettings {
    fn default() -> Self {
        ExactSettings {
            terms: None,
            max_terms: 128,
            layer_resolution: Self::LAYER_RESOLUTION,
            quadrature_order: 24,
            tolerance: 1e-12,
            panel_nodes: 8,
        }
    }
}

/// A rigid cylinder rolling on a viscoelastic half-space (plane strain).
#[derive(Debug, Clone)]
pub struct RollingCylinder {
    compliance: CreepCompliance,
    /// The shortest relaxation time τ_min of the modulus, s: its edge layer,
    /// v τ_min wide, is the thinnest the graded mesh must resolve.
    shortest_relaxation: f64,
    radius: f64,
    load: f64,
    settings: ExactSettings,
    quadrature: MemoryQuadrature,
}

/// The steady rolling contact at one speed.
#[derive(Debug, Clone, PartialEq)]
pub struct RollingSolution {
    /// Rolling speed v, m/s.
    pub speed: f64,
    /// Friction (rolling-resistance) coefficient μ = x̄/R.
    pub mu: f64,
    /// Pressure centroid x̄ relative to the axis, m (> 0: leading side).
    pub centroid: f64,
    /// Trailing edge a1, m (relative to the axis).
    pub trailing_edge: f64,
    /// Leading edge a2, m.
    pub leading_edge: f64,
    /// Chebyshev coefficients α_n: p = b √(1 − t²) Σ α_n U_n(t), 1/(Pa·m)·Pa.
    /// On the graded mesh, the first N (the capped automatic count) of the
    /// series of its pressure: α_0 and α_1 give the load and the centroid
    /// exactly, the truncated series is not the pressure near a thin layer
    /// (see [`Self::pressure`]).
    pub coefficients: Vec<f64>,
    /// Newton (Chebyshev) or secant (graded mesh) iterations used.
    pub iterations: usize,
    /// Whether the automatic Chebyshev terms resolved the pressure's edge
    /// layers ([`RollingCylinder::resolves_edge_layers`]; explicit terms
    /// count as resolved). Where they would not, the solution comes from the
    /// graded mesh (`method`), which resolves them: see `error_estimate`.
    pub resolved: bool,
    /// How the solution was discretised.
    pub method: ExactMethod,
    /// On the graded mesh: F there, for [`Self::pressure`].
    profile: Option<Arc<PressureProfile>>,
    /// Estimated relative error of μ from the discretisation: the claimed
    /// [`ExactSettings::resolved_error`] with Chebyshev terms (NaN with
    /// explicit `terms`: not estimated); on the graded mesh [`GRADED_ERROR`],
    /// or from [`RollingCylinder::solve_with_error_estimate`] twice the
    /// change of μ from q to q + 2 nodes per panel (at least
    /// [`GRADED_FLOOR`]).
    pub error_estimate: f64,
}

/// The discretisation of a [`RollingSolution`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExactMethod {
    /// Gauss–Chebyshev collocation, as many terms as
    /// [`RollingSolution::coefficients`].
    Chebyshev,
    /// Collocation of the Hilbert transform of the pressure on the mesh
    /// graded toward the leading edge, with this many nodes.
    GradedMesh {
        /// Mesh nodes.
        nodes: usize,
    },
}

impl RollingSolution {
    /// Contact centre c = (a1 + a2)/2, m.
    pub fn center(&self) -> f64 {
        0.5 * (self.trailing_edge + self.leading_edge)
    }

    /// Contact half-width b = (a2 − a1)/2, m.
    pub fn half_width(&self) -> f64 {
        0.5 * (self.leading_edge - self.trailing_edge)
    }

    /// The pressure p(x), Pa (zero outside the contact): the Chebyshev
    /// series, or on the graded mesh the inversion of F there (the series
    /// of `coefficients` is then only its truncation, see
    /// `cylinder_pressure.rs`).
    pub fn pressure(&self, x: f64) -> f64 {
        let b = self.half_width();
        if let Some(profile) = &self.profile {
            // u = 1 − t from the leading edge keeps the digits of thin layers.
            let u = (self.leading_edge - x) / b;
            return if u > 0.0 && u < 2.0 {
                b * profile.reduced_pressure(u)
            } else {
                0.0
            };
        }
        let t = (x - self.center()) / b;
        if t.abs() >= 1.0 {
            return 0.0;
        }
        // Σ α_n U_n(t) by Clenshaw's recurrence.
        let (mut b1, mut b2) = (0.0, 0.0);
        for &a in self.coefficients.iter().rev() {
            let b0 = a + 2.0 * t * b1 - b2;
            b2 = b1;
            b1 = b0;
        }
        b * (1.0 - t * t).sqrt() * b1
    }

    /// The pressure on `points` equally spaced positions from a1 to a2:
    /// (x, p(x)).
    pub fn pressure_profile(&self, points: usize) -> Vec<(f64, f64)> {
        let n = points.max(2);
        (0..n)
            .map(|i| {
                let x = self.trailing_edge
                    + (self.leading_edge - self.trailing_edge) * i as f64 / (n - 1) as f64;
                (x, self.pressure(x))
            })
            .collect()
    }

    /// ∫ p dx, N/m, of the discrete pressure (exact for the series).
    pub fn load(&self) -> f64 {
        let b = self.half_width();
        0.5 * PI * b * b * self.coefficients[0]
    }
}

impl RollingCylinder {
    /// A cylinder of radius `radius` (m) under load `load` (N/m) on a solid
    /// with Prony modulus `modulus` and Poisson ratio `poisson`, with the
    /// default settings. A standard linear solid enters through
    /// [`crate::StandardLinearSolid::to_prony`].
    pub fn new(modulus: &Prony, poisson: f64, radius: f64, load: f64) -> Result<Self, ModelError> {
        Self::with_settings(modulus, poisson, radius, load, ExactSettings::default())
    }

    /// As [`Self::new`] with explicit settings.
    pub fn with_settings(
        modulus: &Prony,
        poisson: f64,
        radius: f64,
        load: f64,
        settings: ExactSettings,
    ) -> Result<Self, ModelError> {
        check_body(poisson, radius, load)?;
        if !(1.5..=ExactSettings::LAYER_RESOLUTION).contains(&settings.layer_resolution) {
            return Err(ModelError::parameter(
                "layer_resolution",
                settings.layer_resolution,
                "must lie between 1.5 and 3.5 (the calibrated range)",
            ));
        }
        if settings.terms.is_some_and(|n| n < 2)
            || settings.quadrature_order < 4
            || settings.panel_nodes < 4
        {
            return Err(ModelError::ExactTooCoarse);
        }
        let compliance = CreepCompliance::from_prony(modulus).scaled(1.0 - poisson * poisson);
        let shortest_relaxation = modulus
            .relaxation_times()
            .iter()
            .zip(modulus.strengths())
            .filter(|(_, h)| **h > 0.0)
            .map(|(t, _)| *t)
            .fold(f64::INFINITY, f64::min);
        Ok(RollingCylinder {
            compliance,
            shortest_relaxation,
            radius,
            load,
            settings,
            quadrature: MemoryQuadrature::new(settings.quadrature_order, 0.5),
        })
    }

    /// The same cylinder with the automatic term count's layer resolution
    /// set to C (clamped to 1.5 … 3.5): fewer terms for a looser accuracy.
    pub fn with_layer_resolution(&self, resolution: f64) -> Self {
        let mut cylinder = self.clone();
        cylinder.settings.layer_resolution = resolution.clamp(1.5, ExactSettings::LAYER_RESOLUTION);
        cylinder
    }

    /// The settings.
    pub fn settings(&self) -> &ExactSettings {
        &self.settings
    }

    /// The effective (plane-strain) creep compliance, 1/Pa.
    pub fn compliance(&self) -> &CreepCompliance {
        &self.compliance
    }

    /// Hertz half-width a0 (m) with the static effective modulus E_eff(0).
    pub fn static_half_width(&self) -> f64 {
        hertz_contact_size(
            Shape::Cylinder,
            self.radius,
            self.load,
            1.0 / self.compliance.equilibrium(),
        )
    }

    /// Hertz half-width (m) with the glassy effective modulus E_eff(∞).
    pub fn glassy_half_width(&self) -> f64 {
        hertz_contact_size(
            Shape::Cylinder,
            self.radius,
            self.load,
            1.0 / self.compliance.instantaneous,
        )
    }

    /// The starting half-width, the number of Chebyshev terms and whether
    /// they resolve the edge layers at speed `v` (m/s).
    fn discretisation(&self, v: f64) -> Discretisation {
        // Start from Hertz with the compliance the contact time a/v sees.
        let mut b = self.static_half_width();
        for _ in 0..3 {
            let j = self.compliance.at(2.0 * b / v);
            b = hertz_contact_size(Shape::Cylinder, self.radius, self.load, 1.0 / j);
        }
        let (terms, resolved) = match self.settings.terms {
            Some(n) => (n, true),
            None => self.settings.automatic_terms(v * self.glassy_time(), b),
        };
        Discretisation {
            half_width: b,
            terms,
            resolved,
        }
    }

    /// The glassy time t_g = J(0)/J̇(0) = J(0)/Σ_j (c_j/λ_j), s: how long
    /// material entering the contact stays near its glassy compliance. It
    /// sets the width v·t_g of the pressure's edge layer: where the memory
    /// dominates (c_j ≫ J(0), large E1/E0) the equation J(0)h + c M\[h\] = g
    /// is nearly of the first kind, and its inverse has a layer of width
    /// ℓ J(0)/c = v λ J(0)/c at the leading edge — for a standard linear
    /// solid v times the relaxation time τE0/E1, not the retardation time τ.
    fn glassy_time(&self) -> f64 {
        let rate: f64 = self
            .compliance
            .strengths
            .iter()
            .zip(&self.compliance.retardation_times)
            .map(|(c, l)| c / l)
            .sum();
        self.compliance.instantaneous / rate
    }

    /// Whether the automatic number of Chebyshev terms resolves the
    /// pressure's edge layers at speed `v` (m/s), i.e. is not held at
    /// `max_terms`: then μ is grid-converged to about 1e-6
    /// (tests/exact_cylinder.rs). Where it would be held, [`Self::solve`]
    /// uses the graded mesh instead (module documentation, "Thin edge
    /// layers"). Explicit `terms` count as resolved: their accuracy is the
    /// caller's choice.
    pub fn resolves_edge_layers(&self, v: f64) -> bool {
        self.discretisation(v).resolved
    }

    /// The steady rolling contact at speed `v` (m/s): by Chebyshev
    /// collocation where the automatic terms resolve the edge layers (or
    /// with explicit `terms`), otherwise on the graded mesh.
    pub fn solve(&self, v: f64) -> Result<RollingSolution, ModelError> {
        require_positive("v", v)?;
        let d = self.discretisation(v);
        if d.resolved {
            return self.solve_discretised(v, &d);
        }
        let start = GradedStart::Guess(d.half_width);
        let mut solution = self.solve_graded(v, d.terms, self.settings.panel_nodes, start)?;
        solution.error_estimate = GRADED_ERROR;
        Ok(solution)
    }

    /// As [`Self::solve`] (the same μ), with the error estimate of a
    /// solution on the graded mesh made a posteriori: twice the change of
    /// μ from q to q + 2 nodes per panel, at least [`GRADED_FLOOR`]. The
    /// q + 2 mesh converges two orders of magnitude further at low speed
    /// and several times further elsewhere, so the change is nearly the q
    /// solution's error (the factor 2 covers the worst measured case).
    /// Started at the q solution's half-width, its secant costs about one
    /// more solve.
    pub fn solve_with_error_estimate(&self, v: f64) -> Result<RollingSolution, ModelError> {
        require_positive("v", v)?;
        let d = self.discretisation(v);
        if d.resolved {
            return self.solve_discretised(v, &d);
        }
        self.graded_with_estimate(v, d.terms, GradedStart::Guess(d.half_width))
    }

    /// The contact at speed `v` on the graded mesh with `order` nodes per
    /// panel, the secant started at `start`; `terms` Chebyshev
    /// coefficients of the pressure are kept.
    fn solve_graded(
        &self,
        v: f64,
        terms: usize,
        order: usize,
        start: GradedStart,
    ) -> Result<RollingSolution, ModelError> {
        // From another mesh's root the secant needs only a small first step.
        let (b, step) = match start {
            GradedStart::Guess(b) => (b, 1e-3),
            GradedStart::Root(b) => (b, 1e-7),
        };
        let contact = GradedContact::new(
            &self.compliance,
            self.shortest_relaxation,
            v,
            self.radius,
            self.load,
            b,
            order,
        );
        let GradedSolution {
            center: c,
            half_width: b,
            alpha,
            profile,
            iterations,
            nodes,
        } = contact.solve(b, step, self.settings.tolerance, terms)?;
        Ok(self.solution(
            v,
            (c, b),
            alpha,
            iterations,
            ExactMethod::GradedMesh { nodes },
            Some(Arc::new(profile)),
        ))
    }

    /// The contact at speed `v` as `d` discretises it (Chebyshev), with
    /// the error claimed for that discretisation.
    fn solve_discretised(&self, v: f64, d: &Discretisation) -> Result<RollingSolution, ModelError> {
        let mut solution = self.solve_with(v, d.terms, d.half_width)?;
        solution.resolved = d.resolved;
        solution.error_estimate = if self.settings.terms.is_some() {
            f64::NAN
        } else {
            self.settings.resolved_error()
        };
        Ok(solution)
    }

    /// The contact at speed `v` with `terms` Chebyshev terms, Newton started
    /// from half-width `b`.
    fn solve_with(&self, v: f64, terms: usize, b: f64) -> Result<RollingSolution, ModelError> {
        let (c, b, colloc, iterations) = solver::solve_edges(
            &self.compliance,
            &self.quadrature,
            v,
            self.radius,
            self.load,
            terms,
            b,
            self.settings.tolerance,
        )?;
        Ok(self.solution(
            v,
            (c, b),
            colloc.alpha,
            iterations,
            ExactMethod::Chebyshev,
            None,
        ))
    }

    /// The solution with contact centre `c` and half-width `b`
    /// (`edges` = (c, b), m) and Chebyshev coefficients `alpha` of the
    /// pressure: the centroid x̄ = c + π b³ α1/(4F) (the α1 term is the
    /// only odd moment of the series), μ = x̄/R. Resolved where the
    /// Chebyshev series carries the pressure itself; the estimate is set by
    /// the caller.
    fn solution(
        &self,
        v: f64,
        (c, b): (f64, f64),
        alpha: Vec<f64>,
        iterations: usize,
        method: ExactMethod,
        profile: Option<Arc<PressureProfile>>,
    ) -> RollingSolution {
        let centroid = c + PI * b * b * b * alpha[1] / (4.0 * self.load);
        RollingSolution {
            speed: v,
            mu: centroid / self.radius,
            centroid,
            trailing_edge: c - b,
            leading_edge: c + b,
            coefficients: alpha,
            iterations,
            resolved: method == ExactMethod::Chebyshev,
            method,
            profile,
            error_estimate: f64::NAN,
        }
    }
}

/// Refuses a radius or load that is not positive and a Poisson ratio
/// outside [0, 0.5]: the checks every exact rolling body makes.
fn check_body(poisson: f64, radius: f64, load: f64) -> Result<(), ModelError> {
    require_positive("radius", radius)?;
    require_positive("load", load)?;
    crate::scene::check_poisson(poisson)?;
    Ok(())
}

/// The error claimed for μ where the edge layers are resolved at the
/// default layer resolution (measured ≤ 3.6e-7 against N = 192,
/// tests/exact_cylinder.rs).
pub const RESOLVED_ERROR: f64 = 1e-5;

/// The error claimed for μ on the graded mesh without an a-posteriori
/// estimate (q = 8): measured ≤ 6.0e-8 against the semi-analytic standard
/// linear solid (E1/E0 = 2 … 1e5, ν = 0 and 0.5, vτ/a0 ≥ 1e-5) and
/// ≤ 7.4e-8 against q = 12 for random Prony series (tests/exact_cylinder.rs,
/// `stiff_study`).
pub const GRADED_ERROR: f64 = 1e-7;

/// The a-posteriori estimate on the graded mesh is this many times the
/// change of μ from q to q + 2 nodes per panel: the change was 0.93 … 1.06
/// times the error of the q solution, once 0.31 (E1/E0 = 2, vτ/a0 =
/// 2e-5, error 5e-10, where q and q + 2 err alike).
const GRADED_SAFETY: f64 = 2.0;

/// The least a-posteriori estimate on the graded mesh: below it the change
/// from q to q + 2 nodes per panel is rounding and the secant's tolerance
/// (the errors of q = 8 and q = 12 against the semi-analytic solution
/// level off at 1e-11 … 1e-10).
pub const GRADED_FLOOR: f64 = 1e-10;

#[cfg(test)]
mod tests {
    use super::*;
    use kernel::{CollocationGrid, memory_matrix_per_term};

    /// A broad rubber: 200 relaxation times log-spaced over
    /// 1e-12 … 1e8 s, E0 = 2 MPa, E1 = 2 GPa, the strengths a log-normal
    /// bump around 1e-5 s on a floor.
    fn rubber_200() -> Prony {
        let n = 200;
        let tau: Vec<f64> = (0..n)
            .map(|k| 10f64.powf(-12.0 + 20.0 * k as f64 / (n - 1) as f64))
            .collect();
        let w: Vec<f64> = tau
            .iter()
            .map(|t| (-0.5 * ((t.log10() + 5.0) / 3.0).powi(2)).exp() + 1e-3)
            .collect();
        let total: f64 = w.iter().sum();
        let (e0, e1) = (2e6, 2e9);
        let h = w.iter().map(|x| (e1 - e0) * x / total).collect();
        Prony::new(e1, h, tau).unwrap()
    }

    /// μ from the edges and coefficients of the solver.
    fn mu(cylinder: &RollingCylinder, c: f64, b: f64, alpha: &[f64]) -> f64 {
        (c + PI * b * b * b * alpha[1] / (4.0 * cylinder.load)) / cylinder.radius
    }

    /// With 200 retardation times the grouped memory matrix gives
    /// the μ of the slow per-term quadrature (the reference of `kernel.rs`,
    /// whose cost made this series take 15 s per speed), on panels of 0.25
    /// (cos((n+1)φ) turns by at most 12 radians on one). N = 48 keeps the
    /// reference affordable; the methods' switch-overs move with N
    /// (β_F = N²/16), and kernel.rs checks them at N = 24 … 128. Measured:
    /// ≤ 1.0e-12 relative.
    #[test]
    fn many_terms_match_the_per_term_evaluation() {
        let cylinder = RollingCylinder::new(&rubber_200(), 0.5, 0.01, 100.0).unwrap();
        let (terms, tolerance) = (48, cylinder.settings.tolerance);
        let grid = CollocationGrid::new(terms);
        let reference = MemoryQuadrature::new(cylinder.settings.quadrature_order, 0.25);
        let compliance = &cylinder.compliance;
        for v in [1e-6, 1e-3, 1.0] {
            let start = cylinder.discretisation(v).half_width;
            let (c, b, fast, _) = solver::solve_edges(
                compliance,
                &cylinder.quadrature,
                v,
                cylinder.radius,
                cylinder.load,
                terms,
                start,
                tolerance,
            )
            .unwrap();
            let memory = |b: f64| memory_matrix_per_term(&reference, &grid, compliance, b / v);
            let (c_slow, b_slow, slow, _) = solver::solve_edges_with(
                &grid,
                compliance.instantaneous,
                &memory,
                v,
                cylinder.radius,
                cylinder.load,
                start,
                tolerance,
            )
            .unwrap();
            let (mu_fast, mu_slow) = (
                mu(&cylinder, c, b, &fast.alpha),
                mu(&cylinder, c_slow, b_slow, &slow.alpha),
            );
            let error = (mu_fast / mu_slow - 1.0).abs();
            println!("v = {v:e} m/s: μ = {mu_fast:.15e}, per term {mu_slow:.15e}, {error:.1e}");
            assert!(error < 1e-9, "v = {v}: {mu_fast} vs {mu_slow}");
            assert!((b / b_slow - 1.0).abs() < 1e-9);
        }
    }
}
