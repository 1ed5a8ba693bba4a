//! The cross-check of a temperature set's shifts: each temperature fitted
//! alone, the single-temperature tan δ(ω) curves overlapped, and the
//! shifts so found weighed against the joint fit's with the σ of both.
//!
//! - Single shifts: neighbouring single fits' ln tan δ(log10 ω) curves are
//!   overlapped ([`crate::shift::overlap`]), s_p the shift of pair p
//!   (temperatures p, p + 1), and chained: log10 a_{T_j} = Σ_{p<j} s_p
//!   − offset, the offset tying the chain to T_ref when it was measured,
//!   else to the joint fit's mean.
//! - Their σ: each pair's σ_p from the two single fits' tan δ bands
//!   ([`relative_shift_sigma`]); the pairs are fitted to different data
//!   and independent, so with log10 a_{T_j} = Σ_p c_jp s_p (c_jp =
//!   1[p < j] − 1[p < r] tied to T_ref at r, or 1[p < j] − (K − 1 − p)/K
//!   tied to the mean of K temperatures), σ_j² = Σ_p c_jp² σ_p².
//! - The test: the difference d_j = single − joint has the combined σ
//!   (σ_j² + σ_joint,j²)^{1/2}; |d_j| above [`CROSS_CHECK_SIGMAS`] times it
//!   questions the joint shift at T_j. A temperature whose single fit
//!   does not determine its shift (a flat overlap, no finite band)
//!   questions nothing.
//! - What limits a single fit, named with the temperature
//!   ([`single_fit_limits`]): few speeds, low μ, and μ written with few
//!   digits. A rig's export rounds μ to a fixed number of decimals; at μ
//!   near the last decimal the rounding is the scatter (μ = 0.0003 written
//!   to 4 decimals: a step of a third of μ, a uniform error of σ = step/√12,
//!   10 % of μ), and the single fit's band is wide there. The step is the
//!   largest power of ten of which every μ of the temperature is a whole
//!   multiple.

use super::{Fit, ShiftStart, rows_by_temperature};
use crate::data::Measurements;
use crate::params::{ModulusAnchor, ValidFitParams};
use crate::report::{CrossCheckRow, ShiftCrossCheck, ShiftRecord};
use crate::shift::index_of;
use crate::shift::overlap::{Curve, chained_shifts, relative_shift_sigma};
use crate::vertical::log10_factor;

/// How many combined σ the joint and single shifts may differ by: beyond
/// 3σ a difference arises by chance in 0.3 % of temperatures when the
/// joint shift is right (with Gaussian errors), so a set of five
/// temperatures raises a false alarm in about one fit of seventy.
pub(crate) const CROSS_CHECK_SIGMAS: f64 = 3.0;

/// Fewer distinct speeds than this at one temperature limit its single
/// fit: a fit of 4–6 effective parameters (15 speeds, 3 % noise) then has
/// a handful of residual degrees of freedom, and its tan δ curve's place
/// along log ω rests on a few points.
const FEW_SPEEDS: usize = 8;

/// A temperature whose median μ is below this fraction of the set's has
/// low μ: a tenth of the rest, where a rig's absolute resolution and
/// offsets weigh ten times more.
const LOW_FRICTION: f64 = 0.1;

