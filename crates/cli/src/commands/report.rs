//! `rollfit report DIR [--dma DMA]`: the pictures of a fit (PNG and SVG)
//! and DIR/report.html, one self-contained page with them, the fit's table
//! and, with --dma, the comparison with DMA data (also written to
//! DIR/compare.json, as `rollfit compare` does).
//!
//! Everything is computed before anything is written, so a bad DMA file or
//! fit directory leaves DIR as it was; each file is then written
//! atomically.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result};
use rollfit_report::FitDir;
use rollfit_report::compare::compare;
use rollfit_report::dma::DmaData;
use rollfit_report::html::{ComparisonSection, report_html};
use rollfit_report::plot::{self, master_curve::DmaMarker};

use super::compare::DmaFlags;
use crate::output;

/// Arguments of `rollfit report`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Fit result folder, as written by `rollfit fit` (fit.json, mu.csv,
    /// modulus.csv). The pictures and report.html are written into it.
    pub dir: PathBuf,
    /// DMA data to draw on the master curve and compare with: CSV (f or
    /// omega; E_storage, E_loss or G_storage, G_loss; optional T) or a TA
    /// Instruments TRIOS "LIMS" text export.
    #[arg(long, value_name = "DMA")]
    pub dma: Option<PathBuf>,
    #[command(flatten)]
    pub dma_flags: DmaFlags,
}

/// Runs `rollfit report`.
pub fn run(args: &Args) -> Result<()> {
    let started = Instant::now();
    let fit = FitDir::read(&args.dir).context("cannot read the fit")?;

    let mut markers = Vec::new();
    let mut comparison = None;
    if let Some(path) = &args.dma {
        let options = args.dma_flags.options();
        let dma = DmaData::read(path, fit.summary.poisson, &options)
            .context("cannot read the DMA data")?;
        let result = compare(&fit, &dma, &options).context("cannot compare with the DMA data")?;
        markers = result
            .points
            .iter()
            .map(|p| DmaMarker {
                omega: p.omega,
                storage: p.storage,
                loss: p.loss,
            })
            .collect();
        let metrics = serde_json::to_value(&result).context("cannot serialise the comparison")?;
        let mut warnings = dma.warnings.clone();
        warnings.extend(result.warnings.iter().cloned());
        comparison = Some((path.clone(), metrics, warnings));
    }

    let pictures = plot::pictures(&fit, &markers)?;
    let section = comparison.as_ref().map(|(path, metrics, warnings)| ComparisonSection {
        dma_file: path.to_str().unwrap_or("DMA file"),
        metrics,
        warnings,
    });
    let page = report_html(&fit, &pictures, section.as_ref());

    let mut written = Vec::new();
    for p in &pictures {
        for (extension, bytes) in [("png", p.png.as_slice()), ("svg", p.svg.as_bytes())] {
            let path = args.dir.join(format!("{}.{extension}", p.name));
            output::write_atomically(&path, bytes)?;
            written.push(path);
        }
    }
    if let Some((_, metrics, _)) = &comparison {
        let path = args.dir.join("compare.json");
        let mut text = serde_json::to_string_pretty(metrics)?;
        text.push('\n');
        output::write_atomically(&path, text.as_bytes())?;
        written.push(path);
    }
    let html_path = args.dir.join("report.html");
    output::write_atomically(&html_path, page.as_bytes())?;

    for (_, _, warnings) in &comparison {
        for w in warnings {
            eprintln!("warning: {w}");
        }
    }
    eprintln!(
        "wrote {} and {} pictures ({} files) in {:.2} s",
        html_path.display(),
        pictures.len(),
        written.len(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}
