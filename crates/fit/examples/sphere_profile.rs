// SCRATCH (not for commit): profile the σ = 0.1 % sphere fit.
#[path = "../tests/common/mod.rs"]
mod common;
use common::{BothPhysics, broad_rubber, exact_and_approximate, setup, window_errors, with_noise};
use rollfit_fit::{FitParams, Physics, ScaleAnchor, fit};

fn truth() -> BothPhysics {
    let path = "/tmp/sphere_truth_1e-4.txt";
    if let Ok(s) = std::fs::read_to_string(path) {
        let rows: Vec<Vec<f64>> = s
            .lines()
            .map(|l| l.split(' ').map(|x| x.parse().unwrap()).collect())
            .collect();
        return BothPhysics {
            speeds: rows.iter().map(|r| r[0]).collect(),
            approximate: rows.iter().map(|r| r[1]).collect(),
            exact: rows.iter().map(|r| r[2]).collect(),
        };
    }
    let t = std::time::Instant::now();
    let d = exact_and_approximate(setup(), &broad_rubber(), 1e-4).unwrap();
    eprintln!("truth in {:.1} s", t.elapsed().as_secs_f64());
    let s: String = (0..41)
        .map(|i| {
            format!(
                "{:e} {:e} {:e}\n",
                d.speeds[i], d.approximate[i], d.exact[i]
            )
        })
        .collect();
    std::fs::write(path, s).unwrap();
    d
}

fn main() {
    let d = truth();
    let noise: f64 = std::env::args()
        .nth(1)
        .map(|s| s.parse().unwrap())
        .unwrap_or(0.001);
    let params = |physics| {
        FitParams {
            anchor: Some(ScaleAnchor::StaticModulus(2e6)),
            physics,
            ..FitParams::default()
        }
        .check(setup())
        .unwrap()
    };
    let measured = with_noise(&d.speeds, &d.exact, noise, 1);
    let reference = fit(
        &with_noise(&d.speeds, &d.approximate, noise, 1),
        &params(Physics::Approximate),
    )
    .unwrap();
    let r = fit(&measured, &params(Physics::Exact)).unwrap();
    let truth = broad_rubber();
    let (rt, rm, _) = window_errors(&reference, &truth);
    let (ct, cm, _) = window_errors(&r, &truth);
    let p = r.physics.as_ref().unwrap();
    eprintln!(
        "σ {noise}: refits {} solves {} converged {} last_change {:.2e} max_err_est {:.2e} wall {:.1} s",
        p.iterations,
        p.exact_solves,
        p.converged,
        p.last_change,
        p.max_error_estimate,
        r.wall_time_s
    );
    eprintln!(
        "reference {:.3}% / {:.3}%  corrected {:.3}% / {:.3}%  ratios {:.3} / {:.3}",
        100.0 * rt,
        100.0 * rm,
        100.0 * ct,
        100.0 * cm,
        ct / rt,
        cm / rm
    );
    for w in &r.warnings {
        eprintln!("warning: {w}");
    }
}
