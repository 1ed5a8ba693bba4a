//! DMA data shifted to the fit's reference state, the causality
//! (Kramers–Kronig) check and the comparison with a fit's master curve.
//! Reading the DMA files themselves is tested in crates/io/tests/it/dma.rs.
//!
//! Every expected value is computed here independently: the Prony and WLF
//! formulas written out in the test, analytic values of the metrics.

use std::fs;
use std::path::{Path, PathBuf};

use rollfit_io::FitDir;
use rollfit_io::dma::{DmaData, DmaOptions, DmaPoint, DmaWlf, ModulusKind};
use rollfit_report::causality::{self, KK_MAX_MISFIT_THRESHOLD, KK_MISFIT_THRESHOLD};
use rollfit_report::compare::compare;
use rollfit_report::dma_shift::ToReference;
use rollfit_testkit::files::TempDir;
use rollfit_testkit::series::{Series, wlf};

// ---------------------------------------------------------------- helpers

/// Writes a minimal fit directory (the contract's keys, one mu.csv row,
/// a modulus.csv over the window) for `series`, with `shift` (a JSON value
/// or "") and `poisson`.
fn fit_dir(dir: &Path, series: &Series, window: (f64, f64), shift: &str, poisson: f64) -> FitDir {
    fs::create_dir_all(dir).unwrap();
    let list = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:e}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let shift = if shift.is_empty() {
        String::new()
    } else {
        format!(", \"shift\": {shift}")
    };
    let json = format!(
        r#"{{"model": {{"kind": "prony", "E1": {:e}, "tau": [{}], "H": [{}]}},
 "poisson": {poisson}, "window": {{"omega_min": {:e}, "omega_max": {:e}}},
 "method": "test", "objective": 0.0, "iterations": 0, "converged": true, "wall_time_s": 0.0{shift}}}"#,
        series.e1,
        list(&series.tau),
        list(&series.h),
        window.0,
        window.1
    );
    fs::write(dir.join("fit.json"), json).unwrap();
    fs::write(dir.join("mu.csv"), "v,mu_measured,mu_fit\n1e-3,0.1,0.1\n").unwrap();
    let mut modulus = String::from("omega,E_storage,E_loss,tan_delta\n");
    for j in 0..=10 {
        let omega = window.0 * (window.1 / window.0).powf(j as f64 / 10.0);
        let (s, l) = series.at(omega);
        modulus.push_str(&format!("{omega:e},{s:e},{l:e},{:e}\n", l / s));
    }
    fs::write(dir.join("modulus.csv"), modulus).unwrap();
    FitDir::read(dir).unwrap()
}

