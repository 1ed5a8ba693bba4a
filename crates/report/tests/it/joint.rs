//! The report of a joint fit of DMA and rolling data:
//! with fit.json's `joint` the page gets the section "DMA and rolling
//! friction together" (the compatibility verdict, highlighted when the
//! parts are incompatible, κ ± σ with its verdict, each part's χ², the
//! decades where the parts disagree) and two pictures, the joint master
//! curve and the residuals of both parts; friction.png's dense curve
//! carries κ. Without `joint` nothing changes.
//!
//! The joint record is made by hand on the committed temperature set
//! (examples/fits/hn-rubber-tset): DMA isotherms taken from its own master
//! curve and shift, with a known misfit.

use crate::common;

use common::{Decoded, assert_contains, committed_fit, count, decode, dense_line};
use plotters::style::RGBColor;
use rollfit_fit::joint::{
    Compatibility, DmaFitPoint, FrictionFactorRecord, JointRecord, JointSigma, PartChi2,
    ResidualRange,
};
use rollfit_io::FitDir;
use rollfit_report::ReportError;
use rollfit_report::fitted_friction::{FittedLine, dense_curves, friction_factor};
use rollfit_report::html::report_html;
use rollfit_report::plot::joint_residuals::JointResidualsFigure;
use rollfit_report::plot::{JOINT_PICTURES, Picture, pictures, style};

/// Isotherms of the hand-made DMA data, °C.
const ISOTHERMS: [f64; 4] = [-20.0, 0.0, 20.0, 40.0];
/// Relative σ of the DMA part.
const DMA_SIGMA: f64 = 0.02;
/// The isotherm the hand-made E″ misses by 3σ.
const OFF_ISOTHERM: f64 = 40.0;

/// DMA points on `fit`'s own master curve at ω = 0.1 … 100 rad/s per
/// isotherm, E′ off by ±0.5σ alternately, E″ exact but at
/// [`OFF_ISOTHERM`], where it is 3σ above the curve.
fn dma_points(fit: &FitDir) -> Vec<DmaFitPoint> {
    let shift = fit.summary.shift.as_ref().unwrap();
    let mut points = Vec::new();
    for t in ISOTHERMS {
        for k in 0..7 {
            let omega = 10f64.powf(-1.0 + 0.5 * f64::from(k));
            let reduced = omega * 10f64.powf(shift.log_shift_at(t).unwrap());
            let e = fit.modulus_at(reduced);
            let storage_off = if k % 2 == 0 { 0.5 } else { -0.5 };
            let loss_off = if t == OFF_ISOTHERM { -3.0 } else { 0.0 };
            points.push(DmaFitPoint {
                temperature: t,
                omega,
                reduced_omega: reduced,
                storage: e.re * (-storage_off * DMA_SIGMA).exp(),
                loss: e.im * (-loss_off * DMA_SIGMA).exp(),
                storage_fit: e.re,
                loss_fit: e.im,
            });
        }
    }
    points
}

/// A joint record on `fit`: incompatible with a fitted κ, or compatible
/// without one.
fn record(fit: &FitDir, compatible: bool) -> JointRecord {
    let dma = dma_points(fit);
    let range = |part: &str, mean: f64| ResidualRange {
        part: part.into(),
        omega_min: 1e3,
        omega_max: 1e4,
        points: 7,
        mean,
        rms: mean.abs() + 0.5,
    };
    JointRecord {
        dma_source: "data/hn-rubber-dma.csv".into(),
        dma_points: dma.len(),
        rolling_points: fit.friction.len(),
        sigma: JointSigma {
            dma: DMA_SIGMA,
            dma_source: "given".into(),
            rolling: Some(0.01),
            rolling_source: "estimated".into(),
        },
        chi2: PartChi2 {
            rolling_joint: 130.5,
            dma_joint: 90.25,
            rolling_alone: 101.0,
            dma_alone: 55.0,
            rolling_alone_parameters: 12.0,
            dma_alone_parameters: 14.0,
            joint_parameters: 16.0,
        },
        dma_alone: Default::default(),
        compatibility: Compatibility {
            statistic: if compatible { 8.0 } else { 64.75 },
            dof: 10.0,
            p_value: if compatible { 0.63 } else { 5.4e-10 },
            effect_decades: if compatible { 0.004 } else { 0.12 },
            tolerance_decades: 0.013,
            compatible,
            verdict: if compatible {
                "compatible: one material describes both".into()
            } else {
                "incompatible: the rolling friction is not the bulk hysteresis".into()
            },
        },
        friction_factor: (!compatible).then(|| FrictionFactorRecord {
            value: 1.375,
            sigma: 0.0625,
            unexplained: true,
            verdict: "κ beyond 2σ of 1: friction the bulk viscoelasticity does not explain".into(),
        }),
        residual_ranges: vec![
            range("rolling", 0.4),
            range("dma E′", -1.5),
            range("dma E″", if compatible { 1.0 } else { -3.25 }),
        ],
        dma,
        notes: vec!["start from the DMA master curve".into()],
    }
}

