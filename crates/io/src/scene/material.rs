//! `[material]`: the modulus E*(ω) at the reference temperature, its keys
//! per model, and what the fit and the exact solution take from it
//! (docs/ARCHITECTURE.md, "Contract", "Scene file"). A `table` is read by
//! [`crate::table`], a `dma` file read by [`crate::dma`] and made a master
//! curve by the fit library's pipeline
//! ([`rollfit_fit::master::pipeline`]); what they say is passed on as it
//! is.

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use rollfit_fit::StartMaterial;
use rollfit_fit::master::MasterCurve;
use rollfit_fit::master::pipeline::{self, Built};
use rollfit_model::{
    HavriliakNegami, ModelError, Prony, StandardLinearSolid, TabulatedModulus, VerticalShift,
    ViscoelasticModulus,
};
use serde::Deserialize;

use super::InSection;
use super::messages::quoted_or;
use super::setup::DEFAULT_POISSON;
use super::shift::{ShiftRule, ShiftSection};
use super::values::{Real, RealOrList, reals};
use super::vertical;
use crate::dma::{DmaInput, group_isotherms};
use crate::error::IoError;
use crate::table;

/// Material model names as written in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MaterialKind {
    /// Standard linear solid: E0, E1, tau.
    Sls,
    /// Prony series: E1, H = [..], tau = [..].
    Prony,
    /// Tabulated master curve: file.
    Table,
    /// Havriliak–Negami: E0, E1, tau, alpha, beta.
    #[serde(rename = "havriliak-negami", alias = "hn")]
    HavriliakNegami,
    /// DMA isotherms made into a master curve in memory (as `rollfit
    /// master` does): file, optional T_ref, modulus, shift_law, vertical.
    Dma,
}

impl MaterialKind {
    /// The name as written in the file ("sls", "havriliak-negami", …).
    pub fn name(self) -> &'static str {
        match self {
            MaterialKind::Sls => "sls",
            MaterialKind::Prony => "prony",
            MaterialKind::Table => "table",
            MaterialKind::HavriliakNegami => "havriliak-negami",
            MaterialKind::Dma => "dma",
        }
    }

    fn keys(self) -> &'static str {
        match self {
            MaterialKind::Sls => "E0, E1, tau",
            MaterialKind::Prony => "E1, H, tau",
            MaterialKind::Table => "file",
            MaterialKind::HavriliakNegami => "E0, E1, tau, alpha, beta",
            MaterialKind::Dma => {
                "file (one, a list or a folder), and optionally sheet, temperatures, T_ref, \
                 modulus, shift_law, vertical"
            }
        }
    }
}

/// `[material]`: Young's modulus E*(ω) at the reference temperature.
///
/// One flat struct for all models, rather than a tagged enum, so that a key
/// of the wrong model gets a message saying which model it belongs to instead
/// of serde's generic "unknown field".
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSection {
    /// "sls", "prony", "table" or "havriliak-negami" ("hn").
    pub model: MaterialKind,
    /// Rubbery (static) Young's modulus E0, Pa ("sls", "havriliak-negami").
    #[serde(rename = "E0")]
    pub e0: Option<Real>,
    /// Glassy Young's modulus E1, Pa ("sls", "prony", "havriliak-negami").
    #[serde(rename = "E1")]
    pub e1: Option<Real>,
    /// Time constant τ, s ("sls", "havriliak-negami": one number; "prony":
    /// one per term).
    pub tau: Option<RealOrList>,
    /// Havriliak–Negami width exponent α, 0 < α ≤ 1 ("havriliak-negami").
    pub alpha: Option<Real>,
    /// Havriliak–Negami asymmetry exponent β, 0 < β ≤ 1 ("havriliak-negami").
    pub beta: Option<Real>,
    /// Prony strengths H_k, Pa ("prony").
    #[serde(rename = "H")]
    pub h: Option<Vec<Real>>,
    /// Modulus table ("table") or DMA file ("dma"), relative to the scene
    /// file's folder; for "dma" also a list of files or a folder (one
    /// isotherm per file).
    pub file: Option<Files>,
    /// The temperature of each DMA file, °C, for files that state none
    /// ("dma"; as `rollfit master --temperatures`).
    pub temperatures: Option<Vec<Real>>,
    /// The sheet of a workbook `file` ("dma", "table"; default: the
    /// first).
    pub sheet: Option<String>,
    /// Reference temperature of the master curve, °C ("dma"; default as
    /// `rollfit master`).
    #[serde(rename = "T_ref")]
    pub t_ref: Option<Real>,
    /// What a TRIOS file's moduli are ("dma", "table"): "shear" or
    /// "young" (a CSV says it with its column names).
    pub modulus: Option<ModulusName>,
    /// The law of the DMA shift factors ("dma"): "auto" (default), "wlf",
    /// "free", "arrhenius" or "wlf-arrhenius".
    pub shift_law: Option<DmaShiftLaw>,
    /// Whether to find vertical shift factors ("dma"; default false).
    pub vertical: Option<bool>,
    /// `[material.shift]`: time–temperature shift.
    pub shift: Option<ShiftSection>,
    /// The master curve of a "dma" material, built once.
    #[serde(skip)]
    pub(crate) dma: DmaCache,
}

