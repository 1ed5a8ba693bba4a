//! Bands that cover: on laboratory-shaped sets (12–20
//! speeds a temperature, 3 % noise, no sigma column, so that the noise is
//! estimated from the residuals), the 2σ band of tan δ holds the truth over
//! the determined window at ≥ 90 % of its points on average, and the noise
//! estimate's median lies within ±10 % of the noise drawn.
//!
//! The cases: the broad real-curve replica of `broad_polymer::` (a
//! stiff polymer's spectrum over 16 decades, kinked non-WLF shifts, five
//! temperatures), the bundled Havriliak–Negami rubber as a WLF temperature
//! set, and the broad and narrow rubbers of `tests/sparse.rs` at one
//! temperature; each with one scale anchor.

use rollfit_testkit::broad_polymer;
use rollfit_testkit::materials::{hn_rubber, narrow_rubber};
use rollfit_testkit::rolling::{setup, sparse, sparse_temperature_set};

use rollfit_fit::{
    FitParams, FitReport, Measurements, ScaleAnchor, ShiftKind, ShiftSettings, ValidFitParams, fit,
};
use rollfit_model::{Prony, ViscoelasticModulus};

/// The relative noise of every case.
const NOISE: f64 = 0.03;

/// The five temperatures of the rubber's set, °C.
const TEMPERATURES: [f64; 5] = [-10.0, 0.0, 10.0, 20.0, 30.0];

/// A truth of a case.
enum Truth {
    Polymer(Prony),
    Rubber(rollfit_model::HavriliakNegami),
}

impl Truth {
    fn modulus(&self) -> &dyn ViscoelasticModulus {
        match self {
            Truth::Polymer(m) => m,
            Truth::Rubber(m) => m,
        }
    }
}

/// One coverage case: its name, truth, data of `count` speeds a temperature
/// for a seed, and fit settings.
struct Case {
    name: &'static str,
    truth: Truth,
    data: fn(usize, u64) -> Measurements,
    params: fn() -> ValidFitParams,
}

/// The settings of an anchored single-temperature rubber fit: |E| of
/// `truth` at the contact frequency of the middle speed.
fn rubber_params(truth: &rollfit_model::HavriliakNegami, v_mid: f64) -> ValidFitParams {
    let s = setup();
    let omega = v_mid / rollfit_fit::tau_grid::contact_size(&s, truth.rubbery_modulus());
    FitParams {
        anchor: Some(ScaleAnchor::ModulusAt {
            omega,
            modulus: truth.modulus(omega).norm(),
        }),
        ..FitParams::default()
    }
    .check(s)
    .unwrap()
}

fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "broad polymer",
            truth: Truth::Polymer(broad_polymer::truth()),
            data: |count, seed| broad_polymer::lab_set(count, NOISE, seed),
            params: || broad_polymer::params(ShiftKind::Auto, true),
        },
        Case {
            name: "broad polymer free",
            truth: Truth::Polymer(broad_polymer::truth()),
            data: |count, seed| broad_polymer::lab_set(count, NOISE, seed),
            params: || broad_polymer::params(ShiftKind::Free, true),
        },
        Case {
            name: "broad polymer unanchored",
            truth: Truth::Polymer(broad_polymer::truth()),
            data: |count, seed| broad_polymer::lab_set(count, NOISE, seed),
            params: || broad_polymer::params(ShiftKind::Auto, false),
        },
        Case {
            name: "rubber set",
            truth: Truth::Rubber(hn_rubber()),
            data: |count, seed| {
                sparse_temperature_set(hn_rubber(), &TEMPERATURES, 1e-5, 4.0, count, NOISE, seed)
            },
            params: || {
                FitParams {
                    anchor: Some(ScaleAnchor::ModulusAt {
                        omega: 10.0,
                        modulus: hn_rubber().modulus(10.0).norm(),
                    }),
                    shift: ShiftSettings {
                        t_ref: Some(20.0),
                        cross_check: false,
                        ..ShiftSettings::default()
                    },
                    ..FitParams::default()
                }
                .check(setup())
                .unwrap()
            },
        },
        Case {
            name: "broad rubber",
            truth: Truth::Rubber(hn_rubber()),
            data: |count, seed| sparse(setup(), hn_rubber(), 1e-6, 5.0, count, NOISE, seed),
            params: || rubber_params(&hn_rubber(), 1e-6 * 10f64.powf(2.5)),
        },
        Case {
            name: "narrow rubber",
            truth: Truth::Rubber(narrow_rubber()),
            data: |count, seed| sparse(setup(), narrow_rubber(), 1e-5, 5.0, count, NOISE, seed),
            params: || rubber_params(&narrow_rubber(), 1e-5 * 10f64.powf(2.5)),
        },
    ]
}

/// What one fit's bands did: the fraction of the determined window's
/// points whose 2σ tan δ and |E| bands hold the truth, the RMS of the
/// errors in units of the reported σ (1 for an honest band), the noise
/// estimate, the effective parameters and the window's points.
#[derive(Debug, Clone, Copy)]
struct Bands {
    tan_delta: f64,
    magnitude: f64,
    z_rms: f64,
    noise: f64,
    effective: f64,
    points: usize,
}

