//! Unit tests of the fit folder: fit.json edited by hand is refused naming
//! the key and line; invalid bytes are located.

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

use super::columns::MODULUS_COLUMNS;
use super::write::MODULUS_VALUES;
use super::*;

/// A fit folder of its own under the system's temporary folder,
/// removed on drop.
struct Folder(PathBuf);

impl Folder {
    /// fit.json as given, with a valid mu.csv and modulus.csv.
    fn new(name: &str, fit_json: &[u8]) -> Folder {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let path = std::env::temp_dir().join(format!(
            "rollfit-io-fitdir-{}-{name}-{n}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&path);
        std::fs::create_dir_all(&path).unwrap();
        std::fs::write(path.join("fit.json"), fit_json).unwrap();
        std::fs::write(path.join("mu.csv"), "v,mu_measured,mu_fit\n1e-3,0.1,0.1\n").unwrap();
        std::fs::write(
            path.join("modulus.csv"),
            "omega,E_storage,E_loss,tan_delta\n1,1e6,1e5,0.1\n10,2e6,2e5,0.1\n",
        )
        .unwrap();
        Folder(path)
    }

    fn error(&self) -> String {
        match FitDir::read(&self.0) {
            Ok(_) => panic!("{}: expected an error", self.0.display()),
            Err(e) => e.to_string(),
        }
    }
}

impl Drop for Folder {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A temperature set's fit.json, one key per line (line numbers below
/// count on it).
const GOOD: &str = r#"{
  "model": {"kind": "prony", "E1": 1e9, "tau": [0.001, 0.01], "H": [4e8, 5e8]},
  "poisson": 0.5,
  "window": {"omega_min": 0.1, "omega_max": 1000.0},
  "method": "test",
  "objective": 0.0,
  "iterations": 3,
  "converged": true,
  "wall_time_s": 0.5,
  "shift": {"model": "wlf", "T_ref": 20.0, "C1": 8.86, "C2": 101.6,
    "log_aT": [{"T": 0.0, "log_aT": 1.26}, {"T": 40.0, "log_aT": -1.2}]}
}
"#;

fn edited(name: &str, from: &str, to: &str) -> Folder {
    assert!(GOOD.contains(from), "{from}");
    Folder::new(name, GOOD.replacen(from, to, 1).as_bytes())
}

fn assert_contains(text: &str, fragments: &[&str]) {
    for f in fragments {
        assert!(text.contains(f), "{f:?} not in:\n{text}");
    }
}

#[test]
fn the_unedited_fit_json_reads() {
    let folder = Folder::new("good", GOOD.as_bytes());
    let fit = FitDir::read(&folder.0).unwrap();
    assert_eq!(fit.summary.shift.unwrap().model, "wlf");
    assert_eq!(fit.summary.iterations, 3);
}

/// An unknown shift model was read as WLF.
#[test]
fn unknown_or_incomplete_shift_models_are_refused() {
    let e = edited("foo", r#""model": "wlf""#, r#""model": "foo""#).error();
    assert_contains(
        &e,
        &[
            "fit.json, line 10",
            "shift.model = \"foo\": unknown shift model; allowed: \"wlf\", \"arrhenius\", \"free\"",
        ],
    );
    let e = edited("noc2", r#", "C2": 101.6"#, "").error();
    assert_contains(
        &e,
        &[
            "fit.json, line 10",
            "shift.model = \"wlf\" needs the key shift.C2",
        ],
    );
    let e = edited("free", r#""model": "wlf""#, r#""model": "free""#).error();
    assert_contains(
        &e,
        &[
            "fit.json, line 10",
            "shift.C1 does not belong to shift.model = \"free\"",
        ],
    );
    let free = GOOD.replacen(r#""model": "wlf", "#, r#""model": "free", "#, 1);
    let free = free.replacen(r#", "C1": 8.86, "C2": 101.6"#, "", 1);
    let folder = Folder::new("free-ok", free.as_bytes());
    assert_eq!(
        FitDir::read(&folder.0)
            .unwrap()
            .summary
            .shift
            .unwrap()
            .model,
        "free"
    );
}

/// An Arrhenius shift reads back with its law (log10 a_T at any
/// temperature from E_a), a null σ reads as NaN, and an Arrhenius record
/// without a positive E_a or with a WLF constant is refused.
#[test]
fn arrhenius_shifts_and_null_sigmas_read() {
    let arrhenius = GOOD
        .replacen(r#""model": "wlf", "#, r#""model": "arrhenius", "#, 1)
        .replacen(
            r#", "C1": 8.86, "C2": 101.6"#,
            r#", "E_a": 2e5, "E_a_sigma": null"#,
            1,
        )
        .replacen(
            r#""log_aT": 1.26}"#,
            r#""log_aT": 1.26, "log_aT_sigma": null}"#,
            1,
        );
    let folder = Folder::new("arrhenius-ok", arrhenius.as_bytes());
    let shift = FitDir::read(&folder.0).unwrap().summary.shift.unwrap();
    assert_eq!(shift.model, "arrhenius");
    assert!(shift.log_shift[0].log_shift_sigma.is_nan());
    let hand = 2e5 / (8.314462618 * 10f64.ln()) * (1.0 / 283.15 - 1.0 / 293.15);
    assert!((shift.log_shift_at(10.0).unwrap() - hand).abs() < 1e-12);
    let without = arrhenius.replacen(r#", "E_a": 2e5"#, "", 1);
    let e = Folder::new("arrhenius-no-energy", without.as_bytes()).error();
    assert_contains(
        &e,
        &["shift.model = \"arrhenius\" needs a positive shift.E_a"],
    );
    let with_c1 = arrhenius.replacen(r#", "E_a": 2e5"#, r#", "E_a": 2e5, "C1": 8.0"#, 1);
    let e = Folder::new("arrhenius-c1", with_c1.as_bytes()).error();
    assert_contains(
        &e,
        &["shift.C1 does not belong to shift.model = \"arrhenius\""],
    );
}

/// Ν and WLF constants outside their range were
/// accepted, and a bad ν was blamed on the DMA file later.
#[test]
fn poisson_and_wlf_constants_out_of_range_are_refused_naming_fit_json() {
    for (name, nu) in [
        ("nu1", "1"),
        ("nu-1", "-1"),
        ("nu06", "0.6"),
        ("nu-03", "-0.3"),
    ] {
        let e = edited(name, r#""poisson": 0.5"#, &format!(r#""poisson": {nu}"#)).error();
        assert_contains(
            &e,
            &[
                "fit.json, line 3",
                &format!("poisson = {nu} outside [0, 0.5]: Poisson's ratio of rubber is 0.5"),
            ],
        );
    }
    let e = edited("c2", r#""C2": 101.6"#, r#""C2": -5"#).error();
    assert_contains(
        &e,
        &[
            "fit.json, line 10",
            "shift.C2 = -5: the WLF constant C2 must be > 0 K",
        ],
    );
    let e = edited("c1", r#""C1": 8.86"#, r#""C1": 0"#).error();
    assert_contains(&e, &["fit.json, line 10", "shift.C1 = 0"]);
    // C2 = 10 K: the WLF form diverges at 10 °C, above the 0 °C isotherm.
    let e = edited("pole", r#""C2": 101.6"#, r#""C2": 10"#).error();
    assert_contains(
        &e,
        &[
            "fit.json, line 11",
            "shift.log_aT[0].T = 0 °C: C2 + T − T_ref = -10 K is not positive",
            "diverges at T_ref − C2 = 10 °C",
        ],
    );
}

/// Null (a NaN as serde_json writes it) or a
/// non-finite number where a number belongs: the key, not only
/// "invalid type: null".
#[test]
fn null_and_non_finite_numbers_are_refused_naming_the_key() {
    let e = edited("objective", r#""objective": 0.0"#, r#""objective": null"#).error();
    assert_contains(
        &e,
        &[
            "fit.json, line 6",
            "`objective` is null where a number is required",
        ],
    );
    let e = edited("tau", "[0.001, 0.01]", "[0.001, null]").error();
    assert_contains(
        &e,
        &[
            "fit.json, line 2",
            "`model.tau[1]` is null where a number is required",
        ],
    );
    let e = edited("iterations", r#""iterations": 3"#, r#""iterations": null"#).error();
    assert_contains(
        &e,
        &["fit.json, line 7", "`iterations` is null where a count"],
    );
    let e = edited("shiftT", r#"{"T": 40.0"#, r#"{"T": null"#).error();
    assert_contains(&e, &["fit.json, line 11", "`shift.log_aT[1].T` is null"]);
    let e = edited("huge", r#""E1": 1e9"#, r#""E1": 1e999"#).error();
    assert_contains(
        &e,
        &[
            "fit.json, line 2",
            "`model.E1`",
            "out of range",
            "must be finite",
        ],
    );
    let e = edited("nan", r#""wall_time_s": 0.5"#, r#""wall_time_s": NaN"#).error();
    assert_contains(&e, &["fit.json, line 9", "`wall_time_s`", "must be finite"]);
    let e = edited("inf", r#""objective": 0.0"#, r#""objective": -Infinity"#).error();
    assert_contains(&e, &["fit.json, line 6", "`objective`", "must be finite"]);
    let e = edited("converged", r#""converged": true"#, r#""converged": null"#).error();
    assert_contains(
        &e,
        &[
            "fit.json, line 8",
            "`converged` is null where a boolean is required",
        ],
    );
    let e = edited("missing", r#""E1": 1e9, "#, "").error();
    assert_contains(&e, &["fit.json, line 2", "`model`", "missing field `E1`"]);
}

/// "stream did not contain valid UTF-8" said neither
/// where nor which byte.
#[test]
fn invalid_utf8_in_a_fit_folder_is_located_by_line_and_offset() {
    let mut bytes = GOOD.as_bytes().to_vec();
    let offset = GOOD.find("test").unwrap();
    bytes[offset] = 0xFF;
    let line_start = GOOD[..offset].rfind('\n').unwrap() + 1;
    let folder = Folder::new("json-bytes", &bytes);
    assert_contains(
        &folder.error(),
        &[
            "fit.json, line 5",
            &format!(
                "not UTF-8: byte 0xFF at byte offset {offset} (byte {} of the line)",
                offset - line_start + 1
            ),
        ],
    );
    let folder = Folder::new("csv-bytes", GOOD.as_bytes());
    let mut mu = b"v,mu_measured,mu_fit\n1e-3,0.1,0.1\n2e-3,0.".to_vec();
    let offset = mu.len();
    mu.extend(b"\xE9,0.1\n");
    std::fs::write(folder.0.join("mu.csv"), mu).unwrap();
    assert_contains(
        &folder.error(),
        &[
            "mu.csv, line 3",
            &format!("not UTF-8: byte 0xE9 at byte offset {offset} (byte 8 of the line)"),
        ],
    );
}

/// modulus.csv's writer and its column list agree.
#[test]
fn modulus_values_follow_the_column_list() {
    assert_eq!(MODULUS_VALUES.map(|(name, _)| name), MODULUS_COLUMNS);
}

/// A fit of 8 speeds made by a standard linear solid under a cylinder,
/// anchored by E0 (σ = 1 % given, no noise): the report, and what it fits
/// as mu.csv's measured columns.
struct SmallFit {
    speeds: Vec<f64>,
    mu: Vec<f64>,
    sigma: Vec<f64>,
}

impl SmallFit {
    fn new() -> SmallFit {
        use rollfit_model::{Scene, StandardLinearSolid};
        let setup = small_setup();
        let truth = StandardLinearSolid::new(2e6, 2e7, 1e-2).unwrap();
        let scene = Scene::new(setup.geometry, setup.substrate, setup.contact, truth).unwrap();
        let speeds: Vec<f64> = (0..8).map(|k| 1e-6 * 10f64.powf(0.5 * k as f64)).collect();
        let mu = scene.friction_sweep(&speeds).unwrap();
        let sigma: Vec<f64> = mu.iter().map(|m| 0.01 * m).collect();
        SmallFit { speeds, mu, sigma }
    }

    fn fit(&self, physics: rollfit_fit::Physics) -> rollfit_fit::FitReport {
        use rollfit_fit::{FitParams, Lambda, Measurements, ScaleAnchor};
        let data = Measurements::new(
            self.speeds.clone(),
            self.mu.clone(),
            Some(self.sigma.clone()),
            None,
        )
        .unwrap();
        let params = FitParams {
            anchor: Some(ScaleAnchor::StaticModulus(2e6)),
            lambda: Lambda::Fixed(1.0),
            starts: 1,
            terms: rollfit_fit::TermRule::PerDecade(1.0),
            physics,
            ..FitParams::default()
        }
        .check(small_setup())
        .unwrap();
        rollfit_fit::fit(&data, &params).unwrap()
    }

    /// `report`'s files written to a folder of their own, and read back.
    fn round_trip(&self, report: &rollfit_fit::FitReport, name: &str) -> (FitDir, FitFiles) {
        let input = FitInput {
            scene: "scene.toml".into(),
            data: "data.csv".into(),
            temperature: None,
            rollfit_version: "test",
        };
        let measured = Measured {
            speeds: &self.speeds,
            friction: &self.mu,
            sigma: Some(&self.sigma),
            temperature: None,
        };
        let files = FitFiles::encode(report, &measured, &input).unwrap();
        let folder = Folder::new(name, b"{}");
        for (name, bytes) in files.named() {
            std::fs::write(folder.0.join(name), bytes).unwrap();
        }
        (FitDir::read(&folder.0).unwrap(), files)
    }
}

/// A 5 mm cylinder at 1000 N/m on a thick rubber, ν = 0.5, dynamic
/// contact, as a scene file says it.
fn small_setup() -> rollfit_fit::RollingSetup {
    let scene = "[geometry]\nshape = \"cylinder\"\nradius = 0.005\nload = 1000.0\n";
    crate::scene::parse(scene).unwrap().fit_setup().unwrap().0
}

/// A fit with `physics = "exact"` writes fit.json's `physics`
/// and mu.csv's `exact_correction`, and the reader reads back what the
/// writer wrote; the approximate fit of the same data writes neither.
#[test]
fn exact_physics_round_trips_through_the_fit_folder() {
    use rollfit_fit::Physics;
    let small = SmallFit::new();
    for physics in [Physics::Approximate, Physics::Exact] {
        let report = small.fit(physics);
        let (read, files) = small.round_trip(&report, physics.name());
        let fitted: Vec<f64> = read.friction.iter().map(|r| r.mu_fit).collect();
        assert_eq!(fitted, report.mu_fit);
        let corrections: Vec<Option<f64>> =
            read.friction.iter().map(|r| r.exact_correction).collect();
        match (&report.physics, &read.summary.physics) {
            (None, None) => {
                assert!(corrections.iter().all(Option::is_none));
                let json = String::from_utf8(files.named()[2].1.to_vec()).unwrap();
                assert!(!json.contains("\"physics\""), "{json}");
            }
            (Some(written), Some(back)) => {
                assert_eq!(back.kind, "exact");
                assert_eq!(back.iterations, Some(written.iterations));
                assert_eq!(back.exact_solves, Some(written.exact_solves));
                assert_eq!(back.converged, Some(written.converged));
                assert_eq!(back.max_correction, Some(written.max_correction));
                assert_eq!(back.accuracy, Some(written.accuracy));
                let expected: Vec<Option<f64>> =
                    written.correction.iter().copied().map(Some).collect();
                assert_eq!(corrections, expected);
            }
            (written, back) => panic!("{physics:?}: wrote {written:?}, read {back:?}"),
        }
    }
}

/// Fit.json's `fit_quality` and `scale` read back as written,
/// the scale absent, undetermined with both ends open (null), or
/// determined with both ends; the "invalid" verdict reads as not good. A
/// fit.json without them (another program's) reads with neither.
#[test]
fn verdict_noise_and_scale_round_trip_through_the_fit_folder() {
    use rollfit_fit::ScaleRecord;
    let small = SmallFit::new();
    let mut report = small.fit(rollfit_fit::Physics::Approximate);
    // Noiseless data may leave too few residuals of one sign for a runs
    // test; one is set so that its keys are read back too.
    report.fit_quality.runs = Some(rollfit_fit::quality::RunsTest {
        observed: 3,
        expected: 4.5,
        z: -1.2,
        p_value: 0.115,
    });
    let (read, _) = small.round_trip(&report, "quality");
    let q = read.summary.fit_quality.expect("fit_quality reads");
    let written = &report.fit_quality;
    assert_eq!(q.verdict, written.verdict);
    assert_eq!(q.is_good(), written.verdict == "good");
    assert_eq!(q.noise_source.as_deref(), Some(written.noise_source));
    assert_eq!(q.noise, Some(written.noise));
    assert_eq!(q.chi2, Some(written.chi2));
    assert_eq!(q.degrees_of_freedom, Some(written.degrees_of_freedom));
    assert_eq!(q.chi2_p_value, written.chi2_p_value);
    assert!(q.chi2_p_value.is_some(), "σ is given: a χ² p-value");
    let runs = written.runs.unwrap();
    let back = q.runs.expect("the runs test reads");
    assert_eq!(
        (back.observed, back.expected, back.p_value),
        (runs.observed, runs.expected, runs.p_value)
    );
    assert!(read.summary.scale.is_none(), "an anchored fit has no scale");

    let e0 = report.model.static_modulus;
    let open = ScaleRecord {
        status: "undetermined",
        static_modulus: e0,
        low: None,
        high: None,
        range: [1e4, 1e10],
        profile: vec![[1e5, 0.5], [e0, 0.0], [1e8, 0.25]],
        reason: "the data fit as well at every E0 profiled".into(),
    };
    let closed = ScaleRecord {
        status: "data",
        low: Some(0.5 * e0),
        high: Some(2.0 * e0),
        ..open.clone()
    };
    report.fit_quality.verdict = "invalid";
    report.fit_quality.reasons = vec!["the contact is too large".into()];
    for record in [open, closed] {
        report.scale = Some(record.clone());
        let (read, _) = small.round_trip(&report, record.status);
        let q = read.summary.fit_quality.unwrap();
        assert_eq!(q.verdict, "invalid");
        assert!(!q.is_good());
        assert_eq!(q.reasons, report.fit_quality.reasons);
        let scale = read.summary.scale.expect("scale reads");
        assert_eq!(scale.status, record.status);
        assert_eq!(scale.is_determined(), !record.is_undetermined());
        assert_eq!(scale.static_modulus, record.static_modulus);
        assert_eq!((scale.low, scale.high), (record.low, record.high));
        assert_eq!(scale.range, Some(record.range));
        assert_eq!(scale.profile, record.profile);
        assert_eq!(scale.reason.as_deref(), Some(record.reason.as_str()));
    }

    let folder = Folder::new("bare", GOOD.as_bytes());
    let bare = FitDir::read(&folder.0).unwrap().summary;
    assert!(bare.fit_quality.is_none() && bare.scale.is_none() && bare.condensed.is_none());
}
