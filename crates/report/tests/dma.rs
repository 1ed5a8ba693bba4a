//! DMA files, their shift to the fit's reference state, the causality
//! (Kramers–Kronig) check and the comparison with a fit's master curve.
//!
//! Every expected value is computed here independently: the Prony and WLF
//! formulas written out in the test, unit conversions by hand, analytic
//! values of the metrics. Fixtures in tests/fixtures/ are the project's own
//! (synthetic numbers from the model named in each file's comment).

use std::f64::consts::PI;
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use rollfit_report::causality::{self, KK_MAX_MISFIT_THRESHOLD, KK_MISFIT_THRESHOLD};
use rollfit_report::compare::compare;
use rollfit_report::dma::{DmaData, DmaOptions, DmaPoint, DmaWlf, ModulusKind};
use rollfit_report::{FitDir, ReportError};

// ---------------------------------------------------------------- helpers

/// A folder of its own under the system's temporary folder, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> TempDir {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let path = std::env::temp_dir().join(format!(
            "rollfit-report-dma-{}-{name}-{n}",
            std::process::id()
        ));
        let _ = fs::remove_dir_all(&path);
        fs::create_dir_all(&path).unwrap();
        TempDir(path)
    }

    fn write(&self, name: &str, content: &str) -> PathBuf {
        let path = self.0.join(name);
        fs::write(&path, content).unwrap();
        path
    }

    fn path(&self) -> &Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
}

/// A Prony series in the paper's form E*(ω) = E1 − Σ H_k/(1 + iωτ_k),
/// written out: E′ = E1 − Σ H_k/(1 + ω²τ²), E″ = Σ H_k ωτ/(1 + ω²τ²).
#[derive(Clone)]
struct Series {
    e1: f64,
    h: Vec<f64>,
    tau: Vec<f64>,
}

impl Series {
    fn at(&self, omega: f64) -> (f64, f64) {
        let mut storage = self.e1;
        let mut loss = 0.0;
        for (h, tau) in self.h.iter().zip(&self.tau) {
            let x = omega * tau;
            storage -= h / (1.0 + x * x);
            loss += h * x / (1.0 + x * x);
        }
        (storage, loss)
    }

    /// A broad rubber: E0 = 2 MPa, E1 = 2 GPa, one term per decade with a
    /// smooth (log-normal) strength distribution centred at τ = 1e-4 s.
    fn broad_rubber() -> Series {
        let tau: Vec<f64> = (-12..=4).map(|k| 10f64.powi(k)).collect();
        let weights: Vec<f64> = tau
            .iter()
            .map(|t| (-(t.log10() + 4.0).powi(2) / 8.0).exp())
            .collect();
        let total: f64 = weights.iter().sum();
        let (e0, e1) = (2e6, 2e9);
        Series {
            e1,
            h: weights.iter().map(|w| (e1 - e0) * w / total).collect(),
            tau,
        }
    }
}

/// WLF written out: log10 a_T = −C1 (T − T_ref)/(C2 + T − T_ref).
fn wlf(t: f64, t_ref: f64, c1: f64, c2: f64) -> f64 {
    -c1 * (t - t_ref) / (c2 + t - t_ref)
}

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

