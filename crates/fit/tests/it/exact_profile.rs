//! Where the time of an exact-physics fit goes: the fits of the
//! `exact_physics` benches (41 speeds of the broad rubber, cylinder at
//! σ = 1 %, sphere at σ = 1 % and 0.1 %), each stage of the defect
//! correction timed in wall and CPU time (user + system of the process,
//! from /proc/self/stat) through the fit's progress observer, with its
//! exact solves. The truth is cached in `$ROLLFIT_TRUTH_DIR` (default
//! /tmp) as it costs minutes for the sphere. Linux only.
//!
//! `cargo test --release -p rollfit-fit --test it exact_profile:: -- --ignored --nocapture`
//! (`PROFILE_CASES=sphere1` and so on picks cases).

use rollfit_testkit::materials::rubber_200;
use rollfit_testkit::rolling::{exact_and_approximate, exact_cylinder_setup, setup, with_noise};

use std::sync::{Arc, Mutex};
use std::time::Instant;

use rollfit_fit::{FitParams, Observer, Physics, Progress, RollingSetup, ScaleAnchor, fit};

/// Process CPU time (user + system), s.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // Fields after the command name (which is in parentheses).
    let rest = stat.rsplit(')').next().unwrap_or("");
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| fields.get(i).and_then(|f| f.parse::<f64>().ok());
    // utime and stime are fields 14 and 15 of the whole line: 12 and 13
    // after the state (field 3 is index 0 here).
    match (ticks(11), ticks(12)) {
        (Some(u), Some(s)) => (u + s) / 100.0,
        _ => f64::NAN,
    }
}

/// CPU time (s) of a thread from its stat file.
fn thread_cpu(stat: &str) -> f64 {
    let rest = stat.rsplit(')').next().unwrap_or("");
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| fields.get(i).and_then(|f| f.parse::<f64>().ok());
    (ticks(11).unwrap_or(f64::NAN) + ticks(12).unwrap_or(f64::NAN)) / 100.0
}

fn this_thread() -> (String, f64) {
    let stat = std::fs::read_to_string("/proc/thread-self/stat").unwrap_or_default();
    let tid = stat.split_whitespace().next().unwrap_or("").to_string();
    (tid, thread_cpu(&stat))
}

fn all_threads() -> std::collections::HashMap<String, f64> {
    std::fs::read_dir("/proc/self/task")
        .map(|d| {
            d.flatten()
                .map(|e| {
                    let stat = std::fs::read_to_string(e.path().join("stat")).unwrap_or_default();
                    (
                        e.file_name().to_string_lossy().to_string(),
                        thread_cpu(&stat),
                    )
                })
                .collect()
        })
        .unwrap_or_default()
}

/// The makespan of `jobs` (s each) on `workers`, each job to the first
/// worker free, in the given order.
fn makespan(jobs: &[f64], workers: usize) -> f64 {
    let mut free = vec![0.0f64; workers];
    for j in jobs {
        let w = (0..workers)
            .min_by(|a, b| free[*a].total_cmp(&free[*b]))
            .unwrap();
        free[w] += j;
    }
    free.into_iter().fold(0.0, f64::max)
}

#[derive(Default)]
struct Log {
    /// (stage, wall at start, cpu at start, solves planned, solves done)
    stages: Vec<(String, f64, f64, usize, usize)>,
    /// Per stage, per batch: each solve's thread CPU time, s.
    batches: Vec<Vec<Vec<f64>>>,
    /// Thread CPU at the last event per thread.
    last: std::collections::HashMap<String, f64>,
}

struct Timer {
    clock: Instant,
    log: Mutex<Log>,
}

impl Progress for Timer {
    fn stage(&self, what: &str) {
        let t = self.clock.elapsed().as_secs_f64();
        self.log
            .lock()
            .unwrap()
            .stages
            .push((what.to_string(), t, cpu_seconds(), 0, 0));
        self.log.lock().unwrap().batches.push(Vec::new());
    }
    fn planned(&self, count: usize) {
        let snapshot = all_threads();
        let mut log = self.log.lock().unwrap();
        log.last = snapshot;
        if let Some(s) = log.stages.last_mut() {
            s.3 += count;
        }
        if let Some(b) = log.batches.last_mut() {
            b.push(Vec::new());
        }
    }
    fn solved(&self) {
        let (tid, now) = this_thread();
        let mut log = self.log.lock().unwrap();
        let before = log.last.insert(tid, now).unwrap_or(now);
        if let Some(s) = log.stages.last_mut() {
            s.4 += 1;
        }
        if let Some(b) = log.batches.last_mut().and_then(|b| b.last_mut()) {
            b.push(now - before);
        }
    }
}

