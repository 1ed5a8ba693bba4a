//! `rollfit fit SCENE.toml DATA.csv [-o DIR]`: recover the master curve
//! E*(ω) from measured μ(v) (Persson 2010, Appendix B; docs/ARCHITECTURE.md,
//! "Data flow" and "Contract").
//!
//! The scene's [geometry], [substrate] and [contact] describe the
//! experiment; its optional `[fit]` table holds the scale anchor and the
//! solver settings; an "sls" or "prony" `[material]` is the starting point.
//! Flags override the scene. Writes DIR/fit.json, DIR/modulus.csv and
//! DIR/mu.csv (as one folder swap) and a summary on stderr. A fit that does
//! not converge, or does not describe its data, writes nothing and fails,
//! unless `--allow-unconverged` or `--allow-poor-fit`.
//!
//! With DMA isotherms (`--dma FILE`, or the scene's `[fit] dma`), the fit
//! is the joint fit of both ([`joint`]): one master curve and
//! shift law for the DMA moduli and the rolling friction, and a summary
//! block that says whether the two describe one material.

use std::path::{Path, PathBuf};
use std::str::FromStr;

use anyhow::{Context, Result, anyhow, bail};
use rollfit_fit::{
    FitError, FitReport, FitSettings, FrictionFactor, Lambda, Method, Physics, PhysicsRecord,
    RollingSetup, ShiftKind, ShiftRecord, TermRule,
};
use rollfit_io::fit_dir::{FitFolder, FitInput, Measured, MuCsv};
use rollfit_io::output;
use rollfit_model::Shape;

use rollfit_io::data::{DataTable, read_sheet};
use rollfit_io::dma::DmaInput;
use rollfit_io::scene as scene_file;

use crate::commands::compare::{DmaFileFlags, DmaModulus};
use crate::{hints, progress};

mod joint;

pub use joint::SettingsFrom;

/// Arguments of `rollfit fit`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Scene file (TOML): [geometry], optional [substrate], [contact],
    /// [material] (starting point) and [fit] (anchor and settings).
    pub scene: PathBuf,
    /// Measured data: CSV (',', ';' or tab; decimal commas with ';' or tab)
    /// or a workbook (.xlsx, .xlsm, .xls, .ods) with a speed column (v,
    /// velocity, speed; m/s or a unit such as "velocity (mm/s)") and a
    /// friction column (mu, µ, COF, friction coefficient), optional sigma and
    /// T (°C, or a unit such as T_K).
    pub data: PathBuf,
    /// The sheet of a workbook DATA to read (default: the first).
    #[arg(long, value_name = "NAME")]
    pub sheet: Option<String>,
    /// DMA isotherms (any form `rollfit master` reads; shear moduli
    /// converted with the scene's ν) fitted jointly with DATA: one master
    /// curve for both, and a test of whether they describe one material.
    /// Relative to the current folder; overrides [fit] dma. Several files
    /// (one isotherm each, the temperature in each file or its name) or a
    /// folder of them are read as `rollfit master` reads them.
    #[arg(long, value_name = "DMAFILE", num_args = 1..)]
    pub dma: Option<Vec<PathBuf>>,
    /// How the --dma files' temperatures and moduli are read where they do
    /// not say (as `rollfit master` reads them).
    #[command(flatten)]
    pub dma_files: DmaFileFlags,
    /// Read the --dma files' storage and loss moduli as Young's or shear
    /// moduli where their column names do not say (TRIOS: default from the
    /// file's torque or force variables).
    #[arg(long = "dma-modulus", value_enum, value_name = "KIND")]
    pub dma_modulus: Option<DmaModulus>,
    /// Folder for fit.json, modulus.csv and mu.csv (created if missing).
    /// Default: fits/<DATA file stem>.
    #[arg(short, long, value_name = "DIR")]
    pub output: Option<PathBuf>,
    #[command(flatten)]
    pub settings: Settings,
    /// Replace an output folder another command wrote (`rollfit master`,
    /// `rollfit batch`); files rollfit did not write there stay.
    #[arg(long)]
    pub force: bool,
    /// Exit with status 0 even when the final solver run did not converge.
    #[arg(long)]
    pub allow_unconverged: bool,
    /// Exit with status 0 even when the goodness-of-fit tests (χ², runs of
    /// one-signed residuals) find that the fit does not describe the data.
    #[arg(long)]
    pub allow_poor_fit: bool,
    /// Without a scale anchor in [fit]: write the result even when the data
    /// do not determine the modulus scale (fit.json's "scale" then says
    /// "undetermined", with the interval of E0 the data allow).
    #[arg(long)]
    pub allow_unanchored: bool,
}

