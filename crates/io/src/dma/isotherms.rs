//! A DMA file's points as the isotherms of a master curve or a joint fit:
//! grouped by [`rollfit_fit::master::grouping`] (by step, else by
//! temperature), a temperature ramp refused, sweeps at one temperature
//! from several files or result blocks merged into one isotherm ordered
//! by frequency, and repeated frequencies averaged
//! ([`rollfit_fit::master::repeats`]), each merge noted. Here because
//! only the reader knows the file and line of each point, which every
//! refusal names.

use std::fmt;
use std::path::Path;

use rollfit_fit::master::grouping::{ISOTHERM_GAP, ISOTHERM_SPAN, measured_order, range};
use rollfit_fit::master::pipeline::PipelineError;
use rollfit_fit::master::repeats::average_repeats;
use rollfit_fit::master::{Isotherm, Sweep, sweep_turn};

use super::{DmaData, DmaFile};
use crate::error::IoError;

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

/// Groups the points of `data` into isotherms (module doc), refusing a
/// temperature ramp and an isotherm whose frequencies do not run one way:
/// what `rollfit master`, a scene's `model = "dma"` and a joint fit's
/// `dma` share. A file without temperatures is one isotherm at `untimed`
/// (None: refused). Errors name the file and, where one point is at
/// fault, its line.
pub fn group_isotherms(mut data: DmaData, untimed: Option<f64>) -> Result<DmaIsotherms, IoError> {
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
        measured_order(grouping.isotherms)
    };
    let mut sets = Vec::with_capacity(groups.len());
    let mut kept = Vec::with_capacity(groups.len());
    let mut merges = Vec::new();
    for (temperature, mut indices) in groups {
        if let Some(merged) = merge_files(&data, temperature, &mut indices) {
            data.notes.push(merged.clone());
            merges.push(merged);
        }
        let (isotherm, firsts, note) = average_repeats_of(&data, temperature, &indices);
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

/// The pipeline's refusal of the isotherms of the DMA file `path`
/// (frequency, relaxation or creep alike), behind the file's name.
pub fn master_refused(path: &Path, error: PipelineError) -> IoError {
    match error {
        PipelineError::Settings(error) => {
            err!("DMA file {}", path.display()).caused_by(err!("{error}"))
        }
        PipelineError::Build(error) => {
            err!("DMA file {}: master curve", path.display()).caused_by(err!("{error}"))
        }
    }
}

impl DmaIsotherms {
    /// The lowest and highest measured temperature of each isotherm (°C,
    /// in the order of the isotherms; empty for a file without
    /// temperatures).
    pub fn ranges(&self) -> Vec<(f64, f64)> {
        let temperatures = self.data.temperatures_of_points();
        match temperatures.iter().any(Option::is_some) {
            true => (self.indices.iter())
                .map(|i| range(&temperatures, i))
                .collect(),
            false => Vec::new(),
        }
    }
}

/// Orders the points `indices` of an isotherm by frequency when they come
/// from more than one file or result block (sweeps at one temperature
/// merged), saying so.
fn merge_files(data: &DmaData, temperature: f64, indices: &mut [usize]) -> Option<String> {
    let mut from: Vec<&DmaFile> = indices.iter().filter_map(|&i| data.source_of(i)).collect();
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
fn average_repeats_of(
    data: &DmaData,
    temperature: f64,
    indices: &[usize],
) -> (Isotherm, Vec<usize>, Option<String>) {
    let point = |i: usize| &data.points[i];
    let averaged = average_repeats(
        indices,
        |i| point(i).omega,
        &[&|i| point(i).storage, &|i| point(i).loss],
    );
    let note = averaged.merged_any().then(|| {
        format!(
            "isotherm at {temperature:.2} °C: {} points at repeated frequencies averaged into {}",
            averaged.repeated_points, averaged.repeated_runs
        )
    });
    let firsts = averaged.firsts.clone();
    (Isotherm::from_averaged(temperature, averaged), firsts, note)
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
