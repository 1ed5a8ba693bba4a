//! DMA data: storage and loss moduli measured by dynamic mechanical analysis
//! (or an oscillatory shear rheometer), read from a file and moved to the
//! reference state of a fit, to be compared with the master curve the fit
//! recovered from μ(v).
//!
//! Two file forms (docs/ARCHITECTURE.md, "Contract", "DMA files"):
//! - CSV ([`csv_form`]): a frequency column `f` (Hz) or `omega` (rad/s),
//!   storage and loss columns `E_storage`, `E_loss` (Young's) or
//!   `G_storage`, `G_loss` (shear), optional `T` (°C). Unit-suffixed
//!   spellings such as `omega_rad_s`, `f_Hz`, `G_storage_Pa`,
//!   `E_loss_MPa`, `T_C` or `T_K` are read with their unit.
//! - the TA Instruments TRIOS "LIMS" text export ([`trios`]), which
//!   carries its own units and says (through its variables and instrument)
//!   whether the moduli are shear or tensile.
//!
//! Shear moduli become Young's moduli with the fit's Poisson's ratio ν,
//! frequency-independent as everywhere in rollfit:
//!
//! E*(ω) = 2 (1 + ν) G*(ω),
//!
//! so E′ = 2(1+ν) G′, E″ = 2(1+ν) G″ and tan δ is unchanged.
//!
//! Several temperatures are moved onto the fit's reference temperature by
//! time–temperature superposition ([`shift`]) with the convention of
//! `rollfit_model::modulus::shift`: E*(ω, T) = E*_ref(ω a_T), i.e. a point
//! measured at (ω, T) lies on the master curve at the reduced frequency
//! ω a_T.
//!
//! What is checked when reading: the file is whole and in one encoding
//! (a cut-off or damaged file is refused with its line, see [`csv_form`]
//! and [`trios`]), ω > 0, E′ > 0, every number finite. A
//! point with E″ ≤ 0 is dropped with a warning naming its line and column
//! rather than refusing the whole file: a negative loss modulus is not
//! physical (E″ ≥ 0 for a passive solid), and real exports carry one now
//! and then where the loss angle is below the instrument's phase
//! resolution (the 468MP adhesive's coldest point, glassy, reads
//! E″ = −30 MPa against E′ = 550 MPa); every metric compares logarithms or
//! ratios of E″, which a zero or negative E″ has none of.
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley 1980,
//!   Ch. 1 (E = 2(1+ν)G) and Ch. 11 (reduced variables).
//! - TA Instruments, *TRIOS Software: Export to LIMS*, the "LIMS" text
//!   export format (sections, `Variables`/`Units` lines, `Data point`
//!   rows).

use std::path::{Path, PathBuf};

use crate::error::ReportError;
use crate::fit_dir::FitDir;

pub mod csv_form;
pub mod shift;
pub mod trios;

pub use shift::Shifted;

/// One DMA point. In [`DmaData::points`] as measured; after
/// [`DmaData::at_reference`] `omega` is the reduced frequency ω a_T at the
/// fit's reference state and `temperature` still the measured one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DmaPoint {
    /// Angular frequency, rad/s.
    pub omega: f64,
    /// Young's storage modulus E′, Pa.
    pub storage: f64,
    /// Young's loss modulus E″, Pa.
    pub loss: f64,
    /// Temperature, °C, when the file gives one.
    pub temperature: Option<f64>,
}

impl DmaPoint {
    /// tan δ = E″/E′.
    pub fn tan_delta(&self) -> f64 {
        self.loss / self.storage
    }

    /// |E*| = √(E′² + E″²), Pa.
    pub fn abs_modulus(&self) -> f64 {
        self.storage.hypot(self.loss)
    }
}

/// Which modulus a file held: Young's (tensile, bending, compression DMA)
/// or shear (torsion, parallel plates, shear sandwich).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModulusKind {
    /// E′, E″.
    Young,
    /// G′, G″, converted with E = 2(1+ν)G.
    Shear,
}

impl ModulusKind {
    /// "young" or "shear", as in compare.json and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            ModulusKind::Young => "young",
            ModulusKind::Shear => "shear",
        }
    }
}

/// The DMA's own WLF shift: log10 a_T = −C1 (T − T_ref)/(C2 + T − T_ref),
/// temperatures in °C, C2 in K.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DmaWlf {
    /// °C.
    pub t_ref: f64,
    /// Dimensionless.
    pub c1: f64,
    /// K.
    pub c2: f64,
}

