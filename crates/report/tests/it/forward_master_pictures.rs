//! The pictures of `rollfit forward` (μ(v) of a sweep) and `rollfit master`
//! (DMA isotherms shifted onto one master curve) render to a PNG that
//! decodes at the stated size and is not blank, with one colour per
//! temperature, and to an SVG that carries the axis labels and the legend;
//! bad values (NaN, negative μ) and a single isotherm render too. The
//! master picture puts a verdict that is not "good" in its title and names
//! the shift law under the shift panel, outside the plot; relaxation
//! isotherms get their master picture; the van Gurp–Palmen plot draws the
//! isotherms as measured; shear data are labelled G throughout.
//!
//! The data are synthetic with known shapes: μ(v) from a standard linear
//! solid (tan δ of E* = E0 + ΔE iωτ/(1 + iωτ) at ω = v a_T / a, so μ rises
//! ∝ v, peaks and falls), shifted between temperatures by WLF; the DMA
//! isotherms from a Prony series sampled over 15 frequencies at 8
//! temperatures and shifted back by the same WLF.

use crate::common;

use common::{Decoded, count, decode};
use plotters::style::RGBColor;
use rollfit_report::plot::dma_master::{
    DmaMasterFigure, MasterCurveFit, ShiftMarker, ShiftedPoint, Verdict,
};
use rollfit_report::plot::forward_sweep::{ForwardSweepFigure, SweepCurve};
use rollfit_report::plot::relaxation_master::{RelaxationMasterFigure, ShiftedRelaxation};
use rollfit_report::plot::van_gurp_palmen::{MeasuredPoint, VanGurpPalmenFigure};
use rollfit_report::plot::{Picture, render, style};

/// WLF constants (the "universal" ones) and the reference temperature, °C.
const C1: f64 = 8.86;
const C2: f64 = 101.6;
const T_REF: f64 = 20.0;

/// log10 a_T by WLF.
fn log_shift(t: f64) -> f64 {
    -C1 * (t - T_REF) / (C2 + t - T_REF)
}

/// Standard linear solid: relaxed modulus (arbitrary unit), glassy over
/// relaxed, relaxation time (s), contact half-width (m) and μ per tan δ.
const E0: f64 = 1.0;
const E1: f64 = 100.0;
const TAU: f64 = 1e-2;
const HALF_WIDTH: f64 = 1e-3;
const MU_PER_TAN_DELTA: f64 = 0.01;

/// μ and its low-speed asymptote at speed `v` (m/s) and `t` °C.
fn sls_mu(v: f64, t: f64) -> (f64, f64) {
    let x = v * 10f64.powf(log_shift(t)) / HALF_WIDTH * TAU;
    let tan_delta = (E1 - E0) * x / (E0 + E1 * x * x);
    let low = (E1 - E0) * x / E0;
    (MU_PER_TAN_DELTA * tan_delta, MU_PER_TAN_DELTA * low)
}

/// The friction maximum, analytically: tan δ peaks at ωτ = √(E0/E1).
fn sls_maximum(t: f64) -> (f64, f64) {
    let x = (E0 / E1).sqrt();
    let v = x / TAU * HALF_WIDTH / 10f64.powf(log_shift(t));
    (v, sls_mu(v, t).0)
}

/// 60 speeds from 10⁻⁸ to 10 m/s.
fn speeds() -> Vec<f64> {
    (0..60)
        .map(|i| 10f64.powf(-8.0 + 9.0 * f64::from(i) / 59.0))
        .collect()
}

fn sweep(t: Option<f64>) -> SweepCurve {
    let at = t.unwrap_or(T_REF);
    let speeds = speeds();
    let (mu, mu_low_speed) = speeds.iter().map(|&v| sls_mu(v, at)).unzip();
    SweepCurve {
        temperature: t,
        speeds,
        mu,
        mu_low_speed,
        maximum: Some(sls_maximum(at)),
    }
}