fn truth(name: &str, setup: RollingSetup, accuracy: f64) -> (Vec<f64>, Vec<f64>) {
    let dir = std::env::var("ROLLFIT_TRUTH_DIR").unwrap_or_else(|_| "/tmp".into());
    let path = format!("{dir}/rollfit_truth_{name}.txt");
    if let Ok(text) = std::fs::read_to_string(&path) {
        let pairs: Vec<(f64, f64)> = text
            .lines()
            .map(|l| {
                let mut it = l
                    .split_whitespace()
                    .map(|w| f64::from_bits(u64::from_str_radix(w, 16).unwrap()));
                (it.next().unwrap(), it.next().unwrap())
            })
            .collect();
        return pairs.into_iter().unzip();
    }
    let both = exact_and_approximate(setup, &rubber_200(), accuracy).unwrap();
    let text: String = both
        .speeds
        .iter()
        .zip(&both.exact)
        .map(|(v, m)| format!("{:016x} {:016x}\n", v.to_bits(), m.to_bits()))
        .collect();
    std::fs::write(&path, text).unwrap();
    (both.speeds, both.exact)
}

#[test]
#[ignore = "profile, minutes: --ignored --nocapture"]
fn profile_exact_physics_fits() {
    let cases = std::env::var("PROFILE_CASES").unwrap_or_else(|_| "cyl1,sphere1,sphere01".into());
    for case in cases.split(',') {
        let (name, setup, accuracy, noise) = match case {
            "cyl1" => ("cylinder", exact_cylinder_setup(), 1e-6, 0.01),
            "cyl01" => ("cylinder", exact_cylinder_setup(), 1e-6, 0.001),
            "sphere1" => ("sphere", setup(), 1e-4, 0.01),
            "sphere01" => ("sphere", setup(), 1e-4, 0.001),
            other => panic!("unknown case {other}"),
        };
        let (speeds, exact) = truth(name, setup, accuracy);
        let measured = with_noise(&speeds, &exact, noise, 1);
        let timer = Arc::new(Timer {
            clock: Instant::now(),
            log: Mutex::new(Log::default()),
        });
        let params = FitParams {
            anchor: Some(ScaleAnchor::StaticModulus(2e6)),
            physics: Physics::Exact,
            ..FitParams::default()
        }
        .check(setup)
        .unwrap()
        .with_progress(Observer::new(timer.clone()));
        let cpu0 = cpu_seconds();
        let report = fit(&measured, &params).unwrap();
        let (wall, cpu) = (timer.clock.elapsed().as_secs_f64(), cpu_seconds() - cpu0);
        let log = timer.log.lock().unwrap();
        eprintln!(
            "== {case}: wall {wall:.2} s, cpu {cpu:.2} s (load {})",
            std::fs::read_to_string("/proc/loadavg")
                .unwrap_or_default()
                .trim()
        );
        for (k, (stage, t, c, planned, done)) in log.stages.iter().enumerate() {
            let (t1, c1) = log
                .stages
                .get(k + 1)
                .map_or((wall, cpu0 + cpu), |s| (s.1, s.2));
            let batches = &log.batches[k];
            let sizes: Vec<usize> = batches.iter().map(Vec::len).collect();
            let solve_cpu: f64 = batches.iter().flatten().sum();
            let two: f64 = batches.iter().map(|b| makespan(b, 2)).sum();
            let one: f64 = batches.iter().map(|b| makespan(b, 1)).sum();
            eprintln!(
                "  {stage:26} wall {:6.2} s cpu {:6.2} s  solves {done}/{planned} in batches {sizes:?}: \
                 solve cpu {solve_cpu:.2} s, 2-core makespan {two:.2} s (efficiency {:.2})",
                t1 - t,
                c1 - c,
                one / (2.0 * two)
            );
            if std::env::var("PROFILE_SOLVES").is_ok() {
                eprintln!("    {batches:.2?}");
            }
        }
        let p = report.physics.as_ref().unwrap();
        eprintln!(
            "  refits {}, exact solves {}, runs {}, evaluations {}, last change {:.1e}, accuracy {:.0e}",
            p.iterations,
            p.exact_solves,
            report.runs.len(),
            report.evaluations,
            p.last_change,
            p.accuracy
        );
        let m = &report.model;
        eprintln!(
            "  modulus: E1 {:.6e}, strengths[..3] {:?}",
            m.glassy_modulus,
            &m.strengths[..3.min(m.strengths.len())]
        );
    }
}
