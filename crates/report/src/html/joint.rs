//! The page's section on a joint fit of DMA and rolling data
//! (fit.json's `joint`): whether the two parts describe one material (the
//! compatibility test, highlighted when they do not), the friction factor κ
//! when fitted, each part's χ² fitted together and alone, the decades of
//! reduced frequency where a part's mean residual exceeds
//! [`DISAGREE_SIGMA`], the fit's notes, and the joint pictures.

use std::fmt::Write as _;

use rollfit_fit::JointRecord;

use super::{escape, figure, list, num};
use crate::plot::{JOINT_PICTURES, Picture};

/// A decade whose mean residual is beyond this many σ is where the parts
/// disagree: the table lists it.
pub const DISAGREE_SIGMA: f64 = 2.0;

/// The section "DMA and rolling friction together".
pub(super) fn section(joint: &JointRecord, pictures: &[Picture]) -> String {
    let mut t = String::from("<h2 id=\"joint\">DMA and rolling friction together</h2>\n");
    let _ = writeln!(
        t,
        "<p>A joint fit of {} DMA points (<code>{}</code>; each gives a residual in ln E′ and \
         one in ln E″) and {} rolling rows: one master curve and one shift for both.</p>",
        joint.dma_points,
        escape(&joint.dma_source),
        joint.rolling_points
    );
    let c = &joint.compatibility;
    let class = if c.compatible { "ok" } else { "bad" };
    let _ = writeln!(
        t,
        "<div class=\"status {class}\" id=\"joint-compatibility\"><strong>Do the DMA and the \
         rolling data describe one material?</strong> {}</div>",
        escape(&c.verdict)
    );
    if let Some(k) = &joint.friction_factor {
        let class = if k.unexplained { "caution" } else { "ok" };
        let _ = writeln!(
            t,
            "<div class=\"status {class}\" id=\"joint-friction-factor\"><strong>Friction \
             factor κ = {} ± {}</strong> (μ_measured = κ μ_theory; the rolling fit is κ times the \
             model's μ). {}</div>",
            num(k.value),
            num(k.sigma),
            escape(&k.verdict)
        );
    }
    t.push_str(&chi2_table(joint));
    t.push_str(&disagreement(joint));
    list(&mut t, "meta", &joint.notes);
    for p in pictures.iter().filter(|p| JOINT_PICTURES.contains(&p.name)) {
        figure(&mut t, p);
    }
    t.push_str(
        "<p>The rolling μ(v) with its fit is <a href=\"#friction\">friction</a> \
         (Pictures).</p>\n",
    );
    t
}

/// Each part's χ² at the joint optimum and fitted alone, and the test.
fn chi2_table(joint: &JointRecord) -> String {
    let x = &joint.chi2;
    let s = &joint.sigma;
    let rolling_sigma = match s.rolling {
        Some(r) => format!("{} relative ({})", num(r), escape(&s.rolling_source)),
        None => format!("the data's σ column ({})", escape(&s.rolling_source)),
    };
    let mut t = String::from(
        "<table id=\"joint-chi2\">\n<tr><th>part</th><th>σ</th><th>χ² joint</th>\
         <th>χ² alone</th><th>effective parameters alone</th></tr>\n",
    );
    let rows = [
        (
            "rolling friction",
            rolling_sigma,
            x.rolling_joint,
            x.rolling_alone,
            x.rolling_alone_parameters,
        ),
        (
            "DMA (E′ and E″)",
            format!("{} relative ({})", num(s.dma), escape(&s.dma_source)),
            x.dma_joint,
            x.dma_alone,
            x.dma_alone_parameters,
        ),
    ];
    for (part, sigma, together, alone, parameters) in rows {
        let _ = writeln!(
            t,
            "<tr><th>{part}</th><td>{sigma}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>\
             <td class=\"num\">{}</td></tr>",
            num(together),
            num(alone),
            num(parameters)
        );
    }
    let c = &joint.compatibility;
    let class = if c.compatible { "" } else { " class=\"warn\"" };
    let _ = writeln!(
        t,
        "<tr{class}><th>together</th><td>Δχ² = {} on {} shared degrees of freedom, p = {}; \
         the parts differ by {} decade (tolerance {} decade)</td>\
         <td class=\"num\">{}</td><td></td><td class=\"num\">{} (joint)</td></tr>",
        num(c.statistic),
        num(c.dof),
        num(c.p_value),
        num(c.effect_decades),
        num(c.tolerance_decades),
        num(x.rolling_joint + x.dma_joint),
        num(x.joint_parameters)
    );
    t.push_str("</table>\n");
    t
}

/// The decades where a part's mean residual is beyond [`DISAGREE_SIGMA`].
fn disagreement(joint: &JointRecord) -> String {
    let off: Vec<_> = joint
        .residual_ranges
        .iter()
        .filter(|r| r.mean.abs() > DISAGREE_SIGMA)
        .collect();
    if off.is_empty() {
        return format!(
            "<p id=\"joint-disagreement\">In no decade of reduced frequency is a part's mean \
             residual beyond {DISAGREE_SIGMA}σ: the parts do not pull against each other \
             anywhere in particular.</p>\n"
        );
    }
    let mut t = format!(
        "<p>Where the parts disagree: the decades of reduced angular frequency (rolling rows at \
         their contact frequency v a_T/r) where a part's mean residual is beyond {DISAGREE_SIGMA}σ \
         (residual = fit − measured; in ln E for DMA).</p>\n\
         <table id=\"joint-disagreement\">\n<tr><th>part</th><th>ω a_T (rad/s)</th>\
         <th>points</th><th>mean (σ)</th><th>RMS (σ)</th></tr>\n"
    );
    for r in off {
        let _ = writeln!(
            t,
            "<tr class=\"warn\"><th>{}</th><td>{} … {}</td><td class=\"num\">{}</td>\
             <td class=\"num\">{}</td><td class=\"num\">{}</td></tr>",
            escape(&r.part),
            num(r.omega_min),
            num(r.omega_max),
            r.points,
            num(r.mean),
            num(r.rms)
        );
    }
    t.push_str("</table>\n");
    t
}
