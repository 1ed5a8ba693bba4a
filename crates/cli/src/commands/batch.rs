//! `rollfit batch MANIFEST.toml [-o DIR]`: many independent fits, in
//! parallel (docs/ARCHITECTURE.md, "Contract").
//!
//! Each manifest entry (see [`crate::manifest`]) is one `rollfit fit` of a
//! scene and a data file into DIR/<entry name>/ — the same files, made by
//! the same [`fit_files`]. The entries run on a local rayon pool
//! (`--jobs`); a failing entry is reported and does not stop the others.
//! An entry whose DIR/<name>/fit.json exists is skipped (an entry's folder
//! is replaced as a whole, so fit.json marks a complete result) unless
//! `--force`: running the same command again resumes an interrupted batch,
//! and `--shard i/n` spreads one batch over several processes or machines
//! that share DIR. A batch holds DIR's lock (`.rollfit-batch.lock`; shards
//! share it and each holds its own), so a second batch into DIR is refused
//! at once, and removes what killed runs left (temporary files and
//! folders). DIR/summary.csv (DIR/summary-<i>-of-<n>.csv for a shard) has
//! one row per entry run, in manifest order, its numbers read back from
//! each entry's fit.json. Unlike `rollfit fit`, which then writes nothing,
//! an unconverged entry, or a converged one whose fit_quality verdict is
//! poor, keeps its results (marked in fit.json) but makes the exit status
//! non-zero unless `--allow-unconverged` or `--allow-poor-fit`.
//!
//! Settings, from strongest to weakest: the entry's own keys, the command
//! line's flags, the manifest's `[defaults]`, the scene's `[fit]` table.

use std::cell::RefCell;
use std::fmt::Write as _;
use std::panic::{self, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use anyhow::{Context, Result, bail};
use indicatif::ProgressBar;
use rayon::prelude::*;
use rollfit_fit::{FitError, FitSettings};
use rollfit_io::dma::DmaInput;
use rollfit_io::fit_dir::columns::FIT_JSON;
use rollfit_io::fit_dir::digest::Digest;
use rollfit_io::{csv_text, output};

use crate::commands::fit::{Job, Settings, SettingsFrom, fit_files};
use crate::progress;

mod folder;
use rollfit_io::manifest::{self, Entry};

/// The lock file of a batch's output folder.
const BATCH_LOCK: &str = ".rollfit-batch.lock";

/// Columns of summary.csv.
pub const SUMMARY_COLUMNS: [&str; 11] = [
    "entry",
    "status",
    "objective",
    "misfit_per_point",
    "omega_min",
    "omega_max",
    "wall_time_s",
    "converged",
    "C1",
    "C2",
    "message",
];

/// Arguments of `rollfit batch`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Manifest (TOML): optional [defaults] (method, lambda, seed, starts,
    /// terms, physics, dma_sigma, friction_factor, dma) and one [[entry]]
    /// per fit with name, scene and data (paths relative to the manifest's
    /// folder), optional dma (DMA isotherms of a joint fit) and settings.
    pub manifest: PathBuf,
    /// Folder for the results: DIR/<entry name>/ per entry and
    /// DIR/summary.csv. Default: fits/<MANIFEST file stem>.
    #[arg(short, long, value_name = "DIR")]
    pub output: Option<PathBuf>,
    /// Overrides of every entry's scene [fit] and the manifest's
    /// [defaults]; an entry's own settings override these.
    #[command(flatten)]
    pub settings: Settings,
    /// Refit entries whose result (DIR/<name>/fit.json) exists; by default
    /// they are skipped, so that running the same command again resumes an
    /// interrupted batch.
    #[arg(long)]
    pub force: bool,
    /// Exit with status 0 even when some fits did not converge.
    #[arg(long)]
    pub allow_unconverged: bool,
    /// Exit with status 0 even when the goodness-of-fit tests (χ², runs of
    /// one-signed residuals) find that some converged fits do not describe
    /// their data (status "poor"; a kept, skipped result counts too).
    #[arg(long)]
    pub allow_poor_fit: bool,
    /// Exit with status 0 even when some unanchored fits leave the modulus
    /// scale undetermined (fit.json's "scale"; their results are kept,
    /// marked).
    #[arg(long)]
    pub allow_unanchored: bool,
    /// Run only shard i of n (0 ≤ i < n): the entries whose position in the
    /// manifest, counting from 0, is i modulo n. The summary is then
    /// DIR/summary-<i>-of-<n>.csv.
    #[arg(long, value_name = "i/n", value_parser = parse_shard, allow_hyphen_values = true)]
    pub shard: Option<Shard>,
    /// Number of fits run at the same time (threads). Default: all cores.
    #[arg(short, long, value_name = "N", value_parser = parse_jobs, allow_hyphen_values = true)]
    pub jobs: Option<usize>,
}