/// Hue sectors of 30° holding at least `min_pixels` clearly coloured
/// pixels (grey axes, grid and text are not coloured).
fn hue_sectors(image: &Decoded, min_pixels: usize) -> usize {
    let mut sectors = [0usize; 12];
    for px in image.rgb.chunks_exact(3) {
        let (r, g, b) = (f64::from(px[0]), f64::from(px[1]), f64::from(px[2]));
        let (max, min) = (r.max(g).max(b), r.min(g).min(b));
        if max - min < 60.0 {
            continue;
        }
        let d = max - min;
        let hue = if max == r {
            60.0 * ((g - b) / d).rem_euclid(6.0)
        } else if max == g {
            60.0 * ((b - r) / d + 2.0)
        } else {
            60.0 * ((r - g) / d + 4.0)
        };
        sectors[((hue / 30.0) as usize).min(11)] += 1;
    }
    sectors.iter().filter(|&&n| n >= min_pixels).count()
}

fn hex(c: RGBColor) -> String {
    format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
}

/// A text element of the SVG: its content and position, px.
struct SvgText {
    text: String,
    x: f64,
    y: f64,
}

/// Checks the PNG (size, not blank) and that the SVG parses at that size;
/// returns the decoded image and the SVG's text elements.
fn check(p: &Picture, size: (u32, u32)) -> (Decoded, Vec<SvgText>) {
    assert_eq!(p.size, size, "{}: stated size", p.name);
    let image = decode(p);
    assert_eq!((image.width, image.height), size, "{}: PNG size", p.name);
    let total = (image.width * image.height) as usize;
    let inked = image
        .rgb
        .chunks_exact(3)
        .filter(|px| px.iter().any(|&c| c < 200))
        .count();
    assert!(
        inked > total / 100,
        "{}: only {inked} of {total} pixels are drawn",
        p.name
    );

    let doc = roxmltree::Document::parse(&p.svg).expect("the SVG parses as XML");
    let root = doc.root_element();
    assert_eq!(root.attribute("width"), Some(size.0.to_string().as_str()));
    assert_eq!(root.attribute("height"), Some(size.1.to_string().as_str()));
    let texts = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| {
            Some(SvgText {
                text: n.text()?.trim().to_string(),
                x: n.attribute("x")?.parse().ok()?,
                y: n.attribute("y")?.parse().ok()?,
            })
        })
        .collect();
    (image, texts)
}

fn joined(texts: &[SvgText]) -> String {
    texts
        .iter()
        .map(|t| t.text.as_str())
        .collect::<Vec<_>>()
        .join("\n")
}

/// The exponent n of a tick label "10ⁿ" (None for other text).
fn decade_exponent(label: &str) -> Option<i32> {
    if label == "1" {
        return Some(0);
    }
    let rest = label.strip_prefix("10")?;
    if rest.is_empty() {
        return None;
    }
    let mut n = 0;
    let mut sign = 1;
    for c in rest.chars() {
        match c {
            '⁻' => sign = -1,
            _ => {
                let d = "⁰¹²³⁴⁵⁶⁷⁸⁹".chars().position(|s| s == c)?;
                n = 10 * n + d as i32;
            }
        }
    }
    Some(sign * n)
}

/// Polylines (lines and dashes) of this stroke colour and width.
fn strokes(svg: &str, c: RGBColor, width: u32) -> usize {
    svg.matches(&format!("stroke=\"{}\" stroke-width=\"{width}\"", hex(c)))
        .count()
}

