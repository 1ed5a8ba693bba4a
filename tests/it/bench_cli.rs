//! End-to-end test of `rollfit bench --quick`: both CSVs have their
//! columns and one row per measured setting, the charts decode, and the
//! measured behaviour is the documented one — the dynamic rung's error
//! falls as the tolerance tightens, the static rung's stays at its model
//! error, Levenberg–Marquardt converges where Nelder–Mead on a small
//! budget does not.

use crate::common;

use std::fs;
use std::path::{Path, PathBuf};

use common::{TempDir, rollfit_in, text};

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Rows of a CSV whose first column is text: (label, numbers).
fn labelled(path: &Path) -> (Vec<String>, Vec<(String, Vec<String>)>) {
    let content = fs::read_to_string(path).unwrap();
    let mut lines = content.lines().filter(|l| !l.starts_with('#'));
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
            "setting",
            "time_per_mu_s",
            "max_rel_error",
            "rms_rel_error",
            "numerical_rel_error"
        ]
    );
    let first = fs::read_to_string(tmp.path().join("forward.csv")).unwrap();
    assert!(first.starts_with("# errors against the exact rolling cylinder"));
    // Numbers after the setting: time, max error, rms error, numerical error.
    let rung = |name: &str| -> Vec<(String, Vec<f64>)> {
        rows.iter()
            .filter(|(l, _)| l == name)
            .map(|(_, f)| {
                let numbers = f[1..].iter().map(|x| x.parse::<f64>().unwrap()).collect();
                (f[0].clone(), numbers)
            })
            .collect()
    };
    let (asymptote, static_rung, dynamic, exact) = (
        rung("asymptote"),
        rung("static"),
        rung("dynamic"),
        rung("exact"),
    );
    assert_eq!(
        (
            asymptote.len(),
            static_rung.len(),
            dynamic.len(),
            exact.len()
        ),
        (1, 2, 2, 2)
    );
    for (_, r) in asymptote
        .iter()
        .chain(&static_rung)
        .chain(&dynamic)
        .chain(&exact)
    {
        assert!(r[0] > 0.0 && r[0] < 0.1, "time per μ {} s", r[0]);
    }
    // Against the exact cylinder: Eq. (11) keeps its model error (a few
    // per cent near the maximum for E1/E0 = 10) whatever the tolerance,
    // while its quadrature error alone falls; the static contact size is
    // far off; the exact solution at its automatic N is converged.
    assert!(
        dynamic.iter().all(|(_, r)| r[1] > 0.01 && r[1] < 0.1),
        "{dynamic:?}"
    );
    assert!(dynamic[1].1[3] <= dynamic[0].1[3] && dynamic[1].1[3] < 1e-3);
    assert!(
        static_rung.iter().all(|(_, r)| r[1] > 0.2),
        "{static_rung:?}"
    );
    assert!(
        asymptote[0].1[1] < 0.05,
        "asymptote well below the peak: {asymptote:?}"
    );
    assert_eq!(
        (exact[0].0.as_str(), exact[1].0.as_str()),
        ("N = 16", "N auto")
    );
    assert!(
        exact[1].1[1] < 1e-5 && exact[1].1[1] < exact[0].1[1],
        "{exact:?}"
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
