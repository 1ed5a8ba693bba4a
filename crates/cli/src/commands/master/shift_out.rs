//! The shift factors as `rollfit master` writes them, for frequency
//! sweeps and relaxation runs alike: shift.csv, the shift keys of
//! master.json (`wlf`, `arrhenius`, `wlf_arrhenius`, `shifts`, `pairs`)
//! and the law lines and table of the summary on stdout.

use anyhow::Result;
pub(super) use rollfit_fit::master::law_choice::temperature as celsius;
use rollfit_fit::master::pairwise::{DETERMINED_SIGMA, PairCause, PairVerdict, TTS_DISAGREEMENT};
use rollfit_fit::master::van_gurp_palmen::VGP_TOLERANCE;
use rollfit_fit::master::{LawTest, ShiftFactors, ShiftLaw, ValidMasterSettings, VanGurpPalmen};
use rollfit_io::csv_text;
use rollfit_io::fit_dir::columns::{LOG_AT, T};
use serde::Serialize;

/// The shift keys of master.json, in their order.
#[derive(Serialize)]
pub(super) struct ShiftJson {
    wlf: Option<WlfSummary>,
    arrhenius: Option<ArrheniusSummary>,
    wlf_arrhenius: Option<WlfArrheniusSummary>,
    /// The laws `auto` rejected as unable to hold, with the reason.
    rejected_laws: Vec<RejectedLaw>,
    /// What "determined" means, for pairs and isotherms alike.
    determined_rule: String,
    shifts: Vec<ShiftRow>,
    pairs: Vec<PairRow>,
    /// The pairs where E′ and tan δ need different shifts.
    superposition_fails: Vec<TtsFailure>,
}

#[derive(Serialize)]
struct RejectedLaw {
    law: &'static str,
    reason: String,
}

/// A pair where no single shift superposes E′ and tan δ.
#[derive(Serialize)]
struct TtsFailure {
    #[serde(rename = "T_lower")]
    t_lower: f64,
    #[serde(rename = "T_upper")]
    t_upper: f64,
    /// The shift log E′ alone needs, decades.
    shift_storage: f64,
    /// The shift log tan δ alone needs, decades.
    shift_tan_delta: f64,
    /// The quantity the combined shift follows: "E′" or "tan δ".
    carried_by: &'static str,
}

/// The rule behind every "determined" flag.
fn determined_rule() -> String {
    format!(
        "a pair's shift is determined when its profile (Δχ² = 4) is bounded inside the \
         isotherms' overlap, no second minimum comes within Δχ² = 4, and σ ≤ {DETERMINED_SIGMA} \
         decade (σ = max(profile, jackknife), at least half the difference of the E′ and tan δ \
         shifts where they differ by more than {TTS_DISAGREEMENT}); an isotherm's shift is \
         determined when determined pairs join it to the reference part and its σ about T_ref \
         is ≤ {DETERMINED_SIGMA} decade"
    )
}

