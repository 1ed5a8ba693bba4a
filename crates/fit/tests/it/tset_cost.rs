//! The cost of a temperature set's joint fit: 7 temperatures
//! (−25 … 65 °C, 15 K apart) × 21 speeds (1e-8 … 1 m/s) of the bundled
//! broad rubber under the WLF truth (C1 = 8.86, C2 = 101.6 K at 20 °C),
//! 1 % noise, σ known, |E| at 10 rad/s at T_ref as the anchor; fitted with
//! WLF and with free shifts. Evaluation counts are deterministic (fixed
//! seeds), so they are bounded here; times are not.

use rollfit_testkit::materials::hn_rubber;
use rollfit_testkit::rolling;
use rollfit_testkit::rolling::{set_with_shifts, wlf_truth};

use rollfit_fit::{FitParams, FitReport, Measurements, ScaleAnchor, ShiftKind, ShiftSettings, fit};
use rollfit_model::ViscoelasticModulus;

/// The shape of a synthetic set.
#[derive(Debug, Clone, Copy)]
struct Shape {
    /// `count` speeds over `decades` from `v_min`, m/s.
    v_min: f64,
    decades: f64,
    count: usize,
    /// `temperatures` from `t0` in steps of `step`, °C.
    t0: f64,
    step: f64,
    temperatures: usize,
    /// Relative noise, and whether σ is given.
    noise: f64,
    sigma: bool,
    /// Decades of a sine (period 20π K) added to the WLF truth: shifts no
    /// law describes.
    wiggle: f64,
    /// T_ref, °C (NaN: the middle temperature), where the anchor is.
    t_ref: f64,
}

impl Default for Shape {
    fn default() -> Self {
        Shape {
            v_min: 1e-8,
            decades: 8.0,
            count: 21,
            t0: -25.0,
            step: 15.0,
            temperatures: 7,
            noise: 0.01,
            sigma: true,
            wiggle: 0.0,
            t_ref: 20.0,
        }
    }
}