/// Fit settings that override the scene's [fit] table (shared by `fit` and
/// `batch`). Each flag's value goes through its type's `FromStr`, the
/// syntax a scene's `[fit]` and a batch manifest share (crates/fit/src/settings.rs).
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Settings {
    /// Solver: auto (= levenberg-marquardt), levenberg-marquardt, lbfgs or
    /// nelder-mead. Overrides [fit] method.
    #[arg(long, value_name = "NAME", value_parser = setting::<Method>)]
    pub method: Option<Method>,
    /// Smoothness weight λ ≥ 0 on ln H_k, or "auto" (discrepancy principle
    /// with sigma, else the marginal likelihood). Overrides [fit] lambda.
    #[arg(long, value_name = "VALUE|auto", value_parser = setting::<Lambda>, allow_hyphen_values = true)]
    pub lambda: Option<Lambda>,
    /// Seed of the multi-start perturbations. Overrides [fit] seed.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub seed: Option<u64>,
    /// Number of starts (the neutral one plus seeded perturbations).
    /// Overrides [fit] starts.
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub starts: Option<usize>,
    /// Relaxation times: a count N, "auto" (1, 2 or 3 per decade by AICc) or
    /// a density "X/decade". Overrides [fit] terms (or its aliases
    /// terms_per_decade and tau).
    #[arg(
        long,
        value_name = "N|auto|X/decade",
        value_parser = setting::<TermRule>,
        allow_hyphen_values = true
    )]
    pub terms: Option<TermRule>,
    /// The model's physics: approximate (Eq. (11)/(17), the default) or
    /// exact (the exact rolling contact, by defect correction; slower).
    /// Overrides [fit] physics.
    #[arg(long, value_name = "approximate|exact", value_parser = setting::<Physics>)]
    pub physics: Option<Physics>,
    /// The shift law of a temperature set: auto (the default: WLF unless
    /// the data reject it against free shifts, then Arrhenius, else free),
    /// wlf, arrhenius or free. Overrides [fit] shift.
    #[arg(long, value_name = "auto|wlf|arrhenius|free", value_parser = setting::<ShiftKind>)]
    pub shift: Option<ShiftKind>,
    /// In a joint fit with DMA data: the relative standard deviation of
    /// E′ and E″ (0.01 for 1 %; default: estimated from the DMA data).
    /// Overrides [fit] dma_sigma.
    #[arg(long, value_name = "X", allow_hyphen_values = true)]
    pub dma_sigma: Option<f64>,
    /// In a joint fit with DMA data: μ_measured = κ μ_theory with κ = 1
    /// ("one", the default) or fitted ("free"). Overrides [fit]
    /// friction_factor.
    #[arg(long, value_name = "one|free", value_parser = setting::<FrictionFactor>)]
    pub friction_factor: Option<FrictionFactor>,
}

impl Settings {
    /// The flags as fit settings (unset where not given).
    pub fn fit_settings(&self) -> FitSettings {
        let mut settings = FitSettings::default();
        settings.method = self.method;
        settings.lambda = self.lambda;
        settings.seed = self.seed;
        settings.starts = self.starts;
        settings.terms = self.terms.clone();
        settings.physics = self.physics;
        settings.shift = self.shift;
        settings.dma_sigma = self.dma_sigma;
        settings.friction_factor = self.friction_factor;
        settings
    }
}

/// A flag's value by its type's `FromStr`; clap puts the problem after
/// "invalid value 'TEXT' for '--FLAG'", which names the flag.
fn setting<T: FromStr<Err = FitError>>(text: &str) -> Result<T, String> {
    text.parse().map_err(|e| match e {
        FitError::InvalidSetting { problem, .. } => problem,
        other => other.to_string(),
    })
}

/// The default output folder: fits/<DATA file stem>.
pub fn default_output(data: &Path) -> Result<PathBuf> {
    let stem = data
        .file_stem()
        .with_context(|| format!("data file {} has no file name", data.display()))?;
    Ok(Path::new("fits").join(stem))
}

