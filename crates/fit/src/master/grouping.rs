//! Measured points grouped into isotherms (docs/ARCHITECTURE.md, "Data
//! flow", `master`): the points of one frequency sweep, relaxation or
//! creep run at one set temperature, whose temperature is their mean. A controller's ±0.1 K scatter should
//! not split an isotherm, and "the 150 °C isotherm" is what a user names.
//!
//! The rule, in order:
//! 1. A step column (`Step`, `Set`, `Segment`: the TA TRIOS step, the
//!    Netzsch/GABO Eplexor set, a segment number) says which points were
//!    measured together: each step is one isotherm ([`group_steps`]).
//! 2. Else the distinct temperatures, sorted, split at every gap wider
//!    than [`ISOTHERM_GAP`] (1 K). A temperature programme steps by 2 K or
//!    more (typically 5–10 K) and a controller holds its set point to
//!    ±0.1 K, ±0.5 K at worst: a gap over 1 K cannot lie inside one
//!    isotherm's scatter band, and one of 1 K or less cannot separate two
//!    isotherms 2 K apart. A fixed gap rather than one taken from the
//!    data: a file of two isotherms, or of a few points each, has no
//!    scatter statistics to take it from.
//! 3. Gaps alone chain: a ramp in 0.02 K steps has no gap over 1 K and
//!    would be one "isotherm" over 200 K. So a group may span at most
//!    [`ISOTHERM_SPAN`] (2 K, four times the worst scatter): a wider one
//!    is no isotherm but a temperature sweep ([`Ramp`]). `rollfit master`
//!    refuses it (a temperature sweep at fixed frequency is not a set of
//!    isotherms); where each point can be shifted alone (`rollfit
//!    compare`) its points are grouped by exact temperature instead.
//!
//! Groups are ascending in temperature; each lists its points in the
//! order [`group_temperatures`] met them (ascending temperature, file
//! order among equal ones) or, by step, in file order.
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, Ch. 11 (isothermal frequency sweeps for reduced variables).

/// How far a DMA isotherm may lie from a temperature a free shift lists
/// and still take its shift (K).
pub const ISOTHERM_TOLERANCE: f64 = 0.5;

/// Distinct temperatures more than this apart (K) start a new isotherm.
pub const ISOTHERM_GAP: f64 = 1.0;

/// The widest an isotherm may span, max − min (K); wider is a ramp.
pub const ISOTHERM_SPAN: f64 = 2.0;

/// One isotherm: the points measured at one set temperature.
#[derive(Debug, Clone, PartialEq)]
pub struct Group {
    /// Mean temperature, °C.
    pub temperature: f64,
    /// Indices of its points in the sequence grouped.
    pub points: Vec<usize>,
}

/// Temperatures that chain into a span no isotherm has: a temperature
/// sweep (the first such run of the file).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ramp {
    /// Its points.
    pub count: usize,
    /// Its lowest and highest temperature, °C.
    pub low: f64,
    pub high: f64,
    /// Its widest gap between neighbouring temperatures, K.
    pub widest_gap: f64,
}

/// The isotherms of a file and the ramp that did not form one, if any.
#[derive(Debug, Clone, PartialEq)]
pub struct Grouping {
    /// Ascending in temperature; a ramp's points grouped by exact
    /// temperature.
    pub isotherms: Vec<Group>,
    pub ramp: Option<Ramp>,
}

/// The isotherms of points with these temperatures (those with one),
/// ascending; `points` of each index the sequence.
pub fn group_temperatures(temperatures: impl Iterator<Item = Option<f64>>) -> Vec<Group> {
    group(temperatures).isotherms
}

/// The grouping of points with these temperatures by the gaps between
/// them (rules 2 and 3 of the module doc).
pub fn group(temperatures: impl Iterator<Item = Option<f64>>) -> Grouping {
    let mut order: Vec<(usize, f64)> = temperatures
        .enumerate()
        .filter_map(|(i, t)| t.map(|t| (i, t)))
        .collect();
    order.sort_by(|a, b| a.1.total_cmp(&b.1));
    let mut runs: Vec<&[(usize, f64)]> = Vec::new();
    let mut start = 0;
    for k in 1..=order.len() {
        if k == order.len() || order[k].1 - order[k - 1].1 > ISOTHERM_GAP {
            runs.push(&order[start..k]);
            start = k;
        }
    }
    let mut isotherms = Vec::new();
    let mut ramp = None;
    for run in runs {
        let (low, high) = (run[0].1, run[run.len() - 1].1);
        if high - low <= ISOTHERM_SPAN {
            isotherms.push(isotherm(run));
            continue;
        }
        let widest_gap = run.windows(2).map(|w| w[1].1 - w[0].1).fold(0.0, f64::max);
        ramp.get_or_insert(Ramp {
            count: run.len(),
            low,
            high,
            widest_gap,
        });
        isotherms.extend(run.chunk_by(|a, b| a.1 == b.1).map(isotherm));
    }
    Grouping { isotherms, ramp }
}

