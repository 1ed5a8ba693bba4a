//! Universal kernels of the friction integrals and their product-integration
//! weights. See [`weights`] for the method.
pub(crate) mod chebyshev;
pub mod cylinder;
pub mod film_sphere;
pub(crate) mod gauss_kronrod;
pub(crate) mod quadrature;
pub mod sphere;
pub mod weights;
pub mod window;
pub(crate) mod windowed;

pub use weights::{KernelCursor, KernelTable, STEPS, step_for_tolerance};