/// `--shard i/n`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This shard, 0 ≤ index < count.
    pub index: usize,
    /// Number of shards.
    pub count: usize,
}

impl Shard {
    fn holds(self, entry: &Entry) -> bool {
        entry.index % self.count == self.index
    }
}

fn parse_shard(text: &str) -> Result<Shard, String> {
    let usage = || {
        format!(
            "expected i/n with whole numbers 0 ≤ i < n (e.g. 0/4 … 3/4), got {:?}",
            text
        )
    };
    let (i, n) = text.trim().split_once('/').ok_or_else(usage)?;
    let index: usize = i.trim().parse().map_err(|_| usage())?;
    let count: usize = n.trim().parse().map_err(|_| usage())?;
    if count == 0 {
        return Err(format!(
            "{text:?}: the number of shards n must be at least 1"
        ));
    }
    if index >= count {
        return Err(format!(
            "{text:?}: shards count from 0, so i must be below n = {count} (0/{count} … {}/{count})",
            count - 1
        ));
    }
    Ok(Shard { index, count })
}

fn parse_jobs(text: &str) -> Result<usize, String> {
    match text.trim().parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err(format!(
            "expected a whole number of threads ≥ 1, got {text:?}"
        )),
    }
}

/// The default output folder: fits/<MANIFEST file stem>.
pub fn default_output(manifest: &Path) -> Result<PathBuf> {
    let stem = manifest
        .file_stem()
        .with_context(|| format!("manifest {} has no file name", manifest.display()))?;
    Ok(Path::new("fits").join(stem))
}

/// The summary's file name.
fn summary_name(shard: Option<Shard>) -> String {
    match shard {
        None => "summary.csv".into(),
        Some(s) => format!("summary-{}-of-{}.csv", s.index, s.count),
    }
}

/// How an entry ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Status {
    Ok,
    /// Converged, but the fit_quality verdict is poor (or invalid).
    Poor,
    /// Converged and good, but without an anchor the data leave the
    /// modulus scale undetermined (fit.json `scale`).
    Unanchored,
    Unconverged,
    Failed,
    Skipped,
}

impl Status {
    fn name(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Poor => "poor",
            Status::Unanchored => "unanchored",
            Status::Unconverged => "unconverged",
            Status::Failed => "failed",
            Status::Skipped => "skipped",
        }
    }
}

/// One row of the summary.
#[derive(Debug, Clone)]
struct EntryResult {
    name: String,
    status: Status,
    objective: Option<f64>,
    misfit_per_point: Option<f64>,
    omega_min: Option<f64>,
    omega_max: Option<f64>,
    wall_time_s: Option<f64>,
    converged: Option<bool>,
    /// The fit_quality verdict is "poor" or "invalid" (also of a kept
    /// result).
    poor_fit: bool,
    /// The data leave the modulus scale undetermined (also of a kept
    /// result).
    undetermined_scale: bool,
    wlf: Option<(f64, f64)>,
    message: String,
}

