//! Crashes, hangs and wrong answers with exit 0 that real
//! files caused: each input is a synthetic replica of the shape that broke,
//! and each test asserts the message that now names the cause.

use crate::common;
use rollfit_testkit::workbook;

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use common::{TempDir, assert_failure, copy_tree, rollfit};
use workbook::X;

fn repo(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .join(name)
}

fn run(args: &[&dyn AsRef<OsStr>]) -> Output {
    let args: Vec<&OsStr> = args.iter().map(|a| a.as_ref()).collect();
    rollfit(&args)
}

/// Runs rollfit with `args`, killed after `limit`: None when it ran that
/// long (a hang).
fn run_within(args: &[&dyn AsRef<OsStr>], limit: Duration) -> Option<Output> {
    let mut child = Command::new(env!("CARGO_BIN_EXE_rollfit"))
        .args(args.iter().map(|a| a.as_ref()))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("cannot start the rollfit binary");
    let start = Instant::now();
    while start.elapsed() < limit {
        if child.try_wait().unwrap().is_some() {
            return Some(child.wait_with_output().unwrap());
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let _ = child.kill();
    let _ = child.wait();
    None
}

/// F1: a T_ref at the singular temperature of the shift law (WLF of the
/// bundled isotherms: −81.6 °C; Arrhenius: absolute zero) is refused naming
/// T_ref, the singular temperature and the measured range, in `master`
/// and in a scene's `model = "dma"`; nothing is written.
#[test]
fn t_ref_at_a_singular_temperature_is_refused_naming_it() {
    let tmp = TempDir::new("tref-singular");
    let dma = repo("data/hn-rubber-dma-isotherms.csv");
    let out = tmp.path().join("m");
    let cases: [(&[&str], &[&str]); 3] = [
        (
            &["--T-ref", "-81.6", "--shift", "wlf"],
            &[
                "T_ref = -81.6 °C",
                "singular at",
                "measured from -20 to 60 °C",
            ],
        ),
        (
            &["--T-ref", "-80", "--shift", "wlf"],
            &[
                "T_ref = -80 °C",
                "singular at",
                "measured from -20 to 60 °C",
            ],
        ),
        (
            &["--T-ref", "-260", "--shift", "arrhenius"],
            &[
                "T_ref = -260 °C",
                "absolute zero",
                "measured from -20 to 60 °C",
            ],
        ),
    ];
    for (extra, expected) in cases {
        let mut args: Vec<&dyn AsRef<OsStr>> = vec![&"master", &dma, &"-o", &out];
        args.extend(extra.iter().map(|e| e as &dyn AsRef<OsStr>));
        assert_failure(&run(&args), expected);
        assert!(!out.exists(), "{extra:?}: a folder was written");
    }
    let scene = tmp.write(
        "scene.toml",
        format!(
            "[geometry]\nshape = \"sphere\"\nradius = 0.005\nload = 1.0\n[substrate]\npoisson = \
             0.5\n[material]\nmodel = \"dma\"\nfile = {dma:?}\nT_ref = -81.6\nshift_law = \"wlf\"\n[sweep]\nv_min = \
             1e-6\nv_max = 1.0\ncount = 5\n"
        ),
    );
    let csv = tmp.path().join("mu.csv");
    assert_failure(
        &run(&[&"forward", &scene, &"-o", &csv]),
        &["T_ref = -81.6 °C", "singular at"],
    );
    assert!(!csv.exists());
}

/// The CSV `path` (comment lines dropped) as the rows of a sheet.
fn sheet_rows(path: &Path) -> Vec<Vec<X<'static>>> {
    let text = fs::read_to_string(path).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&'static str> = lines
        .next()
        .unwrap()
        .split(',')
        .map(|h| &*Box::leak(h.to_string().into_boxed_str()))
        .collect();
    let mut rows = vec![workbook::texts(&header)];
    rows.extend(lines.map(|l| {
        l.split(',')
            .map(|c| X::N(c.trim().parse().unwrap()))
            .collect()
    }));
    rows
}

/// F2, F3: a workbook with one stray cell far below and right of its data
/// (XFD1048576: a sheet extent of 1.7e10 cells, CZ1048576) is read from
/// its cells, not its extent, by `master`, by `fit` (rolling data and
/// `--dma`) and by `compare` — where it aborted on a 512 GiB allocation or
/// took 7 GB: each names the stray row (a row skipped, or a value beyond
/// the header's columns refused) and ends with status 0 or 1. Time and
/// memory are measured in BENCHMARKS.md.
#[test]
fn a_stray_cell_far_from_the_data_is_refused_from_its_cells() {
    let tmp = TempDir::new("stray-cell");
    let dma_rows = sheet_rows(&repo("data/hn-rubber-dma-isotherms.csv"));
    let mu_rows = sheet_rows(&repo("data/hn-rubber.csv"));
    let fit_dir = tmp.path().join("fit");
    copy_tree(&repo("examples/fits/hn-rubber-tset"), &fit_dir);
    let scene = repo("data/hn-rubber.toml");
    let joint = repo("data/hn-rubber-joint.toml");
    let tset = repo("data/hn-rubber-tset.csv");
    for at in ["XFD1048576", "CZ1048576"] {
        let dma = tmp.path().join(format!("dma-{at}.xlsx"));
        fs::write(
            &dma,
            workbook::xlsx_with_stray(&[("DMA", dma_rows.clone())], Some(at)),
        )
        .unwrap();
        let mu = tmp.path().join(format!("mu-{at}.xlsx"));
        fs::write(
            &mu,
            workbook::xlsx_with_stray(&[("Data", mu_rows.clone())], Some(at)),
        )
        .unwrap();
        let out = tmp.path().join("out");
        let runs: [Vec<&dyn AsRef<OsStr>>; 4] = [
            vec![&"master", &dma, &"-o", &out],
            vec![&"fit", &scene, &mu, &"-o", &out],
            vec![&"fit", &joint, &tset, &"--dma", &dma, &"-o", &out],
            vec![&"compare", &fit_dir, &dma],
        ];
        for args in runs {
            let started = Instant::now();
            let result = run(&args);
            let stderr = String::from_utf8_lossy(&result.stderr);
            assert!(
                matches!(result.status.code(), Some(0 | 1)),
                "{at}: {:?}\n{stderr}",
                result.status
            );
            assert!(stderr.contains("row 1048576"), "{at}:\n{stderr}");
            assert!(
                started.elapsed() < Duration::from_secs(60),
                "{at}: took {:?}",
                started.elapsed()
            );
            if !result.status.success() {
                assert!(!out.exists(), "{at}: output written on a failure");
            }
            let _ = fs::remove_dir_all(&out);
        }
    }
}

/// F4: a joint fit whose one DMA isotherm lies below the WLF singularity
/// of the rolling data (−95 °C against −81.6 °C) ends with a message
/// instead of looping in the SVD.
#[test]
fn a_dma_isotherm_below_the_wlf_singularity_does_not_hang_the_joint_fit() {
    let tmp = TempDir::new("joint-below-singular");
    let text = fs::read_to_string(repo("data/hn-rubber-dma-isotherms.csv")).unwrap();
    let mut csv = String::from("f,G_storage,G_loss,T\n");
    for line in text.lines().filter(|l| l.ends_with(",-20")) {
        csv += &line.replace(",-20", ",-95");
        csv += "\n";
    }
    let dma = tmp.write("cold.csv", &csv);
    let out = tmp.path().join("out");
    let result = run_within(
        &[
            &"fit",
            &repo("data/hn-rubber-joint.toml"),
            &repo("data/hn-rubber-tset.csv"),
            &"--dma",
            &dma,
            &"--shift",
            &"wlf",
            &"-o",
            &out,
        ],
        Duration::from_secs(300),
    )
    .expect("the joint fit still ran after 300 s");
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    if !result.status.success() {
        assert!(stderr.contains("error:"), "{stderr}");
        assert!(!out.exists());
    }
}

/// A relaxation CSV of `rows` (t in s, E(t) in Pa) at one temperature.
fn relaxation(tmp: &TempDir, name: &str, rows: &[(f64, f64)]) -> PathBuf {
    let mut text = String::from("t_s,E_relax,T\n");
    for (t, e) in rows {
        text += &format!("{t:e},{e:e},20\n");
    }
    tmp.write(name, &text)
}

/// F5: relaxation times of 1e300 s or 1e-300 s are refused naming the
/// line, at once (they took 70 s and ended in a NaN naming no input).
#[test]
fn relaxation_times_outside_any_measurement_are_refused_naming_the_line() {
    let tmp = TempDir::new("relaxation-times");
    for (bad, shown) in [(1e300, "t = 1e300 s"), (1e-300, "t = 1e-300 s")] {
        let mut rows: Vec<(f64, f64)> = (0..20)
            .map(|k| {
                (
                    10f64.powf(k as f64 / 4.0),
                    1e6 * (1.0 + 1.0 / (1.0 + k as f64)),
                )
            })
            .collect();
        if bad > 1.0 {
            rows[19].0 = bad;
        } else {
            rows[0].0 = bad;
        }
        let file = relaxation(&tmp, "times.csv", &rows);
        let out = tmp.path().join("m");
        let started = Instant::now();
        let line = if bad > 1.0 { "line 21" } else { "line 2" };
        assert_failure(
            &run(&[&"master", &file, &"-o", &out]),
            &["times.csv", line, shown, "outside 1e-30 … 1e30 s"],
        );
        assert!(started.elapsed() < Duration::from_secs(20));
        assert!(!out.exists());
    }
}

/// F6: E(t) that rises three decades over the run is no relaxation
/// modulus: the verdict is poor (nothing written) with the series' misfit
/// named, where it was "good" with a flat series 0.97 decades off.
#[test]
fn a_rising_relaxation_modulus_gets_a_poor_verdict() {
    let tmp = TempDir::new("relaxation-rising");
    let rows: Vec<(f64, f64)> = (0..=30)
        .map(|k| {
            let x = k as f64 / 10.0;
            (10f64.powf(x), 1e5 * 10f64.powf(x))
        })
        .collect();
    let file = relaxation(&tmp, "rising.csv", &rows);
    let out = tmp.path().join("m");
    assert_failure(
        &run(&[&"master", &file, &"-o", &out]),
        &["misses E(t) by", "never rises with time"],
    );
    assert!(!out.exists());
    // The same run falling as a relaxation modulus does stays good.
    let falling: Vec<(f64, f64)> = rows.iter().map(|&(t, e)| (t, 1e13 / e)).collect();
    let file = relaxation(&tmp, "falling.csv", &falling);
    let result = run(&[&"master", &file, &"-o", &out]);
    let stderr = String::from_utf8_lossy(&result.stderr);
    assert!(result.status.success(), "{stderr}");
}

/// F7: DMA moduli in MPa under Pa headers are refused by `master` as the
/// joint fit refuses them, naming the isotherm, the point and the unit.
#[test]
fn moduli_in_mpa_under_pa_headers_are_refused_by_master() {
    let tmp = TempDir::new("mpa-as-pa");
    let text = fs::read_to_string(repo("data/hn-rubber-dma-isotherms.csv")).unwrap();
    let mut csv = String::new();
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        let cells: Vec<&str> = line.split(',').collect();
        match cells[1].parse::<f64>() {
            Ok(g1) => {
                let g2: f64 = cells[2].parse().unwrap();
                csv += &format!("{},{:e},{:e},{}\n", cells[0], g1 / 1e6, g2 / 1e6, cells[3]);
            }
            Err(_) => csv += &format!("{line}\n"),
        }
    }
    let file = tmp.write("mpa.csv", &csv);
    let out = tmp.path().join("m");
    assert_failure(
        &run(&[&"master", &file, &"-o", &out]),
        &[
            "mpa.csv",
            "must lie in 1 … 1e13 Pa",
            "is the modulus in Pa?",
        ],
    );
    assert!(!out.exists());
}