#[test]
fn a_sweep_at_three_temperatures_has_a_coloured_curve_asymptote_and_maximum_each() {
    // Given out of order: the figure orders them by temperature.
    let curves = [sweep(Some(20.0)), sweep(Some(-10.0)), sweep(Some(50.0))];
    let figure = ForwardSweepFigure {
        curves: &curves,
        title: "Forward sweep μ(v)".into(),
    };
    let p = render(&figure).unwrap();
    assert_eq!(p.name, "forward");
    let (image, texts) = check(&p, (900, 620));
    let text = joined(&texts);
    for label in [
        "Forward sweep μ(v)",
        "rolling speed v (m/s)",
        "friction coefficient μ",
        "low-speed asymptote (Eqs. 18/19)",
        "friction maximum",
    ] {
        assert!(text.contains(label), "no text {label:?}");
    }
    // Legend entries in order of temperature, each with its maximum.
    let legend: Vec<&str> = texts
        .iter()
        .map(|t| t.text.as_str())
        .filter(|t| t.contains(" °C: μ_max = "))
        .collect();
    assert_eq!(legend.len(), 3, "{legend:?}");
    for (entry, t) in legend.iter().zip(["-10 °C", "20 °C", "50 °C"]) {
        assert!(entry.starts_with(t), "{entry:?} should be {t}");
    }
    // The maximum at 20 °C, analytically μ = 0.0495 at v = 10⁻² m/s.
    assert!(
        legend[1].ends_with("μ_max = 0.0495 at 1.0e-2 m/s"),
        "{}",
        legend[1]
    );

    // Cold blue, middle green, warm red: each a line, its dashes and its
    // marker.
    for f in [0.0, 0.5, 1.0] {
        let c = style::cold_to_warm(f);
        assert!(count(&image, c) > 300, "too few pixels of {}", hex(c));
        assert!(
            strokes(&p.svg, c, 1) >= 10,
            "no dashed asymptote in {}",
            hex(c)
        );
        assert!(strokes(&p.svg, c, 2) >= 2, "no μ line in {}", hex(c));
    }
    assert!(hue_sectors(&image, 150) >= 3);
    assert!(!p.svg.contains(&hex(style::FITTED)));

    // The asymptote rises 9 decades across the sweep; clipped to 3 μ_max it
    // keeps the y axis below 1.
    let y_decades: Vec<i32> = texts
        .iter()
        .filter(|t| t.x < 90.0)
        .filter_map(|t| decade_exponent(&t.text))
        .collect();
    assert!(y_decades.len() >= 3, "y ticks {y_decades:?}");
    assert!(y_decades.iter().all(|&n| n <= 0), "y ticks {y_decades:?}");
    assert!(p.caption.contains("-10 °C, 20 °C, 50 °C"), "{}", p.caption);
}

#[test]
fn a_single_sweep_is_drawn_in_the_house_colour_with_its_maximum_labelled() {
    let curves = [sweep(None)];
    let p = render(&ForwardSweepFigure {
        curves: &curves,
        title: "μ(v)".into(),
    })
    .unwrap();
    let (image, texts) = check(&p, (900, 620));
    let text = joined(&texts);
    assert!(count(&image, style::FITTED) > 300);
    assert!(
        strokes(&p.svg, style::FITTED, 1) >= 10,
        "no dashed asymptote"
    );
    // On the plot next to the marker, not in the legend.
    let label = "μ_max = 0.0495 at 1.0e-2 m/s";
    assert!(texts.iter().any(|t| t.text == label), "no {label:?}");
    assert!(text.contains("low-speed asymptote (Eqs. 18/19)"));
    assert!(p.caption.contains(label), "{}", p.caption);
}

#[test]
fn non_positive_and_non_finite_values_are_skipped() {
    let mut broken = sweep(Some(0.0));
    broken.mu[5] = f64::NAN;
    broken.mu[20] = -0.01;
    broken.mu[21] = 0.0;
    broken.mu[40] = f64::INFINITY;
    broken.mu_low_speed[3] = f64::NAN;
    broken.mu_low_speed[4] = -1.0;
    broken.speeds[10] = 0.0;
    broken.speeds[11] = f64::NAN;
    broken.maximum = Some((f64::NAN, 0.05));
    let nothing = SweepCurve {
        temperature: Some(40.0),
        speeds: vec![1e-3, 1e-2, 1e-1],
        mu: vec![f64::NAN, -1.0, 0.0],
        mu_low_speed: vec![f64::NAN; 2],
        maximum: Some((1e-2, -1.0)),
    };
    let curves = [broken, nothing];
    let p = render(&ForwardSweepFigure {
        curves: &curves,
        title: "broken".into(),
    })
    .unwrap();
    let (image, texts) = check(&p, (900, 620));
    // What is valid of the 0 °C curve is still drawn, in the cold colour.
    assert!(count(&image, style::cold_to_warm(0.0)) > 300);
    let text = joined(&texts);
    assert!(text.contains("0 °C"));
    assert!(text.contains("friction coefficient μ"));

    // And with nothing at all.
    let p = render(&ForwardSweepFigure {
        curves: &[],
        title: "empty".into(),
    })
    .unwrap();
    assert_eq!(decode(&p).width, 900);
}

