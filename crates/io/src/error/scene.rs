//! The errors of a scene file ([`SceneError`], reached as
//! [`super::IoError::Scene`]; read by [`crate::scene`], docs/ARCHITECTURE.md,
//! "Contract", "Scene file"). The causes inside a file name the section
//! and key at fault, and toml's own messages the line and column; the
//! file is named by [`SceneError::InFile`], the section of a cause found
//! further down by [`SceneError::InSection`], each printed before its
//! source by `{:#}`: `scene file s.toml: [sweep]: count = 0: must be at
//! least 1`. The model's messages are shown as they are, behind the
//! section they came from.

use rollfit_model::ModelError;

/// The section a parameter checked by `Scene::new` lives in, as a message
/// prefix, so that "radius = -1" reads "[geometry]: radius = -1". The
/// model checks the geometry, the substrate and the material together (the
/// load's check needs the material's E(0)) and owns their ranges, so the
/// sections cannot check themselves without copying them.
pub(crate) fn section_of(error: &ModelError) -> &'static str {
    match error {
        ModelError::InvalidParameter { name, .. } => match name.as_str() {
            "radius" | "load" => "[geometry]: ",
            "poisson" | "thickness" => "[substrate]: ",
            _ => "[material]: ",
        },
        ModelError::Poisson(_) => "[substrate]: ",
        _ => "",
    }
}

/// `"dma" or "table"`.
pub(crate) fn quoted_or(models: &[&str]) -> String {
    let quoted: Vec<String> = models.iter().map(|m| format!("\"{m}\"")).collect();
    quoted.join(" or ")
}