fn bands(report: &FitReport, truth: &dyn ViscoelasticModulus) -> Bands {
    let (mut t, mut e, mut z2) = (0usize, 0usize, 0.0);
    let n = report.curve.len();
    for p in &report.curve {
        let x = truth.modulus(p.omega);
        let z = (p.tan_delta - x.im / x.re) / p.tan_delta_sigma;
        z2 += z * z;
        t += usize::from(z.abs() <= 2.0);
        e += usize::from((p.magnitude - x.norm()).abs() <= 2.0 * p.magnitude_sigma);
    }
    let nf = n.max(1) as f64;
    Bands {
        tan_delta: t as f64 / nf,
        magnitude: e as f64 / nf,
        z_rms: (z2 / nf).sqrt(),
        noise: report.noise,
        effective: report.effective_parameters,
        points: n,
    }
}

/// The fits of `case` at `seeds` with `count` speeds a temperature, each
/// printed.
fn run(case: &Case, count: usize, seeds: std::ops::Range<u64>) -> Vec<Bands> {
    let params = (case.params)();
    seeds
        .filter_map(|seed| {
            let report = match fit(&(case.data)(count, seed), &params) {
                Ok(r) => r,
                Err(e) => {
                    eprintln!("{} seed {seed}: error {e}", case.name);
                    return None;
                }
            };
            let b = bands(&report, case.truth.modulus());
            eprintln!(
                "{} seed {seed}: 2σ covers tan δ {:.2} |E| {:.2}, z RMS {:.2}, noise {:.4}, \
                 t {:.1}, {} points, λ {:.2e}, {} evaluations, {:.2} s",
                case.name,
                b.tan_delta,
                b.magnitude,
                b.z_rms,
                b.noise,
                b.effective,
                b.points,
                report.lambda.value,
                report.evaluations,
                report.wall_time_s
            );
            Some(b)
        })
        .collect()
}

/// The mean tan δ coverage, the worst three seeds and the median noise.
fn summarise(name: &str, rows: &[Bands]) -> (f64, f64) {
    let mean = rows.iter().map(|b| b.tan_delta).sum::<f64>() / rows.len() as f64;
    let mean_e = rows.iter().map(|b| b.magnitude).sum::<f64>() / rows.len() as f64;
    let mut noise: Vec<f64> = rows.iter().map(|b| b.noise).collect();
    noise.sort_by(f64::total_cmp);
    let median = if noise.len() % 2 == 1 {
        noise[noise.len() / 2]
    } else {
        0.5 * (noise[noise.len() / 2 - 1] + noise[noise.len() / 2])
    };
    let mut order: Vec<usize> = (0..rows.len()).collect();
    order.sort_by(|&a, &b| rows[a].tan_delta.total_cmp(&rows[b].tan_delta));
    let worst: Vec<String> = order
        .iter()
        .take(3)
        .map(|&k| format!("seed {k}: {:.2}", rows[k].tan_delta))
        .collect();
    eprintln!(
        "{name} ({} fits): 2σ tan δ coverage mean {mean:.3} (worst {}), |E| {mean_e:.3}; noise \
         median {median:.4} ({:+.1} % of the truth)",
        rows.len(),
        worst.join(", "),
        100.0 * (median / NOISE - 1.0)
    );
    (mean, median)
}

/// The study over 40 seeds (CASE, SEEDS, COUNT in the environment):
/// `SEEDS=40 cargo test --release -p rollfit-fit --test it coverage::study_coverage -- --ignored --nocapture`
#[test]
#[ignore = "study: run by hand"]
fn study_coverage() {
    let knob = |name: &str, default: usize| {
        std::env::var(name)
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(default)
    };
    let (seeds, count) = (knob("SEEDS", 40) as u64, knob("COUNT", 15));
    let only = std::env::var("CASE").ok();
    for case in cases() {
        if only.as_deref().is_some_and(|o| !case.name.contains(o)) {
            continue;
        }
        let rows = run(&case, count, 0..seeds);
        summarise(case.name, &rows);
    }
}

/// The study's fast version: seeds 0–2 of the anchored cases at 15 speeds,
/// each case's mean 2σ tan δ coverage at least 0.9 and the median noise
/// estimate of the twelve fits within ±10 % of the noise drawn. Measured
/// (this test's output): coverage 0.93 (polymer, seed 0 at 0.79), 0.98
/// (rubber set), 1.00 and 0.99 (single rubbers).
#[test]
fn bands_cover_on_lab_shaped_sets() {
    let mut noise = Vec::new();
    for case in cases() {
        if case.name.contains("unanchored") || case.name.contains("free") {
            continue;
        }
        let rows = run(&case, 15, 0..3);
        assert_eq!(rows.len(), 3, "{}: a fit failed", case.name);
        let (coverage, _) = summarise(case.name, &rows);
        assert!(coverage >= 0.9, "{}: mean coverage {coverage}", case.name);
        noise.extend(rows.iter().map(|b| b.noise));
    }
    noise.sort_by(f64::total_cmp);
    let median = 0.5 * (noise[5] + noise[6]);
    eprintln!(
        "median noise estimate of the {} fits: {median:.4}",
        noise.len()
    );
    assert!(
        (median / NOISE - 1.0).abs() <= 0.1,
        "median noise estimate {median}"
    );
}