/// A WLF shift block of fit.json.
fn wlf_shift_json(t_ref: f64, c1: f64, c2: f64, temperatures: &[f64]) -> String {
    let list: Vec<String> = temperatures
        .iter()
        .map(|&t| format!(r#"{{"T": {t}, "log_aT": {}}}"#, wlf(t, t_ref, c1, c2)))
        .collect();
    format!(
        r#"{{"model": "wlf", "T_ref": {t_ref}, "C1": {c1}, "C2": {c2}, "log_aT": [{}]}}"#,
        list.join(", ")
    )
}

fn relative(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

fn assert_contains(text: &str, fragments: &[&str]) {
    for f in fragments {
        assert!(text.contains(f), "{f:?} not in:\n{text}");
    }
}

// ---------------------------------------------------------------- real data

/// The 3M 468MP data in ../shared (not in the repository): both forms give
/// the same points; figures printed for the causality module's doc.
#[test]
fn real_468mp_files_when_present() {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/dma");
    let csv = folder.join("468mp_shear_isotherms.csv");
    let lims = folder.join("468mp_trios_lims_export.txt");
    if !csv.exists() || !lims.exists() {
        println!(
            "note: {} absent; the real-data check is skipped",
            folder.display()
        );
        return;
    }
    let options = DmaOptions::default();
    let from_csv = DmaData::read(&csv, 0.5, &options).unwrap();
    let from_lims = DmaData::read(&lims, 0.5, &options).unwrap();
    assert_eq!(from_csv.kind, ModulusKind::Shear);
    assert_eq!(from_lims.kind, ModulusKind::Shear);
    assert_eq!(from_csv.format, "csv");
    assert_eq!(from_lims.format, "trios-lims");
    // 20 isotherms × 17 frequencies, less the one negative E″ (−40 °C,
    // 125.7 rad/s), dropped with a warning in both.
    assert_eq!(from_csv.points.len(), 339);
    assert_eq!(from_lims.points.len(), 339);
    for data in [&from_csv, &from_lims] {
        assert!(
            data.warnings.iter().any(|w| w.contains("point dropped")),
            "{:?}",
            data.warnings
        );
    }
    // The CSV has six significant digits, the export (MPa) all of them.
    for (a, b) in from_csv.points.iter().zip(&from_lims.points) {
        assert!(relative(a.omega, b.omega) < 1e-5, "{a:?} {b:?}");
        assert!(relative(a.storage, b.storage) < 1e-5, "{a:?} {b:?}");
        assert!(relative(a.loss, b.loss) < 1e-5, "{a:?} {b:?}");
        assert!((a.temperature.unwrap() - b.temperature.unwrap()).abs() < 1e-3);
    }
    let temperatures = from_csv.temperatures();
    assert_eq!(temperatures.len(), 20);
    assert!((temperatures[0] + 40.0).abs() < 0.1 && (temperatures[19] - 150.0).abs() < 0.1);

    // Shifted to 20 °C with WLF constants estimated from the isotherms
    // (pairwise overlap of log G′, log G″, then a WLF fit: C1 = 9.06,
    // C2 = 129.3 K, 0.07 decades RMS), on a fit without a shift of its own.
    let dir = TempDir::new("real");
    let fit = fit_dir(
        &dir.path().join("fit"),
        &Series::broad_rubber(),
        (1e-2, 1e6),
        "",
        0.5,
    );
    let options = DmaOptions {
        kind: None,
        wlf: Some(DmaWlf {
            t_ref: 20.0,
            c1: 9.06,
            c2: 129.3,
        }),
        ..Default::default()
    };
    for data in [&from_csv, &from_lims] {
        let points = data.at_reference(&fit, &options).unwrap();
        let check = causality::check(&points).unwrap();
        println!(
            "468MP {}: {} points, {} isotherms {:.1}..{:.1} °C, reduced ω {:.3e}..{:.3e} rad/s, KK misfit E′ {:.4}, E″ {:.4} decades",
            data.format,
            points.len(),
            temperatures.len(),
            temperatures[0],
            temperatures[19],
            points[0].omega,
            points[points.len() - 1].omega,
            check.misfit_storage,
            check.misfit_loss
        );
        println!(
            "   largest: E′ {:.4} decades at {:?}; E″ {:.4} decades at {:?}",
            check.max_misfit_storage.0,
            check.max_misfit_storage.1,
            check.max_misfit_loss.0,
            check.max_misfit_loss.1
        );
        // Causal to a few tenths of a per cent over most of the curve; the
        // glassy end (the −30 and −40 °C isotherms, where they overlap) is
        // not, and the check says where.
        assert!(check.misfit_storage < KK_MISFIT_THRESHOLD);
        assert!(check.max_misfit_loss.0 > KK_MAX_MISFIT_THRESHOLD);
        let worst = check.max_misfit_loss.1.temperature.unwrap();
        assert!(worst < -29.0, "worst E″ at {worst} °C");
        assert!(
            check.warnings.iter().any(|w| w.contains("not causal near")),
            "{:?}",
            check.warnings
        );
    }
}

// ---------------------------------------------------------------- shifting

const C1: f64 = 8.86;
const C2: f64 = 101.6;

/// A DMA file of the broad rubber measured at `temperatures` (°C), the
/// master curve at 20 °C shifted by WLF (C1, C2): E*(ω, T) = E*_ref(ω a_T).
fn multi_temperature_csv(dir: &TempDir, name: &str, temperatures: &[f64]) -> PathBuf {
    let series = Series::broad_rubber();
    let mut text = String::from("T,omega,E_storage,E_loss\n");
    for &t in temperatures {
        let a_t = 10f64.powf(wlf(t, 20.0, C1, C2));
        for j in 0..9 {
            let omega = 0.1 * 10f64.powf(j as f64 / 4.0);
            let (s, l) = series.at(omega * a_t);
            text.push_str(&format!("{t},{omega:e},{s:e},{l:e}\n"));
        }
    }
    dir.write(name, &text)
}

/// The points lie on the master curve at their reduced frequency, and the
/// reduced frequency is ω·a_T from the WLF written out here.
fn assert_on_master_curve(points: &[DmaPoint], tolerance: f64) {
    let series = Series::broad_rubber();
    for pair in points.windows(2) {
        assert!(pair[0].omega <= pair[1].omega, "not sorted by reduced ω");
    }
    for p in points {
        let (s, l) = series.at(p.omega);
        assert!(relative(p.storage, s) < tolerance, "{p:?}: E′ {s}");
        assert!(relative(p.loss, l) < tolerance, "{p:?}: E″ {l}");
    }
}

#[test]
fn several_temperatures_are_shifted_back_onto_the_master_curve() {
    let dir = TempDir::new("shift");
    let temperatures = [0.0, 20.0, 40.0, 60.0];
    let path = multi_temperature_csv(&dir, "dma.csv", &temperatures);
    let data = DmaData::read(&path, 0.5, &DmaOptions::default()).unwrap();
    assert_eq!(data.temperatures(), temperatures.to_vec());
    let series = Series::broad_rubber();

    // With the fit's WLF shift.
    let shift = wlf_shift_json(20.0, C1, C2, &[0.0, 20.0, 40.0]);
    let fit = fit_dir(&dir.path().join("wlf"), &series, (1e-3, 1e6), &shift, 0.5);
    let points = data.at_reference(&fit, &DmaOptions::default()).unwrap();
    assert_eq!(points.len(), 36);
    assert_on_master_curve(&points, 1e-13);
    let measured: Vec<f64> = data
        .points
        .iter()
        .map(|p| p.omega * 10f64.powf(wlf(p.temperature.unwrap(), 20.0, C1, C2)))
        .collect();
    for p in &points {
        assert!(
            measured.iter().any(|m| relative(p.omega, *m) < 1e-14),
            "{p:?}"
        );
    }
    // 60 °C lies outside the fit's temperatures: extrapolated WLF, said so.
    let shifted = data.shifted(&fit, &DmaOptions::default()).unwrap();
    assert!(
        shifted
            .notes
            .iter()
            .any(|n| n.contains("60.0") && n.contains("extrapolated")),
        "{:?}",
        shifted.notes
    );

    // With the DMA's own WLF at another reference temperature: the same
    // shifts (WLF re-referenced to 40 °C: C1′ = C1 C2/(C2 + 20), C2′ = C2 + 20).
    let own = DmaOptions {
        kind: None,
        wlf: Some(DmaWlf {
            t_ref: 40.0,
            c1: C1 * C2 / (C2 + 20.0),
            c2: C2 + 20.0,
        }),
        ..Default::default()
    };
    let again = data.at_reference(&fit, &own).unwrap();
    for (a, b) in again.iter().zip(&points) {
        assert!(relative(a.omega, b.omega) < 1e-13, "{a:?} {b:?}");
    }
    // On a fit without a shift the DMA's own WLF takes the fit to be at
    // its T_ref (here 20 °C).
    let plain = fit_dir(&dir.path().join("plain"), &series, (1e-3, 1e6), "", 0.5);
    let own20 = DmaOptions {
        kind: None,
        wlf: Some(DmaWlf {
            t_ref: 20.0,
            c1: C1,
            c2: C2,
        }),
        ..Default::default()
    };
    assert_on_master_curve(&data.at_reference(&plain, &own20).unwrap(), 1e-13);

    // No shift anywhere: refused, with the flag to use.
    let e = data
        .at_reference(&plain, &DmaOptions::default())
        .unwrap_err()
        .to_string();
    assert_contains(
        &e,
        &[
            "dma.csv",
            "4 temperatures",
            "0.0, 20.0, 40.0, 60.0",
            "--dma-wlf T_REF,C1,C2",
        ],
    );

    // A free shift says nothing outside its temperatures.
    let free = r#"{"model": "free", "T_ref": 20.0, "log_aT": [{"T": 0.0, "log_aT": 2.0}, {"T": 20.0, "log_aT": 0.0}, {"T": 40.0, "log_aT": -1.5}]}"#;
    let free_fit = fit_dir(&dir.path().join("free"), &series, (1e-3, 1e6), free, 0.5);
    let e = data
        .at_reference(&free_fit, &DmaOptions::default())
        .unwrap_err()
        .to_string();
    assert_contains(&e, &["60.0 °C", "free shift", "0 to 40 °C", "--dma-wlf"]);
}

#[test]
fn isotherms_with_controller_scatter_take_a_free_shifts_listed_values() {
    let dir = TempDir::new("free");
    let text = "T,omega,E_storage,E_loss\n-0.02,1,1e7,1e6\n0.03,2,1e7,1e6\n39.98,1,1e7,1e6\n40.01,3,1e7,1e6\n";
    let data = DmaData::read(&dir.write("dma.csv", text), 0.5, &DmaOptions::default()).unwrap();
    assert_eq!(data.temperatures().len(), 2);
    let free = r#"{"model": "free", "T_ref": 20.0, "log_aT": [{"T": 0.0, "log_aT": 2.0}, {"T": 20.0, "log_aT": 0.0}, {"T": 40.0, "log_aT": -1.5}]}"#;
    let fit = fit_dir(
        &dir.path().join("fit"),
        &Series::broad_rubber(),
        (1e-3, 1e6),
        free,
        0.5,
    );
    let omegas: Vec<f64> = data
        .at_reference(&fit, &DmaOptions::default())
        .unwrap()
        .iter()
        .map(|p| p.omega)
        .collect();
    let expected = [10f64.powf(-1.5), 3.0 * 10f64.powf(-1.5), 100.0, 200.0];
    for (o, e) in omegas.iter().zip(expected) {
        assert!(relative(*o, e) < 1e-14, "{omegas:?}");
    }
}

#[test]
fn one_temperature_is_used_as_measured_or_shifted_to_the_fits_reference() {
    let dir = TempDir::new("single");
    let path = multi_temperature_csv(&dir, "dma40.csv", &[40.0]);
    let data = DmaData::read(&path, 0.5, &DmaOptions::default()).unwrap();
    let series = Series::broad_rubber();
    let plain = fit_dir(&dir.path().join("plain"), &series, (1e-3, 1e6), "", 0.5);
    let shifted = data.shifted(&plain, &DmaOptions::default()).unwrap();
    for (a, b) in shifted.points.iter().zip(&data.points) {
        assert_eq!(a.omega, b.omega);
    }
    assert!(shifted.notes.iter().any(|n| n.contains("as measured")));
    let shift = wlf_shift_json(20.0, C1, C2, &[20.0, 40.0]);
    let fit = fit_dir(&dir.path().join("wlf"), &series, (1e-3, 1e6), &shift, 0.5);
    assert_on_master_curve(
        &data.at_reference(&fit, &DmaOptions::default()).unwrap(),
        1e-13,
    );
    // No temperature column at all: as measured, also on a temperature set.
    let path = dir.write("not.csv", "omega,E_storage,E_loss\n1,1e7,1e6\n");
    let data = DmaData::read(&path, 0.5, &DmaOptions::default()).unwrap();
    let points = data.at_reference(&fit, &DmaOptions::default()).unwrap();
    assert_eq!(points[0].omega, 1.0);
}

// ---------------------------------------------------------------- causality

/// Points of `series` at `count` log-spaced ω over [lo, hi] rad/s.
fn sample(series: &Series, lo: f64, hi: f64, count: usize) -> Vec<DmaPoint> {
    (0..count)
        .map(|j| {
            let omega = lo * (hi / lo).powf(j as f64 / (count - 1) as f64);
            let (storage, loss) = series.at(omega);
            DmaPoint {
                omega,
                storage,
                loss,
                temperature: None,
            }
        })
        .collect()
}

/// A quasi-continuous spectrum: four terms per decade, log-normal
/// strengths, shifted off the check's grid by `offset` decades.
fn dense_rubber(offset: f64) -> Series {
    let tau: Vec<f64> = (-48..=16)
        .map(|k| 10f64.powf(k as f64 / 4.0 + offset))
        .collect();
    let weights: Vec<f64> = tau
        .iter()
        .map(|t| (-(t.log10() - offset + 4.0).powi(2) / 8.0).exp())
        .collect();
    let total: f64 = weights.iter().sum();
    Series {
        e1: 2e9,
        h: weights.iter().map(|w| (2e9 - 2e6) * w / total).collect(),
        tau,
    }
}

#[test]
fn causal_data_fit_a_causal_model_to_a_thousandth_of_a_decade() {
    for offset in [0.37, 0.11] {
        let series = dense_rubber(offset);
        let points = sample(&series, 1e-2, 1e9, 80);
        let check = causality::check(&points).unwrap();
        println!(
            "causal (offset {offset}): misfit E′ {:.2e}, E″ {:.2e} decades",
            check.misfit_storage, check.misfit_loss
        );
        assert!(check.misfit_storage < 1e-4 && check.misfit_loss < 1e-4);
        assert!(check.max_misfit_storage.0 < 1e-3 && check.max_misfit_loss.0 < 1e-3);
        assert!(check.warnings.is_empty(), "{:?}", check.warnings);
        // The fitted curve is the check's model: it follows the data.
        for p in check.curve(50) {
            let (s, l) = series.at(p.omega);
            assert!(
                relative(p.storage, s) < 1e-3 && relative(p.loss, l) < 1e-3,
                "{p:?}"
            );
        }
    }
    // The hardest causal case: two isolated Maxwell elements between grid
    // nodes (module doc: about 3e-3/5e-3 decades), still far from a warning.
    let narrow = Series {
        e1: 1e8,
        h: vec![6e7, 3e7],
        tau: vec![2.3e-3, 4.1e-2],
    };
    let check = causality::check(&sample(&narrow, 1e-1, 1e5, 80)).unwrap();
    println!(
        "isolated elements: misfit E′ {:.2e}, E″ {:.2e} decades",
        check.misfit_storage, check.misfit_loss
    );
    assert!(check.misfit_storage < 1e-2 && check.misfit_loss < 1e-2);
    assert!(check.warnings.is_empty(), "{:?}", check.warnings);
}

#[test]
fn loss_inflated_near_the_peak_is_not_causal() {
    let series = Series::broad_rubber();
    let mut points = sample(&series, 1e-2, 1e9, 100);
    // The loss peak of the broad rubber is near ω = 1/τ_centre = 1e4 rad/s.
    let peak = points
        .iter()
        .max_by(|a, b| a.tan_delta().total_cmp(&b.tan_delta()))
        .unwrap()
        .omega;
    for p in &mut points {
        if (p.omega / peak).log10().abs() < 1.0 {
            p.loss *= 1.5;
        }
    }
    let check = causality::check(&points).unwrap();
    println!(
        "inflated: misfit E′ {:.4}, E″ {:.4}, max E″ {:.4} decades",
        check.misfit_storage, check.misfit_loss, check.max_misfit_loss.0
    );
    assert!(check.misfit_loss > KK_MISFIT_THRESHOLD);
    assert!(check.max_misfit_loss.0 > KK_MAX_MISFIT_THRESHOLD);
    assert!(
        check.warnings.iter().any(|w| w.contains("not causal")),
        "{:?}",
        check.warnings
    );
}

/// Lawson–Hanson against the definition: the NNLS optimum is the best of
/// the unconstrained least-squares solutions on every subset of columns
/// that are feasible (x ≥ 0), found here by enumerating all 2^n subsets.
#[test]
fn nnls_matches_brute_force_enumeration() {
    use nalgebra::{DMatrix, DVector};
    // A fixed linear congruential sequence: reproducible, no dependency.
    let mut state: u64 = 0x2545_F491_4F6C_DD1D;
    let mut next = || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((state >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    for _ in 0..20 {
        let (m, n) = (9, 5);
        let a = DMatrix::from_fn(m, n, |_, _| next());
        let b = DVector::from_fn(m, |_, _| next());
        let x = causality::nnls(&a, &b);
        let mut best = f64::INFINITY;
        for mask in 0u32..(1 << n) {
            let cols: Vec<usize> = (0..n).filter(|j| mask & (1 << j) != 0).collect();
            let mut z = DVector::zeros(n);
            if !cols.is_empty() {
                let sub = a.select_columns(&cols);
                let s = (sub.transpose() * &sub).try_inverse().unwrap() * sub.transpose() * &b;
                if s.iter().any(|v| *v < 0.0) {
                    continue;
                }
                for (k, &j) in cols.iter().enumerate() {
                    z[j] = s[k];
                }
            }
            best = best.min((&a * z - &b).norm());
        }
        assert!(x.iter().all(|v| *v >= 0.0));
        assert!(
            ((&a * &x - &b).norm() - best).abs() < 1e-12,
            "{} vs {best}",
            (&a * &x - &b).norm()
        );
    }
}

// ---------------------------------------------------------------- compare

use rollfit_testkit::contract::COMPARE_KEYS as CONTRACT_KEYS;

/// A DMA file made from the broad rubber (Young's, no temperature) at
/// `count` ω over [lo, hi], E′ multiplied by `storage_factor`.
fn own_curve_csv(
    dir: &TempDir,
    name: &str,
    lo: f64,
    hi: f64,
    count: usize,
    storage_factor: f64,
) -> PathBuf {
    let mut text = String::from("omega,E_storage,E_loss\n");
    for p in sample(&Series::broad_rubber(), lo, hi, count) {
        text.push_str(&format!(
            "{:e},{:e},{:e}\n",
            p.omega,
            p.storage * storage_factor,
            p.loss
        ));
    }
    dir.write(name, &text)
}

#[test]
fn a_dma_of_the_fits_own_curve_matches_to_rounding() {
    let dir = TempDir::new("own");
    let fit = fit_dir(
        &dir.path().join("fit"),
        &Series::broad_rubber(),
        (0.09, 1.1e5),
        "",
        0.5,
    );
    // 41 points over 1e-3..1e7, four per decade: 25 inside the window.
    let path = own_curve_csv(&dir, "own.csv", 1e-3, 1e7, 41, 1.0);
    let dma = DmaData::read(&path, 0.5, &DmaOptions::default()).unwrap();
    let c = compare(&fit, &dma, &DmaOptions::default()).unwrap();
    assert_eq!(c.n_points, 25);
    assert!(
        relative(c.omega_min.unwrap(), 0.1) < 1e-12 && relative(c.omega_max.unwrap(), 1e5) < 1e-12
    );
    for value in [
        c.tan_delta_rms_rel,
        c.tan_delta_max_rel,
        c.abs_modulus_rms_rel,
        c.abs_modulus_max_rel,
        c.log10_storage_rms,
        c.log10_loss_rms,
    ] {
        assert!(value.unwrap() < 1e-12, "{value:?}");
    }
    assert!(c.dma_kk_misfit_storage < 1e-3 && c.dma_kk_misfit_loss < 1e-3);
    assert!(!c.overlap_empty);
    assert_eq!(c.points.len(), 41);
    let json = serde_json::to_value(&c).unwrap();
    for key in CONTRACT_KEYS {
        assert!(
            json.get(key).is_some_and(|v| !v.is_null()),
            "{key} in {json}"
        );
    }
    assert!(json.get("points").is_none() && json.get("causal").is_none());
}

#[test]
fn ten_per_cent_more_storage_gives_the_analytic_errors() {
    let dir = TempDir::new("offset");
    let series = Series::broad_rubber();
    let fit = fit_dir(&dir.path().join("fit"), &series, (0.09, 1.1e5), "", 0.5);
    let path = own_curve_csv(&dir, "stiff.csv", 1e-1, 1e5, 25, 1.1);
    let dma = DmaData::read(&path, 0.5, &DmaOptions::default()).unwrap();
    let c = compare(&fit, &dma, &DmaOptions::default()).unwrap();
    assert_eq!(c.n_points, 25);
    // log10(E′_fit/E′_DMA) = −log10 1.1 at every point.
    assert!((c.log10_storage_rms.unwrap() - 1.1f64.log10()).abs() < 1e-12);
    assert!(c.log10_loss_rms.unwrap() < 1e-12);
    // tan δ_fit/tan δ_DMA = 1.1 at every point: relative error 0.1.
    assert!((c.tan_delta_rms_rel.unwrap() - 0.1).abs() < 1e-12);
    assert!((c.tan_delta_max_rel.unwrap() - 0.1).abs() < 1e-12);
    // |E*|: (√(E′² + E″²) − √(1.21 E′² + E″²))/√(1.21 E′² + E″²) per point.
    let errors: Vec<f64> = sample(&series, 1e-1, 1e5, 25)
        .iter()
        .map(|p| {
            let dma = (1.21 * p.storage * p.storage + p.loss * p.loss).sqrt();
            (p.storage.hypot(p.loss) - dma) / dma
        })
        .collect();
    let rms = (errors.iter().map(|e| e * e).sum::<f64>() / 25.0).sqrt();
    let max = errors.iter().fold(0.0f64, |m, e| m.max(e.abs()));
    assert!(relative(c.abs_modulus_rms_rel.unwrap(), rms) < 1e-10);
    assert!(relative(c.abs_modulus_max_rel.unwrap(), max) < 1e-10);
}

#[test]
fn no_overlap_gives_null_metrics_and_says_why() {
    let dir = TempDir::new("apart");
    let fit = fit_dir(
        &dir.path().join("fit"),
        &Series::broad_rubber(),
        (1e-1, 1e2),
        "",
        0.5,
    );
    let path = own_curve_csv(&dir, "high.csv", 1e4, 1e7, 10, 1.0);
    let dma = DmaData::read(&path, 0.5, &DmaOptions::default()).unwrap();
    let c = compare(&fit, &dma, &DmaOptions::default()).unwrap();
    assert_eq!(c.n_points, 0);
    assert!(c.overlap_empty);
    let json = serde_json::to_value(&c).unwrap();
    for key in &CONTRACT_KEYS[1..9] {
        assert!(json[key].is_null(), "{key}: {}", json[key]);
    }
    assert_eq!(json["n_points"], 0);
    assert!(json["dma_kk_misfit_storage"].is_number());
    // The readable rows (compare's table, the report page) follow the
    // contract's keys and show no number where there is none.
    let rows = c.metric_rows();
    let keys: Vec<&str> = rows.iter().map(|r| r.key).collect();
    assert_eq!(&keys[..11], &CONTRACT_KEYS[..]);
    for row in &rows[1..9] {
        assert_eq!(row.value_text(), "—", "{}", row.key);
    }
    assert_eq!(rows[0].value_text(), "0");
    assert!(
        c.warnings.iter().any(|w| w.contains("[1.000e-1, 1.000e2]")
            && w.contains("[1.000e4, 1.000e7]")
            && w.contains("do not overlap")),
        "{:?}",
        c.warnings
    );
}

/// Thousands of points are checked on their bins (`condense`): a logger's
/// dense sampling of a causal rubber, with a deterministic ±1 % ripple that
/// changes sign from point to point (scatter a causal series cannot
/// follow), gives the floor the same points give checked one by one when
/// they are few enough: the ripple's 0.0043 decades.
#[test]
fn a_dense_sampling_checks_like_a_sparse_one() {
    let series = dense_rubber(0.37);
    let ripple = |points: Vec<DmaPoint>| -> Vec<DmaPoint> {
        points
            .into_iter()
            .enumerate()
            .map(|(j, mut p)| {
                let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
                p.storage *= 1.0 + 0.01 * sign;
                p.loss *= 1.0 - 0.01 * sign;
                p
            })
            .collect()
    };
    let sparse = causality::check(&ripple(sample(&series, 1e-2, 1e9, 1500))).unwrap();
    let dense = causality::check(&ripple(sample(&series, 1e-2, 1e9, 200_000))).unwrap();
    println!(
        "ripple: sparse E′ {:.5}, E″ {:.5}; dense E′ {:.5}, E″ {:.5} decades",
        sparse.misfit_storage, sparse.misfit_loss, dense.misfit_storage, dense.misfit_loss
    );
    let ripple_decades = (1.01f64).log10();
    for misfit in [
        sparse.misfit_storage,
        sparse.misfit_loss,
        dense.misfit_storage,
        dense.misfit_loss,
    ] {
        assert!((misfit / ripple_decades - 1.0).abs() < 0.05, "{misfit}");
    }
    assert!(dense.warnings.is_empty(), "{:?}", dense.warnings);
}
