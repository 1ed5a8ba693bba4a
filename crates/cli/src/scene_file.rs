//! The scene file (TOML, DESIGN.md §4): its schema and its conversion into
//! validated model objects.
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

use anyhow::{Context, Result, anyhow, bail, ensure};
use rollfit_model::{
    ContactSize, Geometry, ModelError, Prony, Scene, Shape, Shifted, StandardLinearSolid,
    Substrate, TabulatedModulus, ViscoelasticModulus, Wlf,
};
use serde::Deserialize;
use serde::de::{self, Deserializer, SeqAccess, Visitor};

use crate::table_file;

/// The scene the forward model runs on: any material behind one pointer, so
/// that a shifted table and a plain standard linear solid share one type.
pub type DynScene = Scene<Box<dyn ViscoelasticModulus>>;

/// Default number of log-spaced speeds of a `[sweep]` given by its range.
pub const DEFAULT_SWEEP_COUNT: i64 = 61;

/// Largest accepted `count`: far beyond any useful sweep, but small enough
/// that a typo cannot make the tool try to allocate exabytes.
pub const MAX_SWEEP_COUNT: i64 = 1_000_000;

const TEMPERATURE_WITHOUT_SHIFT: &str = "[sweep] temperature is set but [material] has no \
     [material.shift]: without a time-temperature shift the material is known only at its \
     reference temperature";

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

/// Contact-size rule names as written in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ContactName {
    /// |E_eff(ω)| at the local frequency.
    Dynamic,
    /// E_eff(0) for every frequency.
    Static,
}

/// `[contact]`.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSection {
    /// "dynamic" (default) or "static".
    pub size: Option<ContactName>,
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
}

impl MaterialKind {
    fn name(self) -> &'static str {
        match self {
            MaterialKind::Sls => "sls",
            MaterialKind::Prony => "prony",
            MaterialKind::Table => "table",
        }
    }

    fn keys(self) -> &'static str {
        match self {
            MaterialKind::Sls => "E0, E1, tau",
            MaterialKind::Prony => "E1, H, tau",
            MaterialKind::Table => "file",
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
    /// "sls", "prony" or "table".
    pub model: MaterialKind,
    /// Rubbery (static) Young's modulus E0, Pa ("sls").
    #[serde(rename = "E0")]
    pub e0: Option<Real>,
    /// Glassy Young's modulus E1, Pa ("sls", "prony").
    #[serde(rename = "E1")]
    pub e1: Option<Real>,
    /// Time constant τ, s ("sls": one number; "prony": one per term).
    pub tau: Option<RealOrList>,
    /// Prony strengths H_k, Pa ("prony").
    #[serde(rename = "H")]
    pub h: Option<Vec<Real>>,
    /// Modulus table, relative to the scene file's folder ("table").
    pub file: Option<PathBuf>,
    /// `[material.shift]`: time–temperature shift.
    pub shift: Option<ShiftSection>,
}

/// Shift model names as written in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ShiftKind {
    /// Williams–Landel–Ferry: T_ref, C1, C2.
    Wlf,
    /// One log10 a_T per temperature: T_ref, log_aT = [{T, log_aT}, ..].
    Free,
}

/// `[material.shift]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShiftSection {
    /// "wlf" or "free".
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
    /// Solver name ("lbfgs", "nelder-mead", "auto", ...).
    pub method: Option<String>,
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
    /// Temperature, °C; needs `[material.shift]`.
    pub temperature: Option<Real>,
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

/// Everything `rollfit forward` needs, validated.
pub struct ForwardSetup {
    /// The scene, material already shifted to the sweep temperature.
    pub scene: DynScene,
    /// Strictly increasing speeds, m/s.
    pub speeds: Vec<f64>,
    /// The temperature shift, if the sweep asked for a temperature.
    pub shift: Option<ShiftApplied>,
}

/// Reads, parses and validates a scene file; every error names `path`.
pub fn load(path: &Path) -> Result<SceneFile> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read scene file {}", path.display()))?;
    parse(&text).with_context(|| format!("scene file {}", path.display()))
}

