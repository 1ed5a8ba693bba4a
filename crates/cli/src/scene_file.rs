//! The scene file (TOML; docs/ARCHITECTURE.md, "Contract", "Scene file"):
//! its schema and its conversion into validated model objects.
//!
//! Parsing happens in two steps. serde with `deny_unknown_fields` turns the
//! text into the plain structs below; type errors, unknown keys and
//! non-finite numbers are caught there, so toml can point at the line and
//! column. The conversion into [`Scene`] then checks what serde cannot see
//! (which keys a material model needs, ranges, ordering) and names the
//! section and key of every problem. Physical ranges of scene and material
//! parameters are left to the model's constructors, which own them; this
//! module only prefixes their messages with the section they came from.

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{Context, Result, anyhow, bail, ensure};
use rollfit_fit::{FitParams, Lambda, Method, RollingSetup, ScaleAnchor, StartMaterial, TermRule};
use rollfit_model::exact::{ExactSettings, RollingCylinder};
use rollfit_model::modulus::{Arrhenius, FreeShift};
use rollfit_model::{
    ContactSize, Geometry, HavriliakNegami, ModelError, Prony, Scene, Shape, Shifted,
    StandardLinearSolid, Substrate, TabulatedModulus, ViscoelasticModulus, Wlf,
};
use serde::Deserialize;
use serde::de::{self, Deserializer, SeqAccess, Visitor};

use crate::dma_master::{self, DmaMaster};
use crate::table_file;

/// The scene the forward model runs on: any material behind one pointer, so
/// that a shifted table and a plain standard linear solid share one type.
pub type DynScene = Scene<Box<dyn ViscoelasticModulus>>;

/// Default number of log-spaced speeds of a `[sweep]` given by its range.
pub const DEFAULT_SWEEP_COUNT: i64 = 61;

/// Largest accepted `count`: far beyond any useful sweep, but small enough
/// that a typo cannot make the tool try to allocate exabytes.
pub const MAX_SWEEP_COUNT: i64 = 1_000_000;

/// The error of a `[sweep] temperature` without `[material.shift]`.
fn temperature_without_shift(temperature: &SweepTemperature) -> String {
    format!(
        "[sweep] {} is set but [material] has no [material.shift]: without a \
         time-temperature shift the material is known only at its reference temperature",
        temperature.describe()
    )
}

/// Default Poisson's ratio (incompressible rubber).
pub const DEFAULT_POISSON: f64 = 0.5;

/// A finite floating-point number from the scene file.
///
/// TOML admits `nan` and `inf`; no parameter of a scene can take them, and
/// rejecting them while deserializing lets toml report the line and column.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Real(pub f64);

fn finite<E: de::Error>(v: f64) -> Result<Real, E> {
    if v.is_finite() {
        Ok(Real(v))
    } else {
        Err(E::custom(format!(
            "found {v}, expected a finite number (nan and inf are not allowed)"
        )))
    }
}

