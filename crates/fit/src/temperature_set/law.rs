//! `shift = "auto"`: the temperature law the data support.
//!
//! The candidates, in order of preference: WLF (two constants, the
//! customary law of amorphous polymers above T_g, and one that
//! extrapolates), Arrhenius (one constant: below T_g, or a secondary
//! relaxation), and the free shifts (one log10 a_T per temperature but
//! T_ref, which follow any law but say nothing between and beyond the
//! measured temperatures). The first law the data do not reject is chosen;
//! when both are rejected, the free shifts are.
//!
//! Each law is nested in the free shifts (the free shifts can take the
//! law's values at every temperature), so whether a law describes the data
//! is a test of a nested model. The law and the free shifts are fitted
//! jointly with the master curve at the same smoothness weight λ and on the
//! same τ grid ([`crate::driver`]), so their objectives V (weighted misfit
//! plus the same penalty) differ by what the shifts explain. With
//! k = (n − 1) − p extra parameters of the free shifts (n temperatures, p
//! the law's constants; k is taken as at least 1, so that with three
//! temperatures WLF, which has as many constants as there are free shifts,
//! must still come within one parameter's worth of them), the extra sum of
//! squares
//!
//!   F = [(V_law − V_free)/k] / [χ²_free/(N − t_free)]
//!
//! follows Fisher's F(k, N − t_free) distribution when the law holds
//! (N points, t_free the effective parameters of the free fit). The law is
//! rejected when p = P(F_{k, N−t} ≥ F) < [`ALPHA`].
//!
//! Why a test and not AICc: the test fixes how often a true law is lost.
//! With AIC(c) a law is rejected whenever the k free parameters lower χ²
//! by more than about 2k, which a true law suffers with probability
//! P(χ²_k > 2k), 8 % for k = 5 (seven temperatures): one WLF data set in
//! twelve would get free shifts. At α = 1 % the preference for the law,
//! which extrapolates and has two numbers a user can compare, costs a
//! real deviation a little power; a deviation that matters (the issue's
//! 0.35 decade at 1 % noise) gives p far below 1e-10. Why F and not χ²:
//! the denominator is the free fit's own residual variance, so the test
//! holds without a sigma column (σ estimated from the residuals) and is not
//! fooled by a measured σ somewhat too small, or by a model error common to
//! both fits, which would inflate a χ² difference.
//!
//! # References
//! - G.A.F. Seber, C.J. Wild, *Nonlinear Regression*, Wiley 1989, §5.3
//!   (the extra-sum-of-squares F test of nested nonlinear models).
//! - K.P. Burnham, D.R. Anderson, *Model Selection and Multimodel
//!   Inference*, 2nd ed., Springer 2002, §2.4 (AICc), for the comparison.

use serde::Serialize;
use statrs::distribution::{ContinuousCDF, FisherSnedecor};

use crate::params::ShiftSubstitute;

/// Significance level below which a law is rejected against the free
/// shifts.
pub const ALPHA: f64 = 0.01;

/// A joint fit of a temperature set under one law, as the choice sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LawFit {
    /// "wlf", "arrhenius" or "free".
    pub model: &'static str,
    /// Constants of the law (free shifts: temperatures − 1).
    pub parameters: usize,
    /// V at the optimum.
    pub objective: f64,
    /// Weighted misfit (χ² with a measured σ).
    pub misfit: f64,
    /// Effective parameters of the fit.
    pub effective_parameters: f64,
}

/// One candidate law in fit.json's `shift_choice.candidates`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LawCandidate {
    /// "wlf", "arrhenius" or "free".
    pub model: &'static str,
    /// Constants of the law (free shifts: one per temperature but T_ref).
    pub parameters: usize,
    /// V of the joint fit under this law at the λ and on the τ grid of the
    /// WLF fit (the fits the test compares; a law chosen over a rejected
    /// WLF is reported as fitted again with its own λ).
    pub objective: f64,
    /// Its weighted misfit there.
    pub misfit: f64,
    /// The F statistic against the free shifts (null for the free shifts).
    #[serde(rename = "F")]
    pub f: Option<f64>,
    /// P(F_{k, N−t} ≥ F) (null for the free shifts).
    pub p_value: Option<f64>,
    /// Whether the data reject the law (p < alpha; null for the free
    /// shifts).
    pub rejected: Option<bool>,
}

