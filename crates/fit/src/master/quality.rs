//! Is a master curve a material to trust? The verdict `rollfit master`
//! (and the Python `build_master`) gates its output on, as `fit` gates on
//! [`crate::quality`]: "good", or "poor" with each reason and what would
//! fix it.
//!
//! A master curve is the shift factors and the Prony series on the shifted
//! points; it fails in three ways, each judged from its own figures.
//!
//! 1. *The data are not causal.* The Kramers–Kronig floor — the RMS misfit,
//!    in decades, of the best non-negative Prony series on a dense τ grid
//!    to the shifted points ([`crate::causality`], computed by the front
//!    end and handed in as [`Misfits`]) — is what no linear
//!    viscoelastic solid can get below. DMA scatter of 1–5 % gives a floor
//!    of 0.004–0.021 decades, a global Kramers–Kronig violation of 50 % in
//!    E″ near the loss peak 0.04 (the causality module's measurements); the
//!    causality check warns from 0.03. The floor that refuses is that of
//!    the isotherms whose shifts the data determine ([`Floors`]): an
//!    isotherm the law placed may sit where no material puts it, which
//!    says nothing against the data. The gate refuses from
//!    [`NONCAUSAL_FLOOR`] = 0.1 decades RMS (26 % RMS): five times the 5 %
//!    scatter's floor, two and a half times the worst violation a real
//!    material curve was seen to carry, so it refuses only what no
//!    instrument scatter or poor isotherm explains — moduli in the wrong
//!    columns or units, E″ given as tan δ, or shifts that put isotherms
//!    where they cannot belong.
//! 2. *The series misses data it could follow.* The smooth Prony series
//!    (λ by marginal likelihood) is allowed to lie above the floor by the
//!    noise the smoothing averages out, a few thousandths of a decade on
//!    the bundled examples (ratio 1.03–1.07). Its RMS misfit beyond the
//!    floor by more than [`SERIES_EXCESS`] = 0.1 decades (26 %) in E′ or
//!    E″ is a series that does not describe data a causal series can
//!    follow: a fit stopped far from its optimum, or a spectrum outside
//!    the τ grid.
//! 3. *The shifts are not measured.* Superposition is a measurement only
//!    where neighbouring isotherms overlap on a slope
//!    ([`super::pairwise`]): on a plateau any shift fits, and the law, or
//!    the best-overlap placement, decides it instead of the data.
//!    - No isotherm determined (each σ about T_ref above
//!      [`super::pairwise::DETERMINED_SIGMA`]): nothing of the curve is a
//!      measurement. A curve with some undetermined isotherms is a curve:
//!      they are marked, and the window the determined ones cover is
//!      stated, but the data they do determine are not withheld.
//!    - (For a law asked for by name; `auto` rejects such candidates
//!      before choosing, [`super::law_choice`].)
//!    - WLF (alone or above a junction) with C1 above [`WLF_C1_MAX`] = 100:
//!      C1 = B/(2.303 f) with the free-volume fraction f ≈ 0.025 at T_g
//!      gives C1 ≈ 17 (Ferry's tables span about 5–35 at T_g, less above
//!      it); C1 = 100 would need f ≈ 0.004, no polymer's. C1 and C2 that
//!      large together are WLF pushed to a straight line, fitted to shifts
//!      that sit on the overlap rule's edge.
//!    - A law whose constants have a standard error of exactly 0: the
//!      covariance is degenerate, which a measurement with any scatter
//!      never gives; the constants were not determined by the shifts.
//!
//! Warnings that stay warnings (the material is usable with care): no
//! rubbery plateau (E0 undetermined: an extrapolation, named as such),
//! a law asked for that misses the shifts (the user chose it), an
//! unconverged Prony fit (the best series found; its misfit is judged by
//! 2), undetermined isotherms among determined ones (refused only under
//! `--strict`, by the front end).
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 11 (WLF constants and the free volume).