/// A Prony series: relaxed modulus (Pa) and ten terms, τ_k = 10^(k−8) s.
fn prony(omega: f64) -> (f64, f64) {
    let mut storage = 1e6;
    let mut loss = 0.0;
    for k in 0..10 {
        let tau = 10f64.powf(f64::from(k) - 8.0);
        let strength = 3e8 * 0.5f64.powi(k);
        let x = omega * tau;
        storage += strength * x * x / (1.0 + x * x);
        loss += strength * x / (1.0 + x * x);
    }
    (storage, loss)
}

/// Isotherms of 15 frequencies, 0.1–100 Hz, shifted to T_REF, with a few
/// percent of deterministic scatter.
fn isotherms(temperatures: &[f64]) -> Vec<ShiftedPoint> {
    let mut points = Vec::new();
    for (j, &t) in temperatures.iter().enumerate() {
        for i in 0..15 {
            let hz = 10f64.powf(-1.0 + 3.0 * f64::from(i) / 14.0);
            let reduced_omega = 2.0 * std::f64::consts::PI * hz * 10f64.powf(log_shift(t));
            let (storage, loss) = prony(reduced_omega);
            let scatter = 0.03 * (f64::from(i) * 1.7 + j as f64).sin();
            points.push(ShiftedPoint {
                reduced_omega,
                storage: storage * (1.0 + scatter),
                loss: loss * (1.0 - scatter),
                temperature: t,
            });
        }
    }
    points
}

fn prony_fit(points: &[ShiftedPoint]) -> MasterCurveFit {
    let (lo, hi) = points.iter().fold((f64::INFINITY, 0f64), |(a, b), p| {
        (a.min(p.reduced_omega), b.max(p.reduced_omega))
    });
    let omega: Vec<f64> = (0..200)
        .map(|i| 10f64.powf(lo.log10() + (hi / lo).log10() * f64::from(i) / 199.0))
        .collect();
    let (storage, loss) = omega.iter().map(|&w| prony(w)).unzip();
    MasterCurveFit {
        omega,
        storage,
        loss,
    }
}

#[test]
fn eight_isotherms_make_a_master_curve_with_its_shift_and_colour_key() {
    let temperatures = [-30.0, -15.0, 0.0, 10.0, 20.0, 35.0, 50.0, 70.0];
    let points = isotherms(&temperatures);
    assert_eq!(points.len(), 120);
    let fit = prony_fit(&points);
    // The coldest isotherm undetermined (hollow, at the law's value), the
    // others measured with an error bar.
    let shifts: Vec<ShiftMarker> = temperatures
        .iter()
        .enumerate()
        .map(|(k, &t)| ShiftMarker {
            temperature: t,
            log_shift: log_shift(t),
            sigma: 0.05,
            determined: k > 0,
        })
        .collect();
    let shift_curve: Vec<(f64, f64)> = (0..=100)
        .map(|i| -30.0 + f64::from(i))
        .map(|t| (t, log_shift(t)))
        .collect();
    let figure = DmaMasterFigure {
        points: &points,
        fit: &fit,
        t_ref: T_REF,
        shifts: &shifts,
        shift_curve: &shift_curve,
        shift_law: &[],
        modulus_symbol: "E",
        verdict: None,
    };
    let p = render(&figure).unwrap();
    assert_eq!(p.name, "master");
    let (image, texts) = check(&p, (1100, 800));
    let text = joined(&texts);
    for label in [
        "reduced frequency ω a_T (rad/s), T_ref = 20 °C",
        "E′, E″ (Pa)",
        "tan δ",
        "E′ (storage), per isotherm",
        "E″ (loss), per isotherm",
        "Prony E′",
        "Prony E″",
        "Prony tan δ",
        "Shift factors a_T",
        "T (°C)",
        "log₁₀ a_T",
        "fitted shift curve",
        "measured, ±1σ",
        "not determined (value applied)",
        "-30 °C (coldest)",
        "70 °C (warmest)",
        "T_ref = 20 °C",
    ] {
        assert!(text.contains(label), "no text {label:?}");
    }
    assert!(!text.contains("Single isotherm"));

    // Points in the colours of the coldest and warmest isotherms (in all
    // three panels and the key), and many hues in between.
    for c in [style::cold_to_warm(0.0), style::cold_to_warm(1.0)] {
        assert!(count(&image, c) > 150, "too few pixels of {}", hex(c));
    }
    assert!(hue_sectors(&image, 150) >= 5);
    // The Prony curves: E′ and tan δ solid, E″ dashed, all black.
    assert!(strokes(&p.svg, RGBColor(0, 0, 0), 2) >= 20);
    // The shift curve.
    assert!(count(&image, style::WLF) > 100);
    assert!(p.caption.contains("8 DMA isotherms"), "{}", p.caption);
}

