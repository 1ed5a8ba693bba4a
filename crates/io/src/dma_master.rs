//! A DMA file, or several (one per isotherm, [`crate::dma::files`]), to a
//! master curve: read the files (any form [`crate::dma`] accepts,
//! docs/ARCHITECTURE.md, "Contract", "DMA files"), group their points into
//! isotherms, and run `rollfit_fit::master` on them.
//!
//! Sweeps at one temperature from several files are merged into one
//! isotherm ordered by frequency (the fit takes one isotherm per
//! temperature), and points at a repeated frequency within an isotherm —
//! a frequency printed with too few digits, or two sweeps merged — are
//! averaged into one: E′ and E″ as arithmetic means, which at equal ω is
//! what a least-squares fit through both would see. Each merge is noted. Shared by
//! `rollfit master` and a scene's `[material] model = "dma"`, so that both
//! give the same series. Nothing is written here: `rollfit master` writes
//! the folder, [`crate::material_file`] its material.toml.

use std::fmt;

use rollfit_fit::master::{
    Isotherm, MasterCurve, MasterSettings, ValidMasterSettings, build_master_curve, sweep_turn,
};

pub use crate::dma::files::DmaInput;
use crate::dma::{DmaData, ISOTHERM_GAP, ISOTHERM_SPAN, range};
use crate::error::IoError;

/// A master curve built from a DMA file.
pub struct DmaMaster {
    /// The file as read (Young's moduli).
    pub data: DmaData,
    /// The checked settings (T_ref resolved).
    pub settings: ValidMasterSettings,
    /// Shift factors, shifted points and the Prony series.
    pub master: MasterCurve,
    /// The lowest and highest measured temperature of each isotherm (°C,
    /// in the order of the isotherms; empty for a file without
    /// temperatures).
    pub ranges: Vec<(f64, f64)>,
    /// Sweeps at one temperature merged into one isotherm, as said.
    pub merged: Vec<String>,
}

/// Reads `input` and builds its master curve ([`read_isotherms`], then
/// the master-curve fit). `poisson` converts shear moduli (E = 2(1+ν)G).
/// Errors name the file and, where one point is at fault, its line.
pub fn build(
    input: &DmaInput,
    poisson: f64,
    settings: &MasterSettings,
) -> Result<DmaMaster, IoError> {
    build_told(input, poisson, settings, |_| {})
}

/// [`build`], telling `on_read` the file as read (its notes and warnings:
/// rows skipped, units converted) before the master curve is fitted, so
/// that a refusal of the fit can be read next to the rows that explain it.
pub fn build_told(
    input: &DmaInput,
    poisson: f64,
    settings: &MasterSettings,
    on_read: impl FnOnce(&DmaData),
) -> Result<DmaMaster, IoError> {
    // No temperatures: the file is one curve, taken at T_ref.
    let untimed = settings.t_ref.unwrap_or(rollfit_fit::master::DEFAULT_T_REF);
    let DmaIsotherms {
        data,
        isotherms,
        indices,
        merged,
    } = read_isotherms(input, poisson, Some(untimed))?;
    on_read(&data);
    let path = data.path.as_path();
    let ranges = match data.points.iter().any(|p| p.temperature.is_some()) {
        true => indices.iter().map(|i| range(&data.points, i)).collect(),
        false => Vec::new(),
    };
    let in_file = |source: IoError| err!("DMA file {}", path.display()).caused_by(source);
    let valid = settings
        .check(&isotherms)
        .map_err(|error| in_file(err!("{error}")))?;
    let master = build_master_curve(&isotherms, &valid).map_err(|error| {
        err!("DMA file {}: master curve", path.display()).caused_by(err!("{error}"))
    })?;
    Ok(DmaMaster {
        data,
        settings: valid.resolved(&master.shift),
        master,
        ranges,
        merged,
    })
}