/// A rounding step of μ from this fraction of the temperature's median μ
/// up is coarse: its uniform error, step/√12, is then 1.4 % of μ or more,
/// the scatter of a good rig (μ written to two significant digits or
/// fewer).
const COARSE_ROUNDING: f64 = 0.05;

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
    let mut singles = Vec::with_capacity(temps.len());
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
        singles.push(SingleFit::of(&fitted, &subset, data.friction()));
    }
    let curves: Vec<Curve> = singles.iter().map(|s| s.tan_delta.clone()).collect();
    let chain = chained_shifts(&curves).ok_or_else(|| {
        "the tan δ windows of neighbouring single-temperature fits do not overlap".to_string()
    })?;
    let pair_sigma: Vec<Option<f64>> = (0..temps.len() - 1)
        .map(|p| {
            let (lower, upper) = (&singles[p], &singles[p + 1]);
            relative_shift_sigma(
                &lower.tan_delta,
                &lower.band,
                &upper.tan_delta,
                &upper.band,
                chain[p + 1] - chain[p],
            )
        })
        .collect();
    let joint_at: Vec<f64> = temps
        .iter()
        .map(|&t| joint.log_shift_at(t).unwrap_or(f64::NAN))
        .collect();
    // Chained shifts are relative: tie them to T_ref when it was measured,
    // else to the joint fit's mean.
    let reference = index_of(&temps, start.param.t_ref());
    let (offset, method) = match reference {
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
            let difference = single - joint_at[j];
            let single_sigma = chain_sigma(&pair_sigma, j, reference);
            let joint_sigma = joint_sigma(joint, t);
            let difference_sigma = single_sigma.zip(joint_sigma).map(|(s, j)| s.hypot(j));
            CrossCheckRow {
                temperature: t,
                log_shift_joint: joint_at[j],
                log_shift_single: single,
                difference,
                single_misfit_per_point: singles[j].misfit_per_point,
                log_shift_single_sigma: single_sigma,
                log_shift_joint_sigma: joint_sigma,
                difference_sigma,
                beyond_sigma: difference_sigma
                    .is_some_and(|s| difference.abs() > CROSS_CHECK_SIGMAS * s),
                single_fit_limits: singles[j].limits.clone(),
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

/// What the cross-check keeps of one temperature's single fit.
struct SingleFit {
    /// ln tan δ against log10 ω over the fit's determined window.
    tan_delta: Curve,
    /// The 1σ of ln tan δ there (σ_tanδ/tan δ).
    band: Curve,
    misfit_per_point: f64,
    /// What limits the fit ([`single_fit_limits`]).
    limits: Vec<String>,
}

impl SingleFit {
    /// The single fit `fitted` of the temperature's rows `rows`, among the
    /// set's μ `all_friction`.
    fn of(fitted: &crate::report::FitReport, rows: &Measurements, all_friction: &[f64]) -> Self {
        let at = |f: fn(&crate::analysis::ModulusPoint) -> f64| {
            Curve::new(
                fitted
                    .curve
                    .iter()
                    .map(|p| (p.omega.log10(), f(p)))
                    .collect(),
            )
        };
        SingleFit {
            tan_delta: at(|p| p.tan_delta.ln()),
            band: at(|p| p.tan_delta_sigma / p.tan_delta),
            misfit_per_point: fitted.misfit_per_point,
            limits: single_fit_limits(rows, all_friction),
        }
    }
}

/// σ of the chained single shift at temperature `j` from the pairs' σ
/// `pair_sigma`, tied to T_ref at `reference` or to the mean (module doc);
/// None when a pair it depends on has no σ.
fn chain_sigma(pair_sigma: &[Option<f64>], j: usize, reference: Option<usize>) -> Option<f64> {
    let k = pair_sigma.len() + 1;
    let mut variance = 0.0;
    for (p, sigma) in pair_sigma.iter().enumerate() {
        let tie = match reference {
            Some(r) => f64::from(u8::from(p < r)),
            None => (k - 1 - p) as f64 / k as f64,
        };
        let weight = f64::from(u8::from(p < j)) - tie;
        if weight != 0.0 {
            variance += (weight * (*sigma)?).powi(2);
        }
    }
    Some(variance.sqrt())
}

/// The joint fit's finite 1σ of log10 a_T at `t`.
fn joint_sigma(joint: &ShiftRecord, t: f64) -> Option<f64> {
    let shifts = joint.log_shifts();
    let temperatures: Vec<f64> = shifts.iter().map(|s| s.temperature).collect();
    index_of(&temperatures, t)
        .map(|k| shifts[k].log_shift_sigma)
        .filter(|s| s.is_finite())
}

/// What limits a fit of one temperature's `rows` among a set whose μ are
/// `all_friction`: fewer than [`FEW_SPEEDS`] distinct speeds, a median μ
/// below [`LOW_FRICTION`] of the set's, μ rounded to a step of at least
/// [`COARSE_ROUNDING`] of its median.
pub(crate) fn single_fit_limits(rows: &Measurements, all_friction: &[f64]) -> Vec<String> {
    let mut limits = Vec::new();
    let speeds = rows.distinct_speeds();
    if speeds < FEW_SPEEDS {
        limits.push(format!("{speeds} speeds"));
    }
    let mu = median(rows.friction());
    let set_mu = median(all_friction);
    if mu < LOW_FRICTION * set_mu {
        limits.push(format!(
            "low μ (median {mu:.1e}, {:.0} times below the set's)",
            set_mu / mu
        ));
    }
    if let Some(step) = rounding_step(rows.friction())
        && step >= COARSE_ROUNDING * mu
    {
        limits.push(format!(
            "μ written to {} decimals (a step of {:.0} % of its median {mu:.1e})",
            -step.log10().round(),
            100.0 * step / mu
        ));
    }
    limits
}

/// The median of `values` (not empty).
fn median(values: &[f64]) -> f64 {
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    0.5 * (sorted[(n - 1) / 2] + sorted[n / 2])
}

/// The step 10^(−d) to which every value of `values` is rounded: the
/// largest power of ten (d = 0 … 12 decimals) of which each is a whole
/// multiple, up to the binary representation of a decimal (1e-6 of a
/// step, or 1e-12 of the multiple for long ones); None when no such step
/// is found (full precision).
fn rounding_step(values: &[f64]) -> Option<f64> {
    (0..=12).map(|d| 10f64.powi(-d)).find(|&step| {
        values.iter().all(|&v| {
            let multiple = v / step;
            (multiple - multiple.round()).abs() <= (1e-12 * multiple.abs()).max(1e-6)
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rounding step is the last decimal written; data at full
    /// precision have none.
    #[test]
    fn the_rounding_step_is_the_last_decimal_written() {
        let step = rounding_step(&[0.0003, 0.0011, 0.0002, 0.0007]).unwrap();
        assert!((step / 1e-4 - 1.0).abs() < 1e-12, "{step}");
        let step = rounding_step(&[0.03446, 0.02907, 0.002486]).unwrap();
        assert!((step / 1e-6 - 1.0).abs() < 1e-12, "{step}");
        assert!(rounding_step(&[0.1 / 3.0, 0.02]).is_none());
    }

    /// μ ≈ 3e-4 to four decimals at 6 speeds, among a set whose μ is
    /// about 0.03: all three limits named; a temperature at full precision
    /// only its few speeds.
    #[test]
    fn limits_name_few_speeds_low_friction_and_rounding() {
        let speeds = vec![1e-5, 1e-4, 1e-3, 1e-2, 0.03, 0.1];
        let coarse = [0.0003, 0.0004, 0.0003, 0.0002, 0.0003, 0.0002];
        let rows = Measurements::new(speeds.clone(), coarse.to_vec(), None, None).unwrap();
        // Two more temperatures at μ ≈ 0.03: the set's median is theirs.
        let mut set: Vec<f64> = (0..12).map(|i| 0.025 + 0.001 * i as f64).collect();
        set.extend(coarse);
        let limits = single_fit_limits(&rows, &set);
        assert_eq!(limits.len(), 3, "{limits:?}");
        assert!(limits[0].contains("6 speeds"), "{limits:?}");
        assert!(limits[1].contains("low μ"), "{limits:?}");
        assert!(
            limits[2].contains("4 decimals") && limits[2].contains("33 %"),
            "{limits:?}"
        );
        let fine: Vec<f64> = speeds.iter().map(|v| 0.03 + v / 7.0).collect();
        let rows = Measurements::new(speeds, fine.clone(), None, None).unwrap();
        assert!(
            single_fit_limits(&rows, &fine)
                .iter()
                .all(|l| l.contains("speeds"))
        );
    }

    /// The σ of a chained shift: tied to T_ref in the middle, the pairs on
    /// the way add in quadrature and T_ref has none; tied to the mean,
    /// every pair weighs in; an undetermined pair on the way leaves the
    /// shift undetermined.
    #[test]
    fn chained_sigmas_add_along_the_chain() {
        let pairs = [Some(0.1), Some(0.2), Some(0.3), Some(0.4)];
        assert_eq!(chain_sigma(&pairs, 2, Some(2)), Some(0.0));
        let s0 = chain_sigma(&pairs, 0, Some(2)).unwrap();
        assert!((s0 - 0.1f64.hypot(0.2)).abs() < 1e-12);
        let s4 = chain_sigma(&pairs, 4, Some(2)).unwrap();
        assert!((s4 - 0.3f64.hypot(0.4)).abs() < 1e-12);
        // Tied to the mean of five: the first temperature's weights are
        // −4/5, −3/5, −2/5, −1/5.
        let m0 = chain_sigma(&pairs, 0, None).unwrap();
        let expected =
            (0.08f64.powi(2) + 0.12f64.powi(2) + 0.12f64.powi(2) + 0.08f64.powi(2)).sqrt();
        assert!((m0 - expected).abs() < 1e-12, "{m0} {expected}");
        let gap = [Some(0.1), None, Some(0.3), Some(0.4)];
        assert!(chain_sigma(&gap, 0, Some(2)).is_none());
        assert!(chain_sigma(&gap, 4, Some(2)).is_some());
    }
}