#[test]
fn a_single_isotherm_leaves_the_shift_panel_to_a_note() {
    let mut points = isotherms(&[T_REF]);
    // Values a log axis cannot show are skipped.
    points[3].loss = -1.0;
    points[4].storage = f64::NAN;
    points[5].reduced_omega = 0.0;
    let mut fit = prony_fit(&points[6..]);
    fit.storage[10] = f64::NAN;
    fit.loss[11] = -5.0;
    let p = render(&DmaMasterFigure {
        points: &points,
        fit: &fit,
        t_ref: T_REF,
        shifts: &[ShiftMarker {
            temperature: T_REF,
            log_shift: 0.0,
            sigma: 0.0,
            determined: true,
        }],
        shift_curve: &[],
        shift_law: &[],
        modulus_symbol: "G",
        verdict: None,
    })
    .unwrap();
    let (image, texts) = check(&p, (1100, 800));
    let text = joined(&texts);
    assert!(text.contains("Single isotherm (20 °C):"), "no note");
    assert!(text.contains("the one isotherm, 20 °C"));
    assert!(!text.contains("log₁₀ a_T"), "a shift panel was drawn");
    assert!(text.contains("G′, G″ (Pa)") && !text.contains("E′"));
    assert!(count(&image, style::cold_to_warm(0.5)) > 100);
    assert!(p.caption.contains("shear modulus"), "{}", p.caption);

    // No points at all, no fit: still a picture.
    let empty = MasterCurveFit::default();
    let p = render(&DmaMasterFigure {
        points: &[],
        fit: &empty,
        t_ref: T_REF,
        shifts: &[],
        shift_curve: &[],
        shift_law: &[],
        modulus_symbol: "E",
        verdict: None,
    })
    .unwrap();
    assert_eq!(decode(&p).height, 800);
}

/// The verdict's reason as the fit crate words one (cause: advice).
const POOR_REASON: &str = "the shifts are not determined by the overlap: only 3 of 8 isotherms \
                           overlap their neighbours on a slope; measure isotherms closer in \
                           temperature";

/// The law's legend as `shift_panel::law_legend` words a WLF fit.
fn wlf_legend() -> Vec<String> {
    vec![
        "WLF, T_ref = 20 °C:".to_string(),
        "C1 = 8.86 ± 0.12, C2 = 101.6 ± 2.1 K".to_string(),
    ]
}

