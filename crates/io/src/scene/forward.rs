//! The forward problem of `rollfit forward` (and `rollfit bench`) from a
//! scene file (docs/ARCHITECTURE.md, "Contract", "Scene file"): one scene
//! per `[sweep]` temperature, and the rung of the model ladder that gives
//! μ.

use std::path::Path;
use std::sync::Arc;

use rollfit_fit::RollingSetup;
use rollfit_model::Shape;
use rollfit_model::exact::{ExactRolling, ExactSettings, RollingCylinder, RollingSphere};
use rollfit_model::{Prony, Scene, Shifted, ViscoelasticModulus};

use super::material::MaterialSection;
use super::messages::section_of;
use super::setup::{ContactName, DEFAULT_ACCURACY, ShapeName};
use super::sweep::temperature_without_shift;
use super::values::Real;
use super::vertical;
use super::{DynScene, InSection, SceneFile};
use crate::error::IoError;

/// How `rollfit forward` computes μ for a block.
pub enum ForwardRung {
    /// Eq. (11)/(17) with the scene's contact-size rule.
    Paper,
    /// The low-speed asymptote at every speed.
    LowSpeed,
    /// The exact rolling cylinder or sphere of the (shifted) material.
    Exact(Box<dyn ExactRolling>),
    /// `auto` with its accuracy and, where the scene has one, the exact
    /// rolling body (else why not).
    Auto {
        /// Requested relative accuracy.
        accuracy: f64,
        /// The exact rolling cylinder or sphere, or why there is none.
        exact: std::result::Result<Box<dyn ExactRolling>, String>,
    },
}

