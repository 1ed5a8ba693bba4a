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
use rollfit_io::FitDir;
use rollfit_io::output;
use rollfit_report::html::{ComparisonSection, report_html};
use rollfit_report::plot::{self, master_curve::DmaMarker};

use super::compare::{DmaFlags, comparison};

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

    let comparison = match &args.dma {
        Some(path) => Some((path, comparison(&args.dir, path, &args.dma_flags)?)),
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
    let pictures = plot::pictures(&fit, &markers)?;
    let section = comparison.as_ref().map(|(path, c)| ComparisonSection {
        dma_file: path.to_str().unwrap_or("DMA file"),
        comparison: c,
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
    if let Some((_, c)) = &comparison {
        // The same bytes as `rollfit compare` writes.
        let path = args.dir.join("compare.json");
        let mut json = serde_json::to_vec_pretty(c).context("cannot format compare.json")?;
        json.push(b'\n');
        output::write_atomically(&path, &json)?;
        written.push(path);
    }
    let html_path = args.dir.join("report.html");
    output::write_atomically(&html_path, page.as_bytes())?;

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
        written.len(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}
