//! `rollfit master DMA... [-o DIR] [--temperatures T1,T2,…] [--T-ref T]
//! [--shift auto|wlf|free|arrhenius|wlf-arrhenius] [--vertical]`: a master curve from DMA isotherms by time–temperature
//! superposition, and the material a scene can use.
//!
//! Writes, to DIR as a whole (nothing on an error):
//! - master.csv: every DMA point at the reference state — omega (ω a_T,
//!   rad/s), E_storage, E_loss (Young's, Pa, divided by b_T), tan_delta, T
//!   (the isotherm, °C), omega_measured (rad/s);
//! - shift.csv: per isotherm T (°C), log_aT (applied), log_aT_measured
//!   (from the overlap, anchored at T_ref; empty where the data do not
//!   determine it), log_bT, points, log_aT_sigma (1σ of the applied value),
//!   log_aT_measured_sigma (1σ of the measured one; empty where
//!   undetermined), determined (true/false);
//! - modulus.csv: the Prony series at T_ref over the data's reduced range,
//!   the columns of a fit's modulus.csv (omega, E_storage, E_loss,
//!   tan_delta), so that `table` scenes and plots read it alike;
//! - material.toml: `[material]` with model = "prony" and, with more than
//!   one isotherm, `[material.shift]`, for a scene to copy or include;
//! - master.json: the numbers (the law chosen and why, every law tried
//!   with its constants, standard errors and χ² test, the pairwise shifts
//!   with their errors, λ, misfits and the Kramers–Kronig floor, warnings);
//! - master.png and master.svg: the shifted isotherms with the series,
//!   tan δ and the shift factors with the law and its constants, the
//!   verdict in the title when it is not "good"; shear data drawn as G′, G″;
//! - vgp.png and vgp.svg: the van Gurp–Palmen plot, phase angle δ against
//!   |E*| of every isotherm as measured (no shift), where the isotherms of
//!   a thermorheologically simple material fall on one curve.
//!
//! A master curve whose verdict (`rollfit_fit::master::quality`: data no
//! causal series can follow, a series that misses them, no shift the data
//! determine) is poor writes nothing and fails, unless `--allow-poor-fit`,
//! as `fit` does with a poor fit. A curve with some undetermined shifts
//! is written, those isotherms marked and the frequency window the
//! determined ones cover stated; `--strict` refuses it instead.

use std::path::PathBuf;

use anyhow::{Context, Result};
use rollfit_fit::causality::{self, CausalFit, ModulusSample};
use rollfit_fit::master::pairwise::DETERMINED_SIGMA;
use rollfit_fit::master::quality::{Floors, MasterQuality, Misfits};
use rollfit_fit::master::{MasterSettings, ShiftFactors, ShiftLaw};
use rollfit_io::columns::OMEGA_MEASURED;
use rollfit_io::fit_dir::columns::{
    E_LOSS, E_STORAGE, MODULUS_COLUMNS, MODULUS_CSV, OMEGA, T, TAN_DELTA,
};
use rollfit_io::{csv_text, output};
use rollfit_model::ViscoelasticModulus;
use rollfit_report::master_input::frequency::{self, DmaMaster};
use serde::Serialize;

use crate::commands::compare::{
    DmaFileFlags, DmaModulus, is_relaxation_data, poisson_source, temperature_sources,
};
use crate::{hints, progress, stdout};

mod pictures;
mod relaxation;
mod shift_out;

use shift_out::{ShiftJson, VgpJson, shift_csv, shift_text};