/// `fit` with `joint` in its fit.json.
fn with_joint(fit: &FitDir, joint: JointRecord) -> FitDir {
    let mut joint_fit = fit.clone();
    joint_fit.summary.joint = Some(joint);
    joint_fit
}

/// The text of an SVG's `<text>` elements, one a line.
fn svg_text(p: &Picture) -> String {
    let doc = roxmltree::Document::parse(&p.svg).expect("the SVG parses as XML");
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text().map(str::to_string))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The element with `id` in `page`, up to its end tag `end`.
fn element<'a>(page: &'a str, id: &str, end: &str) -> &'a str {
    let at = page
        .find(&format!("id=\"{id}\""))
        .unwrap_or_else(|| panic!("no id {id}"));
    let start = page[..at].rfind('<').unwrap();
    let stop = at + page[at..].find(end).unwrap() + end.len();
    &page[start..stop]
}

#[test]
fn an_incompatible_joint_fit_gets_its_section_with_the_verdict_and_kappa() {
    let plain = committed_fit("hn-rubber-tset");
    let fit = with_joint(&plain, record(&plain, false));
    let all = pictures(&fit, &[], &FittedLine::AtData { why: "test".into() }).unwrap();
    // After the pictures of the temperature set, the joint ones.
    let names: Vec<&str> = all.iter().map(|p| p.name).collect();
    assert_eq!((names.len(), &names[6..]), (8, &JOINT_PICTURES[..]));
    let page = report_html(&fit, &all, None);
    assert_contains(
        &page,
        &[
            "<h2 id=\"joint\">DMA and rolling friction together</h2>",
            "<a href=\"#joint\">joint fit with the DMA data</a> <code>data/hn-rubber-dma.csv</code>",
            "28 DMA points",
            "start from the DMA master curve",
            "<a href=\"#friction\">friction</a>",
        ],
    );
    let verdict = element(&page, "joint-compatibility", "</div>");
    assert_contains(
        verdict,
        &[
            "class=\"status bad\"",
            "describe one material?</strong> incompatible: the rolling friction is not the bulk hysteresis",
        ],
    );
    let kappa = element(&page, "joint-friction-factor", "</div>");
    assert_contains(
        kappa,
        &[
            "class=\"status caution\"",
            "κ = 1.375 ± 0.06250",
            "does not explain",
        ],
    );
    let chi2 = element(&page, "joint-chi2", "</table>");
    assert_contains(
        chi2,
        &[
            "rolling friction",
            "0.01000 relative (estimated)",
            "130.5",
            "101.0",
            "DMA (E′ and E″)",
            "0.02000 relative (given)",
            "90.25",
            "<tr class=\"warn\"><th>together</th><td>Δχ² = 64.75 on 10.00 shared degrees of freedom, p = 5.400e-10",
            "220.8",
        ],
    );
    // Only the decade beyond 2σ is listed.
    let ranges = element(&page, "joint-disagreement", "</table>");
    assert_contains(ranges, &["dma E″", "-3.250", "3.750"]);
    assert!(!ranges.contains("dma E′") && !ranges.contains(">rolling<"));
    // The joint pictures stand in the section, before the other pictures,
    // once each.
    let section = &page[page.find("id=\"joint\"").unwrap()..page.find("<h2>Pictures").unwrap()];
    for name in JOINT_PICTURES {
        assert!(
            section.contains(&format!("<figure id=\"{name}\">")),
            "{name}"
        );
        assert_eq!(page.matches(&format!("<figure id=\"{name}\">")).count(), 1);
    }
    assert!(page.contains("<figure id=\"friction\">"));
    let friction = &all[0];
    assert_contains(&friction.caption, &["κ = 1.3750 ± 0.0625"]);
}

