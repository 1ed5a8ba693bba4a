//! A stress-relaxation or creep file to a master curve: read the file
//! ([`crate::dma::relaxation`]), group its points into isotherms, and run
//! `rollfit_fit::master::relaxation` on them (shifts in log t, a smooth
//! Prony series of E(t), fitted to E(t) or through its exact creep
//! compliance to D(t)). The twin of [`crate::dma_master`] for frequency
//! sweeps; `rollfit master` writes the folder, [`crate::material_file`]
//! its material.toml in the same form.

use std::path::Path;

use rollfit_fit::master::relaxation::{RelaxationIsotherm, RelaxationMaster, build_time_master};
use rollfit_fit::master::{DEFAULT_T_REF, MasterSettings, ValidMasterSettings};

use crate::dma::ModulusKind;
use crate::dma::relaxation::{RelaxationData, groups};
use crate::error::IoError;

/// A master curve built from a relaxation file.
pub struct RelaxationBuilt {
    /// The file as read (Young's moduli).
    pub data: RelaxationData,
    /// The checked settings (T_ref resolved).
    pub settings: ValidMasterSettings,
    /// Shift factors, shifted points and the Prony series.
    pub master: RelaxationMaster,
}

/// Reads `path` and builds its master curve; `poisson` converts a shear
/// G(t) or J(t), `kind` states a creep compliance's
/// ([`RelaxationData::read_as`]). Errors name the file and, where one
/// point is at fault, its line.
pub fn build(
    path: &Path,
    poisson: f64,
    kind: Option<ModulusKind>,
    settings: &MasterSettings,
) -> Result<RelaxationBuilt, IoError> {
    let mut data = RelaxationData::read_as(path, poisson, kind)?;
    let mut isotherms: Vec<RelaxationIsotherm> = Vec::new();
    for (temperature, indices) in groups(&data.points) {
        // No temperatures: the file is one curve, taken at T_ref.
        let temperature = if temperature.is_nan() {
            settings.t_ref.unwrap_or(DEFAULT_T_REF)
        } else {
            temperature
        };
        let mut isotherm = RelaxationIsotherm {
            temperature,
            time: Vec::new(),
            value: Vec::new(),
        };
        // Time stamps printed with too few digits repeat: each run of one
        // time is averaged into one point (the reader refused times that
        // fall).
        let runs = indices.chunk_by(|&a, &b| data.points[a].time == data.points[b].time);
        let mut repeated = 0;
        for run in runs {
            let mean = run.iter().map(|&i| data.points[i].value).sum::<f64>() / run.len() as f64;
            isotherm.time.push(data.points[run[0]].time);
            isotherm.value.push(mean);
            repeated += if run.len() > 1 { run.len() } else { 0 };
        }
        if repeated > 0 {
            data.notes.push(format!(
                "{}: isotherm at {temperature:.2} °C: {repeated} points at repeated times averaged into {}",
                path.display(),
                repeated - (indices.len() - isotherm.time.len())
            ));
        }
        isotherms.push(isotherm);
    }
    let in_file = |source: IoError| err!("DMA file {}", path.display()).caused_by(source);
    let valid = settings
        .check_time(&isotherms, data.quantity)
        .map_err(|error| in_file(err!("{error}")))?;
    let master = build_time_master(&isotherms, data.quantity, &valid).map_err(|error| {
        err!("DMA file {}: master curve", path.display()).caused_by(err!("{error}"))
    })?;
    Ok(RelaxationBuilt {
        data,
        settings: valid.resolved(&master.shift),
        master,
    })
}