/// The bundled temperature-set truth with `from` replaced by `to`.
fn truth_scene(tmp: &TempDir, name: &str, from: &str, to: &str) -> PathBuf {
    let text = fs::read_to_string(repo("data/hn-rubber-tset-truth.toml")).unwrap();
    assert!(text.contains(from), "{from}");
    tmp.write(name, text.replace(from, to))
}

/// F9: `forward` refuses a sweep temperature the data reader would refuse
/// (1e300 °C, 1001 °C), naming the key.
#[test]
fn sweep_temperatures_outside_the_data_readers_range_are_refused() {
    let tmp = TempDir::new("sweep-temperature");
    let line = "temperature = [-20.0, 0.0, 20.0, 40.0, 60.0]";
    for (value, expected) in [
        (
            "[1e300]",
            "temperature[0] = 1e300 °C must be at most 1000 °C",
        ),
        (
            "[20.0, 1001.0]",
            "temperature[1] = 1001 °C must be at most 1000 °C",
        ),
    ] {
        let scene = truth_scene(&tmp, "hot.toml", line, &format!("temperature = {value}"));
        let csv = tmp.path().join("mu.csv");
        assert_failure(
            &run(&[&"forward", &scene, &"-o", &csv]),
            &["hot.toml", "[sweep]", expected],
        );
        assert!(!csv.exists());
    }
}

