//! # rollfit-python
//!
//! The Python module `rollfit` (PyO3, abi3, NumPy arrays through
//! rust-numpy; built by maturin, `pip install ./crates/python`): a thin
//! front door over the library crates, beside the `rollfit` command line.
//! It computes nothing itself: μ(v) is `rollfit_model::Scene`'s, a fit is
//! `rollfit_fit::fit` on settings parsed by `rollfit_fit::FitSettings::set`
//! (the parser of the scene's `[fit]`, the manifests and the flags), scene
//! and DMA files are read by `rollfit_io`, the fit folder is encoded by
//! `rollfit_io::fit_dir::FitFiles` and the DMA comparison is
//! `rollfit_report::compare`. The same inputs therefore give the CLI's
//! numbers bit for bit (crates/python/tests).
//!
//! Where each piece lives: `material.rs` (the moduli E*(ω)), `scene.rs`
//! (the rolling scene and μ(v)), `fit.rs` (the fit and its result),
//! `dma.rs` (DMA files and the comparison), `convert.rs` (errors and
//! arrays at the boundary).
//!
//! Units are SI throughout (Pa, m, N or N/m, s, rad/s, m/s; °C for
//! temperatures), as in every rollfit file (docs/ARCHITECTURE.md,
//! "Conventions").
//!
//! ## References
//! - B.N.J. Persson, "Rolling friction for hard cylinder and sphere on
//!   viscoelastic solid", Eur. Phys. J. E 33 (2010) 327.
//! - PyO3 user guide, <https://pyo3.rs>; rust-numpy, <https://docs.rs/numpy>.

use pyo3::prelude::*;

mod convert;
mod dma;
mod fit;
mod material;
mod scene;

/// The Python module `rollfit`.
#[pymodule]
#[pyo3(name = "rollfit")]
fn rollfit(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<material::Material>()?;
    m.add_class::<material::Sls>()?;
    m.add_class::<material::PronySeries>()?;
    m.add_class::<material::HavriliakNegamiSolid>()?;
    m.add_class::<material::Table>()?;
    m.add_class::<scene::PyScene>()?;
    m.add_class::<fit::FitResult>()?;
    m.add_class::<dma::Dma>()?;
    m.add_function(wrap_pyfunction!(fit::fit, m)?)?;
    m.add_function(wrap_pyfunction!(dma::read_dma, m)?)?;
    m.add_function(wrap_pyfunction!(dma::compare, m)?)?;
    m.add_function(wrap_pyfunction!(fit::read_data, m)?)?;
    Ok(())
}