#[test]
fn a_poor_verdict_titles_the_picture_and_the_law_is_named_under_the_shift_panel() {
    let temperatures = [-30.0, -15.0, 0.0, 10.0, 20.0, 35.0, 50.0, 70.0];
    let points = isotherms(&temperatures);
    let fit = prony_fit(&points);
    // Wide bars (±0.8 decade) on every measured shift: a legend inside the
    // plot would cover some of them wherever it went.
    let shifts: Vec<ShiftMarker> = temperatures
        .iter()
        .enumerate()
        .map(|(k, &t)| ShiftMarker {
            temperature: t,
            log_shift: log_shift(t),
            sigma: 0.8,
            determined: k % 3 != 0,
        })
        .collect();
    let shift_curve: Vec<(f64, f64)> = (0..=100)
        .map(|i| -30.0 + f64::from(i))
        .map(|t| (t, log_shift(t)))
        .collect();
    let law = wlf_legend();
    let reasons = vec![POOR_REASON.to_string()];
    let figure = |verdict| DmaMasterFigure {
        points: &points,
        fit: &fit,
        t_ref: T_REF,
        shifts: &shifts,
        shift_curve: &shift_curve,
        shift_law: &law,
        modulus_symbol: "E",
        verdict,
    };
    let poor = render(&figure(Some(Verdict {
        verdict: "poor",
        reasons: &reasons,
    })))
    .unwrap();
    let (width, height) = poor.size;
    assert!(width == 1100 && height > 800, "{:?}", poor.size);
    let (image, texts) = check(&poor, poor.size);
    let text = joined(&texts);
    for label in [
        "Verdict: poor",
        "the shifts are not determined by the overlap",
        "WLF, T_ref = 20 °C:",
        "C1 = 8.86 ± 0.12, C2 = 101.6 ± 2.1 K",
        "measured, ±1σ",
        "not determined (value applied)",
    ] {
        assert!(text.contains(label), "no text {label:?} in\n{text}");
    }
    // Only the cause, not the advice, and the law instead of a vague name.
    assert!(!text.contains("measure isotherms closer") && !text.contains("fitted shift curve"));
    // The title is the topmost text.
    let title = texts
        .iter()
        .find(|t| t.text.starts_with("Verdict"))
        .unwrap();
    assert!(
        texts.iter().all(|t| t.y >= title.y),
        "the verdict is not on top"
    );
    assert!(
        count(&image, style::VERDICT) > 200,
        "the verdict is not in its colour"
    );
    // The legend lies under the shift panel's temperature axis (whose
    // description "T (°C)" is the lowest text of the plot), in the right
    // column: outside the plot, so no marker or bar is under it.
    let axis = texts.iter().find(|t| t.text == "T (°C)").unwrap();
    for label in [
        "WLF, T_ref = 20 °C:",
        "measured, ±1σ",
        "not determined (value applied)",
    ] {
        let entry = texts.iter().find(|t| t.text == label).unwrap();
        assert!(
            entry.y > axis.y && entry.x > 740.0,
            "{label} at ({}, {})",
            entry.x,
            entry.y
        );
    }

    // A good verdict takes no room and says nothing.
    let good = render(&figure(Some(Verdict {
        verdict: "good",
        reasons: &[],
    })))
    .unwrap();
    let (_, texts) = check(&good, (1100, 800));
    assert!(!joined(&texts).contains("Verdict"));
}

/// A relaxation modulus of the same spectrum as [`prony`]: E(t) = E0 +
/// Σ H_k exp(−t/τ_k), Pa.
fn relaxation_modulus(t: f64) -> f64 {
    1e6 + (0..10)
        .map(|k| {
            let tau = 10f64.powf(f64::from(k) - 8.0);
            3e8 * 0.5f64.powi(k) * (-t / tau).exp()
        })
        .sum::<f64>()
}