impl ShiftJson {
    pub(super) fn of(shift: &ShiftFactors) -> ShiftJson {
        ShiftJson {
            wlf: shift.wlf.map(|w| WlfSummary {
                c1: w.c1,
                c2: w.c2,
                c1_sigma: defined(w.c1_sigma),
                c2_sigma: defined(w.c2_sigma),
                rms: defined(w.rms),
                test: TestSummary::of(&w.test),
            }),
            arrhenius: shift.arrhenius.map(|a| ArrheniusSummary {
                activation_energy: a.activation_energy,
                activation_energy_sigma: defined(a.activation_energy_sigma),
                rms: defined(a.rms),
                test: TestSummary::of(&a.test),
            }),
            wlf_arrhenius: shift.wlf_arrhenius.map(|w| WlfArrheniusSummary {
                c1: w.c1,
                c2: w.c2,
                t_junction: w.t_junction,
                activation_energy: w.activation_energy,
                c1_sigma: defined(w.sigma[0]),
                c2_sigma: defined(w.sigma[1]),
                activation_energy_sigma: defined(w.sigma[2]),
                rms: defined(w.rms),
                test: TestSummary::of(&w.test),
            }),
            rejected_laws: shift
                .rejected_laws
                .iter()
                .map(|(law, reason)| RejectedLaw {
                    law: law.name(),
                    reason: reason.clone(),
                })
                .collect(),
            determined_rule: determined_rule(),
            superposition_fails: shift
                .pairs
                .iter()
                .filter(|p| p.tts_fails)
                .map(|p| TtsFailure {
                    t_lower: shift.shifts[p.lower].temperature,
                    t_upper: shift.shifts[p.upper].temperature,
                    shift_storage: p.curve_shift[0],
                    shift_tan_delta: p.curve_shift[1],
                    carried_by: ["E′", "tan δ"][p.carrier.min(1)],
                })
                .collect(),
            shifts: shift
                .shifts
                .iter()
                .map(|s| ShiftRow {
                    temperature: s.temperature,
                    log_shift: s.log_shift,
                    log_shift_sigma: defined(s.log_shift_sigma),
                    log_shift_measured: s.log_shift_measured,
                    log_shift_measured_sigma: s
                        .log_shift_measured
                        .and_then(|_| defined(s.log_shift_measured_sigma)),
                    determined: s.determined,
                    log_vertical: s.log_vertical,
                    points: s.points,
                })
                .collect(),
            pairs: shift
                .pairs
                .iter()
                .map(|p| PairRow {
                    t_lower: shift.shifts[p.lower].temperature,
                    t_upper: shift.shifts[p.upper].temperature,
                    shift: p.shift,
                    sigma: defined(p.sigma),
                    determined: p.verdict == PairVerdict::Determined,
                    cause: cause_name(p.cause),
                    overlap: p.overlap,
                    shift_storage: defined(p.curve_shift[0]),
                    shift_tan_delta: defined(p.curve_shift[1]),
                    superposition_fails: p.tts_fails,
                })
                .collect(),
        }
    }
}

/// shift.csv.
pub(super) fn shift_csv(shift: &ShiftFactors) -> Result<Vec<u8>> {
    // An empty cell where the data determine no number.
    let cell = |x: Option<f64>| {
        x.filter(|x| x.is_finite())
            .map_or(String::new(), csv_text::number)
    };
    let shift_csv = csv_text::csv_text_bytes(
        &[
            T,
            LOG_AT,
            "log_aT_measured",
            "log_bT",
            "points",
            "log_aT_sigma",
            "log_aT_measured_sigma",
            "determined",
        ],
        shift.shifts.iter().map(|s| {
            vec![
                csv_text::number(s.temperature),
                csv_text::number(s.log_shift),
                cell(s.log_shift_measured),
                csv_text::number(s.log_vertical),
                s.points.to_string(),
                cell(Some(s.log_shift_sigma)),
                cell(s.log_shift_measured.map(|_| s.log_shift_measured_sigma)),
                s.determined.to_string(),
            ]
        }),
    )?;
    Ok(shift_csv)
}

/// "6 isotherms, 186 points, T_ref = 20 °C, shift wlf" (`law_note` after
/// the law), with " with vertical factors" where asked.
pub(super) fn headline(
    shift: &ShiftFactors,
    points: usize,
    settings: &ValidMasterSettings,
    law_note: &str,
) -> String {
    let count = shift.shifts.len();
    format!(
        "{} isotherm{}, {} points, T_ref = {} °C, {}{}",
        count,
        if count == 1 { "" } else { "s" },
        points,
        settings.t_ref(),
        if count == 1 {
            "shift law not determined (one isotherm)".to_string()
        } else {
            format!("shift {}{law_note}", shift.law.name())
        },
        if settings.vertical() {
            " with vertical factors"
        } else {
            ""
        }
    )
}

/// The law lines and the table of shifts of the summary on stdout.
/// A standard error to two significant digits (0.0036, 0.20, 12), so that
/// a small one does not print as "± 0.00"; "—" where none is defined.
fn two_digits(sigma: f64) -> String {
    if !sigma.is_finite() {
        return "—".to_string();
    }
    if sigma == 0.0 {
        return "0".to_string();
    }
    let decimals = (1 - sigma.abs().log10().floor() as i32).max(0) as usize;
    format!("{sigma:.decimals$}")
}

