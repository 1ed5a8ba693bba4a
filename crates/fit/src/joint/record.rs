//! What a joint fit of DMA and rolling data reports beside the usual fit
//! (fit.json's `joint`): each part's χ², the compatibility test, the
//! friction factor κ, where the parts disagree, and every DMA point with
//! the joint curve's value there.

use serde::{Deserialize, Serialize};

/// The joint fit's account of its two sources.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointRecord {
    /// The DMA file (as given).
    pub dma_source: String,
    /// DMA points (ω, T); each gives a residual in ln E′ and one in ln E″.
    pub dma_points: usize,
    /// Rolling rows (after condensing).
    pub rolling_points: usize,
    /// The weights of each part.
    pub sigma: JointSigma,
    /// Each part's χ² at the joint optimum and fitted alone.
    pub chi2: PartChi2,
    /// What the DMA part says alone: which shifts it determines, with
    /// their σ, and its verdict (absent in records written before it was
    /// reported).
    #[serde(default)]
    pub dma_alone: DmaAloneRecord,
    /// Whether the two parts describe one material.
    pub compatibility: Compatibility,
    /// μ_measured = κ μ_theory: fitted with `friction_factor = "free"`
    /// (absent: κ = 1 was assumed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_factor: Option<FrictionFactorRecord>,
    /// Mean and RMS residual of each part over decades of reduced
    /// frequency: where the parts disagree.
    pub residual_ranges: Vec<ResidualRange>,
    /// Every DMA point with the joint master curve at its reduced
    /// frequency.
    pub dma: Vec<DmaFitPoint>,
    /// How the start and the law were found, and what the user should know.
    pub notes: Vec<String>,
}

/// The DMA part fitted alone ([`super::alone`]).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct DmaAloneRecord {
    /// One sentence for the user: which shifts the isotherms alone
    /// determine, and where the others come from.
    pub verdict: String,
    /// The law of the DMA master curve alone ("wlf", "arrhenius",
    /// "wlf-arrhenius", "free"); None where the isotherms determine no
    /// shift.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub law: Option<String>,
    /// Its reference temperature, °C.
    #[serde(rename = "T_ref", skip_serializing_if = "Option::is_none")]
    pub t_ref: Option<f64>,
    /// Per isotherm, ascending in temperature.
    pub shifts: Vec<DmaAloneShift>,
}

/// One isotherm's shift as the DMA part alone measures it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DmaAloneShift {
    /// Temperature, °C.
    #[serde(rename = "T")]
    pub temperature: f64,
    /// Whether the isotherms alone determine this shift.
    pub determined: bool,
    /// log10 a_T measured by the overlaps, about the DMA part's T_ref
    /// (null where not determined).
    #[serde(rename = "log_aT")]
    pub log_shift: Option<f64>,
    /// Its 1σ, decades (null where not determined).
    #[serde(rename = "log_aT_sigma")]
    pub log_shift_sigma: Option<f64>,
}

/// The relative standard deviations each part is weighted by.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointSigma {
    /// Relative σ of E′ and E″ (ln-residual units).
    pub dma: f64,
    /// "given" (`dma_sigma`) or "estimated" (from the DMA master curve's
    /// residuals).
    pub dma_source: String,
    /// The rolling rows' relative σ when estimated (None: measured σ
    /// column used).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rolling: Option<f64>,
    /// "given" (a σ column) or "estimated" (from the rolling fit alone).
    pub rolling_source: String,
}

/// χ² of each part, in units of its σ.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PartChi2 {
    /// Rolling residuals at the joint optimum.
    pub rolling_joint: f64,
    /// DMA residuals (E′ and E″) at the joint optimum.
    pub dma_joint: f64,
    /// Rolling residuals of the rolling data fitted alone.
    pub rolling_alone: f64,
    /// DMA residuals of the DMA master curve (its shifts and Prony series)
    /// fitted alone.
    pub dma_alone: f64,
    /// Effective parameters of the rolling fit alone.
    pub rolling_alone_parameters: f64,
    /// Effective parameters of the DMA fit alone.
    pub dma_alone_parameters: f64,
    /// Effective parameters of the joint fit.
    pub joint_parameters: f64,
}

/// The parameter goodness-of-fit test: how much worse the parts fit
/// together than apart.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Compatibility {
    /// Δχ² = χ²_joint − χ²_rolling,alone − χ²_DMA,alone.
    pub statistic: f64,
    /// Degrees of freedom: the effective parameters the parts share.
    pub dof: f64,
    /// P(χ²_dof ≥ statistic).
    pub p_value: f64,
    /// How far apart the parts are where they overlap, decades: the RMS
    /// residual that sharing one material adds to each part, summed
    /// ([`crate::joint::consistency`]).
    #[serde(default)]
    pub effect_decades: f64,
    /// The modelling tolerance, decades: each part's own RMS misfit alone
    /// (noise and the model's approximation error), summed.
    #[serde(default)]
    pub tolerance_decades: f64,
    /// Not both p < 0.01 and an effect beyond the tolerance.
    pub compatible: bool,
    /// One sentence for the user.
    pub verdict: String,
}

/// The fitted friction factor κ.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FrictionFactorRecord {
    /// κ.
    pub value: f64,
    /// 1σ of κ.
    pub sigma: f64,
    /// |κ − 1| > 2σ: friction the bulk viscoelasticity does not explain.
    pub unexplained: bool,
    /// One sentence for the user (with Greenwood–Tabor's α for scale).
    pub verdict: String,
}

/// One part's residuals over one decade of reduced frequency.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ResidualRange {
    /// "rolling", "dma E′" or "dma E″".
    pub part: String,
    /// Reduced angular frequency range, rad/s (rolling: v a_T / r, r the
    /// static contact size).
    pub omega_min: f64,
    /// Upper end, rad/s.
    pub omega_max: f64,
    /// Points in the range.
    pub points: usize,
    /// Mean residual, σ units.
    pub mean: f64,
    /// RMS residual, σ units.
    pub rms: f64,
}

/// A DMA point and the joint curve at its reduced frequency.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DmaFitPoint {
    /// Isotherm temperature, °C.
    pub temperature: f64,
    /// Measured angular frequency, rad/s.
    pub omega: f64,
    /// ω a_T, rad/s, with the joint fit's a_T.
    pub reduced_omega: f64,
    /// Measured E′, Pa.
    pub storage: f64,
    /// Measured E″, Pa.
    pub loss: f64,
    /// The joint curve's E′ (times b_T where vertical factors are known),
    /// Pa.
    pub storage_fit: f64,
    /// The joint curve's E″, Pa.
    pub loss_fit: f64,
}
