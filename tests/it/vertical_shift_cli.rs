//! End-to-end test of vertical factors: `rollfit master
//! --vertical` on isotherms made here with known a_T and b_T writes the
//! measured b_T into material.toml (`log_bT`), and `rollfit forward` with
//! that material at an isotherm's temperature predicts μ of
//! E*(ω, T) = b_T E*_ref(ω a_T):
//!
//! - exactly the μ computed here from the written Prony series and the
//!   shift.csv factors by the identity μ(v; b E, F) = μ(v; E, F/b), which
//!   goes through neither the scene's vertical code nor `Shifted`;
//! - close to μ of the true modulus at that temperature, and much closer
//!   than the same material without its vertical factor;
//! - the μ of a scene reading the isotherms themselves (`model = "dma"`,
//!   `vertical = true`).
//!
//! And `rollfit fit` of a temperature set made with known b_T, given the
//! same b_T in the scene's `[material.shift]`, recovers the master curve at
//! T_ref (and fails to without them), and `rollfit report` draws its
//! fitted μ(v) under the same b_T.

use crate::common;

use std::ffi::OsStr;
use std::fs;
use std::path::Path;

use common::{Table, TempDir, assert_failure, rollfit, succeed, text};
use rollfit_model::{
    ContactSize, Geometry, HavriliakNegami, Prony, Scene, Shape, Shifted, Substrate,
    ViscoelasticModulus,
};
use rollfit_testkit::materials::hn_rubber;

/// WLF of the synthetic isotherms about 20 °C.
fn wlf(t: f64) -> f64 {
    -9.0 * (t - 20.0) / (110.0 + t - 20.0)
}

/// The true vertical factor: 0.01 decade per kelvin about 20 °C (steeper
/// than a density law, so that b_T visibly changes μ).
fn log_b(t: f64) -> f64 {
    0.01 * (t - 20.0)
}

fn truth() -> HavriliakNegami {
    hn_rubber()
}

/// Noiseless Young's isotherms at `temps`, 16 frequencies over 0.1…100
/// rad/s: E*(ω, T) = b_T E*_truth(ω a_T).
fn isotherms_csv(temps: &[f64]) -> String {
    let master = truth();
    let mut out = String::from("T,omega,E_storage,E_loss\n");
    for &t in temps {
        let (a, b) = (10f64.powf(wlf(t)), 10f64.powf(log_b(t)));
        for i in 0..16 {
            let w = 0.1 * 10f64.powf(3.0 * f64::from(i) / 15.0);
            let e = master.modulus(w * a) * b;
            out += &format!("{t},{w:e},{:e},{:e}\n", e.re, e.im);
        }
    }
    out
}

const RADIUS: f64 = 0.01;
const LOAD: f64 = 0.05;
const T: f64 = 35.0;

/// μ at `speeds` of a sphere on `material` under `load`.
fn friction<M: ViscoelasticModulus>(material: M, load: f64, speeds: &[f64]) -> Vec<f64> {
    let geometry = Geometry {
        shape: Shape::Sphere,
        radius: RADIUS,
        load,
    };
    let substrate = Substrate {
        poisson: 0.5,
        film_thickness: None,
    };
    Scene::new(geometry, substrate, ContactSize::Dynamic, material)
        .unwrap()
        .with_tolerance(1e-6)
        .unwrap()
        .friction_sweep(speeds)
        .unwrap()
}

fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x / y - 1.0).abs())
        .fold(0.0, f64::max)
}

