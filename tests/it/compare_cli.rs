//! End-to-end tests of `rollfit compare DIR DMA`: the committed
//! temperature-set fit (examples/fits/hn-rubber-tset, WLF shift) against DMA files
//! made here from its own master curve, and the refusals.
//!
//! Every test works on a copy of the fit folder in a temporary folder, so
//! compare.json never lands in examples/fits/. Every bad-input test checks the
//! same promise as the other commands (common::assert_failure): non-zero
//! exit, an error naming the file and what is wrong, nothing on stdout —
//! and no compare.json.

use crate::common;

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};

use common::{TempDir, assert_failure, rollfit, text};
use rollfit_testkit::series::{Series, wlf};

use rollfit_testkit::contract::COMPARE_KEYS as KEYS;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A copy of a committed fit folder in `dir`.
fn copy_fit(dir: &TempDir, name: &str) -> PathBuf {
    common::committed_fit_as(dir, name, name)
}

/// The fit's master curve and WLF, read from its fit.json and written out
/// here: E*(ω) = E1 − Σ H_k/(1 + iωτ_k), log10 a_T = −C1 ΔT/(C2 + ΔT).
struct Master {
    series: Series,
    t_ref: f64,
    c1: f64,
    c2: f64,
    window: (f64, f64),
}

impl Master {
    fn read(fit: &Path) -> Master {
        let json: serde_json::Value =
            serde_json::from_str(&fs::read_to_string(fit.join("fit.json")).unwrap()).unwrap();
        let list = |v: &serde_json::Value| -> Vec<f64> {
            v.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        };
        let shift = &json["shift"];
        Master {
            series: Series {
                e1: json["model"]["E1"].as_f64().unwrap(),
                h: list(&json["model"]["H"]),
                tau: list(&json["model"]["tau"]),
            },
            t_ref: shift["T_ref"].as_f64().unwrap(),
            c1: shift["C1"].as_f64().unwrap(),
            c2: shift["C2"].as_f64().unwrap(),
            window: (
                json["window"]["omega_min"].as_f64().unwrap(),
                json["window"]["omega_max"].as_f64().unwrap(),
            ),
        }
    }

    fn at(&self, omega: f64) -> (f64, f64) {
        self.series.at(omega)
    }

    fn log_shift(&self, t: f64) -> f64 {
        wlf(t, self.t_ref, self.c1, self.c2)
    }

    /// A shear DMA CSV (ν = 0.5: G = E/3) of this curve at `temperatures`,
    /// 0.1 to 100 rad/s, E*(ω, T) = E*_ref(ω a_T).
    fn shear_csv(&self, temperatures: &[f64]) -> String {
        let mut csv = String::from(
            "# made by compare_cli from the fit's own curve\nT_C,omega_rad_s,G_storage_Pa,G_loss_Pa\n",
        );
        for &t in temperatures {
            let a_t = 10f64.powf(self.log_shift(t));
            for j in 0..13 {
                let omega = 0.1 * 10f64.powf(j as f64 / 4.0);
                let (s, l) = self.at(omega * a_t);
                csv.push_str(&format!("{t},{omega:e},{:e},{:e}\n", s / 3.0, l / 3.0));
            }
        }
        csv
    }
}

fn run(fit: &Path, dma: &Path, extra: &[&str]) -> std::process::Output {
    let mut list: Vec<&OsStr> = vec![OsStr::new("compare"), fit.as_os_str(), dma.as_os_str()];
    list.extend(extra.iter().map(OsStr::new));
    rollfit(&list)
}

fn compare_json(fit: &Path) -> serde_json::Value {
    serde_json::from_str(&fs::read_to_string(fit.join("compare.json")).unwrap()).unwrap()
}

