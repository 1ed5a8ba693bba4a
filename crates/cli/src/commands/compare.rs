//! `rollfit compare DIR DMA`: the master curve recovered by `rollfit fit`
//! against DMA data (docs/ARCHITECTURE.md, "Contract").
//!
//! Reads DIR (fit.json, mu.csv, modulus.csv) and the DMA file (CSV or a
//! TRIOS LIMS export), moves the DMA points to the fit's reference state
//! (the fit's shift, or the DMA's own WLF with `--dma-wlf`), and prints the
//! errors of tan δ, |E*|, E′ and E″ over the overlap of the fit's window
//! and the DMA frequencies, plus the causality check of the DMA data, as a
//! table on stdout; warnings go to stderr. The same numbers are written to
//! DIR/compare.json (atomically). On any error nothing is written.

use std::path::PathBuf;

use anyhow::{Context, Result};
use rollfit_fit::master::relaxation::TimeQuantity;
use rollfit_io::FitDir;
use rollfit_io::dma::time_files::read_time_files;
use rollfit_io::dma::{
    DmaFile, DmaInput, DmaOptions, DmaWlf, ModulusKind, TemperatureOrigin, WLF_USAGE,
};
use rollfit_io::output;
use rollfit_report::compare::{Comparison, compare};
use rollfit_report::relaxation_compare::compare_relaxation;

use crate::{hints, stdout};

/// Arguments of `rollfit compare`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Fit result folder (as written by `rollfit fit`).
    pub dir: PathBuf,
    /// DMA file: CSV (omega or f; E_storage, E_loss or G_storage, G_loss;
    /// optional T), a TA Instruments TRIOS LIMS text export, or a workbook
    /// (.xlsx, .xls, .ods; the same columns, or an Eplexor export's); or
    /// several files (one isotherm each), or a folder of them.
    #[arg(required = true, num_args = 1..)]
    pub dma: Vec<PathBuf>,
    #[command(flatten)]
    pub flags: DmaFlags,
}

/// How a TRIOS file's moduli are to be read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum DmaModulus {
    /// Young's (tensile, bending, compression) moduli E′, E″.
    Young,
    /// Shear moduli G′, G″, converted with E = 2(1+ν)G.
    Shear,
}

impl DmaModulus {
    /// The DMA reader's word for it.
    pub fn kind(self) -> ModulusKind {
        match self {
            DmaModulus::Young => ModulusKind::Young,
            DmaModulus::Shear => ModulusKind::Shear,
        }
    }
}

/// The DMA flags shared by `rollfit compare` and `rollfit report --dma`.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct DmaFlags {
    /// Read a TRIOS file's Storage/Loss modulus as Young's or shear moduli
    /// (default: decided from the file's torque or force variables and
    /// instrument type). A CSV says it with its column names.
    #[arg(long = "dma-modulus", value_enum, value_name = "KIND")]
    pub dma_modulus: Option<DmaModulus>,
    /// The DMA's own WLF shift, T_REF (°C), C1, C2 (K): moves its
    /// temperatures to the fit's reference instead of the fit's shift.
    /// Needed for DMA data at several temperatures when the fit is not a
    /// temperature set.
    #[arg(
        long = "dma-wlf",
        value_name = "T_REF,C1,C2",
        value_parser = parse_wlf,
        allow_hyphen_values = true
    )]
    pub dma_wlf: Option<DmaWlf>,
    /// The sheet of a workbook DMA file to read (default: the first).
    #[arg(long, value_name = "NAME")]
    pub sheet: Option<String>,
    #[command(flatten)]
    pub files: DmaFileFlags,
}

/// What the command line says about DMA files that do not say it
/// themselves: shared by every command that reads DMA frequency data.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct DmaFileFlags {
    /// The temperature of each DMA file, °C, in the order of the files
    /// (a folder's: by name), for files that state none (in a T column, a
    /// line above the header or the file name).
    #[arg(
        long,
        value_name = "T1,T2,…",
        value_delimiter = ',',
        allow_hyphen_values = true
    )]
    pub temperatures: Option<Vec<f64>>,
    /// The unit of moduli a DMA file gives without one: Pa, kPa, MPa or
    /// GPa (default Pa, said in a note).
    #[arg(long, value_name = "UNIT", value_parser = parse_modulus_unit)]
    pub units: Option<(&'static str, f64)>,
}

impl DmaFileFlags {
    /// The DMA input of `files` (files or folders) read with these flags.
    pub fn input(
        &self,
        files: &[PathBuf],
        sheet: Option<&str>,
        kind: Option<DmaModulus>,
    ) -> DmaInput {
        DmaInput {
            files: files.to_vec(),
            sheet: sheet.map(str::to_string),
            kind: kind.map(DmaModulus::kind),
            temperatures: self.temperatures.clone(),
            modulus_unit: self.units,
        }
    }
}