pub(super) fn shift_text(shift: &ShiftFactors) -> String {
    let count = shift.shifts.len();
    let mut out = String::new();
    if count > 1 {
        out += &format!("Shift law: {}\n", shift.reason);
    }
    let applied = |law: ShiftLaw| {
        if shift.law == law { "applied" } else { "tried" }
    };
    if let Some(w) = shift.wlf {
        out += &format!(
            "WLF ({}): C1 = {:.4} ± {}, C2 = {:.2} ± {} K; {}\n",
            applied(ShiftLaw::Wlf),
            w.c1,
            two_digits(w.c1_sigma),
            w.c2,
            two_digits(w.c2_sigma),
            test_line(&w.test)
        );
    }
    if let Some(w) = shift.wlf_arrhenius {
        out += &format!(
            "WLF–Arrhenius ({}): C1 = {:.4} ± {}, C2 = {:.2} ± {} K above T_g = {:.2} °C, \
             E_a = {:.4e} ± {:.2e} J/mol below; {}\n",
            applied(ShiftLaw::WlfArrhenius),
            w.c1,
            two_digits(w.sigma[0]),
            w.c2,
            two_digits(w.sigma[1]),
            w.t_junction,
            w.activation_energy,
            w.sigma[2],
            test_line(&w.test)
        );
    }
    if let Some(a) = shift.arrhenius {
        out += &format!(
            "Arrhenius ({}): E_a = {:.4e} ± {:.2e} J/mol; {}\n",
            applied(ShiftLaw::Arrhenius),
            a.activation_energy,
            a.activation_energy_sigma,
            test_line(&a.test)
        );
    }
    out += "    T (°C)   log10 a_T       ±1σ   measured       ±1σ   log10 b_T   points\n";
    let number = |x: Option<f64>, width: usize| match x.filter(|x| x.is_finite()) {
        Some(x) => format!("{x:width$.4}"),
        None => format!("{:>width$}", "—"),
    };
    for s in &shift.shifts {
        out += &format!(
            "{:10.2} {:11.4} {} {} {} {:11.4} {:8}{}\n",
            s.temperature,
            s.log_shift,
            number(Some(s.log_shift_sigma), 9),
            number(s.log_shift_measured, 10),
            number(s.log_shift_measured.map(|_| s.log_shift_measured_sigma), 9),
            s.log_vertical,
            s.points,
            if s.determined {
                ""
            } else {
                "   not determined by the data"
            }
        );
    }
    out
}

#[derive(Serialize)]
struct WlfSummary {
    #[serde(rename = "C1")]
    c1: f64,
    #[serde(rename = "C2")]
    c2: f64,
    #[serde(rename = "C1_sigma")]
    c1_sigma: Option<f64>,
    #[serde(rename = "C2_sigma")]
    c2_sigma: Option<f64>,
    /// RMS of the measured shifts about the law (NaN → null where the law
    /// was tried but not applied).
    rms: Option<f64>,
    test: TestSummary,
}

#[derive(Serialize)]
struct ArrheniusSummary {
    #[serde(rename = "E_a")]
    activation_energy: f64,
    #[serde(rename = "E_a_sigma")]
    activation_energy_sigma: Option<f64>,
    rms: Option<f64>,
    test: TestSummary,
}

#[derive(Serialize)]
struct WlfArrheniusSummary {
    #[serde(rename = "C1")]
    c1: f64,
    #[serde(rename = "C2")]
    c2: f64,
    #[serde(rename = "T_g")]
    t_junction: f64,
    #[serde(rename = "E_a")]
    activation_energy: f64,
    #[serde(rename = "C1_sigma")]
    c1_sigma: Option<f64>,
    #[serde(rename = "C2_sigma")]
    c2_sigma: Option<f64>,
    #[serde(rename = "E_a_sigma")]
    activation_energy_sigma: Option<f64>,
    rms: Option<f64>,
    test: TestSummary,
}

