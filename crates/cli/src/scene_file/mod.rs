//! The scene file (TOML; docs/ARCHITECTURE.md, "Contract", "Scene file"):
//! its schema and its conversion into validated model objects.
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
//! One file per job: [`setup`] (`[geometry]`, `[substrate]`, `[contact]`),
//! [`material`], [`shift`] (`[material.shift]` and shift rules), [`sweep`],
//! [`fit`] (`[fit]` and the fit's set-up), [`fit_settings`] (fit settings
//! in any TOML table, shared with the batch manifest), [`forward`] (the
//! forward problem) and [`values`] (the number types).
//!
//! [`Scene`]: rollfit_model::Scene

use std::path::Path;

use anyhow::{Context, Result, anyhow, bail};
use rollfit_model::{Scene, ViscoelasticModulus};
use serde::Deserialize;

mod fit;
pub(crate) mod fit_settings;
mod forward;
mod material;
mod setup;
mod shift;
mod sweep;
mod values;

// What the commands use, at the paths they have always used.
pub use forward::{ForwardBlock, ForwardRung, ForwardSetup, ShiftApplied};
pub use material::MaterialKind;

use fit::FitSection;
use material::MaterialSection;
use setup::{ContactName, ContactSection, DEFAULT_POISSON, GeometrySection, SubstrateSection};
use sweep::SweepSection;
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
pub fn load(path: &Path) -> Result<SceneFile> {
    let text = rollfit_io::text_file::read_utf8(path, "scene file")?;
    parse(&text).with_context(|| format!("scene file {}", path.display()))
}

/// Parses and validates scene-file text (the sections' internal consistency;
/// the model checks physical ranges when the scene is built).
pub fn parse(text: &str) -> Result<SceneFile> {
    // toml's message already carries "line L, column C" and the offending line.
    let mut file: SceneFile =
        toml::from_str(text).map_err(|e| anyhow!("{}", e.to_string().trim_end()))?;
    let poisson = file.substrate.poisson.map_or(DEFAULT_POISSON, |r| r.0);
    if let Some(material) = &mut file.material {
        material.dma.poisson = Some(poisson);
    }
    if let Some(material) = &file.material {
        material.check_keys()?;
        if let Some(shift) = &material.shift {
            shift.check().context("[material.shift]")?;
        }
    }
    file.contact.check()?;
    if file.contact.size == Some(ContactName::Auto)
        && file.sweep.as_ref().is_some_and(|s| s.tolerance.is_some())
    {
        bail!(
            "[sweep]: tolerance is set by size = \"auto\" itself (a tenth of [contact] \
             accuracy); remove it, or choose a rung with size = \"dynamic\""
        );
    }
    if let Some(fit) = &file.fit {
        fit.check().context("[fit]")?;
    }
    if let Some(sweep) = &file.sweep {
        sweep.speeds().context("[sweep]")?;
        if let Some(temperature) = &sweep.temperature {
            temperature.check().context("[sweep]")?;
            if file
                .material
                .as_ref()
                .is_some_and(|m| m.shift.is_none() && m.model != MaterialKind::Dma)
            {
                bail!(temperature_without_shift(temperature));
            }
        }
    }
    Ok(file)
}

#[cfg(test)]
mod tests;