/// `--units`: a modulus unit of the DMA readers' one table.
pub fn parse_modulus_unit(text: &str) -> Result<(&'static str, f64), String> {
    rollfit_io::dma::modulus_unit(text)
        .ok_or_else(|| format!("{text:?} is not a unit of modulus (Pa, kPa, MPa, GPa, N/mm²)"))
}

/// ν of `rollfit master` (`--poisson`, else 0.5) and whose it is, in the
/// words the DMA reader's "(the fit's)" is replaced by: no fit is involved.
pub fn poisson_source(given: Option<f64>) -> (f64, &'static str) {
    match given {
        Some(nu) => (nu, "(--poisson)"),
        None => (0.5, "(the default; --poisson sets another)"),
    }
}

impl DmaFlags {
    /// The options of the DMA reader and of the comparison.
    pub fn options(&self) -> DmaOptions {
        DmaOptions {
            kind: self.dma_modulus.map(DmaModulus::kind),
            wlf: self.dma_wlf,
            modulus_unit: self.files.units,
        }
    }
}

/// Parses `T_REF,C1,C2`.
fn parse_wlf(text: &str) -> Result<DmaWlf, String> {
    let usage = WLF_USAGE;
    let values: Vec<f64> = text
        .split(',')
        .map(|v| v.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| format!("\"{text}\": {usage}"))?;
    let [t_ref, c1, c2] = values[..] else {
        return Err(format!("\"{text}\" has {} numbers: {usage}", values.len()));
    };
    DmaWlf::new(t_ref, c1, c2).map_err(|problem| format!("\"{text}\": {problem}"))
}

/// Reads the fit and the DMA files (or folders) `dma` and compares them
/// (no output written).
pub fn comparison(dir: &std::path::Path, dma: &[PathBuf], flags: &DmaFlags) -> Result<Comparison> {
    const USAGE: &str = "rollfit compare DIR DMA.csv (DIR the folder `rollfit fit` wrote)";
    let first = &dma[0];
    let fit = FitDir::read(dir).context("cannot read the fit");
    let fit = hints::with_hint(fit, || hints::for_fit_folder(dir, Some(first), USAGE))?;
    let options = flags.options();
    let input = flags
        .files
        .input(dma, flags.sheet.as_deref(), flags.dma_modulus);
    let data = input
        .read(fit.summary.poisson, options.wlf)
        .context("cannot read the DMA file");
    let data = hints::with_hint(data, || hints::for_dma(first, USAGE))?;
    compare(&fit, &data, &options).context("cannot compare the fit with the DMA data")
}

/// Whether the DMA input `dma` (files or folders) holds relaxation or
/// creep data: whether its first file does (`rollfit master` reads
/// several such files as one data set).
pub fn is_relaxation_data(dma: &[PathBuf]) -> Result<bool> {
    let files = rollfit_io::dma::files::expand(dma)?;
    Ok(files
        .first()
        .is_some_and(|first| rollfit_io::dma::relaxation::is_relaxation_file(first)))
}

/// Where each file's temperature came from, one line per file, when the
/// data are several files or one whose temperature is not a T column.
pub(crate) fn temperature_sources(files: &[DmaFile]) -> String {
    let stated = |f: &DmaFile| f.temperature != TemperatureOrigin::Column;
    if files.len() < 2 && !files.iter().any(stated) {
        return String::new();
    }
    let mut out = String::new();
    for f in files {
        let origin = match &f.temperature {
            TemperatureOrigin::Given(t) => format!("{t} °C, from --temperatures"),
            other => other.to_string(),
        };
        out += &format!(
            "  {}: {} points, {origin}\n",
            f.path.display(),
            f.points.len()
        );
    }
    out
}

/// Runs the command.
pub fn run(args: &Args) -> Result<()> {
    if is_relaxation_data(&args.dma)? {
        return run_relaxation(args);
    }
    let result = comparison(&args.dir, &args.dma, &args.flags)?;
    let mut json = serde_json::to_vec_pretty(&result).context("cannot format compare.json")?;
    json.push(b'\n');
    let target = args.dir.join("compare.json");
    output::add_files(&args.dir, output::Writer::Fit, &[("compare.json", &json)])?;
    for note in &result.notes {
        eprintln!("note: {note}");
    }
    for warning in &result.warnings {
        eprintln!("warning: {warning}");
    }
    stdout::write_stdout(table(&result).as_bytes())?;
    eprintln!("wrote {}", target.display());
    Ok(())
}

