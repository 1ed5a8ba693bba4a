//! The joint fit where the DMA part alone cannot shift its isotherms: the
//! broad stiff polymer of `broad_polymer::` (a glassy polymer's
//! master curve over 16 decades with kinked, non-WLF shifts) as a lab
//! rolling set (5 temperatures −20 … 60 °C × 12 speeds over 4 decades, no σ
//! column, no anchor, 2.5 % noise) plus 4 DMA isotherms 20 K apart
//! (−20 … 40 °C), 10 frequencies each from 0.1 Hz over 2 decades or over
//! one, 1 % noise. Neighbouring isotherms lie 1.1 to 2 decades apart on
//! the reduced-frequency axis: over 2 decades only the coldest pair
//! overlaps enough to determine its shift, over one decade none does and
//! the DMA alone makes no master curve. The rolling data cover every DMA
//! temperature and determine the rest.

use rollfit_testkit::rolling::window_errors;
use rollfit_testkit::{broad_polymer, joint_case};

use broad_polymer::{lab_set, log_shift, params as rolling_params, truth, worst_shift_error};
use joint_case::isotherms_with_shifts;
use rollfit_fit::master::Isotherm;
use rollfit_fit::{DmaRows, FitReport, ShiftKind, ValidFitParams};
use rollfit_model::ViscoelasticModulus;

/// The DMA temperatures, °C.
const DMA_TEMPERATURES: [f64; 4] = [-20.0, 0.0, 20.0, 40.0];

/// Four isotherms × 10 frequencies from 0.1 Hz over `decades`, 1 % noise.
fn isotherms(decades: f64, seed: u64) -> Vec<Isotherm> {
    let omega: Vec<f64> = (0..10)
        .map(|i| 2.0 * std::f64::consts::PI * 0.1 * 10f64.powf(decades * i as f64 / 9.0))
        .collect();
    isotherms_with_shifts(&truth(), &DMA_TEMPERATURES, &omega, log_shift, 0.01, seed)
}

/// The joint settings: shift `kind` about 20 °C, no anchor, the
/// isotherms over `decades`.
fn params(kind: ShiftKind, decades: f64, seed: u64) -> ValidFitParams {
    let dma = DmaRows::new(isotherms(decades, seed), "broad-dma.csv").unwrap();
    rolling_params(kind, false).with_dma(dma).unwrap()
}

fn joint(kind: ShiftKind, decades: f64, seed: u64) -> FitReport {
    rollfit_fit::fit(
        &lab_set(12, 0.025, seed + 100),
        &params(kind, decades, seed),
    )
    .unwrap()
}

/// Every DMA and rolling temperature, °C.
fn all_temperatures() -> Vec<f64> {
    vec![-20.0, 0.0, 20.0, 40.0, 60.0]
}

