//! Whether the DMA and rolling parts describe one material, and where they
//! disagree.
//!
//! The test is the parameter goodness of fit of Maltoni and Schwetz: with
//! each part fitted alone (χ²_R,alone, p_R effective parameters; χ²_D,alone,
//! p_D) and both together (χ²_joint, p_J),
//!
//!   Δχ² = χ²_joint − χ²_R,alone − χ²_D,alone  ~  χ²(p_R + p_D − p_J)
//!
//! when both parts measure one material (χ² in units of each part's σ):
//! Δχ² counts only the misfit that
//! sharing the parameters forces, whatever each part's own goodness of fit
//! (a poor part alone does not make the pair incompatible). Effective
//! parameters (traces of the influence matrices) stand in for parameter
//! counts under the smoothness penalty; the degrees of freedom are at
//! least one. Where a part's σ is estimated from its fit alone
//! (σ² = χ²_alone/(N − p) of that part in the units of its weights), Δχ²
//! is measured in an estimated unit, and the test is Snedecor's F,
//!
//!   F = (Δχ²/d₁)/(Σ χ²_alone/d₂) ~ F(d₁, d₂),  d₁ = p_R + p_D − p_J,  d₂ = Σ (N − p)
//!
//! over the parts whose σ is estimated (with the χ² in those units ≈ d₂ by
//! construction, F ≈ Δχ²/d₁ and its tail is the χ² test's, widened for
//! the estimate's own scatter). The parts are called incompatible at
//! p < [`P_VALUE`].
//!
//! A χ² test alone judges sample size, not physics: every model has a small
//! approximation error (a causal Prony series cannot follow a real master
//! curve exactly, and its Kramers–Kronig relations tie E′ to E″ more
//! tightly than measured isotherms obey), and with enough points any such
//! error is significant (same-material data: p = 0.57 at 13 points per
//! isotherm, 3e-8 at 2000). So the parts are called incompatible only when
//! the test finds a difference *and* the difference is larger than the
//! modelling tolerance:
//!
//! - effect size d (decades): what sharing one material costs each part,
//!   as the RMS of the residual it adds per point, d_part = s_part
//!   √(max(0, χ²_part,joint − χ²_part,alone)/N_part)/ln 10 (s_part the
//!   part's relative σ), summed over the parts: a systematic offset between
//!   the parts is split between them by the joint fit, and the two bends
//!   add up to it;
//! - tolerance t (decades): each part's own RMS misfit alone, in decades,
//!   summed, t = Σ s_part √(χ²_part,alone/N_part)/ln 10: the noise plus
//!   what the model cannot follow of that part alone (for the DMA part its
//!   Kramers–Kronig floor: the causal master curve's miss of the
//!   isotherms);
//! - incompatible: p < [`P_VALUE`] and d > t.
//!
//! d does not grow with sampling (it is a mean per point), and for one
//! material it falls toward the model's own error as the points grow,
//! while t does not fall below it.
//!
//! The friction factor κ (μ_measured = κ μ_theory, fitted with
//! `friction_factor = "free"`) absorbs a dissipation that the bulk
//! viscoelasticity of the DMA's material does not explain; κ beyond two σ
//! from 1 is reported as such. For scale: Greenwood and Tabor (1958)
//! needed a hysteresis-loss fraction α about twice the one measured in
//! uniaxial deformation to explain rolling friction, a κ of about 2 here.
//!
//! Where the parts disagree is shown by each part's residuals (σ units)
//! averaged over decades of reduced angular frequency: a rolling row at
//! its contact frequency v a_T/r(ω) ([`crate::analysis`]'s probed band's
//! lower edge), a DMA point at ω a_T.
//!
//! # References
//! - M. Maltoni, T. Schwetz, "Testing the statistical compatibility of
//!   independent data sets", Phys. Rev. D 68 (2003) 033020.
//! - J.A. Greenwood, D. Tabor, "The friction of hard sliders on lubricated
//!   rubber: the importance of deformation losses", Proc. Phys. Soc. 71
//!   (1958) 989–1001.

use statrs::distribution::{ChiSquared, ContinuousCDF, FisherSnedecor};

use super::record::{Compatibility, FrictionFactorRecord, ResidualRange};

/// Below this p-value the parts are called incompatible.
pub const P_VALUE: f64 = 0.01;

/// χ² and effective parameters of the parts alone and together.
pub(crate) struct Parts {
    pub rolling_alone: (f64, f64),
    pub dma_alone: (f64, f64),
    /// χ² of both parts at the joint optimum, and its effective parameters.
    pub joint: (f64, f64),
    /// N − p of the parts whose σ was estimated from their fit alone (0:
    /// every σ given).
    pub estimated_dof: f64,
    /// Each part's χ² at the joint optimum, its residual rows N and its
    /// relative σ (RMS of σ_i/μ_i for the rolling rows, σ of ln E′ and
    /// ln E″ for the DMA points): rolling, then DMA.
    pub shares: [PartShare; 2],
}