/// The readable table of stdout: one line per compare.json key.
pub fn table(c: &Comparison) -> String {
    let mut out = format!(
        "DMA {} ({}, {} moduli{}), {} points at the fit's reference state, ω = {:.3e} … {:.3e} rad/s\n",
        c.dma_file,
        c.dma_format,
        c.modulus_kind,
        if c.modulus_kind == "shear" {
            format!(" → Young's with ν = {}", c.poisson)
        } else {
            String::new()
        },
        c.dma_points,
        c.dma_omega_range[0],
        c.dma_omega_range[1],
    );
    out.push_str(&format!(
        "fit window {:.3e} … {:.3e} rad/s; overlap: {} points{}\n\n",
        c.fit_window[0],
        c.fit_window[1],
        c.n_points,
        match (c.omega_min, c.omega_max) {
            (Some(lo), Some(hi)) => format!(", ω = {lo:.3e} … {hi:.3e} rad/s"),
            _ => " (no metric)".to_string(),
        }
    ));
    out.push_str(&format!(
        "{:<24} {:>10}  {}\n",
        "metric", "value", "meaning"
    ));
    for row in c.metric_rows() {
        out.push_str(&format!(
            "{:<24} {:>10}  {}\n",
            row.key,
            row.value_text(),
            row.meaning_text()
        ));
    }
    out
}

/// `rollfit compare DIR RELAXATION.csv` (or a creep file): the fit's
/// series as E(t), or as its exact creep compliance D(t), against the
/// measured values (`rollfit_report::relaxation_compare`, whose module doc
/// says why in the time domain). compare.json gets the relaxation keys
/// (`E_relax_rms_rel`, `E_relax_max_rel`, `log10_E_relax_rms`, …) or the
/// creep keys (`D_creep_rms_rel`, …).
fn run_relaxation(args: &Args) -> Result<()> {
    let fit = FitDir::read(&args.dir).context("cannot read the fit")?;
    let kind = args.flags.dma_modulus.map(DmaModulus::kind);
    // Several files (or a folder) are one data set, each file's
    // temperature from its T column, its name or --temperatures, as
    // `rollfit master` reads them.
    let temperatures = args.flags.files.temperatures.as_deref();
    let read = read_time_files(&args.dma, fit.summary.poisson, kind, temperatures)
        .context("cannot read the relaxation file")?;
    let data = read.data;
    let c = compare_relaxation(&fit, &data, &args.flags.options())
        .context("cannot compare the fit with the relaxation data")?;
    let mut json = serde_json::to_vec_pretty(&c).context("cannot format compare.json")?;
    json.push(b'\n');
    let target = args.dir.join("compare.json");
    output::add_files(&args.dir, output::Writer::Fit, &[("compare.json", &json)])?;
    for note in &c.notes {
        eprintln!("note: {note}");
    }
    // Where each file's temperature came from, as `rollfit master` says,
    // where there are several or one took it from its name or the flag
    // (one file without a temperature is at the fit's reference state).
    let told = |f: &DmaFile| {
        !matches!(
            f.temperature,
            TemperatureOrigin::None | TemperatureOrigin::Column
        )
    };
    if read.files.len() > 1 || read.files.iter().any(told) {
        for line in temperature_sources(&read.files).lines() {
            eprintln!("note: {}", line.trim_start());
        }
    }
    for warning in &c.warnings {
        eprintln!("warning: {warning}");
    }
    let value = |x: Option<f64>| x.map_or("—".to_string(), |x| format!("{x:.4}"));
    let (rms_rel, max_rel, log10_rms) = c.metrics.values();
    let creep = data.quantity == TimeQuantity::Creep;
    let (title, values, symbol, key) = if creep {
        ("Creep", "compliances", "D(t)", "D_creep")
    } else {
        ("Relaxation", "moduli", "E(t)", "E_relax")
    };
    let series = if creep {
        "the fit's series' exact creep compliance"
    } else {
        "the fit's series as E(t)"
    };
    let table = format!(
        "{title} {} ({} {values}), {} points at the fit's reference state, t = {:.3e} … {:.3e} s\n\
         fit window as times {:.3e} … {:.3e} s; overlap: {} points\n\n\
         {:<19} {:>10}  RMS relative error of {symbol} ({series})\n\
         {:<19} {:>10}  largest |relative error| of {symbol}\n\
         {:<19} {:>10}  RMS log10 error of {symbol}, decades\n",
        c.dma_file,
        c.modulus_kind,
        c.dma_points,
        c.dma_time_range[0],
        c.dma_time_range[1],
        c.fit_window_time[0],
        c.fit_window_time[1],
        c.n_points,
        format!("{key}_rms_rel"),
        value(rms_rel),
        format!("{key}_max_rel"),
        value(max_rel),
        format!("log10_{key}_rms"),
        value(log10_rms),
    );
    stdout::write_stdout(table.as_bytes())?;
    eprintln!("wrote {}", target.display());
    Ok(())
}
