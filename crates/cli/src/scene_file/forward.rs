//! The forward problem of `rollfit forward`: one scene per `[sweep]`
//! temperature, and the rung of the model ladder that gives μ.

use std::path::Path;
use std::sync::Arc;

use anyhow::{Context, Result, anyhow, bail};
use rollfit_fit::RollingSetup;
use rollfit_model::exact::{ExactSettings, RollingCylinder};
use rollfit_model::{Prony, Scene, Shifted, ViscoelasticModulus};

use super::material::MaterialSection;
use super::setup::{ContactName, DEFAULT_ACCURACY, ShapeName, section_of};
use super::sweep::temperature_without_shift;
use super::values::Real;
use super::{DynScene, SceneFile};

/// How `rollfit forward` computes μ for a block.
pub enum ForwardRung {
    /// Eq. (11)/(17) with the scene's contact-size rule.
    Paper,
    /// The low-speed asymptote at every speed.
    LowSpeed,
    /// The exact rolling cylinder of the (shifted) material.
    Exact(RollingCylinder),
    /// `auto` with its accuracy and, where the scene has one, the exact
    /// cylinder (else why not).
    Auto {
        /// Requested relative accuracy.
        accuracy: f64,
        /// The exact rolling cylinder, or why there is none.
        exact: std::result::Result<RollingCylinder, String>,
    },
}

/// A temperature the material was shifted to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShiftApplied {
    /// Temperature, °C.
    pub temperature: f64,
    /// log10 a_T applied to the reference-temperature modulus.
    pub log10_a_t: f64,
}

/// One sweep of `rollfit forward`: the scene at one temperature.
pub struct ForwardBlock {
    /// The scene, material already shifted to the block's temperature.
    pub scene: DynScene,
    /// The rung that gives μ.
    pub rung: ForwardRung,
    /// The temperature shift, if the sweep asked for a temperature.
    pub shift: Option<ShiftApplied>,
}

/// Everything `rollfit forward` needs, validated.
pub struct ForwardSetup {
    /// One block per `[sweep] temperature`, in the listed order; a single
    /// block at the material's reference temperature without the key.
    pub blocks: Vec<ForwardBlock>,
    /// Strictly increasing speeds, m/s, the same in every block.
    pub speeds: Vec<f64>,
}

impl SceneFile {
    /// Builds the forward problem. `scene_path` locates files the scene refers to.
    pub fn forward_setup(&self, scene_path: &Path) -> Result<ForwardSetup> {
        let material_section = self
            .material
            .as_ref()
            .context("forward needs a [material] section (the modulus to predict μ(v) from)")?;
        let sweep = self
            .sweep
            .as_ref()
            .context("forward needs a [sweep] section (v_min, v_max, count or v = [..])")?;
        let speeds = sweep.speeds().context("[sweep]")?;

        let base_dir = scene_path.parent().unwrap_or(Path::new(""));
        let material = material_section.build(base_dir).context("[material]")?;
        let materials: Vec<(Box<dyn ViscoelasticModulus>, Option<ShiftApplied>)> =
            match &sweep.temperature {
                None => vec![(material, None)],
                Some(temperatures) => {
                    temperatures.check().context("[sweep]")?;
                    let rule = material_section
                        .shift_rule(base_dir)
                        .context("[material]")?
                        .with_context(|| temperature_without_shift(temperatures))?;
                    // One reference modulus (a table is read once), shifted
                    // to each temperature.
                    let reference: Arc<dyn ViscoelasticModulus> = Arc::from(material);
                    let mut materials = Vec::new();
                    for (i, &temperature) in temperatures.values().iter().enumerate() {
                        let log10_a_t = rule.log10_shift(temperature).with_context(|| {
                            format!("[material.shift] at [sweep] {} °C", temperatures.entry(i))
                        })?;
                        let shifted = Shifted::new(Arc::clone(&reference), log10_a_t)
                            .map_err(|e| anyhow!("[material.shift]: {e}"))?;
                        let applied = ShiftApplied {
                            temperature,
                            log10_a_t,
                        };
                        materials.push((
                            Box::new(shifted) as Box<dyn ViscoelasticModulus>,
                            Some(applied),
                        ));
                    }
                    materials
                }
            };

        let RollingSetup {
            geometry,
            substrate,
            contact,
        } = self.rolling_setup();
        let mut blocks = Vec::with_capacity(materials.len());
        for (material, shift) in materials {
            let mut scene = Scene::new(geometry, substrate, contact, material)
                .map_err(|e| anyhow!("{}{e}", section_of(&e)))?;
            if let Some(Real(tolerance)) = sweep.tolerance {
                scene = scene
                    .with_tolerance(tolerance)
                    .map_err(|e| anyhow!("[sweep]: {e}"))?;
            }
            let log10_a_t = shift.map(|s| s.log10_a_t);
            let rung = match self.contact.size {
                Some(ContactName::Exact) => ForwardRung::Exact(self.exact_cylinder(
                    material_section,
                    base_dir,
                    log10_a_t,
                )?),
                Some(ContactName::LowSpeed) => ForwardRung::LowSpeed,
                Some(ContactName::Auto) => ForwardRung::Auto {
                    accuracy: self.contact.accuracy.map_or(DEFAULT_ACCURACY, |r| r.0),
                    // auto may use the exact cylinder where a film is
                    // negligible, so the film does not rule it out here.
                    exact: self
                        .exact_material_for(material_section, base_dir, log10_a_t, false)
                        .and_then(|prony| {
                            self.exact_cylinder_with(&prony, ExactSettings::default())
                        })
                        .map_err(|e| format!("{e:#}")),
                },
                None | Some(ContactName::Dynamic) | Some(ContactName::Static) => ForwardRung::Paper,
            };
            blocks.push(ForwardBlock { scene, shift, rung });
        }
        Ok(ForwardSetup { blocks, speeds })
    }
}