#[test]
fn a_compatible_joint_fit_without_kappa_says_so_in_green() {
    let plain = committed_fit("hn-rubber-tset");
    let fit = with_joint(&plain, record(&plain, true));
    let all = pictures(&fit, &[], &FittedLine::AtData { why: "test".into() }).unwrap();
    let page = report_html(&fit, &all, None);
    let verdict = element(&page, "joint-compatibility", "</div>");
    assert_contains(
        verdict,
        &["class=\"status ok\"", "</strong> compatible: one material"],
    );
    assert!(!page.contains("joint-friction-factor"));
    assert!(!page.contains("κ ="));
    let none = element(&page, "joint-disagreement", "</p>");
    assert_contains(none, &["In no decade", "beyond 2σ"]);
    assert!(!element(&page, "joint-chi2", "</table>").contains("class=\"warn\""));
}

/// Checks the PNG and SVG of `p`: decoded at its size, not blank.
fn check(p: &Picture) -> Decoded {
    let image = decode(p);
    assert_eq!((image.width, image.height), p.size, "{}", p.name);
    let white = count(&image, RGBColor(255, 255, 255));
    assert!(white < (image.width * image.height) as usize * 97 / 100);
    assert!(p.svg.len() > 1000);
    image
}

#[test]
fn the_joint_pictures_render_with_their_axes_legends_and_temperatures() {
    let plain = committed_fit("hn-rubber-tset");
    let fit = with_joint(&plain, record(&plain, false));
    let all = pictures(&fit, &[], &FittedLine::AtData { why: "test".into() }).unwrap();
    let master = all.iter().find(|p| p.name == "joint_master").unwrap();
    check(master);
    assert_contains(
        &svg_text(master),
        &[
            "Master curve of the DMA isotherms at T_ref = 20 °C",
            "reduced frequency ω a_T (rad/s), T_ref = 20 °C",
            "E′ (storage), per isotherm",
            "Prony E′",
            "Prony E″",
            "tan δ",
            "Shift factors a_T",
            "WLF, T_ref = ",
            "C1 = ",
            "Isotherm colours",
            "-20 °C (coldest)",
            "40 °C (warmest)",
        ],
    );
    assert_contains(
        &master.caption,
        &[
            "Joint master curve at T_ref = 20 °C",
            "28 points of 4 DMA isotherms",
        ],
    );

    let residuals = all.iter().find(|p| p.name == "joint_residuals").unwrap();
    assert_contains(&residuals.caption, &["σ = 2.000 % of E, given"]);
    let image = check(residuals);
    let text = svg_text(residuals);
    assert_contains(
        &text,
        &[
            "Joint fit residuals: DMA (σ units)",
            "reduced frequency ω a_T (rad/s)",
            "ln(E_fit/E_meas)/σ",
            "E′: ln(E′_fit/E′)/σ, per isotherm",
            "E″: ln(E″_fit/E″)/σ, per isotherm",
            "-20 °C (coldest)",
            "40 °C (warmest)",
            "±2σ",
            "Joint fit residuals: rolling friction (σ units)",
            "reduced speed v·a_T (m/s)",
            "(μ_fit − μ_meas)/σ",
            "T = -20 °C",
            "T = 60 °C",
        ],
    );
    // The coldest isotherm's markers are in the coldest colour of the ramp.
    assert!(count(&image, style::cold_to_warm(0.0)) > 20);
}