/// A law's χ² test against the determined pairwise shifts.
#[derive(Serialize)]
struct TestSummary {
    chi2: f64,
    dof: usize,
    p_value: Option<f64>,
    passes: bool,
}

impl TestSummary {
    fn of(t: &LawTest) -> TestSummary {
        TestSummary {
            chi2: t.chi2,
            dof: t.dof,
            p_value: t.p_value,
            passes: t.passes(),
        }
    }
}

#[derive(Serialize)]
struct ShiftRow {
    #[serde(rename = "T")]
    temperature: f64,
    #[serde(rename = "log_aT")]
    log_shift: f64,
    #[serde(rename = "log_aT_sigma")]
    log_shift_sigma: Option<f64>,
    #[serde(rename = "log_aT_measured")]
    log_shift_measured: Option<f64>,
    #[serde(rename = "log_aT_measured_sigma")]
    log_shift_measured_sigma: Option<f64>,
    determined: bool,
    #[serde(rename = "log_bT")]
    log_vertical: f64,
    points: usize,
}

/// One pair of isotherms compared.
#[derive(Serialize)]
struct PairRow {
    #[serde(rename = "T_lower")]
    t_lower: f64,
    #[serde(rename = "T_upper")]
    t_upper: f64,
    /// log10 a_upper − log10 a_lower at the best overlap.
    shift: f64,
    sigma: Option<f64>,
    determined: bool,
    /// "measured", or why not: "flat", "overlap_end", "ambiguous",
    /// "wide", "too_few_points".
    cause: &'static str,
    /// The overlap of the two frequency ranges at `shift`, decades.
    overlap: f64,
    /// The shift log E′ (log E(t)) alone needs.
    shift_storage: Option<f64>,
    /// The shift log tan δ alone needs.
    shift_tan_delta: Option<f64>,
    /// Whether E′ and tan δ need shifts more than 0.3 decade apart.
    superposition_fails: bool,
}

fn cause_name(cause: PairCause) -> &'static str {
    match cause {
        PairCause::Measured => "measured",
        PairCause::Flat => "flat",
        PairCause::OverlapEnd => "overlap_end",
        PairCause::Ambiguous => "ambiguous",
        PairCause::Wide => "wide",
        PairCause::TooFewPoints => "too_few_points",
    }
}

/// The van Gurp–Palmen keys of master.json.
#[derive(Serialize)]
pub(super) struct VgpJson {
    /// The modelling part of each pair's tolerance, degrees.
    tolerance_fixed_deg: f64,
    pairs: Vec<VgpPairRow>,
    ranges: Vec<VgpRangeRow>,
    /// Every point: [T °C, log10 |E*| (Pa), δ (degrees)].
    points: Vec<[f64; 3]>,
}

#[derive(Serialize)]
struct VgpPairRow {
    #[serde(rename = "T_lower")]
    t_lower: f64,
    #[serde(rename = "T_upper")]
    t_upper: f64,
    /// Common range of log10 |E*|, decades.
    overlap: f64,
    /// RMS δ difference, degrees (null: not tested).
    mismatch_deg: Option<f64>,
    tolerance_deg: f64,
    collapses: Option<bool>,
}

#[derive(Serialize)]
struct VgpRangeRow {
    #[serde(rename = "T_from")]
    t_from: f64,
    #[serde(rename = "T_to")]
    t_to: f64,
    collapses: Option<bool>,
    worst_deg: Option<f64>,
    tolerance_deg: f64,
}

impl VgpJson {
    pub(super) fn of(v: &VanGurpPalmen) -> VgpJson {
        VgpJson {
            tolerance_fixed_deg: VGP_TOLERANCE,
            pairs: v
                .pairs
                .iter()
                .map(|p| VgpPairRow {
                    t_lower: p.t_lower,
                    t_upper: p.t_upper,
                    overlap: p.overlap,
                    mismatch_deg: p.mismatch,
                    tolerance_deg: p.tolerance,
                    collapses: p.collapses(),
                })
                .collect(),
            ranges: v
                .ranges
                .iter()
                .map(|r| VgpRangeRow {
                    t_from: r.t_from,
                    t_to: r.t_to,
                    collapses: r.collapses,
                    worst_deg: defined(r.worst),
                    tolerance_deg: r.tolerance,
                })
                .collect(),
            points: v
                .points
                .iter()
                .map(|p| [p.temperature, p.log_modulus, p.phase_angle])
                .collect(),
        }
    }
}

