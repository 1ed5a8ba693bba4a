//! Free shifts on a broad real spectrum: the replica of
//! `broad_polymer::` (a stiff polymer's master curve over 16 decades
//! with kinked, non-WLF shifts), 7 temperatures × 21 speeds with σ and an
//! anchor. The fit must recover log a_T within 0.05 decade and tan δ within
//! 3 % RMS in ≤ 600 evaluations, with `shift = "free"` and `"auto"`.
//! Evaluation counts are deterministic (fixed seeds); times are not.

use rollfit_testkit::broad_polymer;
use rollfit_testkit::rolling::window_errors;

use broad_polymer::{params, set_7x21, temperatures, truth, worst_shift_error};
use rollfit_fit::{FitReport, ShiftKind, fit};

fn total_evaluations(report: &FitReport) -> usize {
    report.runs.iter().map(|r| r.evaluations).sum()
}

fn summary(label: &str, report: &FitReport) -> (usize, f64, f64) {
    let (tan_delta, modulus, _) = window_errors(report, &truth());
    let shift = worst_shift_error(report, &temperatures());
    let n = total_evaluations(report);
    eprintln!(
        "{label}: {} runs, {n} evaluations, λ {:.3e}, χ²/N {:.3}, E1 {:.3e}, log a_T within \
         {shift:.3}, tan δ {:.2} %, |E| {:.2} %, window {:.2e} … {:.2e} rad/s, {:.2} s",
        report.runs.len(),
        report.lambda.value,
        report.misfit_per_point,
        report.model.glassy_modulus,
        100.0 * tan_delta,
        100.0 * modulus,
        report.window.omega_min,
        report.window.omega_max,
        report.wall_time_s,
    );
    (n, shift, tan_delta)
}

/// Every run of the replica's fits, free and auto (`SEED=n`, default 1).
/// `cargo test --release -p rollfit-fit --test it broad_spectrum::probe -- --ignored --nocapture`
#[test]
#[ignore = "probe: run by hand"]
fn probe() {
    let seed = std::env::var("SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let data = set_7x21(seed);
    for kind in [ShiftKind::Free, ShiftKind::Auto] {
        let report = fit(&data, &params(kind, true)).unwrap();
        for r in &report.runs {
            eprintln!(
                "{kind:?}: {:<50} λ {:.3e} it {:>5} ev {:>5} V {:.6e} {}",
                r.stage, r.lambda, r.iterations, r.evaluations, r.objective, r.stop_reason
            );
        }
        for w in &report.warnings {
            eprintln!("  warning: {w}");
        }
        summary(&format!("{kind:?}"), &report);
    }
}

/// The targets on the replica (seed 1), with the counts they
/// hold: free 394 evaluations (747 before the free shifts got a λ of their
/// own when WLF does not describe the data), auto 452 (933 before).
#[test]
fn free_shifts_on_a_broad_spectrum_are_fast_and_right() {
    let data = set_7x21(1);
    for kind in [ShiftKind::Free, ShiftKind::Auto] {
        let report = fit(&data, &params(kind, true)).unwrap();
        let (n, shift, tan_delta) = summary(&format!("{kind:?}"), &report);
        assert!(n <= 600, "{kind:?}: {n} evaluations");
        assert!(shift <= 0.05, "{kind:?}: log a_T off by {shift}");
        assert!(tan_delta <= 0.03, "{kind:?}: tan δ {tan_delta}");
        let chi2 = report.misfit_per_point;
        assert!((0.7..=1.3).contains(&chi2), "{kind:?}: χ²/N {chi2}");
    }
}
