//! The pictures of `rollfit master`, end to end: on the bundled shear
//! isotherms (data/hn-rubber-dma-isotherms.csv, G′ and G″ columns) the
//! master picture is drawn in G′, G″ with the shift law and its constants
//! named in the shift panel's legend, next to a van Gurp–Palmen plot; a
//! relaxation file gets its master picture (and no van Gurp–Palmen plot:
//! E(t) has no phase angle). The SVG's text says what the picture shows.
//!
//! The relaxation isotherms are a stretched exponential (Kohlrausch–
//! Williams–Watts), E(t) = E0 + (E1 − E0) exp(−(t/τ)^β), at six
//! temperatures shifted by WLF: a smooth relaxation that a Prony series
//! follows.

use crate::common;

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};

use common::{TempDir, succeed};

/// The workspace's root (the tests belong to crates/cli).
fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The text of every `<text>` element of an SVG file, one per line.
fn svg_text(path: &Path) -> String {
    let svg = fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let doc = roxmltree::Document::parse(&svg).expect("the SVG parses as XML");
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text())
        .map(str::trim)
        .collect::<Vec<_>>()
        .join("\n")
}

fn master(dma: &Path, dir: &Path) {
    succeed(&[
        OsStr::new("master"),
        dma.as_os_str(),
        OsStr::new("-o"),
        dir.as_os_str(),
    ]);
}

#[test]
fn shear_isotherms_are_drawn_as_g_with_the_law_named_and_a_van_gurp_palmen_plot() {
    let tmp = TempDir::new("shear");
    let dir = tmp.path().join("master");
    master(&workspace().join("data/hn-rubber-dma-isotherms.csv"), &dir);
    let json: serde_json::Value =
        serde_json::from_slice(&fs::read(dir.join("master.json")).unwrap()).unwrap();
    assert_eq!(json["modulus_kind"], "shear");
    let text = svg_text(&dir.join("master.svg"));
    for label in ["G′, G″ (Pa)", "Prony G′", "tan δ = G″/G′, per isotherm"] {
        assert!(text.contains(label), "no {label:?} in\n{text}");
    }
    assert!(
        !text.contains("E′"),
        "Young's labels on shear data:\n{text}"
    );
    // The law applied, named with its constants as master.json has them.
    let law = json["shift_law"].as_str().unwrap();
    assert_eq!(law, "wlf", "the bundled isotherms follow WLF");
    let c1 = json["wlf"]["C1"].as_f64().unwrap();
    assert!(text.contains("WLF, T_ref = 20 °C:"), "{text}");
    let constants = text
        .lines()
        .find(|l| l.starts_with("C1 = "))
        .unwrap_or_else(|| panic!("no constants in\n{text}"));
    let shown: f64 = constants[5..].split(' ').next().unwrap().parse().unwrap();
    assert!(
        (shown - c1).abs() <= 0.01 * c1.abs(),
        "{constants} against C1 = {c1}"
    );
    assert!(
        constants.contains("C2 = ") && constants.ends_with(" K"),
        "{constants}"
    );
    // A good verdict says nothing.
    assert_eq!(json["quality"]["verdict"], "good");
    assert!(!text.contains("Verdict"));

    let vgp = svg_text(&dir.join("vgp.svg"));
    for label in ["van Gurp–Palmen plot", "|G*|", "phase angle δ (°)"] {
        assert!(vgp.contains(label), "no {label:?} in\n{vgp}");
    }
    assert!(dir.join("vgp.png").is_file());
}

/// A relaxation CSV of the module doc's stretched exponential, in MPa.
fn kww_relaxation_csv(temps: &[f64]) -> String {
    let (e0, e1, tau, beta) = (2.0, 2000.0, 1e-2, 0.35);
    let wlf = |t: f64| -8.86 * (t - 20.0) / (101.6 + t - 20.0);
    let mut out = String::from("T_C,t_s,E_relax_MPa\n");
    for &t in temps {
        for i in 0..16 {
            let time = 10f64.powf(-1.0 + 3.0 * f64::from(i) / 15.0);
            let reduced = time / 10f64.powf(wlf(t));
            let e = e0 + (e1 - e0) * (-(reduced / tau).powf(beta)).exp();
            out += &format!("{t},{time:e},{e:e}\n");
        }
    }
    out
}

#[test]
fn relaxation_isotherms_get_a_master_picture() {
    let tmp = TempDir::new("relaxation");
    let data = tmp.write(
        "kww.csv",
        kww_relaxation_csv(&[-10.0, 0.0, 10.0, 20.0, 30.0, 40.0]),
    );
    let dir = tmp.path().join("master");
    master(&data, &dir);
    assert!(dir.join("master.png").is_file());
    let text = svg_text(&dir.join("master.svg"));
    for label in [
        "Relaxation master curve at T_ref = 20 °C",
        "reduced time t/a_T (s), T_ref = 20 °C",
        "E(t) (Pa)",
        "Prony E(t)",
        "Shift factors a_T",
        "-10 °C (coldest)",
        "40 °C (warmest)",
    ] {
        assert!(text.contains(label), "no {label:?} in\n{text}");
    }
    assert!(!dir.join("vgp.svg").exists(), "a phase angle of E(t)?");
}
