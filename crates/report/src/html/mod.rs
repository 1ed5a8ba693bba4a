//! DIR/report.html: one self-contained page (no network, no external
//! files: the pictures are inline SVG) that opens with how far to trust
//! the fit — convergence, the goodness-of-fit verdict with its tests and
//! noise, and a flagged modulus scale ([`quality`]) — followed by the fit's
//! table, the warnings, the pictures, its parameters and their uncertainty
//! and, when DMA data were given, the comparison metrics. A joint fit of
//! DMA and rolling data gets its own section before the pictures
//! ([`joint`]).

use std::fmt::Write as _;

mod joint;
mod quality;

pub use joint::DISAGREE_SIGMA;

use crate::compare::Comparison;
use crate::plot::{JOINT_PICTURES, Picture};
use rollfit_io::fit_dir::FitDir;

/// The page's style: readable without any external resource.
const STYLE: &str = "
body { font-family: 'DejaVu Sans', Verdana, Arial, sans-serif; margin: 2em auto; max-width: 1000px; color: #222; line-height: 1.45; padding: 0 1em; }
h1 { font-size: 1.6em; margin-bottom: 0.2em; }
h2 { font-size: 1.25em; border-bottom: 1px solid #ccc; padding-bottom: 0.2em; margin-top: 2em; }
table { border-collapse: collapse; margin: 0.8em 0; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.7em; text-align: left; vertical-align: top; }
th { background: #f3f3f3; font-weight: normal; color: #444; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
tr.undetermined td { color: #888; }
tr.warn td { background: #fff3e0; }
.status { padding: 0.6em 1em; border-radius: 4px; margin: 1em 0; }
.ok { background: #e8f5e9; border: 1px solid #a5d6a7; }
.bad { background: #ffebee; border: 1px solid #ef9a9a; }
.caution { background: #fff8e1; border: 1px solid #ffe082; }
.status ul { margin: 0.3em 0; }
.status p.reasons { margin: 0.3em 0 0 0; }
.warnings { background: #fff8e1; border: 1px solid #ffe082; padding: 0.6em 1em 0.6em 2em; }
figure { margin: 1.5em 0; }
figure svg { max-width: 100%; height: auto; border: 1px solid #eee; }
figcaption { color: #555; font-size: 0.92em; margin-top: 0.3em; }
.meta { color: #666; font-size: 0.92em; }
";

/// Escapes text for HTML element content and attribute values.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(c),
        }
    }
    out
}

/// A number as the page writes it: 4 significant digits, in exponent form
/// outside 1e-3 … 1e5.
pub fn num(v: f64) -> String {
    if !v.is_finite() {
        return v.to_string();
    }
    if v == 0.0 {
        return "0".into();
    }
    if v != 0.0 && !(1e-3..1e5).contains(&v.abs()) {
        return format!("{v:.3e}");
    }
    let digits = (3 - v.abs().log10().floor().max(-3.0) as i32).clamp(0, 6) as usize;
    format!("{v:.digits$}")
}

/// The comparison with DMA data as the page shows it.
pub struct ComparisonSection<'a> {
    /// The DMA file's name.
    pub dma_file: &'a str,
    /// The comparison (compare.json's content).
    pub comparison: &'a Comparison,
}

/// The whole page.
pub fn report_html(
    fit: &FitDir,
    pictures: &[Picture],
    comparison: Option<&ComparisonSection<'_>>,
) -> String {
    let s = &fit.summary;
    let title = s
        .input
        .as_ref()
        .and_then(|i| i.data.clone())
        .unwrap_or_else(|| fit.dir.display().to_string());
    let mut page = String::new();
    let _ = write!(
        page,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>rollfit report: {}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n",
        escape(&title)
    );
    let _ = writeln!(page, "<h1>rollfit report: {}</h1>", escape(&title));
    let mut meta = format!(
        "Fit directory <code>{}</code>",
        escape(&fit.dir.display().to_string())
    );
    if let Some(input) = &s.input {
        if let Some(scene) = &input.scene {
            let _ = write!(meta, "; scene <code>{}</code>", escape(scene));
        }
        if let Some(points) = input.points {
            let _ = write!(meta, "; {points} data points");
        }
    }
    if let Some(shift) = &s.shift {
        let _ = write!(
            meta,
            "; a temperature set, its master curve at T_ref = {} °C",
            num(shift.t_ref)
        );
    }
    if let Some(joint) = &s.joint {
        let _ = write!(
            meta,
            "; a <a href=\"#joint\">joint fit with the DMA data</a> <code>{}</code>",
            escape(&joint.dma_source)
        );
    }
    let _ = writeln!(page, "<p class=\"meta\">{meta}.</p>");

    // stop_reason reads "converged (…)" or says why not; the box says it once.
    let reason = s.stop_reason.as_deref().unwrap_or("");
    let reason = reason.strip_prefix("converged").unwrap_or(reason).trim();
    let (class, text) = if s.converged {
        ("ok", format!("The fit converged {}.", escape(reason)))
    } else {
        (
            "bad",
            format!("The fit did not converge: {}.", escape(reason)),
        )
    };
    let _ = writeln!(page, "<div class=\"status {class}\">{text}</div>");
    page.push_str(&quality::verdict_banner(s));
    if let Some(banner) = quality::scale_banner(s) {
        page.push_str(&banner);
    }
    list(&mut page, "warnings", &s.warnings);

    page.push_str("<h2>Fit</h2>\n");
    page.push_str(&fit_table(fit));
    if let Some(section) = comparison {
        page.push_str(&comparison_table(section));
    }
    if let Some(joint) = &s.joint {
        page.push_str(&joint::section(joint, pictures));
    }
    page.push_str("<h2>Pictures</h2>\n");
    for p in pictures
        .iter()
        .filter(|p| !JOINT_PICTURES.contains(&p.name))
    {
        figure(&mut page, p);
    }
    page.push_str("<h2>Parameters</h2>\n");
    page.push_str(&parameter_table(fit));
    let _ = writeln!(
        page,
        "<p class=\"meta\">Written by rollfit {}.</p>\n</body>\n</html>",
        env!("CARGO_PKG_VERSION")
    );
    page
}

/// A picture as a figure: inline SVG, its caption and links to its files.
fn figure(out: &mut String, p: &Picture) {
    let _ = writeln!(
        out,
        "<figure id=\"{name}\">\n{svg}\n<figcaption>{caption} (Also <a href=\"{name}.png\">{name}.png</a>, <a href=\"{name}.svg\">{name}.svg</a>.)</figcaption>\n</figure>",
        name = p.name,
        svg = inline_svg(&p.svg),
        caption = escape(&p.caption)
    );
}

/// An SVG document as an element inside HTML: without an XML declaration.
fn inline_svg(svg: &str) -> &str {
    let trimmed = svg.trim_start();
    if trimmed.starts_with("<?xml") {
        trimmed
            .find("?>")
            .map_or(trimmed, |end| trimmed[end + 2..].trim_start())
    } else {
        trimmed
    }
}

/// `items` as an unordered list of class `class`, each escaped; nothing
/// when there are none.
fn list<S: AsRef<str>>(out: &mut String, class: &str, items: &[S]) {
    if items.is_empty() {
        return;
    }
    let _ = writeln!(out, "<ul class=\"{class}\">");
    for item in items {
        let _ = writeln!(out, "<li>{}</li>", escape(item.as_ref()));
    }
    out.push_str("</ul>\n");
}

fn row(out: &mut String, name: &str, value: &str) {
    let _ = writeln!(out, "<tr><th>{}</th><td>{}</td></tr>", escape(name), value);
}

/// The shift law of a temperature set in words, with its constants.
fn shift_law(shift: &rollfit_io::fit_dir::ShiftSummary) -> String {
    let sigma = |v: Option<f64>| num(v.unwrap_or(f64::NAN));
    match (
        shift.model.as_str(),
        shift.c1,
        shift.c2,
        shift.activation_energy,
    ) {
        ("wlf", Some(c1), Some(c2), _) => format!(
            "WLF at T_ref = {} °C: C1 = {} ± {}, C2 = {} ± {} K",
            num(shift.t_ref),
            num(c1),
            sigma(shift.c1_sigma),
            num(c2),
            sigma(shift.c2_sigma)
        ),
        ("arrhenius", _, _, Some(e)) => format!(
            "Arrhenius at T_ref = {} °C: E_a = {} ± {} J/mol",
            num(shift.t_ref),
            num(e),
            sigma(shift.activation_energy_sigma)
        ),
        _ => format!("free, T_ref = {} °C", num(shift.t_ref)),
    }
}

fn fit_table(fit: &FitDir) -> String {
    let s = &fit.summary;
    let m = &s.model;
    let mut t = String::from("<table>\n");
    let determined = if m.determined.is_empty() {
        m.tau.len()
    } else {
        m.determined.iter().filter(|d| **d).count()
    };
    row(
        &mut t,
        "model",
        &format!(
            "Prony series, {} relaxation times ({} determined by the data)",
            m.tau.len(),
            determined
        ),
    );
    let e0 = m.glassy_modulus - m.strengths.iter().sum::<f64>();
    row(&mut t, "static modulus E0", &format!("{} Pa", num(e0)));
    row(
        &mut t,
        "glassy modulus E1",
        &format!("{} Pa", num(m.glassy_modulus)),
    );
    row(&mut t, "Poisson's ratio", &num(s.poisson));
    row(
        &mut t,
        "window",
        &format!(
            "{} … {} rad/s",
            num(s.window.omega_min),
            num(s.window.omega_max)
        ),
    );
    if let Some(shift) = &s.shift {
        row(
            &mut t,
            "reference temperature T_ref",
            &format!("{} °C", num(shift.t_ref)),
        );
        let text = shift_law(shift);
        row(&mut t, "shift", &escape(&text));
        let list: Vec<String> = shift
            .log_shift
            .iter()
            .map(|p| {
                format!(
                    "{} °C: {} ± {}",
                    num(p.temperature),
                    num(p.log_shift),
                    num(p.log_shift_sigma)
                )
            })
            .collect();
        row(&mut t, "log10 a_T", &escape(&list.join("; ")));
    }
    row(&mut t, "scale", &quality::scale_row(s));
    row(&mut t, "method", &escape(&s.method));
    row(&mut t, "objective V", &num(s.objective));
    if let Some(m) = s.misfit_per_point {
        row(&mut t, "misfit per point", &num(m));
    }
    if let Some(l) = &s.lambda {
        let rule = l.rule.as_deref().unwrap_or("given");
        row(
            &mut t,
            "smoothness λ",
            &escape(&format!("{} ({rule})", num(l.value))),
        );
    }
    if let Some(p) = s.effective_parameters {
        row(&mut t, "effective parameters", &num(p));
    }
    row(&mut t, "iterations (final run)", &s.iterations.to_string());
    if let Some(e) = s.evaluations {
        row(&mut t, "evaluations (all runs)", &e.to_string());
    }
    row(&mut t, "solver runs", &s.runs.len().to_string());
    row(&mut t, "wall time", &format!("{} s", num(s.wall_time_s)));
    row(
        &mut t,
        "converged",
        &if s.converged {
            "yes".to_string()
        } else {
            format!(
                "no: {}",
                escape(s.stop_reason.as_deref().unwrap_or("unknown"))
            )
        },
    );
    t.push_str("</table>\n");
    t
}

fn parameter_table(fit: &FitDir) -> String {
    let m = &fit.summary.model;
    let mut t = String::from(
        "<table>\n<tr><th>k</th><th>τ_k (s)</th><th>H_k (Pa)</th><th>1σ of ln H_k</th><th>determined</th></tr>\n",
    );
    for (k, (tau, h)) in m.tau.iter().zip(&m.strengths).enumerate() {
        let determined = m.determined.get(k).copied().unwrap_or(true);
        let sigma = m
            .ln_strength_sigma
            .get(k)
            .map_or_else(|| "–".to_string(), |s| num(*s));
        let _ = writeln!(
            t,
            "<tr{}><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td>{}</td></tr>",
            if determined {
                ""
            } else {
                " class=\"undetermined\""
            },
            k + 1,
            num(*tau),
            num(*h),
            sigma,
            if determined {
                "yes"
            } else {
                "no (outside the window; not a result)"
            }
        );
    }
    t.push_str("</table>\n");
    t
}

fn comparison_table(section: &ComparisonSection<'_>) -> String {
    let c = section.comparison;
    let mut t = format!(
        "<h2>Comparison with DMA data</h2>\n<p>DMA file <code>{}</code> ({}, {} moduli; {} points at the \
         fit's reference state, ω = {} … {} rad/s; the fit's window {} … {} rad/s).</p>\n",
        escape(section.dma_file),
        escape(c.dma_format),
        escape(c.modulus_kind),
        c.dma_points,
        num(c.dma_omega_range[0]),
        num(c.dma_omega_range[1]),
        num(c.fit_window[0]),
        num(c.fit_window[1]),
    );
    list(&mut t, "warnings", &c.warnings);
    list(&mut t, "meta", &c.notes);
    if c.overlap_empty {
        t.push_str(
            "<p class=\"status bad\">The fit's window and the DMA frequencies do not overlap: \
             no metric can be computed.</p>\n",
        );
    }
    t.push_str("<table>\n<tr><th>metric</th><th>value</th><th>meaning</th></tr>\n");
    for row in c.metric_rows() {
        let class = if row.warns(c) { " class=\"warn\"" } else { "" };
        let _ = writeln!(
            t,
            "<tr{class}><th><code>{}</code></th><td class=\"num\">{}</td><td>{}</td></tr>",
            escape(row.key),
            escape(&row.value_text()),
            escape(&row.meaning_text())
        );
    }
    t.push_str("</table>\n");
    t
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_is_escaped() {
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }

    #[test]
    fn numbers_keep_four_significant_digits() {
        assert_eq!(num(0.123456), "0.1235");
        assert_eq!(num(12.3456), "12.35");
        assert_eq!(num(2.5e7), "2.500e7");
        assert_eq!(num(0.0), "0");
    }

    #[test]
    fn an_xml_declaration_is_dropped_for_inline_svg() {
        assert_eq!(inline_svg("<?xml version=\"1.0\"?>\n<svg/>"), "<svg/>");
        assert_eq!(inline_svg("<svg/>"), "<svg/>");
    }
}
