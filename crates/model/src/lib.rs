//! # rollfit-model
//!
//! The forward model of rollfit: the friction coefficient μ(v) of a hard
//! sphere or cylinder rolling on a linear viscoelastic solid, after
//! B.N.J. Persson, "Rolling friction for hard cylinder and sphere on
//! viscoelastic solid", Eur. Phys. J. E 33 (2010) — equation numbers refer to
//! that paper. No I/O happens here.
//!
//! Where each equation lives:
//! - [`modulus`]: E*(ω) — standard linear solid (Eq. 12), Prony series
//!   (Eq. B2), Havriliak–Negami, tabulated master curves, time–temperature
//!   shift (WLF).
//! - `contact`: Hertz contact size and mean pressure (static and dynamic).
//! - [`film`]: the film factor S(qd) of a layer on a rigid base.
//! - [`kernel`]: the universal kernels of the friction integrals — J1²(y)/y for
//!   the cylinder (Eq. 11), x²G(x) for the sphere (Eq. 17 reduced to one
//!   frequency integral) — and their product-integration weights.
//! - `friction`: μ(v) and its derivatives with respect to Prony parameters.
//! - [`exact`]: the exact steady rolling cylinder (Hunter 1961), the
//!   reference Eq. (11) approximates.
//! - [`ladder`]: the rungs of model fidelity and `auto`, the cheapest rung
//!   that meets a requested accuracy.
//! - [`plausibility`]: warnings for inputs and materials outside the
//!   theory's assumptions or any laboratory (a unit slip, most often).
//! - `asymptotes`: the low-speed limit (Eqs. 18/19, generalised to
//!   E″ ∝ ω^p), Greenwood–Tabor α
//!   (Eqs. 20–21), pressure-centroid shift, friction maximum.
//!
//! # Example
//!
//! μ(v) of a steel ball on a standard linear solid; far below the
//! relaxation frequency it follows the low-speed asymptote (Eqs. 18/19).
//! `examples/sweep.rs` prints a whole sweep (`cargo run --example sweep
//! -p rollfit-model`).
//!
//! ```
//! use rollfit_model::{ContactSize, Geometry, Scene, Shape, StandardLinearSolid, Substrate};
//!
//! // E0 = 1 MPa, E1 = 100 MPa, τ = 10 ms.
//! let rubber = StandardLinearSolid::new(1e6, 1e8, 1e-2)?;
//! let scene = Scene::new(
//!     Geometry { shape: Shape::Sphere, radius: 0.01, load: 1.0 },
//!     Substrate { poisson: 0.5, film_thickness: None },
//!     ContactSize::Dynamic,
//!     rubber,
//! )?;
//! let speeds = [1e-7, 1e-3, 1e-1];
//! let mu = scene.friction_sweep(&speeds)?;
//! assert!(mu.iter().all(|&m| m > 0.0 && m < 1.0));
//! let low = scene.low_speed_asymptote(speeds[0]);
//! assert!((mu[0] / low - 1.0).abs() < 0.02, "μ = {} vs asymptote {low}", mu[0]);
//! # Ok::<(), rollfit_model::ModelError>(())
//! ```
//!
//! Sign convention: E*(ω) = E′ + iE″ with E″ ≥ 0 for ω > 0; the loss
//! compliance L(ω) = E″_eff/|E_eff|² = −Im 1/E_eff(ω) is what the paper calls
//! "Im 1/E" (its Fourier convention gives the complex conjugate).

// The modules other crates use.
pub mod exact;
pub mod film;
pub mod kernel;
pub mod ladder;
pub mod modulus;
pub mod plausibility;

// The forward model's parts, reached through the items below and `Scene`.
mod asymptotes;
mod contact;
mod error;
mod friction;
mod scene;

pub use contact::{ContactSize, Shape};
pub use error::{ModelError, PoissonOutOfRange};
pub use friction::FrictionJacobian;
pub use modulus::{
    HavriliakNegami, Prony, Shifted, StandardLinearSolid, TabulatedModulus, VerticalShift,
    ViscoelasticModulus, Wlf,
};
pub use scene::{
    Geometry, POISSON_RANGE, RollingSetup, Scene, Substrate, check_film_thickness, check_poisson,
};
