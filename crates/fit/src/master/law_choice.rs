//! The law of the shift factor: the one asked for, or with `auto` the one
//! the determined shifts support.
//!
//! `auto` tries, in order of simplicity for a polymer through its
//! transition,
//! 1. WLF: taken when its χ² test against the pairs' errors passes
//!    ([`temperature_law::LAW_P_VALUE`]);
//! 2. else WLF above a junction T_g with Arrhenius below, and Arrhenius
//!    alone: of those whose test passes, the one with the smaller AICc
//!    (χ² + 2p + 2p(p+1)/(n−p−1), n pairs, p constants), so that the
//!    four-constant law must earn its two extra constants;
//! 3. else the measured shifts themselves ("free", linear in T between
//!    isotherms): no law describes them within their errors, and a law
//!    would move well-measured isotherms off their best overlap.
//!
//! A candidate that cannot hold is rejected before its test is read, with
//! its reason, and `auto` goes on to the next: a WLF branch that diverges
//! (T = T_ref − C2) at or above the coldest measured isotherm, a WLF C1
//! above [`super::quality::WLF_C1_MAX`] (no polymer's free volume gives
//! it), or a constant with a standard error of exactly 0 (a degenerate
//! fit the shifts do not determine). A law asked for by name that
//! diverges inside the measured temperatures is an error naming its
//! constants, where it diverges, the measured range and the laws that do
//! fit.
//!
//! When T_ref lies outside the measured temperatures a free shift cannot
//! reach it; `auto` then keeps the law with the largest p-value and says
//! that it does not pass.
//!
//! # References
//! - C.M. Hurvich, C.-L. Tsai, "Regression and time series model selection
//!   in small samples", Biometrika 76 (1989) 297–307 (AICc).
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, ch. 11.

use super::ShiftLaw;
use super::quality::WLF_C1_MAX;
use super::temperature_law::{
    self, ArrheniusFit, LawTest, PairObservation, WlfArrheniusFit, WlfFit,
};
use crate::error::FitError;

/// The law chosen and the fits tried on the way.
#[derive(Debug, Clone, PartialEq)]
pub struct LawChoice {
    /// The law applied (never `Auto`).
    pub law: ShiftLaw,
    /// Why, in a sentence with the tests' numbers.
    pub reason: String,
    /// Things the user should know.
    pub warnings: Vec<String>,
    /// WLF, where tried.
    pub wlf: Option<WlfFit>,
    /// Arrhenius, where tried.
    pub arrhenius: Option<ArrheniusFit>,
    /// WLF–Arrhenius, where tried.
    pub wlf_arrhenius: Option<WlfArrheniusFit>,
    /// Candidates `auto` rejected as unable to hold, each with its reason.
    pub rejected: Vec<(ShiftLaw, String)>,
}

/// Why a fitted law cannot hold over the measured temperatures `measured`
/// (ascending, °C), or None: a WLF branch that diverges inside or above
/// their lower end, C1 above [`WLF_C1_MAX`], or a standard error of
/// exactly 0 (module doc).
pub(crate) fn cannot_hold(
    law: ShiftLaw,
    choice: &LawChoice,
    measured: &[f64],
    t_ref: f64,
) -> Option<String> {
    let (lo, hi) = (measured[0], measured[measured.len() - 1]);
    let range = format!("{} to {} °C", temperature(lo), temperature(hi));
    let (wlf, sigmas): (Option<(f64, f64)>, Vec<f64>) = match law {
        ShiftLaw::Wlf => {
            let w = choice.wlf?;
            (Some((w.c1, w.c2)), vec![w.c1_sigma, w.c2_sigma])
        }
        ShiftLaw::WlfArrhenius => {
            let w = choice.wlf_arrhenius?;
            (Some((w.c1, w.c2)), w.sigma.to_vec())
        }
        ShiftLaw::Arrhenius => (None, vec![choice.arrhenius?.activation_energy_sigma]),
        ShiftLaw::Free | ShiftLaw::Auto => return None,
    };
    if let Some((c1, c2)) = wlf {
        let below = match law {
            ShiftLaw::WlfArrhenius => choice.wlf_arrhenius.map_or(lo, |w| w.t_junction.max(lo)),
            _ => lo,
        };
        let diverges = t_ref - c2;
        // The WLF branch holds above `below`; measured temperatures there
        // must lie above its divergence.
        if measured
            .iter()
            .any(|&t| t >= below && c2 + t - t_ref <= 0.0)
        {
            return Some(format!(
                "C1 = {c1:.4}, C2 = {c2:.2} K about T_ref = {t_ref} °C diverge at T_ref − C2 = {}                  °C, inside the measured temperatures ({range})",
                temperature(diverges)
            ));
        }
        if c1 > WLF_C1_MAX {
            return Some(format!(
                "C1 = {c1:.4e} is far above any polymer's (at most about {WLF_C1_MAX}): WLF is \
                 stretched to a straight line"
            ));
        }
    }
    if sigmas.contains(&0.0) {
        return Some(
            "a constant has a standard error of exactly 0: the shifts do not \
                     determine it (a degenerate fit)"
                .to_string(),
        );
    }
    None
}

