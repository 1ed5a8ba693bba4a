//! What fit.json says about how far to trust a fit, as read back for the
//! report: the goodness-of-fit verdict with its χ² and runs tests and the
//! noise they assume (`fit_quality`, written from
//! [`rollfit_fit::FitQuality`]), how well the data alone determine the
//! modulus scale of a fit without an anchor (`scale`, from
//! [`rollfit_fit::ScaleRecord`]) and how dense data were condensed
//! (`condensed`, whose within-bin scatter is then the noise).
//!
//! Like the rest of fit.json beyond the contract, every one of them is
//! optional, and within them only what names the result is required (the
//! verdict, the scale's status and E0): a fit.json from an older rollfit
//! or another program still reads, and the report says what it lacks. An
//! open end of the scale's interval is null (`E0_low`, `E0_high`).

use serde::Deserialize;

/// fit.json's `fit_quality`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct QualitySummary {
    /// "good", "poor" (a test failed: the model does not describe the
    /// data) or "invalid" (at the fitted modulus the model's own
    /// assumptions fail at a measured speed); anything else is shown as
    /// written and flagged as not good.
    pub verdict: String,
    /// "measured" (a sigma column), "estimated" (from the residuals) or
    /// "scatter within bins" (condensed dense data).
    #[serde(default)]
    pub noise_source: Option<String>,
    /// The noise level: 1 in units of the σ given or measured within
    /// bins, else the estimated relative scatter of μ.
    #[serde(default)]
    pub noise: Option<f64>,
    /// Σ r² in units of σ (measured or estimated).
    #[serde(default)]
    pub chi2: Option<f64>,
    /// N − t, t the effective number of parameters.
    #[serde(default)]
    pub degrees_of_freedom: Option<f64>,
    /// P(χ² ≥ observed), only when σ is measured.
    #[serde(default)]
    pub chi2_p_value: Option<f64>,
    /// The runs test of the residuals' signs (null with too few of either
    /// sign).
    #[serde(default)]
    pub runs: Option<RunsSummary>,
    /// Why the verdict is not "good", or what to look at.
    #[serde(default)]
    pub reasons: Vec<String>,
}

impl QualitySummary {
    /// Whether the verdict is "good" (anything else is flagged).
    pub fn is_good(&self) -> bool {
        self.verdict == "good"
    }
}

/// The runs test of fit.json's `fit_quality.runs`.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
pub struct RunsSummary {
    /// Runs of one sign, in order of speed (per temperature).
    pub observed: usize,
    /// Their expected number for random signs.
    pub expected: f64,
    /// P(as few runs or fewer).
    pub p_value: f64,
}

/// fit.json's `scale`: E0 of an unanchored fit and the 2σ interval of E0
/// the data allow (profile Δχ² ≤ 4).
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct ScaleSummary {
    /// "data" (the interval is closed within the profiled range) or
    /// "undetermined"; anything else is shown as written and flagged.
    pub status: String,
    /// E0 of the fit, Pa.
    #[serde(rename = "E0")]
    pub static_modulus: f64,
    /// Lower end of the 2σ interval of E0, Pa; None (null) when the data
    /// fit as well down to the lowest E0 profiled.
    #[serde(default, rename = "E0_low")]
    pub low: Option<f64>,
    /// Upper end, Pa; None (null) when open upward.
    #[serde(default, rename = "E0_high")]
    pub high: Option<f64>,
    /// The range of E0 profiled, Pa.
    #[serde(default, rename = "E0_range")]
    pub range: Option<[f64; 2]>,
    /// (E0 in Pa, Δχ² against the profile's best) of every profiled E0.
    #[serde(default)]
    pub profile: Vec<[f64; 2]>,
    /// What the profile says, in words.
    #[serde(default)]
    pub reason: Option<String>,
}

impl ScaleSummary {
    /// Whether the data determine the scale ("data"; anything else is
    /// flagged).
    pub fn is_determined(&self) -> bool {
        self.status == "data"
    }
}

/// fit.json's `condensed` (dense data fitted as bins).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
pub struct CondensedSummary {
    /// Rows of the data file.
    pub rows: usize,
    /// Bins the fit saw.
    pub bins: usize,
    /// Scatter of μ within the bins, relative to μ (null when σ was
    /// measured or the bins hold too few repeats).
    #[serde(default)]
    pub scatter: Option<f64>,
}