/// A DMA file read and grouped into isotherms.
pub struct DmaIsotherms {
    /// The file as read (Young's moduli).
    pub data: DmaData,
    /// The isotherms, ascending in temperature, each in file order.
    pub isotherms: Vec<Isotherm>,
    /// For each isotherm, the indices of its points in `data.points` (and
    /// `data.lines`), in the isotherm's order.
    pub indices: Vec<Vec<usize>>,
    /// Sweeps at one temperature from several files or result blocks,
    /// merged into one isotherm: what was merged (also among the notes).
    pub merged: Vec<String>,
}

/// Reads `input` and groups its points into isotherms ([`crate::dma::isotherm`]: by step,
/// else by temperature), refusing a temperature ramp and an isotherm
/// whose frequencies do not run one way: what `rollfit master`, a scene's
/// `model = "dma"` and a joint fit's `dma` share. `poisson` converts shear
/// moduli (E = 2(1+ν)G). A file without temperatures is one isotherm at
/// `untimed` (None: refused). Errors
/// name the file and, where one point is at fault, its line.
pub fn read_isotherms(
    input: &DmaInput,
    poisson: f64,
    untimed: Option<f64>,
) -> Result<DmaIsotherms, IoError> {
    let mut data = input
        .read(poisson, None)
        .map_err(|e| err!("{error}", error = e))?;
    let path = data.path.clone();
    let path = path.as_path();
    let with_t = data
        .points
        .iter()
        .filter(|p| p.temperature.is_some())
        .count();
    let groups: Vec<(f64, Vec<usize>)> = if with_t == 0 {
        let t = untimed.ok_or_else(|| {
            err!(
                "DMA file {}: no point has a temperature: a joint fit places each DMA point at its \
         temperature; add a T column, or give `T_ref` (the temperature of this one curve)",
                path.display()
            )
        })?;
        vec![(t, (0..data.points.len()).collect())]
    } else if with_t < data.points.len() {
        return Err(err!(
            "DMA file {}: {missing} of {total} points have no temperature: cannot tell which \
         isotherm they belong to",
            path.display(),
            missing = data.points.len() - with_t,
            total = data.points.len()
        ));
    } else {
        let grouping = data.grouping();
        if let Some(ramp) = grouping.ramp {
            return Err(err!(
                "DMA file {}: this looks like a temperature ramp, not isotherms: {count} points from \
         {low:.2} to {high:.2} °C with no gap over {gap} K between neighbouring temperatures \
         (the widest is {widest_gap:.2} K), where an isotherm spans at most {span} K. A \
         temperature sweep at fixed frequency is not a set of isotherms: rollfit master needs \
         frequency sweeps at several fixed temperatures (a column `Step`, `Set` or `Segment` \
         says which points form one)",
                path.display(),
                count = ramp.count,
                gap = ISOTHERM_GAP,
                high = ramp.high,
                low = ramp.low,
                span = ISOTHERM_SPAN,
                widest_gap = ramp.widest_gap
            ));
        }
        grouping
            .isotherms
            .into_iter()
            .map(|iso| {
                // File order: the grouping sorts by temperature, and a
                // controller's scatter would shuffle a sweep.
                let mut points = iso.points;
                points.sort_unstable();
                (iso.temperature, points)
            })
            .collect()
    };
    let mut sets = Vec::with_capacity(groups.len());
    let mut kept = Vec::with_capacity(groups.len());
    let mut merges = Vec::new();
    for (temperature, mut indices) in groups {
        if let Some(merged) = merge_files(&data, temperature, &mut indices) {
            data.notes.push(merged.clone());
            merges.push(merged);
        }
        let (isotherm, firsts, note) = average_repeats(&data, temperature, &indices);
        data.notes.extend(note);
        check_monotone(&data, temperature, &firsts).map_err(|source| {
            err!(
                "DMA file {}",
                (data.file_of(firsts[0]).to_path_buf()).display()
            )
            .caused_by(source)
        })?;
        sets.push(isotherm);
        kept.push(firsts);
    }
    Ok(DmaIsotherms {
        merged: merges,
        data,
        isotherms: sets,
        indices: kept,
    })
}