/// `file` as written: one path, or a list ("dma").
#[derive(Debug, Clone, Deserialize)]
#[serde(untagged)]
pub enum Files {
    One(PathBuf),
    Many(Vec<PathBuf>),
}

impl Files {
    /// The paths, as written.
    fn paths(&self) -> Vec<PathBuf> {
        match self {
            Files::One(path) => vec![path.clone()],
            Files::Many(paths) => paths.clone(),
        }
    }
}

/// `shift_law` of a "dma" material as written in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DmaShiftLaw {
    /// Chosen by the data (`rollfit master --shift auto`).
    Auto,
    /// Williams–Landel–Ferry.
    Wlf,
    /// The measured shifts.
    Free,
    /// Arrhenius.
    Arrhenius,
    /// WLF above T_g, Arrhenius below.
    WlfArrhenius,
}

/// `modulus` as written in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ModulusName {
    /// G′, G″, converted with E = 2(1+ν)G.
    Shear,
    /// E′, E″.
    Young,
}

impl ModulusName {
    fn kind(self) -> crate::dma::ModulusKind {
        match self {
            ModulusName::Shear => crate::dma::ModulusKind::Shear,
            ModulusName::Young => crate::dma::ModulusKind::Young,
        }
    }
}

/// The master curve of a "dma" material, built on first use (a forward
/// sweep over several temperatures, the exact cylinder and the shift all
/// need it), with the scene's Poisson's ratio that converts shear moduli.
#[derive(Clone, Default)]
pub(crate) struct DmaCache {
    /// [substrate] poisson (set when the scene is parsed).
    pub(super) poisson: Option<f64>,
    built: std::sync::OnceLock<Arc<Built<MasterCurve>>>,
}

impl fmt::Debug for DmaCache {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("DmaCache")
            .field("poisson", &self.poisson)
            .field("built", &self.built.get().is_some())
            .finish()
    }
}