/// Arguments of `rollfit master`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// DMA file: CSV (f or omega; E_storage, E_loss or G_storage, G_loss; T),
    /// a TRIOS LIMS export or a workbook (Eplexor export), several isotherms;
    /// or several files (one isotherm each), or a folder of them.
    #[arg(required = true, num_args = 1..)]
    pub dma: Vec<PathBuf>,
    #[command(flatten)]
    pub files: DmaFileFlags,
    /// The sheet of a workbook DMA file to read (default: the first).
    #[arg(long, value_name = "NAME")]
    pub sheet: Option<String>,
    /// Output folder (replaced as a whole).
    #[arg(short, long, value_name = "DIR", default_value = "master")]
    pub output: PathBuf,
    /// Reference temperature, °C (default 20 °C when inside the measured
    /// temperatures, else the nearest measured one).
    #[arg(long = "T-ref", value_name = "T", allow_hyphen_values = true)]
    pub t_ref: Option<f64>,
    /// The law of the shift factor a_T: chosen by the data (auto: WLF,
    /// else WLF above T_g with Arrhenius below or Arrhenius, else the
    /// measured shifts), WLF, the measured shifts themselves (linear in T
    /// between isotherms), Arrhenius, or WLF–Arrhenius.
    #[arg(long, value_enum, default_value = "auto")]
    pub shift: ShiftChoice,
    /// Also find vertical shift factors b_T from the data (E′ offsets at
    /// the overlap; material.toml then carries them as `log_bT`); off by
    /// default, as in most TTS practice.
    #[arg(long)]
    pub vertical: bool,
    /// Poisson's ratio converting shear moduli to Young's, E = 2(1+ν)G:
    /// 0 to 0.5, as a scene's [substrate] poisson. Default 0.5.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_poisson)]
    pub poisson: Option<f64>,
    /// Read a TRIOS file's moduli as Young's or shear (default: decided
    /// from the file).
    #[arg(long = "dma-modulus", value_enum, value_name = "KIND")]
    pub dma_modulus: Option<DmaModulus>,
    /// Write the master curve even when its verdict is poor (data no
    /// causal series can follow, or shifts the data do not determine);
    /// master.json's "quality" then says "poor", with the reasons.
    #[arg(long)]
    pub allow_poor_fit: bool,
    /// Replace an output folder another command wrote (`rollfit fit`,
    /// `rollfit batch`); files rollfit did not write there stay.
    #[arg(long)]
    pub force: bool,
    /// Refuse (write nothing, exit non-zero) when any isotherm's shift is
    /// not determined by the data (σ about T_ref above 0.3 decade), for a
    /// pipeline that must not use a curve placed partly by a law.
    #[arg(long)]
    pub strict: bool,
}

/// `--poisson`: a number in the one range of Poisson's ratio
/// (`rollfit_model::POISSON_RANGE`), refused with the model's words.
fn parse_poisson(text: &str) -> Result<f64, String> {
    let value: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("{text:?} is not a number"))?;
    rollfit_model::check_poisson(value).map_err(|e| e.to_string())
}

/// `--shift`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ShiftChoice {
    /// Chosen by the data.
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

impl ShiftChoice {
    fn law(self) -> ShiftLaw {
        match self {
            ShiftChoice::Auto => ShiftLaw::Auto,
            ShiftChoice::Wlf => ShiftLaw::Wlf,
            ShiftChoice::Free => ShiftLaw::Free,
            ShiftChoice::Arrhenius => ShiftLaw::Arrhenius,
            ShiftChoice::WlfArrhenius => ShiftLaw::WlfArrhenius,
        }
    }
}

/// Frequencies of modulus.csv per decade of the data's reduced range.
const CURVE_PER_DECADE: f64 = 20.0;

/// Runs `rollfit master`.
pub fn run(args: &Args) -> Result<()> {
    output::check_replaceable(&args.output, output::Writer::Master, args.force)?;
    let settings = MasterSettings {
        t_ref: args.t_ref,
        law: args.shift.law(),
        vertical: args.vertical,
    };
    let first = &args.dma[0];
    if is_relaxation_data(&args.dma)? {
        return relaxation::run(args, &settings);
    }
    let (poisson, whose) = poisson_source(args.poisson);
    let spinner = progress::spinner(format!("master curve of {}", dma_name(args)));
    let input = args
        .files
        .input(&args.dma, args.sheet.as_deref(), args.dma_modulus);
    // The file's notes and warnings come before the master curve's
    // verdict, so that a refusal is read next to the rows that explain it
    // (rows skipped for a temperature in a merged cell).
    let on_read = |data: &rollfit_io::dma::DmaData| {
        spinner.suspend(|| {
            for note in &data.notes {
                eprintln!("note: {}", note.replace("(the fit's)", whose));
            }
            for warning in &data.warnings {
                eprintln!("warning: {}", warning.replace("(the fit's)", whose));
            }
        });
    };
    let built = frequency::build_told(&input, poisson, &settings, on_read).map_err(Into::into);
    let hint = || hints::for_dma(first, "rollfit master DMA.csv");
    let built = hints::with_hint(built, hint);
    let causal = built.as_ref().ok().map(causal_floor);
    spinner.finish_and_clear();
    let built = built?;
    let shift = &built.master.shift;
    if shift.shifts.len() > 1 {
        eprintln!("note: shift law {}: {}", shift.law.name(), shift.reason);
    } else {
        eprintln!("note: {}", shift.reason);
    }
    for warning in &built.master.warnings {
        eprintln!("warning: {}", warning.replace("(the fit's)", whose));
    }
    let causal = causal.context("no causal fit")??;
    for warning in &causal.warnings {
        eprintln!("warning: {warning}");
    }
    let all = Misfits {
        storage: causal.misfit_storage,
        loss: causal.misfit_loss,
    };
    let determined = match determined_floor(&built) {
        Some(part) => {
            let part = part?;
            eprintln!(
                "note: whether the data are causal is judged on the isotherms whose shifts are \
                 determined: Kramers–Kronig floor there E′ {:.4}, E″ {:.4} decades (of every \
                 point {:.4}, {:.4})",
                part.misfit_storage, part.misfit_loss, all.storage, all.loss
            );
            Misfits {
                storage: part.misfit_storage,
                loss: part.misfit_loss,
            }
        }
        None => all,
    };
    let quality = built.master.quality(Floors { all, determined });
    gate(&quality, args)?;
    strict_gate(&built.master.shift, args)?;
    let files = encode(&built, &causal, poisson, &quality)?;
    let named: Vec<(&str, &[u8])> = files.iter().map(|(n, b)| (*n, b.as_slice())).collect();
    output::replace_folder(&args.output, output::Writer::Master, args.force, &named)?;
    stdout::write_stdout(summary(&built, &causal).as_bytes())?;
    eprintln!("wrote {}", args.output.display());
    Ok(())
}

