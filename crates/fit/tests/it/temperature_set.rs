//! Temperature sets (fixed seeds): one master curve at T_ref and the shift,
//! recovered from synthetic μ(v) at five temperatures.
//!
//! The truth: the bundled broad Havriliak–Negami rubber (not a Prony series)
//! as the master curve at 20 °C, shifted by WLF with C1 = 8.86,
//! C2 = 101.6 K; 41 speeds over 8 decades at −20, 0, 20, 40 and 60 °C (about
//! 16 decades of reduced speed); 1 % noise; one scale anchor, |E| at
//! 10 rad/s at T_ref.

use rollfit_testkit::materials::{hn_rubber, narrow_rubber};
use rollfit_testkit::rolling::{
    points_to_free_shifts, setup, sparse_temperature_set, temperature_set, window_errors, wlf_truth,
};

use rollfit_fit::{
    FitParams, FitReport, Measurements, ScaleAnchor, ShiftKind, ShiftRecord, ShiftSettings, fit,
};
use rollfit_model::ViscoelasticModulus;

const TEMPERATURES: [f64; 5] = [-20.0, 0.0, 20.0, 40.0, 60.0];

fn params(kind: ShiftKind, cross_check: bool) -> rollfit_fit::ValidFitParams {
    FitParams {
        anchor: Some(ScaleAnchor::ModulusAt {
            omega: 10.0,
            modulus: hn_rubber().modulus(10.0).norm(),
        }),
        shift: ShiftSettings {
            kind,
            t_ref: Some(20.0),
            cross_check,
            ..ShiftSettings::default()
        },
        ..FitParams::default()
    }
    .check(setup())
    .unwrap()
}

/// RMS relative errors of tan δ and |E| over the reported (combined) window
/// shrunk by half a decade at each end.
fn errors(report: &FitReport) -> (f64, f64) {
    let (t, e, n) = window_errors(report, &hn_rubber());
    assert!(n > 100, "window too small: {n} points");
    (t, e)
}

/// The WLF target: C1 and C2 within 5 %, tan δ and |E| within
/// 5 % RMS over the combined window, on three noise seeds. (Measured: C1,
/// C2 within 0.5 %, tan δ and |E| about 1 %.)
#[test]
fn wlf_set_is_recovered() {
    for seed in 1..4 {
        let report = fit(
            &temperature_set(hn_rubber(), &TEMPERATURES, 0.01, seed),
            &params(ShiftKind::Wlf, false),
        )
        .unwrap();
        let (t, e) = errors(&report);
        let Some(ShiftRecord::Wlf { c1, c2, t_ref, .. }) = report.shift.clone() else {
            panic!("no WLF shift: {:?}", report.shift)
        };
        eprintln!(
            "seed {seed}: C1 {c1:.4} C2 {c2:.3} tan δ {t:.4} |E| {e:.4} χ²/N {:.3} window {:.2e}…{:.2e} {} terms {:.2} s",
            report.misfit_per_point,
            report.window.omega_min,
            report.window.omega_max,
            report.model.tau.len(),
            report.wall_time_s
        );
        assert_eq!(t_ref, 20.0);
        assert!(report.converged, "{}", report.stop_reason);
        assert!((c1 / 8.86 - 1.0).abs() <= 0.05, "C1 {c1}");
        assert!((c2 / 101.6 - 1.0).abs() <= 0.05, "C2 {c2}");
        assert!(t <= 0.05 && e <= 0.05, "tan δ {t}, |E| {e}");
        // The window spans the combined, shifted range: about 16 decades of
        // reduced speed.
        assert!((report.window.omega_max / report.window.omega_min).log10() > 15.0);
    }
}

/// The free-shift target: every log10 a_T within 0.1 decade of
/// the truth, and the master curve within 5 %.
#[test]
fn free_shifts_are_recovered() {
    for seed in [1, 5] {
        let report = fit(
            &temperature_set(hn_rubber(), &TEMPERATURES, 0.01, seed),
            &params(ShiftKind::Free, false),
        )
        .unwrap();
        let Some(ShiftRecord::Free { log_shift, t_ref }) = report.shift.clone() else {
            panic!("no free shift: {:?}", report.shift)
        };
        assert_eq!(t_ref, 20.0);
        assert_eq!(log_shift.len(), 5);
        for s in &log_shift {
            let truth = wlf_truth(s.temperature);
            eprintln!(
                "seed {seed} T {}: log a_T {:.4} ± {:.4} (truth {truth:.4})",
                s.temperature, s.log_shift, s.log_shift_sigma
            );
            assert!((s.log_shift - truth).abs() <= 0.1, "{s:?} vs {truth}");
        }
        let (t, e) = errors(&report);
        assert!(t <= 0.05 && e <= 0.05, "tan δ {t}, |E| {e}");
    }
}

