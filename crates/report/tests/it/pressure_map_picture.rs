//! The picture of an exact rolling contact's pressure map (`rollfit
//! forward` with `[contact] size = "exact"`) renders to a PNG that decodes
//! at the stated size and shows the pressure's colours, the black outline
//! and the blue static Hertz comparison, and to an SVG that carries the
//! title (speed and μ), the axis labels and the legend; an empty map
//! renders too.
//!
//! The maps are synthetic with a known shape: a Hertz-like pressure on a
//! disc shifted toward the leading side (sphere), and an asymmetric
//! profile between two edges (cylinder).

use crate::common;

use common::{count, decode};
use plotters::style::RGBColor;
use rollfit_model::exact::{ContactPressure, PressureMap};
use rollfit_report::plot::pressure_map::PressureMapFigure;
use rollfit_report::plot::{Picture, render, style};

/// Static Hertz radius or half-width, m.
const SIZE: f64 = 1e-3;

/// A sphere's map: cells of side r0/20 on a disc of radius 0.8 r0 centred
/// at x = 0.2 r0, pressure √(1 − ρ²) scaled to peak at 1.5 p0.
fn sphere_map() -> PressureMap {
    let h = SIZE / 20.0;
    let (centre, radius) = (0.2 * SIZE, 0.8 * SIZE);
    let load = 0.15;
    let p0 = 1.5 * load / (std::f64::consts::PI * SIZE * SIZE);
    let mut cells = Vec::new();
    let mut outline = Vec::new();
    for j in -20..20 {
        let y = (f64::from(j) + 0.5) * h;
        if y.abs() >= radius {
            continue;
        }
        let half = (radius * radius - y * y).sqrt();
        outline.push((y, centre - half, centre + half));
        for i in -20..24 {
            let x = (f64::from(i) + 0.5) * h;
            let rho2 = ((x - centre).powi(2) + y * y) / (radius * radius);
            if rho2 < 1.0 {
                cells.push((x, y, 1.5 * p0 * (1.0 - rho2).sqrt()));
            }
        }
    }
    PressureMap {
        speed: 1e-3,
        mu: 0.0213,
        error_estimate: 1e-4,
        static_contact_size: SIZE,
        load,
        pressure: ContactPressure::Cells {
            cell: h,
            cells,
            outline,
        },
    }
}

/// A cylinder's map: p ∝ √((x − a1)(a2 − x)) (1 + x/a0) between
/// a1 = −0.5 a0 and a2 = 0.9 a0.
fn cylinder_map() -> PressureMap {
    let (a1, a2) = (-0.5 * SIZE, 0.9 * SIZE);
    let points = (0..=200)
        .map(|k| {
            let x = a1 + (a2 - a1) * f64::from(k) / 200.0;
            let p = 1e5 * ((x - a1) * (a2 - x)).max(0.0).sqrt() / SIZE * (1.0 + x / SIZE);
            (x, p)
        })
        .collect();
    PressureMap {
        speed: 2e-2,
        mu: 0.05,
        error_estimate: 1e-6,
        static_contact_size: SIZE,
        load: 100.0,
        pressure: ContactPressure::Profile {
            points,
            trailing_edge: a1,
            leading_edge: a2,
        },
    }
}

/// The PNG decodes at 900 × 620 and is not blank; the SVG parses and
/// holds every `labels` fragment in its text. Returns the PNG's pixels.
fn check(p: &Picture, labels: &[&str]) -> common::Decoded {
    assert_eq!(p.name, "pressure_map");
    let image = decode(p);
    assert_eq!((image.width, image.height), (900, 620));
    let inked = image
        .rgb
        .chunks_exact(3)
        .filter(|px| px.iter().any(|&c| c < 200))
        .count();
    assert!(inked > 900 * 620 / 100, "only {inked} pixels drawn");
    let doc = roxmltree::Document::parse(&p.svg).expect("the SVG parses as XML");
    let text: String = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text())
        .collect::<Vec<_>>()
        .join("\n");
    for label in labels {
        assert!(text.contains(label), "no text {label:?} in:\n{text}");
    }
    image
}

/// Pixels close to `c` (within 12 per channel): the ramp's colours are
/// interpolated, so a band rather than one value.
fn near(image: &common::Decoded, c: RGBColor) -> usize {
    image
        .rgb
        .chunks_exact(3)
        .filter(|px| {
            (i32::from(px[0]) - i32::from(c.0)).abs() <= 12
                && (i32::from(px[1]) - i32::from(c.1)).abs() <= 12
                && (i32::from(px[2]) - i32::from(c.2)).abs() <= 12
        })
        .count()
}

#[test]
fn a_sphere_map_shows_its_pressure_outline_and_hertz_circle() {
    let map = sphere_map();
    let p = render(&PressureMapFigure {
        map: &map,
        label: "ball.toml: exact sphere".into(),
    })
    .unwrap();
    let image = check(
        &p,
        &[
            "ball.toml: exact sphere, v = 1.000e-3 m/s, μ = 0.02130",
            "x / r₀, rolling direction →",
            "r₀ = 1.00 mm",
            "y / r₀",
            "p / p₀",
            "static Hertz",
            "exact outline",
            "sphere's axis",
        ],
    );
    // The map's pale low pressures, its dark peak, the black outline and
    // the dashed blue circle are all there.
    assert!(near(&image, style::pressure_ramp(0.05)) > 200);
    assert!(near(&image, style::pressure_ramp(0.95)) > 200);
    assert!(count(&image, RGBColor(0, 0, 0)) > 300);
    assert!(count(&image, RGBColor(31, 119, 180)) > 300);
    assert!(p.caption.contains("sphere") && p.caption.contains("static Hertz"));
    // Runs of one colour level are merged: far fewer rectangles than the
    // 1600-odd cells.
    let ContactPressure::Cells { cells, .. } = &map.pressure else {
        unreachable!()
    };
    let rects = p.svg.matches("<rect").count();
    assert!(
        rects < cells.len(),
        "{rects} rectangles for {} cells",
        cells.len()
    );
}

#[test]
fn a_cylinder_map_shows_its_profile_against_hertz() {
    let p = render(&PressureMapFigure {
        map: &cylinder_map(),
        label: "roller.toml: exact cylinder, T = 20 °C".into(),
    })
    .unwrap();
    let image = check(
        &p,
        &[
            "roller.toml: exact cylinder, T = 20 °C, v = 2.000e-2 m/s, μ = 0.05000",
            "x / a₀, rolling direction →",
            "a₀ = 1.00 mm",
            "p / p₀",
            "exact pressure",
            "static Hertz",
        ],
    );
    assert!(count(&image, style::FITTED) > 300);
    assert!(count(&image, RGBColor(31, 119, 180)) > 300);
}

#[test]
fn a_map_without_pressure_still_renders() {
    let mut map = sphere_map();
    map.pressure = ContactPressure::Cells {
        cell: SIZE / 20.0,
        cells: Vec::new(),
        outline: Vec::new(),
    };
    let p = render(&PressureMapFigure {
        map: &map,
        label: "empty".into(),
    })
    .unwrap();
    check(&p, &["static Hertz"]);
    assert!(!p.svg.is_empty());
}
