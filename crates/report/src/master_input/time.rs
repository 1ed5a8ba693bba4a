//! Stress-relaxation or creep files to a master curve: one file, or one
//! per temperature ([`rollfit_io::dma::time_files`], each file's
//! temperature from its T column, its name or the temperatures given),
//! read by io ([`rollfit_io::dma::relaxation`]), grouped into isotherms with
//! repeated time stamps averaged ([`rollfit_io::dma::relaxation::time_isotherms`]),
//! and built by the same pipeline as frequency sweeps
//! ([`rollfit_fit::master::pipeline`]; shifts in log t, a smooth Prony
//! series of E(t), fitted to E(t) or through its exact creep compliance to
//! D(t)). `rollfit master` writes the folder,
//! [`rollfit_io::material_file`] its material.toml in the same form.

use rollfit_fit::master::pipeline;
use rollfit_fit::master::relaxation::RelaxationMaster;
use rollfit_fit::master::{DEFAULT_T_REF, MasterSettings, ValidMasterSettings};
use rollfit_io::dma::relaxation::{RelaxationData, time_isotherms};
use rollfit_io::dma::time_files::read_time_files;
use rollfit_io::dma::{DmaFile, DmaInput, master_refused};
use rollfit_io::{IoError, material_file};

/// A master curve built from a relaxation or creep file.
pub struct RelaxationBuilt {
    /// The files as read (Young's moduli or tensile compliances).
    pub data: RelaxationData,
    /// Each file and where its temperature came from.
    pub files: Vec<DmaFile>,
    /// The checked settings (T_ref resolved).
    pub settings: ValidMasterSettings,
    /// Shift factors, shifted points and the Prony series.
    pub master: RelaxationMaster,
}

impl RelaxationBuilt {
    /// Its material.toml ([`material_file::encode_relaxation`]).
    pub fn material_file(&self) -> Result<Vec<u8>, IoError> {
        material_file::encode_relaxation(&self.data.path, &self.master, &self.settings)
    }
}

/// Reads the files of `input` and builds their master curve; `poisson`
/// converts a shear G(t) or J(t), `input.kind` states a creep
/// compliance's ([`RelaxationData::read_as`]), `input.temperatures` one
/// temperature per file. Errors name the file and, where one point is at
/// fault, its line.
pub fn build(
    input: &DmaInput,
    poisson: f64,
    settings: &MasterSettings,
) -> Result<RelaxationBuilt, IoError> {
    let given = input.temperatures.as_deref();
    let read = read_time_files(&input.files, poisson, input.kind, given)?;
    let (mut data, files) = (read.data, read.files);
    let path = data.path.clone();
    // No temperatures: the file is one curve, taken at T_ref.
    let untimed = settings.t_ref.unwrap_or(DEFAULT_T_REF);
    let isotherms = time_isotherms(&path, &data.points, &mut data.notes, untimed);
    let built = pipeline::build(&isotherms, data.quantity, settings)
        .map_err(|error| master_refused(&path, error))?;
    Ok(RelaxationBuilt {
        data,
        files,
        settings: built.settings,
        master: built.master,
    })
}