#[test]
fn the_residuals_are_each_parts_own_in_sigma_units() {
    let plain = committed_fit("hn-rubber-tset");
    let joint = record(&plain, false);
    let figure = JointResidualsFigure {
        fit: &plain,
        joint: &joint,
    };
    let (storage, loss) = figure.dma_residuals();
    assert_eq!((storage.len(), loss.len()), (28, 28));
    for (k, p) in storage.iter().enumerate() {
        let expected = if k % 7 % 2 == 0 { 0.5 } else { -0.5 };
        assert!((p.1 - expected).abs() < 1e-9, "{k}: {}", p.1);
    }
    // E″ of the last isotherm, 3σ above the curve: fit − measured = −3σ.
    assert!(loss[21..].iter().all(|p| (p.1 + 3.0).abs() < 1e-9));
    assert!(loss[..21].iter().all(|p| p.1.abs() < 1e-9));
    let rolling = figure.rolling_residuals();
    assert_eq!(rolling.len(), 5);
    let rows = &rollfit_report::fitted_friction::temperature_groups(&plain.friction)[0].1;
    let r = &rows[0];
    let expected = (r.mu_fit - r.mu_measured) / (0.01 * r.mu_measured);
    assert_eq!(rolling[0].0, Some(-20.0));
    assert!((rolling[0].1[0].1 - expected).abs() < 1e-12);
    assert!((rolling[0].1[0].0 - r.reduced_speed.unwrap().log10()).abs() < 1e-12);
}

/// friction.png's dense curve of a joint fit is κ times the model's μ, as
/// the fit's `mu_fit`; the same rows without the record do not match the
/// scene. Without `joint`, κ is 1.
#[test]
fn the_dense_fitted_friction_carries_kappa() {
    let plain = committed_fit("hn-rubber");
    assert_eq!(friction_factor(&plain.summary), 1.0);
    let FittedLine::Dense(curves) = dense_line(&plain, "hn-rubber") else {
        unreachable!()
    };
    let kappa = 1.375;
    let mut scaled = plain.clone();
    for row in &mut scaled.friction {
        row.mu_fit *= kappa;
    }
    let scene = common::scene("hn-rubber");
    assert!(matches!(
        dense_curves(&scaled, &scene),
        Err(ReportError::SceneMismatch { .. })
    ));
    let mut joint = record(&committed_fit("hn-rubber-tset"), false);
    joint.friction_factor.as_mut().unwrap().value = kappa;
    let scaled = with_joint(&scaled, joint);
    assert_eq!(friction_factor(&scaled.summary), kappa);
    let with_kappa = dense_curves(&scaled, &scene).expect("κ reproduces mu_fit");
    for (a, b) in curves[0].friction.iter().zip(&with_kappa[0].friction) {
        assert!((b / (kappa * a) - 1.0).abs() < 1e-12);
    }
}

/// Without `joint` the page and the pictures are those of a fit of rolling
/// data alone: no section, no joint picture, the pictures section as it
/// was (.ci/regen-fits compares the committed examples byte for byte).
#[test]
fn without_joint_nothing_changes() {
    let plain = committed_fit("hn-rubber-tset");
    let line = dense_line(&plain, "hn-rubber-tset");
    // (tests/pictures.rs checks the names of the plain set's pictures.)
    let all = pictures(&plain, &[], &line).unwrap();
    assert!(all.iter().all(|p| !JOINT_PICTURES.contains(&p.name)));
    let page = report_html(&plain, &all, None);
    for absent in [
        "DMA and rolling friction together",
        "id=\"joint",
        "#joint",
        "joint_master",
        "joint_residuals",
        "κ",
    ] {
        assert!(!page.contains(absent), "{absent}");
    }
    // The joint fit's page is this page with the section before the
    // pictures and the two joint pictures in it.
    let fit = with_joint(&plain, record(&plain, true));
    let joint_all = pictures(&fit, &[], &line).unwrap();
    assert_eq!(joint_all.len(), all.len() + JOINT_PICTURES.len());
    for (a, b) in all.iter().zip(&joint_all) {
        assert_eq!((a.name, &a.svg, &a.png), (b.name, &b.svg, &b.png));
    }
    let joint_page = report_html(&fit, &joint_all, None);
    let tail = |page: &str| page[page.find("<h2>Pictures").unwrap()..].to_string();
    assert_eq!(tail(&page), tail(&joint_page));
}