/// The targets: the fit is made (the DMA part alone refuses nothing), log
/// a_T within 0.1 decade at every temperature of either part, tan δ and
/// |E| within 5 % RMS over the window the fit determines; the DMA part
/// alone is reported with the shifts it does not determine.
#[test]
fn rolling_data_shift_the_isotherms_the_dma_alone_cannot() {
    let cases = [
        (ShiftKind::Free, 1.0),
        (ShiftKind::Auto, 1.0),
        (ShiftKind::Free, 2.0),
        (ShiftKind::Auto, 2.0),
    ];
    for (kind, decades) in cases {
        let report = joint(kind, decades, 1);
        let shift = worst_shift_error(&report, &all_temperatures());
        let (tan_delta, modulus, n) = window_errors(&report, &truth());
        let record = report.joint.as_ref().expect("a joint record");
        eprintln!(
            "{kind:?}, {decades} decade(s): log a_T within {shift:.3} decade, tan δ {:.2} %, |E| {:.2} % ({n} points, \
             window {:.2e} … {:.2e} rad/s), {} evaluations, verdict {} {:?}; DMA alone: {}",
            100.0 * tan_delta,
            100.0 * modulus,
            report.window.omega_min,
            report.window.omega_max,
            report.evaluations,
            report.fit_quality.verdict,
            report.fit_quality.reasons,
            record.dma_alone.verdict
        );
        eprintln!(
            "  σ DMA {:.4} ({}), rolling {:?}; χ² {:?}",
            record.sigma.dma, record.sigma.dma_source, record.sigma.rolling, record.chi2
        );
        if let Some(s) = &report.shift {
            eprintln!("  shifts {:?}", s.log_shifts());
        }
        for r in &report.runs {
            eprintln!(
                "  run {:<60} λ {:.2e} ev {:>4} V {:.4e}",
                r.stage, r.lambda, r.evaluations, r.objective
            );
        }
        assert!(shift <= 0.1, "{kind:?}: log a_T off by {shift}");
        assert!(n > 0, "{kind:?}: no curve inside the window");
        assert!(tan_delta <= 0.05, "{kind:?}: tan δ {tan_delta}");
        assert!(modulus <= 0.05, "{kind:?}: |E| {modulus}");
        // `auto` chooses on both parts' shifts together: the kink at 0 °C
        // rejects every law.
        if kind == ShiftKind::Auto {
            let model = report.shift.as_ref().map(|s| s.model_name());
            assert_eq!(model, Some("free"), "{:?}", report.warnings);
            assert!(
                report
                    .warnings
                    .iter()
                    .any(|w| w.contains("chosen on both parts' shifts together")),
                "{:?}",
                report.warnings
            );
        }
        // The DMA part's σ, estimated from the part alone, is the noise
        // drawn (1 %), not the misfit of isotherms placed by a law.
        let sigma = record.sigma.dma;
        assert!((0.007..=0.014).contains(&sigma), "{kind:?}: DMA σ {sigma}");
        // What the DMA part alone determines: over one decade nothing,
        // over two the coldest pair only.
        let alone = &record.dma_alone;
        assert_eq!(alone.shifts.len(), DMA_TEMPERATURES.len());
        let determined: Vec<f64> = alone
            .shifts
            .iter()
            .filter(|s| s.determined)
            .map(|s| s.temperature)
            .collect();
        if decades == 1.0 {
            assert!(determined.is_empty(), "{alone:?}");
            assert!(alone.verdict.contains("any shift"), "{}", alone.verdict);
        } else {
            assert_eq!(determined, [-20.0, 0.0], "{alone:?}");
            assert!(alone.verdict.contains("20, 40 °C"), "{}", alone.verdict);
        }
    }
}

/// A DMA temperature that neither part determines (far above the rolling
/// temperatures, without overlap with the other isotherms) is refused,
/// naming the DMA file and the temperature.
#[test]
fn a_temperature_neither_part_determines_is_named() {
    let mut far = isotherms(1.0, 2);
    // The isotherm as the truth gives it at 160 °C: far beyond the rolling
    // temperatures (−20 … 60 °C), and with no overlap with the others.
    let a = 10f64.powf(log_shift(160.0));
    let omega = far[0].omega.clone();
    let moduli: Vec<_> = omega.iter().map(|w| truth().modulus(w * a)).collect();
    let hot = Isotherm {
        temperature: 160.0,
        storage: moduli.iter().map(|e| e.re).collect(),
        loss: moduli.iter().map(|e| e.im).collect(),
        omega,
    };
    far.push(hot);
    let dma = DmaRows::new(far, "far-dma.csv").unwrap();
    let p = rolling_params(ShiftKind::Free, false)
        .with_dma(dma)
        .unwrap();
    let error = rollfit_fit::fit(&lab_set(12, 0.025, 102), &p).unwrap_err();
    let text = error.to_string();
    assert!(text.contains("far-dma.csv"), "{text}");
    assert!(text.contains("160"), "{text}");
}
