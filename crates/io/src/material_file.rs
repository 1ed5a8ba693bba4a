//! material.toml, written by `rollfit master`: the `[material]` table of a
//! scene file (docs/ARCHITECTURE.md, "Contract", "Scene file") holding the master
//! curve's Prony series at T_ref and, for several isotherms, its
//! `[material.shift]`, for a scene to copy (or to use the DMA file itself,
//! `model = "dma"`). With `--vertical` the shift carries the measured
//! vertical factors as the table `log_bT = [{ T, log_bT }, ..]`, so that
//! a scene reproduces each isotherm as E*(ω, T) = b_T E*_ref(ω a_T)
//! (`scene/vertical.rs`). Numbers are written with the shortest digits that read
//! back to the same f64, so a scene using the file predicts exactly what
//! the master curve does.

use std::path::Path;

use rollfit_fit::master::relaxation::RelaxationMaster;
use rollfit_fit::master::{MasterCurve, ShiftFactors, ShiftLaw, ValidMasterSettings};
use rollfit_model::{Prony, ViscoelasticModulus};
use serde::Serialize;

use crate::error::IoError;

#[derive(Serialize)]
struct MaterialFile {
    material: Material,
}

#[derive(Serialize)]
struct Material {
    model: &'static str,
    #[serde(rename = "E1")]
    glassy_modulus: f64,
    #[serde(rename = "H")]
    strengths: Vec<f64>,
    tau: Vec<f64>,
    // Last: a table after the values.
    #[serde(skip_serializing_if = "Option::is_none")]
    shift: Option<Shift>,
}

#[derive(Serialize)]
struct Shift {
    model: &'static str,
    #[serde(rename = "T_ref")]
    t_ref: f64,
    #[serde(rename = "C1", skip_serializing_if = "Option::is_none")]
    c1: Option<f64>,
    #[serde(rename = "C2", skip_serializing_if = "Option::is_none")]
    c2: Option<f64>,
    #[serde(rename = "T_g", skip_serializing_if = "Option::is_none")]
    t_junction: Option<f64>,
    #[serde(rename = "E_a", skip_serializing_if = "Option::is_none")]
    activation_energy: Option<f64>,
    #[serde(rename = "log_aT", skip_serializing_if = "Option::is_none")]
    log_shift: Option<Vec<ShiftPoint>>,
    #[serde(rename = "log_bT", skip_serializing_if = "Option::is_none")]
    log_vertical: Option<Vec<VerticalPoint>>,
}

#[derive(Serialize)]
struct ShiftPoint {
    #[serde(rename = "T")]
    temperature: f64,
    #[serde(rename = "log_aT")]
    log_shift: f64,
}

#[derive(Serialize)]
struct VerticalPoint {
    #[serde(rename = "T")]
    temperature: f64,
    #[serde(rename = "log_bT")]
    log_vertical: f64,
}

/// What material.toml is written from: the series at T_ref, its shift
/// and where it came from.
struct Source<'a> {
    path: &'a Path,
    /// "isotherms" or "relaxation isotherms", for the comment.
    isotherms: &'static str,
    /// What else a scene may do with the file, for the comment.
    also: &'static str,
    points: usize,
    shift: &'a ShiftFactors,
    prony: &'a Prony,
    settings: &'a ValidMasterSettings,
    /// The reduced frequencies (rad/s) the determined isotherms cover.
    window: Option<[f64; 2]>,
}

/// The file's text, with a comment header saying where it came from
/// (`path`, the DMA file or the folder of several), of the master curve
/// built with `settings`.
pub fn encode(
    path: &Path,
    master: &MasterCurve,
    settings: &ValidMasterSettings,
) -> Result<Vec<u8>, IoError> {
    encode_source(&Source {
        path,
        isotherms: "isotherms",
        also: " (or use the DMA file itself: [material] model = \"dma\")",
        points: master.points.len(),
        shift: &master.shift,
        prony: &master.fit.prony,
        settings,
        window: master.determined_window,
    })
}

/// The file of a relaxation master curve: the same tables (the series is
/// one object in time and frequency, `rollfit_fit::master::relaxation`).
pub fn encode_relaxation(
    path: &Path,
    master: &RelaxationMaster,
    settings: &ValidMasterSettings,
) -> Result<Vec<u8>, IoError> {
    encode_source(&Source {
        path,
        isotherms: "relaxation isotherms",
        // A scene's `model = "dma"` reads frequency sweeps only.
        also: "",
        points: master.points.len(),
        shift: &master.shift,
        prony: &master.fit.prony,
        settings,
        window: None,
    })
}

