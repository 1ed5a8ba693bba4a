//! What the top of report.html says about trusting the fit:
//! the goodness-of-fit verdict with its χ² and runs tests, the noise the
//! tests assume and the reasons (fit.json `fit_quality`), and the modulus
//! scale — the anchor, or for a fit without one how well the data alone
//! determine E0 (`scale`), or that fit.json does not say.
//!
//! A verdict other than "good" and a scale the data do not determine are
//! banners in the warning colour at the top of the page: a reader who
//! looks no further than the first screen must still see them. Every
//! part of fit.json read here is optional ([`rollfit_io::fit_dir::quality`]);
//! what is missing is said, not guessed.

use std::fmt::Write as _;

use rollfit_io::fit_dir::{
    AnchorSummary, CondensedSummary, FitSummary, QualitySummary, ScaleSummary,
};

use super::{escape, list, num};

/// The verdict banner: green for "good", red for anything else, amber
/// without a verdict; the tests, the noise and the reasons below the
/// headline.
pub(super) fn verdict_banner(s: &FitSummary) -> String {
    let Some(q) = &s.fit_quality else {
        return "<div class=\"status caution\" id=\"verdict\"><strong>No verdict:</strong> \
                fit.json has no <code>fit_quality</code> (written by an older rollfit or \
                another program), so whether the model describes the data is not known.</div>\n"
            .into();
    };
    let (class, meaning) = match q.verdict.as_str() {
        "good" => (
            "ok",
            "the goodness-of-fit tests below find nothing the model leaves unexplained in the data.",
        ),
        "poor" => (
            "bad",
            "the model does not describe the data (a goodness-of-fit test failed); the \
             master curve is not a result until the reasons below are resolved.",
        ),
        "invalid" => (
            "bad",
            "at the fitted modulus the model's own assumptions fail at a measured speed; \
             the master curve is not a result.",
        ),
        _ => ("bad", "a verdict this version of rollfit does not know."),
    };
    let mut out = format!(
        "<div class=\"status {class}\" id=\"verdict\"><strong>Verdict: {}</strong> — {}\n",
        escape(&q.verdict),
        escape(meaning)
    );
    let tests = [chi2_test(q), runs_test(q), noise(q, s.condensed.as_ref())];
    list(&mut out, "tests", &tests);
    if !q.reasons.is_empty() {
        out.push_str("<p class=\"reasons\">Reasons:</p>\n");
        list(&mut out, "reasons", &q.reasons);
    }
    out.push_str("</div>\n");
    out
}

/// The χ² test in words: χ², its degrees of freedom and p when σ is
/// measured; with σ estimated from the same residuals χ² equals its
/// degrees of freedom by construction and the test says nothing.
fn chi2_test(q: &QualitySummary) -> String {
    match (q.chi2, q.degrees_of_freedom, q.chi2_p_value) {
        (Some(chi2), Some(dof), Some(p)) => format!(
            "χ² test: χ² = {} for {} degrees of freedom, p = {}",
            num(chi2),
            num(dof),
            num(p)
        ),
        (_, Some(dof), None) => format!(
            "χ² test: not made — σ is estimated from the residuals themselves, so χ² equals its \
             {} degrees of freedom by construction; the size of the estimated noise is judged \
             instead",
            num(dof)
        ),
        _ => "χ² test: not recorded in fit.json".into(),
    }
}

/// The runs test in words.
fn runs_test(q: &QualitySummary) -> String {
    match q.runs {
        Some(r) => format!(
            "runs test: {} runs of one sign in order of speed where {} are expected for random \
             signs, p = {}",
            r.observed,
            num(r.expected),
            num(r.p_value)
        ),
        None => "runs test: not made (fewer than two residuals of either sign)".into(),
    }
}

/// The noise the tests assume, its value and where it came from.
fn noise(q: &QualitySummary, condensed: Option<&CondensedSummary>) -> String {
    let value = q.noise.map_or_else(|| "not recorded".to_string(), num);
    match q.noise_source.as_deref() {
        Some("measured") => {
            format!("noise: {value} in units of the given σ (measured: the data's sigma column)")
        }
        Some("estimated") => format!(
            "noise: {value} relative scatter of μ ({} %), estimated from the residuals (no sigma \
             column)",
            q.noise.map_or_else(|| "?".to_string(), |n| num(100.0 * n))
        ),
        Some("scatter within bins") => {
            let scatter = condensed
                .and_then(|c| c.scatter)
                .map_or_else(String::new, |s| {
                    format!(
                        ", the rows scattering by {} % of μ within a bin",
                        num(100.0 * s)
                    )
                });
            format!(
                "noise: {value} in units of each bin's σ (scatter within bins: the dense data \
                 were condensed to bins and σ of a bin mean measured from its rows{scatter})"
            )
        }
        Some(other) => format!("noise: {value} ({other})"),
        None => format!("noise: {value} (source not recorded)"),
    }
}

/// Whether the scale is a banner, and in which colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Flag {
    /// Fixed by an anchor or by the data: the table row says it.
    Fine,
    /// Not known: fit.json has neither an anchor nor a scale record.
    Caution,
    /// The data do not determine it.
    Bad,
}