#[test]
fn master_vertical_factors_reach_forward() {
    let tmp = TempDir::new("vertical");
    let temps: Vec<f64> = (0..9).map(|k| 5.0 * f64::from(k)).collect();
    let dma = tmp.write("iso.csv", isotherms_csv(&temps));
    let dir = tmp.path().join("master");
    succeed(&[
        OsStr::new("master"),
        dma.as_os_str(),
        OsStr::new("-o"),
        dir.as_os_str(),
        OsStr::new("--vertical"),
        OsStr::new("--T-ref"),
        OsStr::new("20"),
    ]);

    // The measured b_T: the truth's, within 0.02 decade.
    let shift = Table::read(&dir.join("shift.csv"));
    let (t, log_a, log_bt) = (
        shift.column("T"),
        shift.column("log_aT"),
        shift.column("log_bT"),
    );
    for (t, l) in t.iter().zip(&log_bt) {
        assert!(
            (l - log_b(*t)).abs() < 0.02,
            "T = {t}: log b_T {l} vs {}",
            log_b(*t)
        );
    }
    let row = t.iter().position(|&x| x == T).unwrap();
    let (log_a, log_bt) = (log_a[row], log_bt[row]);
    let material = fs::read_to_string(dir.join("material.toml")).unwrap();
    assert!(material.contains("log_bT"), "{material}");

    // forward with the written material at 35 °C.
    let scene = tmp.write(
        "scene.toml",
        format!(
            "[geometry]\nshape = \"sphere\"\nradius = {RADIUS}\nload = {LOAD}\n{material}\n\
             [sweep]\nv_min = 1e-4\nv_max = 0.1\ncount = 7\ntemperature = {T}\n"
        ),
    );
    let out = tmp.path().join("mu.csv");
    let summary = succeed(&[
        OsStr::new("forward"),
        scene.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ]);
    let said = format!("log10 b_T = {log_bt:.4}");
    assert!(summary.contains(&said), "{said:?} in {summary}");
    let table = Table::read(&out);
    let (speeds, mu) = (table.column("v"), table.column("mu"));

    // The written series, read back as a scene reads it.
    let prony: Prony = rollfit_io::scene::load(&scene)
        .unwrap()
        .material
        .unwrap()
        .as_prony(Path::new(""), &|_| {})
        .unwrap()
        .unwrap();
    // Directly: the series shifted by a_T under the load divided by b_T.
    let b = 10f64.powf(log_bt);
    let direct = friction(prony.shifted(log_a).unwrap(), LOAD / b, &speeds);
    let exact = largest_difference(&mu, &direct);
    assert!(exact < 1e-9, "forward vs direct: {exact:e}");

    // Against the truth at 35 °C, with and without b_T.
    let true_mu = friction(
        Shifted::new(truth(), wlf(T)).unwrap(),
        LOAD / 10f64.powf(log_b(T)),
        &speeds,
    );
    let without = friction(prony.shifted(log_a).unwrap(), LOAD, &speeds);
    let (with_error, without_error) = (
        largest_difference(&mu, &true_mu),
        largest_difference(&without, &true_mu),
    );
    eprintln!("μ against the truth: {with_error:.4} with b_T, {without_error:.4} without");
    // Found: 4e-4 with b_T, 0.15 without.
    assert!(with_error < 0.005, "{with_error}");
    assert!(without_error > 0.1, "{without_error}");

    // A scene with the isotherms themselves, model = "dma" with
    // vertical = true, applies the same b_T: the same μ.
    let dma_scene = tmp.write(
        "dma.toml",
        format!(
            "[geometry]\nshape = \"sphere\"\nradius = {RADIUS}\nload = {LOAD}\n[material]\n\
             model = \"dma\"\nfile = \"iso.csv\"\nT_ref = 20.0\nvertical = true\n[sweep]\n\
             v_min = 1e-4\nv_max = 0.1\ncount = 7\ntemperature = {T}\n"
        ),
    );
    let dma_out = tmp.path().join("dma-mu.csv");
    succeed(&[
        OsStr::new("forward"),
        dma_scene.as_os_str(),
        OsStr::new("-o"),
        dma_out.as_os_str(),
    ]);
    let dma_mu = Table::read(&dma_out).column("mu");
    let same = largest_difference(&dma_mu, &mu);
    assert!(same < 1e-6, "model = \"dma\" vs material.toml: {same:e}");
}