/// The comment on what the data determine: every isotherm's shift, or
/// which are placed by the law and the window the others cover.
fn determined_comment(source: &Source<'_>) -> String {
    let shifts = &source.shift.shifts;
    let undetermined: Vec<String> = shifts
        .iter()
        .filter(|s| !s.determined)
        .map(|s| format!("{}", s.temperature))
        .collect();
    if shifts.len() < 2 || undetermined.is_empty() {
        return String::new();
    }
    let window = source.window.map_or(String::new(), |[lo, hi]| {
        format!(
            "; they cover ω a_T = {lo:.3e} … {hi:.3e} rad/s at T_ref, the window the series \
             measures"
        )
    });
    format!(
        "\n# The data determine the shifts of {} of {} isotherms (σ ≤ {} decade){window}.\n# The \
         isotherms at {} °C are placed by the law: the series beyond that window rests on it.",
        shifts.len() - undetermined.len(),
        shifts.len(),
        rollfit_fit::master::pairwise::DETERMINED_SIGMA,
        undetermined.join(", ")
    )
}

fn encode_source(source: &Source<'_>) -> Result<Vec<u8>, IoError> {
    let shift_factors = source.shift;
    let prony = source.prony;
    let settings = source.settings;
    let t_ref = settings.t_ref();
    let shift = (shift_factors.shifts.len() > 1).then(|| {
        let mut shift = Shift {
            model: shift_factors.law.name(),
            t_ref,
            c1: None,
            c2: None,
            t_junction: None,
            activation_energy: None,
            log_shift: None,
            log_vertical: settings.vertical().then(|| {
                shift_factors
                    .shifts
                    .iter()
                    .map(|s| VerticalPoint {
                        temperature: s.temperature,
                        log_vertical: s.log_vertical,
                    })
                    .collect()
            }),
        };
        match shift_factors.law {
            ShiftLaw::Wlf => {
                if let Some(w) = shift_factors.wlf {
                    shift.c1 = Some(w.c1);
                    shift.c2 = Some(w.c2);
                }
            }
            ShiftLaw::Arrhenius => {
                shift.activation_energy = shift_factors.arrhenius.map(|a| a.activation_energy);
            }
            ShiftLaw::WlfArrhenius => {
                if let Some(w) = shift_factors.wlf_arrhenius {
                    shift.c1 = Some(w.c1);
                    shift.c2 = Some(w.c2);
                    shift.t_junction = Some(w.t_junction);
                    shift.activation_energy = Some(w.activation_energy);
                }
            }
            ShiftLaw::Free | ShiftLaw::Auto => {
                shift.log_shift = Some(
                    shift_factors
                        .shifts
                        .iter()
                        .map(|s| ShiftPoint {
                            temperature: s.temperature,
                            log_shift: s.log_shift,
                        })
                        .collect(),
                );
            }
        }
        shift
    });
    let file = MaterialFile {
        material: Material {
            model: "prony",
            glassy_modulus: prony.glassy_modulus(),
            strengths: prony.strengths().to_vec(),
            tau: prony.relaxation_times().to_vec(),
            shift,
        },
    };
    let body = toml::to_string(&file).map_err(|source| {
        err!("cannot format material.toml")
            .caused_by(source)
            .internal()
    })?;
    let mut text = format!(
        "# Written by rollfit master from {} ({} {}, {} points).\n\
         # Young's modulus at T_ref = {t_ref} °C: a Prony series E*(ω) = E0 + Σ H_k iωτ_k/(1 + iωτ_k),\n\
         # E0 = E1 − Σ H_k = {:e} Pa.{}{}\n\
         # Copy these tables into a scene file{}.\n\n",
        source.path.display(),
        shift_factors.shifts.len(),
        source.isotherms,
        source.points,
        prony.static_modulus(),
        if settings.vertical() && shift_factors.shifts.len() > 1 {
            "\n# Away from T_ref, E*(ω, T) = b_T E*(ω a_T) with the measured vertical factors \
             log_bT (log10 b_T,\n# linear in T between isotherms, not extrapolated beyond them)."
        } else {
            ""
        },
        determined_comment(source),
        source.also
    );
    text.push_str(&body);
    Ok(text.into_bytes())
}