/// The modulus scale in words, and whether it is flagged.
fn scale(s: &FitSummary) -> (Flag, String) {
    if let Some(anchor) = &s.anchor {
        return (Flag::Fine, anchored(anchor));
    }
    match &s.scale {
        Some(scale) if scale.is_determined() => (
            Flag::Fine,
            format!(
                "from the data alone (no anchor): E0 = {} Pa, 2σ interval {}",
                num(scale.static_modulus),
                interval(scale)
            ),
        ),
        Some(scale) => {
            let mut text = format!(
                "{} — the data do not determine the modulus scale (no anchor): E0 = {} Pa is the \
                 fit's, but its 2σ interval is {}; E′, E″, E0 and E1 are known only up to a \
                 common factor (tan δ and the shape are not affected)",
                scale.status,
                num(scale.static_modulus),
                interval(scale)
            );
            if let Some(reason) = &scale.reason {
                let _ = write!(text, ". {reason}");
            }
            (Flag::Bad, text)
        }
        None => (
            Flag::Caution,
            "no anchor, and fit.json does not record whether the data determine the modulus \
             scale (no scale): E′, E″, E0 and E1 may all be off by one common factor; an anchor \
             (E0, E_at or contact_radius in the scene's [fit]) fixes it"
                .into(),
        ),
    }
}

/// "|E*| = … Pa at ω = … rad/s, from the anchor E_at".
fn anchored(anchor: &AnchorSummary) -> String {
    format!(
        "anchored by {}: |E*| = {} Pa at ω = {} rad/s",
        anchor.source,
        num(anchor.modulus),
        num(anchor.omega)
    )
}

/// The 2σ interval of E0, an open end named with the end of the profiled
/// range it reaches.
fn interval(scale: &ScaleSummary) -> String {
    let range = scale.range;
    let low = match (scale.low, range) {
        (Some(low), _) => format!("{} Pa", num(low)),
        (None, Some([lo, _])) => format!(
            "open below (down to {} Pa, the lowest E0 profiled)",
            num(lo)
        ),
        (None, None) => "open below".into(),
    };
    let high = match (scale.high, range) {
        (Some(high), _) => format!("{} Pa", num(high)),
        (None, Some([_, hi])) => {
            format!("open above (up to {} Pa, the highest E0 profiled)", num(hi))
        }
        (None, None) => "open above".into(),
    };
    format!("{low} … {high}")
}

/// The scale banner, only when the scale is flagged: red when the data do
/// not determine it, amber when fit.json does not say.
pub(super) fn scale_banner(s: &FitSummary) -> Option<String> {
    let (flag, text) = scale(s);
    let class = match flag {
        Flag::Fine => return None,
        Flag::Caution => "caution",
        Flag::Bad => "bad",
    };
    Some(format!(
        "<div class=\"status {class}\" id=\"scale\"><strong>Scale:</strong> {}.</div>\n",
        escape(&text)
    ))
}

/// The scale as the fit table's row says it (every case).
pub(super) fn scale_row(s: &FitSummary) -> String {
    escape(&scale(s).1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scale_of(low: Option<f64>, high: Option<f64>) -> ScaleSummary {
        ScaleSummary {
            status: "undetermined".into(),
            static_modulus: 2e6,
            low,
            high,
            range: Some([1e4, 1e10]),
            profile: Vec::new(),
            reason: None,
        }
    }

    fn quality(source: &str, noise: f64) -> QualitySummary {
        QualitySummary {
            verdict: "good".into(),
            noise_source: Some(source.into()),
            noise: Some(noise),
            chi2: None,
            degrees_of_freedom: None,
            chi2_p_value: None,
            runs: None,
            reasons: Vec::new(),
        }
    }

    /// Each noise source says its value and what the value is in: σ given,
    /// the relative scatter estimated, or σ of bin means from the scatter
    /// of the rows within bins (with that scatter when fit.json has it).
    #[test]
    fn the_noise_says_its_value_and_source() {
        assert_eq!(
            noise(&quality("measured", 1.0), None),
            "noise: 1.000 in units of the given σ (measured: the data's sigma column)"
        );
        assert_eq!(
            noise(&quality("estimated", 0.0312), None),
            "noise: 0.03120 relative scatter of μ (3.120 %), estimated from the residuals (no \
             sigma column)"
        );
        let condensed = CondensedSummary {
            rows: 4000,
            bins: 81,
            scatter: Some(0.025),
        };
        assert_eq!(
            noise(&quality("scatter within bins", 1.0), Some(&condensed)),
            "noise: 1.000 in units of each bin's σ (scatter within bins: the dense data were \
             condensed to bins and σ of a bin mean measured from its rows, the rows scattering \
             by 2.500 % of μ within a bin)"
        );
        assert_eq!(
            noise(&quality("guessed", 0.5), None),
            "noise: 0.5000 (guessed)"
        );
    }

    /// An open end names the end of the profiled range it reaches; a
    /// closed one is its value.
    #[test]
    fn open_ends_of_the_scale_interval_are_said() {
        assert_eq!(
            interval(&scale_of(None, Some(8e6))),
            "open below (down to 10000 Pa, the lowest E0 profiled) … 8.000e6 Pa"
        );
        assert_eq!(
            interval(&scale_of(Some(1e6), None)),
            "1.000e6 Pa … open above (up to 1.000e10 Pa, the highest E0 profiled)"
        );
        let bare = ScaleSummary {
            range: None,
            ..scale_of(None, None)
        };
        assert_eq!(interval(&bare), "open below … open above");
    }
}
