//! The fitted μ(v) friction.png draws: the model's μ on
//! a dense grid of speeds through the measured range, not a line through
//! mu.csv's values; refused for a scene that does not reproduce the fit;
//! and for `physics = "exact"` carried by the fit's own correction r.
//!
//! The fits are the committed example under examples/fits/ with its scene under
//! data/, and a copy of it given an exact correction here.

use crate::common;

use common::{TempDir, assert_contains, committed_fit, dense_line, model, scene};
use rollfit_io::FitDir;
use rollfit_io::fit_dir::columns;
use rollfit_report::fitted_friction::{
    DENSE_POINTS, FittedLine, MATCH_TOLERANCE, dense_curves, temperature_groups,
};
use rollfit_report::plot::friction::FrictionFigure;
use rollfit_report::plot::pictures;

/// The fitted line friction.png draws has at least 200 points, log-spaced
/// from the lowest measured speed to the highest; between the measured
/// speeds it is the model (not the chord of mu.csv's values), and it meets
/// mu.csv's μ at the measured speeds.
#[test]
fn the_fitted_curve_is_the_model_on_a_dense_grid() {
    let fit = committed_fit("hn-rubber");
    let line = dense_line(&fit, "hn-rubber");
    let series = FrictionFigure {
        fit: &fit,
        line: &line,
    }
    .fitted_series();
    assert_eq!(series.len(), 1);
    let points = &series[0].1;
    assert_eq!(points.len(), DENSE_POINTS);
    assert!(points.len() >= 200, "{} points", points.len());
    let rows = &temperature_groups(&fit.friction)[0].1;
    let (lo, hi) = (rows[0].speed.log10(), rows[rows.len() - 1].speed.log10());
    assert_eq!((points[0].0, points[points.len() - 1].0), (lo, hi));
    let step = (hi - lo) / (DENSE_POINTS - 1) as f64;
    for pair in points.windows(2) {
        assert!((pair[1].0 - pair[0].0 - step).abs() < 1e-9, "{pair:?}");
    }
    let ends = [
        (points[0].1, rows[0].mu_fit),
        (points[points.len() - 1].1, rows[rows.len() - 1].mu_fit),
    ];
    for (drawn, fitted) in ends {
        assert!((10f64.powf(drawn) / fitted - 1.0).abs() < MATCH_TOLERANCE);
    }

    let FittedLine::Dense(curves) = &line else {
        unreachable!()
    };
    let curve = &curves[0];
    let scene = scene("hn-rubber");
    let mut largest_sag: f64 = 0.0;
    for k in (1..DENSE_POINTS - 1).step_by(17) {
        let v = curve.speeds[k];
        // μ alone at v: a sweep shares its quadrature between speeds, so
        // the two agree to the quadrature's tolerance, not to the bit
        // (found: 4e-11).
        let alone = model(&scene, &fit, v);
        assert!((curve.friction[k] / alone - 1.0).abs() < scene.tolerance);
        // The chord of mu.csv's two neighbouring values, in log–log.
        let j = rows.partition_point(|r| r.speed <= v);
        let (a, b) = (&rows[j - 1], &rows[j]);
        let t = (v / a.speed).ln() / (b.speed / a.speed).ln();
        let chord = a.mu_fit.log10() + t * (b.mu_fit / a.mu_fit).log10();
        largest_sag = largest_sag.max((curve.friction[k].log10() - chord).abs());
    }
    assert!(
        largest_sag > 1e-4,
        "the curve is the chord: {largest_sag:e} decades"
    );
}