fn error_text(result: Result<DmaData, ReportError>) -> String {
    match result {
        Ok(data) => panic!("expected an error, read {} points", data.points.len()),
        Err(e) => e.to_string(),
    }
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

// ---------------------------------------------------------------- CSV forms

/// Five points of the broad rubber (Young's, Pa) at 20 °C.
fn reference_points() -> Vec<(f64, f64, f64)> {
    let series = Series::broad_rubber();
    [0.5, 3.0, 20.0, 150.0, 900.0]
        .iter()
        .map(|&omega| {
            let (s, l) = series.at(omega);
            (omega, s, l)
        })
        .collect()
}

fn assert_points(data: &DmaData, expected: &[(f64, f64, f64)], temperature: Option<f64>) {
    assert_eq!(data.points.len(), expected.len());
    for (p, &(omega, storage, loss)) in data.points.iter().zip(expected) {
        assert!(relative(p.omega, omega) < 1e-13, "{p:?} vs ω {omega}");
        assert!(relative(p.storage, storage) < 1e-13, "{p:?} vs E′ {storage}");
        assert!(relative(p.loss, loss) < 1e-13, "{p:?} vs E″ {loss}");
        match (p.temperature, temperature) {
            (Some(t), Some(e)) => assert!((t - e).abs() < 1e-12, "T {t} vs {e}"),
            (None, None) => {}
            other => panic!("temperature {other:?}"),
        }
    }
}

#[test]
fn every_csv_form_reads_the_same_points() {
    let dir = TempDir::new("forms");
    let points = reference_points();
    let nu = 0.5;
    // (file name, header, row maker, expected temperature)
    type Row = fn(f64, f64, f64) -> String;
    let forms: Vec<(&str, &str, Row, Option<f64>)> = vec![
        ("plain.csv", "omega,E_storage,E_loss", |w, s, l| {
            format!("{w:e},{s:e},{l:e}")
        }, None),
        ("hz.csv", "f,E_storage,E_loss,T", |w, s, l| {
            format!("{:e},{s:e},{l:e},20", w / (2.0 * PI))
        }, Some(20.0)),
        ("suffixed.csv", "T_C,omega_rad_s,G_storage_Pa,G_loss_Pa,tan_delta", |w, s, l| {
            format!("20,{w:e},{:e},{:e},{:e}", s / 3.0, l / 3.0, l / s)
        }, Some(20.0)),
        ("hz_mpa.csv", "sample,f_Hz,E_loss_MPa,E_storage_MPa,T_K", |w, s, l| {
            format!("A-1,{:e},{:e},{:e},293.15", w / (2.0 * PI), l / 1e6, s / 1e6)
        }, Some(20.0)),
        ("shear_kpa.csv", "omega,G_storage_kPa,G_loss_GPa", |w, s, l| {
            format!("{w:e},{:e},{:e}", s / 3e3, l / 3e9)
        }, None),
    ];
    for (name, header, row, temperature) in forms {
        let mut text = format!("# {name}: made for the test\n{header}\n");
        for &(w, s, l) in &points {
            text.push_str(&row(w, s, l));
            text.push('\n');
        }
        text.push_str("\n# trailing comment\n");
        let path = dir.write(name, &text);
        let data = DmaData::read(&path, nu, &DmaOptions::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(data.format, "csv");
        let shear = name.contains("shear") || name.contains("suffixed");
        assert_eq!(
            data.kind,
            if shear { ModulusKind::Shear } else { ModulusKind::Young },
            "{name}"
        );
        // T_K: 293.15 − 273.15 is 20 only up to the rounding of the
        // subtraction (5.7e-14), hence the tolerance of assert_points.
        assert_points(&data, &points, temperature);
    }
}

#[test]
fn shear_becomes_young_with_the_fits_poisson_ratio() {
    let dir = TempDir::new("nu");
    let path = dir.write("g.csv", "omega,G_storage,G_loss\n1,1e6,2e5\n10,2e6,5e5\n");
    for nu in [0.5, 0.3, 0.0] {
        let data = DmaData::read(&path, nu, &DmaOptions::default()).unwrap();
        let factor = 2.0 + 2.0 * nu;
        assert_eq!(data.kind, ModulusKind::Shear);
        assert!(relative(data.points[0].storage, factor * 1e6) < 1e-15);
        assert!(relative(data.points[1].loss, factor * 5e5) < 1e-15);
        assert!(
            data.warnings.iter().any(|w| w.contains(&format!("ν = {nu}"))),
            "{:?}",
            data.warnings
        );
    }
    let e = DmaData::read(&path, 0.7, &DmaOptions::default()).unwrap_err();
    assert_contains(&e.to_string(), &["0.7"]);
}

// ---------------------------------------------------------------- TRIOS

/// The fixtures' model (their Notes line): shear Prony with WLF.
fn fixture_model(omega: f64, t: f64) -> (f64, f64) {
    let series = Series {
        e1: 1e8,
        h: vec![3e7, 4e7, 2.5e7],
        tau: vec![1e-3, 1e-2, 1e-1],
    };
    series.at(omega * 10f64.powf(wlf(t, 20.0, 8.86, 101.6)))
}

#[test]
fn trios_lims_shear_export_with_its_units() {
    let path = fixture("trios_shear_two_steps.txt");
    let data = DmaData::read(&path, 0.5, &DmaOptions::default()).unwrap();
    assert_eq!(data.format, "trios-lims");
    assert_eq!(data.kind, ModulusKind::Shear);
    assert_eq!(data.points.len(), 10);
    assert!(
        data.warnings
            .iter()
            .any(|w| w.contains("shear") && w.contains("Oscillation torque") && w.contains("AresG2")),
        "{:?}",
        data.warnings
    );
    // Step 1: rad/s, °C, MPa and kPa; step 2: Hz, K, GPa and Pa.
    let omegas = [1.0, 3.16227766017, 10.0, 31.6227766017, 100.0]
        .into_iter()
        .chain([0.1, 0.5, 1.0, 5.0, 10.0].into_iter().map(|f| 2.0 * PI * f));
    let temperatures = [20.01, 19.99, 20.02, 20.0, 19.98, 40.01, 39.99, 40.0, 40.02, 40.0];
    for ((p, omega), t) in data.points.iter().zip(omegas).zip(temperatures) {
        let (g_storage, g_loss) = fixture_model(omega, t);
        assert!(relative(p.omega, omega) < 1e-11, "{p:?}");
        assert!((p.temperature.unwrap() - t).abs() < 1e-9, "{p:?}");
        // ν = 0.5: E = 3 G; the file has 12 significant digits.
        assert!(relative(p.storage, 3.0 * g_storage) < 1e-10, "{p:?}");
        assert!(relative(p.loss, 3.0 * g_loss) < 1e-10, "{p:?}");
    }
    assert_eq!(data.temperatures().len(), 2);

    // The user's word wins over the file's torque.
    let young = DmaOptions {
        kind: Some(ModulusKind::Young),
        wlf: None,
    };
    let data = DmaData::read(&path, 0.5, &young).unwrap();
    assert_eq!(data.kind, ModulusKind::Young);
    let (g_storage, _) = fixture_model(1.0, 20.01);
    assert!(relative(data.points[0].storage, g_storage) < 1e-10);
}

#[test]
fn trios_lims_tensile_export_and_utf16() {
    let path = fixture("trios_tensile.txt");
    let data = DmaData::read(&path, 0.5, &DmaOptions::default()).unwrap();
    assert_eq!(data.kind, ModulusKind::Young);
    assert!(data.warnings.iter().any(|w| w.contains("Oscillation force")));
    for (p, omega) in data.points.iter().zip([1.0, 10.0, 100.0]) {
        let (s, l) = fixture_model(omega, 20.0);
        assert!(relative(p.storage, s) < 1e-10 && relative(p.loss, l) < 1e-10, "{p:?}");
    }
    // The same text as UTF-16 with a byte-order mark, as Windows tools
    // write it, and with a .csv name: the content decides.
    let dir = TempDir::new("utf16");
    let text = fs::read_to_string(&path).unwrap();
    let mut bytes = vec![0xFF, 0xFE];
    bytes.extend(text.encode_utf16().flat_map(u16::to_le_bytes));
    let copy = dir.path().join("export.csv");
    fs::write(&copy, bytes).unwrap();
    let again = DmaData::read(&copy, 0.5, &DmaOptions::default()).unwrap();
    assert_eq!(again.format, "trios-lims");
    assert_eq!(again.points, data.points);
}

// ---------------------------------------------------------------- bad input

#[test]
fn bad_csv_files_are_refused_with_file_line_and_column() {
    let dir = TempDir::new("bad");
    let options = DmaOptions::default();
    let read = |name: &str, text: &str| DmaData::read(&dir.write(name, text), 0.5, &options);

    let missing = dir.path().join("absent.csv");
    let e = error_text(DmaData::read(&missing, 0.5, &options));
    assert_contains(&e, &["absent.csv"]);

    let e = error_text(read("noloss.csv", "omega,E_storage,T\n1,1e6,20\n"));
    assert_contains(&e, &["noloss.csv", "no E_loss column", "the header has: omega, E_storage, T"]);
    let e = error_text(read("nofreq.csv", "w,E_storage,E_loss\n1,1e6,1e5\n"));
    assert_contains(&e, &["nofreq.csv", "no frequency column", "the header has: w, E_storage, E_loss"]);
    let e = error_text(read("nomod.csv", "omega,storage,loss\n1,1e6,1e5\n"));
    assert_contains(&e, &["E_storage and E_loss (or G_storage and G_loss)"]);
    let e = error_text(read("half.csv", "omega,G_storage\n1,1e6\n"));
    assert_contains(&e, &["no G_loss column"]);

    let e = error_text(read("text.csv", "# c\nomega,E_storage,E_loss\n1,1e6,1e5\n2,abc,1e5\n"));
    assert_contains(&e, &["text.csv, line 4", "column 2 (E_storage)", "\"abc\" is not a number"]);
    let e = error_text(read("nan.csv", "omega,E_storage,E_loss\n1,1e6,NaN\n"));
    assert_contains(&e, &["nan.csv, line 2", "column 3 (E_loss)", "not a finite number"]);
    let e = error_text(read("inf.csv", "omega,E_storage,E_loss\ninf,1e6,1e5\n"));
    assert_contains(&e, &["inf.csv, line 2", "column 1 (omega)", "not a finite number"]);
    let e = error_text(read("zero.csv", "f,E_storage,E_loss\n1,1e6,1e5\n0,1e6,1e5\n"));
    assert_contains(&e, &["zero.csv, line 3", "column 1 (f)", "not positive"]);
    let e = error_text(read("soft.csv", "omega,E_storage,E_loss\n1,-1e6,1e5\n"));
    assert_contains(&e, &["soft.csv, line 2", "column 2 (E_storage)", "not positive"]);
    let e = error_text(read("short.csv", "omega,E_storage,E_loss\n1,1e6\n"));
    assert_contains(&e, &["short.csv, line 2", "2 fields", "3 columns"]);
    let e = error_text(read("empty.csv", "# nothing\nomega,E_storage,E_loss\n"));
    assert_contains(&e, &["empty.csv", "no data rows"]);
    let e = error_text(read("blank.csv", "# nothing at all\n"));
    assert_contains(&e, &["blank.csv", "no header"]);

    // A negative loss modulus is dropped with a warning naming it; a file
    // with nothing else is refused.
    let data = read("neg.csv", "omega,E_storage,E_loss\n1,1e6,1e5\n2,1e6,-3e4\n").unwrap();
    assert_eq!(data.points.len(), 1);
    assert!(
        data.warnings
            .iter()
            .any(|w| w.contains("neg.csv, line 3") && w.contains("column 3 (E_loss)") && w.contains("dropped")),
        "{:?}",
        data.warnings
    );
    let e = error_text(read("allneg.csv", "omega,E_storage,E_loss\n1,1e6,-1e5\n"));
    assert_contains(&e, &["allneg.csv", "no usable points"]);
}

#[test]
fn bad_trios_files_are_refused_with_line_and_variable() {
    let dir = TempDir::new("badtrios");
    let good = fs::read_to_string(fixture("trios_tensile.txt")).unwrap();
    let options = DmaOptions::default();
    let read = |name: &str, text: &str| DmaData::read(&dir.write(name, text), 0.5, &options);

    let e = error_text(read("unit.txt", &good.replacen("MPa\tMPa", "MPa\tpsi", 1)));
    assert_contains(&e, &["unit.txt, line 21", "Loss modulus", "column 6", "\"psi\"", "Pa, kPa, MPa, GPa"]);
    let e = error_text(read("hz.txt", &good.replacen("\trad/s\t", "\trpm\t", 1)));
    assert_contains(&e, &["hz.txt, line 21", "Angular frequency", "\"rpm\""]);
    let e = error_text(read("novar.txt", &good.replace("\tLoss modulus", "\tComplex modulus")));
    assert_contains(&e, &["novar.txt", "no step has the variables needed", "Complex modulus"]);
    let e = error_text(read("num.txt", &good.replacen("Data point\t20\t1\t", "Data point\t20\tx\t", 1)));
    assert_contains(&e, &["num.txt, line 22", "column 3 (Angular frequency)", "\"x\""]);
    let undecided = good
        .replace("Oscillation force", "Amplitude")
        .replace("RSA-G2", "Mystery 3000");
    let e = error_text(read("kind.txt", &undecided));
    assert_contains(&e, &["kind.txt", "shear (G) or tensile (E)", "Mystery 3000", "--dma-modulus"]);
    let told = DmaOptions {
        kind: Some(ModulusKind::Shear),
        wlf: None,
    };
    let data = DmaData::read(&dir.path().join("kind.txt"), 0.5, &told).unwrap();
    assert_eq!(data.kind, ModulusKind::Shear);
    let e = error_text(read("nodata.txt", good.split("Data point").next().unwrap()));
    assert_contains(&e, &["nodata.txt", "without data points"]);
}
