//! `[fit]`: the scale anchor and the fit settings, and the inverse
//! problem's set-up built from the scene.
//!
//! The anchors (`E0`, `E_at`, `contact_radius`) are measurements of this
//! rolling experiment and are read here; every other key is a fit setting,
//! read by [`FitSettings::set`] through [`super::fit_settings`] like the
//! settings of a batch manifest and the flags of `rollfit fit`
//! (docs/ARCHITECTURE.md, "Contract", "Scene file").

use std::fmt;
use std::path::{Path, PathBuf};

use rollfit_fit::{FitParams, FitSettings, RollingSetup, ScaleAnchor};
use rollfit_model::{Scene, StandardLinearSolid};
use serde::Deserialize;
use serde::de::{Deserializer, MapAccess, Visitor};

use super::fit_settings::{Key, TableSettings};
use super::material::MaterialSection;
use super::messages::section_of;
use super::setup::ContactName;
use super::shift::ShiftKind;
use super::values::{Real, require_positive};
use super::{InSection, SceneFile};
use crate::error::IoError;

/// The keys of `[fit]`: the scale anchors, then the fit settings
/// ([`rollfit_fit::settings::SETTING_KEYS`], in the order messages have
/// always listed them).
pub const FIT_KEYS: [&str; 20] = [
    "E0",
    "E_at",
    "contact_radius",
    "E1_max",
    "terms",
    "terms_per_decade",
    "tau",
    "method",
    "lambda",
    "seed",
    "starts",
    "max_evaluations",
    "tolerance",
    "shift",
    "T_ref",
    "cross_check",
    "physics",
    "dma",
    "dma_sigma",
    "friction_factor",
];

/// `[fit]`: scale anchors and fit settings; forward only validates them.
#[derive(Debug, Clone, Default)]
pub struct FitSection {
    /// Known static Young's modulus, Pa.
    pub e0: Option<Real>,
    /// Known |E| (Young's, Pa) at one angular frequency (rad/s).
    pub e_at: Option<ModulusAnchor>,
    /// Measured contact radius (m) at one speed (m/s).
    pub contact_radius: Option<ContactAnchor>,
    /// Every other key: the fit settings, parsed and range-checked as
    /// they were read.
    pub settings: FitSettings,
}

impl<'de> Deserialize<'de> for FitSection {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct SectionVisitor;
        impl<'de> Visitor<'de> for SectionVisitor {
            type Value = FitSection;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("struct FitSection")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<FitSection, A::Error> {
                let mut section = FitSection::default();
                let mut settings = TableSettings::new("[fit]: ");
                while let Some(key) = map.next_key_seed(Key(&FIT_KEYS))? {
                    match key {
                        "E0" => section.e0 = Some(map.next_value()?),
                        "E_at" => section.e_at = Some(map.next_value()?),
                        "contact_radius" => section.contact_radius = Some(map.next_value()?),
                        setting => map.next_value_seed(settings.value_of(setting))?,
                    }
                }
                section.settings = settings.finish();
                Ok(section)
            }
        }
        deserializer.deserialize_map(SectionVisitor)
    }
}

/// `E_at = { omega, E }`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModulusAnchor {
    /// Angular frequency, rad/s.
    pub omega: Real,
    /// |E*| at that frequency, Pa.
    #[serde(rename = "E")]
    pub e: Real,
}

/// `contact_radius = { v, r }`.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactAnchor {
    /// Rolling speed, m/s.
    pub v: Real,
    /// Contact radius, m.
    pub r: Real,
}

/// Why a scene's `[material.shift] model = "wlf-arrhenius"` is fitted with
/// free shifts.
const WLF_ARRHENIUS_SUBSTITUTE: &str = "the fit's shift laws are WLF, Arrhenius and free \
     shifts: one free log10 a_T per measured temperature follows the two-branch law, its kink at \
     T_g included, but its constants (C1, C2, T_g, E_a) are not fitted (the free log10 a_T are in \
     fit.json's shift); give [fit] shift = \"free\" to ask for free shifts, or \"wlf\" or \
     \"arrhenius\" for one law over all temperatures";

impl FitSection {
    /// Checks the scale anchors: each positive, at most one, and below
    /// `E1_max`. The settings were checked as they were read.
    pub(super) fn check(&self) -> Result<(), IoError> {
        if let Some(Real(e0)) = self.e0 {
            require_positive("E0", e0)?;
        }
        if let Some(anchor) = self.e_at {
            require_positive("E_at.omega", anchor.omega.0)?;
            require_positive("E_at.E", anchor.e.0)?;
        }
        if let Some(anchor) = self.contact_radius {
            require_positive("contact_radius.v", anchor.v.0)?;
            require_positive("contact_radius.r", anchor.r.0)?;
        }
        if let (Some(e1_max), Some(Real(e0))) = (self.settings.e1_max, self.e0)
            && e1_max <= e0
        {
            return Err(err!(
                "E1_max = {e1_max} must exceed the known static modulus E0 = {e0}"
            ));
        }
        let anchors: Vec<&'static str> = [
            ("`E0`", self.e0.is_some()),
            ("`E_at`", self.e_at.is_some()),
            ("`contact_radius`", self.contact_radius.is_some()),
        ]
        .into_iter()
        .filter_map(|(key, present)| present.then_some(key))
        .collect();
        if anchors.len() > 1 {
            return Err(err!(
                "more than one scale anchor ({}): give at most one of E0, E_at and contact_radius",
                anchors.join(", ")
            ));
        }
        Ok(())
    }

    /// The fit parameters the section asks for: its anchor and settings
    /// over the defaults of [`FitParams`].
    pub fn params(&self) -> Result<FitParams, IoError> {
        self.fit_params()
    }

    /// [`Self::params`], with the scene's own error.
    fn fit_params(&self) -> Result<FitParams, IoError> {
        let anchor = match (self.e0, self.e_at, self.contact_radius) {
            (Some(Real(e0)), None, None) => Some(ScaleAnchor::StaticModulus(e0)),
            (None, Some(a), None) => Some(ScaleAnchor::ModulusAt {
                omega: a.omega.0,
                modulus: a.e.0,
            }),
            (None, None, Some(a)) => Some(ScaleAnchor::ContactRadius {
                speed: a.v.0,
                radius: a.r.0,
            }),
            (None, None, None) => None,
            _ => {
                return Err(err!(
                    "give at most one scale anchor (E0, E_at or contact_radius)"
                ));
            }
        };
        let mut params = FitParams {
            anchor,
            ..FitParams::default()
        };
        self.settings.apply(&mut params);
        Ok(params)
    }
}