/// Orders the points `indices` of an isotherm by frequency when they come
/// from more than one file or result block (sweeps at one temperature
/// merged), saying so.
fn merge_files(data: &DmaData, temperature: f64, indices: &mut [usize]) -> Option<String> {
    let mut from: Vec<&crate::dma::DmaFile> =
        indices.iter().filter_map(|&i| data.source_of(i)).collect();
    from.dedup();
    if from.len() < 2 {
        return None;
    }
    let names: Vec<String> = from.iter().map(|f| f.name()).collect();
    indices.sort_by(|&a, &b| data.points[a].omega.total_cmp(&data.points[b].omega));
    Some(format!(
        "{} sweeps at {temperature:.2} °C ({}) merged into one isotherm, ordered by frequency",
        names.len(),
        names.join(", ")
    ))
}

/// The isotherm of the points `indices` (in sweep order), each run of
/// points at one frequency averaged into one point; the index of each
/// run's first point; a note when any run had more than one point.
fn average_repeats(
    data: &DmaData,
    temperature: f64,
    indices: &[usize],
) -> (Isotherm, Vec<usize>, Option<String>) {
    let mut isotherm = Isotherm {
        temperature,
        omega: Vec::new(),
        storage: Vec::new(),
        loss: Vec::new(),
    };
    let mut firsts = Vec::new();
    let runs = indices.chunk_by(|&a, &b| data.points[a].omega == data.points[b].omega);
    for run in runs {
        let mean = |f: fn(&crate::dma::DmaPoint) -> f64| {
            run.iter().map(|&i| f(&data.points[i])).sum::<f64>() / run.len() as f64
        };
        isotherm.omega.push(data.points[run[0]].omega);
        isotherm.storage.push(mean(|p| p.storage));
        isotherm.loss.push(mean(|p| p.loss));
        firsts.push(run[0]);
    }
    let note = (firsts.len() < indices.len()).then(|| {
        format!(
            "isotherm at {temperature:.2} °C: {} points at repeated frequencies averaged into {}",
            indices.len() - isotherm.omega.len() + runs_repeated(data, indices),
            runs_repeated(data, indices)
        )
    });
    (isotherm, firsts, note)
}

/// The number of runs of more than one point at one frequency.
fn runs_repeated(data: &DmaData, indices: &[usize]) -> usize {
    indices
        .chunk_by(|&a, &b| data.points[a].omega == data.points[b].omega)
        .filter(|run| run.len() > 1)
        .count()
}

/// Refuses an isotherm whose frequencies neither rise nor fall
/// throughout, naming the lines where the sweep turns.
fn check_monotone(data: &DmaData, temperature: f64, indices: &[usize]) -> Result<(), IoError> {
    let omega: Vec<f64> = indices.iter().map(|&i| data.points[i].omega).collect();
    let Some(k) = sweep_turn(&omega) else {
        return Ok(());
    };
    let at = |j: usize| TurnPoint {
        line: data.lines.get(indices[j]).copied(),
        index: indices[j],
        omega: omega[j],
    };
    let turn: Vec<TurnPoint> = (k - 1..(k + 2).min(omega.len()))
        .filter(|&j| j <= k || omega[k] != omega[k - 1])
        .map(at)
        .collect();
    Err(err!(
        "the isotherm at {temperature:.2} °C has frequencies that are not monotone ({}): a sweep \
         runs up or down once; split a repeated sweep into its own temperature or remove the \
         repeated points",
        turn_list(&turn)
    ))
}

/// A point of an isotherm where its sweep turns, as a message names it:
/// `line 13: ω = 5.2e0 rad/s`, or `point 7: …` where the file has no line
/// for it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct TurnPoint {
    /// The point's file line, if known.
    line: Option<usize>,
    /// Its index among the file's points, from 0.
    index: usize,
    /// Its frequency, rad/s.
    omega: f64,
}

impl fmt::Display for TurnPoint {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(l) => write!(f, "line {l}: ω = {:e} rad/s", self.omega),
            None => write!(f, "point {}: ω = {:e} rad/s", self.index + 1, self.omega),
        }
    }
}

/// `line 12: ω = …, line 13: ω = …`.
fn turn_list(turn: &[TurnPoint]) -> String {
    let listed: Vec<String> = turn.iter().map(TurnPoint::to_string).collect();
    listed.join(", ")
}
