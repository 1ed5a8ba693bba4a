//! A DMA file to a master curve: read the file (any form [`crate::dma`]
//! accepts, docs/ARCHITECTURE.md, "Contract", "DMA files"), group its
//! points into isotherms, and run `rollfit_fit::master` on them. Shared by
//! `rollfit master` and a scene's `[material] model = "dma"`, so that both
//! give the same series. Nothing is written here: `rollfit master` writes
//! the folder, [`crate::material_file`] its material.toml.

use std::path::Path;

use rollfit_fit::master::{
    Isotherm, MasterCurve, MasterSettings, ValidMasterSettings, build_master_curve, sweep_turn,
};

use crate::dma::{DmaData, DmaOptions, ISOTHERM_GAP, ISOTHERM_SPAN, ModulusKind, range};
use crate::error::{DmaMasterError, IoError, TurnPoint};

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
}

/// Reads `path` (of a workbook the sheet `sheet`, default the first) and
/// builds its master curve ([`read_isotherms`], then the master-curve fit).
/// `poisson` converts shear moduli (E = 2(1+ν)G); `kind` overrides a TRIOS
/// file's shear/tensile decision. Errors ([`DmaMasterError`]) name the
/// file and, where one point is at fault, its line.
pub fn build(
    path: &Path,
    poisson: f64,
    kind: Option<ModulusKind>,
    sheet: Option<&str>,
    settings: &MasterSettings,
) -> Result<DmaMaster, IoError> {
    build_told(path, poisson, kind, sheet, settings, |_| {})
}

/// [`build`], telling `on_read` the file as read (its notes and warnings:
/// rows skipped, units converted) before the master curve is fitted, so
/// that a refusal of the fit can be read next to the rows that explain it.
pub fn build_told(
    path: &Path,
    poisson: f64,
    kind: Option<ModulusKind>,
    sheet: Option<&str>,
    settings: &MasterSettings,
    on_read: impl FnOnce(&DmaData),
) -> Result<DmaMaster, IoError> {
    // No temperatures: the file is one curve, taken at T_ref.
    let untimed = settings.t_ref.unwrap_or(rollfit_fit::master::DEFAULT_T_REF);
    let DmaIsotherms {
        data,
        isotherms,
        indices,
    } = read_isotherms(path, poisson, kind, sheet, Some(untimed))?;
    on_read(&data);
    let ranges = match data.points.iter().any(|p| p.temperature.is_some()) {
        true => indices.iter().map(|i| range(&data.points, i)).collect(),
        false => Vec::new(),
    };
    let in_file = |source: DmaMasterError| DmaMasterError::InFile {
        path: path.to_path_buf(),
        source: Box::new(source),
    };
    let valid = settings
        .check(&isotherms)
        .map_err(|error| in_file(DmaMasterError::Fit { error }))?;
    let master =
        build_master_curve(&isotherms, &valid).map_err(|error| DmaMasterError::MasterCurve {
            path: path.to_path_buf(),
            source: Box::new(DmaMasterError::Fit { error }),
        })?;
    Ok(DmaMaster {
        data,
        settings: valid.resolved(&master.shift),
        master,
        ranges,
    })
}

/// A DMA file read and grouped into isotherms.
pub struct DmaIsotherms {
    /// The file as read (Young's moduli).
    pub data: DmaData,
    /// The isotherms, ascending in temperature, each in file order.
    pub isotherms: Vec<Isotherm>,
    /// For each isotherm, the indices of its points in `data.points` (and
    /// `data.lines`), in the isotherm's order.
    pub indices: Vec<Vec<usize>>,
}

/// Reads `path` (of a workbook the sheet `sheet`, default the first) and
/// groups its points into isotherms ([`crate::dma::isotherm`]: by step,
/// else by temperature), refusing a temperature ramp and an isotherm
/// whose frequencies do not run one way: what `rollfit master`, a scene's
/// `model = "dma"` and a joint fit's `dma` share. `poisson` converts shear
/// moduli (E = 2(1+ν)G); `kind` overrides a TRIOS file's shear/tensile
/// decision. A file without temperatures is one isotherm at `untimed`
/// (None: refused, [`DmaMasterError::NoTemperature`]). Errors name the
/// file and, where one point is at fault, its line.
pub fn read_isotherms(
    path: &Path,
    poisson: f64,
    kind: Option<ModulusKind>,
    sheet: Option<&str>,
    untimed: Option<f64>,
) -> Result<DmaIsotherms, IoError> {
    let options = DmaOptions { kind, wlf: None };
    let data = DmaData::read_sheet(path, poisson, &options, sheet)
        .map_err(|e| DmaMasterError::Read { error: Box::new(e) })?;
    let with_t = data
        .points
        .iter()
        .filter(|p| p.temperature.is_some())
        .count();
    let groups: Vec<(f64, Vec<usize>)> = if with_t == 0 {
        let t = untimed.ok_or_else(|| DmaMasterError::NoTemperature {
            path: path.to_path_buf(),
        })?;
        vec![(t, (0..data.points.len()).collect())]
    } else if with_t < data.points.len() {
        return Err(DmaMasterError::TemperatureMissing {
            path: path.to_path_buf(),
            missing: data.points.len() - with_t,
            total: data.points.len(),
        }
        .into());
    } else {
        let grouping = data.grouping();
        if let Some(ramp) = grouping.ramp {
            return Err(DmaMasterError::Ramp {
                path: path.to_path_buf(),
                count: ramp.count,
                low: ramp.low,
                high: ramp.high,
                widest_gap: ramp.widest_gap,
                gap: ISOTHERM_GAP,
                span: ISOTHERM_SPAN,
            }
            .into());
        }
        grouping
            .isotherms
            .into_iter()
            .map(|iso| {
                // File order: the grouping sorts by temperature, and a
                // controller's scatter would shuffle a sweep.
                let mut points = iso.points;
                points.sort_unstable();
                (iso.temperature, points)
            })
            .collect()
    };
    let mut sets = Vec::with_capacity(groups.len());
    for (temperature, indices) in &groups {
        check_monotone(&data, *temperature, indices).map_err(|source| DmaMasterError::InFile {
            path: path.to_path_buf(),
            source: Box::new(source),
        })?;
        let point = |i: &usize| data.points[*i];
        sets.push(Isotherm {
            temperature: *temperature,
            omega: indices.iter().map(|i| point(i).omega).collect(),
            storage: indices.iter().map(|i| point(i).storage).collect(),
            loss: indices.iter().map(|i| point(i).loss).collect(),
        });
    }
    Ok(DmaIsotherms {
        data,
        isotherms: sets,
        indices: groups.into_iter().map(|(_, indices)| indices).collect(),
    })
}

/// Refuses an isotherm whose frequencies neither rise nor fall
/// throughout, naming the lines where the sweep turns.
fn check_monotone(
    data: &DmaData,
    temperature: f64,
    indices: &[usize],
) -> Result<(), DmaMasterError> {
    let omega: Vec<f64> = indices.iter().map(|&i| data.points[i].omega).collect();
    let Some(k) = sweep_turn(&omega) else {
        return Ok(());
    };
    let at = |j: usize| TurnPoint {
        line: data.lines.get(indices[j]).copied(),
        index: indices[j],
        omega: omega[j],
    };
    let turn: Vec<TurnPoint> = (k - 1..(k + 2).min(omega.len()))
        .filter(|&j| j <= k || omega[k] != omega[k - 1])
        .map(at)
        .collect();
    Err(DmaMasterError::NotMonotone { temperature, turn })
}