impl<'de> Deserialize<'de> for Real {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct RealVisitor;
        impl Visitor<'_> for RealVisitor {
            type Value = Real;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a finite number")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Real, E> {
                finite(v)
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Real, E> {
                Ok(Real(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Real, E> {
                Ok(Real(v as f64))
            }
        }
        deserializer.deserialize_f64(RealVisitor)
    }
}

fn reals(values: &[Real]) -> Vec<f64> {
    values.iter().map(|r| r.0).collect()
}

/// A key that is a number for one material model and a list for another
/// (`tau`: one time for "sls", one per term for "prony").
#[derive(Debug, Clone, PartialEq)]
pub enum RealOrList {
    /// A single number.
    One(f64),
    /// An array of numbers.
    List(Vec<f64>),
}

impl<'de> Deserialize<'de> for RealOrList {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct OneOrListVisitor;
        impl<'de> Visitor<'de> for OneOrListVisitor {
            type Value = RealOrList;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a finite number or an array of finite numbers")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<RealOrList, E> {
                finite(v).map(|r| RealOrList::One(r.0))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<RealOrList, E> {
                Ok(RealOrList::One(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<RealOrList, E> {
                Ok(RealOrList::One(v as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<RealOrList, A::Error> {
                let mut values = Vec::new();
                while let Some(Real(v)) = seq.next_element::<Real>()? {
                    values.push(v);
                }
                Ok(RealOrList::List(values))
            }
        }
        deserializer.deserialize_any(OneOrListVisitor)
    }
}

/// `[sweep] temperature`, °C: one temperature, or a list of them (a
/// synthetic temperature set, one block of rows per temperature).
#[derive(Debug, Clone, PartialEq)]
pub enum SweepTemperature {
    /// `temperature = 20.0`.
    One(f64),
    /// `temperature = [-20.0, 0.0, ..]`, in the listed order.
    List(Vec<f64>),
}

impl SweepTemperature {
    /// The temperatures in order (one for [`SweepTemperature::One`]).
    pub fn values(&self) -> &[f64] {
        match self {
            SweepTemperature::One(t) => std::slice::from_ref(t),
            SweepTemperature::List(list) => list,
        }
    }

    /// How messages name the `i`-th temperature: `temperature = 20` or
    /// `temperature[i] = 20`.
    pub fn entry(&self, i: usize) -> String {
        match self {
            SweepTemperature::One(t) => format!("temperature = {t}"),
            SweepTemperature::List(list) => format!("temperature[{i}] = {}", list[i]),
        }
    }

    /// The key as written, for messages: `temperature = 20` or
    /// `temperature = [-20, 0, 20]`.
    fn describe(&self) -> String {
        match self {
            SweepTemperature::One(t) => format!("temperature = {t}"),
            SweepTemperature::List(list) => {
                let listed: Vec<String> = list.iter().map(f64::to_string).collect();
                format!("temperature = [{}]", listed.join(", "))
            }
        }
    }

    /// Checks what serde cannot see: a list names at least one temperature
    /// and none twice (within the model's [`FreeShift::TEMPERATURE_TOLERANCE`],
    /// the rule the fit uses to tell the temperatures of a set apart).
    fn check(&self) -> Result<()> {
        let SweepTemperature::List(list) = self else {
            return Ok(());
        };
        ensure!(
            !list.is_empty(),
            "`temperature = []` lists no temperatures: give at least one (°C), e.g. \
             temperature = [0.0, 20.0, 40.0], or leave the key out"
        );
        for (j, &t) in list.iter().enumerate() {
            if let Some(i) = list[..j]
                .iter()
                .position(|&s| (s - t).abs() <= FreeShift::TEMPERATURE_TOLERANCE)
            {
                bail!(
                    "temperature[{j}] = {t} repeats temperature[{i}] = {}: list each temperature once",
                    list[i]
                );
            }
        }
        Ok(())
    }
}

impl<'de> Deserialize<'de> for SweepTemperature {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct TemperatureVisitor;
        impl<'de> Visitor<'de> for TemperatureVisitor {
            type Value = SweepTemperature;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a temperature in °C or an array of temperatures")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<SweepTemperature, E> {
                finite(v).map(|r| SweepTemperature::One(r.0))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<SweepTemperature, E> {
                Ok(SweepTemperature::One(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<SweepTemperature, E> {
                Ok(SweepTemperature::One(v as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<SweepTemperature, A::Error> {
                let mut values = Vec::new();
                // Real rejects nan and inf; the entry's index is added here,
                // toml adds the line and column.
                while let Some(Real(t)) = seq.next_element::<Real>().map_err(|e| {
                    de::Error::custom(format!("[sweep] temperature[{}]: {e}", values.len()))
                })? {
                    values.push(t);
                }
                Ok(SweepTemperature::List(values))
            }
        }
        deserializer.deserialize_any(TemperatureVisitor)
    }
}

/// `[fit] terms`: a number of Prony terms or `"auto"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Terms {
    /// Let the fit choose the number of terms.
    Auto,
    /// This many terms (checked to be at least 1 after parsing).
    Count(i64),
}

impl<'de> Deserialize<'de> for Terms {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct TermsVisitor;
        impl Visitor<'_> for TermsVisitor {
            type Value = Terms;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a whole number of terms or \"auto\"")
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Terms, E> {
                Ok(Terms::Count(v))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Terms, E> {
                Ok(Terms::Count(i64::try_from(v).unwrap_or(i64::MAX)))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Terms, E> {
                if v == "auto" {
                    Ok(Terms::Auto)
                } else {
                    Err(E::invalid_value(de::Unexpected::Str(v), &self))
                }
            }
        }
        deserializer.deserialize_any(TermsVisitor)
    }
}

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

/// Shape names as written in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ShapeName {
    /// A ball; `load` is a force, N.
    Sphere,
    /// A roller; `load` is a force per length, N/m.
    Cylinder,
}

/// `[geometry]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GeometrySection {
    /// "sphere" or "cylinder".
    pub shape: ShapeName,
    /// Radius R of the rolling body, m.
    pub radius: Real,
    /// F_N in N (sphere) or f_N in N/m (cylinder).
    pub load: Real,
}

/// `[substrate]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SubstrateSection {
    /// Poisson's ratio ν of the viscoelastic solid (default ½).
    pub poisson: Option<Real>,
    /// Film thickness d, m, for a film on a rigid base; absent = half-space.
    pub thickness: Option<Real>,
}

/// The rungs of the model ladder as written in the file (`[contact] size`;
/// the contract, docs/ARCHITECTURE.md, "Contract", names "dynamic" and
/// "static", the rest extend it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ContactName {
    /// |E_eff(ω)| at the local frequency.
    Dynamic,
    /// E_eff(0) for every frequency.
    Static,
    /// The exact steady rolling contact (cylinder on a half-space, standard
    /// linear solid or Prony series; forward only): the reference Eq. (11)
    /// approximates.
    Exact,
    /// The low-speed asymptote, Eqs. (18)/(19) (forward only).
    #[serde(rename = "low-speed")]
    LowSpeed,
    /// The cheapest rung that meets `[contact] accuracy`, per speed
    /// (forward only; crates/model/src/ladder).
    Auto,
}

/// Default `[contact] accuracy` of `size = "auto"`.
pub const DEFAULT_ACCURACY: f64 = 1e-3;

/// `[contact]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSection {
    /// "dynamic" (default), "static", "exact", "low-speed" or "auto".
    pub size: Option<ContactName>,
    /// Relative accuracy of μ that `size = "auto"` must meet (default 1e-3).
    pub accuracy: Option<Real>,
}

impl ContactSection {
    /// `accuracy` belongs to `size = "auto"`.
    fn check(&self) -> Result<()> {
        if let Some(Real(accuracy)) = self.accuracy {
            if self.size != Some(ContactName::Auto) {
                bail!(
                    "[contact]: accuracy = {accuracy} is the target of size = \"auto\"; \
                     add size = \"auto\" or remove accuracy"
                );
            }
            if !(1e-8..=0.5).contains(&accuracy) {
                bail!("[contact]: accuracy = {accuracy} must lie between 1e-8 and 0.5 (relative)");
            }
        }
        Ok(())
    }
}

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
    fn name(self) -> &'static str {
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
            MaterialKind::Dma => "file, and optionally T_ref, modulus, shift_law, vertical",
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
    /// file's folder.
    pub file: Option<PathBuf>,
    /// Reference temperature of the master curve, °C ("dma"; default as
    /// `rollfit master`).
    #[serde(rename = "T_ref")]
    pub t_ref: Option<Real>,
    /// What a TRIOS file's moduli are ("dma", "table"): "shear" or
    /// "young" (a CSV says it with its column names).
    pub modulus: Option<ModulusName>,
    /// The law of the DMA shift factors ("dma"): "wlf" (default), "free"
    /// or "arrhenius".
    pub shift_law: Option<ShiftKind>,
    /// Whether to find vertical shift factors ("dma"; default false).
    pub vertical: Option<bool>,
    /// `[material.shift]`: time–temperature shift.
    pub shift: Option<ShiftSection>,
    /// The master curve of a "dma" material, built once.
    #[serde(skip)]
    pub(crate) dma: DmaCache,
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
    fn kind(self) -> rollfit_io::dma::ModulusKind {
        match self {
            ModulusName::Shear => rollfit_io::dma::ModulusKind::Shear,
            ModulusName::Young => rollfit_io::dma::ModulusKind::Young,
        }
    }
}

/// The master curve of a "dma" material, built on first use (a forward
/// sweep over several temperatures, the exact cylinder and the shift all
/// need it), with the scene's Poisson's ratio that converts shear moduli.
#[derive(Clone, Default)]
pub(crate) struct DmaCache {
    /// [substrate] poisson (set when the scene is parsed).
    poisson: Option<f64>,
    built: std::sync::OnceLock<Arc<DmaMaster>>,
}

impl fmt::Debug for DmaCache {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("DmaCache")
            .field("poisson", &self.poisson)
            .field("built", &self.built.get().is_some())
            .finish()
    }
}

/// Shift model names as written in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ShiftKind {
    /// Williams–Landel–Ferry: T_ref, C1, C2.
    Wlf,
    /// One log10 a_T per temperature: T_ref, log_aT = [{T, log_aT}, ..].
    Free,
    /// Arrhenius: T_ref, E_a (J/mol).
    Arrhenius,
}

/// `[material.shift]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShiftSection {
    /// "wlf", "free" or "arrhenius".
    pub model: ShiftKind,
    /// Reference temperature of `[material]`, °C.
    #[serde(rename = "T_ref")]
    pub t_ref: Real,
    /// WLF C1 (dimensionless).
    #[serde(rename = "C1")]
    pub c1: Option<Real>,
    /// WLF C2, K.
    #[serde(rename = "C2")]
    pub c2: Option<Real>,
    /// Free shift: log10 a_T at each listed temperature.
    #[serde(rename = "log_aT")]
    pub log_at: Option<Vec<ShiftPoint>>,
    /// Arrhenius activation energy, J/mol.
    #[serde(rename = "E_a")]
    pub activation_energy: Option<Real>,
}

/// One entry of a free shift.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShiftPoint {
    /// Temperature, °C.
    #[serde(rename = "T")]
    pub t: Real,
    /// log10 a_T at that temperature.
    #[serde(rename = "log_aT")]
    pub log_at: Real,
}

