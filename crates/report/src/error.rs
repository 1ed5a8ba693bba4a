//! The one error type of the report crate: what stops a comparison with
//! DMA data or a picture. Reading the fit folder and the DMA file is the
//! io crate's, with its own error ([`rollfit_io::IoError`]).

use std::path::PathBuf;

use thiserror::Error;

/// Everything that can stop a report or a comparison. A DMA file is named
/// by its path; temperatures are shown to 0.1 °C.
#[derive(Debug, Error)]
pub enum ReportError {
    /// Some DMA points have a temperature and some do not.
    #[error(
        "{}: {without} of {total} points have no temperature: cannot tell which isotherm they \
         belong to",
        path.display()
    )]
    MixedTemperatures {
        /// The DMA file.
        path: PathBuf,
        /// Points without a temperature.
        without: usize,
        /// All points.
        total: usize,
    },
    /// A DMA isotherm outside what the fit's shift covers.
    #[error(
        "{}: the DMA isotherm at {temperature:.1} °C cannot be shifted with the fit's {model} \
         shift (it covers {lo} to {hi} °C{}); give the DMA's own WLF constants with --dma-wlf \
         T_REF,C1,C2 (`rollfit master` finds them from the isotherms)",
        path.display(),
        if *wlf { ", and WLF diverges below T_ref − C2" } else { "" }
    )]
    OutsideFitShift {
        /// The DMA file.
        path: PathBuf,
        /// The isotherm, °C.
        temperature: f64,
        /// The fit's shift model.
        model: String,
        /// Lowest temperature the shift covers, °C.
        lo: f64,
        /// Highest, °C.
        hi: f64,
        /// The fit's shift is WLF.
        wlf: bool,
    },
    /// A DMA temperature at or below the divergence of the DMA's own WLF.
    #[error(
        "{}: {temperature:.1} °C is at or below the divergence of the DMA's WLF (T_ref − C2 = \
         {pole} °C): it cannot be shifted",
        path.display()
    )]
    BelowDmaWlfPole {
        /// The DMA file.
        path: PathBuf,
        /// °C.
        temperature: f64,
        /// T_ref − C2 of the DMA's WLF, °C.
        pole: f64,
    },
    /// Several DMA temperatures and no shift to bring them together.
    #[error(
        "{}: {} temperatures ({} °C) but the fit has no shift (it is not a temperature set): give \
         the DMA's own WLF constants with --dma-wlf T_REF,C1,C2 (`rollfit master` finds them \
         from the isotherms)",
        path.display(),
        temperatures.len(),
        temperatures.iter().map(|t| format!("{t:.1}")).collect::<Vec<_>>().join(", ")
    )]
    NoShift {
        /// The DMA file.
        path: PathBuf,
        /// The isotherms, °C.
        temperatures: Vec<f64>,
    },
    /// The causality check of the DMA points failed.
    #[error(transparent)]
    Causality(#[from] rollfit_fit::FitError),
    /// The scene read for the dense fitted μ(v) does not give the fit's μ
    /// at the measured speeds (`fitted_friction`).
    #[error(
        "the scene does not reproduce the fit's μ at the measured speeds ({:.2} % off at v = \
         {speed:e} m/s{}): it is not the scene the fit was made with, or it was edited since",
        100.0 * off,
        temperature.map_or_else(String::new, |t| format!(", T = {t} °C"))
    )]
    SceneMismatch {
        /// |μ_scene/μ_fit − 1| at that speed (NaN when not a number).
        off: f64,
        /// The measured speed, m/s.
        speed: f64,
        /// Its temperature, °C, in a temperature set.
        temperature: Option<f64>,
    },
    /// The fitted μ(v) cannot be computed under the scene.
    #[error("the fitted μ(v) cannot be computed under the scene: {message}")]
    FittedFriction {
        /// What the model or the shift said.
        message: String,
    },
    /// Drawing a picture failed.
    #[error("picture {name}: {message}")]
    Plot {
        /// The picture's file stem.
        name: String,
        /// What plotters or the encoder said.
        message: String,
    },
}