/// A temperature the material was shifted to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShiftApplied {
    /// Temperature, °C.
    pub temperature: f64,
    /// log10 a_T applied to the reference-temperature modulus.
    pub log10_a_t: f64,
    /// log10 b_T applied (0 without vertical factors):
    /// E*(ω, T) = b_T E*_ref(ω a_T).
    pub log10_b_t: f64,
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
    /// Builds the forward problem. `scene_path` locates files the scene
    /// refers to; `note` receives what a modulus table's reader says about
    /// the file, each time the table is read.
    pub fn forward_setup(
        &self,
        scene_path: &Path,
        note: &dyn Fn(&str),
    ) -> Result<ForwardSetup, IoError> {
        self.forward_blocks(scene_path, note)
    }

    /// [`Self::forward_setup`], with the scene's own error.
    fn forward_blocks(
        &self,
        scene_path: &Path,
        note: &dyn Fn(&str),
    ) -> Result<ForwardSetup, IoError> {
        let material_section = self.material.as_ref().ok_or(err!(
            "forward needs a [material] section (the modulus to predict μ(v) from)"
        ))?;
        let sweep = self.sweep.as_ref().ok_or(err!(
            "forward needs a [sweep] section (v_min, v_max, count or v = [..])"
        ))?;
        let speeds = sweep.check_speeds().section("[sweep]")?;

        let base_dir = scene_path.parent().unwrap_or(Path::new(""));
        let material = material_section
            .build(base_dir, note)
            .section("[material]")?;
        let materials: Vec<(Box<dyn ViscoelasticModulus>, Option<ShiftApplied>)> =
            match &sweep.temperature {
                None => vec![(material, None)],
                Some(temperatures) => {
                    temperatures.check().section("[sweep]")?;
                    let rule = material_section
                        .shift_rule(base_dir)
                        .section("[material]")?
                        .ok_or_else(|| temperature_without_shift(temperatures))?;
                    let vertical = material_section
                        .vertical_rule(base_dir)
                        .section("[material]")?;
                    // One reference modulus (a table is read once), shifted
                    // to each temperature.
                    let reference: Arc<dyn ViscoelasticModulus> = Arc::from(material);
                    let mut materials = Vec::new();
                    for (i, &temperature) in temperatures.values().iter().enumerate() {
                        let at = |e| {
                            err!(
                                "[material.shift] at [sweep] {entry} °C",
                                entry = temperatures.entry(i)
                            )
                            .caused_by(e)
                        };
                        let log10_a_t = rule.log10_shift(temperature).map_err(at)?;
                        let log10_b_t = match &vertical {
                            Some(v) => vertical::log10_factor(v, temperature).map_err(at)?,
                            None => 0.0,
                        };
                        let shifted = Shifted::new(Arc::clone(&reference), log10_a_t)
                            .and_then(|s| s.with_vertical(log10_b_t))
                            .map_err(|error| {
                                err!("{section}: {error}", section = "[material.shift]")
                            })?;
                        let applied = ShiftApplied {
                            temperature,
                            log10_a_t,
                            log10_b_t,
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
                .map_err(|error| err!("{}{error}", section_of(&error)))?;
            if let Some(Real(tolerance)) = sweep.tolerance {
                scene = scene
                    .with_tolerance(tolerance)
                    .map_err(|error| err!("{section}: {error}", section = "[sweep]"))?;
            }
            let rung = match self.contact.size {
                Some(ContactName::Exact) => {
                    ForwardRung::Exact(self.exact_body(material_section, base_dir, shift, note)?)
                }
                Some(ContactName::LowSpeed) => ForwardRung::LowSpeed,
                Some(ContactName::Auto) => ForwardRung::Auto {
                    accuracy: self.contact.accuracy.map_or(DEFAULT_ACCURACY, |r| r.0),
                    // auto may use the exact cylinder where a film is
                    // negligible, so the film does not rule it out here.
                    exact: self
                        .exact_material_for(
                            material_section,
                            base_dir,
                            shift.map(|s| (s.log10_a_t, s.log10_b_t)),
                            false,
                            note,
                        )
                        .and_then(|prony| self.exact_body_with(&prony))
                        .map_err(|e| crate::chain(&e)),
                },
                None | Some(ContactName::Dynamic) | Some(ContactName::Static) => ForwardRung::Paper,
            };
            blocks.push(ForwardBlock { scene, shift, rung });
        }
        Ok(ForwardSetup { blocks, speeds })
    }
}

impl SceneFile {
    /// The exact rolling body of `[contact] size = "exact"`: a cylinder or
    /// sphere on a half-space, the material a standard linear solid or a
    /// Prony series (shifted by log10 a_T: τ_k → τ_k a_T, and scaled by
    /// b_T: E1, H_k → b_T E1, b_T H_k).
    fn exact_body(
        &self,
        material: &MaterialSection,
        base_dir: &Path,
        shift: Option<ShiftApplied>,
        note: &dyn Fn(&str),
    ) -> Result<Box<dyn ExactRolling>, IoError> {
        let factors = shift.map(|s| (s.log10_a_t, s.log10_b_t));
        let prony = self.exact_material_for(material, base_dir, factors, true, note)?;
        self.exact_body_with(&prony)
    }

    /// The exact rolling cylinder or sphere of this scene for `prony`, with
    /// the default discretisation.
    fn exact_body_with(&self, prony: &Prony) -> Result<Box<dyn ExactRolling>, IoError> {
        Ok(match self.rolling_setup().geometry.shape {
            Shape::Cylinder => Box::new(self.exact_with(prony, ExactSettings::default())?),
            Shape::Sphere => {
                let setup = self.rolling_setup();
                Box::new(
                    RollingSphere::new(
                        prony,
                        setup.substrate.poisson,
                        setup.geometry.radius,
                        setup.geometry.load,
                    )
                    .map_err(|error| err!("{section}: {error}", section = "[contact] exact"))?,
                )
            }
        })
    }

    /// The Prony series the exact solution of this scene uses, after
    /// checking that it applies (cylinder, half-space, "sls" or "prony");
    /// `note` as for [`Self::forward_setup`].
    pub fn exact_material(
        &self,
        material: &MaterialSection,
        base_dir: &Path,
        log10_a_t: Option<f64>,
        note: &dyn Fn(&str),
    ) -> Result<Prony, IoError> {
        // The callers build the exact cylinder from it.
        if self.geometry.shape != ShapeName::Cylinder {
            return Err(err!(
                "[contact]: this needs shape = \"cylinder\": the reference is the plane-strain exact \
         rolling cylinder"
            ));
        }
        let factors = log10_a_t.map(|a| (a, 0.0));
        self.exact_material_for(material, base_dir, factors, true, note)
    }

    /// As [`Self::exact_material`], shifted by `factors` = (log10 a_T,
    /// log10 b_T); `refuse_film`: a film rules the exact solution out (it
    /// is for a half-space).
    fn exact_material_for(
        &self,
        material: &MaterialSection,
        base_dir: &Path,
        factors: Option<(f64, f64)>,
        refuse_film: bool,
        note: &dyn Fn(&str),
    ) -> Result<Prony, IoError> {
        if refuse_film && self.substrate.thickness.is_some() {
            return Err(err!(
                "[contact]: size = \"exact\" is for a half-space; remove [substrate] thickness (films use \
         size = \"dynamic\" or \"static\")"
            ));
        }
        let Some(prony) = material.prony(base_dir, note).section("[material]")? else {
            return Err(err!(
                "[contact]: size = \"exact\" needs [material] model = \"sls\" or \"prony\" (the exact \
         solution works with the creep compliance of a Prony series)"
            ));
        };
        Ok(match factors {
            Some((log10_a_t, log10_b_t)) => prony
                .shifted(log10_a_t)
                .and_then(|p| p.scaled(log10_b_t))
                .map_err(|error| err!("{section}: {error}", section = "[material.shift]"))?,
            None => prony,
        })
    }

    /// The exact rolling cylinder of this scene's geometry and substrate
    /// for `prony` with explicit discretisation settings.
    pub fn exact_cylinder_with(
        &self,
        prony: &Prony,
        settings: ExactSettings,
    ) -> Result<RollingCylinder, IoError> {
        self.exact_with(prony, settings)
    }

    /// [`Self::exact_cylinder_with`], with the scene's own error.
    fn exact_with(
        &self,
        prony: &Prony,
        settings: ExactSettings,
    ) -> Result<RollingCylinder, IoError> {
        let setup = self.rolling_setup();
        RollingCylinder::with_settings(
            prony,
            setup.substrate.poisson,
            setup.geometry.radius,
            setup.geometry.load,
            settings,
        )
        .map_err(|error| err!("{section}: {error}", section = "[contact] exact"))
    }
}
