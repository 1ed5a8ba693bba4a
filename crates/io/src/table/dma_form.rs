//! A modulus table in a DMA form other than the plain one (docs/
//! ARCHITECTURE.md, "Contract", "DMA files": shear or unit-suffixed CSV
//! columns, a temperature column, a TRIOS export), read by
//! [`crate::dma::DmaData::read`] and made one master curve: one
//! temperature only, points sorted by frequency, no frequency twice, two
//! points at least. The DMA reader's messages and notes are said in the
//! scene's words ([`crate::error::table`]).

use std::path::Path;

use super::ModulusTable;
use crate::dma::{DmaData, DmaOptions, ModulusKind, isotherms};
use crate::error::table::{celsius, in_scene_words};
use crate::error::{IoError, TableError, TableIsotherm};

/// Reads a file of the DMA forms and makes one master curve of it;
/// `shifted_points`: the file looks like the master.csv of `rollfit
/// master`, which a refusal then says.
pub(super) fn read(
    path: &Path,
    poisson: f64,
    kind: Option<ModulusKind>,
    sheet: Option<&str>,
    shifted_points: bool,
) -> Result<ModulusTable, IoError> {
    // ν matters only for shear moduli: a bad ν is refused only then, and
    // named as the scene's (the DMA reader would call it the fit's).
    let usable = rollfit_model::check_poisson(poisson).is_ok();
    let options = DmaOptions {
        kind,
        ..DmaOptions::default()
    };
    let data = DmaData::read_sheet(path, if usable { poisson } else { 0.5 }, &options, sheet)
        .map_err(|e| TableError::Dma { error: Box::new(e) })?;
    if !usable && data.kind == ModulusKind::Shear {
        return Err(TableError::ShearWithoutPoisson {
            path: path.to_path_buf(),
            poisson,
        }
        .into());
    }
    let isotherms = isotherms(&data.points);
    if isotherms.len() > 1 {
        return Err(TableError::SeveralTemperatures {
            path: path.to_path_buf(),
            isotherms: isotherms
                .iter()
                .map(|i| {
                    let lines = i.points.iter().map(|&k| data.lines[k]);
                    TableIsotherm {
                        temperature: i.temperature,
                        points: i.points.len(),
                        lines: (lines.clone().min().unwrap_or(0), lines.max().unwrap_or(0)),
                    }
                })
                .collect(),
            shifted_points,
        }
        .into());
    }

    // How the file was read first, then what was left out.
    let mut notes: Vec<String> = data.notes.iter().map(|m| in_scene_words(m)).collect();
    if let Some(isotherm) = isotherms.first() {
        notes.push(format!(
            "{}: all points at {}: read as the master curve at that temperature \
             ([material.shift] T_ref, if given, should be it)",
            path.display(),
            celsius(isotherm.temperature)
        ));
    }
    notes.extend(data.warnings.iter().map(|m| in_scene_words(m)));
    let order = sorted(path, &data)?;
    Ok(ModulusTable {
        omega: order.iter().map(|&k| data.points[k].omega).collect(),
        storage: order.iter().map(|&k| data.points[k].storage).collect(),
        loss: order.iter().map(|&k| data.points[k].loss).collect(),
        lines: order.iter().map(|&k| data.lines[k]).collect(),
        notes,
    })
}

/// The points of `data` in increasing frequency; refused with a frequency
/// twice or fewer than two points.
fn sorted(path: &Path, data: &DmaData) -> Result<Vec<usize>, TableError> {
    let mut order: Vec<usize> = (0..data.points.len()).collect();
    order.sort_by(|&a, &b| data.points[a].omega.total_cmp(&data.points[b].omega));
    for pair in order.windows(2) {
        let (a, b) = (&data.points[pair[0]], &data.points[pair[1]]);
        if b.omega <= a.omega {
            let (first, second) = (data.lines[pair[0]], data.lines[pair[1]]);
            return Err(TableError::RepeatedFrequency {
                path: path.to_path_buf(),
                lines: (first.min(second), first.max(second)),
                omega: a.omega,
            });
        }
    }
    if order.len() < 2 {
        return Err(TableError::TooFewPoints {
            path: path.to_path_buf(),
            rows: order.len(),
        });
    }
    Ok(order)
}