/// "χ² = 12.3 for 9 degrees of freedom, p = 0.2".
fn describe(test: &LawTest) -> String {
    match test.p_value {
        Some(p) => format!(
            "χ² = {:.3} for {} degrees of freedom, p = {:.2e}",
            test.chi2, test.dof, p
        ),
        None => "exactly, with no degree of freedom left to test it".into(),
    }
}

/// A temperature for a message, °C, to 0.01 K (a controller's scatter
/// about its set point is noise in a sentence).
pub fn temperature(t: f64) -> String {
    let rounded = (t * 100.0).round() / 100.0;
    // −0 reads oddly.
    format!("{}", if rounded == 0.0 { 0.0 } else { rounded })
}

fn aicc(test: &LawTest, parameters: usize, pairs: usize) -> f64 {
    let (p, n) = (parameters as f64, pairs as f64);
    let correction = if n - p - 1.0 > 0.0 {
        2.0 * p * (p + 1.0) / (n - p - 1.0)
    } else {
        f64::INFINITY
    };
    test.chi2 + 2.0 * p + correction
}

/// Chooses and fits the law of the determined `pairs`; `temps` are the
/// determined isotherms' temperatures, `measured` every isotherm's
/// (both ascending).
pub(crate) fn choose(
    asked: ShiftLaw,
    pairs: &[PairObservation],
    temps: &[f64],
    measured: &[f64],
    t_ref: f64,
) -> Result<LawChoice, FitError> {
    let n = pairs.len();
    let missing = |law: &str, need: &str| {
        FitError::InsufficientData(format!(
            "the data determine the shifts of {} isotherm(s) only ({} pair(s)); {law} needs {need}: \
             use the shift \"free\" or \"auto\", or measure isotherms through the transition",
            temps.len(),
            n
        ))
    };
    let mut choice = LawChoice {
        law: asked,
        reason: String::new(),
        warnings: Vec::new(),
        wlf: None,
        arrhenius: None,
        wlf_arrhenius: None,
        rejected: Vec::new(),
    };
    let fails = |name: &str, test: &LawTest| {
        format!(
            "{name} does not describe the determined shifts within their errors ({}): it moves \
             well-measured isotherms off their best overlap; consider --shift auto, or free",
            describe(test)
        )
    };
    match asked {
        ShiftLaw::Wlf => {
            let fit = temperature_law::fit_wlf(pairs, t_ref)
                .ok_or_else(|| missing("WLF", "two determined pairs and a positive C1"))?;
            choice.reason = format!("asked for; it fits the shifts {}", describe(&fit.test));
            if !fit.test.passes() {
                choice.warnings.push(fails("WLF", &fit.test));
            }
            choice.wlf = Some(fit);
        }
        ShiftLaw::Arrhenius => {
            let fit = temperature_law::fit_arrhenius(pairs, t_ref)
                .ok_or_else(|| missing("Arrhenius", "one determined pair"))?;
            if fit.activation_energy <= 0.0 {
                return Err(FitError::InsufficientData(format!(
                    "the shifts give a non-positive activation energy ({:.3e} J/mol): warmer \
                     isotherms are not faster; check the temperatures",
                    fit.activation_energy
                )));
            }
            choice.reason = format!("asked for; it fits the shifts {}", describe(&fit.test));
            if !fit.test.passes() {
                choice.warnings.push(fails("Arrhenius", &fit.test));
            }
            choice.arrhenius = Some(fit);
        }
        ShiftLaw::WlfArrhenius => {
            let fit = temperature_law::fit_wlf_arrhenius(pairs, t_ref).ok_or_else(|| {
                missing(
                    "WLF–Arrhenius",
                    "four determined pairs, one below the junction and two above",
                )
            })?;
            choice.reason = format!("asked for; it fits the shifts {}", describe(&fit.test));
            if !fit.test.passes() {
                choice.warnings.push(fails("WLF–Arrhenius", &fit.test));
            }
            choice.wlf_arrhenius = Some(fit);
        }
        ShiftLaw::Free => {
            choice.reason = "asked for: the measured shifts, linear in T between isotherms".into();
        }
        ShiftLaw::Auto => choose_auto(&mut choice, pairs, temps, measured, t_ref),
    }
    if asked != ShiftLaw::Auto
        && let Some(why) = cannot_hold(asked, &choice, measured, t_ref)
        && why.contains("diverge")
    {
        let mut others = LawChoice {
            law: ShiftLaw::Auto,
            rejected: Vec::new(),
            ..choice.clone()
        };
        choose_auto(&mut others, pairs, temps, measured, t_ref);
        let fit: Vec<&str> = [
            (ShiftLaw::Wlf, others.wlf.map(|w| w.test)),
            (ShiftLaw::WlfArrhenius, others.wlf_arrhenius.map(|w| w.test)),
            (ShiftLaw::Arrhenius, others.arrhenius.map(|a| a.test)),
        ]
        .into_iter()
        .filter(|(law, test)| {
            *law != asked
                && test.is_some_and(|t| t.passes())
                && !others.rejected.iter().any(|r| r.0 == *law)
        })
        .map(|(law, _)| law.name())
        .chain(std::iter::once("free"))
        .collect();
        return Err(FitError::InsufficientData(format!(
            "the {} law cannot hold: {why}; laws that fit the determined shifts: {} (--shift {})",
            asked.name(),
            fit.join(", "),
            fit[0]
        )));
    }
    Ok(choice)
}