/// `[fit]`: scale anchors and solver choices; forward only validates them.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FitSection {
    /// Known static Young's modulus, Pa.
    #[serde(rename = "E0")]
    pub e0: Option<Real>,
    /// Known |E| (Young's, Pa) at one angular frequency (rad/s).
    #[serde(rename = "E_at")]
    pub e_at: Option<ModulusAnchor>,
    /// Measured contact radius (m) at one speed (m/s).
    pub contact_radius: Option<ContactAnchor>,
    /// Upper bound on the glassy modulus, Pa.
    #[serde(rename = "E1_max")]
    pub e1_max: Option<Real>,
    /// Number of Prony terms or "auto".
    pub terms: Option<Terms>,
    /// Relaxation times per decade of the τ grid (the default grid has 2).
    pub terms_per_decade: Option<Real>,
    /// Explicit relaxation times, s, strictly increasing.
    pub tau: Option<Vec<Real>>,
    /// Solver name ("lbfgs", "nelder-mead", "auto", ...).
    pub method: Option<String>,
    /// Smoothness weight λ ≥ 0 on ln H_k, or "auto" (data-driven).
    pub lambda: Option<LambdaSetting>,
    /// Seed of the multi-start perturbations.
    pub seed: Option<u64>,
    /// Number of starts.
    pub starts: Option<usize>,
    /// Budget of objective evaluations per solver run.
    pub max_evaluations: Option<usize>,
    /// Relative quadrature tolerance of the forward model during the fit.
    pub tolerance: Option<Real>,
    /// Shift fitted to a temperature set: "wlf" (default) or "free".
    pub shift: Option<ShiftKind>,
    /// Reference temperature of the master curve, °C (overrides
    /// `[material.shift] T_ref`).
    #[serde(rename = "T_ref")]
    pub t_ref: Option<Real>,
    /// Whether a temperature set is also fitted one temperature at a time to
    /// cross-check the shifts (default true).
    pub cross_check: Option<bool>,
}

/// `[fit] lambda`: a fixed smoothness weight or `"auto"`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LambdaSetting {
    /// Chosen from the data.
    Auto,
    /// This value (checked to be ≥ 0 after parsing).
    Value(f64),
}

impl<'de> Deserialize<'de> for LambdaSetting {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct LambdaVisitor;
        impl Visitor<'_> for LambdaVisitor {
            type Value = LambdaSetting;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a finite number ≥ 0 or \"auto\"")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<LambdaSetting, E> {
                finite(v).map(|r| LambdaSetting::Value(r.0))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<LambdaSetting, E> {
                Ok(LambdaSetting::Value(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<LambdaSetting, E> {
                Ok(LambdaSetting::Value(v as f64))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<LambdaSetting, E> {
                if v == "auto" {
                    Ok(LambdaSetting::Auto)
                } else {
                    Err(E::invalid_value(de::Unexpected::Str(v), &self))
                }
            }
        }
        deserializer.deserialize_any(LambdaVisitor)
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

/// `[sweep]`: the speeds forward evaluates μ at.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSection {
    /// Lowest speed, m/s.
    pub v_min: Option<Real>,
    /// Highest speed, m/s.
    pub v_max: Option<Real>,
    /// Number of log-spaced speeds (default 61).
    pub count: Option<i64>,
    /// Explicit speeds, m/s, instead of a range.
    pub v: Option<Vec<Real>>,
    /// Temperature, °C, or a list of them (a temperature set); needs
    /// `[material.shift]`.
    pub temperature: Option<SweepTemperature>,
    /// Relative quadrature tolerance of μ (default 1e-6).
    pub tolerance: Option<Real>,
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
    /// The body, substrate and contact rule of [geometry], [substrate] and
    /// [contact] (values unchecked: `Scene::new` checks them).
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

    pub fn rolling_setup(&self) -> RollingSetup {
        RollingSetup {
            geometry: Geometry {
                shape: match self.geometry.shape {
                    ShapeName::Sphere => Shape::Sphere,
                    ShapeName::Cylinder => Shape::Cylinder,
                },
                radius: self.geometry.radius.0,
                load: self.geometry.load.0,
            },
            substrate: Substrate {
                poisson: self.substrate.poisson.map_or(DEFAULT_POISSON, |r| r.0),
                film_thickness: self.substrate.thickness.map(|r| r.0),
            },
            // The exact solution has no contact-size rule; the columns
            // forward writes beside its μ (asymptote, static contact) come
            // from the paper's model with the dynamic size.
            contact: match self.contact.size {
                None
                | Some(ContactName::Dynamic)
                | Some(ContactName::Exact)
                | Some(ContactName::LowSpeed)
                | Some(ContactName::Auto) => ContactSize::Dynamic,
                Some(ContactName::Static) => ContactSize::Static,
            },
        }
    }

    /// Builds the inverse problem's settings: the rolling set-up (checked
    /// by the model, errors prefixed with their section), the `[fit]`
    /// table (defaults where absent) and, for an "sls" or "prony"
    /// `[material]`, its E0 and E1 as the starting point. `[sweep]` is not
    /// used. Ranges of the fit settings are checked later by
    /// [`FitParams::check`].
    pub fn fit_setup(&self) -> Result<(RollingSetup, FitParams)> {
        match self.contact.size {
            Some(ContactName::Exact) => bail!(
                "[contact]: size = \"exact\" is a forward-only reference (its μ has no fast \
                 gradient); fit with size = \"dynamic\" (the paper's) or \"static\""
            ),
            Some(name @ (ContactName::LowSpeed | ContactName::Auto)) => bail!(
                "[contact]: size = \"{}\" is for rollfit forward only (a fit needs one model \
                 with a gradient at every speed); fit with size = \"dynamic\" (the paper's) \
                 or \"static\"",
                if name == ContactName::Auto {
                    "auto"
                } else {
                    "low-speed"
                }
            ),
            _ => {}
        }
        let setup = self.rolling_setup();
        // The model owns the ranges of the set-up; a placeholder material
        // lets it check them before any fitting starts.
        let placeholder = StandardLinearSolid::new(1.0, 2.0, 1.0).map_err(|e| anyhow!("{e}"))?;
        let scene = Scene::new(setup.geometry, setup.substrate, setup.contact, placeholder)
            .map_err(|e| anyhow!("{}{e}", section_of(&e)))?;
        let fit = self.fit.clone().unwrap_or_default();
        let mut params = fit.params().context("[fit]")?;
        scene
            .with_tolerance(params.model_tolerance)
            .map_err(|e| anyhow!("[fit]: {e}"))?;
        params.start = self.material.as_ref().and_then(MaterialSection::start);
        // A scene's shift gives a temperature set its reference temperature
        // and, for WLF, starting constants; [fit] shift and T_ref override.
        if let Some(shift) = self.material.as_ref().and_then(|m| m.shift.as_ref()) {
            shift.check().context("[material.shift]")?;
            if params.shift.t_ref.is_none() {
                params.shift.t_ref = Some(shift.t_ref.0);
            }
            if let (Some(Real(c1)), Some(Real(c2))) = (shift.c1, shift.c2) {
                params.shift.wlf_start = Some((c1, c2));
            }
            if fit.shift.is_none() && shift.model == ShiftKind::Free {
                params.shift.kind = rollfit_fit::ShiftKind::Free;
            }
        }
        Ok((setup, params))
    }
}

/// The section a parameter checked by `Scene::new` lives in, as a message
/// prefix, so that "radius = -1" reads "[geometry]: radius = -1".
fn section_of(error: &ModelError) -> &'static str {
    match error {
        ModelError::InvalidParameter { name, .. } => match name.as_str() {
            "radius" | "load" => "[geometry]: ",
            "poisson" | "thickness" => "[substrate]: ",
            _ => "[material]: ",
        },
        _ => "",
    }
}

impl MaterialSection {
    /// Checks that exactly the keys of the chosen model are present.
    fn check_keys(&self) -> Result<()> {
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
        ];
        for (key, is_present, models) in optional {
            if is_present && !models.contains(&kind) {
                bail!(
                    "[material]: key `{key}` does not belong to model \"{}\" (it takes {}); \
                     `{key}` is for model {}",
                    kind.name(),
                    kind.keys(),
                    models
                        .iter()
                        .map(|m| format!("\"{}\"", m.name()))
                        .collect::<Vec<_>>()
                        .join(" or ")
                );
            }
        }
        if kind == MaterialKind::Dma && self.shift.is_some() {
            bail!(
                "[material.shift] does not go with model = \"dma\": the shift factors come from \
                 the isotherms themselves (`shift_law` chooses \"wlf\", \"free\" or \
                 \"arrhenius\"); remove [material.shift]"
            );
        }
        for (key, is_present) in present {
            let wanted = needed.contains(&key);
            if wanted && !is_present {
                bail!(
                    "[material]: model \"{}\" needs the key `{key}` (it takes {})",
                    kind.name(),
                    kind.keys()
                );
            }
            if !wanted && is_present {
                let hint = if kind == MaterialKind::Prony && key == "E0" {
                    "; the static modulus of a Prony series is E0 = E1 - sum(H)"
                } else {
                    ""
                };
                bail!(
                    "[material]: key `{key}` does not belong to model \"{}\" (it takes {}){hint}",
                    kind.name(),
                    kind.keys()
                );
            }
        }
        match (kind, &self.tau) {
            (MaterialKind::Sls | MaterialKind::HavriliakNegami, Some(RealOrList::List(_))) => {
                bail!(
                    "[material]: model \"{}\" takes one relaxation time: `tau` must be a number, not an array",
                    kind.name()
                )
            }
            (MaterialKind::Prony, Some(RealOrList::One(_))) => bail!(
                "[material]: model \"prony\" takes one relaxation time per term: \
                 `tau` must be an array like H"
            ),
            _ => Ok(()),
        }
    }

    /// The validated modulus at the reference temperature.
    pub(crate) fn build(&self, base_dir: &Path) -> Result<Box<dyn ViscoelasticModulus>> {
        self.check_keys()?;
        let value = |r: Option<Real>| r.map_or(f64::NAN, |r| r.0);
        let model = |e: ModelError| anyhow!("{e}");
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
                for note in &table.notes {
                    eprintln!("note: {note}");
                }
                Box::new(
                    TabulatedModulus::new(table.omega, table.storage, table.loss)
                        .map_err(|e| anyhow!("modulus table {}: {e}", path.display()))?,
                )
            }
        })
    }
}