impl MaterialSection {
    /// Checks that exactly the keys of the chosen model are present.
    pub(super) fn check_keys(&self) -> Result<(), IoError> {
        let kind = self.model;
        let present = [
            ("E0", self.e0.is_some()),
            ("E1", self.e1.is_some()),
            ("tau", self.tau.is_some()),
            ("H", self.h.is_some()),
            ("file", self.file.is_some()),
            ("alpha", self.alpha.is_some()),
            ("beta", self.beta.is_some()),
        ];
        let needed: &[&str] = match kind {
            MaterialKind::Sls => &["E0", "E1", "tau"],
            MaterialKind::Prony => &["E1", "H", "tau"],
            MaterialKind::Table => &["file"],
            MaterialKind::HavriliakNegami => &["E0", "E1", "tau", "alpha", "beta"],
            MaterialKind::Dma => &["file"],
        };
        let optional = [
            ("T_ref", self.t_ref.is_some(), &[MaterialKind::Dma][..]),
            (
                "temperatures",
                self.temperatures.is_some(),
                &[MaterialKind::Dma][..],
            ),
            (
                "shift_law",
                self.shift_law.is_some(),
                &[MaterialKind::Dma][..],
            ),
            (
                "vertical",
                self.vertical.is_some(),
                &[MaterialKind::Dma][..],
            ),
            (
                "modulus",
                self.modulus.is_some(),
                &[MaterialKind::Dma, MaterialKind::Table][..],
            ),
            (
                "sheet",
                self.sheet.is_some(),
                &[MaterialKind::Dma, MaterialKind::Table][..],
            ),
        ];
        for (key, is_present, models) in optional {
            if is_present && !models.contains(&kind) {
                let models: Vec<&str> = models.iter().map(|m| m.name()).collect();
                return Err(err!(
                    "[material]: key `{key}` does not belong to model \"{}\" (it takes {}); \
                     `{key}` is for model {}",
                    kind.name(),
                    kind.keys(),
                    quoted_or(&models)
                ));
            }
        }
        if kind == MaterialKind::Dma && self.shift.is_some() {
            return Err(err!(
                "[material.shift] does not go with model = \"dma\": the shift factors come from the \
         isotherms themselves (`shift_law` chooses \"wlf\", \"free\" or \"arrhenius\"); remove \
         [material.shift]"
            ));
        }
        for (key, is_present) in present {
            let wanted = needed.contains(&key);
            let (model, takes) = (kind.name(), kind.keys());
            if wanted && !is_present {
                return Err(err!(
                    "[material]: model \"{model}\" needs the key `{key}` (it takes {takes})"
                ));
            }
            if !wanted && is_present {
                return Err(err!(
                    "[material]: key `{key}` does not belong to model \"{model}\" (it takes {takes}){}",
                    if model == "prony" && key == "E0" {
                        "; the static modulus of a Prony series is E0 = E1 - sum(H)"
                    } else {
                        ""
                    }
                ));
            }
        }
        match (kind, &self.tau) {
            (MaterialKind::Sls | MaterialKind::HavriliakNegami, Some(RealOrList::List(_))) => {
                Err(err!(
                    "[material]: model \"{model}\" takes one relaxation time: `tau` must be a number, not an \
         array",
                    model = kind.name()
                ))
            }
            (MaterialKind::Prony, Some(RealOrList::One(_))) => Err(err!(
                "[material]: model \"prony\" takes one relaxation time per term: `tau` must be an array \
         like H"
            )),
            _ => Ok(()),
        }
    }

    /// The validated modulus at the reference temperature; `note` receives
    /// what a modulus table's reader says about the file (how it was read).
    pub fn build(
        &self,
        base_dir: &Path,
        note: &dyn Fn(&str),
    ) -> Result<Box<dyn ViscoelasticModulus>, IoError> {
        self.make_modulus(base_dir, note)
    }