impl EntryResult {
    fn failed(entry: &Entry, message: String) -> Self {
        EntryResult {
            name: entry.name.clone(),
            status: Status::Failed,
            objective: None,
            misfit_per_point: None,
            omega_min: None,
            omega_max: None,
            wall_time_s: None,
            converged: None,
            poor_fit: false,
            undetermined_scale: false,
            wlf: None,
            message,
        }
    }

    /// Counts against the exit status as not converged (a kept result that
    /// did not converge counts too: the batch's status covers every entry).
    fn unconverged(&self) -> bool {
        self.converged == Some(false)
    }

    /// Counts against the exit status as a poor fit: converged (the
    /// convergence gate judges an unconverged one), but the goodness-of-fit
    /// tests find that it does not describe the data (a kept result too).
    fn poor(&self) -> bool {
        self.poor_fit && !self.unconverged()
    }

    /// One line for the log.
    fn line(&self) -> String {
        let mut line = format!("{}: {}", self.name, self.status.name());
        let mut details = Vec::new();
        if let Some(m) = self.misfit_per_point {
            details.push(format!("misfit per point {m:.4}"));
        }
        if let Some(t) = self.wall_time_s
            && self.status != Status::Skipped
        {
            details.push(format!("{t:.2} s"));
        }
        if !details.is_empty() {
            let _ = write!(line, " ({})", details.join(", "));
        }
        if !self.message.is_empty() {
            let _ = write!(line, " — {}", self.message);
        }
        line
    }
}

/// Runs the command.
pub fn run(args: &Args) -> Result<()> {
    // Everything is checked before the first fit starts.
    let flags = args.settings.fit_settings();
    flags.check().map_err(|e| match &e {
        FitError::InvalidSetting { key, .. } => anyhow::anyhow!("command line: --{key}: {e}"),
        _ => anyhow::anyhow!("command line: {e}"),
    })?;
    let manifest = manifest::load(&args.manifest)?;
    let dir = match &args.output {
        Some(dir) => dir.clone(),
        None => default_output(&args.manifest)?,
    };
    if dir.exists() && !dir.is_dir() {
        bail!(
            "output {} exists and is not a folder; give a folder for the batch's results",
            dir.display()
        );
    }
    // Another command's folder is refused before the lock is made in it.
    output::check_replaceable(&dir, output::Writer::Batch, args.force)?;
    let _locks = folder::lock_and_clean(&dir, args.shard, &manifest.entries)?;
    // The folder's record names the summary and every entry's folder as
    // the batch's, so that another command leaves them alone and a rerun
    // resumes.
    let names = folder::recorded_names(&manifest.entries, args.shard);
    output::claim_folder(&dir, output::Writer::Batch, args.force, &names)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.jobs.unwrap_or(0))
        .thread_name(|i| format!("rollfit-batch-{i}"))
        .build()
        .context("cannot start the worker threads")?;

    let selected: Vec<&Entry> = manifest
        .entries
        .iter()
        .filter(|e| args.shard.is_none_or(|s| s.holds(e)))
        .collect();
    let shard_note = match args.shard {
        Some(s) => format!(" (shard {}/{})", s.index, s.count),
        None => String::new(),
    };
    eprintln!(
        "batch {}: {} of {} entries{shard_note} on {} thread(s); results in {}",
        args.manifest.display(),
        selected.len(),
        manifest.entries.len(),
        pool.current_num_threads(),
        dir.display()
    );

    let progress = Progress::new(selected.len());
    let results: Vec<EntryResult> = pool.install(|| {
        selected
            .par_iter()
            .with_max_len(1)
            .map(|entry| {
                let settings = entry.settings.over(&flags.over(&manifest.defaults));
                let from = SettingsFrom::Manifest {
                    path: &args.manifest,
                    entry,
                    flags: &flags,
                };
                let result = run_entry(entry, &dir, &settings, args.force, from);
                progress.finished(&result);
                result
            })
            .collect()
    });
    progress.finish();

    let summary = dir.join(summary_name(args.shard));
    output::write_atomically(&summary, &summary_csv(&results)?)?;
    let count = |status: Status| results.iter().filter(|r| r.status == status).count();
    let unanchored = match count(Status::Unanchored) {
        0 => String::new(),
        n => format!(", {n} unanchored"),
    };
    eprintln!(
        "wrote {}: {} ok, {} poor, {} unconverged, {} failed, {} skipped{unanchored}",
        summary.display(),
        count(Status::Ok),
        count(Status::Poor),
        count(Status::Unconverged),
        count(Status::Failed),
        count(Status::Skipped)
    );

    verdict(args, &results, &summary)
}