impl DmaWlf {
    /// log10 a_T at `t` (°C), or `None` at and below the divergence
    /// T = T_ref − C2, where the WLF form means nothing.
    pub fn log_shift_at(&self, t: f64) -> Option<f64> {
        let dt = t - self.t_ref;
        (self.c2 + dt > 0.0).then(|| -self.c1 * dt / (self.c2 + dt))
    }
}

/// How to read and shift a DMA file beyond what the file says.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DmaOptions {
    /// Overrides the shear/tensile decision for a TRIOS file (a CSV says
    /// it with its column names, `E_…` or `G_…`).
    pub kind: Option<ModulusKind>,
    /// The DMA's own WLF constants; when given they shift the DMA
    /// temperatures instead of the fit's shift.
    pub wlf: Option<DmaWlf>,
}

/// A DMA file read, its moduli as Young's moduli in Pa.
#[derive(Debug, Clone)]
pub struct DmaData {
    /// The file.
    pub path: PathBuf,
    /// The points in file order, as measured.
    pub points: Vec<DmaPoint>,
    /// The file line (from 1) of each entry of `points`, same order: for
    /// messages about a point.
    pub lines: Vec<usize>,
    /// What the file held (before conversion to Young's).
    pub kind: ModulusKind,
    /// "csv" or "trios-lims".
    pub format: &'static str,
    /// Points dropped, columns or steps skipped, and how the file was
    /// read where that was a decision (shear or tensile, ν).
    pub warnings: Vec<String>,
    /// How the file was read where the file itself said so (a CSV's shear
    /// columns converted with ν): worth knowing, nothing to check.
    pub notes: Vec<String>,
}

/// One point as a reader found it, before the checks common to all forms.
pub(crate) struct RawPoint {
    /// Line in the file, counting from 1.
    pub line: usize,
    /// rad/s.
    pub omega: f64,
    /// Pa, shear or Young's as the file says.
    pub storage: f64,
    /// Pa.
    pub loss: f64,
    /// °C.
    pub temperature: Option<f64>,
}

/// Column (or variable) names of the three moduli fields, for messages.
pub(crate) struct FieldNames {
    pub omega: String,
    pub storage: String,
    pub loss: String,
}

impl DmaData {
    /// Reads a DMA file: TRIOS LIMS when its first line is `[Version]` or
    /// mentions the LIMS export, CSV otherwise (the extension is not
    /// consulted: exports are renamed freely). Shear moduli become Young's
    /// with `poisson` (the fit's ν).
    pub fn read(path: &Path, poisson: f64, options: &DmaOptions) -> Result<DmaData, ReportError> {
        if !(poisson > -1.0 && poisson <= 0.5) {
            // Not the DMA file's fault: say whose number it is.
            return Err(ReportError::Unanswerable(format!(
                "the fit's Poisson's ratio {poisson} is outside (−1, 0.5]: cannot convert the shear moduli of {} to Young's moduli",
                path.display()
            )));
        }
        let bytes = std::fs::read(path).map_err(|e| ReportError::io(path, e))?;
        let text = trios::decode(path, &bytes)?;
        let (raw, kind, names, format, mut warnings) = if trios::is_lims(&text) {
            let file = trios::parse(path, &text, options)?;
            (
                file.points,
                file.kind,
                file.names,
                "trios-lims",
                file.warnings,
            )
        } else {
            let mut file = csv_form::parse(path, &text)?;
            if options.kind.is_some_and(|k| k != file.kind) {
                file.warnings.push(format!(
                    "{}: the CSV's column names say {} moduli; the requested modulus kind applies to TRIOS files only and is ignored",
                    path.display(),
                    file.kind.name()
                ));
            }
            (file.points, file.kind, file.names, "csv", file.warnings)
        };
        let mut notes = Vec::new();
        let factor = match kind {
            ModulusKind::Young => 1.0,
            ModulusKind::Shear => {
                let conversion = format!(
                    "{}: shear moduli G′, G″ converted to Young's with E = 2(1+ν)G, ν = {poisson} (the fit's)",
                    path.display()
                );
                // A TRIOS file's kind was inferred (a warning); a CSV's
                // column names state it (a note).
                if format == "csv" {
                    notes.push(conversion);
                } else {
                    warnings.push(conversion);
                }
                2.0 * (1.0 + poisson)
            }
        };
        let (points, lines) = check_points(path, raw, &names, factor, &mut warnings)?;
        Ok(DmaData {
            path: path.to_path_buf(),
            points,
            lines,
            kind,
            format,
            warnings,
            notes,
        })
    }

    /// The points moved to the fit's reference state (ω·a_T), sorted by
    /// reduced ω. See [`shift`] for which shift is used when.
    pub fn at_reference(
        &self,
        fit: &FitDir,
        options: &DmaOptions,
    ) -> Result<Vec<DmaPoint>, ReportError> {
        Ok(self.shifted(fit, options)?.points)
    }