/// `auto` (module doc).
fn choose_auto(
    choice: &mut LawChoice,
    pairs: &[PairObservation],
    temps: &[f64],
    measured: &[f64],
    t_ref: f64,
) {
    let n = pairs.len();
    choice.wlf = temperature_law::fit_wlf(pairs, t_ref);
    choice.wlf_arrhenius = temperature_law::fit_wlf_arrhenius(pairs, t_ref);
    choice.arrhenius =
        temperature_law::fit_arrhenius(pairs, t_ref).filter(|a| a.activation_energy > 0.0);
    for law in [ShiftLaw::Wlf, ShiftLaw::WlfArrhenius, ShiftLaw::Arrhenius] {
        if let Some(why) = cannot_hold(law, choice, measured, t_ref) {
            choice.rejected.push((law, why));
        }
    }
    let rejected_laws: Vec<ShiftLaw> = choice.rejected.iter().map(|r| r.0).collect();
    let rejected = |law: ShiftLaw| rejected_laws.contains(&law);
    // The other rejected candidates, said after WLF's verdict.
    let others_rejected: Vec<String> = choice
        .rejected
        .iter()
        .filter(|r| r.0 != ShiftLaw::Wlf)
        .map(|(law, why)| format!("{} rejected: {why}", law.name()))
        .collect();
    if let Some(w) = choice
        .wlf
        .filter(|w| w.test.passes() && !rejected(ShiftLaw::Wlf))
    {
        choice.law = ShiftLaw::Wlf;
        choice.reason = format!(
            "auto: WLF describes the {} determined shifts ({})",
            temps.len(),
            describe(&w.test)
        );
        return;
    }
    let wlf_said = match choice.rejected.iter().find(|r| r.0 == ShiftLaw::Wlf) {
        Some((_, why)) => format!("WLF cannot hold ({why})"),
        None => choice.wlf.map_or_else(
            || "WLF cannot be fitted to them".to_string(),
            |w| format!("WLF does not describe them ({})", describe(&w.test)),
        ),
    };
    let wlf_said = if others_rejected.is_empty() {
        wlf_said
    } else {
        format!("{wlf_said}; {}", others_rejected.join("; "))
    };
    let mut passing: Vec<(ShiftLaw, f64, String)> = Vec::new();
    if let Some(w) = choice
        .wlf_arrhenius
        .filter(|w| w.test.passes() && !rejected(ShiftLaw::WlfArrhenius))
    {
        passing.push((
            ShiftLaw::WlfArrhenius,
            aicc(&w.test, 4, n),
            format!(
                "WLF above T_g = {} °C with Arrhenius below does ({})",
                temperature(w.t_junction),
                describe(&w.test)
            ),
        ));
    }
    if let Some(a) = choice
        .arrhenius
        .filter(|a| a.test.passes() && !rejected(ShiftLaw::Arrhenius))
    {
        passing.push((
            ShiftLaw::Arrhenius,
            aicc(&a.test, 1, n),
            format!("Arrhenius does ({})", describe(&a.test)),
        ));
    }
    passing.sort_by(|a, b| a.1.total_cmp(&b.1));
    if let Some((law, _, said)) = passing.into_iter().next() {
        choice.law = law;
        choice.reason = format!("auto: {wlf_said}; {said}");
        return;
    }
    let reachable = (temps[0]..=temps[temps.len() - 1]).contains(&t_ref);
    if reachable || n == 0 {
        choice.law = ShiftLaw::Free;
        choice.reason = format!(
            "auto: no law describes the determined shifts within their errors ({wlf_said}{}{}); \
             the measured shifts are used, linear in T between isotherms",
            choice.wlf_arrhenius.map_or(String::new(), |w| format!(
                "; WLF–Arrhenius: {}",
                describe(&w.test)
            )),
            choice.arrhenius.map_or(String::new(), |a| format!(
                "; Arrhenius: {}",
                describe(&a.test)
            )),
        );
        return;
    }
    closest_law(choice, temps, t_ref, &rejected_laws);
}