/// The isotherms of points by their step (rule 1 of the module doc):
/// `steps[i]` the step of point `i`, temperatures as in [`group`]. A step
/// spanning more than [`ISOTHERM_SPAN`] is a ramp.
pub fn group_steps(temperatures: &[Option<f64>], steps: &[u32]) -> Grouping {
    let mut by_step: Vec<(u32, Vec<(usize, f64)>)> = Vec::new();
    for (i, (t, &step)) in temperatures.iter().zip(steps).enumerate() {
        let Some(t) = *t else { continue };
        match by_step.iter_mut().find(|(s, _)| *s == step) {
            Some((_, members)) => members.push((i, t)),
            None => by_step.push((step, vec![(i, t)])),
        }
    }
    let mut ramp = None;
    let mut isotherms: Vec<Group> = Vec::new();
    for (_, members) in &by_step {
        let (low, high) = members
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), m| {
                (lo.min(m.1), hi.max(m.1))
            });
        if high - low > ISOTHERM_SPAN && ramp.is_none() {
            let mut sorted: Vec<f64> = members.iter().map(|m| m.1).collect();
            sorted.sort_by(f64::total_cmp);
            ramp = Some(Ramp {
                count: members.len(),
                low,
                high,
                widest_gap: sorted.windows(2).map(|w| w[1] - w[0]).fold(0.0, f64::max),
            });
        }
        isotherms.push(isotherm(members));
    }
    isotherms.sort_by(|a, b| a.temperature.total_cmp(&b.temperature));
    Grouping { isotherms, ramp }
}

/// The isotherm of these (index, temperature) members.
fn isotherm(members: &[(usize, f64)]) -> Group {
    Group {
        temperature: members.iter().map(|m| m.1).sum::<f64>() / members.len() as f64,
        points: members.iter().map(|m| m.0).collect(),
    }
}

/// The groups of `temperatures` as (temperature °C, indices in the order
/// they were measured); one at NaN when no point has a temperature (a
/// master curve puts it at T_ref).
pub fn in_measured_order(temperatures: &[Option<f64>]) -> Vec<(f64, Vec<usize>)> {
    if temperatures.iter().all(Option::is_none) {
        return vec![(f64::NAN, (0..temperatures.len()).collect())];
    }
    measured_order(group_temperatures(temperatures.iter().copied()))
}

/// Each group's indices in the order they were measured: the grouping
/// sorts by temperature, and a controller's scatter would shuffle a sweep.
pub fn measured_order(groups: Vec<Group>) -> Vec<(f64, Vec<usize>)> {
    groups
        .into_iter()
        .map(|group| {
            let mut points = group.points;
            points.sort_unstable();
            (group.temperature, points)
        })
        .collect()
}

/// The lowest and highest of `temperatures` at `indices` (°C), for the
/// report of an isotherm's spread.
pub fn range(temperatures: &[Option<f64>], indices: &[usize]) -> (f64, f64) {
    indices
        .iter()
        .filter_map(|&i| temperatures[i])
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), t| {
            (lo.min(t), hi.max(t))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ramp in 0.02 K steps is no isotherm (it chained into one over
    /// 200 K under the old 0.5 K neighbour rule); scattered isotherms 5 K
    /// apart are; a step column splits what temperatures alone would not.
    #[test]
    fn groups_cannot_chain() {
        let ramp: Vec<Option<f64>> = (0..=10_000)
            .map(|k| Some(-50.0 + 0.02 * k as f64))
            .collect();
        let grouping = group(ramp.iter().copied());
        let r = grouping.ramp.unwrap();
        assert_eq!((r.count, r.low), (10_001, -50.0));
        assert!((r.high - 150.0).abs() < 1e-9 && (r.widest_gap - 0.02).abs() < 1e-9);
        assert_eq!(grouping.isotherms.len(), 10_001);

        // ±0.3 K scatter (a fixed pattern), isotherms 5 K apart.
        let scatter = [0.3, -0.3, 0.1, -0.25, 0.0, 0.27, -0.1, 0.2];
        let temps: Vec<Option<f64>> = (0..9)
            .flat_map(|k| scatter.map(|d| Some(-20.0 + 5.0 * k as f64 + d)))
            .collect();
        let grouping = group(temps.iter().copied());
        assert_eq!(grouping.ramp, None);
        assert_eq!(grouping.isotherms.len(), 9);
        for (k, iso) in grouping.isotherms.iter().enumerate() {
            assert!((iso.temperature - (-20.0 + 5.0 * k as f64)).abs() < 0.05);
            assert_eq!(iso.points.len(), 8);
        }

        // Two sweeps at 20 °C and 20.5 °C, told apart only by their steps.
        let temps = [Some(20.0), Some(20.1), Some(20.5), Some(20.4)];
        assert_eq!(group(temps.iter().copied()).isotherms.len(), 1);
        let by_step = group_steps(&temps, &[7, 7, 8, 8]);
        assert_eq!(by_step.isotherms.len(), 2);
        assert_eq!(by_step.isotherms[1].points, [2, 3]);
        assert_eq!(by_step.ramp, None);
        // A step holding a ramp is one.
        let by_step = group_steps(&ramp[..300], &[1; 300]);
        assert_eq!(by_step.ramp.map(|r| r.count), Some(300));
    }
}
