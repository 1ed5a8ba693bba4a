//! The scene file (TOML; docs/ARCHITECTURE.md, "Contract", "Scene file"),
//! read by `rollfit forward`, `fit`, `batch` and `bench`: its schema and
//! its conversion into validated model objects. An error names the file
//! ([`in_file`]) and the section ([`InSection`]) before its cause; the
//! files a material refers to are read by [`crate::table`] and
//! [`crate::dma`].
//!
//! Parsing happens in two steps. serde turns the text into the plain
//! structs of the sections; type errors, unknown keys, non-finite numbers
//! and the fit settings of `[fit]` (through the fit library's one parser,
//! [`rollfit_fit::FitSettings::set`]) are caught there, so toml can point
//! at the line and column. The conversion into [`Scene`] then checks what
//! serde cannot see (which keys a material model needs, ranges, ordering)
//! and names the section and key of every problem. Physical ranges of scene
//! and material parameters are left to the model's constructors, which own
//! them; this module only prefixes their messages with the section they
//! came from.
//!
//! One file per job: `setup.rs` (`[geometry]`, `[substrate]`,
//! `[contact]`), `material.rs`, `shift.rs` (`[material.shift]` and shift
//! rules), `sweep.rs`, `fit.rs` (`[fit]` and the fit's set-up),
//! `fit_settings.rs` (fit settings in any TOML table, shared with the
//! batch manifest, [`crate::manifest`]), `forward.rs` (the forward
//! problem) and `values.rs` (the number types).
//!
//! [`Scene`]: rollfit_model::Scene

use std::path::Path;

use rollfit_model::{Scene, ViscoelasticModulus};
use serde::Deserialize;

use crate::error::IoError;

mod fit;
pub(crate) mod fit_settings;
mod forward;
mod material;
mod messages;
mod setup;
mod shift;
mod sweep;
mod values;
mod vertical;

// What the commands use, at the paths they have always used.
pub use fit::{ContactAnchor, FIT_KEYS, FitSection, ModulusAnchor};
pub use forward::{ForwardBlock, ForwardRung, ForwardSetup, ShiftApplied};
pub use material::{MaterialKind, MaterialSection, ModulusName};
pub use setup::{
    ContactName, ContactSection, DEFAULT_ACCURACY, DEFAULT_POISSON, GeometrySection, ShapeName,
    SubstrateSection,
};
pub use shift::{ShiftKind, ShiftPoint, ShiftSection};
pub use sweep::{DEFAULT_SWEEP_COUNT, MAX_SWEEP_COUNT, SweepSection, SweepTemperature, log_spaced};
pub use values::{Real, RealOrList};
pub use vertical::{VerticalLawName, VerticalPoint};

use sweep::temperature_without_shift;

/// The scene the forward model runs on: any material behind one pointer, so
/// that a shifted table and a plain standard linear solid share one type.
pub type DynScene = Scene<Box<dyn ViscoelasticModulus>>;

/// A whole scene file as written. Field names follow the file's keys.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// `[geometry]`, required.
    pub geometry: GeometrySection,
    /// `[substrate]`, optional (ν = ½, half-space).
    #[serde(default)]
    pub substrate: SubstrateSection,
    /// `[contact]`, optional (dynamic contact size).
    #[serde(default)]
    pub contact: ContactSection,
    /// `[material]`: required by forward, a starting point for fit.
    pub material: Option<MaterialSection>,
    /// `[fit]`: only used by fit.
    pub fit: Option<FitSection>,
    /// `[sweep]`: only used by forward.
    pub sweep: Option<SweepSection>,
}

/// Reads, parses and validates a scene file; every error names `path`.
pub fn load(path: &Path) -> Result<SceneFile, IoError> {
    let text = crate::text_file::read_utf8(path, "scene file")?;
    parse_text(&text).map_err(|e| in_file(path, e))
}

/// Parses and validates scene-file text (the sections' internal consistency;
/// the model checks physical ranges when the scene is built).
pub fn parse(text: &str) -> Result<SceneFile, IoError> {
    parse_text(text)
}

/// `error` behind the scene file's name: `scene file PATH: …`.
pub fn in_file(path: &Path, error: impl Into<IoError>) -> IoError {
    err!("scene file {}", path.display())
        .in_file(path)
        .caused_by(error.into())
}

/// `error` behind the section it was found in: `[sweep]: …`.
pub(crate) trait InSection<T> {
    /// The error behind `section` (with its brackets, `"[sweep]"`).
    fn section(self, section: &'static str) -> Result<T, IoError>;
}

impl<T, E: Into<IoError>> InSection<T> for Result<T, E> {
    fn section(self, section: &'static str) -> Result<T, IoError> {
        self.map_err(|e| err!("{section}").caused_by(e.into()))
    }
}

/// [`parse`], with the scene's own error.
fn parse_text(text: &str) -> Result<SceneFile, IoError> {
    // toml's message already carries "line L, column C" and the offending line.
    let mut file: SceneFile =
        toml::from_str(text).map_err(|error| err!("{}", error.to_string().trim_end()))?;
    let poisson = file.substrate.poisson.map_or(DEFAULT_POISSON, |r| r.0);
    // Checked before any material reads a file with it (a table's shear
    // moduli are converted with it), so that ν is refused as the scene's.
    rollfit_model::check_poisson(poisson)
        .map_err(|e| err!("{}", rollfit_model::ModelError::from(e)))
        .section("[substrate]")?;
    if let Some(Real(thickness)) = file.substrate.thickness {
        rollfit_model::check_film_thickness(thickness)
            .map_err(|error| err!("{error}"))
            .section("[substrate]")?;
    }
    if let Some(material) = &mut file.material {
        material.dma.poisson = Some(poisson);
    }
    if let Some(material) = &file.material {
        material.check_keys()?;
        if let Some(shift) = &material.shift {
            shift.check().section("[material.shift]")?;
        }
    }
    file.contact.check()?;
    if file.contact.size == Some(ContactName::Auto)
        && file.sweep.as_ref().is_some_and(|s| s.tolerance.is_some())
    {
        return Err(err!(
            "[sweep]: tolerance is set by size = \"auto\" itself (a tenth of [contact] accuracy); \
         remove it, or choose a rung with size = \"dynamic\""
        ));
    }
    if let Some(fit) = &file.fit {
        fit.check().section("[fit]")?;
    }
    if let Some(sweep) = &file.sweep {
        sweep.check_speeds().section("[sweep]")?;
        if let Some(temperature) = &sweep.temperature {
            temperature.check().section("[sweep]")?;
            if file
                .material
                .as_ref()
                .is_some_and(|m| m.shift.is_none() && m.model != MaterialKind::Dma)
            {
                return Err(temperature_without_shift(temperature));
            }
        }
    }
    Ok(file)
}

#[cfg(test)]
mod tests;