/// A validated time–temperature shift: the model's own objects, so that the
/// rule for a free shift (exact at listed temperatures, linear in T between
/// them, refused outside) lives in one place, `rollfit_model`.
#[derive(Debug)]
pub(crate) enum ShiftRule {
    Wlf(Wlf),
    Free(FreeShift),
    Arrhenius(Arrhenius),
}

impl ShiftRule {
    /// log10 a_T at `temperature` (°C), by the model's rule: WLF,
    /// Arrhenius, or a free shift interpolated linearly in T between its
    /// listed temperatures (T_ref included) and never extrapolated beyond
    /// them.
    pub fn log10_shift(&self, temperature: f64) -> Result<f64> {
        let shift = match self {
            ShiftRule::Wlf(wlf) => wlf.log10_shift(temperature).map_err(|e| anyhow!("{e}"))?,
            ShiftRule::Arrhenius(law) => {
                law.log10_shift(temperature).map_err(|e| anyhow!("{e}"))?
            }
            // The only refusal for a finite temperature is one outside the
            // list, which the file can fix.
            ShiftRule::Free(free) => free.log10_shift(temperature).map_err(|e| {
                anyhow!("{e}; add a `log_aT` entry at or beyond it, or use model = \"wlf\"")
            })?,
        };
        ensure!(
            shift.is_finite(),
            "log10 a_T at T = {temperature} °C is {shift}: the shift is not defined at this temperature"
        );
        Ok(shift)
    }

    /// The rule of a master curve's shift (None for one isotherm).
    fn of_master(built: &DmaMaster) -> Result<Option<ShiftRule>> {
        use rollfit_fit::master::ShiftLaw;
        let shift = &built.master.shift;
        if shift.shifts.len() < 2 {
            return Ok(None);
        }
        let t_ref = shift.t_ref;
        let model = |e: ModelError| anyhow!("the DMA master curve's shift: {e}");
        Ok(Some(match shift.law {
            ShiftLaw::Wlf => {
                let w = shift.wlf.context("WLF fit missing")?;
                ShiftRule::Wlf(Wlf::new(t_ref, w.c1, w.c2).map_err(model)?)
            }
            ShiftLaw::Arrhenius => {
                let a = shift.arrhenius.context("Arrhenius fit missing")?;
                ShiftRule::Arrhenius(Arrhenius::new(t_ref, a.activation_energy).map_err(model)?)
            }
            ShiftLaw::Free => ShiftRule::Free(
                FreeShift::new(
                    t_ref,
                    shift
                        .shifts
                        .iter()
                        .map(|s| (s.temperature, s.log_shift))
                        .collect(),
                )
                .map_err(model)?,
            ),
        }))
    }
}

impl ShiftSection {
    /// Checks that exactly the keys of the chosen shift model are present
    /// and builds the model's shift from them; the model checks the values
    /// (positive WLF constants, distinct and finite free-shift entries).
    fn rule(&self) -> Result<ShiftRule> {
        match self.model {
            ShiftKind::Wlf => {
                ensure!(
                    self.c1.is_some() && self.c2.is_some(),
                    "model \"wlf\" needs the keys `C1` and `C2` (and `T_ref`)"
                );
                ensure!(
                    self.log_at.is_none() && self.activation_energy.is_none(),
                    "keys `log_aT` and `E_a` do not belong to model \"wlf\" (it takes T_ref, C1, C2)"
                );
                // The model names the offending key (T_ref, C1 or C2).
                let wlf = Wlf::new(self.t_ref.0, value_of(self.c1), value_of(self.c2))
                    .map_err(|e| anyhow!("{e}"))?;
                Ok(ShiftRule::Wlf(wlf))
            }
            ShiftKind::Arrhenius => {
                ensure!(
                    self.c1.is_none() && self.c2.is_none() && self.log_at.is_none(),
                    "keys `C1`, `C2` and `log_aT` do not belong to model \"arrhenius\" (it takes \
                     T_ref, E_a)"
                );
                let energy = self.activation_energy.context(
                    "model \"arrhenius\" needs the key `E_a`, the activation energy in J/mol",
                )?;
                let law = Arrhenius::new(self.t_ref.0, energy.0).map_err(|e| anyhow!("{e}"))?;
                Ok(ShiftRule::Arrhenius(law))
            }
            ShiftKind::Free => {
                ensure!(
                    self.c1.is_none() && self.c2.is_none() && self.activation_energy.is_none(),
                    "keys `C1`, `C2` and `E_a` do not belong to model \"free\" (it takes T_ref, \
                     log_aT)"
                );
                let listed = self.log_at.as_deref().context(
                    "model \"free\" needs the key `log_aT`, one entry per measured temperature, \
                     e.g. log_aT = [{ T = 0.0, log_aT = 2.1 }, { T = 40.0, log_aT = -1.3 }]",
                )?;
                let entries = listed.iter().map(|p| (p.t.0, p.log_at.0)).collect();
                // The model's "entry i" is the i-th element of `log_aT`.
                let free = rollfit_model::modulus::FreeShift::new(self.t_ref.0, entries)
                    .map_err(|e| anyhow!("`log_aT`: {e}"))?;
                Ok(ShiftRule::Free(free))
            }
        }
    }

