//! Where commands are assembled: DMA input read by io and built by the
//! fit library, for the command line and the Python module alike (both
//! depend on this crate; io must not, since a master curve is no file
//! format). Each kind of isotherm takes the same path — read, group
//! (with repeated abscissae averaged), check the settings, build — and
//! differs only in the numerics the fit library plugs in
//! ([`rollfit_fit::master::pipeline::Superposed`]):
//!
//! - [`frequency`]: DMA frequency sweeps to a master curve (`rollfit
//!   master`);
//! - [`time`]: relaxation and creep runs to a master curve (`rollfit
//!   master` on E(t), G(t), J(t) or D(t));
//! - [`joint`]: DMA frequency sweeps as the isotherms of a joint fit
//!   (`rollfit fit --dma`, the Python module's `dma=`).
//!
//! A scene's `[material] model = "dma"` is built inside io's scene reader
//! from the same two calls (io's grouping, then the fit library's
//! pipeline), since every scene consumer asks the scene for its material.

pub mod frequency;
pub mod joint;
pub mod time;