/// The batch's exit: warnings for what the flags accept, an error listing
/// what they do not (failed entries, unconverged or poor fits).
fn verdict(args: &Args, results: &[EntryResult], summary: &Path) -> Result<()> {
    let names = |pick: &dyn Fn(&EntryResult) -> bool| {
        results
            .iter()
            .filter(|r| pick(r))
            .map(|r| r.name.as_str())
            .collect::<Vec<_>>()
    };
    let failed = names(&|r| r.status == Status::Failed);
    let unconverged = names(&|r| r.unconverged());
    let poor = names(&|r| r.poor());
    let unanchored = names(&|r| r.undetermined_scale && !r.unconverged());
    if !unanchored.is_empty() && args.allow_unanchored {
        eprintln!(
            "warning: {} fit(s) leave the modulus scale undetermined ({}); accepted because of \
             --allow-unanchored",
            unanchored.len(),
            unanchored.join(", ")
        );
    }
    if !unconverged.is_empty() && args.allow_unconverged {
        eprintln!(
            "warning: {} fit(s) did not converge ({}); accepted because of --allow-unconverged",
            unconverged.len(),
            unconverged.join(", ")
        );
    }
    if !poor.is_empty() && args.allow_poor_fit {
        eprintln!(
            "warning: {} fit(s) do not describe their data ({}); accepted because of \
             --allow-poor-fit",
            poor.len(),
            poor.join(", ")
        );
    }
    let mut problems = Vec::new();
    if !failed.is_empty() {
        problems.push(format!(
            "{} of {} entries failed ({})",
            failed.len(),
            results.len(),
            failed.join(", ")
        ));
    }
    if !unconverged.is_empty() && !args.allow_unconverged {
        problems.push(format!(
            "{} fit(s) did not converge ({}); their results are kept, marked \"converged\": \
             false (give --allow-unconverged to accept them)",
            unconverged.len(),
            unconverged.join(", ")
        ));
    }
    if !poor.is_empty() && !args.allow_poor_fit {
        problems.push(format!(
            "{} fit(s) do not describe their data ({}); their results are kept, marked \
             \"fit_quality\": {{\"verdict\": \"poor\"}} (see the reasons in the summary's \
             message column; give --allow-poor-fit to accept them)",
            poor.len(),
            poor.join(", ")
        ));
    }
    if !unanchored.is_empty() && !args.allow_unanchored {
        problems.push(format!(
            "{} fit(s) leave the modulus scale undetermined ({}); their results are kept, \
             marked \"scale\": {{\"status\": \"undetermined\"}} (anchor the scale in their \
             scenes' [fit] with E0, E_at or contact_radius, or give --allow-unanchored to accept \
             them)",
            unanchored.len(),
            unanchored.join(", ")
        ));
    }
    if !problems.is_empty() {
        bail!("{}; see {}", problems.join("; "), summary.display());
    }
    Ok(())
}

