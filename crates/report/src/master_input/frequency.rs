//! DMA frequency sweeps, one file or several (one per isotherm,
//! [`rollfit_io::dma::files`]), to a master curve: read by io, grouped
//! into isotherms ([`rollfit_io::dma::group_isotherms`]: by step, else by
//! temperature, with the fit library's rule), and built by the fit
//! library's pipeline ([`rollfit_fit::master::pipeline`]).
//!
//! Sweeps at one temperature from several files are merged into one
//! isotherm ordered by frequency (the fit takes one isotherm per
//! temperature), and points at a repeated frequency within an isotherm —
//! a frequency printed with too few digits, or two sweeps merged — are
//! averaged into one ([`rollfit_fit::master::repeats`]). Each merge is
//! noted. Nothing is written here: `rollfit master` writes the folder,
//! [`rollfit_io::material_file`] its material.toml.

use rollfit_fit::master::pipeline;
use rollfit_fit::master::{MasterCurve, MasterSettings, ValidMasterSettings};
pub use rollfit_io::dma::DmaInput;
use rollfit_io::dma::{DmaData, group_isotherms, master_refused};
use rollfit_io::{IoError, material_file};

/// A master curve built from a DMA file.
pub struct DmaMaster {
    /// The file as read (Young's moduli).
    pub data: DmaData,
    /// The checked settings (T_ref resolved).
    pub settings: ValidMasterSettings,
    /// Shift factors, shifted points and the Prony series.
    pub master: MasterCurve,
    /// The lowest and highest measured temperature of each isotherm (°C,
    /// in the order of the isotherms; empty for a file without
    /// temperatures).
    pub ranges: Vec<(f64, f64)>,
    /// Sweeps at one temperature merged into one isotherm, as said.
    pub merged: Vec<String>,
}

impl DmaMaster {
    /// Its material.toml ([`material_file::encode`]).
    pub fn material_file(&self) -> Result<Vec<u8>, IoError> {
        material_file::encode(&self.data.path, &self.master, &self.settings)
    }
}

/// Reads `input` and builds its master curve. `poisson` converts shear
/// moduli (E = 2(1+ν)G). Errors name the file and, where one point is at
/// fault, its line.
pub fn build(
    input: &DmaInput,
    poisson: f64,
    settings: &MasterSettings,
) -> Result<DmaMaster, IoError> {
    build_told(input, poisson, settings, |_| {})
}

/// [`build`], telling `on_read` the file as read (its notes and warnings:
/// rows skipped, units converted) before the master curve is fitted, so
/// that a refusal of the fit can be read next to the rows that explain it.
pub fn build_told(
    input: &DmaInput,
    poisson: f64,
    settings: &MasterSettings,
    on_read: impl FnOnce(&DmaData),
) -> Result<DmaMaster, IoError> {
    let data = input
        .read(poisson, None)
        .map_err(|e| IoError::content(e.to_string()))?;
    // No temperatures: the file is one curve, taken at T_ref.
    let untimed = settings.t_ref.unwrap_or(rollfit_fit::master::DEFAULT_T_REF);
    let read = group_isotherms(data, Some(untimed))?;
    on_read(&read.data);
    let ranges = read.ranges();
    let built = pipeline::build(&read.isotherms, (), settings)
        .map_err(|error| master_refused(&read.data.path, error))?;
    Ok(DmaMaster {
        data: read.data,
        settings: built.settings,
        master: built.master,
        ranges,
        merged: read.merged,
    })
}