/// Runs the command.
pub fn run(args: &Args) -> Result<()> {
    let dir = match &args.output {
        Some(dir) => dir.clone(),
        None => default_output(&args.data)?,
    };
    let job = Job {
        scene: &args.scene,
        data: &args.data,
        sheet: args.sheet.as_deref(),
        dma: args.dma.as_deref(),
        dma_input: args.dma_files.input(&[], None, args.dma_modulus),
        dir: &dir,
        settings: &args.settings.fit_settings(),
        usage: USAGE,
        progress: true,
        force: args.force,
        settings_from: joint::SettingsFrom::CommandLine,
    };
    let outcome = fit_files(&job, |line| eprintln!("{line}"))?;
    let report = &outcome.report;
    // Only an accepted fit is written: a non-zero exit leaves the output
    // folder as it was.
    let quality = &report.fit_quality;
    let undetermined = report.scale.as_ref().filter(|s| s.is_undetermined());
    let accepted = (report.converged || args.allow_unconverged)
        && (!report.converged || quality.is_good() || args.allow_poor_fit)
        && (undetermined.is_none() || args.allow_unanchored);
    if accepted {
        outcome.commit(&dir, args.force)?;
    }
    eprint!("{}", summary(report, &dir, accepted));
    if let Some(t) = outcome.temperature {
        eprintln!(
            "note: every point was measured at T = {t} °C; the master curve is E*(ω) at that \
             temperature"
        );
    }
    if let Some(shift) = &report.shift {
        eprintln!(
            "note: a temperature set; the master curve is E*(ω) at T_ref = {} °C",
            shift.t_ref()
        );
    }
    if let Some(scale) = &report.scale {
        eprintln!("note: modulus scale: {}", scale.reason);
    }
    // An unconverged fit is judged by the convergence gate below alone.
    if report.converged && !quality.is_good() {
        let what = if quality.is_invalid() {
            "the fitted material breaks the model's assumptions"
        } else {
            "the fit does not describe the data"
        };
        if args.allow_poor_fit {
            eprintln!(
                "warning: {what} (fit_quality in fit.json); results kept because of \
                 --allow-poor-fit"
            );
        } else {
            bail!(
                "{what}: {}; nothing was written to {} (check the scene's units and geometry, \
                 or give --allow-poor-fit to write the results, marked \"fit_quality\": \
                 {{\"verdict\": \"{}\"}}, and look at the residuals in mu.csv or `rollfit \
                 report`)",
                quality.reasons.join("; "),
                dir.display(),
                quality.verdict
            );
        }
    }
    if let Some(scale) = undetermined {
        if args.allow_unanchored {
            eprintln!(
                "warning: the data do not determine the modulus scale (fit.json's \"scale\"); \
                 results kept because of --allow-unanchored"
            );
        } else {
            bail!(
                "{}; nothing was written to {} (or give --allow-unanchored to write the result, \
                 marked \"scale\": {{\"status\": \"undetermined\"}})",
                scale.reason,
                dir.display()
            );
        }
    }
    if !report.converged {
        if args.allow_unconverged {
            eprintln!(
                "warning: the fit did not converge ({}); results kept because of --allow-unconverged",
                report.stop_reason
            );
        } else {
            bail!(
                "the fit did not converge: {}; nothing was written to {} (try another --method, \
                 more --starts or a larger [fit] max_evaluations, or give --allow-unconverged to \
                 write the results, marked \"converged\": false)",
                report.stop_reason,
                dir.display()
            );
        }
    }
    Ok(())
}

/// One fit: a scene, a data file, a result folder and overriding settings.
pub struct Job<'a> {
    pub scene: &'a Path,
    pub data: &'a Path,
    /// The sheet of a workbook data file (None: the first).
    pub sheet: Option<&'a str>,
    /// The DMA file of a joint fit (`--dma`, a manifest's `dma`), over the
    /// scene's `[fit] dma`.
    pub dma: Option<&'a [PathBuf]>,
    /// How the DMA files are read (`--temperatures`, `--units`,
    /// `--dma-modulus`); its files are `dma`'s or the scene's.
    pub dma_input: DmaInput,
    pub dir: &'a Path,
    /// Over the scene's `[fit]`: the flags (for a batch, also the
    /// manifest's settings, checked when the manifest was read).
    pub settings: &'a FitSettings,
    /// The right order of scene and data, for the hint when they look
    /// swapped ([`USAGE`], or a manifest's keys).
    pub usage: &'static str,
    /// Whether an exact-physics fit shows a bar of its exact solves (on a
    /// terminal; a batch shows its own bar of entries instead).
    pub progress: bool,
    /// Whether `dir` may hold another command's results, which the fit
    /// then replaces (`--force`).
    pub force: bool,
    /// Where `settings` were given, for the message refusing one.
    pub settings_from: joint::SettingsFrom<'a>,
}

