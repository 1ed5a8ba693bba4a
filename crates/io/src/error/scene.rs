//! The errors of a scene file ([`SceneError`], reached as
//! [`super::IoError::Scene`]; read by [`crate::scene`], docs/ARCHITECTURE.md,
//! "Contract", "Scene file"). The causes inside a file name the section
//! and key at fault, and toml's own messages the line and column; the
//! file is named by [`SceneError::InFile`], the section of a cause found
//! further down by [`SceneError::InSection`], each printed before its
//! source by `{:#}`: `scene file s.toml: [sweep]: count = 0: must be at
//! least 1`. The model's messages are shown as they are, behind the
//! section they came from.

use std::path::PathBuf;

use rollfit_model::ModelError;
use thiserror::Error;

use super::{ErrorKind, IoError};

/// Why a scene file cannot be read or turned into a scene.
#[derive(Debug, Error)]
pub enum SceneError {
    // ------------------------------------------------------------ wrappers
    /// What is wrong inside the file (the source).
    #[error("scene file {}", path.display())]
    InFile {
        path: PathBuf,
        source: Box<SceneError>,
    },
    /// What is wrong inside a section (the source), e.g. `[sweep]`.
    #[error("{section}")]
    InSection {
        /// The section as written, with its brackets.
        section: &'static str,
        source: Box<SceneError>,
    },
    /// The shift refused at one `[sweep]` temperature (the source).
    #[error("[material.shift] at [sweep] {entry} °C")]
    ShiftAt {
        /// The temperature as the sweep names it: `temperature = 20` or
        /// `temperature[1] = 20`.
        entry: String,
        source: Box<SceneError>,
    },
    /// A file the scene refers to (a modulus table, DMA isotherms) that
    /// cannot be read: its reader's error, with its sources.
    #[error(transparent)]
    File(Box<IoError>),

    // ------------------------------------------------------------ syntax
    /// TOML syntax, an unknown key, a value of the wrong type or a fit
    /// setting refused as it was read: toml's message, with the line,
    /// column and the line itself.
    #[error("{}", error.to_string().trim_end())]
    Toml { error: Box<toml::de::Error> },

    // ------------------------------------------------------------ the model
    /// A value the model refuses (its message names the key).
    #[error("{error}")]
    Model { error: ModelError },
    /// The rolling set-up refused by `Scene::new`, behind the section of
    /// the parameter at fault.
    #[error("{}{error}", section_of(error))]
    SetUp { error: ModelError },
    /// A value the model refuses, behind the section it came from, as one
    /// message (`[sweep]: tolerance = …`).
    #[error("{section}: {error}")]
    SectionModel {
        /// `[sweep]`, `[fit]`, `[material.shift]` or `[contact] exact`.
        section: &'static str,
        error: ModelError,
    },
    /// A modulus table the model cannot interpolate.
    #[error("modulus table {}: {error}", path.display())]
    TableModel { path: PathBuf, error: ModelError },
    /// A temperature outside a free shift's list.
    #[error("{error}; add a `log_aT` entry at or beyond it, or use model = \"wlf\"")]
    FreeShiftOutside { error: ModelError },
    /// Free-shift entries the model refuses.
    #[error("`log_aT`: {error}")]
    FreeShiftEntries { error: ModelError },
    /// A temperature outside a table of vertical factors.
    #[error("{error}; add a `log_bT` entry at or beyond it, or use vertical = \"density\"")]
    VerticalOutside { error: ModelError },
    /// Entries of a table of vertical factors the model refuses.
    #[error("`log_bT`: {error}")]
    VerticalEntries { error: ModelError },
    /// The shift law of a DMA master curve the model refuses.
    #[error("the DMA master curve's shift: {error}")]
    MasterShift { error: ModelError },