#[test]
fn the_fits_own_curve_at_three_temperatures_matches() {
    let dir = TempDir::new("own");
    let fit = copy_fit(&dir, "hn-rubber-tset");
    let master = Master::read(&fit);
    let dma = dir.write("dma.csv", master.shear_csv(&[0.0, 20.0, 40.0]));
    let out = run(&fit, &dma, &[]);
    let stderr = text(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let stdout = text(&out.stdout);
    for key in KEYS {
        assert!(stdout.contains(key), "{key} not in the table:\n{stdout}");
    }
    assert!(stderr.contains("G′, G″ converted to Young's"), "{stderr}");
    let json = compare_json(&fit);
    for key in KEYS {
        assert!(json[key].is_number(), "{key}: {}", json[key]);
    }
    // All 39 reduced frequencies lie in the fit's window (checked here).
    let inside = [0.0, 20.0, 40.0]
        .iter()
        .flat_map(|&t| {
            let a_t = 10f64.powf(master.log_shift(t));
            (0..13).map(move |j| 0.1 * 10f64.powf(j as f64 / 4.0) * a_t)
        })
        .filter(|w| *w >= master.window.0 && *w <= master.window.1)
        .count();
    assert_eq!(json["n_points"], inside as u64);
    assert_eq!(inside, 39);
    for key in &KEYS[3..9] {
        let v = json[key].as_f64().unwrap();
        assert!(v < 1e-9, "{key} = {v}");
    }
    assert_eq!(json["modulus_kind"], "shear");
    assert_eq!(json["dma_format"], "csv");
    assert_eq!(json["dma_shift"].as_array().unwrap().len(), 3);
}

#[test]
fn a_trios_export_and_the_dma_wlf_flag() {
    let dir = TempDir::new("trios");
    let fit = copy_fit(&dir, "hn-rubber-tset");
    let fixture = root().join("crates/io/tests/fixtures/trios_shear_two_steps.txt");
    let out = run(&fit, &fixture, &["--dma-wlf", "20,8.86,101.6"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let json = compare_json(&fit);
    assert_eq!(json["dma_format"], "trios-lims");
    assert_eq!(json["dma_points"], 10);
    assert!(text(&out.stderr).contains("DMA's WLF"));
    // Told it is tensile, the moduli are three times smaller.
    let out = run(&fit, &fixture, &["--dma-modulus", "young"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert_eq!(compare_json(&fit)["modulus_kind"], "young");
}

#[test]
fn several_temperatures_on_a_single_temperature_fit_need_the_dma_wlf() {
    let dir = TempDir::new("nowlf");
    let tset = copy_fit(&dir, "hn-rubber-tset");
    let fit = copy_fit(&dir, "hn-rubber");
    let dma = dir.write("dma.csv", Master::read(&tset).shear_csv(&[0.0, 20.0]));
    let out = run(&fit, &dma, &[]);
    assert_failure(
        &out,
        &["dma.csv", "2 temperatures", "--dma-wlf T_REF,C1,C2"],
    );
    assert!(!fit.join("compare.json").exists());
    let out = run(&fit, &dma, &["--dma-wlf", "20,8.86,101.6"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(fit.join("compare.json").exists());
}

#[test]
fn bad_dma_files_and_flags_are_refused_and_nothing_is_written() {
    let dir = TempDir::new("bad");
    let fit = copy_fit(&dir, "hn-rubber-tset");
    let no_loss = dir.write("noloss.csv", "omega,E_storage\n1,1e6\n");
    assert_failure(
        &run(&fit, &no_loss, &[]),
        &[
            "noloss.csv",
            "no E_loss column",
            "the header has: omega, E_storage",
        ],
    );
    let wrong = dir.write(
        "wrong.csv",
        "omega,E_storage,E_loss\n1,1e6,1e5\n2,1e6,oops\n",
    );
    assert_failure(
        &run(&fit, &wrong, &[]),
        &["wrong.csv, line 3", "column 3 (E_loss)", "oops"],
    );
    assert_failure(
        &run(&fit, &dir.path().join("absent.csv"), &[]),
        &["absent.csv"],
    );
    let good = dir.write("good.csv", "omega,E_storage,E_loss\n1,1e6,1e5\n");
    assert_failure(
        &run(&fit, &good, &["--dma-wlf", "20,8.86"]),
        &["--dma-wlf", "T_REF,C1,C2"],
    );
    assert_failure(
        &run(&fit, &good, &["--dma-modulus", "bulk"]),
        &["--dma-modulus"],
    );
    assert_failure(
        &run(&dir.path().join("nofit"), &good, &[]),
        &["nofit", "not a fit directory"],
    );
    assert!(!fit.join("compare.json").exists());
}

/// A relaxation file against a fit: the fit's series is
/// converted to E(t) = E0 + Σ H_k e^(−t/τ_k) and compared over the times
/// its window determines. Data made from that very series (as G = E/3 in
/// kPa) compare to rounding; the same data 10 % stiffer show the fit 9.1 % (1/1.1) softer.
#[test]
fn relaxation_data_compare_as_e_of_t() {
    let dir = TempDir::new("relaxation");
    let fit = copy_fit(&dir, "hn-rubber");
    let series = rollfit_io::FitDir::read(&fit).unwrap().master_curve;
    let write = |name: &str, factor: f64| {
        let mut text = String::from("t_s,G_relax_kPa\n");
        for j in 0..=80 {
            let t = 10f64.powf(-8.0 + 0.1 * j as f64);
            let g = factor * series.relaxation_modulus(t) / 3.0 / 1e3;
            text += &format!("{t:e},{g:e}\n");
        }
        dir.write(name, &text)
    };
    for (factor, expected) in [(1.0f64, 0.0f64), (1.1, 1.0 / 1.1 - 1.0)] {
        let data = write(&format!("relax-{factor}.csv"), factor);
        let out = rollfit(&[OsStr::new("compare"), fit.as_os_str(), data.as_os_str()]);
        assert!(out.status.success(), "{}", text(&out.stderr));
        let json: serde_json::Value =
            serde_json::from_slice(&fs::read(fit.join("compare.json")).unwrap()).unwrap();
        assert_eq!(json["dma_format"], "csv-relaxation");
        assert!(json["n_points"].as_u64().unwrap() > 10, "{json}");
        let max = json["E_relax_max_rel"].as_f64().unwrap();
        let rms = json["E_relax_rms_rel"].as_f64().unwrap();
        assert!((max - expected.abs()).abs() < 1e-6, "{json}");
        assert!((rms - expected.abs()).abs() < 1e-6, "{json}");
    }
}

/// Several relaxation files, one per temperature with the temperature in
/// the name, compare exactly as one file holding the same points with a T
/// column: the same compare.json but for the input's name.
#[test]
fn relaxation_files_compare_as_one_file() {
    let dir = TempDir::new("relaxation-files");
    let fit = copy_fit(&dir, "hn-rubber-tset");
    let series = rollfit_io::FitDir::read(&fit).unwrap().master_curve;
    let rows = |t_celsius: f64| -> Vec<(f64, f64)> {
        (0..=40)
            .map(|j| {
                let t = 10f64.powf(-6.0 + 0.15 * j as f64);
                (
                    t,
                    series.relaxation_modulus(t * (1.0 + 0.01 * t_celsius)) / 1e6,
                )
            })
            .collect()
    };
    let mut one = String::from("t_s,E_relax_MPa,T\n");
    fs::create_dir_all(dir.path().join("parts")).unwrap();
    for temperature in [20.0, 40.0] {
        let mut own = String::from("t_s,E_relax_MPa\n");
        for (t, e) in rows(temperature) {
            one += &format!("{t:e},{e:e},{temperature}\n");
            own += &format!("{t:e},{e:e}\n");
        }
        dir.write(&format!("parts/relax_{temperature}C.csv"), &own);
    }
    let single = dir.write("relax_all.csv", &one);
    let compared = |data: &Path| -> serde_json::Value {
        let out = rollfit(&[OsStr::new("compare"), fit.as_os_str(), data.as_os_str()]);
        assert!(out.status.success(), "{}", text(&out.stderr));
        // Each names its own input; the rest must agree.
        let named = fs::read_to_string(fit.join("compare.json"))
            .unwrap()
            .replace(&data.display().to_string(), "DATA");
        let mut json: serde_json::Value = serde_json::from_str(&named).unwrap();
        json.as_object_mut().unwrap().remove("dma_file");
        json
    };
    let from_one = compared(&single);
    let from_parts = compared(&dir.path().join("parts"));
    // Each file's temperature, and where it came from, is said.
    let out = rollfit(&[
        OsStr::new("compare"),
        fit.as_os_str(),
        dir.path().join("parts").as_os_str(),
    ]);
    let said = text(&out.stderr);
    assert!(
        said.contains("relax_40C.csv: 41 points, 40 °C, from the file name"),
        "{said}"
    );
    assert!(from_one["n_points"].as_u64().unwrap() > 10, "{from_one}");
    assert_eq!(from_one, from_parts);
    // A frequency sweep among them is named as what it is.
    dir.write(
        "parts/sweep_60C.csv",
        "f,E_storage,E_loss\n1,1e6,1e5\n10,2e6,2e5\n",
    );
    assert_failure(
        &run(&fit, &dir.path().join("parts"), &[]),
        &["sweep_60C.csv", "not relaxation or creep data"],
    );
}

/// A creep file against a fit: the fit's series is
/// converted to its exact creep compliance D(t) (retardation times from
/// the zeros of its Laplace transform) and compared over the times its
/// window determines. Shear data made from that compliance
/// (J = 2(1+ν) D, in 1/MPa) compare to rounding; the same data 10 % more
/// compliant show the fit's D 9.1 % (1/1.1) lower.
#[test]
fn creep_data_compare_as_d_of_t() {
    let dir = TempDir::new("creep");
    let fit = copy_fit(&dir, "hn-rubber");
    let read = rollfit_io::FitDir::read(&fit).unwrap();
    let creep = rollfit_model::exact::CreepCompliance::from_prony(&read.master_curve);
    let shear = 2.0 * (1.0 + read.summary.poisson);
    let write = |name: &str, factor: f64| {
        let mut text = String::from("time (s),Creep Compliance (1/MPa)\n");
        for j in 0..=80 {
            let t = 10f64.powf(-8.0 + 0.1 * j as f64);
            let j_mpa = factor * shear * creep.at(t) * 1e6;
            text += &format!("{t:e},{j_mpa:e}\n");
        }
        dir.write(name, &text)
    };
    for (factor, expected) in [(1.0f64, 0.0f64), (1.1, 1.0 / 1.1 - 1.0)] {
        let data = write(&format!("creep-{factor}.csv"), factor);
        let out = rollfit(&[OsStr::new("compare"), fit.as_os_str(), data.as_os_str()]);
        assert!(out.status.success(), "{}", text(&out.stderr));
        assert!(text(&out.stdout).contains("D_creep_rms_rel"));
        let json: serde_json::Value =
            serde_json::from_slice(&fs::read(fit.join("compare.json")).unwrap()).unwrap();
        assert_eq!(json["dma_format"], "csv-creep");
        assert!(json.get("E_relax_rms_rel").is_none(), "{json}");
        assert!(json["n_points"].as_u64().unwrap() > 10, "{json}");
        let max = json["D_creep_max_rel"].as_f64().unwrap();
        let rms = json["D_creep_rms_rel"].as_f64().unwrap();
        assert!((max - expected.abs()).abs() < 1e-6, "{json}");
        assert!((rms - expected.abs()).abs() < 1e-6, "{json}");
    }
}