impl LawCandidate {
    /// The free shifts, against which the laws are tested.
    pub(crate) fn free(free: &LawFit) -> Self {
        LawCandidate {
            model: free.model,
            parameters: free.parameters,
            objective: free.objective,
            misfit: free.misfit,
            f: None,
            p_value: None,
            rejected: None,
        }
    }

    /// `law` tested against `free` on `n` points (module doc).
    pub(crate) fn tested(law: &LawFit, free: &LawFit, n: usize) -> Self {
        let k = (free.parameters.saturating_sub(law.parameters)).max(1) as f64;
        let dof = (n as f64 - free.effective_parameters).max(1.0);
        let variance = (free.misfit / dof).max(f64::MIN_POSITIVE);
        // The free fit starts from the law's optimum, so V_free ≤ V_law up
        // to the solver's tolerance; a rounding-negative gain is none.
        let f = ((law.objective - free.objective).max(0.0) / k) / variance;
        let p = FisherSnedecor::new(k, dof).map_or(f64::NAN, |d| d.sf(f));
        LawCandidate {
            model: law.model,
            parameters: law.parameters,
            objective: law.objective,
            misfit: law.misfit,
            f: Some(f),
            p_value: Some(p),
            // A p that is not a number (no test could be made) keeps the law.
            rejected: Some(p < ALPHA),
        }
    }

    /// "WLF (F = 0.71, p = 0.62)".
    fn describe(&self) -> String {
        let name = law_name(self.model);
        match (self.f, self.p_value) {
            (Some(f), Some(p)) => format!("{name} (F = {f:.3}, p = {p:.2e})"),
            _ => name.to_string(),
        }
    }
}

/// How the shift law of a temperature set was chosen: fit.json's
/// `shift_choice` (with `shift = "auto"`, or when a law the scene asked
/// for was replaced by another).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShiftChoice {
    /// "auto", or "substitute": the law asked for
    /// ([`crate::params::ShiftSubstitute`]) is not one the fit has.
    pub chosen_by: &'static str,
    /// The law chosen: "wlf", "arrhenius" or "free" (= `shift.model`).
    pub model: &'static str,
    /// Why, in words.
    pub reason: String,
    /// With "substitute": the law asked for ("wlf-arrhenius").
    #[serde(skip_serializing_if = "Option::is_none")]
    pub requested: Option<&'static str>,
    /// The test that judged the laws (null for a substitute).
    pub test: Option<&'static str>,
    /// Its significance level (null for a substitute).
    pub alpha: Option<f64>,
    /// The laws fitted, in the order tried, then the free shifts.
    pub candidates: Vec<LawCandidate>,
}

impl ShiftChoice {
    /// The choice among `tested` laws (in order of preference, each tested
    /// against `free`): the first not rejected, else the free shifts.
    pub(crate) fn first_accepted(tested: Vec<LawCandidate>, free: LawCandidate) -> Self {
        let chosen = tested.iter().find(|c| c.rejected == Some(false));
        let rejected: Vec<String> = tested
            .iter()
            .take_while(|c| c.rejected != Some(false))
            .map(LawCandidate::describe)
            .collect();
        let (model, reason) = match chosen {
            Some(c) => {
                let before = if rejected.is_empty() {
                    String::new()
                } else {
                    format!("the data reject {}; ", rejected.join(" and "))
                };
                (
                    c.model,
                    format!(
                        "{before}{} describes the shifts: against one free shift per \
                         temperature it is not rejected at α = {ALPHA}",
                        c.describe()
                    ),
                )
            }
            None => (
                free.model,
                format!(
                    "the data reject {} against one free shift per temperature (α = {ALPHA}): \
                     the shifts follow neither law, so each temperature keeps its own log10 a_T \
                     (linear in T between the measured temperatures, nothing beyond them)",
                    rejected.join(" and ")
                ),
            ),
        };
        let mut candidates = tested;
        candidates.push(free);
        ShiftChoice {
            chosen_by: "auto",
            model,
            reason,
            requested: None,
            test: Some(TEST),
            alpha: Some(ALPHA),
            candidates,
        }
    }

