//! The τ-grid rule of `rollfit_fit::tau_grid`: where the grid ends must not
//! select the answer. Extending the default grid by two decades at each end
//! (same spacing) leaves the recovered tan δ and |E| inside the window
//! unchanged to well below the noise-level uncertainty.

use rollfit_testkit::materials::hn_rubber;
use rollfit_testkit::rolling::{setup, synthetic};

use rollfit_fit::{FitParams, ScaleAnchor, TermRule, fit};
use rollfit_model::{Prony, ViscoelasticModulus};

#[test]
fn extending_the_grid_does_not_move_the_result() {
    let truth = hn_rubber();
    let data = synthetic(hn_rubber(), 0.01, 11);
    let anchor = ScaleAnchor::ModulusAt {
        omega: 10.0,
        modulus: truth.modulus(10.0).norm(),
    };
    let base = fit(
        &data,
        &FitParams {
            anchor: Some(anchor),
            ..FitParams::default()
        }
        .check(setup())
        .unwrap(),
    )
    .unwrap();
    let tau = &base.model.tau;
    let ratio = tau[1] / tau[0];
    let extra = 4; // two decades at two per decade
    let mut extended: Vec<f64> = (1..=extra).rev().map(|k| tau[0] / ratio.powi(k)).collect();
    extended.extend_from_slice(tau);
    extended.extend((1..=extra).map(|k| tau[tau.len() - 1] * ratio.powi(k)));
    let wide = fit(
        &data,
        &FitParams {
            anchor: Some(anchor),
            terms: TermRule::Explicit(extended),
            ..FitParams::default()
        }
        .check(setup())
        .unwrap(),
    )
    .unwrap();
    let m = &wide.model;
    let wide_prony = Prony::new(m.glassy_modulus, m.strengths.clone(), m.tau.clone()).unwrap();
    let (mut worst_tan, mut worst_abs, mut worst_band) = (0.0f64, 0.0f64, 0.0f64);
    for p in &base.curve {
        let e = wide_prony.modulus(p.omega);
        worst_tan = worst_tan.max((e.im / e.re / p.tan_delta - 1.0).abs());
        worst_abs = worst_abs.max((e.norm() / p.magnitude - 1.0).abs());
        worst_band = worst_band.max(p.tan_delta_sigma / p.tan_delta);
    }
    eprintln!(
        "λ {:e} → {:e}; worst change tan δ {worst_tan:.2e}, |E| {worst_abs:.2e} \
         (1σ of tan δ up to {worst_band:.2e})",
        base.lambda.value, wide.lambda.value
    );
    assert!(worst_tan < 0.01 && worst_abs < 0.01);
}