/// One part's share of the joint misfit, for the effect size.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PartShare {
    /// χ² of the part at the joint optimum.
    pub joint: f64,
    /// Residual rows of the part.
    pub rows: usize,
    /// Relative σ of the part's rows.
    pub sigma: f64,
}

/// The effect size and the tolerance, decades (module doc).
fn effect_and_tolerance(parts: &Parts) -> (f64, f64) {
    let alone = [parts.rolling_alone.0, parts.dma_alone.0];
    let per_point = |chi2: f64, share: &PartShare| {
        share.sigma * (chi2.max(0.0) / share.rows.max(1) as f64).sqrt() / std::f64::consts::LN_10
    };
    let (mut effect, mut tolerance) = (0.0, 0.0);
    for (share, alone) in parts.shares.iter().zip(alone) {
        effect += per_point(share.joint - alone, share);
        tolerance += per_point(alone, share);
    }
    (effect, tolerance)
}

/// The parameter goodness-of-fit test (module doc); `factor_free`: κ was
/// fitted (`friction_factor = "free"`), so advice to free it is moot.
pub(crate) fn compatibility(parts: &Parts, factor_free: bool) -> Compatibility {
    let statistic = (parts.joint.0 - parts.rolling_alone.0 - parts.dma_alone.0).max(0.0);
    let dof = (parts.rolling_alone.1 + parts.dma_alone.1 - parts.joint.1).max(1.0);
    let p_value = if parts.estimated_dof > 0.0 {
        FisherSnedecor::new(dof, parts.estimated_dof).map_or(f64::NAN, |d| d.sf(statistic / dof))
    } else {
        ChiSquared::new(dof).map_or(f64::NAN, |d| d.sf(statistic))
    };
    let (effect, tolerance) = effect_and_tolerance(parts);
    // A test that could not be made (NaN) is no evidence against the pair.
    let significant = !p_value.is_nan() && p_value < P_VALUE;
    let compatible = !(significant && effect > tolerance);
    let size = format!(
        "the parts differ by {effect:.3} decade where they overlap, against a modelling \
         tolerance of {tolerance:.3} decade (each part's own misfit alone: its noise and what \
         the model cannot follow of it)"
    );
    let verdict = if !compatible {
        format!(
            "incompatible: fitted together the parts lose Δχ² = {statistic:.1} against {dof:.1} \
             shared degrees of freedom (p = {p_value:.1e}), and {size}; the rolling friction is \
             not the bulk hysteresis of the DMA's material (an extra dissipation such as \
             adhesion or a surface layer, a strain-amplitude effect, or a different compound or \
             temperature calibration). See residual_ranges for where they disagree; {}",
            if factor_free {
                "κ is already fitted, so the difference is not one constant factor of μ"
            } else {
                "friction_factor = \"free\" measures an extra dissipation as κ"
            }
        )
    } else if significant {
        format!(
            "compatible: fitted together the parts lose Δχ² = {statistic:.1} against {dof:.1} \
             shared degrees of freedom (p = {p_value:.1e}, a difference the data resolve), but \
             {size}: within what the model itself misses, one material describes both"
        )
    } else {
        format!(
            "compatible: fitted together the parts lose Δχ² = {statistic:.1} against {dof:.1} \
             shared degrees of freedom (p = {p_value:.2}), and {size}; one material describes \
             both"
        )
    };
    Compatibility {
        statistic,
        dof,
        p_value,
        effect_decades: effect,
        tolerance_decades: tolerance,
        compatible,
        verdict,
    }
}

/// κ with its 1σ as the report states it.
pub(crate) fn friction_factor(value: f64, sigma: f64) -> FrictionFactorRecord {
    let unexplained = (value - 1.0).abs() > 2.0 * sigma;
    let verdict = if unexplained {
        format!(
            "κ = {value:.3} ± {sigma:.3}: the rolling friction is {:.0} % {} than the bulk \
             viscoelasticity of the DMA's material explains (beyond 2σ); for scale, Greenwood \
             and Tabor needed about twice the uniaxial hysteresis loss, κ ≈ 2",
            100.0 * (value - 1.0).abs(),
            if value > 1.0 { "higher" } else { "lower" }
        )
    } else {
        format!(
            "κ = {value:.3} ± {sigma:.3}: within 2σ of 1, the rolling friction is the bulk \
             hysteresis of the DMA's material"
        )
    };
    FrictionFactorRecord {
        value,
        sigma,
        unexplained,
        verdict,
    }
}