/// The scene of another experiment does not reproduce the fit: no dense
/// curve, the line joins mu.csv's values, and the caption says why.
#[test]
fn a_scene_that_does_not_reproduce_the_fit_draws_no_dense_curve() {
    let fit = committed_fit("hn-rubber");
    let other = scene("lab-ball");
    let error = dense_curves(&fit, &other).unwrap_err().to_string();
    assert_contains(&error, &["does not reproduce the fit's μ", "% off at v ="]);
    let line = FittedLine::of(&fit, &other);
    assert_eq!(line, FittedLine::AtData { why: error.clone() });
    let series = FrictionFigure {
        fit: &fit,
        line: &line,
    }
    .fitted_series();
    assert_eq!(series[0].1.len(), fit.friction.len());
    let all = pictures(&fit, &[], &line).unwrap();
    assert_contains(&all[0].caption, &["joined by straight lines", &error]);
}

/// A fit with `physics = "exact"`: mu.csv's `mu_fit` is the approximate
/// model's μ times r = μ_exact/μ_approx (its `exact_correction` column).
/// Here the committed example is given a smooth r of up to ±3 % (far above
/// [`MATCH_TOLERANCE`]), as an exact fit would write it: the dense curve
/// reproduces `mu_fit` only by carrying r, and between the speeds carries
/// it by the fit's own cubic interpolation in ln v, here to 1e-4 of r
/// (found: 4e-7 at 0.2 decades between the speeds); the
/// same folder read as an approximate fit is refused.
#[test]
fn an_exact_physics_fit_gets_a_dense_curve_carrying_its_correction() {
    let r = |v: f64| 1.0 + 0.03 * (v.ln() / 3.0).sin();
    let from = common::workspace().join("examples/fits/hn-rubber");
    let folder = TempDir::new("exact");
    for file in ["fit.json", "modulus.csv"] {
        std::fs::copy(from.join(file), folder.path().join(file)).unwrap();
    }
    let json = std::fs::read_to_string(from.join("fit.json")).unwrap();
    let mut json: serde_json::Value = serde_json::from_str(&json).unwrap();
    json["physics"] = serde_json::json!({"kind": "exact"});
    std::fs::write(folder.path().join("fit.json"), json.to_string()).unwrap();
    let text = std::fs::read_to_string(from.join("mu.csv")).unwrap();
    let mut lines = text.lines();
    let header = lines.next().unwrap();
    let names: Vec<&str> = header.split(',').collect();
    let column = |name: &str| names.iter().position(|n| *n == name).unwrap();
    let (v, mu_fit) = (column(columns::V), column(columns::MU_FIT));
    let mut out = format!("{header},{}\n", columns::EXACT_CORRECTION);
    for line in lines {
        let mut fields: Vec<String> = line.split(',').map(str::to_string).collect();
        let speed: f64 = fields[v].parse().unwrap();
        let fitted: f64 = fields[mu_fit].parse().unwrap();
        fields[mu_fit] = format!("{:e}", fitted * r(speed));
        out += &format!("{},{:e}\n", fields.join(","), r(speed));
    }
    std::fs::write(folder.path().join("mu.csv"), out).unwrap();
    let fit = FitDir::read(folder.path()).unwrap();
    assert!(
        fit.friction
            .iter()
            .all(|row| row.exact_correction.is_some())
    );

    let scene = scene("hn-rubber");
    let curves = dense_curves(&fit, &scene).expect("the exact fit's dense curve");
    let curve = &curves[0];
    assert_eq!(curve.speeds.len(), DENSE_POINTS);
    let mut largest: f64 = 0.0;
    for k in (0..DENSE_POINTS).step_by(7) {
        let v = curve.speeds[k];
        let carried = curve.friction[k] / model(&scene, &fit, v);
        largest = largest.max((carried / r(v) - 1.0).abs());
    }
    eprintln!("r carried between the speeds to {largest:e}");
    assert!(largest < 1e-4, "r carried to {largest:e}");

    let approximate = FitDir {
        summary: rollfit_io::fit_dir::FitSummary {
            physics: None,
            ..fit.summary.clone()
        },
        ..fit.clone()
    };
    let error = dense_curves(&approximate, &scene).unwrap_err().to_string();
    assert_contains(&error, &["does not reproduce the fit's μ"]);
}