    /// [`Self::build`], with the scene's own error.
    fn make_modulus(
        &self,
        base_dir: &Path,
        note: &dyn Fn(&str),
    ) -> Result<Box<dyn ViscoelasticModulus>, IoError> {
        self.check_keys()?;
        let value = |r: Option<Real>| r.map_or(f64::NAN, |r| r.0);
        let model = |error: ModelError| err!("{error}");
        Ok(match self.model {
            MaterialKind::Sls => {
                let tau = match self.tau {
                    Some(RealOrList::One(t)) => t,
                    _ => f64::NAN,
                };
                Box::new(
                    StandardLinearSolid::new(value(self.e0), value(self.e1), tau).map_err(model)?,
                )
            }
            MaterialKind::Prony => {
                let tau = match &self.tau {
                    Some(RealOrList::List(t)) => t.clone(),
                    _ => Vec::new(),
                };
                let h = self.h.as_deref().map(reals).unwrap_or_default();
                Box::new(Prony::new(value(self.e1), h, tau).map_err(model)?)
            }
            MaterialKind::HavriliakNegami => {
                let tau = match self.tau {
                    Some(RealOrList::One(t)) => t,
                    _ => f64::NAN,
                };
                Box::new(
                    HavriliakNegami::new(
                        value(self.e0),
                        value(self.e1),
                        tau,
                        value(self.alpha),
                        value(self.beta),
                    )
                    .map_err(model)?,
                )
            }
            MaterialKind::Dma => Box::new(self.dma_master(base_dir)?.master.fit.prony.clone()),
            MaterialKind::Table => {
                let (path, table) = self.read_table(base_dir)?;
                for line in &table.notes {
                    note(line);
                }
                let rows = table.omega.len();
                let modulus = TabulatedModulus::new(table.omega, table.storage, table.loss)
                    .map_err(|error| err!("modulus table {}: {error}", path.display()))?;
                let (storage, loss) = modulus.interpolation_error_estimate();
                note(&format!(
                    "{}: {rows} rows; between the rows the interpolation is estimated to err by \
                     up to {storage:.1e} in E′ and {loss:.1e} in E″ (relative, from the rows \
                     alone: cubics with third- and fourth-order slopes compared)",
                    path.display()
                ));
                Box::new(modulus)
            }
        })
    }
}
impl MaterialSection {
    /// The modulus table of a "table" material, in any form the DMA reader
    /// accepts (shear columns converted with `[substrate] poisson`), and its
    /// path.
    pub fn read_table(&self, base_dir: &Path) -> Result<(PathBuf, table::ModulusTable), IoError> {
        let file = match &self.file {
            None => return Err(err!("model \"{model}\" needs `file`", model = "table")),
            Some(Files::One(file)) => file,
            Some(Files::Many(_)) => {
                return Err(err!(
                    "model \"table\" reads one file: `file` is a list (several DMA files are model \"dma\")"
                ));
            }
        };
        let path = base_dir.join(file);
        let table = table::read_sheet(
            &path,
            self.dma.poisson.unwrap_or(DEFAULT_POISSON),
            self.modulus.map(ModulusName::kind),
            self.sheet.as_deref(),
        )?;
        Ok((path, table))
    }

    /// The master curve of a "dma" material, built on first use.
    fn dma_master(&self, base_dir: &Path) -> Result<Arc<Built<MasterCurve>>, IoError> {
        if let Some(built) = self.dma.built.get() {
            return Ok(Arc::clone(built));
        }
        let file = self
            .file
            .as_ref()
            .ok_or(err!("model \"{model}\" needs `file`", model = "dma"))?;
        let settings = rollfit_fit::master::MasterSettings {
            t_ref: self.t_ref.map(|r| r.0),
            law: match self.shift_law {
                None | Some(DmaShiftLaw::Auto) => rollfit_fit::master::ShiftLaw::Auto,
                Some(DmaShiftLaw::Wlf) => rollfit_fit::master::ShiftLaw::Wlf,
                Some(DmaShiftLaw::Free) => rollfit_fit::master::ShiftLaw::Free,
                Some(DmaShiftLaw::Arrhenius) => rollfit_fit::master::ShiftLaw::Arrhenius,
                Some(DmaShiftLaw::WlfArrhenius) => rollfit_fit::master::ShiftLaw::WlfArrhenius,
            },
            vertical: self.vertical.unwrap_or(false),
        };
        let input = DmaInput {
            files: file.paths().iter().map(|f| base_dir.join(f)).collect(),
            sheet: self.sheet.clone(),
            kind: self.modulus.map(ModulusName::kind),
            temperatures: (self.temperatures.as_ref()).map(|t| t.iter().map(|r| r.0).collect()),
            modulus_unit: None,
        };
        let data = input
            .read(self.dma.poisson.unwrap_or(DEFAULT_POISSON), None)
            .map_err(|e| err!("{error}", error = e))?;
        // No temperatures: the file is one curve, taken at T_ref.
        let untimed = settings.t_ref.unwrap_or(rollfit_fit::master::DEFAULT_T_REF);
        let read = group_isotherms(data, Some(untimed))?;
        let path = read.data.path.as_path();
        let built = pipeline::build(&read.isotherms, (), &settings)
            .map_err(|error| crate::dma::master_refused(path, error))?;
        let built = Arc::new(built);
        let _ = self.dma.built.set(Arc::clone(&built));
        Ok(built)
    }

