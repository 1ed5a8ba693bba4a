//! End-to-end tests of negative numbers on the command line as users type
//! them: `rollfit master FILE --T-ref -5` and `rollfit report
//! DIR --dma-wlf -5,11.6,79.9`, which clap once refused as "unexpected
//! argument '-5'". Each runs the binary on files made here and checks that
//! the value reached the computation, not only that the exit status is 0.

use crate::common;

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};

use common::{Table, TempDir, succeed};
use rollfit_model::ViscoelasticModulus;
use rollfit_testkit::materials::hn_rubber;

/// WLF of the synthetic isotherms about −5 °C.
const T_REF: f64 = -5.0;
const C1: f64 = 11.6;
const C2: f64 = 79.9;

fn wlf(t: f64) -> f64 {
    -C1 * (t - T_REF) / (C2 + t - T_REF)
}

/// A Young's-modulus DMA CSV of noiseless isotherms at `temps` (°C) of a
/// broad rubber shifted by [`wlf`], `count` frequencies over 0.1…100 rad/s.
fn isotherms_csv(temps: &[f64], count: usize) -> String {
    let master = hn_rubber();
    let mut out = String::from("T,omega,E_storage,E_loss\n");
    for &t in temps {
        let a = 10f64.powf(wlf(t));
        for i in 0..count {
            let w = 0.1 * 10f64.powf(3.0 * i as f64 / (count - 1) as f64);
            let e = master.modulus(w * a);
            out += &format!("{t},{w:e},{:e},{:e}\n", e.re, e.im);
        }
    }
    out
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&fs::read_to_string(path).unwrap()).unwrap()
}

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `master --T-ref -5`: the master curve is at −5 °C (master.json), where
/// the applied shift is zero, and the measured shifts follow the WLF the
/// isotherms were made with.
#[test]
fn master_takes_a_negative_reference_temperature() {
    let tmp = TempDir::new("master");
    let temps = [-20.0, -10.0, -5.0, 0.0, 10.0];
    let dma = tmp.write("iso.csv", isotherms_csv(&temps, 16));
    let dir = tmp.path().join("master");
    succeed(&[
        OsStr::new("master"),
        dma.as_os_str(),
        OsStr::new("-o"),
        dir.as_os_str(),
        OsStr::new("--T-ref"),
        OsStr::new("-5"),
    ]);
    assert_eq!(
        json(&dir.join("master.json"))["T_ref"].as_f64(),
        Some(T_REF)
    );
    let shift = Table::read(&dir.join("shift.csv"));
    let (t, log_a) = (shift.column("T"), shift.column("log_aT"));
    let at_ref = t.iter().position(|&x| x == T_REF).expect("the −5 °C row");
    assert!(
        log_a[at_ref].abs() < 1e-9,
        "log a_T(T_ref) = {}",
        log_a[at_ref]
    );
    for (&t, &log_a) in t.iter().zip(&log_a) {
        assert!(
            (log_a - wlf(t)).abs() < 0.1,
            "T = {t}: log a_T {log_a} against {}",
            wlf(t)
        );
    }
}

/// `report --dma-wlf -5,11.6,79.9` on a copy of the committed
/// single-temperature fit with isotherms at −5 and 10 °C: the report
/// succeeds, and compare.json records the 10 °C isotherm moved by
/// W(10) − W(−5) = W(10) (a single-temperature fit is taken at the DMA's
/// T_ref), which only a T_ref of −5 gives.
#[test]
fn report_takes_a_negative_dma_wlf_reference() {
    let tmp = TempDir::new("report");
    let fit = tmp.path().join("fit");
    fs::create_dir_all(&fit).unwrap();
    for file in ["fit.json", "mu.csv", "modulus.csv"] {
        fs::copy(
            workspace().join("examples/fits/hn-rubber").join(file),
            fit.join(file),
        )
        .unwrap();
    }
    let dma = tmp.write("dma.csv", isotherms_csv(&[-5.0, 10.0], 13));
    succeed(&[
        OsStr::new("report"),
        fit.as_os_str(),
        OsStr::new("--dma"),
        dma.as_os_str(),
        OsStr::new("--dma-wlf"),
        OsStr::new("-5,11.6,79.9"),
    ]);
    let compare = json(&fit.join("compare.json"));
    let shifts = compare["dma_shift"].as_array().expect("dma_shift");
    let warm = shifts
        .iter()
        .find(|s| s["T"].as_f64() == Some(10.0))
        .unwrap_or_else(|| panic!("no 10 °C isotherm in {shifts:?}"));
    let log_a = warm["log_aT"].as_f64().expect("log_aT");
    assert!(
        (log_a - wlf(10.0)).abs() < 1e-12,
        "{log_a} against {}",
        wlf(10.0)
    );
}