/// The order of `rollfit fit`'s files, for the hint when they look
/// swapped.
pub const USAGE: &str = "rollfit fit SCENE.toml DATA.csv";

/// A finished fit and its result files, checked and encoded (mu.csv, which
/// grows with the data, is written row by row when committed).
pub struct Outcome {
    pub report: FitReport,
    /// The one temperature of the data's `T` column, °C.
    pub temperature: Option<f64>,
    /// The data as read, which mu.csv repeats row by row.
    table: DataTable,
    /// fit.json and modulus.csv.
    files: FitFolder,
}

impl Outcome {
    /// Writes the result files, replacing the folder `dir` as a whole
    /// ([`output::replace_folder_with`]): a reader finds either the
    /// previous complete result or this one.
    pub fn commit(&self, dir: &Path, force: bool) -> Result<()> {
        let mu_csv = MuCsv::new(measured(&self.table), &self.report);
        Ok(output::replace_folder_with(
            dir,
            output::Writer::Fit,
            force,
            &self.files.files(&mu_csv),
        )?)
    }
}

/// The rows of `table` as mu.csv repeats them.
fn measured(table: &DataTable) -> Measured<'_> {
    Measured {
        speeds: &table.speeds,
        friction: &table.friction,
        sigma: table.sigma.as_deref(),
        temperature: table.temperature.as_deref(),
    }
}

/// Reads the scene and the data of `job`, fits, and encodes DIR/mu.csv,
/// DIR/modulus.csv and DIR/fit.json; [`Outcome::commit`] writes them (the
/// caller decides whether an unconverged or poor fit is kept). `log`
/// receives the data file's notes and warnings (how it was read, rows
/// skipped) and a line before the (possibly long) fit starts.
pub fn fit_files(job: &Job<'_>, log: impl Fn(&str)) -> Result<Outcome> {
    let (scene_path, data_path, dir) = (job.scene, job.data, job.dir);
    output::check_replaceable(dir, output::Writer::Fit, job.force)?;

    let file = hints::with_hint(scene_file::load(scene_path).map_err(Into::into), || {
        hints::for_scene(scene_path, data_path, job.usage)
    })?;
    let (setup, mut params) = file
        .fit_setup()
        .with_context(|| format!("scene file {}", scene_path.display()))?;
    job.settings.apply(&mut params);
    let table = hints::with_hint(read_sheet(data_path, job.sheet).map_err(Into::into), || {
        hints::for_data(data_path, job.usage)
    })?;
    for note in &table.notes {
        log(&format!("note: data file {}: {note}", data_path.display()));
    }
    for warning in &table.warnings {
        log(&format!(
            "warning: data file {}: {warning}",
            data_path.display()
        ));
    }
    let data = table
        .measurements()
        .with_context(|| format!("data file {}", data_path.display()))?;
    let t_ref = params.shift.t_ref;
    let valid = params.check(setup).map_err(|e| match &e {
        FitError::InvalidSetting { key, .. } => {
            anyhow!(
                "{}: {e}",
                joint::setting_origin(job.settings, job.settings_from, key, scene_path)
            )
        }
        _ => anyhow!("scene file {}: {e}", scene_path.display()),
    })?;
    // The DMA file of a joint fit, read after the rolling data.
    let valid = match joint::dma_file(job.dma, &file, scene_path) {
        Some(dma) => {
            let poisson = setup.substrate.poisson;
            joint::with_dma(valid, dma, &job.dma_input, poisson, t_ref, scene_path, &log)?
        }
        None => valid,
    };

    log(&format!(
        "fitting {} point(s) of {} with scene {}: {}",
        data.len(),
        data_path.display(),
        scene_path.display(),
        describe_setup(&setup)
    ));
    // A bar of the exact solves, the part that takes seconds to minutes.
    let (valid, bar) = if job.progress && valid.physics() == Physics::Exact {
        let (observer, bar) = progress::fit_observer();
        (valid.with_progress(observer), Some(bar))
    } else {
        (valid, None)
    };
    let fitted = rollfit_fit::fit(&data, &valid);
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let report = fitted.map_err(|e| match e {
        FitError::InsufficientData(why) => anyhow!("data file {}: {why}", data_path.display()),
        // Names the DMA file itself.
        FitError::DmaData { .. } => anyhow!("{e}"),
        // The settings only a joint fit reads, refused without DMA data.
        FitError::InvalidSetting { ref key, .. } if key != "dma" => {
            anyhow!(
                "{}: {e}",
                joint::setting_origin(job.settings, job.settings_from, key, scene_path)
            )
        }
        other => anyhow!(
            "fitting data file {} with scene file {}: {other}",
            data_path.display(),
            scene_path.display()
        ),
    })?;

    // Everything is checked before the disk is touched.
    let measured = measured(&table);
    let temperature = measured.single_temperature();
    let input = FitInput {
        scene: job.scene.display().to_string(),
        data: job.data.display().to_string(),
        temperature,
        rollfit_version: env!("CARGO_PKG_VERSION"),
    };
    let files = FitFolder::encode(&report, &measured, &input)?;
    Ok(Outcome {
        report,
        temperature,
        table,
        files,
    })
}