impl SceneFile {
    /// The DMA file of a joint fit, `[fit] dma`, resolved against
    /// `base_dir` (the scene file's folder, as a `table` material's file
    /// is); None without one. [`FitSettings::apply`] leaves it out of the
    /// fit parameters: the command reads it (the report crate's `master_input::joint::read`)
    /// and hands the isotherms to `ValidFitParams::with_dma`.
    pub fn dma_file(&self, base_dir: &Path) -> Option<PathBuf> {
        let dma = self.fit.as_ref()?.settings.dma.as_deref()?;
        Some(base_dir.join(dma))
    }

    /// Builds the inverse problem's settings: the rolling set-up (checked
    /// by the model, errors prefixed with their section), the `[fit]`
    /// table (defaults where absent) and, for an "sls" or "prony"
    /// `[material]`, its E0 and E1 as the starting point. `[sweep]` is not
    /// used. The fit checks the whole against the set-up with
    /// [`FitParams::check`].
    pub fn fit_setup(&self) -> Result<(RollingSetup, FitParams), IoError> {
        self.inverse_setup()
    }

    /// [`Self::fit_setup`], with the scene's own error.
    fn inverse_setup(&self) -> Result<(RollingSetup, FitParams), IoError> {
        match self.contact.size {
            Some(ContactName::Exact) => {
                return Err(err!(
                    "[contact]: size = \"exact\" is a forward-only reference (its μ has no fast gradient); \
         fit with size = \"dynamic\" (the paper's) or \"static\""
                ));
            }
            Some(name @ (ContactName::LowSpeed | ContactName::Auto)) => {
                return Err(err!(
                    "[contact]: size = \"{size}\" is for rollfit forward only (a fit needs one model with a \
         gradient at every speed); fit with size = \"dynamic\" (the paper's) or \"static\"",
                    size = if name == ContactName::Auto {
                        "auto"
                    } else {
                        "low-speed"
                    }
                ));
            }
            _ => {}
        }
        let setup = self.rolling_setup();
        // The model owns the ranges of the set-up; a placeholder material
        // lets it check them before any fitting starts.
        let placeholder =
            StandardLinearSolid::new(1.0, 2.0, 1.0).map_err(|error| err!("{error}"))?;
        let scene = Scene::new(setup.geometry, setup.substrate, setup.contact, placeholder)
            .map_err(|error| err!("{}{error}", section_of(&error)))?;
        let fit = self.fit.clone().unwrap_or_default();
        let mut params = fit.fit_params().section("[fit]")?;
        scene
            .with_tolerance(params.model_tolerance)
            .map_err(|error| err!("{section}: {error}", section = "[fit]"))?;
        params.start = self.material.as_ref().and_then(MaterialSection::start);
        // A scene's shift gives a temperature set its reference temperature,
        // its law (instead of "auto": the scene has said which law the
        // material follows), for WLF starting constants, and its vertical
        // factors b_T (known, not fitted); [fit] shift and T_ref override
        // the law and T_ref.
        if let Some(shift) = self.material.as_ref().and_then(|m| m.shift.as_ref()) {
            shift.check().section("[material.shift]")?;
            if params.shift.t_ref.is_none() {
                params.shift.t_ref = Some(shift.t_ref.0);
            }
            if let (Some(Real(c1)), Some(Real(c2))) = (shift.c1, shift.c2) {
                params.shift.wlf_start = Some((c1, c2));
            }
            if fit.settings.shift.is_none() {
                params.shift.kind = match shift.model {
                    ShiftKind::Wlf => rollfit_fit::ShiftKind::Wlf,
                    ShiftKind::Arrhenius => rollfit_fit::ShiftKind::Arrhenius,
                    ShiftKind::Free | ShiftKind::WlfArrhenius => rollfit_fit::ShiftKind::Free,
                };
                // The fit has no two-branch law: free shifts follow it, the
                // kink included, and the record says so.
                if shift.model == ShiftKind::WlfArrhenius {
                    params.shift.substituted = Some(rollfit_fit::ShiftSubstitute {
                        requested: "wlf-arrhenius",
                        key: "[material.shift] model",
                        reason: WLF_ARRHENIUS_SUBSTITUTE.into(),
                    });
                }
            }
            params.shift.vertical = shift.vertical_rule().section("[material.shift]")?;
        }
        Ok((setup, params))
    }
}