    /// The law `model` fitted in place of the one `substitute` asked for.
    pub(crate) fn substitute(model: &'static str, substitute: &ShiftSubstitute) -> Self {
        ShiftChoice {
            chosen_by: "substitute",
            model,
            reason: format!(
                "{} = \"{}\" asks for a law the fit does not have; fitted instead: {}, \
                 because {}",
                substitute.key,
                substitute.requested,
                law_name(model),
                substitute.reason
            ),
            requested: Some(substitute.requested),
            test: None,
            alpha: None,
            candidates: Vec::new(),
        }
    }

    /// A choice made without a test (`reason` says why), of `model` fitted
    /// as `fit`.
    pub(crate) fn untested(fit: &LawFit, reason: String) -> Self {
        ShiftChoice {
            chosen_by: "auto",
            model: fit.model,
            reason,
            requested: None,
            test: Some(TEST),
            alpha: Some(ALPHA),
            candidates: vec![LawCandidate::free(fit)],
        }
    }

    /// The numbers that must be finite in fit.json.
    pub(crate) fn all_finite(&self) -> bool {
        self.candidates.iter().all(|c| {
            [c.objective, c.misfit]
                .into_iter()
                .chain(c.f)
                .chain(c.p_value)
                .all(f64::is_finite)
        })
    }
}

/// The test, as fit.json names it.
const TEST: &str = "extra-sum-of-squares F test of each law against one free shift per \
                    temperature, at the λ and on the τ grid of the WLF fit";

/// The law's name in messages.
pub(crate) fn law_name(model: &str) -> &str {
    match model {
        "wlf" => "WLF",
        "arrhenius" => "Arrhenius",
        "free" => "free shifts",
        other => other,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn law(model: &'static str, parameters: usize, objective: f64) -> LawFit {
        LawFit {
            model,
            parameters,
            objective,
            misfit: objective,
            effective_parameters: 20.0,
        }
    }

    /// A law whose extra misfit is what k parameters of noise explain is
    /// kept; one 40 noise units worse per parameter is rejected, and the
    /// next law is taken.
    #[test]
    fn the_first_law_not_rejected_is_chosen() {
        // 7 temperatures: free has 6 constants; 120 points, χ²_free = 100.
        let free = law("free", 6, 100.0);
        let wlf = LawCandidate::tested(&law("wlf", 2, 104.0), &free, 120);
        assert_eq!(wlf.rejected, Some(false), "{wlf:?}");
        let choice = ShiftChoice::first_accepted(vec![wlf], LawCandidate::free(&free));
        assert_eq!(choice.model, "wlf");
        let bad = LawCandidate::tested(&law("wlf", 2, 260.0), &free, 120);
        let arrhenius = LawCandidate::tested(&law("arrhenius", 1, 105.0), &free, 120);
        assert_eq!(bad.rejected, Some(true));
        let choice = ShiftChoice::first_accepted(vec![bad, arrhenius], LawCandidate::free(&free));
        assert_eq!(choice.model, "arrhenius");
        assert!(choice.reason.contains("reject WLF"), "{}", choice.reason);
        assert!(choice.all_finite());
    }

    /// F against the distribution by hand: with k = 4 and 100 degrees of
    /// freedom, F = 3.51 is the 1 % point (tables: 3.51).
    #[test]
    fn the_one_percent_point_is_at_the_tabulated_f() {
        let free = law("free", 6, 100.0);
        let at = |excess: f64| LawCandidate::tested(&law("wlf", 2, 100.0 + excess), &free, 120);
        // F = excess/4 / (100/100).
        assert!(at(4.0 * 3.45).p_value.unwrap() > ALPHA);
        assert!(at(4.0 * 3.58).p_value.unwrap() < ALPHA);
        // None of the laws: free, saying both were rejected.
        let choice = ShiftChoice::first_accepted(
            vec![
                at(40.0),
                LawCandidate::tested(&law("arrhenius", 1, 150.0), &free, 120),
            ],
            LawCandidate::free(&free),
        );
        assert_eq!(choice.model, "free");
        assert!(choice.reason.contains("WLF") && choice.reason.contains("Arrhenius"));
    }
}