/// `auto` with T_ref outside the determined isotherms, where no law
/// passes: a free shift cannot reach T_ref, so the law (not among
/// `rejected`) with the largest p-value, said not to pass.
fn closest_law(choice: &mut LawChoice, temps: &[f64], t_ref: f64, rejected: &[ShiftLaw]) {
    let rejected = |law: ShiftLaw| rejected.contains(&law);
    let mut laws: Vec<(ShiftLaw, f64)> = Vec::new();
    if let Some(w) = choice.wlf.filter(|_| !rejected(ShiftLaw::Wlf)) {
        laws.push((ShiftLaw::Wlf, w.test.p_value.unwrap_or(1.0)));
    }
    if let Some(w) = choice
        .wlf_arrhenius
        .filter(|_| !rejected(ShiftLaw::WlfArrhenius))
    {
        laws.push((ShiftLaw::WlfArrhenius, w.test.p_value.unwrap_or(1.0)));
    }
    if let Some(a) = choice.arrhenius.filter(|_| !rejected(ShiftLaw::Arrhenius)) {
        laws.push((ShiftLaw::Arrhenius, a.test.p_value.unwrap_or(1.0)));
    }
    laws.sort_by(|a, b| b.1.total_cmp(&a.1));
    match laws.first() {
        Some(&(law, p)) => {
            choice.law = law;
            choice.reason = format!(
                "auto: no law describes the determined shifts within their errors, and T_ref = \
                 {t_ref} °C lies outside the isotherms whose shifts are determined ({} to {} °C), \
                 where measured shifts cannot reach; {} fits best (p = {p:.2e})",
                temperature(temps[0]),
                temperature(temps[temps.len() - 1]),
                law.name()
            );
            choice.warnings.push(format!(
                "the shift law {} does not describe the determined shifts within their errors \
                 (p = {p:.2e}); choose T_ref between {} and {} °C to use the measured shifts",
                law.name(),
                temperature(temps[0]),
                temperature(temps[temps.len() - 1])
            ));
        }
        None => {
            choice.law = ShiftLaw::Free;
            choice.reason = "auto: no law can be fitted; the measured shifts are used".to_string();
        }
    }
}