#[test]
fn relaxation_isotherms_get_their_master_picture() {
    let temperatures = [-10.0, 0.0, 10.0, 20.0, 30.0, 45.0];
    let mut points = Vec::new();
    for (j, &t) in temperatures.iter().enumerate() {
        for i in 0..15 {
            let time = 10f64.powf(3.0 * f64::from(i) / 14.0);
            let reduced_time = time / 10f64.powf(log_shift(t));
            let fitted = relaxation_modulus(reduced_time);
            let scatter = 0.02 * (f64::from(i) * 1.3 + j as f64).sin();
            points.push(ShiftedRelaxation {
                reduced_time,
                modulus: fitted * (1.0 + scatter),
                fitted,
                temperature: t,
            });
        }
    }
    let (lo, hi) = (
        points[0].reduced_time,
        points[points.len() - 1].reduced_time,
    );
    let (lo, hi) = (lo.min(hi), lo.max(hi));
    let series: Vec<(f64, f64)> = (0..=120)
        .map(|i| lo * (hi / lo).powf(f64::from(i) / 120.0))
        .map(|t| (t, relaxation_modulus(t)))
        .collect();
    let shifts: Vec<ShiftMarker> = temperatures
        .iter()
        .map(|&t| ShiftMarker {
            temperature: t,
            log_shift: log_shift(t),
            sigma: 0.05,
            determined: true,
        })
        .collect();
    let shift_curve: Vec<(f64, f64)> = (0..=55)
        .map(|i| -10.0 + f64::from(i))
        .map(|t| (t, log_shift(t)))
        .collect();
    let law = wlf_legend();
    let p = render(&RelaxationMasterFigure {
        points: &points,
        series: &series,
        t_ref: T_REF,
        shifts: &shifts,
        shift_curve: &shift_curve,
        shift_law: &law,
        modulus_symbol: "G",
        creep: false,
        verdict: None,
    })
    .unwrap();
    assert_eq!(p.name, "master");
    let (image, texts) = check(&p, (1100, 800));
    let text = joined(&texts);
    for label in [
        "Relaxation master curve at T_ref = 20 °C",
        "reduced time t/a_T (s), T_ref = 20 °C",
        "G(t) (Pa)",
        "G(t/a_T), per isotherm",
        "Prony G(t)",
        "log₁₀ G/G_Prony",
        "Shift factors a_T",
        "WLF, T_ref = 20 °C:",
        "-10 °C (coldest)",
        "45 °C (warmest)",
    ] {
        assert!(text.contains(label), "no text {label:?} in\n{text}");
    }
    assert!(!text.contains("E′") && !text.contains("E(t)"));
    for c in [style::cold_to_warm(0.0), style::cold_to_warm(1.0)] {
        assert!(count(&image, c) > 150, "too few pixels of {}", hex(c));
    }
    assert!(hue_sectors(&image, 150) >= 5);
    // The series and the misfit's zero line, black and 2 px.
    assert!(strokes(&p.svg, RGBColor(0, 0, 0), 2) >= 2);
    assert!(p.caption.contains("6 isotherms"), "{}", p.caption);
}

#[test]
fn the_van_gurp_palmen_plot_draws_every_isotherm_as_measured() {
    let temperatures = [-30.0, -15.0, 0.0, 10.0, 20.0, 35.0, 50.0, 70.0];
    let shifted = isotherms(&temperatures);
    let fit = prony_fit(&shifted);
    let measured: Vec<MeasuredPoint> = shifted
        .iter()
        .map(|p| MeasuredPoint {
            storage: p.storage,
            loss: p.loss,
            temperature: p.temperature,
        })
        .collect();
    let figure = |symbol| VanGurpPalmenFigure {
        points: &measured,
        fit: &fit,
        t_ref: T_REF,
        modulus_symbol: symbol,
    };
    let p = render(&figure("E")).unwrap();
    assert_eq!(p.name, "vgp");
    let (image, texts) = check(&p, (1100, 640));
    let text = joined(&texts);
    for label in [
        "van Gurp–Palmen plot (no shift applied)",
        "|E*| = √(E′² + E″²) (Pa)",
        "phase angle δ (°)",
        "per isotherm, as measured",
        "Prony series at T_ref = 20 °C",
        "-30 °C (coldest)",
        "70 °C (warmest)",
    ] {
        assert!(text.contains(label), "no text {label:?} in\n{text}");
    }
    // The phase-angle ticks lie in 0…90°.
    let ticks: Vec<f64> = texts
        .iter()
        .filter(|t| t.x < 80.0)
        .filter_map(|t| t.text.parse().ok())
        .collect();
    assert!(ticks.len() >= 3, "{ticks:?}");
    assert!(ticks.iter().all(|d| (0.0..=90.0).contains(d)), "{ticks:?}");
    for c in [style::cold_to_warm(0.0), style::cold_to_warm(1.0)] {
        assert!(count(&image, c) > 100, "too few pixels of {}", hex(c));
    }
    assert!(hue_sectors(&image, 100) >= 5);
    // One polyline per isotherm in its colour, and the series in black.
    for &t in &temperatures {
        let c = style::cold_to_warm((t + 30.0) / 100.0);
        assert!(strokes(&p.svg, c, 1) >= 1, "no line of the {t} °C isotherm");
    }
    assert!(strokes(&p.svg, RGBColor(0, 0, 0), 2) >= 1);

    let (_, texts) = check(&render(&figure("G")).unwrap(), (1100, 640));
    let text = joined(&texts);
    assert!(text.contains("|G*| = √(G′² + G″²) (Pa)") && !text.contains("E′"));
}
