//! A diagnosis of free shifts' cost (an ignored study, not a check): the singular
//! values of the column-scaled Jacobian J D⁻¹ (D: column norms, as
//! MINPACK's Levenberg–Marquardt scales) of a 7 × 21 temperature set's
//! objective with free shifts, at the WLF fit's λ and optimum (where the
//! free fit starts) and at the free fit's optimum; and the same without the
//! shift columns, which says whether the ill-conditioning is the
//! spectrum's own or the shifts' trade-off with it.
//!
//! `cargo test --release -p rollfit-fit conditioning -- --ignored --nocapture`

use nalgebra::DMatrix;
use rollfit_model::{HavriliakNegami, Scene, ViscoelasticModulus};

use crate::data::Measurements;
use crate::objective::Objective;
use crate::parametrization::Parametrization;
use crate::params::{FitParams, ScaleAnchor, ShiftKind, ShiftSettings, ValidFitParams};
use crate::report::FitReport;
use crate::shift::ShiftParam;

fn truth() -> HavriliakNegami {
    HavriliakNegami::new(2e6, 2e9, 1e-3, 0.55, 0.4).unwrap()
}

/// log10 a_T: WLF (C1 = 8.86, C2 = 101.6 K at 20 °C) plus `wiggle`
/// decades of a sine.
fn log_shift(t: f64, wiggle: f64) -> f64 {
    -8.86 * (t - 20.0) / (101.6 + t - 20.0) + wiggle * (t / 10.0).sin()
}

/// Noise-free μ at 21 speeds (1e-8 … 1 m/s) at −25 … 65 °C, σ = 1 %.
fn set(wiggle: f64) -> Measurements {
    let setup = crate::params::example_setup();
    let scene = Scene::new(setup.geometry, setup.substrate, setup.contact, truth()).unwrap();
    let speeds: Vec<f64> = (0..21).map(|i| 1e-8 * 10f64.powf(0.4 * i as f64)).collect();
    let (mut v, mut mu, mut temps) = (vec![], vec![], vec![]);
    for j in 0..7 {
        let t = -25.0 + 15.0 * j as f64;
        let a = 10f64.powf(log_shift(t, wiggle));
        let reduced: Vec<f64> = speeds.iter().map(|x| x * a).collect();
        v.extend(&speeds);
        mu.extend(scene.friction_sweep(&reduced).unwrap());
        temps.extend([t; 21]);
    }
    let sigma = mu.iter().map(|m| 0.01 * m).collect();
    Measurements::new(v, mu, Some(sigma), Some(temps)).unwrap()
}

fn params(kind: ShiftKind) -> ValidFitParams {
    FitParams {
        anchor: Some(ScaleAnchor::ModulusAt {
            omega: 10.0,
            modulus: truth().modulus(10.0).norm(),
        }),
        shift: ShiftSettings {
            kind,
            t_ref: Some(20.0),
            cross_check: false,
            ..ShiftSettings::default()
        },
        ..FitParams::default()
    }
    .check(crate::params::example_setup())
    .unwrap()
}

/// Singular values of J D⁻¹ over `columns`, descending.
fn scaled_singular_values(jac: &DMatrix<f64>, columns: usize) -> Vec<f64> {
    let mut j = jac.columns(0, columns).into_owned();
    for mut c in j.column_iter_mut() {
        let n = c.norm();
        if n > 0.0 {
            c /= n;
        }
    }
    let mut s: Vec<f64> = j.singular_values().iter().copied().collect();
    s.sort_by(|a, b| b.total_cmp(a));
    s
}

/// The objective with free shifts at λ, and θ at the material and shifts
/// of `report`.
fn free_objective<'a>(
    data: &'a Measurements,
    free: &'a ValidFitParams,
    report: &FitReport,
    lambda: f64,
) -> (Objective<'a>, Vec<f64>) {
    let shift = ShiftParam::new(data, &free.shift).unwrap();
    let param = Parametrization::new(report.model.tau.clone(), free.anchor);
    let mut theta = param.theta_of(report.model.static_modulus, &report.model.strengths);
    let shifts = report.shift.as_ref().unwrap();
    let logs: Vec<f64> = shift
        .temperatures()
        .iter()
        .map(|&t| shifts.log_shift_at(t).unwrap())
        .collect();
    theta.extend(shift.theta_of_log_shifts(&logs));
    let objective = Objective {
        setup: &free.setup,
        data,
        scales: data.residual_scales(),
        param,
        shift: Some(shift),
        lambda,
        e1_max: free.e1_max,
        tolerance: 1e-8,
        vertical: None,
        dma: None,
        friction_factor: false,
        noise_known: data.sigma().is_some(),
    };
    (objective, theta)
}

/// Prints the conditioning of the free-shift objective at λ and the
/// material and shifts of `report`.
fn print_conditioning(label: &str, data: &Measurements, report: &FitReport, lambda: f64) {
    let free = params(ShiftKind::Free);
    let (objective, theta) = free_objective(data, &free, report, lambda);
    let n_material = objective.param.free_count();
    let e = objective.evaluate(&theta, true).unwrap();
    let jac = e.jacobian.clone().unwrap();
    let all = scaled_singular_values(&jac, jac.ncols());
    let material = scaled_singular_values(&jac, n_material);
    let tail = |s: &[f64]| -> String {
        s.iter()
            .rev()
            .take(4)
            .map(|x| format!("{x:.2e}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    eprintln!(
        "{label}: λ {lambda:.3e}, V {:.4e}, {} material + {} shift columns; cond(J D⁻¹) {:.2e} \
         (smallest: {}), material columns alone {:.2e} (smallest: {})",
        e.objective(),
        n_material,
        jac.ncols() - n_material,
        all[0] / all[all.len() - 1],
        tail(&all),
        material[0] / material[material.len() - 1],
        tail(&material),
    );
}

/// The conditioning where the free fit starts and where it ends, on shifts
/// WLF describes (wiggle 0) and on shifts it does not (0.3 decade).
#[test]
#[ignore]
fn conditioning_of_free_shifts() {
    for wiggle in [0.0, 0.3] {
        let data = set(wiggle);
        let wlf = crate::driver::fit(&data, &params(ShiftKind::Wlf)).unwrap();
        let free = crate::driver::fit(&data, &params(ShiftKind::Free)).unwrap();
        let label = format!("wiggle {wiggle}");
        print_conditioning(
            &format!("{label} start (WLF optimum)"),
            &data,
            &wlf,
            wlf.lambda.value,
        );
        print_conditioning(
            &format!("{label} free optimum"),
            &data,
            &free,
            free.lambda.value,
        );
        print_conditioning(
            &format!("{label} free optimum at the WLF fit's λ"),
            &data,
            &free,
            wlf.lambda.value,
        );
        for r in free.runs.iter().filter(|r| r.evaluations > 100) {
            eprintln!(
                "{label}: {} at λ {:.2e}: {} evaluations",
                r.stage, r.lambda, r.evaluations
            );
        }
    }
}