    /// Checks the section by building its shift.
    fn check(&self) -> Result<()> {
        self.rule().map(|_| ())
    }
}

fn value_of(r: Option<Real>) -> f64 {
    r.map_or(f64::NAN, |r| r.0)
}

fn require_positive(key: &str, value: f64) -> Result<()> {
    ensure!(value > 0.0, "{key} = {value}: must be greater than zero");
    Ok(())
}

impl MaterialSection {
    /// The modulus table of a "table" material, in any form the DMA reader
    /// accepts (shear columns converted with [substrate] poisson), and its
    /// path.
    pub(crate) fn read_table(
        &self,
        base_dir: &Path,
    ) -> Result<(PathBuf, table_file::ModulusTable)> {
        let file = self.file.as_ref().context("model \"table\" needs `file`")?;
        let path = base_dir.join(file);
        let table = table_file::read_with(
            &path,
            self.dma.poisson.unwrap_or(DEFAULT_POISSON),
            self.modulus.map(ModulusName::kind),
        )?;
        Ok((path, table))
    }

    /// The master curve of a "dma" material, built on first use.
    fn dma_master(&self, base_dir: &Path) -> Result<Arc<DmaMaster>> {
        if let Some(built) = self.dma.built.get() {
            return Ok(Arc::clone(built));
        }
        let file = self.file.as_ref().context("model \"dma\" needs `file`")?;
        let settings = rollfit_fit::master::MasterSettings {
            t_ref: self.t_ref.map(|r| r.0),
            law: match self.shift_law {
                None | Some(ShiftKind::Wlf) => rollfit_fit::master::ShiftLaw::Wlf,
                Some(ShiftKind::Free) => rollfit_fit::master::ShiftLaw::Free,
                Some(ShiftKind::Arrhenius) => rollfit_fit::master::ShiftLaw::Arrhenius,
            },
            vertical: self.vertical.unwrap_or(false),
        };
        let built = Arc::new(dma_master::build(
            &base_dir.join(file),
            self.dma.poisson.unwrap_or(DEFAULT_POISSON),
            self.modulus.map(ModulusName::kind),
            &settings,
        )?);
        let _ = self.dma.built.set(Arc::clone(&built));
        Ok(built)
    }

    /// The time–temperature shift of this material: `[material.shift]`, or
    /// for "dma" the master curve's own (None without either, or for one
    /// isotherm).
    pub(crate) fn shift_rule(&self, base_dir: &Path) -> Result<Option<ShiftRule>> {
        if self.model == MaterialKind::Dma {
            return ShiftRule::of_master(self.dma_master(base_dir)?.as_ref());
        }
        self.shift
            .as_ref()
            .map(|s| s.rule().context("[material.shift]"))
            .transpose()
    }

    /// An "sls" (one term), "prony" or "dma" material as a Prony series;
    /// None for other models.
    fn prony(&self, base_dir: &Path) -> Result<Option<Prony>> {
        let modulus = self.build(base_dir)?;
        Ok(match self.model {
            MaterialKind::Sls => {
                let tau = match self.tau {
                    Some(RealOrList::One(t)) => t,
                    _ => f64::NAN,
                };
                let e1 = self.e1.map_or(f64::NAN, |r| r.0);
                let sls = StandardLinearSolid::new(modulus.static_modulus(), e1, tau)
                    .map_err(|e| anyhow!("{e}"))?;
                Some(sls.to_prony())
            }
            MaterialKind::Prony => {
                let tau = match &self.tau {
                    Some(RealOrList::List(t)) => t.clone(),
                    _ => Vec::new(),
                };
                let h = self.h.as_deref().map(reals).unwrap_or_default();
                let e1 = self.e1.map_or(f64::NAN, |r| r.0);
                Some(Prony::new(e1, h, tau).map_err(|e| anyhow!("{e}"))?)
            }
            MaterialKind::Dma => Some(self.dma_master(base_dir)?.master.fit.prony.clone()),
            _ => None,
        })
    }

