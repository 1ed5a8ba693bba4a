//! DMA data and the comparison of a fit with it, as `rollfit compare` does
//! them: `rollfit_io::dma::DmaData::read` (CSV or TRIOS LIMS export; shear
//! moduli converted to Young's by E* = 2(1 + ν)G*) and
//! `rollfit_report::compare::compare` (the DMA points moved to the fit's
//! reference state, the causality check, the errors of tan δ, |E*|, E′
//! and E″ over the overlap of the fit's window and the DMA frequencies).
//! The comparison reads the fit folder back, as `rollfit compare` does: a
//! `FitResult` not yet saved is written to a temporary folder first, so
//! that both see the same numbers.
//!
//! ## References
//! - B.N.J. Persson, Eur. Phys. J. E 33 (2010) 327.
//! - M.L. Williams, R.F. Landel, J.D. Ferry, J. Am. Chem. Soc. 77 (1955)
//!   3701 (the WLF shift).

#![allow(non_snake_case)] // E_storage, T: the column names of rollfit's files.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use numpy::PyArray1;
use pyo3::prelude::*;
use rollfit_io::FitDir;
use rollfit_io::dma::{DmaData, DmaOptions, DmaWlf, ModulusKind};
use rollfit_io::output;
use rollfit_report::compare::compare as compare_fit;

use crate::convert::{array, io_error, json_to_python, value_error, value_error_text};
use crate::fit::FitResult;

/// DMA data as read: every point's ω (rad/s), Young's E′ and E″ (Pa) and
/// temperature (°C, NaN where the file gives none).
#[pyclass(name = "DMA", module = "rollfit", frozen)]
pub struct Dma {
    data: DmaData,
    options: DmaOptions,
}

fn options(modulus: Option<&str>, dma_wlf: Option<(f64, f64, f64)>) -> PyResult<DmaOptions> {
    let kind = match modulus {
        None => None,
        Some("young") => Some(ModulusKind::Young),
        Some("shear") => Some(ModulusKind::Shear),
        Some(other) => {
            return Err(value_error_text(format!(
                "modulus: unknown kind {other:?} (use \"young\" or \"shear\")"
            )));
        }
    };
    let wlf = dma_wlf
        .map(|(t_ref, c1, c2)| DmaWlf::new(t_ref, c1, c2))
        .transpose()
        .map_err(|problem| value_error_text(format!("dma_wlf: {problem}")))?;
    Ok(DmaOptions {
        kind,
        wlf,
        ..DmaOptions::default()
    })
}

/// Reads a DMA file (CSV: omega or f; E_storage, E_loss or G_storage,
/// G_loss; optional T; or a TRIOS LIMS text export). poisson converts shear
/// moduli to Young's; modulus ("young" or "shear") overrides what a TRIOS
/// file's variables say; dma_wlf = (T_ref °C, C1, C2 K) is the DMA's own
/// shift, used by compare.
#[pyfunction]
#[pyo3(signature = (path, poisson = 0.5, *, modulus = None, dma_wlf = None))]
pub fn read_dma(
    path: PathBuf,
    poisson: f64,
    modulus: Option<&str>,
    dma_wlf: Option<(f64, f64, f64)>,
) -> PyResult<Dma> {
    let options = options(modulus, dma_wlf)?;
    let data = DmaData::read(&path, poisson, &options).map_err(|e| io_error(&e))?;
    Ok(Dma { data, options })
}

#[pymethods]
impl Dma {
    /// rad/s.
    #[getter]
    fn omega<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.data.points.iter().map(|p| p.omega).collect())
    }

    /// Young's storage modulus E′, Pa.
    #[getter]
    fn E_storage<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.data.points.iter().map(|p| p.storage).collect())
    }

    /// Young's loss modulus E″, Pa.
    #[getter]
    fn E_loss<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.data.points.iter().map(|p| p.loss).collect())
    }

    /// °C (NaN where the file gives no temperature).
    #[getter]
    fn T<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(
            py,
            self.data
                .points
                .iter()
                .map(|p| p.temperature.unwrap_or(f64::NAN))
                .collect(),
        )
    }

    /// "csv" or "trios-lims".
    #[getter]
    fn format(&self) -> &'static str {
        self.data.format
    }

    /// "young" or "shear": what the file held.
    #[getter]
    fn modulus_kind(&self) -> &'static str {
        self.data.kind.name()
    }

    /// What the reader noticed (dropped points, …).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.data.warnings.clone()
    }

    /// How the file was read.
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.data.notes.clone()
    }

    fn __repr__(&self) -> String {
        format!(
            "DMA({:?}, {} points, {})",
            self.data.path.display().to_string(),
            self.data.points.len(),
            self.data.format
        )
    }
}

/// A fresh folder name under the system's temporary folder.
fn scratch_folder() -> PathBuf {
    static COUNT: AtomicUsize = AtomicUsize::new(0);
    std::env::temp_dir().join(format!(
        "rollfit-python-{}-{}",
        std::process::id(),
        COUNT.fetch_add(1, Ordering::Relaxed)
    ))
}

/// The fit as `rollfit compare` reads it: from its folder.
fn read_fit(result: &Bound<'_, PyAny>) -> PyResult<FitDir> {
    if let Ok(fit) = result.cast::<FitResult>() {
        let dir = scratch_folder();
        let files = fit.get().files.named();
        output::replace_folder(&dir, output::Writer::Fit, false, &files).map_err(|e| io_error(&e))?;
        let read = FitDir::read(&dir);
        let _ = std::fs::remove_dir_all(&dir);
        return read.map_err(|e| io_error(&e));
    }
    let dir: PathBuf = result.extract().map_err(|_| {
        value_error_text("compare: expected a FitResult or the path of a fit folder")
    })?;
    FitDir::read(&dir).map_err(|e| io_error(&e))
}

/// Compares a fit (a FitResult, or the folder `rollfit fit` wrote) with DMA
/// data (a path, read with the fit's Poisson's ratio as `rollfit compare`
/// reads it, or a DMA from read_dma) and returns compare.json's content as
/// a dict: the errors of tan δ and |E*| (relative), of log10 E′ and log10
/// E″ over the overlap of the fit's window and the DMA's frequencies, the
/// causality check of the DMA data, notes and warnings.
#[pyfunction]
#[pyo3(signature = (result, dma, *, modulus = None, dma_wlf = None))]
pub fn compare<'py>(
    py: Python<'py>,
    result: &Bound<'py, PyAny>,
    dma: &Bound<'py, PyAny>,
    modulus: Option<&str>,
    dma_wlf: Option<(f64, f64, f64)>,
) -> PyResult<Bound<'py, PyAny>> {
    let fit = read_fit(result)?;
    let comparison = if let Ok(read) = dma.cast::<Dma>() {
        if modulus.is_some() || dma_wlf.is_some() {
            return Err(value_error_text(
                "compare: give modulus and dma_wlf to read_dma, or pass the DMA file's path",
            ));
        }
        let read = read.get();
        compare_fit(&fit, &read.data, &read.options)
    } else {
        let path: PathBuf = dma.extract().map_err(|_| {
            value_error_text("compare: expected a DMA from read_dma or the path of a DMA file")
        })?;
        let options = options(modulus, dma_wlf)?;
        let data = DmaData::read(Path::new(&path), fit.summary.poisson, &options)
            .map_err(|e| io_error(&e))?;
        compare_fit(&fit, &data, &options)
    }
    .map_err(|e| value_error(&e))?;
    let json = serde_json::to_vec(&comparison).map_err(|e| value_error(&e))?;
    json_to_python(py, &json)
}
