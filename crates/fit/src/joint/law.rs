//! The shift law of a joint fit with `shift = "auto"`, chosen on both
//! parts together.
//!
//! Each part measures shifts between pairs of temperatures: the DMA
//! isotherms by their overlaps (the determined pairs of
//! [`crate::master::pairwise`], s_ij ± σ_ij), the rolling data by the free
//! shifts of the rolling fit alone (neighbouring temperatures k, k+1:
//! s = x_{k+1} − x_k, σ = (σ_k² + σ_{k+1}²)^½, the fit's 1σ of each about
//! its T_ref). Pooled, they are the observations
//! [`crate::master::law_choice`] tests laws on, as `rollfit master` does
//! for isotherms: WLF when its χ² test passes, else the two-branch law or
//! Arrhenius, else free shifts. A part that determines no shift adds no
//! pair; the law is then the other part's.
//!
//! The joint fit fits the chosen law's constants (or the free shifts) to
//! both parts at once; this choice only decides which.

use crate::master::ShiftLaw;
use crate::master::law_choice::choose;
use crate::master::pairwise::PairVerdict;
use crate::master::temperature_law::PairObservation;
use crate::params::ShiftKind;
use crate::shift::ShiftRecord;

use super::alone::DmaAlone;

/// The law `auto` takes for the joint fit, with a sentence saying why.
pub(crate) fn joint_law(
    alone: &DmaAlone,
    rolling_free: Option<&ShiftRecord>,
    t_ref: f64,
) -> (ShiftKind, String) {
    let mut pairs = dma_pairs(alone);
    let dma_count = pairs.len();
    pairs.extend(rolling_free.map(rolling_pairs).unwrap_or_default());
    let rolling_count = pairs.len() - dma_count;
    let mut measured: Vec<f64> = pairs.iter().flat_map(|p| [p.t_lower, p.t_upper]).collect();
    measured.sort_by(f64::total_cmp);
    measured.dedup();
    let counted =
        format!("{dma_count} pair(s) of DMA isotherms and {rolling_count} of rolling temperatures");
    if pairs.is_empty() || measured.len() < 3 {
        return (
            ShiftKind::Free,
            format!(
                "shift law free: the parts together measure too few shifts to test a law \
                 ({counted})"
            ),
        );
    }
    match choose(ShiftLaw::Auto, &pairs, &measured, &measured, t_ref) {
        Ok(choice) => {
            let kind = match choice.law {
                ShiftLaw::Wlf => ShiftKind::Wlf,
                ShiftLaw::Arrhenius => ShiftKind::Arrhenius,
                _ => ShiftKind::Free,
            };
            let two_branch = if choice.law == ShiftLaw::WlfArrhenius {
                "; a joint fit has no two-branch law, so it fits the shifts free"
            } else {
                ""
            };
            (
                kind,
                format!(
                    "shift law {}: chosen on both parts' shifts together ({counted}; {}: {}{two_branch})",
                    super::start::kind_name(kind),
                    choice.law.name(),
                    choice.reason
                ),
            )
        }
        Err(e) => (
            ShiftKind::Free,
            format!(
                "shift law free: no law could be tested on both parts' shifts ({counted}: {e})"
            ),
        ),
    }
}

/// The DMA isotherms' determined pairs.
fn dma_pairs(alone: &DmaAlone) -> Vec<PairObservation> {
    let Some(master) = &alone.master else {
        return Vec::new();
    };
    let temps: Vec<f64> = master.shift.shifts.iter().map(|s| s.temperature).collect();
    master
        .shift
        .pairs
        .iter()
        .filter(|p| p.verdict == PairVerdict::Determined && p.sigma.is_finite() && p.sigma > 0.0)
        .map(|p| PairObservation {
            t_lower: temps[p.lower],
            t_upper: temps[p.upper],
            shift: p.shift,
            sigma: p.sigma,
        })
        .collect()
}

/// The rolling fit's free shifts as neighbour pairs (module doc).
fn rolling_pairs(record: &ShiftRecord) -> Vec<PairObservation> {
    record
        .log_shifts()
        .windows(2)
        .filter_map(|w| {
            let sigma = w[0].log_shift_sigma.hypot(w[1].log_shift_sigma);
            (sigma.is_finite() && sigma > 0.0).then_some(PairObservation {
                t_lower: w[0].temperature,
                t_upper: w[1].temperature,
                shift: w[1].log_shift - w[0].log_shift,
                sigma,
            })
        })
        .collect()
}
