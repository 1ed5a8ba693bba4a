//! The checks every DMA form shares (docs/ARCHITECTURE.md, "Contract",
//! "DMA files"): ω and E′ positive and within what any solid measures, a
//! temperature within (−273.15, 1000] °C; a point with E″ ≤ 0 dropped with
//! a warning; at least one point left.

use super::form::{FieldNames, Place, RawPoint};
use super::point::DmaPoint;
use crate::error::IoError;

/// Accepted angular frequencies, rad/s.
const OMEGA_RANGE: (f64, f64) = (1e-30, 1e30);

/// The largest accepted modulus, Pa (after a shear modulus is converted).
const MAX_MODULUS: f64 = 1e13;

/// E″/E′ below which a point is dropped as unresolved.
const MIN_TAN_DELTA: f64 = 1e-9;

/// The smallest accepted storage modulus, Pa.
const MIN_STORAGE: f64 = 1e-3;

/// The checks common to all forms: ω > 0, E′ > 0 (errors); E″ ≤ 0 (point
/// dropped with a warning); at least one point left. Multiplies the moduli
/// by `factor` (2(1+ν) for shear). Returns the points kept, their lines
/// and their steps (numbered in order of appearance; `None` unless every
/// point kept has one).
pub(super) fn check_points(
    place: &Place,
    raw: Vec<RawPoint>,
    names: &FieldNames,
    factor: f64,
    warnings: &mut Vec<String>,
) -> Result<Checked, IoError> {
    let mut points = Vec::with_capacity(raw.len());
    let mut lines = Vec::with_capacity(raw.len());
    let mut labels: Vec<String> = Vec::new();
    let mut steps: Option<Vec<u32>> = Some(Vec::new());
    let mut dropped = 0usize;
    let path = place.path;
    for p in raw {
        check_point(place, &p, names, factor)?;
        // No instrument resolves tan δ below about 1e-4; a smaller E″ is
        // noise around zero (and 1/E″ weights overflow near 1e-308).
        if p.loss <= MIN_TAN_DELTA * p.storage {
            dropped += 1;
            warnings.push(format!(
                "{}, {}: {}: loss modulus {} ≤ 0 or below 1e-9 E′ (not physical; below the instrument's phase resolution?): point dropped",
                path.display(),
                place.row(p.line),
                names.loss,
                p.loss
            ));
            continue;
        }
        points.push(DmaPoint {
            omega: p.omega,
            storage: factor * p.storage,
            loss: factor * p.loss,
            temperature: p.temperature,
        });
        lines.push(p.line);
        steps = steps.zip(p.step).map(|(mut steps, label)| {
            let id = labels.iter().position(|l| *l == label).unwrap_or_else(|| {
                labels.push(label);
                labels.len() - 1
            });
            steps.push(u32::try_from(id).unwrap_or(u32::MAX));
            steps
        });
    }
    if points.is_empty() {
        let path = path.to_path_buf();
        return Err(if dropped > 0 {
            err!(
                "{}: no usable points: all {dropped} have a loss modulus ≤ 0",
                path.display()
            )
        } else {
            err!("{}: no data points", path.display())
        });
    }
    Ok((points, lines, steps))
}

/// The points kept, their lines and steps (see [`check_points`]).
pub(super) type Checked = (Vec<DmaPoint>, Vec<usize>, Option<Vec<u32>>);

/// The errors of one point (see [`check_points`]).
fn check_point(
    place: &Place,
    p: &RawPoint,
    names: &FieldNames,
    factor: f64,
) -> Result<(), IoError> {
    let row = || place.row(p.line);
    let path = || place.path.to_path_buf();
    if p.omega <= 0.0 {
        return Err(err!(
            "{}, {row}: {column}: frequency {value} is not positive",
            path().display(),
            column = names.omega,
            row = row(),
            value = p.omega
        ));
    }
    if p.storage <= 0.0 {
        return Err(err!(
            "{}, {row}: {column}: storage modulus {value} is not positive",
            path().display(),
            column = names.storage,
            row = row(),
            value = p.storage
        ));
    }
    // Far outside any DMA measurement, and beyond what the causality
    // check's τ grid and least squares can represent.
    if !(OMEGA_RANGE.0..=OMEGA_RANGE.1).contains(&p.omega) {
        return Err(err!(
            "{}, {row}: {column}: frequency {value:e} rad/s is outside 1e-30 … 1e30 rad/s, \
         beyond any master curve",
            path().display(),
            column = names.omega,
            row = row(),
            value = p.omega
        ));
    }
    for (column, value) in [(&names.storage, p.storage), (&names.loss, p.loss)] {
        if factor * value > MAX_MODULUS {
            return Err(err!(
                "{}, {row}: {column}: modulus {value:e} is above 1e13 Pa, stiffer than any solid \
         (diamond: about 1.2e12 Pa); is the column in Pa?",
                path().display(),
                row = row()
            ));
        }
    }
    if factor * p.storage < MIN_STORAGE {
        return Err(err!(
            "{}, {row}: {column}: storage modulus {value:e} is below 1e-3 Pa, softer than any \
         solid; is the column in Pa?",
            path().display(),
            column = names.storage,
            row = row(),
            value = p.storage
        ));
    }
    if let Some(t) = p.temperature
        && !(t > -273.15 && t <= 1000.0)
    {
        return Err(err!(
            "{}, {row}: temperature {value} °C is outside (−273.15, 1000] °C",
            path().display(),
            row = row(),
            value = t
        ));
    }
    Ok(())
}