fn describe_setup(setup: &RollingSetup) -> String {
    let g = setup.geometry;
    let (shape, unit) = match g.shape {
        Shape::Sphere => ("sphere", "N"),
        Shape::Cylinder => ("cylinder", "N/m"),
    };
    format!(
        "{shape} R = {} m, load {} {unit}, ν = {}",
        g.radius, g.load, setup.substrate.poisson
    )
}

/// A few lines for a person at a terminal.
pub fn summary(report: &FitReport, dir: &Path, written: bool) -> String {
    let mut text = String::new();
    let weights = if report.sigma_weights {
        "χ² with the measured sigma"
    } else {
        "relative residuals"
    };
    let status = if report.converged {
        report.stop_reason.clone()
    } else {
        format!("NOT converged — {}", report.stop_reason)
    };
    text += &format!(
        "method {}: {status}; {} iterations in the final run, {} evaluations in {} runs\n",
        report.method,
        report.iterations,
        report.evaluations,
        report.runs.len()
    );
    text += &format!(
        "objective V = {:.6e}; misfit per point {:.4} ({weights})\n",
        report.objective, report.misfit_per_point
    );
    let quality = &report.fit_quality;
    text += &if report.sigma_weights {
        format!(
            "fit quality {}: χ² = {:.1} for {:.1} degrees of freedom{}",
            quality.verdict,
            quality.chi2,
            quality.degrees_of_freedom,
            quality
                .chi2_p_value
                .map_or(String::new(), |p| format!(" (p = {p:.2})"))
        )
    } else {
        format!(
            "fit quality {}: noise estimated from the residuals (no sigma column): {:.2} % of μ",
            quality.verdict,
            100.0 * report.noise
        )
    };
    if let Some(runs) = &quality.runs {
        text += &format!(
            "; runs test p = {:.2} ({} runs, {:.1} expected)",
            runs.p_value, runs.observed, runs.expected
        );
    }
    text += "\n";
    text += &format!(
        "λ = {:.4e} ({}); {} effective parameters\n",
        report.lambda.value,
        lambda_rule(report),
        fmt_short(report.effective_parameters)
    );
    let determined = report.model.determined.iter().filter(|d| **d).count();
    text += &format!(
        "window ω = {:.3e} … {:.3e} rad/s; {} relaxation times ({:.3} per decade, rule {}), \
         {determined} determined by the data\n",
        report.window.omega_min,
        report.window.omega_max,
        report.terms.count,
        report.terms.per_decade,
        report.terms.rule
    );
    match &report.anchor {
        Some(a) if a.omega == 0.0 => {
            text += &format!("scale anchor {}: E0 = {:.4e} Pa\n", a.source, a.modulus)
        }
        Some(a) => {
            text += &format!(
                "scale anchor {}: |E| = {:.4e} Pa at ω = {:.4e} rad/s\n",
                a.source, a.modulus, a.omega
            )
        }
        None => {}
    }
    if let Some(scale) = &report.scale {
        let end = |x: Option<f64>| x.map_or("open".to_string(), |x| format!("{x:.3e}"));
        text += &format!(
            "no scale anchor: E0 2σ interval {} … {} Pa from the scale profile ({})\n",
            end(scale.low),
            end(scale.high),
            if scale.is_undetermined() {
                "NOT determined by the data"
            } else {
                "determined by the data"
            }
        );
    }
    text += &format!(
        "E0 = {:.4e} Pa, E1 = {:.4e} Pa; wall time {:.3} s\n",
        report.model.static_modulus, report.model.glassy_modulus, report.wall_time_s
    );
    text += &shift_lines(report);
    if let Some(check) = &report.shift_cross_check {
        text += &format!(
            "cross-check (each temperature alone, tan δ overlapped): log10 a_T differs from the \
             joint fit by {:.3} decades RMS, {:.3} at most\n",
            check.rms_difference, check.max_difference
        );
    }
    if let Some(p) = &report.physics {
        text += &physics_line(p);
    }
    if let Some(j) = &report.joint {
        text += &joint::summary_lines(j);
    }
    for warning in &report.warnings {
        text += &format!("warning: {warning}\n");
    }
    if written {
        text += &format!("wrote {} (fit.json, modulus.csv, mu.csv)\n", dir.display());
    }
    text
}