    /// As [`DmaData::at_reference`], with notes on how the points were
    /// shifted (which shift, extrapolations).
    pub fn shifted(&self, fit: &FitDir, options: &DmaOptions) -> Result<Shifted, ReportError> {
        shift::to_reference(self, fit, options)
    }

    /// The measured temperatures grouped into isotherms (°C, ascending):
    /// points within [`shift::ISOTHERM_TOLERANCE`] of their neighbour
    /// belong to one isotherm, whose temperature is their mean.
    pub fn temperatures(&self) -> Vec<f64> {
        shift::isotherms(&self.points)
            .iter()
            .map(|i| i.temperature)
            .collect()
    }
}

/// Accepted angular frequencies, rad/s.
const OMEGA_RANGE: (f64, f64) = (1e-30, 1e30);

/// The largest accepted modulus, Pa (after a shear modulus is converted).
const MAX_MODULUS: f64 = 1e13;

/// E″/E′ below which a point is dropped as unresolved.
const MIN_TAN_DELTA: f64 = 1e-9;

/// The smallest accepted storage modulus, Pa.
const MIN_STORAGE: f64 = 1e-3;

/// The checks common to all forms: ω > 0, E′ > 0 (errors); E″ ≤ 0 (point
/// dropped with a warning); at least one point left. Multiplies the moduli
/// by `factor` (2(1+ν) for shear). Returns the points kept and their lines.
fn check_points(
    path: &Path,
    raw: Vec<RawPoint>,
    names: &FieldNames,
    factor: f64,
    warnings: &mut Vec<String>,
) -> Result<(Vec<DmaPoint>, Vec<usize>), ReportError> {
    let mut points = Vec::with_capacity(raw.len());
    let mut lines = Vec::with_capacity(raw.len());
    let mut dropped = 0usize;
    for p in raw {
        if p.omega <= 0.0 {
            return Err(ReportError::line(
                path,
                p.line,
                format!("{}: frequency {} is not positive", names.omega, p.omega),
            ));
        }
        if p.storage <= 0.0 {
            return Err(ReportError::line(
                path,
                p.line,
                format!(
                    "{}: storage modulus {} is not positive",
                    names.storage, p.storage
                ),
            ));
        }
        // Far outside any DMA measurement, and beyond what the causality
        // check's τ grid and least squares can represent.
        if !(OMEGA_RANGE.0..=OMEGA_RANGE.1).contains(&p.omega) {
            return Err(ReportError::line(
                path,
                p.line,
                format!(
                    "{}: frequency {:e} rad/s is outside 1e-30 … 1e30 rad/s, beyond any master \
                     curve",
                    names.omega, p.omega
                ),
            ));
        }
        for (name, value) in [(&names.storage, p.storage), (&names.loss, p.loss)] {
            if factor * value > MAX_MODULUS {
                return Err(ReportError::line(
                    path,
                    p.line,
                    format!(
                        "{name}: modulus {value:e} is above 1e13 Pa, stiffer than any solid \
                         (diamond: about 1.2e12 Pa); is the column in Pa?"
                    ),
                ));
            }
        }
        if factor * p.storage < MIN_STORAGE {
            return Err(ReportError::line(
                path,
                p.line,
                format!(
                    "{}: storage modulus {:e} is below 1e-3 Pa, softer than any solid; is the \
                     column in Pa?",
                    names.storage, p.storage
                ),
            ));
        }
        if let Some(t) = p.temperature
            && !(t > -273.15 && t <= 1000.0)
        {
            return Err(ReportError::line(
                path,
                p.line,
                format!("temperature {t} °C is outside (−273.15, 1000] °C"),
            ));
        }
        // No instrument resolves tan δ below about 1e-4; a smaller E″ is
        // noise around zero (and 1/E″ weights overflow near 1e-308).
        if p.loss <= MIN_TAN_DELTA * p.storage {
            dropped += 1;
            warnings.push(format!(
                "{}, line {}: {}: loss modulus {} ≤ 0 or below 1e-9 E′ (not physical; below the instrument's phase resolution?): point dropped",
                path.display(),
                p.line,
                names.loss,
                p.loss
            ));
            continue;
        }
        points.push(DmaPoint {
            omega: p.omega,
            storage: factor * p.storage,
            loss: factor * p.loss,
            temperature: p.temperature,
        });
        lines.push(p.line);
    }
    if points.is_empty() {
        return Err(ReportError::format(
            path,
            if dropped > 0 {
                format!("no usable points: all {dropped} have a loss modulus ≤ 0")
            } else {
                "no data points".to_string()
            },
        ));
    }
    Ok((points, lines))
}
