//! The message pieces the sections of a scene share: the section a
//! model's refusal belongs to, and a list of model names.

use rollfit_model::ModelError;

/// The section a parameter checked by `Scene::new` lives in, as a message
/// prefix, so that "radius = -1" reads "[geometry]: radius = -1". The
/// model checks the geometry, the substrate and the material together (the
/// load's check needs the material's E(0)) and owns their ranges, so the
/// sections cannot check themselves without copying them.
pub(super) fn section_of(error: &ModelError) -> &'static str {
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
pub(super) fn quoted_or(models: &[&str]) -> String {
    let quoted: Vec<String> = models.iter().map(|m| format!("\"{m}\"")).collect();
    quoted.join(" or ")
}