/// An environment variable's number, else `default`.
fn env(name: &str, default: f64) -> f64 {
    std::env::var(name)
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

impl Shape {
    /// The default shape with the probe's environment variables: VMIN,
    /// DECADES, COUNT, T0, TSTEP, NT, NOISE, SIGMA (0: none), WIGGLE, TREF.
    fn from_env() -> Shape {
        let d = Shape::default();
        Shape {
            v_min: env("VMIN", d.v_min),
            decades: env("DECADES", d.decades),
            count: env("COUNT", d.count as f64) as usize,
            t0: env("T0", d.t0),
            step: env("TSTEP", d.step),
            temperatures: env("NT", d.temperatures as f64) as usize,
            noise: env("NOISE", d.noise),
            sigma: env("SIGMA", 1.0) > 0.0,
            wiggle: env("WIGGLE", d.wiggle),
            t_ref: env("TREF", d.t_ref),
        }
    }

    fn truth(&self, t: f64) -> f64 {
        wlf_truth(t) + self.wiggle * (t / 10.0).sin()
    }

    fn data(&self, seed: u64) -> Measurements {
        let speeds: Vec<f64> = (0..self.count)
            .map(|i| self.v_min * 10f64.powf(self.decades * i as f64 / (self.count - 1) as f64))
            .collect();
        let temps: Vec<f64> = (0..self.temperatures)
            .map(|j| self.t0 + self.step * j as f64)
            .collect();
        let truth = |t: f64| self.truth(t);
        set_with_shifts(
            hn_rubber(),
            &temps,
            &speeds,
            truth,
            self.noise,
            seed,
            self.sigma,
        )
    }

    fn params(&self, kind: ShiftKind) -> rollfit_fit::ValidFitParams {
        let t_ref = self.t_ref.is_finite().then_some(self.t_ref);
        let t_mid = self.t0 + self.step * ((self.temperatures - 1) / 2) as f64;
        let a_ref = 10f64.powf(self.truth(t_ref.unwrap_or(t_mid)));
        FitParams {
            anchor: Some(ScaleAnchor::ModulusAt {
                omega: 10.0,
                modulus: hn_rubber().modulus(10.0 * a_ref).norm(),
            }),
            shift: ShiftSettings {
                kind,
                t_ref,
                cross_check: false,
                ..ShiftSettings::default()
            },
            ..FitParams::default()
        }
        .check(rolling::setup())
        .unwrap()
    }
}

fn total_evaluations(report: &FitReport) -> usize {
    report.runs.iter().map(|r| r.evaluations).sum()
}

fn print_runs(label: &str, report: &FitReport) {
    for r in &report.runs {
        eprintln!(
            "{label}: {:<40} λ {:.3e} it {:>5} ev {:>5} V {:.6e} {:.3} s {}",
            r.stage,
            r.lambda,
            r.iterations,
            r.evaluations,
            r.objective,
            r.wall_time_s,
            r.stop_reason
        );
        if r.evaluations > 150 {
            let h = &r.history;
            let step = (h.len() / 12).max(1);
            let points: Vec<String> = h
                .iter()
                .step_by(step)
                .chain(h.last())
                .map(|[e, v]| format!("{e}:{v:.6e}"))
                .collect();
            eprintln!("    history {}", points.join(" "));
        }
    }
}

fn print_totals(label: &str, report: &FitReport) {
    eprintln!(
        "{label}: {} runs, {} evaluations, largest run {}, V {:.6e}, χ²/N {:.4}, {:.2} s",
        report.runs.len(),
        total_evaluations(report),
        report.runs.iter().map(|r| r.evaluations).max().unwrap_or(0),
        report.objective,
        report.misfit_per_point,
        report.wall_time_s,
    );
}

/// The runs, evaluations and iterations of a set (the 7 × 21 one unless
/// the environment says otherwise, see [`Shape::from_env`]) under WLF and
/// free shifts; `SEEDS=n` seeds from `SEED0` (default 1), `QUIET=1` for
/// the totals only.
/// `cargo test --release -p rollfit-fit --test it tset_cost::probe -- --ignored --nocapture`
#[test]
#[ignore = "probe: run by hand"]
fn probe_7x21() {
    let shape = Shape::from_env();
    let first = env("SEED0", 1.0) as u64;
    for seed in first..first + env("SEEDS", 1.0) as u64 {
        for kind in [ShiftKind::Wlf, ShiftKind::Free] {
            let report = fit(&shape.data(seed), &shape.params(kind)).unwrap();
            let label = format!("seed {seed} {kind:?}");
            if env("QUIET", 0.0) == 0.0 {
                print_runs(&label, &report);
            }
            print_totals(&label, &report);
        }
    }
}

/// The cost bounds on the 7 × 21 set (seed 1), with the counts they
/// hold: WLF ≤ 260 evaluations (235), free ≤ 300 (240: the free fit starts at the WLF fit's λ and does not
/// probe the bump starts and restarts again, which cost 190 evaluations
/// and never won); and on
/// shifts WLF does not describe (0.3 decade of a sine on top: WLF's λ goes
/// to 1e-8 and free shifts get a λ of their own), free ≤ 600 (455; 991
/// while the free shifts were first fitted at WLF's λ, BENCHMARKS.md).
/// The fits must also stay good: χ²/N within 0.8 … 1.2.
#[test]
fn the_7x21_set_costs_few_evaluations() {
    let plain = Shape::default();
    let wiggled = Shape {
        wiggle: 0.3,
        ..Shape::default()
    };
    for (shape, kind, bound) in [
        (plain, ShiftKind::Wlf, 260),
        (plain, ShiftKind::Free, 300),
        (wiggled, ShiftKind::Free, 600),
    ] {
        let report = fit(&shape.data(1), &shape.params(kind)).unwrap();
        let label = format!("{kind:?} wiggle {}", shape.wiggle);
        print_totals(&label, &report);
        let n = total_evaluations(&report);
        assert!(n <= bound, "{label}: {n} evaluations");
        let chi2 = report.misfit_per_point;
        assert!((0.8..=1.2).contains(&chi2), "{label}: χ²/N {chi2}");
    }
}
