//! Universal kernels of the friction integrals and their product-integration
//! weights. See [`weights`] for the method.
pub(crate) mod chebyshev;
pub mod cylinder;
pub(crate) mod quadrature;
pub mod sphere;
pub mod weights;
pub mod window;

pub use weights::{KernelTable, STEPS, step_for_tolerance};