/// Mean and RMS of `residuals` (σ units) over decades of `omega` (rad/s),
/// for the part named `part`.
pub(crate) fn residual_ranges(part: &str, omega: &[f64], residuals: &[f64]) -> Vec<ResidualRange> {
    let mut decades: Vec<i32> = omega.iter().map(|w| w.log10().floor() as i32).collect();
    let order = decades.clone();
    decades.sort_unstable();
    decades.dedup();
    decades
        .into_iter()
        .map(|d| {
            let inside: Vec<f64> = order
                .iter()
                .zip(residuals)
                .filter(|(k, _)| **k == d)
                .map(|(_, r)| *r)
                .collect();
            let n = inside.len() as f64;
            ResidualRange {
                part: part.to_string(),
                omega_min: 10f64.powi(d),
                omega_max: 10f64.powi(d + 1),
                points: inside.len(),
                mean: inside.iter().sum::<f64>() / n,
                rms: (inside.iter().map(|r| r * r).sum::<f64>() / n).sqrt(),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The statistic against the χ² distribution: Δχ² at its dof's median
    /// is compatible, far above it is not; p falls as Δχ² grows.
    #[test]
    fn compatibility_follows_the_chi_square_tail() {
        let parts = |joint: f64| Parts {
            rolling_alone: (40.0, 8.0),
            dma_alone: (100.0, 14.0),
            joint: (joint, 16.0),
            estimated_dof: 0.0,
            shares: [
                PartShare {
                    joint: 40.0 + (joint - 140.0) / 2.0,
                    rows: 48,
                    sigma: 0.02,
                },
                PartShare {
                    joint: 100.0 + (joint - 140.0) / 2.0,
                    rows: 120,
                    sigma: 0.01,
                },
            ],
        };
        // dof = 8 + 14 − 16 = 6, median ≈ 5.35.
        let c = compatibility(&parts(145.35), false);
        assert!(
            (c.dof - 6.0).abs() < 1e-12 && (c.p_value - 0.5).abs() < 0.01,
            "{c:?}"
        );
        assert!(c.compatible);
        // Δχ² = 30 over 168 rows: significant, but 0.006 decade against a
        // tolerance of 0.012 (2 % and 1 % noise): the model's own error.
        let near = compatibility(&parts(140.0 + 30.0), false);
        assert!(near.p_value < 1e-4, "{near:?}");
        assert!(near.compatible && near.effect_decades < near.tolerance_decades);
        assert!(near.verdict.contains("within what the model itself misses"));
        // Δχ² = 3000: each part bent by several times its noise.
        let far = compatibility(&parts(140.0 + 3000.0), false);
        assert!(!far.compatible && far.effect_decades > 0.05, "{far:?}");
        assert!(far.verdict.contains("incompatible"));
        assert!(far.verdict.contains("friction_factor = \"free\" measures"));
        // With κ fitted already, freeing it is no advice.
        let freed = compatibility(&parts(140.0 + 3000.0), true);
        assert!(!freed.verdict.contains("friction_factor = \"free\""));
        assert!(freed.verdict.contains("κ is already fitted"));
    }

    /// The effect size is the bend per point: the same Δχ² per point on ten
    /// times the rows gives the same effect, where p falls by orders.
    #[test]
    fn the_effect_size_does_not_grow_with_sampling() {
        let parts = |scale: f64| Parts {
            rolling_alone: (40.0 * scale, 8.0),
            dma_alone: (100.0 * scale, 14.0),
            joint: (140.0 * scale + 10.0 * scale, 16.0),
            estimated_dof: 0.0,
            shares: [
                PartShare {
                    joint: 45.0 * scale,
                    rows: (48.0 * scale) as usize,
                    sigma: 0.02,
                },
                PartShare {
                    joint: 105.0 * scale,
                    rows: (120.0 * scale) as usize,
                    sigma: 0.01,
                },
            ],
        };
        let (few, many) = (
            compatibility(&parts(1.0), false),
            compatibility(&parts(10.0), false),
        );
        assert!(many.p_value < 1e-3 * few.p_value, "{few:?} {many:?}");
        assert!((few.effect_decades - many.effect_decades).abs() < 1e-12);
        assert!(few.compatible && many.compatible);
    }

    #[test]
    fn residuals_are_averaged_per_decade() {
        let r = residual_ranges("rolling", &[2.0, 5.0, 20.0], &[1.0, 3.0, -2.0]);
        assert_eq!(r.len(), 2);
        assert_eq!((r[0].points, r[0].mean, r[0].rms), (2, 2.0, 5f64.sqrt()));
        assert_eq!((r[1].omega_min, r[1].mean), (10.0, -2.0));
    }
}
