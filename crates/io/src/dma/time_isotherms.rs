//! The points of a relaxation or creep file ([`super::relaxation`]) and
//! their isotherms: grouping by temperature, and the checks every
//! isotherm of a time-domain file passes (times that increase; a creep
//! compliance that does not fall, since every linear viscoelastic solid's
//! creep compliance rises from the step of stress: Ferry 1980, ch. 3).
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 3.

use std::path::Path;

use rollfit_fit::master::Sweep;
use rollfit_fit::master::grouping::in_measured_order;
use rollfit_fit::master::relaxation::{RelaxationIsotherm, TimeQuantity};
use rollfit_fit::master::repeats::average_repeats;

use crate::error::{ColumnRef, IoError};

/// The largest fall of a creep compliance below an earlier value of its
/// isotherm that is read as scatter: 20 %, twenty times a DMA's per cent
/// and far beyond rounding, while a relaxation modulus or a stress put in
/// the column falls by much more over a run.
pub const COMPLIANCE_FALL: f64 = 0.2;

/// One point of a relaxation or creep file, as Young's or tensile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RelaxationPoint {
    /// Time since the step of strain or stress, s.
    pub time: f64,
    /// Young's relaxation modulus E(t), Pa, or tensile creep compliance
    /// D(t), 1/Pa.
    pub value: f64,
    /// °C, when the file gives one.
    pub temperature: Option<f64>,
}

/// All rows with a temperature or none; increasing times in each isotherm
/// (file order), else the two lines where they stop; a creep compliance
/// that does not fall (module doc).
pub(super) fn check_isotherms(
    path: &Path,
    (quantity, column): (TimeQuantity, &ColumnRef),
    points: &[RelaxationPoint],
    lines: &[usize],
) -> Result<(), IoError> {
    let with_t = points.iter().filter(|p| p.temperature.is_some()).count();
    if with_t > 0 && with_t < points.len() {
        return Err(err!(
            "{}: {missing} of {total} rows have no temperature: cannot tell which isotherm they \
         belong to",
            path.display(),
            missing = points.len() - with_t,
            total = points.len()
        ));
    }
    for (temperature, indices) in groups(points) {
        // Equal times are rounded stamps, averaged by [`time_isotherms`];
        // a time that falls is a new run.
        let falls = indices
            .windows(2)
            .position(|w| points[w[1]].time < points[w[0]].time);
        if let Some(k) = falls.map(|j| j + 1) {
            let (a, b) = (indices[k - 1], indices[k]);
            return Err(err!(
                "{}: the {} isotherm at {temperature:.2} °C has times that do not increase: \
         line {} (t = {:e} s) is followed by line {} (t = {:e} s); a {} run's times \
         increase from the step of {}, and a repeated run is another isotherm",
                path.display(),
                quantity.name(),
                lines[a],
                points[a].time,
                lines[b],
                points[b].time,
                quantity.name(),
                if quantity == TimeQuantity::Creep {
                    "stress"
                } else {
                    "strain"
                }
            ));
        }
        if quantity == TimeQuantity::Creep {
            check_rising(path, column, temperature, (points, lines), &indices)?;
        }
    }
    Ok(())
}

/// A creep isotherm (`indices` in time order) whose compliance falls more
/// than [`COMPLIANCE_FALL`] below the highest earlier value is refused,
/// naming that value's line and the first line below the limit.
fn check_rising(
    path: &Path,
    column: &ColumnRef,
    temperature: f64,
    (points, lines): (&[RelaxationPoint], &[usize]),
    indices: &[usize],
) -> Result<(), IoError> {
    let mut highest: Option<usize> = None;
    for &i in indices {
        let value = points[i].value;
        match highest {
            Some(h) if value < (1.0 - COMPLIANCE_FALL) * points[h].value => {
                return Err(err!(
                    "{}: column {column}: the creep isotherm at {temperature:.2} °C falls with time: line {} \
         (D = {:e} 1/Pa) is followed at a later time by line {} (D = {:e} 1/Pa), {:.0} % lower; \
         a creep compliance never decreases with time (it rises from the step of stress), so \
         this column is not a creep compliance (a modulus or a stress?)",
                    path.display(),
                    lines[h],
                    points[h].value,
                    lines[i],
                    value,
                    100.0 * (1.0 - value / points[h].value),
                ));
            }
            Some(h) if value <= points[h].value => {}
            _ => highest = Some(i),
        }
    }
    Ok(())
}

/// The isotherms of `points` as (temperature °C, indices in file order);
/// one at NaN when the file has no temperatures (a master curve puts it at
/// T_ref). The rule: [`rollfit_fit::master::grouping`].
pub fn groups(points: &[RelaxationPoint]) -> Vec<(f64, Vec<usize>)> {
    let temperatures: Vec<Option<f64>> = points.iter().map(|p| p.temperature).collect();
    in_measured_order(&temperatures)
}

/// The isotherms of the points of the file `path` (grouped as [`groups`]
/// does), each run of points at one time averaged into one point
/// ([`rollfit_fit::master::repeats`]: time stamps printed with too few
/// digits repeat; the reader refused times that fall), each average noted
/// in `notes`. A file without temperatures is one isotherm at `untimed`.
pub fn time_isotherms(
    path: &Path,
    points: &[RelaxationPoint],
    notes: &mut Vec<String>,
    untimed: f64,
) -> Vec<RelaxationIsotherm> {
    let mut isotherms = Vec::new();
    for (temperature, indices) in groups(points) {
        let temperature = if temperature.is_nan() {
            untimed
        } else {
            temperature
        };
        let averaged = average_repeats(&indices, |i| points[i].time, &[&|i| points[i].value]);
        if averaged.merged_any() {
            notes.push(format!(
                "{}: isotherm at {temperature:.2} °C: {} points at repeated times averaged into {}",
                path.display(),
                averaged.repeated_points,
                averaged.repeated_runs
            ));
        }
        isotherms.push(RelaxationIsotherm::from_averaged(temperature, averaged));
    }
    isotherms
}