use serde::Serialize;

use super::{MasterCurve, ShiftFactors, ShiftLaw};

/// RMS Kramers–Kronig floor (decades) from which the data are refused as
/// not causal (module doc, 1).
pub const NONCAUSAL_FLOOR: f64 = 0.1;

/// RMS misfit of the series above the floor (decades) from which it does
/// not describe its data (module doc, 2).
pub const SERIES_EXCESS: f64 = 0.1;

/// Largest plausible WLF C1 (module doc, 3).
pub const WLF_C1_MAX: f64 = 100.0;

/// An RMS misfit to the shifted points per component, decades: the
/// series' or the best causal fit's (the floor).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Misfits {
    /// Of log10 E′ (or of log10 E(t) for relaxation data).
    pub storage: f64,
    /// Of log10 E″ (0 where there is no second component).
    pub loss: f64,
}

/// The verdict on a master curve, as master.json's `quality`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MasterQuality {
    /// "good" or "poor".
    pub verdict: &'static str,
    /// Why poor, each with what would fix it; empty when good.
    pub reasons: Vec<String>,
}

impl MasterQuality {
    /// True for the verdict "good".
    pub fn is_good(&self) -> bool {
        self.verdict == "good"
    }
}

/// The causal floors of a master curve's shifted points: of all of them,
/// which the series' misfit is measured against, and of the isotherms
/// whose shifts the data determine, which alone can show that the data
/// are not causal (isotherms the law or the best overlap placed can sit
/// where no material puts them without the data being at fault).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Floors {
    /// The floor of every shifted point.
    pub all: Misfits,
    /// The floor of the determined isotherms' points (equal to `all`
    /// when every isotherm is determined).
    pub determined: Misfits,
}

impl MasterCurve {
    /// The verdict on this curve, given the causal floors of its shifted
    /// points (module doc).
    pub fn quality(&self, floors: Floors) -> MasterQuality {
        let series = Misfits {
            storage: self.fit.misfit_storage,
            loss: self.fit.misfit_loss,
        };
        assess(&self.shift, Some((series, floors)))
    }
}

/// The verdict on a master curve of shift factors `shift` and, where a
/// causal floor was computed, the series' misfit and the floors (module
/// doc); relaxation data, without a floor, are judged by their shifts.
pub fn assess(shift: &ShiftFactors, series: Option<(Misfits, Floors)>) -> MasterQuality {
    let mut reasons = shift_reasons(shift);
    if let Some((misfit, floors)) = series {
        let parts = [
            (
                "E′",
                misfit.storage,
                floors.all.storage,
                floors.determined.storage,
            ),
            ("E″", misfit.loss, floors.all.loss, floors.determined.loss),
        ];
        for (name, misfit, floor, determined_floor) in parts {
            if determined_floor > NONCAUSAL_FLOOR {
                reasons.push(format!(
                    "the shifted data are not causal: no linear viscoelastic (Prony) series \
                     comes closer than {determined_floor:.3} decades RMS to {name} (limit \
                     {NONCAUSAL_FLOOR}); check the file's moduli (E′ and E″ columns, their \
                     units, E″ not tan δ) and the isotherms' shifts (with --vertical if the \
                     isotherms step in modulus)"
                ));
            } else if misfit - floor > SERIES_EXCESS {
                reasons.push(format!(
                    "the Prony series misses {name} by {misfit:.3} decades RMS where a causal \
                     series comes within {floor:.3} (limit {SERIES_EXCESS} above it); the series \
                     does not describe the data: report the file to rollfit's maintainers"
                ));
            }
        }
    }
    MasterQuality {
        verdict: if reasons.is_empty() { "good" } else { "poor" },
        reasons,
    }
}

