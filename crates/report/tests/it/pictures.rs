//! Every picture of a fit renders to a PNG that decodes at its stated size
//! and an SVG that parses, and each expected series is in both: in the PNG
//! by its colour, in the SVG by its legend text and stroke colour.
//!
//! The fits are the committed example results under examples/fits/ (a single
//! temperature and a temperature set), read as any user's would be.

use crate::common;

use common::{Decoded, committed_fit as fit, count, decode, dense_line};
use plotters::style::RGBColor;
use rollfit_report::plot::master_curve::DmaMarker;
use rollfit_report::plot::{Picture, pictures, style};

fn hex(c: RGBColor) -> String {
    format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
}

/// Checks the PNG and the SVG of `p` and returns the SVG's text content.
fn check(p: &Picture) -> (Decoded, String) {
    let image = decode(p);
    assert_eq!((image.width, image.height), p.size, "{}: PNG size", p.name);
    let white = count(&image, RGBColor(255, 255, 255));
    let total = (image.width * image.height) as usize;
    assert!(white < total * 97 / 100, "{}: PNG is nearly blank", p.name);
    // Text was drawn (the embedded font works): dark pixels of the
    // caption's anti-aliased glyphs in the top strip.
    let dark_in_caption = image.rgb[..(image.width as usize * 40 * 3)]
        .chunks_exact(3)
        .filter(|px| px[0] < 100 && px[1] < 100 && px[2] < 100)
        .count();
    assert!(
        dark_in_caption > 50,
        "{}: no caption text in the PNG",
        p.name
    );

    let doc = roxmltree::Document::parse(&p.svg).expect("the SVG parses as XML");
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    assert_eq!(root.attribute("width"), Some(p.size.0.to_string().as_str()));
    assert_eq!(
        root.attribute("height"),
        Some(p.size.1.to_string().as_str())
    );
    let text: Vec<String> = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text().map(str::to_string))
        .collect();
    (image, text.join("\n"))
}

fn strokes(svg: &str, c: RGBColor) -> usize {
    svg.matches(&format!("stroke=\"{}\"", hex(c))).count()
}

#[test]
fn a_single_temperature_fit_gets_four_pictures_with_every_series() {
    let fit = fit("hn-rubber");
    let all = pictures(&fit, &[], &dense_line(&fit, "hn-rubber")).unwrap();
    let names: Vec<&str> = all.iter().map(|p| p.name).collect();
    assert_eq!(
        names,
        ["friction", "master_curve", "spectrum", "convergence"]
    );

    let friction = &all[0];
    let (image, text) = check(friction);
    for label in [
        "Rolling friction μ(v)",
        "measured",
        "fit",
        "v (m/s)",
        "μ",
        "(μ_fit − μ_meas)/μ_meas (%)",
    ] {
        assert!(text.contains(label), "friction: no text {label:?}");
    }
    assert!(
        count(&image, style::FITTED) > 200,
        "friction: no fitted line"
    );
    assert!(
        count(&image, style::MEASURED) > 100,
        "friction: no measured points"
    );
    // One error bar per point with σ, in the upper and the lower panel.
    let points = fit.friction.len();
    assert!(strokes(&friction.svg, style::MEASURED) >= 2 * points);
    assert!(text.contains("10⁻⁸"), "friction: decade labels");

    let master = &all[1];
    let (image, text) = check(master);
    for label in [
        "E′ (storage)",
        "E″ (loss)",
        "tan δ = E″/E′",
        "window the data determine",
        "ω (rad/s)",
    ] {
        assert!(text.contains(label), "master curve: no text {label:?}");
    }
    for (what, c) in [
        ("E′", style::STORAGE),
        ("E″", style::LOSS),
        ("tan δ", style::TAN_DELTA),
        ("window", style::WINDOW),
    ] {
        assert!(count(&image, c) > 300, "master curve: no {what} pixels");
    }
    // Solid inside the window and dashed outside: several stroke segments
    // per curve.
    assert!(strokes(&master.svg, style::STORAGE) >= 3);
    assert!(!text.contains("DMA"));

    let spectrum = &all[2];
    let (image, text) = check(spectrum);
    let undetermined = fit.summary.model.determined.iter().filter(|d| !**d).count();
    assert!(undetermined > 0, "the example has undetermined terms");
    assert!(text.contains("not determined (extrapolation only)"));
    assert!(text.contains("determined by the data"));
    assert!(count(&image, style::UNDETERMINED) > 20 * undetermined);
    assert!(count(&image, style::STORAGE) > 20 * (fit.summary.model.tau.len() - undetermined));

    let convergence = &all[3];
    let (image, text) = check(convergence);
    assert!(text.contains("levenberg-marquardt"));
    assert!(text.contains("final V"));
    assert!(count(&image, style::SERIES[0]) > 200);
}

#[test]
fn dma_points_are_drawn_on_the_master_curve() {
    let fit = fit("hn-rubber");
    let dma: Vec<DmaMarker> = [0.1, 1.0, 10.0, 100.0]
        .iter()
        .map(|&omega| {
            let e = fit.modulus_at(omega);
            DmaMarker {
                omega,
                storage: e.re * 1.1,
                loss: e.im * 0.9,
            }
        })
        .collect();
    let all = pictures(&fit, &dma, &dense_line(&fit, "hn-rubber")).unwrap();
    let (_, text) = check(&all[1]);
    for label in ["DMA E′", "DMA E″", "DMA tan δ"] {
        assert!(text.contains(label), "no {label:?}");
    }
    // Four points plus one legend entry, each outlined in black.
    let outlines = all[1]
        .svg
        .matches(&format!("stroke=\"{}\"", hex(style::DMA)))
        .count();
    assert!(outlines >= 3 * (dma.len() + 1), "DMA outlines: {outlines}");
    assert!(all[1].caption.contains("4 DMA points"));
}

#[test]
fn a_temperature_set_gets_its_master_friction_curve_and_shift() {
    let fit = fit("hn-rubber-tset");
    let all = pictures(&fit, &[], &dense_line(&fit, "hn-rubber-tset")).unwrap();
    let names: Vec<&str> = all.iter().map(|p| p.name).collect();
    assert_eq!(
        names,
        [
            "friction",
            "master_curve",
            "spectrum",
            "convergence",
            "master_friction",
            "shift"
        ]
    );
    let temperatures: Vec<f64> = fit
        .summary
        .shift
        .as_ref()
        .unwrap()
        .log_shift
        .iter()
        .map(|s| s.temperature)
        .collect();
    assert_eq!(temperatures.len(), 5);
    for p in [&all[0], &all[4]] {
        let (image, text) = check(p);
        for (i, t) in temperatures.iter().enumerate() {
            let label = format!("T = {t} °C");
            assert!(text.contains(&label), "{}: no {label:?}", p.name);
            assert!(
                count(&image, style::SERIES[i]) > 50,
                "{}: no colour for {t} °C",
                p.name
            );
        }
    }
    let (_, text) = check(&all[4]);
    assert!(text.contains("joint fit") && text.contains("v·a_T (m/s)"));
    let (image, text) = check(&all[5]);
    assert!(text.contains("WLF fit") && text.contains("T (°C)") && text.contains("log₁₀ a_T"));
    assert!(count(&image, style::WLF) > 300, "no WLF curve");
    let c1 = fit.summary.shift.as_ref().unwrap().c1.unwrap();
    assert!(all[5].caption.contains(&format!("C1 = {c1:.4}")));
}