/// The summary's lines about a temperature set's shift (none without one).
fn shift_lines(report: &FitReport) -> String {
    let mut out = String::new();
    match &report.shift {
        Some(ShiftRecord::Wlf {
            t_ref,
            c1,
            c2,
            c1_sigma,
            c2_sigma,
            ..
        }) => {
            out += &format!(
                "shift WLF at T_ref = {t_ref} °C: C1 = {c1:.4} ± {c1_sigma:.2e}, \
                 C2 = {c2:.4} ± {c2_sigma:.2e} K\n"
            )
        }
        Some(ShiftRecord::Arrhenius {
            t_ref,
            activation_energy,
            activation_energy_sigma,
            ..
        }) => {
            out += &format!(
                "shift Arrhenius at T_ref = {t_ref} °C: E_a = {:.4} ± {:.2} kJ/mol\n",
                activation_energy / 1e3,
                activation_energy_sigma / 1e3
            )
        }
        Some(ShiftRecord::Free { t_ref, log_shift }) => {
            out += &format!("shift free, T_ref = {t_ref} °C: log10 a_T =");
            for s in log_shift {
                out += &format!(" {:.3} ({} °C)", s.log_shift, s.temperature);
            }
            out += "\n";
        }
        None => {}
    }
    out
}

/// The summary's line about a fit with `physics = "exact"`.
fn physics_line(p: &PhysicsRecord) -> String {
    format!(
        "physics exact (defect correction): {} refit(s), {} exact solves, {}; μ_exact/μ_approx \
         within {:.2} % of 1, each exact μ to {:.1e}\n",
        p.iterations,
        p.exact_solves,
        if p.converged {
            "converged"
        } else {
            "NOT converged"
        },
        100.0 * p.max_correction,
        p.accuracy
    )
}

fn lambda_rule(report: &FitReport) -> String {
    serde_json::to_value(report.lambda.rule)
        .ok()
        .and_then(|v| v.as_str().map(|s| s.replace('_', " ")))
        .unwrap_or_else(|| "?".into())
}

fn fmt_short(x: f64) -> String {
    format!("{x:.1}")
}

#[cfg(test)]
mod tests {
    use rollfit_fit::FitParams;

    use super::*;