/// Parses and validates scene-file text (the sections' internal consistency;
/// the model checks physical ranges when the scene is built).
pub fn parse(text: &str) -> Result<SceneFile> {
    // toml's message already carries "line L, column C" and the offending line.
    let file: SceneFile =
        toml::from_str(text).map_err(|e| anyhow!("{}", e.to_string().trim_end()))?;
    if let Some(material) = &file.material {
        material.check_keys()?;
        if let Some(shift) = &material.shift {
            shift.check().context("[material.shift]")?;
        }
    }
    if let Some(fit) = &file.fit {
        fit.check().context("[fit]")?;
    }
    if let Some(sweep) = &file.sweep {
        sweep.speeds().context("[sweep]")?;
        if sweep.temperature.is_some() && file.material.as_ref().is_some_and(|m| m.shift.is_none())
        {
            bail!(TEMPERATURE_WITHOUT_SHIFT);
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
        let mut material = material_section.build(base_dir).context("[material]")?;
        let mut shift = None;
        if let Some(Real(temperature)) = sweep.temperature {
            let section = material_section
                .shift
                .as_ref()
                .context(TEMPERATURE_WITHOUT_SHIFT)?;
            let log10_a_t = section
                .log10_shift(temperature)
                .context("[material.shift]")?;
            material = Box::new(
                Shifted::new(material, log10_a_t).map_err(|e| anyhow!("[material.shift]: {e}"))?,
            );
            shift = Some(ShiftApplied {
                temperature,
                log10_a_t,
            });
        }

        let geometry = Geometry {
            shape: match self.geometry.shape {
                ShapeName::Sphere => Shape::Sphere,
                ShapeName::Cylinder => Shape::Cylinder,
            },
            radius: self.geometry.radius.0,
            load: self.geometry.load.0,
        };
        let substrate = Substrate {
            poisson: self.substrate.poisson.map_or(DEFAULT_POISSON, |r| r.0),
            film_thickness: self.substrate.thickness.map(|r| r.0),
        };
        let contact = match self.contact.size {
            None | Some(ContactName::Dynamic) => ContactSize::Dynamic,
            Some(ContactName::Static) => ContactSize::Static,
        };
        let mut scene = Scene::new(geometry, substrate, contact, material)
            .map_err(|e| anyhow!("{}{e}", section_of(&e)))?;
        if let Some(Real(tolerance)) = sweep.tolerance {
            scene = scene
                .with_tolerance(tolerance)
                .map_err(|e| anyhow!("[sweep]: {e}"))?;
        }
        Ok(ForwardSetup {
            scene,
            speeds,
            shift,
        })
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
        ];
        let needed: &[&str] = match kind {
            MaterialKind::Sls => &["E0", "E1", "tau"],
            MaterialKind::Prony => &["E1", "H", "tau"],
            MaterialKind::Table => &["file"],
        };
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
            (MaterialKind::Sls, Some(RealOrList::List(_))) => {
                bail!(
                    "[material]: model \"sls\" takes one relaxation time: `tau` must be a number, not an array"
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
    fn build(&self, base_dir: &Path) -> Result<Box<dyn ViscoelasticModulus>> {
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
            MaterialKind::Table => {
                let file = self.file.as_ref().context("model \"table\" needs `file`")?;
                let path = base_dir.join(file);
                let table = table_file::read(&path)?;
                Box::new(
                    TabulatedModulus::new(table.omega, table.storage, table.loss)
                        .map_err(|e| anyhow!("modulus table {}: {e}", path.display()))?,
                )
            }
        })
    }
}

impl ShiftSection {
    /// Checks that exactly the keys of the chosen shift model are present
    /// and that a free shift's temperatures are distinct.
    fn check(&self) -> Result<()> {
        match self.model {
            ShiftKind::Wlf => {
                ensure!(
                    self.c1.is_some() && self.c2.is_some(),
                    "model \"wlf\" needs the keys `C1` and `C2` (and `T_ref`)"
                );
                ensure!(
                    self.log_at.is_none(),
                    "key `log_aT` does not belong to model \"wlf\" (it takes T_ref, C1, C2)"
                );
                Wlf::new(self.t_ref.0, value_of(self.c1), value_of(self.c2))
                    .map_err(|e| anyhow!("{e}"))?;
            }
            ShiftKind::Free => {
                ensure!(
                    self.c1.is_none() && self.c2.is_none(),
                    "keys `C1` and `C2` do not belong to model \"free\" (it takes T_ref, log_aT)"
                );
                let points = self.free_points()?;
                ensure!(
                    points.len() >= 2,
                    "model \"free\" needs `log_aT` entries at two or more temperatures, \
                     e.g. log_aT = [{{ T = 0.0, log_aT = 2.1 }}, {{ T = 40.0, log_aT = -1.3 }}]"
                );
            }
        }
        Ok(())
    }

    /// The free shift's (T, log10 a_T) pairs sorted by temperature, the
    /// reference temperature included with log10 a_T = 0.
    fn free_points(&self) -> Result<Vec<(f64, f64)>> {
        let listed = self.log_at.as_deref().unwrap_or_default();
        let t_ref = self.t_ref.0;
        let mut points: Vec<(f64, f64)> = listed.iter().map(|p| (p.t.0, p.log_at.0)).collect();
        if let Some(&(_, at_ref)) = points.iter().find(|(t, _)| *t == t_ref) {
            ensure!(
                at_ref == 0.0,
                "log_aT = {at_ref} at T = T_ref = {t_ref}: the shift is 0 at the reference temperature by definition"
            );
        } else {
            points.push((t_ref, 0.0));
        }
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        if let Some(pair) = points.windows(2).find(|w| w[0].0 == w[1].0) {
            bail!("log_aT lists the temperature T = {} twice", pair[0].0);
        }
        Ok(points)
    }

    /// log10 a_T at `temperature` (°C). A free shift is interpolated linearly
    /// in T between its listed temperatures and never extrapolated: outside
    /// them nothing is known about the material.
    pub fn log10_shift(&self, temperature: f64) -> Result<f64> {
        let shift = match self.model {
            ShiftKind::Wlf => {
                let wlf = Wlf::new(self.t_ref.0, value_of(self.c1), value_of(self.c2))
                    .map_err(|e| anyhow!("{e}"))?;
                wlf.log10_shift(temperature).map_err(|e| anyhow!("{e}"))?
            }
            ShiftKind::Free => {
                let points = self.free_points()?;
                let (first, last) = (points[0].0, points[points.len() - 1].0);
                ensure!(
                    (first..=last).contains(&temperature),
                    "temperature {temperature} °C lies outside the temperatures of the free shift \
                     ({first} … {last} °C); add a log_aT entry for it or use model = \"wlf\""
                );
                let i = points
                    .windows(2)
                    .position(|w| temperature <= w[1].0)
                    .unwrap_or(points.len() - 2);
                let ((t0, s0), (t1, s1)) = (points[i], points[i + 1]);
                s0 + (s1 - s0) * (temperature - t0) / (t1 - t0)
            }
        };
        ensure!(
            shift.is_finite(),
            "log10 a_T at T = {temperature} °C is {shift}: the shift is not defined at this temperature"
        );
        Ok(shift)
    }
}

fn value_of(r: Option<Real>) -> f64 {
    r.map_or(f64::NAN, |r| r.0)
}

fn require_positive(key: &str, value: f64) -> Result<()> {
    ensure!(value > 0.0, "{key} = {value}: must be greater than zero");
    Ok(())
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
        if let Some(Terms::Count(n)) = self.terms {
            ensure!(n >= 1, "terms = {n}: must be at least 1 (or \"auto\")");
        }
        if let Some(method) = &self.method {
            ensure!(
                !method.trim().is_empty(),
                "method is empty: name a solver such as \"lbfgs\", \"nelder-mead\" or \"auto\""
            );
        }
        Ok(())
    }
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
        assert_eq!(s.scene.substrate().poisson, 0.5);
        assert_eq!(s.scene.substrate().film_thickness, None);
        assert_eq!(s.scene.contact(), ContactSize::Dynamic);
        assert_eq!(s.speeds.len(), 7);
        assert_eq!(s.speeds[0], 1e-6);
        assert_eq!(s.speeds[6], 1.0);
        assert!((s.speeds[3] - 1e-3).abs() < 1e-15);
        assert!(s.shift.is_none());
        assert_eq!(s.scene.material().static_modulus(), 1e6);
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
        assert!((s.scene.material().static_modulus() - 1e6).abs() < 1e-6);
    }

    #[test]
    fn fit_section_is_accepted() {
        let text = format!(
            "{SLS}[fit]\nE0 = 2e6\nE_at = {{ omega = 1.0, E = 1.2e8 }}\n\
             contact_radius = {{ v = 1e-6, r = 1e-3 }}\nE1_max = 1e10\nterms = \"auto\"\nmethod = \"lbfgs\"\n"
        );
        let file = parse(&text).unwrap();
        assert_eq!(file.fit.unwrap().terms, Some(Terms::Auto));
        let file = parse(&format!("{SLS}[fit]\nterms = 15\n")).unwrap();
        assert_eq!(file.fit.unwrap().terms, Some(Terms::Count(15)));
        assert!(parse(&format!("{SLS}[fit]\nterms = 0\n")).is_err());
        assert!(parse(&format!("{SLS}[fit]\nterms = \"many\"\n")).is_err());
    }

    #[test]
    fn wlf_shift_is_applied() {
        let text = SLS.replace(
            "tau = 1\n",
            "tau = 1\n[material.shift]\nmodel = \"wlf\"\nT_ref = 20.0\nC1 = 8.86\nC2 = 101.6\n",
        ) + "temperature = 40.0\n";
        let s = setup(&text).unwrap();
        let shift = s.shift.unwrap();
        let expected = -8.86 * 20.0 / (101.6 + 20.0);
        assert!((shift.log10_a_t - expected).abs() < 1e-12);
    }

    #[test]
    fn free_shift_interpolates_and_refuses_to_extrapolate() {
        let text = SLS.replace(
            "tau = 1\n",
            "tau = 1\n[material.shift]\nmodel = \"free\"\nT_ref = 20.0\n\
             log_aT = [{ T = 0.0, log_aT = 2.0 }, { T = 60.0, log_aT = -3.0 }]\n",
        );
        let shift_at = |t: f64| {
            setup(&format!("{text}temperature = {t:?}\n")).map(|s| s.shift.unwrap().log10_a_t)
        };
        assert!((shift_at(10.0).unwrap() - 1.0).abs() < 1e-12);
        assert!((shift_at(40.0).unwrap() + 1.5).abs() < 1e-12);
        assert_eq!(shift_at(20.0).unwrap(), 0.0);
        assert_eq!(shift_at(0.0).unwrap(), 2.0);
        assert_eq!(shift_at(60.0).unwrap(), -3.0);
        let err = format!("{:#}", shift_at(70.0).unwrap_err());
        assert!(err.contains("outside"), "{err}");
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