/// An isotherm's spread (K, max − min) above which the summary names it:
/// a controller holds ±0.1 K, so more is worth a look.
const WIDE_ISOTHERM: f64 = 0.5;

/// How the points were grouped: "9 isotherms: −20.0 … 60.0 °C (each within
/// ±0.1 K)", naming the isotherms that spread over [`WIDE_ISOTHERM`];
/// nothing for a file without temperatures.
fn isotherms_line(ranges: &[(f64, f64)]) -> String {
    let (Some(first), Some(last)) = (ranges.first(), ranges.last()) else {
        return String::new();
    };
    let mean = |r: &(f64, f64)| 0.5 * (r.0 + r.1);
    let half = ranges.iter().map(|r| 0.5 * (r.1 - r.0)).fold(0.0, f64::max);
    let count = match ranges.len() {
        1 => "1 isotherm".to_string(),
        n => format!("{n} isotherms"),
    };
    let mut line = format!(
        "{count}: {:.1} … {:.1} °C (each within ±{half:.1} K)",
        mean(first),
        mean(last)
    );
    let wide: Vec<String> = ranges
        .iter()
        .filter(|r| r.1 - r.0 > WIDE_ISOTHERM)
        .map(|r| format!("{:.1} … {:.1} °C", r.0, r.1))
        .collect();
    if !wide.is_empty() {
        line += &format!("; spread over {WIDE_ISOTHERM} K: {}", wide.join(", "));
    }
    line + "\n"
}

/// Refuses a poor master curve unless `--allow-poor-fit` (then says it is
/// kept); before anything is encoded or written, so DIR stays as it was.
fn gate(quality: &MasterQuality, args: &Args) -> Result<()> {
    if quality.is_good() {
        return Ok(());
    }
    if args.allow_poor_fit {
        eprintln!(
            "warning: the master curve is poor: {}; written because of --allow-poor-fit \
             (master.json's \"quality\")",
            quality.reasons.join("; ")
        );
        return Ok(());
    }
    anyhow::bail!(
        "DMA file {}: the master curve is poor: {}; nothing was written to {} (give \
         --allow-poor-fit to write it, marked \"quality\": {{\"verdict\": \"poor\"}} in \
         master.json)",
        dma_name(args),
        quality.reasons.join("; "),
        args.output.display()
    )
}

/// Under `--strict`, refuses a curve with any undetermined shift, naming
/// the isotherms; before anything is written.
pub(super) fn strict_gate(shift: &ShiftFactors, args: &Args) -> Result<()> {
    let undetermined: Vec<String> = shift
        .shifts
        .iter()
        .filter(|s| !s.determined)
        .map(|s| shift_out::celsius(s.temperature))
        .collect();
    if !args.strict || undetermined.is_empty() {
        return Ok(());
    }
    anyhow::bail!(
        "DMA file {}: --strict: the shifts of the isotherms at {} °C are not determined by the \
         data (σ about T_ref above {DETERMINED_SIGMA} decade); nothing was written to {} (without \
         --strict the curve is written with those isotherms marked)",
        dma_name(args),
        undetermined.join(", "),
        args.output.display()
    )
}

/// The DMA files as messages name them: the one file, or every one.
fn dma_name(args: &Args) -> String {
    rollfit_io::dma::files::names(&args.dma)
}