    #[test]
    fn terms_flag_forms() {
        let parse_terms = setting::<TermRule>;
        assert_eq!(parse_terms("15"), Ok(TermRule::Count(15)));
        assert_eq!(parse_terms("auto"), Ok(TermRule::Auto));
        assert_eq!(parse_terms("2/decade"), Ok(TermRule::PerDecade(2.0)));
        assert_eq!(parse_terms("1.5/decade"), Ok(TermRule::PerDecade(1.5)));
        for bad in ["", "-3", "2.5", "x/decade", "0/decade", "many"] {
            assert!(parse_terms(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn lambda_and_method_flags() {
        let (parse_lambda, parse_method) = (setting::<Lambda>, setting::<Method>);
        assert_eq!(parse_lambda("auto"), Ok(Lambda::Auto));
        assert_eq!(parse_lambda("0"), Ok(Lambda::Fixed(0.0)));
        assert_eq!(parse_lambda("1e-3"), Ok(Lambda::Fixed(1e-3)));
        for bad in ["-1", "nan", "inf", "x"] {
            assert!(parse_lambda(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_method("lbfgs"), Ok(Method::Lbfgs));
        assert_eq!(parse_method("auto"), Ok(Method::LevenbergMarquardt));
        let err = parse_method("newton").unwrap_err();
        assert!(
            err.contains("\"newton\"") && err.contains("nelder-mead"),
            "{err}"
        );
    }

    /// The flags become the same settings a scene or a manifest gives.
    #[test]
    fn flags_are_fit_settings() {
        use clap::Parser;
        #[derive(Parser)]
        struct Cli {
            #[command(flatten)]
            settings: Settings,
        }
        let cli = Cli::try_parse_from([
            "rollfit",
            "--terms",
            "2/decade",
            "--starts",
            "2",
            "--physics",
            "exact",
        ])
        .unwrap();
        let flags = cli.settings.fit_settings();
        assert_eq!(flags.terms, Some(TermRule::PerDecade(2.0)));
        assert_eq!(flags.starts, Some(2));
        assert_eq!(flags.physics, Some(Physics::Exact));
        assert!(flags.gives("physics"));
        let err = Cli::try_parse_from(["rollfit", "--physics", "exakt"])
            .err()
            .unwrap()
            .to_string();
        assert!(
            err.contains("--physics") && err.contains("\"exakt\"") && err.contains("exact"),
            "{err}"
        );
        assert!(flags.gives("terms") && flags.gives("tau") && !flags.gives("lambda"));
        let err = Cli::try_parse_from(["rollfit", "--terms", "0/decade"])
            .err()
            .unwrap()
            .to_string();
        assert!(
            err.contains("--terms") && err.contains("per decade"),
            "{err}"
        );
    }

    /// One setting through every front door: the scene's `[fit]` under its
    /// alias and its own spelling, the flag, and a manifest's `[defaults]`
    /// and `[[entry]]` give the same fit parameters (3 per decade, not the
    /// default 2); a bad value names the key at each door.
    #[test]
    fn one_setting_through_every_front_door() {
        use clap::Parser;
        #[derive(Parser)]
        struct Cli {
            #[command(flatten)]
            settings: Settings,
        }
        let geometry = "[geometry]\nshape = \"sphere\"\nradius = 0.005\nload = 1.0\n";
        let scene = |fit: &str| scene_file::parse(&format!("{geometry}[fit]\n{fit}\n"));
        let params_of = |fit: &str| scene(fit).unwrap().fit_setup().unwrap().1;
        let flags = |args: &[&str]| {
            Cli::try_parse_from(["rollfit"].iter().chain(args)).map(|cli| cli.settings)
        };
        let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data");
        let entry =
            "[[entry]]\nname = \"a\"\nscene = \"hn-rubber.toml\"\ndata = \"hn-rubber.csv\"\n";
        let manifest = |text: &str| rollfit_io::manifest::parse(text, &base);

        let default = FitParams::default();
        let alias = params_of("terms_per_decade = 3");
        assert_eq!(alias.terms, TermRule::PerDecade(3.0));
        assert_ne!(
            alias.terms, default.terms,
            "the test needs a non-default value"
        );
        assert_eq!(params_of("terms = \"3/decade\""), alias);
        let mut by_flag = params_of("");
        flags(&["--terms", "3/decade"])
            .unwrap()
            .fit_settings()
            .apply(&mut by_flag);
        assert_eq!(by_flag, alias);
        let read = manifest(&format!("[defaults]\nterms = \"3/decade\"\n{entry}")).unwrap();
        let mut by_defaults = params_of("");
        read.entries[0]
            .settings
            .over(&read.defaults)
            .apply(&mut by_defaults);
        assert_eq!(by_defaults, alias);
        let read = manifest(&format!("{entry}terms = \"3/decade\"\n")).unwrap();
        let mut by_entry = params_of("");
        read.entries[0].settings.apply(&mut by_entry);
        assert_eq!(by_entry, alias);

        // A bad value names the key (and, in a file, its line).
        for fit in ["terms = \"3/decennium\"", "terms_per_decade = -3"] {
            let err = format!("{:#}", anyhow::Error::from(scene(fit).unwrap_err()));
            let key = fit.split(' ').next().unwrap();
            for fragment in ["[fit]", &format!("`{key}`"), "line 6"] {
                assert!(err.contains(fragment), "{fragment:?} in {err}");
            }
        }
        let err = flags(&["--terms", "3/decennium"])
            .err()
            .unwrap()
            .to_string();
        assert!(
            err.contains("--terms") && err.contains("3/decennium"),
            "{err}"
        );
        let err = format!(
            "{:#}",
            anyhow::Error::from(
                manifest(&format!("{entry}terms = \"3/decennium\"\n")).unwrap_err()
            )
        );
        for fragment in ["entry \"a\"", "`terms`", "line 5", "3/decennium"] {
            assert!(err.contains(fragment), "{fragment:?} in {err}");
        }
    }

    /// `physics` through every front door: the scene's `[fit]`, the flag,
    /// a manifest's `[defaults]` and `[[entry]]` give the exact physics;
    /// a bad value names the key (and, in a file, its line) at each door.
    #[test]
    fn physics_through_every_front_door() {
        use clap::Parser;
        #[derive(Parser)]
        struct Cli {
            #[command(flatten)]
            settings: Settings,
        }
        let geometry = "[geometry]\nshape = \"cylinder\"\nradius = 0.005\nload = 1000.0\n";
        let scene = |fit: &str| scene_file::parse(&format!("{geometry}[fit]\n{fit}\n"));
        let params_of = |fit: &str| scene(fit).unwrap().fit_setup().unwrap().1;
        let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data");
        let entry =
            "[[entry]]\nname = \"a\"\nscene = \"hn-rubber.toml\"\ndata = \"hn-rubber.csv\"\n";
        let manifest = |text: &str| rollfit_io::manifest::parse(text, &base);

        assert_eq!(params_of("").physics, Physics::Approximate);
        assert_eq!(params_of("physics = \"exact\"").physics, Physics::Exact);
        let mut by_flag = params_of("");
        Cli::try_parse_from(["rollfit", "--physics", "exact"])
            .unwrap()
            .settings
            .fit_settings()
            .apply(&mut by_flag);
        assert_eq!(by_flag.physics, Physics::Exact);
        let read = manifest(&format!("[defaults]\nphysics = \"exact\"\n{entry}")).unwrap();
        let mut by_defaults = params_of("");
        read.entries[0]
            .settings
            .over(&read.defaults)
            .apply(&mut by_defaults);
        assert_eq!(by_defaults.physics, Physics::Exact);
        let read = manifest(&format!(
            "[defaults]\nphysics = \"exact\"\n{entry}physics = \"approximate\"\n"
        ))
        .unwrap();
        let mut by_entry = params_of("");
        read.entries[0]
            .settings
            .over(&read.defaults)
            .apply(&mut by_entry);
        assert_eq!(by_entry.physics, Physics::Approximate);

        let err = format!(
            "{:#}",
            anyhow::Error::from(scene("physics = \"exakt\"").unwrap_err())
        );
        for fragment in ["[fit]", "`physics`", "line 6", "\"exakt\""] {
            assert!(err.contains(fragment), "{fragment:?} in {err}");
        }
        let err = format!(
            "{:#}",
            anyhow::Error::from(manifest(&format!("{entry}physics = \"exakt\"\n")).unwrap_err())
        );
        for fragment in ["entry \"a\"", "`physics`", "line 5", "\"exakt\""] {
            assert!(err.contains(fragment), "{fragment:?} in {err}");
        }
        let err = format!(
            "{:#}",
            anyhow::Error::from(
                manifest(&format!("[defaults]\nphysics = true\n{entry}")).unwrap_err()
            )
        );
        for fragment in ["`physics`", "line 2", "expected text"] {
            assert!(err.contains(fragment), "{fragment:?} in {err}");
        }
    }

    #[test]
    fn default_output_is_fits_stem() {
        assert_eq!(
            default_output(Path::new("data/hn-rubber.csv")).unwrap(),
            Path::new("fits").join("hn-rubber")
        );
    }
}