    /// The time–temperature shift of this material: `[material.shift]`, or
    /// for "dma" the master curve's own (None without either, or for one
    /// isotherm).
    pub(crate) fn shift_rule(&self, base_dir: &Path) -> Result<Option<ShiftRule>, IoError> {
        if self.model == MaterialKind::Dma {
            return ShiftRule::of_master(self.dma_master(base_dir)?.as_ref());
        }
        self.shift
            .as_ref()
            .map(|s| s.rule().section("[material.shift]"))
            .transpose()
    }

    /// The vertical factors b_T of this material: `[material.shift]`'s, or
    /// for "dma" with `vertical = true` the master curve's (None: b_T = 1).
    pub(crate) fn vertical_rule(&self, base_dir: &Path) -> Result<Option<VerticalShift>, IoError> {
        if self.model == MaterialKind::Dma {
            return vertical::of_master(self.dma_master(base_dir)?.as_ref());
        }
        self.shift
            .as_ref()
            .map(|s| s.vertical_rule().section("[material.shift]"))
            .transpose()
            .map(Option::flatten)
    }

    /// An "sls" (one term), "prony" or "dma" material as a Prony series;
    /// None for other models (the Python module's μ with its Jacobian).
    pub fn as_prony(&self, base_dir: &Path, note: &dyn Fn(&str)) -> Result<Option<Prony>, IoError> {
        self.prony(base_dir, note)
    }

    /// [`Self::as_prony`], with the scene's own error.
    pub(super) fn prony(
        &self,
        base_dir: &Path,
        note: &dyn Fn(&str),
    ) -> Result<Option<Prony>, IoError> {
        let modulus = self.make_modulus(base_dir, note)?;
        let model = |error: ModelError| err!("{error}");
        Ok(match self.model {
            MaterialKind::Sls => {
                let tau = match self.tau {
                    Some(RealOrList::One(t)) => t,
                    _ => f64::NAN,
                };
                let e1 = self.e1.map_or(f64::NAN, |r| r.0);
                let sls =
                    StandardLinearSolid::new(modulus.static_modulus(), e1, tau).map_err(model)?;
                Some(sls.to_prony())
            }
            MaterialKind::Prony => {
                let tau = match &self.tau {
                    Some(RealOrList::List(t)) => t.clone(),
                    _ => Vec::new(),
                };
                let h = self.h.as_deref().map(reals).unwrap_or_default();
                let e1 = self.e1.map_or(f64::NAN, |r| r.0);
                Some(Prony::new(e1, h, tau).map_err(model)?)
            }
            MaterialKind::Dma => Some(self.dma_master(base_dir)?.master.fit.prony.clone()),
            _ => None,
        })
    }

    /// E0 and E1 of an "sls" or "prony" material, as the fit's starting
    /// point (other models give none).
    pub(super) fn start(&self) -> Option<StartMaterial> {
        let glassy_modulus = self.e1?.0;
        let static_modulus = match self.model {
            MaterialKind::Sls => self.e0?.0,
            MaterialKind::Prony => {
                glassy_modulus - self.h.as_deref()?.iter().map(|h| h.0).sum::<f64>()
            }
            _ => return None,
        };
        Some(StartMaterial {
            static_modulus,
            glassy_modulus,
        })
    }
}
