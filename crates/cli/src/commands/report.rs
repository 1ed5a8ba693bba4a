//! `rollfit report DIR [--scene SCENE] [--dma DMA]`: the pictures of a fit
//! (PNG and SVG) and DIR/report.html, one self-contained page with the
//! fit's verdict and scale, them, the fit's table and, with --dma, the
//! comparison with DMA data (also written to DIR/compare.json, as
//! `rollfit compare` does).
//!
//! friction.png draws the fitted μ(v) on a dense grid of speeds, which
//! needs the fit's scene: --scene, else the scene fit.json names
//! (`input.scene`, as `rollfit fit` was given it, so relative to the
//! folder the fit was run from). Without a readable scene that reproduces
//! the fit, the line joins the fit's μ at the measured speeds and a
//! warning says why; a --scene given that cannot be read or does not
//! reproduce the fit is an error.
//!
//! Everything is computed before anything is written, so a bad DMA file or
//! fit directory leaves DIR as it was; each file is then written
//! atomically.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use rollfit_io::FitDir;
use rollfit_io::output;
use rollfit_io::scene as scene_file;
use rollfit_report::fitted_friction::{FittedLine, RollingScene};
use rollfit_report::html::{ComparisonSection, report_html};
use rollfit_report::plot::{self, master_curve::DmaMarker};

use super::compare::{DmaFlags, comparison};
use crate::hints;

/// Arguments of `rollfit report`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Fit result folder, as written by `rollfit fit` (fit.json, mu.csv,
    /// modulus.csv). The pictures and report.html are written into it.
    pub dir: PathBuf,
    /// DMA data to draw on the master curve and compare with: CSV (f or
    /// omega; E_storage, E_loss or G_storage, G_loss; optional T) or a TA
    /// Instruments TRIOS "LIMS" text export; or several files (one
    /// isotherm each), or a folder of them.
    #[arg(long, value_name = "DMA", num_args = 1..)]
    pub dma: Option<Vec<PathBuf>>,
    /// The fit's scene file, for the fitted μ(v) on a dense grid of speeds
    /// in friction.png (default: the scene fit.json names, relative to the
    /// current folder).
    #[arg(long, value_name = "SCENE")]
    pub scene: Option<PathBuf>,
    #[command(flatten)]
    pub dma_flags: DmaFlags,
}

/// Runs `rollfit report`.
pub fn run(args: &Args) -> Result<()> {
    let started = Instant::now();
    let fit = FitDir::read(&args.dir).context("cannot read the fit");
    let fit = hints::with_hint(fit, || {
        hints::for_fit_folder(
            &args.dir,
            None,
            "rollfit report DIR (the folder `rollfit fit` wrote)",
        )
    })?;

    let comparison = match &args.dma {
        Some(files) => Some((
            rollfit_io::dma::files::names(files),
            comparison(&args.dir, files, &args.dma_flags)?,
        )),
        None => None,
    };
    let markers: Vec<DmaMarker> = comparison.as_ref().map_or_else(Vec::new, |(_, c)| {
        c.points
            .iter()
            .map(|p| DmaMarker {
                omega: p.omega,
                storage: p.storage,
                loss: p.loss,
            })
            .collect()
    });
    let line = fitted_line(&fit, args.scene.as_deref())?;
    let pictures = plot::pictures(&fit, &markers, &line)?;
    let section = comparison.as_ref().map(|(path, c)| ComparisonSection {
        dma_file: path.as_str(),
        comparison: c,
    });
    let page = report_html(&fit, &pictures, section.as_ref());

    let mut written: Vec<(String, &[u8])> = Vec::new();
    for p in &pictures {
        for (extension, bytes) in [("png", p.png.as_slice()), ("svg", p.svg.as_bytes())] {
            written.push((format!("{}.{extension}", p.name), bytes));
        }
    }
    let json = match &comparison {
        // The same bytes as `rollfit compare` writes.
        Some((_, c)) => {
            let mut json = serde_json::to_vec_pretty(c).context("cannot format compare.json")?;
            json.push(b'\n');
            Some(json)
        }
        None => None,
    };
    if let Some(json) = &json {
        written.push(("compare.json".into(), json));
    }
    let html_path = args.dir.join("report.html");
    written.push(("report.html".into(), page.as_bytes()));
    let named: Vec<(&str, &[u8])> = written.iter().map(|(n, b)| (n.as_str(), *b)).collect();
    output::add_files(&args.dir, output::Writer::Fit, &named)?;

    if let FittedLine::AtData { why } = &line {
        eprintln!(
            "warning: friction.png joins the fit's μ at the measured speeds, with no dense \
             curve: {why}"
        );
    }
    if let Some((_, c)) = &comparison {
        for note in &c.notes {
            eprintln!("note: {note}");
        }
        for warning in &c.warnings {
            eprintln!("warning: {warning}");
        }
    }
    eprintln!(
        "wrote {} and {} pictures ({} files) in {:.2} s",
        html_path.display(),
        pictures.len(),
        written.len() - 1,
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// The fitted line of friction.png: dense under the scene `flag` names
/// (an error when it cannot be read or does not reproduce the fit), else
/// under the scene fit.json names, else through the measured speeds.
fn fitted_line(fit: &FitDir, flag: Option<&Path>) -> Result<FittedLine> {
    if let Some(path) = flag {
        let scene = rolling_scene(path).with_context(|| format!("--scene {}", path.display()))?;
        let line = FittedLine::of(fit, &scene);
        if let FittedLine::AtData { why } = &line {
            bail!("--scene {}: {why}", path.display());
        }
        return Ok(line);
    }
    let named = fit.summary.input.as_ref().and_then(|i| i.scene.as_deref());
    let Some(named) = named else {
        return Ok(FittedLine::AtData {
            why: "fit.json names no scene (input.scene); give it with --scene".into(),
        });
    };
    Ok(match rolling_scene(Path::new(named)) {
        Ok(scene) => match FittedLine::of(fit, &scene) {
            FittedLine::AtData { why } => FittedLine::AtData {
                why: format!("scene file {named} (named in fit.json): {why}"),
            },
            dense => dense,
        },
        Err(e) => FittedLine::AtData {
            why: format!("{e:#}; give the fit's scene with --scene"),
        },
    })
}

/// What the fitted μ(v) needs of the scene file at `path`.
fn rolling_scene(path: &Path) -> Result<RollingScene> {
    let (setup, params) = scene_file::load(path)?
        .fit_setup()
        .with_context(|| format!("scene file {}", path.display()))?;
    Ok(RollingScene::new(setup, &params))
}
