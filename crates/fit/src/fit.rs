//! The entry point of a fit at the path it has always had
//! (`rollfit_fit::fit::fit`); the method is described in [`crate::driver`].

pub use crate::driver::fit;