    /// E0 and E1 of an "sls" or "prony" material, as the fit's starting
    /// point (other models give none).
    fn start(&self) -> Option<StartMaterial> {
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

impl FitSection {
    fn check(&self) -> Result<()> {
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
        if let Some(Real(e1_max)) = self.e1_max {
            require_positive("E1_max", e1_max)?;
            if let Some(Real(e0)) = self.e0 {
                ensure!(
                    e1_max > e0,
                    "E1_max = {e1_max} must exceed the known static modulus E0 = {e0}"
                );
            }
        }
        let anchors: Vec<&str> = [
            ("`E0`", self.e0.is_some()),
            ("`E_at`", self.e_at.is_some()),
            ("`contact_radius`", self.contact_radius.is_some()),
        ]
        .into_iter()
        .filter_map(|(key, present)| present.then_some(key))
        .collect();
        ensure!(
            anchors.len() <= 1,
            "more than one scale anchor ({}): give at most one of E0, E_at and contact_radius",
            anchors.join(", ")
        );
        if let Some(Terms::Count(n)) = self.terms {
            ensure!(n >= 2, "terms = {n}: must be at least 2 (or \"auto\")");
        }
        let grids: Vec<&str> = [
            ("`terms`", self.terms.is_some()),
            ("`terms_per_decade`", self.terms_per_decade.is_some()),
            ("`tau`", self.tau.is_some()),
        ]
        .into_iter()
        .filter_map(|(key, present)| present.then_some(key))
        .collect();
        ensure!(
            grids.len() <= 1,
            "{} each choose the relaxation times: give at most one of terms, \
             terms_per_decade and tau",
            grids.join(" and ")
        );
        if let Some(Real(d)) = self.terms_per_decade {
            require_positive("terms_per_decade", d)?;
        }
        if let Some(tau) = &self.tau {
            for (i, &Real(t)) in tau.iter().enumerate() {
                require_positive(&format!("tau[{i}]"), t)?;
            }
        }
        if let Some(LambdaSetting::Value(l)) = self.lambda {
            ensure!(
                l >= 0.0,
                "lambda = {l}: must be zero or greater (or \"auto\")"
            );
        }
        if let Some(Real(tolerance)) = self.tolerance {
            require_positive("tolerance", tolerance)?;
        }
        if let Some(method) = &self.method {
            ensure!(
                !method.trim().is_empty(),
                "method is empty: name a solver such as \"lbfgs\", \"nelder-mead\" or \"auto\""
            );
            Method::parse(method).map_err(|e| anyhow!("{e}"))?;
        }
        Ok(())
    }

    /// The fit settings the section asks for; what it leaves out keeps the
    /// defaults of [`FitParams`]. Ranges are checked by
    /// [`FitParams::check`], which names the key.
    pub fn params(&self) -> Result<FitParams> {
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
            _ => bail!("give at most one scale anchor (E0, E_at or contact_radius)"),
        };
        let mut params = FitParams {
            anchor,
            ..FitParams::default()
        };
        if let Some(Real(e1_max)) = self.e1_max {
            params.e1_max = e1_max;
        }
        if let Some(terms) = self.terms {
            params.terms = match terms {
                Terms::Auto => TermRule::Auto,
                Terms::Count(n) => TermRule::Count(usize::try_from(n).unwrap_or(0)),
            };
        } else if let Some(Real(d)) = self.terms_per_decade {
            params.terms = TermRule::PerDecade(d);
        } else if let Some(tau) = &self.tau {
            params.terms = TermRule::Explicit(reals(tau));
        }
        if let Some(method) = &self.method {
            params.method = Method::parse(method).map_err(|e| anyhow!("{e}"))?;
        }
        if let Some(lambda) = self.lambda {
            params.lambda = match lambda {
                LambdaSetting::Auto => Lambda::Auto,
                LambdaSetting::Value(l) => Lambda::Fixed(l),
            };
        }
        if let Some(seed) = self.seed {
            params.seed = seed;
        }
        if let Some(starts) = self.starts {
            params.starts = starts;
        }
        if let Some(budget) = self.max_evaluations {
            params.max_evaluations = Some(budget);
        }
        if let Some(Real(tolerance)) = self.tolerance {
            params.model_tolerance = tolerance;
        }
        if let Some(kind) = self.shift {
            params.shift.kind = match kind {
                ShiftKind::Wlf => rollfit_fit::ShiftKind::Wlf,
                ShiftKind::Free => rollfit_fit::ShiftKind::Free,
                ShiftKind::Arrhenius => bail!(
                    "shift = \"arrhenius\": a temperature set is fitted with \"wlf\" or \"free\" \
                     shifts (a free shift follows any law)"
                ),
            };
        }
        if let Some(Real(t)) = self.t_ref {
            params.shift.t_ref = Some(t);
        }
        if let Some(check) = self.cross_check {
            params.shift.cross_check = check;
        }
        Ok(params)
    }
}

/// The speeds `rollfit fit` accepts ([`rollfit_fit::data::SPEED_RANGE`]),
/// so that a synthetic measurement can be fitted back.
fn in_speed_range(key: &str, v: f64) -> Result<()> {
    let (low, high) = rollfit_fit::data::SPEED_RANGE;
    ensure!(
        (low..=high).contains(&v),
        "{key} = {v:e}: speeds must lie between {low:e} and {high:e} m/s (the range of a rolling \
         measurement that `rollfit fit` accepts)"
    );
    Ok(())
}

impl SweepSection {
    /// The speeds (m/s), strictly increasing: log-spaced from the range or
    /// the explicit list.
    pub fn speeds(&self) -> Result<Vec<f64>> {
        if let Some(list) = &self.v {
            ensure!(
                self.v_min.is_none() && self.v_max.is_none() && self.count.is_none(),
                "give either `v = [..]` or `v_min`, `v_max` (and `count`), not both"
            );
            ensure!(!list.is_empty(), "`v` is empty: list at least one speed");
            let speeds = reals(list);
            for (i, &v) in speeds.iter().enumerate() {
                ensure!(v > 0.0, "v[{i}] = {v}: speeds must be greater than zero");
                in_speed_range(&format!("v[{i}]"), v)?;
            }
            if let Some(i) = speeds.windows(2).position(|w| w[1] <= w[0]) {
                bail!(
                    "v[{}] = {} does not exceed v[{i}] = {}: list the speeds in increasing order",
                    i + 1,
                    speeds[i + 1],
                    speeds[i]
                );
            }
            return Ok(speeds);
        }
        let v_min = self
            .v_min
            .context("needs `v_min` and `v_max` (m/s), or a list `v = [..]`")?
            .0;
        let v_max = self
            .v_max
            .context("needs `v_min` and `v_max` (m/s), or a list `v = [..]`")?
            .0;
        require_positive("v_min", v_min)?;
        require_positive("v_max", v_max)?;
        in_speed_range("v_min", v_min)?;
        in_speed_range("v_max", v_max)?;
        ensure!(
            v_min < v_max,
            "v_min = {v_min} must be less than v_max = {v_max}"
        );
        let count = self.count.unwrap_or(DEFAULT_SWEEP_COUNT);
        ensure!(count >= 1, "count = {count}: must be at least 1");
        ensure!(
            count <= MAX_SWEEP_COUNT,
            "count = {count}: at most {MAX_SWEEP_COUNT} speeds"
        );
        let speeds = log_spaced(v_min, v_max, count as usize);
        ensure!(
            speeds.windows(2).all(|w| w[0] < w[1]),
            "count = {count} is too many distinct speeds between v_min = {v_min} and v_max = {v_max}"
        );
        Ok(speeds)
    }
}

/// `count` speeds log-spaced from `v_min` to `v_max`, both ends exact; a
/// single speed is `v_min`.
pub fn log_spaced(v_min: f64, v_max: f64, count: usize) -> Vec<f64> {
    if count == 1 {
        return vec![v_min];
    }
    let (a, b) = (v_min.log10(), v_max.log10());
    let last = (count - 1) as f64;
    (0..count)
        .map(|i| match i {
            0 => v_min,
            i if i == count - 1 => v_max,
            i => 10f64.powf(a + (b - a) * i as f64 / last),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const SLS: &str = r#"
[geometry]
shape = "sphere"
radius = 0.01
load = 0.15
[material]
model = "sls"
E0 = 1e6
E1 = 1e7
tau = 1
[sweep]
v_min = 1e-6
v_max = 1.0
count = 7
"#;

    fn setup(text: &str) -> Result<ForwardSetup> {
        parse(text)?.forward_setup(Path::new("scene.toml"))
    }

    #[test]
    fn defaults_fill_optional_sections() {
        let s = setup(SLS).unwrap();
        assert_eq!(s.blocks[0].scene.substrate().poisson, 0.5);
        assert_eq!(s.blocks[0].scene.substrate().film_thickness, None);
        assert_eq!(s.blocks[0].scene.contact(), ContactSize::Dynamic);
        assert_eq!(s.speeds.len(), 7);
        assert_eq!(s.speeds[0], 1e-6);
        assert_eq!(s.speeds[6], 1.0);
        assert!((s.speeds[3] - 1e-3).abs() < 1e-15);
        assert!(s.blocks[0].shift.is_none());
        assert_eq!(s.blocks[0].scene.material().static_modulus(), 1e6);
    }

    #[test]
    fn default_count_is_61() {
        let s = setup(&SLS.replace("count = 7\n", "")).unwrap();
        assert_eq!(s.speeds.len(), 61);
    }

    #[test]
    fn prony_and_explicit_speeds() {
        let text = SLS
            .replace("model = \"sls\"\nE0 = 1e6\n", "model = \"prony\"\n")
            .replace("tau = 1", "H = [4e6, 5e6]\ntau = [0.1, 1.0]")
            .replace(
                "v_min = 1e-6\nv_max = 1.0\ncount = 7",
                "v = [1e-3, 2e-3, 1]",
            );
        let s = setup(&text).unwrap();
        assert_eq!(s.speeds, vec![1e-3, 2e-3, 1.0]);
        assert!((s.blocks[0].scene.material().static_modulus() - 1e6).abs() < 1e-6);
    }

    #[test]
    fn fit_section_is_accepted() {
        for anchor in [
            "E0 = 2e6",
            "E_at = { omega = 1.0, E = 1.2e8 }",
            "contact_radius = { v = 1e-6, r = 1e-3 }",
        ] {
            let text = format!(
                "{SLS}[fit]\n{anchor}\nE1_max = 1e10\nterms = \"auto\"\nmethod = \"lbfgs\"\n"
            );
            let file = parse(&text).unwrap();
            assert_eq!(file.fit.unwrap().terms, Some(Terms::Auto));
        }
        let file = parse(&format!("{SLS}[fit]\nterms = 15\n")).unwrap();
        assert_eq!(file.fit.unwrap().terms, Some(Terms::Count(15)));
        assert!(parse(&format!("{SLS}[fit]\nterms = 0\n")).is_err());
        assert!(parse(&format!("{SLS}[fit]\nterms = \"many\"\n")).is_err());
    }

    #[test]
    fn fit_section_gives_fit_params() {
        let text = format!(
            "{SLS}[fit]\nE_at = {{ omega = 2.0, E = 1.2e8 }}\nE1_max = 5e9\nterms_per_decade = 1.5\n\
             method = \"nelder-mead\"\nlambda = 0\nseed = 7\nstarts = 2\nmax_evaluations = 500\n\
             tolerance = 1e-5\n"
        );
        let (setup, params) = parse(&text).unwrap().fit_setup().unwrap();
        assert_eq!(setup.geometry.radius, 0.01);
        assert_eq!(setup.substrate.poisson, DEFAULT_POISSON);
        assert_eq!(
            params.anchor,
            Some(ScaleAnchor::ModulusAt {
                omega: 2.0,
                modulus: 1.2e8
            })
        );
        assert_eq!(params.e1_max, 5e9);
        assert_eq!(params.terms, TermRule::PerDecade(1.5));
        assert_eq!(params.method, Method::NelderMead);
        assert_eq!(params.lambda, Lambda::Fixed(0.0));
        assert_eq!((params.seed, params.starts), (7, 2));
        assert_eq!(params.max_evaluations, Some(500));
        assert_eq!(params.model_tolerance, 1e-5);
        // The scene's standard linear solid is the starting point.
        let start = params.start.clone().unwrap();
        assert_eq!((start.static_modulus, start.glassy_modulus), (1e6, 1e7));
        assert!(params.check(setup).is_ok());

        // Defaults, a Prony start (E0 = E1 - sum H) and explicit tau.
        let prony = SLS
            .replace("model = \"sls\"\nE0 = 1e6\n", "model = \"prony\"\n")
            .replace("tau = 1", "H = [4e6, 5e6]\ntau = [0.1, 1.0]");
        let (_, params) = parse(&format!(
            "{prony}[fit]\ntau = [1e-3, 1e-2, 1e-1]\nlambda = \"auto\"\n"
        ))
        .unwrap()
        .fit_setup()
        .unwrap();
        assert_eq!(params.terms, TermRule::Explicit(vec![1e-3, 1e-2, 1e-1]));
        assert_eq!(params.lambda, Lambda::Auto);
        assert_eq!(params.anchor, None);
        let start = params.start.unwrap();
        assert!((start.static_modulus - 1e6).abs() < 1e-6);
        let (_, params) = parse(SLS.split("[material]").next().unwrap())
            .unwrap()
            .fit_setup()
            .unwrap();
        assert_eq!(params, FitParams::default());
    }

    #[test]
    fn fit_section_conflicts_are_named() {
        let err = |fit: &str| format!("{:#}", parse(&format!("{SLS}[fit]\n{fit}\n")).unwrap_err());
        let m = err("E0 = 1e6\ncontact_radius = { v = 1e-6, r = 1e-3 }");
        assert!(
            m.contains("`E0`, `contact_radius`") && m.contains("at most one"),
            "{m}"
        );
        let m = err("terms = 10\ntau = [1.0, 2.0]");
        assert!(m.contains("`terms` and `tau`"), "{m}");
        assert!(err("lambda = -1").contains("lambda = -1"));
        assert!(err("lambda = \"big\"").contains("auto"));
        assert!(err("method = \"newton\"").contains("unknown method \"newton\""));
        assert!(err("seed = -1").contains("seed"));
        assert!(err("terms_per_decade = 0").contains("terms_per_decade = 0"));
        assert!(err("tau = [1.0, -2.0]").contains("tau[1] = -2"));
        assert!(err("bogus = 1").contains("unknown field `bogus`"));
    }

    #[test]
    fn wlf_shift_is_applied() {
        let text = SLS.replace(
            "tau = 1\n",
            "tau = 1\n[material.shift]\nmodel = \"wlf\"\nT_ref = 20.0\nC1 = 8.86\nC2 = 101.6\n",
        ) + "temperature = 40.0\n";
        let s = setup(&text).unwrap();
        let shift = s.blocks[0].shift.unwrap();
        let expected = -8.86 * 20.0 / (101.6 + 20.0);
        assert!((shift.log10_a_t - expected).abs() < 1e-12);
    }

    #[test]
    fn temperature_list_gives_one_block_per_temperature() {
        let text = SLS.replace(
            "tau = 1\n",
            "tau = 1\n[material.shift]\nmodel = \"wlf\"\nT_ref = 20.0\nC1 = 8.86\nC2 = 101.6\n",
        );
        let wlf = |t: f64| -8.86 * (t - 20.0) / (101.6 + t - 20.0);
        let s = setup(&format!("{text}temperature = [40.0, -20, 20.0]\n")).unwrap();
        assert_eq!(s.speeds.len(), 7);
        let shifts: Vec<ShiftApplied> = s.blocks.iter().map(|b| b.shift.unwrap()).collect();
        assert_eq!(
            shifts.iter().map(|s| s.temperature).collect::<Vec<_>>(),
            vec![40.0, -20.0, 20.0]
        );
        for shift in &shifts {
            assert!((shift.log10_a_t - wlf(shift.temperature)).abs() < 1e-12);
        }
        // The same shift as the single-temperature form.
        let one = setup(&format!("{text}temperature = -20.0\n")).unwrap();
        assert_eq!(one.blocks.len(), 1);
        assert_eq!(one.blocks[0].shift, Some(shifts[1]));

        let err = |list: &str| {
            format!(
                "{:#}",
                parse(&format!("{text}temperature = {list}\n")).unwrap_err()
            )
        };
        assert!(err("[]").contains("[sweep]: `temperature = []`"));
        let m = err("[1.0, 2.0, 1.0]");
        assert!(
            m.contains("temperature[2] = 1 repeats temperature[0] = 1"),
            "{m}"
        );
        let m = err("[1.0, inf]");
        assert!(
            m.contains("[sweep] temperature[1]") && m.contains("finite"),
            "{m}"
        );
        let m = format!(
            "{:#}",
            parse(&format!("{SLS}temperature = [1.0]\n")).unwrap_err()
        );
        assert!(
            m.contains("[sweep] temperature = [1]") && m.contains("[material.shift]"),
            "{m}"
        );
    }

    /// An Arrhenius `[material.shift]` gives the model's law; its keys
    /// are checked like WLF's.
    #[test]
    fn arrhenius_shift() {
        let text = SLS.replace(
            "tau = 1\n",
            "tau = 1\n[material.shift]\nmodel = \"arrhenius\"\nT_ref = 20.0\nE_a = 1.5e5\n",
        );
        let s = setup(&format!("{text}temperature = 35.0\n")).unwrap();
        let law = Arrhenius::new(20.0, 1.5e5).unwrap();
        assert_eq!(
            s.blocks[0].shift.unwrap().log10_a_t,
            law.log10_shift(35.0).unwrap()
        );
        let m = format!(
            "{:#}",
            parse(&text.replace("E_a = 1.5e5", "C1 = 8.0")).unwrap_err()
        );
        assert!(m.contains("do not belong to model \"arrhenius\""), "{m}");
        let m = format!(
            "{:#}",
            parse(&text.replace("E_a = 1.5e5", "E_a = -1.0")).unwrap_err()
        );
        assert!(m.contains("E_a"), "{m}");
    }

    /// The keys of model = "dma" belong to it alone (`modulus` to "table"
    /// as well), and a `[material.shift]` beside it is refused: the shift
    /// comes from the isotherms. A missing file names itself.
    #[test]
    fn dma_material_keys() {
        let dma = "[geometry]\nshape = \"sphere\"\nradius = 0.01\nload = 0.15\n[material]\n\
                   model = \"dma\"\nfile = \"absent.csv\"\n";
        let m = format!(
            "{:#}",
            setup(&format!("{dma}[sweep]\nv_min = 1e-6\nv_max = 1.0\n"))
                .err()
                .expect("a missing DMA file is an error")
        );
        assert!(m.contains("absent.csv"), "{m}");
        let m = format!("{:#}", parse(&format!("{dma}E1 = 1e7\n")).unwrap_err());
        assert!(m.contains("`E1` does not belong to model \"dma\""), "{m}");
        let m = format!(
            "{:#}",
            parse(&format!(
                "{dma}[material.shift]\nmodel = \"wlf\"\nT_ref = 20.0\nC1 = 8.0\nC2 = 100.0\n"
            ))
            .unwrap_err()
        );
        assert!(m.contains("does not go with model = \"dma\""), "{m}");
        let m = format!(
            "{:#}",
            parse(&SLS.replace("tau = 1\n", "tau = 1\nT_ref = 20.0\n")).unwrap_err()
        );
        assert!(
            m.contains("`T_ref` does not belong to model \"sls\"") && m.contains("\"dma\""),
            "{m}"
        );
        assert!(
            parse(&format!(
                "{dma}T_ref = 25.0\nmodulus = \"shear\"\nshift_law = \"free\"\nvertical = true\n"
            ))
            .is_ok()
        );
        // A [sweep] temperature needs no [material.shift] with "dma".
        assert!(
            parse(&format!(
                "{dma}[sweep]\nv_min = 1e-6\nv_max = 1.0\ntemperature = 30.0\n"
            ))
            .is_ok()
        );
    }

    const FREE_SHIFT: &str = "tau = 1\n[material.shift]\nmodel = \"free\"\nT_ref = 20.0\n\
         log_aT = [{ T = 60.0, log_aT = -3.0 }, { T = 0.0, log_aT = 2.0 }]\n";

    #[test]
    fn free_shift_follows_the_model_rule() {
        let text = SLS.replace("tau = 1\n", FREE_SHIFT);
        let shift_at = |t: f64| {
            setup(&format!("{text}temperature = {t:?}\n"))
                .map(|s| s.blocks[0].shift.unwrap().log10_a_t)
        };
        let model =
            rollfit_model::modulus::FreeShift::new(20.0, vec![(60.0, -3.0), (0.0, 2.0)]).unwrap();
        for t in [0.0, 5.0, 10.0, 20.0, 33.3, 40.0, 60.0] {
            assert_eq!(shift_at(t).unwrap(), model.log10_shift(t).unwrap(), "{t}");
        }
        // Exact at listed temperatures and T_ref, linear in T between them.
        assert_eq!(shift_at(0.0).unwrap(), 2.0);
        assert_eq!(shift_at(20.0).unwrap(), 0.0);
        assert_eq!(shift_at(60.0).unwrap(), -3.0);
        assert!((shift_at(10.0).unwrap() - 1.0).abs() < 1e-12);
        assert!((shift_at(40.0).unwrap() + 1.5).abs() < 1e-12);
        for t in [70.0, -0.5] {
            let err = format!("{:#}", shift_at(t).unwrap_err());
            for fragment in [
                "[material.shift] at [sweep] temperature",
                &format!("T = {t} °C"),
                "outside",
                "0 to 60 °C",
                "`log_aT`",
            ] {
                assert!(err.contains(fragment), "{fragment:?} in {err}");
            }
        }
    }

    #[test]
    fn free_shift_entries_are_checked_by_the_model_and_named() {
        let err = |log_at: &str| {
            let text = SLS.replace(
                "tau = 1\n",
                &format!("tau = 1\n[material.shift]\nmodel = \"free\"\nT_ref = 20.0\n{log_at}"),
            );
            format!("{:#}", parse(&text).unwrap_err())
        };
        let msg = err("log_aT = [{ T = 0.0, log_aT = 2.0 }, { T = 0.0, log_aT = 2.5 }]\n");
        assert!(
            msg.contains("[material.shift]") && msg.contains("`log_aT`: free shift: entry 1"),
            "{msg}"
        );
        assert!(msg.contains("listed before as entry 0"), "{msg}");
        let msg = err("log_aT = [{ T = 20.0, log_aT = 0.5 }]\n");
        assert!(
            msg.contains("`log_aT`") && msg.contains("reference temperature"),
            "{msg}"
        );
        let msg = err("log_aT = []\n");
        assert!(
            msg.contains("`log_aT`") && msg.contains("no temperatures"),
            "{msg}"
        );
        let msg = err("");
        assert!(msg.contains("needs the key `log_aT`"), "{msg}");
        let msg = err("log_aT = [{ T = 0.0, log_aT = 2.0 }]\nC1 = 8.86\n");
        assert!(msg.contains("`C1`, `C2` and `E_a` do not belong"), "{msg}");
    }

    #[test]
    fn havriliak_negami_and_its_alias() {
        let hn =
            "model = \"havriliak-negami\"\nE0 = 1e6\nE1 = 1e9\ntau = 1e-3\nalpha = 0.5\nbeta = 0.4";
        let text = SLS.replace("model = \"sls\"\nE0 = 1e6\nE1 = 1e7\ntau = 1", hn);
        let s = setup(&text).unwrap();
        assert_eq!(s.blocks[0].scene.material().static_modulus(), 1e6);
        assert_eq!(s.blocks[0].scene.material().loss_exponent_at_zero(), 0.5);
        let alias = setup(&text.replace("\"havriliak-negami\"", "\"hn\"")).unwrap();
        assert_eq!(
            alias.blocks[0].scene.material().modulus(3.0),
            s.blocks[0].scene.material().modulus(3.0)
        );
        let err = format!(
            "{:#}",
            parse(&text.replace("alpha = 0.5\n", "")).unwrap_err()
        );
        assert!(err.contains("needs the key `alpha`"), "{err}");
    }

    #[test]
    fn log_spacing_is_exact_at_the_ends_and_increasing() {
        let v = log_spaced(1e-8, 10.0, 91);
        assert_eq!(v.len(), 91);
        assert_eq!((v[0], v[90]), (1e-8, 10.0));
        assert!(v.windows(2).all(|w| w[0] < w[1]));
        assert!((v[10] / 1e-7 - 1.0).abs() < 1e-13);
    }

    #[test]
    fn non_finite_numbers_are_reported_with_position() {
        let err = format!(
            "{:#}",
            parse(&SLS.replace("radius = 0.01", "radius = nan")).unwrap_err()
        );
        assert!(
            err.contains("line 4") && err.contains("radius") && err.contains("finite"),
            "{err}"
        );
        let err = format!(
            "{:#}",
            parse(&SLS.replace("tau = 1", "tau = -inf")).unwrap_err()
        );
        assert!(err.contains("tau") && err.contains("finite"), "{err}");
    }
}
