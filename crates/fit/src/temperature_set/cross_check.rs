//! The cross-check of a temperature set's shifts: each temperature fitted
//! alone, and the single-temperature tan δ(ω) curves overlapped.

use super::{Fit, ShiftStart, rows_by_temperature};
use crate::data::Measurements;
use crate::params::{ModulusAnchor, ValidFitParams};
use crate::report::{CrossCheckRow, ShiftCrossCheck, ShiftRecord};
use crate::shift::index_of;
use crate::shift::overlap::{Curve, chained_shifts};
use crate::vertical::log10_factor;

/// The cross-check of the joint fit's shift `joint`: single-temperature
/// fits (by `single_fit`) overlapped by tan δ. `Err` carries a reason the
/// check could not be made (reported as a warning, not a failure of the
/// joint fit).
pub(crate) fn cross_check(
    data: &Measurements,
    params: &ValidFitParams,
    joint: Option<&ShiftRecord>,
    start: &ShiftStart,
    single_fit: impl Fit,
) -> Result<ShiftCrossCheck, String> {
    let joint = joint.ok_or_else(|| "the joint fit has no shift".to_string())?;
    let temps = start.param.temperatures().to_vec();
    let rows = rows_by_temperature(data, &temps);
    let (start_log_shift, _) = start.param.log_shifts(&start.theta);
    let mut curves = Vec::with_capacity(temps.len());
    let mut misfits = Vec::with_capacity(temps.len());
    for (j, r) in rows.iter().enumerate() {
        let pick = |col: &[f64]| r.iter().map(|&i| col[i]).collect::<Vec<f64>>();
        let subset = Measurements::new(
            pick(data.speeds()),
            pick(data.friction()),
            data.sigma().map(pick),
            None,
        )
        .map_err(|e| e.to_string())?;
        // One temperature's rows carry no temperature column: no shift, and
        // so no cross-check, is fitted to them.
        let mut single = params.clone();
        // |E_T(ω_a/a_T)| = b_T |E_ref(ω_a)|: the anchor moves with the start
        // shift (and the vertical factor, 1 without).
        let log_b =
            log10_factor(params.shift.vertical.as_ref(), temps[j]).map_err(|e| e.to_string())?;
        single.anchor = params.anchor.map(|a| ModulusAnchor {
            omega: a.omega / 10f64.powf(start_log_shift[j]),
            modulus: a.modulus * 10f64.powf(log_b),
            ..a
        });
        let fitted = single_fit(&subset, &single)
            .map_err(|e| format!("the fit of T = {} °C alone failed: {e}", temps[j]))?;
        misfits.push(fitted.misfit_per_point);
        curves.push(Curve::new(
            fitted
                .curve
                .iter()
                .map(|p| (p.omega.log10(), p.tan_delta.ln()))
                .collect(),
        ));
    }
    let chain = chained_shifts(&curves).ok_or_else(|| {
        "the tan δ windows of neighbouring single-temperature fits do not overlap".to_string()
    })?;
    let joint_at: Vec<f64> = temps
        .iter()
        .map(|&t| joint.log_shift_at(t).unwrap_or(f64::NAN))
        .collect();
    // Chained shifts are relative: tie them to T_ref when it was measured,
    // else to the joint fit's mean.
    let (offset, method) = match index_of(&temps, start.param.t_ref()) {
        Some(r) => (
            chain[r],
            "single-temperature fits overlapped by ln tan δ(log10 ω), neighbour to neighbour, \
             relative to T_ref",
        ),
        None => (
            chain.iter().zip(&joint_at).map(|(c, j)| c - j).sum::<f64>() / temps.len() as f64,
            "single-temperature fits overlapped by ln tan δ(log10 ω), neighbour to neighbour; \
             T_ref was not measured, so the chain is aligned to the joint fit's mean",
        ),
    };
    let rows: Vec<CrossCheckRow> = temps
        .iter()
        .enumerate()
        .map(|(j, &t)| {
            let single = chain[j] - offset;
            CrossCheckRow {
                temperature: t,
                log_shift_joint: joint_at[j],
                log_shift_single: single,
                difference: single - joint_at[j],
                single_misfit_per_point: misfits[j],
            }
        })
        .collect();
    let n = rows.len() as f64;
    let rms_difference = (rows.iter().map(|r| r.difference.powi(2)).sum::<f64>() / n).sqrt();
    let max_difference = rows.iter().fold(0.0f64, |m, r| m.max(r.difference.abs()));
    Ok(ShiftCrossCheck {
        method: method.into(),
        temperatures: rows,
        rms_difference,
        max_difference,
    })
}