/// Runs (or skips) one entry; every error and panic becomes a failed row.
/// The row's numbers are read back from the fit.json on disk, so that the
/// summary describes the files it points to.
fn run_entry(
    entry: &Entry,
    dir: &Path,
    settings: &FitSettings,
    force: bool,
    settings_from: SettingsFrom<'_>,
) -> EntryResult {
    let folder = dir.join(&entry.name);
    let mut redo = Vec::new();
    if folder.join(FIT_JSON).is_file() && !force {
        let changed = folder::changed_inputs(entry, &folder);
        if changed.is_empty() {
            return from_disk(
                entry,
                &folder,
                Status::Skipped,
                vec!["existing result kept (--force refits)".into()],
            );
        }
        redo.push(format!(
            "note: refitted: the existing result no longer answers the entry ({})",
            changed.join("; ")
        ));
    }
    // A refit replaces the folder as a whole when it is written; until then,
    // and if it fails, the previous result stays as it was.
    let job = Job {
        scene: &entry.scene,
        data: &entry.data,
        sheet: entry.sheet.as_deref(),
        dma: entry.dma.as_ref().map(std::slice::from_ref),
        dma_input: DmaInput::default(),
        dir: &folder,
        settings,
        usage: "in the manifest, scene = \"SCENE.toml\" and data = \"DATA.csv\"",
        // The batch's own bar counts entries.
        progress: false,
        force,
        settings_from,
    };
    // The data file's notes and warnings (unit conversions, skipped rows),
    // which `rollfit fit` prints on stderr, go into the entry's message; the
    // log's other line ("fitting N point(s) …") is left out.
    let data_notes = RefCell::new(redo);
    let outcome = panic::catch_unwind(AssertUnwindSafe(|| {
        let outcome = fit_files(&job, |line| {
            if line.starts_with("note: ") || line.starts_with("warning: ") {
                data_notes.borrow_mut().push(line.to_string());
            }
        })?;
        outcome.commit(&folder, force)?;
        Ok::<_, anyhow::Error>(outcome)
    }));
    let data_notes = data_notes.into_inner();
    let with_notes = |head: String| {
        let mut parts = Vec::with_capacity(1 + data_notes.len());
        if !head.is_empty() {
            parts.push(head);
        }
        parts.extend(data_notes.iter().cloned());
        parts
    };
    match outcome {
        Ok(Ok(outcome)) => {
            let report = &outcome.report;
            // An unconverged fit is judged by the convergence gate alone.
            let (status, head) = if !report.converged {
                (
                    Status::Unconverged,
                    format!("did not converge: {}", report.stop_reason),
                )
            } else if !report.fit_quality.is_good() {
                // The reasons follow among the warnings ("fit quality: …").
                (
                    Status::Poor,
                    format!(
                        "the fit does not describe the data (fit_quality {})",
                        report.fit_quality.verdict
                    ),
                )
            } else if let Some(scale) = report.scale.as_ref().filter(|s| s.is_undetermined()) {
                (Status::Unanchored, scale.reason.clone())
            } else {
                (Status::Ok, String::new())
            };
            let mut parts = with_notes(head);
            parts.extend(report.warnings.iter().map(|w| format!("warning: {w}")));
            from_disk(entry, &folder, status, parts)
        }
        Ok(Err(error)) => EntryResult::failed(entry, with_notes(format!("{error:#}")).join("; ")),
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown cause".into());
            EntryResult::failed(
                entry,
                format!("internal error: the fit panicked ({what}); please report it"),
            )
        }
    }
}

/// The row of an entry from its fit.json in `folder`: its numbers, and for
/// a kept result (`Status::Skipped`) its convergence and verdict in the
/// message after `parts`.
fn from_disk(entry: &Entry, folder: &Path, status: Status, parts: Vec<String>) -> EntryResult {
    let digest = match Digest::read(folder) {
        Ok(digest) => digest,
        Err(e) => return EntryResult::failed(entry, e.to_string()),
    };
    let converged = digest.converged;
    let mut message = parts.join("; ");
    if status == Status::Skipped {
        if converged == Some(false) {
            let reason = digest.stop_reason.as_deref().unwrap_or("no reason given");
            message += &format!("; it did not converge: {reason}");
        }
        if digest.undetermined_scale && converged != Some(false) {
            message += "; its data leave the modulus scale undetermined (scale in fit.json)";
        }
        if digest.poor_fit && converged != Some(false) {
            message += "; it does not describe the data (fit_quality poor)";
            for reason in &digest.reasons {
                message += &format!("; fit quality: {reason}");
            }
        }
    }
    EntryResult {
        name: entry.name.clone(),
        status,
        objective: digest.objective,
        misfit_per_point: digest.misfit_per_point,
        omega_min: digest.omega_min,
        omega_max: digest.omega_max,
        wall_time_s: digest.wall_time_s,
        converged,
        poor_fit: digest.poor_fit,
        undetermined_scale: digest.undetermined_scale,
        wlf: digest.wlf,
        message,
    }
}

