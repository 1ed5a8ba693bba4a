//! Cancelling a fit (crate::cancel): a flag never set leaves the result as
//! it was, bit for bit; a set flag ends the fit with FitError::Cancelled.

use rollfit_fit::{Cancel, FitError, FitParams, FitReport, Measurements, RollingSetup, fit};
use rollfit_model::{ContactSize, Geometry, Scene, Shape, StandardLinearSolid, Substrate};

fn problem() -> (Measurements, RollingSetup) {
    let setup = RollingSetup {
        geometry: Geometry {
            shape: Shape::Sphere,
            radius: 0.01,
            load: 1.0,
        },
        substrate: Substrate {
            poisson: 0.5,
            film_thickness: None,
        },
        contact: ContactSize::Dynamic,
    };
    let truth = StandardLinearSolid::new(1e6, 1e8, 1e-2).unwrap();
    let scene = Scene::new(setup.geometry, setup.substrate, setup.contact, truth).unwrap();
    let speeds: Vec<f64> = (0..21).map(|k| 10f64.powf(-6.0 + 0.3 * k as f64)).collect();
    let mu = scene.friction_sweep(&speeds).unwrap();
    let sigma = mu.iter().map(|m| 0.01 * m).collect();
    let data = Measurements::new(speeds, mu, Some(sigma), None).unwrap();
    (data, setup)
}

/// fit.json's numbers without the wall times, which measure the clock.
fn numbers(report: &FitReport) -> serde_json::Value {
    fn strip(value: &mut serde_json::Value) {
        match value {
            serde_json::Value::Object(map) => {
                map.remove("wall_time_s");
                map.values_mut().for_each(strip);
            }
            serde_json::Value::Array(items) => items.iter_mut().for_each(strip),
            _ => {}
        }
    }
    let mut value = serde_json::to_value(report).unwrap();
    strip(&mut value);
    value
}

#[test]
fn a_flag_never_set_changes_nothing() {
    let (data, setup) = problem();
    let plain = fit(&data, &FitParams::default().check(setup).unwrap()).unwrap();
    let params = FitParams::default()
        .check(setup)
        .unwrap()
        .with_cancel(Cancel::new());
    let flagged = fit(&data, &params).unwrap();
    assert_eq!(numbers(&plain), numbers(&flagged));
    assert_eq!(plain.mu_fit, flagged.mu_fit);
    assert_eq!(plain.curve, flagged.curve);
}

#[test]
fn a_set_flag_ends_the_fit() {
    let (data, setup) = problem();
    let flag = Cancel::new();
    let params = FitParams::default()
        .check(setup)
        .unwrap()
        .with_cancel(flag.clone());
    flag.cancel();
    assert!(matches!(fit(&data, &params), Err(FitError::Cancelled)));
}