/// Reasons of the shifts (module doc, 3).
fn shift_reasons(shift: &ShiftFactors) -> Vec<String> {
    let total = shift.shifts.len();
    if total < 2 {
        return Vec::new();
    }
    let mut reasons = Vec::new();
    let determined = shift.shifts.iter().filter(|s| s.determined).count();
    let fix = "measure isotherms through the transition (where E′ and tan δ change with \
               frequency) or closer in temperature, or use one isotherm as a `table` material \
               with known shift constants in the scene's [material.shift] (model = \"wlf\", \
               C1, C2)";
    if determined == 0 {
        reasons.push(format!(
            "no isotherm's shift is determined by the overlap (σ about T_ref above {} decade \
             for all {total}), so the law or the best-overlap placement, not the data, puts \
             every isotherm; {fix}",
            super::pairwise::DETERMINED_SIGMA
        ));
    }
    let c1 = match shift.law {
        ShiftLaw::Wlf => shift.wlf.map(|w| w.c1),
        ShiftLaw::WlfArrhenius => shift.wlf_arrhenius.map(|w| w.c1),
        _ => None,
    };
    let absurd = c1.is_some_and(|c1| c1 > WLF_C1_MAX);
    if let Some(c1) = c1.filter(|_| absurd) {
        reasons.push(format!(
            "the WLF constant C1 = {c1:.4e} is far above any polymer's (at most about \
             {WLF_C1_MAX}): WLF was stretched to a straight line through shifts the overlap \
             does not measure; {fix}"
        ));
    }
    let sigmas: &[f64] = match shift.law {
        ShiftLaw::Wlf => &shift
            .wlf
            .map_or([f64::NAN; 3], |w| [w.c1_sigma, w.c2_sigma, f64::NAN]),
        ShiftLaw::WlfArrhenius => &shift.wlf_arrhenius.map_or([f64::NAN; 3], |w| w.sigma),
        ShiftLaw::Arrhenius => &shift.arrhenius.map_or([f64::NAN; 3], |a| {
            [a.activation_energy_sigma, f64::NAN, f64::NAN]
        }),
        ShiftLaw::Free | ShiftLaw::Auto => &[],
    };
    // One reason for one cause: absurd constants usually come with σ = 0.
    if !absurd && sigmas.contains(&0.0) {
        reasons.push(format!(
            "the {} law's constants have a standard error of exactly 0: the shifts do not \
             determine them (a degenerate fit); {fix}",
            shift.law.name()
        ));
    }
    reasons
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One isotherm's shift factors: no shift reason, so the floors alone
    /// decide.
    fn one_isotherm() -> ShiftFactors {
        ShiftFactors {
            t_ref: 20.0,
            law: ShiftLaw::Free,
            reason: String::new(),
            shifts: Vec::new(),
            pairs: Vec::new(),
            wlf: None,
            arrhenius: None,
            wlf_arrhenius: None,
            rejected_laws: Vec::new(),
            warnings: Vec::new(),
        }
    }

    fn misfits(value: f64) -> Misfits {
        Misfits {
            storage: value,
            loss: value,
        }
    }

    /// Isotherms placed by the law that no causal series follows do not
    /// make the data non-causal; the determined part's floor does.
    #[test]
    fn only_the_determined_part_shows_data_not_causal() {
        let shift = one_isotherm();
        let series = misfits(0.31);
        let misplaced = Floors {
            all: misfits(0.3),
            determined: misfits(0.01),
        };
        assert!(assess(&shift, Some((series, misplaced))).is_good());
        let noncausal = Floors {
            all: misfits(0.3),
            determined: misfits(0.25),
        };
        let q = assess(&shift, Some((series, noncausal)));
        assert!(!q.is_good());
        assert!(q.reasons[0].contains("not causal") && q.reasons[0].contains("0.250"));
        // The series is still measured against the floor of every point.
        let missed = Floors {
            all: misfits(0.01),
            determined: misfits(0.01),
        };
        assert!(!assess(&shift, Some((series, missed))).is_good());
    }
}
