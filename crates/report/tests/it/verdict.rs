//! The report shows the verdict. report.html opens with
//! the fit's verdict, its tests and the noise they assume, and the modulus
//! scale (the anchor, or the data's interval of E0, flagged when the data
//! do not determine it); the friction picture's title carries the verdict
//! and the master curve's names T_ref; friction.png draws a dense fitted
//! μ(v) per temperature of a set (the curve itself: tests/fitted_friction.rs).
//!
//! The fits are the committed examples under examples/fits/ with their scenes under
//! data/ (sparse σ-weighted data; a temperature set; laboratory-shaped data
//! without σ), and copies of them whose fit.json is edited here: without a
//! scale, with an undetermined scale whose interval is open at both ends,
//! without fit_quality.

use crate::common;

use common::{TempDir, assert_contains, committed_fit, dense_line, model, scene, workspace};
use rollfit_io::FitDir;
use rollfit_report::fitted_friction::{FittedLine, temperature_groups};
use rollfit_report::html::{num, report_html};
use rollfit_report::plot::friction::FrictionFigure;
use rollfit_report::plot::master_curve::MasterCurveFigure;
use rollfit_report::plot::{Picture, pictures};

/// A copy of a committed fit with fit.json edited by `edit`.
struct EditedFit(TempDir);

impl EditedFit {
    fn new(name: &str, edit: impl FnOnce(&mut serde_json::Value)) -> EditedFit {
        let folder = TempDir::new(name);
        let dir = folder.path();
        let from = workspace().join("examples/fits").join(name);
        for file in ["mu.csv", "modulus.csv"] {
            std::fs::copy(from.join(file), dir.join(file)).unwrap();
        }
        let text = std::fs::read_to_string(from.join("fit.json")).unwrap();
        let mut json: serde_json::Value = serde_json::from_str(&text).unwrap();
        edit(&mut json);
        std::fs::write(
            dir.join("fit.json"),
            serde_json::to_string_pretty(&json).unwrap(),
        )
        .unwrap();
        EditedFit(folder)
    }

    fn read(&self) -> FitDir {
        FitDir::read(self.0.path()).expect("the edited fit reads")
    }
}

/// The pictures and report.html of `fit` with its fitted line `line`.
fn report(fit: &FitDir, line: &FittedLine) -> (Vec<Picture>, String) {
    let all = pictures(fit, &[], line).unwrap();
    let page = report_html(fit, &all, None);
    (all, page)
}

/// The text of the SVG's `<text>` elements.
fn svg_text(p: &Picture) -> String {
    let doc = roxmltree::Document::parse(&p.svg).expect("the SVG parses");
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text())
        .collect::<Vec<_>>()
        .join("\n")
}

/// The `<div ... id="{id}">…</div>` of the page (None when absent), and
/// that it comes before the fit's table: at the top, not buried.
fn banner<'a>(page: &'a str, id: &str) -> Option<&'a str> {
    let start = page.find(&format!("id=\"{id}\""))?;
    let open = page[..start].rfind("<div").unwrap();
    let end = start + page[start..].find("</div>").unwrap();
    assert!(
        open < page.find("<h2>Fit</h2>").unwrap(),
        "the {id} banner is below the fit's table"
    );
    Some(&page[open..end])
}

/// The banner `id`, which must be there in the colour `class`.
fn flagged<'a>(page: &'a str, id: &str, class: &str) -> &'a str {
    let found = banner(page, id).unwrap_or_else(|| panic!("no {id} banner"));
    let expected = format!("<div class=\"status {class}\" id=\"{id}\">");
    assert!(found.starts_with(&expected), "{found}");
    found
}

