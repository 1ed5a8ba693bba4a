//! A fit folder as `rollfit fit` writes it and everything after reads it
//! (docs/ARCHITECTURE.md, "Contract", "Fit folder"): fit.json, mu.csv and
//! modulus.csv, their names defined once ([`columns`]), written by
//! [`mod@write`] and read back by [`FitDir::read`] (or, leniently, for a batch
//! summary, by [`digest`]).
//!
//! Reading requires only the contract's keys and columns; everything
//! rollfit adds beyond them (bands, runs, shift, warnings) is optional, so
//! a fit.json written by another program that honours the contract can be
//! reported too. The master curve is rebuilt from the Prony series, so it
//! can be drawn and compared outside the window modulus.csv covers. What
//! fit.json says about trusting the fit (verdict, noise, scale) is read
//! by [`quality`].
//!
//! A fit.json edited by hand is checked where a wrong value would be read
//! as something else rather than fail ([`summary`]). Errors name fit.json
//! and the key (`shift.log_aT[2].T`); serde's own errors get the key too
//! (`json_error.rs`).

use std::path::{Path, PathBuf};

use num_complex::Complex64;
use rollfit_model::{Prony, ViscoelasticModulus};

use crate::error::IoError;
use crate::text_file::read_utf8_file;

pub mod columns;
pub mod digest;
mod json_error;
pub mod mu_csv;
pub mod quality;
mod read;
pub mod summary;
pub mod write;

pub use mu_csv::{Measured, MuCsv};
pub use quality::{CondensedSummary, QualitySummary, RunsSummary, ScaleSummary};
pub use read::{FrictionRow, ModulusRow};
pub use summary::{
    AnchorSummary, FitSummary, InputSummary, LambdaSummary, LogShiftSummary, ModelSummary,
    PhysicsSummary, RunSummary, ShiftSummary, WindowSummary,
};
pub use write::{FitFiles, FitFolder, FitInput};

/// A fit directory read back.
#[derive(Debug, Clone)]
pub struct FitDir {
    /// The directory.
    pub dir: PathBuf,
    /// fit.json.
    pub summary: FitSummary,
    /// mu.csv.
    pub friction: Vec<FrictionRow>,
    /// modulus.csv.
    pub modulus: Vec<ModulusRow>,
    /// The master curve at the reference state, rebuilt from fit.json.
    pub master_curve: Prony,
}

impl FitDir {
    /// Reads DIR/fit.json, DIR/mu.csv and DIR/modulus.csv.
    pub fn read(dir: &Path) -> Result<FitDir, IoError> {
        if !dir.is_dir() {
            return Err(err!(
                "{}: not a fit directory (run `rollfit fit SCENE DATA -o DIR` first)",
                dir.display()
            ));
        }
        let json_path = dir.join(columns::FIT_JSON);
        let text = read_utf8_file(&json_path)?;
        let summary: FitSummary = serde_json::from_str(&text)
            .map_err(|e| json_error::json_error(&json_path, &text, &e))?;
        summary.check(&json_path, &text)?;
        if summary.model.kind != "prony" {
            return Err(err!(
                "{}: model.kind = \"{kind}\": only \"prony\" master curves can be reported",
                json_path.display(),
                kind = summary.model.kind
            ));
        }
        let master_curve = Prony::new(
            summary.model.glassy_modulus,
            summary.model.strengths.clone(),
            summary.model.tau.clone(),
        )
        .map_err(|source| err!("{}: model: {source}", json_path.display()).caused_by(source))?;
        let window = summary.window;
        if !(window.omega_min > 0.0 && window.omega_max > window.omega_min) {
            return Err(err!(
                "{}: window: omega_min = {omega_min}, omega_max = {omega_max}: need 0 < omega_min < \
         omega_max",
                json_path.display(),
                omega_max = window.omega_max,
                omega_min = window.omega_min
            ));
        }
        let friction = read::read_friction(&dir.join(columns::MU_CSV))?;
        let modulus = read::read_modulus(&dir.join(columns::MODULUS_CSV))?;
        Ok(FitDir {
            dir: dir.to_path_buf(),
            summary,
            friction,
            modulus,
            master_curve,
        })
    }

    /// E*(ω) of the master curve at the reference state (Young's, Pa).
    pub fn modulus_at(&self, omega: f64) -> Complex64 {
        self.master_curve.modulus(omega)
    }

    /// Whether the fit is a temperature set (fit.json has a shift).
    pub fn is_temperature_set(&self) -> bool {
        self.summary.shift.is_some()
    }
}

#[cfg(test)]
mod tests;