/// The best causal fit of the shifted points (the causality check of
/// `compare`): the floor the smooth Prony series' misfit is measured
/// against.
fn causal_floor(built: &DmaMaster) -> Result<CausalFit> {
    causal_floor_of(built, |_| true)
}

/// The best causal fit of the determined isotherms' shifted points, where
/// some isotherms are undetermined and some determined (None otherwise):
/// only these can show that the data themselves are not causal.
fn determined_floor(built: &DmaMaster) -> Option<Result<CausalFit>> {
    let shifts = &built.master.shift.shifts;
    let determined = shifts.iter().filter(|s| s.determined).count();
    if determined == 0 || determined == shifts.len() {
        return None;
    }
    // A point's isotherm is the shift of the nearest temperature.
    let isotherm_determined = |t: f64| {
        shifts
            .iter()
            .min_by(|a, b| {
                (a.temperature - t)
                    .abs()
                    .total_cmp(&(b.temperature - t).abs())
            })
            .is_some_and(|s| s.determined)
    };
    Some(causal_floor_of(built, isotherm_determined))
}

/// The best causal fit of the shifted points whose isotherm temperature
/// `keep` accepts.
fn causal_floor_of(built: &DmaMaster, keep: impl Fn(f64) -> bool) -> Result<CausalFit> {
    let has_temperatures = built.data.points.iter().any(|p| p.temperature.is_some());
    let shifted: Vec<ModulusSample> = built
        .master
        .points
        .iter()
        .filter(|p| keep(p.temperature))
        .map(|p| ModulusSample {
            omega: p.reduced_omega,
            storage: p.storage,
            loss: p.loss,
            temperature: has_temperatures.then_some(p.temperature),
        })
        .collect();
    causality::check(&shifted)
        .map_err(|e| anyhow::anyhow!("DMA file {}: {e}", built.data.path.display()))
}

/// Every file of DIR, encoded.
fn encode(
    built: &DmaMaster,
    causal: &CausalFit,
    poisson: f64,
    quality: &MasterQuality,
) -> Result<Vec<(&'static str, Vec<u8>)>> {
    let master = &built.master;
    let master_csv = csv_text::csv_bytes(
        &[OMEGA, E_STORAGE, E_LOSS, TAN_DELTA, T, OMEGA_MEASURED],
        master.points.iter().map(|p| {
            vec![
                p.reduced_omega,
                p.storage,
                p.loss,
                p.loss / p.storage,
                p.temperature,
                p.omega,
            ]
        }),
    )?;
    let shift_csv = shift_csv(&master.shift)?;
    let curve = prony_curve(built);
    let modulus_csv = csv_text::csv_bytes(
        // The first columns of a fit's modulus.csv, which the contract fixes.
        &MODULUS_COLUMNS[..4],
        curve.iter().map(|&(w, s, l)| vec![w, s, l, l / s]),
    )?;
    let material = built.material_file()?;
    let mut json = serde_json::to_vec_pretty(&Summary::of(built, causal, poisson, quality))
        .context("cannot format master.json")?;
    json.push(b'\n');
    let pictures = pictures::frequency(built, &curve, poisson, quality)?;
    Ok(vec![
        ("master.csv", master_csv),
        ("shift.csv", shift_csv),
        (MODULUS_CSV, modulus_csv),
        ("material.toml", material),
        ("master.json", json),
    ]
    .into_iter()
    .chain(pictures)
    .collect())
}

/// (ω, E′, E″) of the Prony series over the data's reduced range.
fn prony_curve(built: &DmaMaster) -> Vec<(f64, f64, f64)> {
    let points = &built.master.points;
    let (lo, hi) = (
        points[0].reduced_omega,
        points[points.len() - 1].reduced_omega,
    );
    let decades = (hi / lo).log10().max(0.0);
    let count = ((decades * CURVE_PER_DECADE).ceil() as usize).max(2);
    (0..=count)
        .map(|j| {
            let w = lo * (hi / lo).powf(j as f64 / count as f64);
            let e = built.master.fit.prony.modulus(w);
            (w, e.re, e.im)
        })
        .collect()
}