/// F14: a WLF fit whose T_ref lies far below the measured temperatures
/// (below the data's WLF singularity) or whose T column is in kelvin is
/// refused naming T_ref, the measured range and what to do, not "a shift
/// factor outside the floating-point range".
#[test]
fn a_wlf_shift_that_cannot_reach_t_ref_names_t_ref_and_the_range() {
    let tmp = TempDir::new("wlf-range");
    let scene = fs::read_to_string(repo("data/hn-rubber-tset.toml")).unwrap();
    let data = repo("data/hn-rubber-tset.csv");
    let out = tmp.path().join("out");
    let cold = tmp.write(
        "cold.toml",
        scene.replace("T_ref = 20.0 ", "T_ref = -150.0 "),
    );
    assert_failure(
        &run(&[&"fit", &cold, &data, &"-o", &out]),
        &[
            "T_ref = -150 °C",
            "130.0 K below the measured temperatures (-20 to 60 °C)",
            "Choose T_ref inside the measured range",
        ],
    );
    assert!(!out.exists());
}

/// F17: a scene's `[material.shift]` WLF whose singularity lies above a
/// measured temperature is refused naming C2 and the singular temperature
/// (not "the contact map is not increasing at ω = 1e231 rad/s").
#[test]
fn a_given_wlf_singular_at_a_measured_temperature_names_c2() {
    let tmp = TempDir::new("wlf-given-singular");
    let scene = truth_scene(&tmp, "c2.toml", "C2 = 101.6 ", "C2 = 30.0 ");
    let out = tmp.path().join("out");
    assert_failure(
        &run(&[
            &"fit",
            &scene,
            &repo("data/hn-rubber-tset.csv"),
            &"-o",
            &out,
        ]),
        &["C2 = 30 K", "T_ref - C2 = -10 °C", "-20 °C"],
    );
    assert!(!out.exists());
}