fn summary_csv(results: &[EntryResult]) -> Result<Vec<u8>> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(SUMMARY_COLUMNS)?;
    let cell = |x: Option<f64>| x.map(csv_text::number).unwrap_or_default();
    for r in results {
        writer.write_record([
            r.name.clone(),
            r.status.name().to_string(),
            cell(r.objective),
            cell(r.misfit_per_point),
            cell(r.omega_min),
            cell(r.omega_max),
            cell(r.wall_time_s),
            r.converged.map(|c| c.to_string()).unwrap_or_default(),
            cell(r.wlf.map(|w| w.0)),
            cell(r.wlf.map(|w| w.1)),
            r.message.clone(),
        ])?;
    }
    writer.into_inner().context("cannot finish the summary CSV")
}

/// Progress on stderr: a bar at a terminal (`progress::shown`), else one
/// line per finished entry (a log keeps every entry's line; a terminal
/// keeps those of the entries that need a look, above the bar).
enum Progress {
    Bar {
        bar: ProgressBar,
        /// Entries that failed, did not converge, or are poor or
        /// unanchored, so far.
        failures: AtomicUsize,
    },
    Lines {
        done: AtomicUsize,
        total: usize,
    },
}

impl Progress {
    fn new(total: usize) -> Self {
        if progress::shown_here() && total > 0 {
            Progress::Bar {
                bar: progress::bar(Some(total as u64), "fits"),
                failures: AtomicUsize::new(0),
            }
        } else {
            Progress::Lines {
                done: AtomicUsize::new(0),
                total,
            }
        }
    }

    fn finished(&self, result: &EntryResult) {
        match self {
            Progress::Bar { bar, failures } => {
                let mut failed = failures.load(Ordering::Relaxed);
                if matches!(
                    result.status,
                    Status::Failed | Status::Unconverged | Status::Poor | Status::Unanchored
                ) {
                    bar.println(result.line());
                    failed = failures.fetch_add(1, Ordering::Relaxed) + 1;
                }
                bar.set_message(format!(
                    "{failed} not ok; last {}: {}",
                    result.name,
                    result.status.name()
                ));
                bar.inc(1);
            }
            Progress::Lines { done, total } => {
                let k = done.fetch_add(1, Ordering::Relaxed) + 1;
                eprintln!("[{k}/{total}] {}", result.line());
            }
        }
    }

    fn finish(&self) {
        if let Progress::Bar { bar, .. } = self {
            bar.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shard_forms() {
        assert_eq!(parse_shard("0/1"), Ok(Shard { index: 0, count: 1 }));
        assert_eq!(parse_shard("3/4"), Ok(Shard { index: 3, count: 4 }));
        assert_eq!(parse_shard(" 1 / 2 "), Ok(Shard { index: 1, count: 2 }));
        for bad in [
            "4/4", "a/2", "1/0", "0/0", "-1/2", "1", "", "1/2/3", "1.0/2",
        ] {
            assert!(parse_shard(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn jobs_and_names() {
        assert_eq!(parse_jobs("2"), Ok(2));
        assert!(parse_jobs("0").is_err() && parse_jobs("x").is_err());
        assert_eq!(summary_name(None), "summary.csv");
        assert_eq!(
            summary_name(Some(Shard { index: 1, count: 4 })),
            "summary-1-of-4.csv"
        );
        assert_eq!(
            default_output(Path::new("data/example-batch.toml")).unwrap(),
            Path::new("fits").join("example-batch")
        );
    }
}