/// master.json.
#[derive(Serialize)]
struct Summary {
    dma_file: String,
    dma_format: &'static str,
    modulus_kind: &'static str,
    poisson: f64,
    #[serde(rename = "T_ref")]
    t_ref: f64,
    /// The law applied.
    shift_law: &'static str,
    /// The law asked for ("auto" by default).
    shift_law_asked: &'static str,
    /// Why the law applied was chosen, with the tests' numbers.
    shift_law_reason: String,
    vertical: bool,
    isotherms: usize,
    /// The lowest and highest measured temperature of each isotherm, °C.
    #[serde(rename = "isotherm_T_ranges")]
    isotherm_ranges: Vec<[f64; 2]>,
    points: usize,
    omega_range: [f64; 2],
    #[serde(flatten)]
    shift: ShiftJson,
    /// The reduced frequencies (rad/s) the isotherms with determined
    /// shifts cover; null where none.
    determined_omega_range: Option<[f64; 2]>,
    /// The van Gurp–Palmen test of the unshifted isotherms.
    van_gurp_palmen: VgpJson,
    prony: PronySummary,
    kramers_kronig: KkSummary,
    /// The gate's verdict ("good", or "poor" with reasons).
    quality: MasterQuality,
    warnings: Vec<String>,
    notes: Vec<String>,
}

#[derive(Serialize)]
struct PronySummary {
    terms: usize,
    #[serde(rename = "E0")]
    static_modulus: f64,
    #[serde(rename = "E1")]
    glassy_modulus: f64,
    lambda: f64,
    misfit_storage: f64,
    misfit_loss: f64,
    converged: bool,
}

#[derive(Serialize)]
struct KkSummary {
    misfit_storage: f64,
    misfit_loss: f64,
    max_storage: f64,
    max_loss: f64,
    /// Prony misfit over the floor, per component.
    ratio_storage: f64,
    ratio_loss: f64,
}

impl Summary {
    fn of(built: &DmaMaster, kk: &CausalFit, poisson: f64, quality: &MasterQuality) -> Summary {
        let m = &built.master;
        let fit = &m.fit;
        Summary {
            dma_file: built.data.path.display().to_string(),
            dma_format: built.data.format,
            modulus_kind: built.data.kind.name(),
            poisson,
            t_ref: built.settings.t_ref(),
            shift_law: m.shift.law.name(),
            shift_law_asked: built.settings.law().name(),
            shift_law_reason: m.shift.reason.clone(),
            vertical: built.settings.vertical(),
            isotherms: m.shift.shifts.len(),
            isotherm_ranges: built.ranges.iter().map(|r| [r.0, r.1]).collect(),
            points: m.points.len(),
            omega_range: [
                m.points[0].reduced_omega,
                m.points[m.points.len() - 1].reduced_omega,
            ],
            shift: ShiftJson::of(&m.shift),
            determined_omega_range: m.determined_window,
            van_gurp_palmen: VgpJson::of(&m.van_gurp_palmen),
            prony: PronySummary {
                terms: fit.prony.relaxation_times().len(),
                static_modulus: fit.prony.static_modulus(),
                glassy_modulus: fit.prony.glassy_modulus(),
                lambda: fit.lambda,
                misfit_storage: fit.misfit_storage,
                misfit_loss: fit.misfit_loss,
                converged: fit.converged,
            },
            kramers_kronig: KkSummary {
                misfit_storage: kk.misfit_storage,
                misfit_loss: kk.misfit_loss,
                max_storage: kk.max_misfit_storage.0,
                max_loss: kk.max_misfit_loss.0,
                ratio_storage: fit.misfit_storage / kk.misfit_storage,
                ratio_loss: fit.misfit_loss / kk.misfit_loss,
            },
            quality: quality.clone(),
            warnings: built
                .data
                .warnings
                .iter()
                .chain(&m.warnings)
                .chain(&kk.warnings)
                .cloned()
                .collect(),
            notes: built.data.notes.clone(),
        }
    }
}

/// The readable summary of stdout.
fn summary(built: &DmaMaster, causal: &CausalFit) -> String {
    let m = &built.master;
    let mut out = format!(
        "DMA {} ({}, {} moduli): {}\n",
        built.data.path.display(),
        built.data.format,
        built.data.kind.name(),
        shift_out::headline(&m.shift, m.points.len(), &built.settings, "")
    );
    out += &isotherms_line(&built.ranges);
    out += &temperature_sources(&built.data.files);
    for merged in &built.merged {
        out += &format!("  {merged}\n");
    }
    out += &shift_text(&m.shift);
    out += &shift_out::window_text(&m.shift, m.determined_window, "ω a_T", "rad/s");
    out += &shift_out::vgp_text(&m.van_gurp_palmen);
    let fit = &m.fit;
    out += &format!(
        "Prony series: {} terms, λ = {:.3e}; RMS misfit E′ {:.4}, E″ {:.4} decades; \
         Kramers–Kronig floor of the shifted data E′ {:.4}, E″ {:.4} decades\n",
        fit.prony.relaxation_times().len(),
        fit.lambda,
        fit.misfit_storage,
        fit.misfit_loss,
        causal.misfit_storage,
        causal.misfit_loss
    );
    out
}