/// The cross-check: each temperature fitted alone and the tan δ curves
/// overlapped gives shifts close to the joint fit's (and to the truth).
#[test]
fn cross_check_agrees_with_the_joint_fit() {
    let report = fit(
        &temperature_set(hn_rubber(), &TEMPERATURES, 0.01, 2),
        &params(ShiftKind::Wlf, true),
    )
    .unwrap();
    let check = report
        .shift_cross_check
        .as_ref()
        .unwrap_or_else(|| panic!("no cross-check: {:?}", report.warnings));
    assert_eq!(check.temperatures.len(), 5);
    for row in &check.temperatures {
        eprintln!("{row:?}");
        assert!((row.log_shift_single - wlf_truth(row.temperature)).abs() <= 0.1);
        assert!((0.5..1.5).contains(&row.single_misfit_per_point));
    }
    assert!(check.max_difference <= 0.1, "{check:?}");
}

/// The temperature-set target on laboratory-shaped data: 5
/// temperatures × 12 speeds over 4 decades (10 µm/s to 10 cm/s), 2 % noise,
/// no sigma column; every log10 a_T within 0.15 decade of the truth and the
/// master tan δ within 8 % RMS over the window, for WLF and free shifts, the
/// broad and the narrow rubber.
///
/// Measured over 10 seeds (`SEEDS=10 cargo test --release -p rollfit-fit
/// --test it temperature_set::sparse_sets -- --nocapture`): every log10 a_T
/// within 0.051 decade in all 40 fits; tan δ ≤ 5.1 % for the broad rubber;
/// for the narrow one ≤ 8 % in 16 of 20, and 9.9–12.5 % in seeds 0 and 9
/// (WLF and free alike). There the glassy end of the window is probed by the
/// coldest temperature's upper speeds alone, and a noise draw that shifts
/// −20 °C by 0.035 decade (2σ) takes |E| there 20 % high, 2.5σ outside the
/// band. The test holds that line on three seeds: shifts within 0.15 decade
/// and the fit judged good always; tan δ ≤ 15 % always and ≤ 8 % in all but
/// two fits per five seeds.
#[test]
fn sparse_sets_are_recovered() {
    let seeds: u64 = std::env::var("SEEDS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    let mut failures = Vec::new();
    let mut over = Vec::new();
    for (name, truth) in [("broad", hn_rubber()), ("narrow", narrow_rubber())] {
        for kind in [ShiftKind::Wlf, ShiftKind::Free] {
            for seed in 0..seeds {
                let data =
                    sparse_temperature_set(truth.clone(), &TEMPERATURES, 1e-5, 4.0, 12, 0.02, seed);
                let params = FitParams {
                    anchor: Some(ScaleAnchor::ModulusAt {
                        omega: 10.0,
                        modulus: truth.modulus(10.0).norm(),
                    }),
                    shift: ShiftSettings {
                        kind,
                        t_ref: Some(20.0),
                        ..ShiftSettings::default()
                    },
                    ..FitParams::default()
                }
                .check(setup())
                .unwrap();
                let report = fit(&data, &params).unwrap();
                let (t, e, n) = window_errors(&report, &truth);
                let worst = report
                    .shift
                    .as_ref()
                    .unwrap()
                    .log_shifts()
                    .iter()
                    .map(|s| (s.log_shift - wlf_truth(s.temperature)).abs())
                    .fold(0.0, f64::max);
                eprintln!(
                    "{name} {kind:?} seed {seed}: worst log a_T {worst:.3}, tan δ {t:.4} |E| \
                     {e:.4} over {n} points, noise {:.4}, quality {}, {:.2} s",
                    report.noise, report.fit_quality.verdict, report.wall_time_s
                );
                if t > 0.08 {
                    over.push(format!("{name} {kind:?} seed {seed}: tan δ {t:.4}"));
                }
                if n < 20 || worst > 0.15 || t > 0.15 || report.fit_quality.is_poor() {
                    failures.push(format!(
                        "{name} {kind:?} seed {seed}: {n} points, log a_T off by {worst:.3}, \
                         tan δ {t:.4}, quality {}",
                        report.fit_quality.verdict
                    ));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
    assert!(over.len() <= 2 * seeds.div_ceil(5) as usize, "{over:#?}");
}

/// No false alarm on a correct shift. A lab-shaped set (15 speeds
/// over 4 decades at −26, −18, −10, 0, 10 and 20 °C, 3 % noise, no sigma
/// column) whose coldest temperature has μ ≈ 3e-4 written to 4 decimals
/// (a rounding step of a third of μ), fitted with WLF: the joint shift is
/// right (every log10 a_T within 0.1 decade of the truth), the cross-check
/// record names what limits the coldest temperature's single fit, and no
/// temperature is questioned: the single fits' shifts differ from the
/// joint ones by up to 1.1 decades, but within 3σ of their own. A rule
/// on the difference alone (a warning above 0.3 decade) warns on at least
/// one seed, which the test checks so that the data stay a trap. Measured (this test's output): joint within 0.061 decade,
/// differences within 0.90 of their combined σ, the single σ 0.14–4.0
/// decades (growing along the chain from T_ref to the coldest).
#[test]
fn a_coarsely_rounded_cold_temperature_raises_no_false_alarm() {
    let temperatures = [-26.0, -18.0, -10.0, 0.0, 10.0, 20.0];
    let mut old_alarms = 0;
    for seed in 0..4 {
        let set = sparse_temperature_set(hn_rubber(), &temperatures, 1e-5, 4.0, 15, 0.03, seed);
        let t = set.temperature().unwrap().to_vec();
        let rounded: Vec<f64> = set
            .friction()
            .iter()
            .zip(&t)
            .map(|(&mu, &t)| {
                if t == -26.0 {
                    (mu * 1e4).round() / 1e4
                } else {
                    mu
                }
            })
            .collect();
        let data = Measurements::new(set.speeds().to_vec(), rounded, None, Some(t)).unwrap();
        let report = fit(&data, &params(ShiftKind::Wlf, true)).unwrap();
        let check = report
            .shift_cross_check
            .as_ref()
            .unwrap_or_else(|| panic!("no cross-check: {:?}", report.warnings));
        for row in &check.temperatures {
            let truth = wlf_truth(row.temperature);
            eprintln!(
                "seed {seed} T {}: joint {:.3} (truth {truth:.3}), single {:.3} ± {:?}, \
                 difference {:+.3} ({:.2} σ), limits {:?}",
                row.temperature,
                row.log_shift_joint,
                row.log_shift_single,
                row.log_shift_single_sigma,
                row.difference,
                row.difference.abs() / row.difference_sigma.unwrap_or(f64::NAN),
                row.single_fit_limits
            );
            assert!((row.log_shift_joint - truth).abs() <= 0.1, "{row:?}");
            assert!(!row.beyond_sigma, "{row:?}");
        }
        let coldest = &check.temperatures[0];
        assert!(coldest.log_shift_single_sigma.is_some(), "{coldest:?}");
        let limits = coldest.single_fit_limits.join("; ");
        assert!(
            limits.contains("4 decimals") && limits.contains("low μ"),
            "{limits}"
        );
        let alarms: Vec<&String> = report
            .warnings
            .iter()
            .filter(|w| w.contains("cross-check"))
            .collect();
        assert!(alarms.is_empty(), "{alarms:?}");
        if check.max_difference > 0.3 {
            old_alarms += 1;
        }
    }
    assert!(
        old_alarms >= 1,
        "the data no longer raise a difference-only alarm"
    );
}

/// A joint shift that is truly off is still questioned: the WLF set of
/// [`wlf_set_is_recovered`] (41 speeds, 1 % noise, σ given) fitted under
/// the Arrhenius law, which cannot follow WLF over 80 K. Every temperature
/// whose joint log10 a_T is more than 0.3 decade off the truth is beyond
/// 3σ of its single fit's and named in a warning; the poor fit's reasons
/// point to free shifts. Measured (this test's output): the joint shifts
/// off by 0.5–1.2 decades at −20, 40 and 60 °C, each 34–68 times the
/// combined σ (0.015–0.047 decade).
#[test]
fn a_wrong_law_is_questioned_by_the_cross_check() {
    let data = temperature_set(hn_rubber(), &TEMPERATURES, 0.01, 1);
    let report = fit(&data, &params(ShiftKind::Arrhenius, true)).unwrap();
    let check = report.shift_cross_check.as_ref().expect("a cross-check");
    let mut questioned = 0;
    for row in &check.temperatures {
        let off = row.log_shift_joint - wlf_truth(row.temperature);
        eprintln!(
            "T {}: joint off by {off:+.3}, difference {:+.3} ± {:?}, beyond σ: {}",
            row.temperature, row.difference, row.difference_sigma, row.beyond_sigma
        );
        if off.abs() > 0.3 {
            assert!(row.beyond_sigma, "{row:?}");
            let named = format!("T = {} °C", row.temperature);
            assert!(
                report
                    .warnings
                    .iter()
                    .any(|w| w.contains(&named) && w.contains("questioned")),
                "{named}: {:?}",
                report.warnings
            );
            questioned += 1;
        }
    }
    assert!(questioned >= 2, "{check:?}");
    assert!(report.fit_quality.is_poor());
    assert!(
        points_to_free_shifts(&report),
        "{:?}",
        report.fit_quality.reasons
    );
}

/// One temperature alone is not a set: no shift is fitted or reported.
#[test]
fn one_temperature_is_not_a_set() {
    let data = temperature_set(hn_rubber(), &[20.0], 0.01, 1);
    let report = fit(&data, &params(ShiftKind::Wlf, true)).unwrap();
    assert!(report.shift.is_none() && report.shift_cross_check.is_none());
}
