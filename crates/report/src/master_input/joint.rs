//! The DMA file of a joint fit (`dma = FILE` in a scene's
//! `[fit]` or a batch manifest, `rollfit fit --dma FILE...|FOLDER`, the Python
//! module's `dma=` keyword): read and grouped into isotherms by
//! [`rollfit_io::dma::group_isotherms`], as `rollfit master` reads a DMA
//! file, then checked by the fit library ([`DmaRows::new`]). Where the
//! library refuses one point, the message names its line in the file.

use std::path::Path;

use rollfit_fit::joint::{DMA_MODULUS_RANGE, DMA_OMEGA_RANGE};
use rollfit_fit::master::Isotherm;
use rollfit_fit::{DmaRows, FitError};

use rollfit_io::IoError;
use rollfit_io::dma::{DmaInput, DmaIsotherms, group_isotherms};
use rollfit_io::error::RowRef;

/// The DMA isotherms of a joint fit and what reading the file said.
#[derive(Debug, Clone)]
pub struct JointDma {
    /// The isotherms, checked (source: the path as displayed).
    pub rows: DmaRows,
    /// How the file was read where the file said so (shear converted).
    pub notes: Vec<String>,
    /// Points dropped and decisions taken while reading.
    pub warnings: Vec<String>,
}

/// Reads the DMA file `path` for a joint fit: any form
/// [`rollfit_io::dma::DmaData::read_sheet`] accepts (a workbook's first sheet),
/// shear moduli converted with `poisson` (the scene's ν). A file without
/// temperatures is one isotherm at `t_ref` (the fit's `T_ref`; refused
/// without one). Errors name the file and, where one point is at fault,
/// its line.
pub fn read(path: &Path, poisson: f64, t_ref: Option<f64>) -> Result<JointDma, IoError> {
    read_input(&DmaInput::file(path), poisson, t_ref)
}

/// [`read`] of several files or folders (one isotherm per file, each
/// file's temperature found as [`rollfit_io::dma::files`] finds it).
pub fn read_input(input: &DmaInput, poisson: f64, t_ref: Option<f64>) -> Result<JointDma, IoError> {
    let data = input
        .read(poisson, None)
        .map_err(|e| IoError::content(e.to_string()))?;
    let read = group_isotherms(data, t_ref)?;
    let source = input.names();
    // Each isotherm alone first, so that a point the library refuses is
    // found in the isotherm it named.
    for (isotherm, indices) in read.isotherms.iter().zip(&read.indices) {
        DmaRows::new(vec![isotherm.clone()], source.as_str())
            .map_err(|error| refused(&read, Some((isotherm, indices)), error))?;
    }
    let rows = DmaRows::new(read.isotherms.clone(), source)
        .map_err(|error| refused(&read, None, error))?;
    let DmaIsotherms { data, .. } = read;
    Ok(JointDma {
        rows,
        notes: data.notes,
        warnings: data.warnings,
    })
}

/// The library's refusal, behind the file and, where `isotherm` has a
/// point outside the library's ranges (or only one point), that point's
/// line.
fn refused(
    read: &DmaIsotherms,
    isotherm: Option<(&Isotherm, &Vec<usize>)>,
    error: FitError,
) -> IoError {
    let source = Box::new(IoError::content(error.to_string()));
    let outside = |x: f64, (lo, hi): (f64, f64)| !(x.is_finite() && x >= lo && x <= hi);
    let point = isotherm.and_then(|(iso, indices)| {
        let k = (0..iso.omega.len())
            .find(|&k| {
                outside(iso.omega[k], DMA_OMEGA_RANGE)
                    || outside(iso.storage[k], DMA_MODULUS_RANGE)
                    || outside(iso.loss[k], DMA_MODULUS_RANGE)
            })
            .or((iso.omega.len() == 1).then_some(0))?;
        indices.get(k).copied()
    });
    // Of several files, the point's own.
    let path = point.map_or(read.data.path.as_path(), |i| read.data.file_of(i));
    let path = path.to_path_buf();
    let line = point.and_then(|i| read.data.lines.get(i).copied());
    match line {
        Some(number) => IoError::content(format!(
            "DMA file {}, {row}",
            path.display(),
            row = RowRef {
                sheet: read.data.sheet.clone(),
                number: number as u64,
            }
        ))
        .caused_by(source),
        None => IoError::content(format!("DMA file {}", path.display())).caused_by(source),
    }
}
