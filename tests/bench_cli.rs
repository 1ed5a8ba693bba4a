//! End-to-end test of `rollfit bench --quick`: both CSVs have their
//! columns and one row per measured setting, the charts decode, and the
//! measured behaviour is the documented one — the dynamic rung's error
//! falls as the tolerance tightens, the static rung's stays at its model
//! error, Levenberg–Marquardt converges where Nelder–Mead on a small
//! budget does not.

mod common;

use std::fs;
use std::path::{Path, PathBuf};

use common::{TempDir, rollfit_in, text};

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Rows of a CSV whose first column is text: (label, numbers).
fn labelled(path: &Path) -> (Vec<String>, Vec<(String, Vec<String>)>) {
    let content = fs::read_to_string(path).unwrap();
    let mut lines = content.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| {
            let mut fields = l.split(',').map(str::to_string);
            let label = fields.next().unwrap();
            (label, fields.collect())
        })
        .collect();
    (header, rows)
}

#[test]
fn quick_bench_measures_every_rung_and_method() {
    let tmp = TempDir::new("bench");
    let out = rollfit_in(
        Some(&workspace()),
        &[
            "bench".as_ref(),
            "--quick".as_ref(),
            "-o".as_ref(),
            tmp.path().as_os_str(),
        ],
    );
    assert!(out.status.success(), "bench failed: {}", text(&out.stderr));

    let (header, rows) = labelled(&tmp.path().join("forward.csv"));
    assert_eq!(
        header,
        [
            "rung",
            "tolerance",
            "time_per_mu_s",
            "max_rel_error",
            "rms_rel_error"
        ]
    );
    let rung = |name: &str| -> Vec<Vec<f64>> {
        rows.iter()
            .filter(|(l, _)| l == name)
            .map(|(_, f)| f.iter().map(|x| x.parse::<f64>().unwrap()).collect())
            .collect()
    };
    let (asymptote, static_rung, dynamic) = (rung("asymptote"), rung("static"), rung("dynamic"));
    assert_eq!(
        (asymptote.len(), static_rung.len(), dynamic.len()),
        (1, 2, 2)
    );
    for r in asymptote.iter().chain(&static_rung).chain(&dynamic) {
        assert!(r[1] > 0.0 && r[1] < 1e-3, "time per μ {} s", r[1]);
    }
    // Tolerance 1e-2 then 1e-3: the dynamic rung converges to the
    // reference; the static rung keeps the static-contact model error.
    assert!(dynamic[0][2] < 1e-2 && dynamic[1][2] <= dynamic[0][2]);
    assert!(
        static_rung[1][2] > 0.1,
        "static vs dynamic: {}",
        static_rung[1][2]
    );
    assert!(
        asymptote[0][2] < 0.05,
        "asymptote well below the peak: {}",
        asymptote[0][2]
    );

    let (header, rows) = labelled(&tmp.path().join("fit.csv"));
    assert_eq!(
        header,
        [
            "method",
            "max_evaluations",
            "wall_time_s",
            "evaluations",
            "tan_delta_rms_rel",
            "converged"
        ]
    );
    let method = |name: &str| rows.iter().filter(|(l, _)| l == name).collect::<Vec<_>>();
    let lm = method("levenberg-marquardt");
    assert_eq!(
        lm.len(),
        1,
        "a converged run is not repeated with larger budgets"
    );
    assert_eq!(lm[0].1[4], "true");
    assert!(lm[0].1[3].parse::<f64>().unwrap() < 0.03, "LM tan δ error");
    let nm = method("nelder-mead");
    assert_eq!(nm.len(), 2);
    assert!(
        nm.iter().all(|(_, f)| f[4] == "false"),
        "Nelder–Mead converged in 300 evaluations?"
    );
    assert_eq!(method("lbfgs").len(), 2);

    for chart in ["forward", "fit"] {
        let bytes = fs::read(tmp.path().join(format!("{chart}.png"))).unwrap();
        let decoder = png::Decoder::new(bytes.as_slice());
        let info = decoder.read_info().unwrap();
        assert_eq!((info.info().width, info.info().height), (900, 620));
        let svg = fs::read_to_string(tmp.path().join(format!("{chart}.svg"))).unwrap();
        roxmltree::Document::parse(&svg).unwrap();
    }
}