/// The summary's van Gurp–Palmen line: per range, whether the unshifted
/// isotherms collapse, with the numbers.
pub(super) fn vgp_text(v: &VanGurpPalmen) -> String {
    if v.ranges.is_empty() {
        return String::new();
    }
    let parts: Vec<String> = v
        .ranges
        .iter()
        .map(|r| {
            let span = format!("{}…{} °C", celsius(r.t_from), celsius(r.t_to));
            match r.collapses {
                Some(true) => format!(
                    "{span} collapse (δ within {:.2}°, tolerance {:.2}°)",
                    r.worst, r.tolerance
                ),
                Some(false) => format!(
                    "{span} do not collapse (δ apart by up to {:.2}°, tolerance {:.2}°): \
                     superposition fails there",
                    r.worst, r.tolerance
                ),
                None => format!("{span} not tested (no common |E*|)"),
            }
        })
        .collect();
    format!(
        "van Gurp–Palmen (δ against log |E*|, no shifts): {}\n",
        parts.join("; ")
    )
}

/// The summary's lines on what the data determine: every shift, or the
/// undetermined isotherms, the window the others cover (`variable` in
/// `unit` at T_ref), and where superposition fails.
pub(super) fn window_text(
    shift: &ShiftFactors,
    window: Option<[f64; 2]>,
    variable: &str,
    unit: &str,
) -> String {
    let total = shift.shifts.len();
    if total < 2 {
        return String::new();
    }
    let undetermined: Vec<String> = shift
        .shifts
        .iter()
        .filter(|s| !s.determined)
        .map(|s| celsius(s.temperature))
        .collect();
    let mut out = if undetermined.is_empty() {
        format!("Determined: all {total} isotherms' shifts (σ ≤ {DETERMINED_SIGMA} decade)\n")
    } else {
        format!(
            "Determined: {} of {total} isotherms' shifts (σ ≤ {DETERMINED_SIGMA} decade){}; not \
             determined, placed by the law: {} °C\n",
            total - undetermined.len(),
            window.map_or(String::new(), |[lo, hi]| format!(
                ", covering {variable} = {lo:.3e} … {hi:.3e} {unit}"
            )),
            undetermined.join(", ")
        )
    };
    for p in shift.pairs.iter().filter(|p| p.tts_fails) {
        out += &format!(
            "Superposition fails at {}–{} °C: E′ alone needs {:.2}, tan δ alone {:.2} decades; \
             the shift {:.2} ± {:.2} follows {}\n",
            celsius(shift.shifts[p.lower].temperature),
            celsius(shift.shifts[p.upper].temperature),
            p.curve_shift[0],
            p.curve_shift[1],
            p.shift,
            p.sigma,
            ["E′", "tan δ"][p.carrier.min(1)]
        );
    }
    out
}

/// A standard error, or None where it is not defined (NaN).
fn defined(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// "χ² = 12.3 for 9 degrees of freedom, p = 0.21 (passes)".
fn test_line(t: &LawTest) -> String {
    match t.p_value {
        Some(p) => format!(
            "χ² = {:.2} for {} degrees of freedom, p = {:.2e} ({})",
            t.chi2,
            t.dof,
            p,
            if t.passes() {
                "describes the shifts"
            } else {
                "does not describe the shifts"
            }
        ),
        None => "no degree of freedom left to test it".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::two_digits;

    /// Two significant digits whatever the size; none defined, a dash.
    #[test]
    fn standard_errors_keep_two_significant_digits() {
        assert_eq!(two_digits(0.0036327), "0.0036");
        assert_eq!(two_digits(0.2), "0.20");
        assert_eq!(two_digits(1.36), "1.4");
        assert_eq!(two_digits(12.3), "12");
        assert_eq!(two_digits(0.0), "0");
        assert_eq!(two_digits(f64::INFINITY), "—");
    }
}
