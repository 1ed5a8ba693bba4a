//! The joint fit of `rollfit fit` and `rollfit batch`: which
//! DMA file a job uses, reading it, and the summary's lines about the two
//! parts.

use std::path::{Path, PathBuf};

use anyhow::{Result, anyhow, bail};
use rollfit_fit::{FitSettings, JointRecord, ValidFitParams};
use rollfit_io::dma::DmaInput;
use rollfit_io::manifest::Entry;
use rollfit_io::scene::SceneFile;

/// Where a joint fit's DMA file was named, for messages.
pub enum DmaOrigin {
    /// `--dma` (or a batch manifest's `dma`), relative to the current
    /// folder (the manifest's paths are resolved when it is read).
    Given,
    /// The scene's `[fit] dma`, relative to the scene file's folder.
    Scene,
}

/// The DMA file of a job: `given` (the flag or the manifest) over the
/// scene's `[fit] dma`.
pub fn dma_file(
    given: Option<&[PathBuf]>,
    scene: &SceneFile,
    scene_path: &Path,
) -> Option<(Vec<PathBuf>, DmaOrigin)> {
    match given {
        Some(paths) => Some((paths.to_vec(), DmaOrigin::Given)),
        None => scene
            .dma_file(scene_path.parent().unwrap_or(Path::new("")))
            .map(|path| (vec![path], DmaOrigin::Scene)),
    }
}

/// Reads the DMA files `paths` (files or folders, read as `how` says;
/// shear moduli converted with `poisson`, a file without temperatures
/// taken at `t_ref`) and makes
/// `valid` a joint fit with them; `log` receives how they were read.
/// `origin` names where they came from when the fit refuses them
/// (`--dma`, or the scene file).
pub fn with_dma(
    valid: ValidFitParams,
    (paths, origin): (Vec<PathBuf>, DmaOrigin),
    how: &DmaInput,
    poisson: f64,
    t_ref: Option<f64>,
    scene_path: &Path,
    log: &impl Fn(&str),
) -> Result<ValidFitParams> {
    for path in &paths {
        check_exists(path, &origin, scene_path)?;
    }
    let input = DmaInput {
        files: paths,
        ..how.clone()
    };
    let read = rollfit_report::master_input::joint::read_input(&input, poisson, t_ref)?;
    for note in &read.notes {
        log(&format!("note: {note}"));
    }
    for warning in &read.warnings {
        log(&format!("warning: {warning}"));
    }
    valid.with_dma(read.rows).map_err(|e| match origin {
        DmaOrigin::Given => anyhow!("--dma {}: {e}", input.names()),
        DmaOrigin::Scene => anyhow!("scene file {}: {e}", scene_path.display()),
    })
}

/// Refuses a DMA path that is neither a file, a folder nor a pipe,
/// saying what it is relative to.
fn check_exists(path: &Path, origin: &DmaOrigin, scene_path: &Path) -> Result<()> {
    // A pipe or `-` is read as a file is; the reader refuses devices.
    let piped = path.as_os_str() == rollfit_io::input_file::STANDARD_INPUT
        || std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir());
    if !path.is_file() && !piped && !path.is_dir() {
        let (what, whose) = match origin {
            DmaOrigin::Given => ("--dma", "the current folder".to_string()),
            DmaOrigin::Scene => (
                "[fit] dma",
                format!("the folder of scene file {}", scene_path.display()),
            ),
        };
        bail!(
            "DMA file {} {} ({what} is relative to {whose})",
            path.display(),
            if path.exists() {
                "is not a file or a folder"
            } else {
                "does not exist"
            }
        );
    }
    Ok(())
}

/// Where a job's settings over the scene's `[fit]` were given.
#[derive(Clone, Copy)]
pub enum SettingsFrom<'a> {
    /// The flags of `rollfit fit`.
    CommandLine,
    /// A batch: the entry's keys over the flags over the manifest's
    /// `[defaults]`.
    Manifest {
        path: &'a Path,
        entry: &'a Entry,
        flags: &'a FitSettings,
    },
}

/// A setting the fit refused under `key`, where the user gave it: a
/// batch entry's key (with the entry and its line), the command line (its
/// flag, spelled with dashes), a manifest's `[defaults]`, else the scene
/// file. `settings` are the job's, all sources merged.
pub fn setting_origin(
    settings: &FitSettings,
    from: SettingsFrom<'_>,
    key: &str,
    scene_path: &Path,
) -> String {
    let flag = || format!("command line: --{}", key.replace('_', "-"));
    match from {
        SettingsFrom::Manifest { path, entry, .. } if entry.settings.gives(key) => {
            format!(
                "manifest {}: {}: `{key}`",
                path.display(),
                entry.key_place(key)
            )
        }
        SettingsFrom::Manifest { flags, .. } if flags.gives(key) => flag(),
        SettingsFrom::Manifest { path, .. } if settings.gives(key) => {
            format!("manifest {}: [defaults]: `{key}`", path.display())
        }
        SettingsFrom::CommandLine if settings.gives(key) => flag(),
        _ => format!("scene file {}", scene_path.display()),
    }
}

/// `p` (a percentage) to three significant digits: fixed from 0.01 to
/// 1e4, else with an exponent (σ = 1e-5 is not "0.00 %", 1e300 not 301
/// digits).
fn percent(p: f64) -> String {
    if p != 0.0 && p.is_finite() && (1e-2..1e4).contains(&p.abs()) {
        let decimals = (2 - p.abs().log10().floor() as i32).max(0) as usize;
        format!("{p:.decimals$}")
    } else {
        format!("{p:.2e}")
    }
}

/// The summary's block about a joint fit: each part's χ² together and
/// alone, which shifts the DMA part alone determines, the compatibility
/// verdict and κ if fitted.
pub fn summary_lines(joint: &JointRecord) -> String {
    let chi2 = &joint.chi2;
    let mut text = format!(
        "joint fit with DMA file {} ({} DMA points, {} rolling rows; DMA σ {} % {}):\n",
        joint.dma_source,
        joint.dma_points,
        joint.rolling_points,
        percent(100.0 * joint.sigma.dma),
        joint.sigma.dma_source
    );
    text += &format!(
        "  χ² rolling {:.1} joint / {:.1} alone; χ² DMA {:.1} joint / {:.1} alone\n",
        chi2.rolling_joint, chi2.rolling_alone, chi2.dma_joint, chi2.dma_alone
    );
    if !joint.dma_alone.verdict.is_empty() {
        text += &format!("  DMA part alone: {}\n", joint.dma_alone.verdict);
    }
    text += &format!("  {}\n", joint.compatibility.verdict);
    if let Some(k) = &joint.friction_factor {
        // The verdict states κ and its σ.
        text += &format!("  friction factor: {}\n", k.verdict);
    }
    text
}