/// σ given, anchored by E_at, no `scale` in fit.json: a green verdict with
/// the χ² test, the runs test and the noise in units of σ; the anchor in
/// the table and no scale banner. Without σ (lab-ball) the noise is the
/// estimated relative scatter and the χ² test is said not to be made.
#[test]
fn the_page_opens_with_the_verdict_its_tests_the_noise_and_the_anchor() {
    let fit = committed_fit("hn-rubber");
    assert!(
        fit.summary.scale.is_none(),
        "the example has no scale record"
    );
    let q = fit.summary.fit_quality.clone().expect("fit_quality");
    let (all, page) = report(&fit, &dense_line(&fit, "hn-rubber"));
    let verdict = flagged(&page, "verdict", "ok");
    let runs = q.runs.expect("a runs test");
    assert_contains(
        verdict,
        &[
            "Verdict: good",
            &format!(
                "χ² = {} for {} degrees of freedom, p = {}",
                num(q.chi2.unwrap()),
                num(q.degrees_of_freedom.unwrap()),
                num(q.chi2_p_value.unwrap())
            ),
            &format!(
                "{} runs of one sign in order of speed where {} are expected",
                runs.observed,
                num(runs.expected)
            ),
            &format!("p = {}", num(runs.p_value)),
            "noise: 1.000 in units of the given σ (measured",
        ],
    );
    assert_eq!(q.noise_source.as_deref(), Some("measured"));
    let anchor = fit.summary.anchor.clone().expect("an anchor");
    assert_contains(
        &page,
        &[&format!(
            "<tr><th>scale</th><td>anchored by {}: |E*| = {} Pa at ω = {} rad/s",
            anchor.source,
            num(anchor.modulus),
            num(anchor.omega)
        )],
    );
    assert!(
        banner(&page, "scale").is_none(),
        "an anchored scale is no banner"
    );
    assert!(svg_text(&all[0]).contains("Rolling friction μ(v) — verdict: good"));

    let fit = committed_fit("lab-ball");
    let q = fit.summary.fit_quality.clone().expect("fit_quality");
    assert_eq!(q.noise_source.as_deref(), Some("estimated"));
    let noise = q.noise.unwrap();
    let (_, page) = report(&fit, &dense_line(&fit, "lab-ball"));
    let verdict = flagged(&page, "verdict", "ok");
    assert_contains(
        verdict,
        &[
            &format!(
                "noise: {} relative scatter of μ ({} %), estimated from the residuals",
                num(noise),
                num(100.0 * noise)
            ),
            "χ² test: not made",
        ],
    );
}

/// An unanchored fit whose scale the data leave undetermined, its 2σ
/// interval of E0 open at both ends (null), and an "invalid" verdict: both
/// are red banners at the top, the open ends name the profiled range, and
/// the pictures' titles say the verdict and that the scale is undetermined.
#[test]
fn an_undetermined_scale_with_open_ends_and_an_invalid_verdict_are_flagged() {
    let reason = "the data fit as well from 1e4 to 1e10 Pa";
    let edited = EditedFit::new("hn-rubber", |json| {
        json["anchor"] = serde_json::Value::Null;
        json["scale"] = serde_json::json!({
            "status": "undetermined",
            "E0": 2.0e6,
            "E0_low": null,
            "E0_high": null,
            "E0_range": [1.0e4, 1.0e10],
            "profile": [[1.0e4, 0.5], [2.0e6, 0.0], [1.0e10, 0.25]],
            "reason": reason,
        });
        json["fit_quality"]["verdict"] = "invalid".into();
        json["fit_quality"]["reasons"] = serde_json::json!(["the contact is larger than R/5"]);
    });
    let fit = edited.read();
    let (all, page) = report(&fit, &dense_line(&fit, "hn-rubber"));
    let verdict = flagged(&page, "verdict", "bad");
    assert_contains(
        verdict,
        &[
            "Verdict: invalid",
            "the model&#39;s own assumptions fail",
            "Reasons:",
            "the contact is larger than R/5",
        ],
    );
    let scale = flagged(&page, "scale", "bad");
    assert_contains(
        scale,
        &[
            "undetermined — the data do not determine the modulus scale",
            "E0 = 2.000e6 Pa",
            &format!(
                "open below (down to {} Pa, the lowest E0 profiled) … open above (up to {} Pa, \
                 the highest E0 profiled)",
                num(1e4),
                num(1e10)
            ),
            reason,
        ],
    );
    assert!(svg_text(&all[0]).contains("Rolling friction μ(v) — verdict: invalid"));
    assert!(svg_text(&all[1]).contains("Recovered master curve E*(ω) — scale undetermined"));

    // One end closed: the interval says its value.
    let closed = EditedFit::new("hn-rubber", |json| {
        json["anchor"] = serde_json::Value::Null;
        json["scale"] = serde_json::json!({
            "status": "data", "E0": 2.0e6, "E0_low": 1.5e6, "E0_high": 2.5e6,
            "E0_range": [1.0e4, 1.0e10], "profile": [], "reason": "closed",
        });
    });
    let fit = closed.read();
    let (_, page) = report(&fit, &dense_line(&fit, "hn-rubber"));
    assert!(
        banner(&page, "scale").is_none(),
        "a scale from the data is no banner"
    );
    assert_contains(
        &page,
        &["from the data alone (no anchor): E0 = 2.000e6 Pa, 2σ interval 1.500e6 Pa … 2.500e6 Pa"],
    );
}

