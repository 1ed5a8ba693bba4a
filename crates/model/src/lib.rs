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
//! - [`contact`]: Hertz contact size and mean pressure (static and dynamic).
//! - [`film`]: the film factor S(qd) of a layer on a rigid base.
//! - [`kernel`]: the universal kernels of the friction integrals — J1²(y)/y for
//!   the cylinder (Eq. 11), x²G(x) for the sphere (Eq. 17 reduced to one
//!   frequency integral) — and their product-integration weights.
//! - [`friction`]: μ(v) and its derivatives with respect to Prony parameters.
//! - [`exact`]: the exact steady rolling cylinder (Hunter 1961), the
//!   reference Eq. (11) approximates.
//! - [`ladder`]: the rungs of model fidelity and `auto`, the cheapest rung
//!   that meets a requested accuracy.
//! - [`asymptotes`]: the low-speed limit (Eqs. 18/19, generalised to
//!   E″ ∝ ω^p), Greenwood–Tabor α
//!   (Eqs. 20–21), pressure-centroid shift, friction maximum.
//!
//! Sign convention: E*(ω) = E′ + iE″ with E″ ≥ 0 for ω > 0; the loss
//! compliance L(ω) = E″_eff/|E_eff|² = −Im 1/E_eff(ω) is what the paper calls
//! "Im 1/E" (its Fourier convention gives the complex conjugate).

pub mod asymptotes;
pub mod contact;
pub mod error;
pub mod exact;
pub mod film;
pub mod friction;
pub mod kernel;
pub mod ladder;
pub mod modulus;
pub mod scene;

pub use contact::{ContactSize, Shape};
pub use error::ModelError;
pub use friction::FrictionJacobian;
pub use modulus::{
    HavriliakNegami, Prony, Shifted, StandardLinearSolid, TabulatedModulus, ViscoelasticModulus,
    Wlf,
};
pub use scene::{Geometry, Scene, Substrate};