/// A temperature set (data/hn-rubber-tset-truth.toml's rubber at five
/// temperatures, 1 % noise) made with known vertical factors,
/// log10 b_T = 0.005 (T − 20 °C), is fitted back with the same `log_bT` in
/// the scene: the master curve at T_ref matches the truth in the window,
/// WLF's constants come back, and the fit describes the data; the same fit
/// without the vertical factors misses by much more.
#[test]
fn a_temperature_set_with_vertical_factors_is_fitted_at_t_ref() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let tmp = TempDir::new("tset");
    let truth_scene = fs::read_to_string(root.join("data/hn-rubber-tset-truth.toml")).unwrap();
    let anchor = "C2 = 101.6          # K\n";
    assert!(truth_scene.contains(anchor));
    let vertical = "log_bT = [{ T = -20.0, log_bT = -0.2 }, { T = 0.0, log_bT = -0.1 }, \
                    { T = 40.0, log_bT = 0.1 }, { T = 60.0, log_bT = 0.2 }]\n";
    // 161 speeds (20 a decade): the rows are condensed to bins for the fit,
    // and mu.csv's μ at every row is evaluated again, with b_T.
    assert!(truth_scene.contains("count = 41\n"));
    let truth_scene = truth_scene.replace("count = 41\n", "count = 161\n");
    let with_vertical = truth_scene.replace(anchor, &format!("{anchor}{vertical}"));
    let truth_path = tmp.write("truth.toml", &with_vertical);
    let data = tmp.path().join("data.csv");
    succeed(&[
        OsStr::new("forward"),
        truth_path.as_os_str(),
        OsStr::new("--noise"),
        OsStr::new("0.01"),
        OsStr::new("--seed"),
        OsStr::new("4"),
        OsStr::new("-o"),
        data.as_os_str(),
    ]);
    let fit_section = "[fit]\nshift = \"wlf\"\nT_ref = 20.0\nE_at = { omega = 10.0, E = 6.26e7 }\n";
    let fit = |scene_text: &str, name: &str| {
        let scene = tmp.write(
            &format!("{name}.toml"),
            format!("{scene_text}{fit_section}"),
        );
        let out = tmp.path().join(name);
        succeed(&[
            OsStr::new("fit"),
            scene.as_os_str(),
            data.as_os_str(),
            OsStr::new("-o"),
            out.as_os_str(),
            OsStr::new("--allow-poor-fit"),
        ]);
        let report: serde_json::Value =
            serde_json::from_str(&fs::read_to_string(out.join("fit.json")).unwrap()).unwrap();
        let curve = Table::read(&out.join("modulus.csv"));
        let truth = truth();
        let (omega, tan, abs_e) = (
            curve.column("omega"),
            curve.column("tan_delta"),
            curve.column("abs_E"),
        );
        let rms = |errors: Vec<f64>| {
            (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt()
        };
        let tan_error = rms(omega
            .iter()
            .zip(&tan)
            .map(|(&w, t)| {
                let e = truth.modulus(w);
                t / (e.im / e.re) - 1.0
            })
            .collect());
        let abs_error = rms(omega
            .iter()
            .zip(&abs_e)
            .map(|(&w, a)| a / truth.modulus(w).norm() - 1.0)
            .collect());
        (report, tan_error, abs_error)
    };
    let (report, tan_error, abs_error) = fit(&with_vertical, "with");
    let (control, control_tan, control_abs) = fit(&truth_scene, "without");
    let chi2 = |r: &serde_json::Value| {
        r["fit_quality"]["chi2"].as_f64().unwrap()
            / r["fit_quality"]["degrees_of_freedom"].as_f64().unwrap()
    };
    eprintln!(
        "with b_T: tan δ {tan_error:.4}, |E| {abs_error:.4} RMS, χ²/dof {:.2}, C1 {}, C2 {}; \
         without: tan δ {control_tan:.4}, |E| {control_abs:.4}, χ²/dof {:.2}",
        chi2(&report),
        report["shift"]["C1"],
        report["shift"]["C2"],
        chi2(&control)
    );
    // Found: tan δ 0.40 %, |E| 0.54 % RMS, χ²/dof 0.97, C1 8.863, C2 101.60;
    // without b_T: 11 %, 19 %, χ²/dof 35.9.
    assert_eq!(report["fit_quality"]["verdict"], "good");
    assert_eq!(report["shift"]["T_ref"], 20.0);
    assert!(
        tan_error < 0.02 && abs_error < 0.02,
        "{tan_error} {abs_error}"
    );
    let c1 = report["shift"]["C1"].as_f64().unwrap();
    let c2 = report["shift"]["C2"].as_f64().unwrap();
    assert!(
        (c1 / 8.86 - 1.0).abs() < 0.02 && (c2 / 101.6 - 1.0).abs() < 0.02,
        "{c1} {c2}"
    );
    assert!(chi2(&report) < 1.5 && chi2(&control) > 5.0);
    assert!(control_tan > 0.05 && control_abs > 0.05);
    // mu.csv's fitted μ at the 805 rows carries b_T too: residuals at the
    // noise.
    assert!(report["condensed"].is_object(), "not condensed");
    let mu = Table::read(&tmp.path().join("with/mu.csv"));
    assert_eq!(mu.column("v").len(), 805);
    let worst = mu
        .column("residual")
        .iter()
        .fold(0.0f64, |m, r| m.max(r.abs()));
    assert!(worst < 0.05, "largest residual {worst}");
    let said = report["warnings"].as_array().unwrap().iter().any(|w| {
        w.as_str()
            .unwrap()
            .contains("log10 b_T = -0.2000 at -20 °C, -0.1000 at 0 °C, 0.0000 at 20 °C")
    });
    assert!(said, "{}", report["warnings"]);

    // The report draws the fitted μ(v) under the scene's b_T, so
    // it reproduces mu.csv at every temperature (805 rows condensed to bins
    // for the fit, μ at every row); under the same scene without b_T it
    // does not, at a temperature other than T_ref.
    let with_dir = tmp.path().join("with");
    let drawn = rollfit(&[OsStr::new("report"), with_dir.as_os_str()]);
    let stderr = text(&drawn.stderr);
    assert!(
        drawn.status.success() && !stderr.contains("warning"),
        "{stderr}"
    );
    let page = fs::read_to_string(with_dir.join("report.html")).unwrap();
    assert!(page.contains("μ(v) on 240 speeds through the measured range"));
    assert!(page.contains("<strong>Verdict: good</strong>"));
    let without_scene = tmp.path().join("without.toml");
    let refused = rollfit(&[
        OsStr::new("report"),
        with_dir.as_os_str(),
        OsStr::new("--scene"),
        without_scene.as_os_str(),
    ]);
    let message = assert_failure(&refused, &["does not reproduce the fit's μ", ", T = "]);
    assert!(!message.contains("T = 20 °C"), "{message}");

    // A measured temperature outside the table is refused before any
    // numerics, naming the key, and nothing is written.
    let short = with_vertical.replace(", { T = 60.0, log_bT = 0.2 }", "");
    let scene = tmp.write("short.toml", format!("{short}{fit_section}"));
    let out = tmp.path().join("short");
    let failed = rollfit(&[
        OsStr::new("fit"),
        scene.as_os_str(),
        data.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ]);
    assert_failure(&failed, &["log_bT", "no vertical factor for T = 60 °C"]);
    assert!(!out.exists());
}