/// fit.json without `fit_quality`, without an anchor and without `scale`
/// (an older rollfit's or another program's): the page says there is no
/// verdict and that the scale is not known, both in amber at the top.
#[test]
fn a_fit_json_without_verdict_or_scale_says_neither_is_known() {
    let edited = EditedFit::new("hn-rubber", |json| {
        let object = json.as_object_mut().unwrap();
        object.remove("fit_quality");
        object.remove("scale");
        object.insert("anchor".into(), serde_json::Value::Null);
    });
    let fit = edited.read();
    let (all, page) = report(&fit, &dense_line(&fit, "hn-rubber"));
    let verdict = flagged(&page, "verdict", "caution");
    assert_contains(verdict, &["No verdict"]);
    let scale = flagged(&page, "scale", "caution");
    assert_contains(scale, &["does not record whether the data determine"]);
    assert!(svg_text(&all[0]).contains("no verdict in fit.json"));
}

/// A temperature set: T_ref in the page's heading line and table and in
/// the master curve's title; one dense curve per temperature over its own
/// measured speeds, at the reduced speeds v·a_T of the fit's shift.
#[test]
fn a_temperature_set_shows_t_ref_and_a_dense_curve_per_temperature() {
    let fit = committed_fit("hn-rubber-tset");
    let t_ref = fit.summary.shift.as_ref().unwrap().t_ref;
    let line = dense_line(&fit, "hn-rubber-tset");
    let (all, page) = report(&fit, &line);
    assert_contains(
        &page,
        &[
            &format!(
                "a temperature set, its master curve at T_ref = {} °C",
                num(t_ref)
            ),
            &format!(
                "<tr><th>reference temperature T_ref</th><td>{} °C",
                num(t_ref)
            ),
            "Verdict: good",
        ],
    );
    let title = format!("Recovered master curve E*(ω) at T_ref = {t_ref} °C");
    assert!(svg_text(&all[1]).contains(&title), "{title}");
    let figure = MasterCurveFigure {
        fit: &fit,
        dma: &[],
    };
    assert_eq!(figure.title(), title);

    let series = FrictionFigure {
        fit: &fit,
        line: &line,
    }
    .fitted_series();
    let groups = temperature_groups(&fit.friction);
    assert_eq!(series.len(), 5);
    for ((t, points), (t_group, members)) in series.iter().zip(&groups) {
        assert_eq!(t, t_group);
        assert!(points.len() >= 200, "T = {t:?}: {} points", points.len());
        assert_eq!(points[0].0, members[0].speed.log10());
        assert_eq!(
            points[points.len() - 1].0,
            members[members.len() - 1].speed.log10()
        );
    }
    // At the coldest temperature (far from T_ref) the curve's first point is
    // the master curve's μ at mu.csv's reduced speed of that row.
    let FittedLine::Dense(curves) = &line else {
        unreachable!()
    };
    let coldest = &groups[0].1[0];
    assert!(coldest.temperature.unwrap() < t_ref - 30.0);
    let expected = model(
        &scene("hn-rubber-tset"),
        &fit,
        coldest.reduced_speed.unwrap(),
    );
    assert!(
        (curves[0].friction[0] / expected - 1.0).abs() < 1e-6,
        "the quadrature tolerance of the scene"
    );
}