    // ------------------------------------------------------------ the whole
    /// `[sweep] tolerance` beside `size = "auto"`.
    #[error(
        "[sweep]: tolerance is set by size = \"auto\" itself (a tenth of [contact] accuracy); \
         remove it, or choose a rung with size = \"dynamic\""
    )]
    AutoSetsTolerance,
    /// `[sweep] temperature` with a material known at one temperature.
    #[error(
        "[sweep] {temperature} is set but [material] has no [material.shift]: without a \
         time-temperature shift the material is known only at its reference temperature"
    )]
    TemperatureWithoutShift {
        /// The key as written: `temperature = 20` or `temperature = [..]`.
        temperature: String,
    },

    // ------------------------------------------------------------ [contact]
    /// `accuracy` without `size = "auto"`.
    #[error(
        "[contact]: accuracy = {accuracy} is the target of size = \"auto\"; add size = \"auto\" \
         or remove accuracy"
    )]
    AccuracyWithoutAuto { accuracy: f64 },
    /// `accuracy` outside 1e-8 … 0.5.
    #[error("[contact]: accuracy = {accuracy} must lie between 1e-8 and 0.5 (relative)")]
    AccuracyOutOfRange { accuracy: f64 },

    // ------------------------------------------------------------ [material]
    /// An optional key of other models.
    #[error(
        "[material]: key `{key}` does not belong to model \"{model}\" (it takes {takes}); `{key}` \
         is for model {}",
        quoted_or(models)
    )]
    KeyOfOtherModels {
        key: &'static str,
        /// The model given.
        model: &'static str,
        /// Its keys, for the message.
        takes: &'static str,
        /// The models the key belongs to.
        models: Vec<&'static str>,
    },
    /// `[material.shift]` beside `model = "dma"`.
    #[error(
        "[material.shift] does not go with model = \"dma\": the shift factors come from the \
         isotherms themselves (`shift_law` chooses \"wlf\", \"free\" or \"arrhenius\"); remove \
         [material.shift]"
    )]
    ShiftWithDma,
    /// A key the model needs is absent.
    #[error("[material]: model \"{model}\" needs the key `{key}` (it takes {takes})")]
    MissingKey {
        key: &'static str,
        model: &'static str,
        takes: &'static str,
    },
    /// A key of another model.
    #[error(
        "[material]: key `{key}` does not belong to model \"{model}\" (it takes {takes}){}",
        if *model == "prony" && *key == "E0" {
            "; the static modulus of a Prony series is E0 = E1 - sum(H)"
        } else {
            ""
        }
    )]
    ForeignKey {
        key: &'static str,
        model: &'static str,
        takes: &'static str,
    },
    /// A list of relaxation times for a model with one.
    #[error(
        "[material]: model \"{model}\" takes one relaxation time: `tau` must be a number, not an \
         array"
    )]
    TauNotNumber { model: &'static str },
    /// One relaxation time for a Prony series.
    #[error(
        "[material]: model \"prony\" takes one relaxation time per term: `tau` must be an array \
         like H"
    )]
    TauNotList,
    /// A file-based model without `file`.
    #[error("model \"{model}\" needs `file`")]
    NeedsFile { model: &'static str },

    /// A list of files for a model that reads one.
    #[error(
        "model \"table\" reads one file: `file` is a list (several DMA files are model \"dma\")"
    )]
    TableFiles,

    // ------------------------------------------------------------ [material.shift]
    /// A shift that is not a finite number.
    #[error(
        "log10 a_T at T = {temperature} °C is {shift}: the shift is not defined at this \
         temperature"
    )]
    ShiftNotFinite { temperature: f64, shift: f64 },
    /// WLF without its constants.
    #[error("model \"wlf\" needs the keys `C1` and `C2` (and `T_ref`)")]
    WlfKeysMissing,
    /// WLF with keys of other laws.
    #[error(
        "keys `log_aT`, `E_a` and `T_g` do not belong to model \"wlf\" (it takes T_ref, C1, C2)"
    )]
    WlfForeignKeys,
    /// WLF–Arrhenius without its constants.
    #[error(
        "model \"wlf-arrhenius\" needs the keys `C1`, `C2` (WLF about T_ref, above T_g), `T_g` \
         (the junction, °C) and `E_a` (J/mol, below T_g), and `T_ref`"
    )]
    WlfArrheniusKeysMissing,
    /// WLF–Arrhenius with a free shift's list.
    #[error(
        "key `log_aT` does not belong to model \"wlf-arrhenius\" (it takes T_ref, C1, C2, T_g, E_a)"
    )]
    WlfArrheniusForeignKeys,
    /// Arrhenius with keys of other laws.
    #[error(
        "keys `C1`, `C2`, `T_g` and `log_aT` do not belong to model \"arrhenius\" (it takes T_ref, \
         E_a)"
    )]
    ArrheniusForeignKeys,
    /// Arrhenius without its energy.
    #[error("model \"arrhenius\" needs the key `E_a`, the activation energy in J/mol")]
    ArrheniusNeedsEnergy,
    /// A free shift with keys of other laws.
    #[error(
        "keys `C1`, `C2`, `T_g` and `E_a` do not belong to model \"free\" (it takes T_ref, log_aT)"
    )]
    FreeForeignKeys,
    /// A free shift without its list.
    #[error(
        "model \"free\" needs the key `log_aT`, one entry per measured temperature, e.g. log_aT \
         = [{{ T = 0.0, log_aT = 2.1 }}, {{ T = 40.0, log_aT = -1.3 }}]"
    )]
    FreeNeedsList,

    /// Both forms of vertical factors.
    #[error(
        "give the vertical factors either as a table `log_bT = [{{ T = .., log_bT = .. }}, ..]` \
         or as the law vertical = \"density\", not both"
    )]
    VerticalTwoForms,
    /// `expansion` without the density law.
    #[error(
        "`expansion` (the volumetric expansion coefficient, 1/K) belongs to vertical = \
         \"density\"; add it, or remove `expansion`"
    )]
    ExpansionWithoutDensity,

    // ------------------------------------------------------------ [sweep]
    /// `temperature = []`.
    #[error(
        "`temperature = []` lists no temperatures: give at least one (°C), e.g. temperature = \
         [0.0, 20.0, 40.0], or leave the key out"
    )]
    NoTemperatures,
    /// A temperature listed twice.
    #[error(
        "temperature[{index}] = {temperature} repeats temperature[{first}] = {first_temperature}: \
         list each temperature once"
    )]
    RepeatedTemperature {
        index: usize,
        temperature: f64,
        /// The index of the first.
        first: usize,
        first_temperature: f64,
    },
    /// A temperature outside what `rollfit fit` accepts in a data file.
    #[error(
        "{entry} °C {requirement}: a data file's T column is refused there, so `rollfit fit` \
         could not read these rows back"
    )]
    TemperatureOutOfRange {
        /// `temperature = …` or `temperature[i] = …`.
        entry: String,
        /// What the value breaks (the data reader's rule).
        requirement: &'static str,
    },
    /// Both a list and a range of speeds.
    #[error("give either `v = [..]` or `v_min`, `v_max` (and `count`), not both")]
    SpeedsTwice,
    /// `v = []`.
    #[error("`v` is empty: list at least one speed")]
    NoSpeedListed,
    /// A listed speed ≤ 0.
    #[error("v[{index}] = {value}: speeds must be greater than zero")]
    SpeedNotPositive { index: usize, value: f64 },
    /// A speed outside what `rollfit fit` accepts.
    #[error(
        "{key} = {value:e}: speeds must lie between {low:e} and {high:e} m/s (the range of a \
         rolling measurement that `rollfit fit` accepts)"
    )]
    SpeedOutOfRange {
        /// `v_min`, `v_max` or `v[i]`.
        key: String,
        value: f64,
        /// m/s.
        low: f64,
        /// m/s.
        high: f64,
    },
    /// Listed speeds not increasing.
    #[error(
        "v[{index}] = {value} does not exceed v[{}] = {previous}: list the speeds in increasing \
         order",
        index - 1
    )]
    SpeedsNotIncreasing {
        index: usize,
        value: f64,
        previous: f64,
    },
    /// Neither a range nor a list.
    #[error("needs `v_min` and `v_max` (m/s), or a list `v = [..]`")]
    NoSpeeds,
    /// `v_min ≥ v_max`.
    #[error("v_min = {v_min} must be less than v_max = {v_max}")]
    RangeNotIncreasing { v_min: f64, v_max: f64 },
    /// `count < 1`.
    #[error("count = {count}: must be at least 1")]
    CountBelowOne { count: i64 },
    /// `count` beyond the largest sweep.
    #[error("count = {count}: at most {max} speeds")]
    CountTooLarge { count: i64, max: i64 },
    /// More speeds than there are numbers between the ends.
    #[error(
        "count = {count} is too many distinct speeds between v_min = {v_min} and v_max = {v_max}"
    )]
    CountTooDense { count: i64, v_min: f64, v_max: f64 },

    // ------------------------------------------------------------ shared, [fit]
    /// A value that must be positive (`E0`, `v_min`, `E_at.omega`, …).
    #[error("{key} = {value}: must be greater than zero")]
    NotPositive { key: &'static str, value: f64 },
    /// `E1_max` not above `E0`.
    #[error("E1_max = {e1_max} must exceed the known static modulus E0 = {e0}")]
    GlassyBelowStatic { e1_max: f64, e0: f64 },
    /// Several scale anchors.
    #[error(
        "more than one scale anchor ({}): give at most one of E0, E_at and contact_radius",
        anchors.join(", ")
    )]
    SeveralAnchors {
        /// The anchors given, as `` `E0` ``.
        anchors: Vec<&'static str>,
    },
    /// Several scale anchors, found when the fit's parameters are made.
    #[error("give at most one scale anchor (E0, E_at or contact_radius)")]
    AnchorConflict,

    // ------------------------------------------------------------ rungs
    /// `size = "exact"` for a fit.
    #[error(
        "[contact]: size = \"exact\" is a forward-only reference (its μ has no fast gradient); \
         fit with size = \"dynamic\" (the paper's) or \"static\""
    )]
    ExactNotForFit,
    /// `size = "low-speed"` or `"auto"` for a fit.
    #[error(
        "[contact]: size = \"{size}\" is for rollfit forward only (a fit needs one model with a \
         gradient at every speed); fit with size = \"dynamic\" (the paper's) or \"static\""
    )]
    ForwardOnly {
        /// "low-speed" or "auto".
        size: &'static str,
    },
    /// `forward` without `[material]`.
    #[error("forward needs a [material] section (the modulus to predict μ(v) from)")]
    NeedsMaterial,
    /// `forward` without `[sweep]`.
    #[error("forward needs a [sweep] section (v_min, v_max, count or v = [..])")]
    NeedsSweep,
    /// The exact cylinder asked of a sphere scene (the benchmark's
    /// reference is the cylinder's).
    #[error(
        "[contact]: this needs shape = \"cylinder\": the reference is the plane-strain exact \
         rolling cylinder"
    )]
    ExactNeedsCylinder,
    /// The exact solution on a film.
    #[error(
        "[contact]: size = \"exact\" is for a half-space; remove [substrate] thickness (films use \
         size = \"dynamic\" or \"static\")"
    )]
    ExactNeedsHalfSpace,
    /// The exact solution of a material that is no Prony series.
    #[error(
        "[contact]: size = \"exact\" needs [material] model = \"sls\" or \"prony\" (the exact \
         solution works with the creep compliance of a Prony series)"
    )]
    ExactNeedsProny,
}

impl From<SceneError> for IoError {
    fn from(e: SceneError) -> Self {
        match e {
            SceneError::File(inner) => *inner,
            other => IoError::transparent(ErrorKind::Content, other),
        }
    }
}

impl From<IoError> for SceneError {
    fn from(e: IoError) -> Self {
        match e.into_transparent::<SceneError>() {
            Ok(inner) => inner,
            Err(other) => SceneError::File(Box::new(other)),
        }
    }
}

/// The section a parameter checked by `Scene::new` lives in, as a message
/// prefix, so that "radius = -1" reads "[geometry]: radius = -1". The
/// model checks the geometry, the substrate and the material together (the
/// load's check needs the material's E(0)) and owns their ranges, so the
/// sections cannot check themselves without copying them.
fn section_of(error: &ModelError) -> &'static str {
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
fn quoted_or(models: &[&str]) -> String {
    let quoted: Vec<String> = models.iter().map(|m| format!("\"{m}\"")).collect();
    quoted.join(" or ")
}