impl SceneFile {
    /// The exact rolling cylinder of `[contact] size = "exact"`: a cylinder
    /// on a half-space, the material a standard linear solid or a Prony
    /// series (shifted by log10 a_T: τ_k → τ_k a_T).
    fn exact_cylinder(
        &self,
        material: &MaterialSection,
        base_dir: &Path,
        log10_a_t: Option<f64>,
    ) -> Result<RollingCylinder> {
        let prony = self.exact_material(material, base_dir, log10_a_t)?;
        self.exact_cylinder_with(&prony, ExactSettings::default())
    }

    /// The Prony series the exact solution of this scene uses, after
    /// checking that it applies (cylinder, half-space, "sls" or "prony").
    pub(crate) fn exact_material(
        &self,
        material: &MaterialSection,
        base_dir: &Path,
        log10_a_t: Option<f64>,
    ) -> Result<Prony> {
        self.exact_material_for(material, base_dir, log10_a_t, true)
    }

    /// As [`Self::exact_material`]; `refuse_film`: a film rules the exact
    /// solution out (it is for a half-space).
    fn exact_material_for(
        &self,
        material: &MaterialSection,
        base_dir: &Path,
        log10_a_t: Option<f64>,
        refuse_film: bool,
    ) -> Result<Prony> {
        if self.geometry.shape != ShapeName::Cylinder {
            bail!(
                "[contact]: size = \"exact\" needs shape = \"cylinder\": the exact solution is the \
                 plane-strain rolling cylinder (there is no three-dimensional one for a sphere)"
            );
        }
        if refuse_film && self.substrate.thickness.is_some() {
            bail!(
                "[contact]: size = \"exact\" is for a half-space; remove [substrate] thickness \
                 (films use size = \"dynamic\" or \"static\")"
            );
        }
        let Some(prony) = material.prony(base_dir).context("[material]")? else {
            bail!(
                "[contact]: size = \"exact\" needs [material] model = \"sls\" or \"prony\" \
                 (the exact solution works with the creep compliance of a Prony series)"
            );
        };
        Ok(match log10_a_t {
            Some(l) => prony
                .shifted(l)
                .map_err(|e| anyhow!("[material.shift]: {e}"))?,
            None => prony,
        })
    }

    /// The exact rolling cylinder of this scene's geometry and substrate
    /// for `prony` with explicit discretisation settings.
    pub(crate) fn exact_cylinder_with(
        &self,
        prony: &Prony,
        settings: ExactSettings,
    ) -> Result<RollingCylinder> {
        let setup = self.rolling_setup();
        RollingCylinder::with_settings(
            prony,
            setup.substrate.poisson,
            setup.geometry.radius,
            setup.geometry.load,
            settings,
        )
        .map_err(|e| anyhow!("[contact] exact: {e}"))
    }
}
