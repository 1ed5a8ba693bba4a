//! Speed of `rollfit master`, timed as a user meets it: the whole process,
//! from reading the DMA file to the written folder with its picture.
//!
//! - `20_isotherms_x_30_points` (target: at most 1 s): a broad
//!   rubber (Havriliak–Negami) under WLF C1 = 9, C2 = 110 K, −30…65 °C
//!   every 5 K, 30 frequencies over 0.1…100 rad/s each, 1 % noise, shear
//!   moduli.
//! - `large/10MB` and `large/50MB` (targets: at most 15 s and
//!   60 s): the same rubber under WLF 8.86/101.6 K as logged by an
//!   instrument that writes every reading, 60 isotherms −40…107.5 °C
//!   every 2.5 K with 3600 and 18 000 frequencies over 0.1…100 Hz each,
//!   1 % noise, Young's moduli; 10.0 and 50.1 MB of CSV.

use std::path::Path;
use std::process::Command;

use criterion::{Criterion, criterion_group, criterion_main};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use rollfit_model::ViscoelasticModulus;
use rollfit_testkit::materials::hn_rubber;

fn isotherms_csv(path: &Path) {
    let master = hn_rubber();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let normal = Normal::new(0.0, 0.01).unwrap();
    let mut out = String::from("T,omega,G_storage,G_loss\n");
    for k in 0..20 {
        let t = -30.0 + 5.0 * k as f64;
        let a = 10f64.powf(-9.0 * (t - 20.0) / (110.0 + t - 20.0));
        for i in 0..30 {
            let w = 0.1 * 10f64.powf(3.0 * i as f64 / 29.0);
            let e = master.modulus(w * a);
            out += &format!(
                "{t},{w:e},{:e},{:e}\n",
                e.re / 3.0 * (1.0 + normal.sample(&mut rng)),
                e.im / 3.0 * (1.0 + normal.sample(&mut rng))
            );
        }
    }
    std::fs::write(path, out).unwrap();
}

/// The logger's file of `points` frequencies per isotherm (module doc).
fn large_csv(path: &Path, points: usize) {
    use std::io::Write;
    let master = hn_rubber();
    let mut rng = ChaCha8Rng::seed_from_u64(36);
    let normal = Normal::new(0.0, 0.01).unwrap();
    let mut out = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
    writeln!(out, "f,E_storage,E_loss,T").unwrap();
    for k in 0..60 {
        let t = -40.0 + 2.5 * k as f64;
        let a = 10f64.powf(-8.86 * (t - 20.0) / (101.6 + t - 20.0));
        for i in 0..points {
            let hz = 0.1 * 10f64.powf(3.0 * i as f64 / (points - 1) as f64);
            let e = master.modulus(2.0 * std::f64::consts::PI * hz * a);
            writeln!(
                out,
                "{hz:.6e},{:.6e},{:.6e},{t:.3}",
                e.re * (1.0 + normal.sample(&mut rng)),
                e.im * (1.0 + normal.sample(&mut rng))
            )
            .unwrap();
        }
    }
}

/// `rollfit master FILE -o OUT`, which must succeed.
fn master_run(file: &Path, out: &Path) {
    let status = Command::new(env!("CARGO_BIN_EXE_rollfit"))
        .arg("master")
        .arg(file)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
}

fn large(c: &mut Criterion) {
    let dir = std::env::temp_dir().join(format!("rollfit-bench-large-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut group = c.benchmark_group("master/large");
    group.sample_size(10);
    for (name, points) in [("10MB", 3600), ("50MB", 18_000)] {
        let file = dir.join(format!("{name}.csv"));
        large_csv(&file, points);
        let out = dir.join(name);
        group.bench_function(name, |b| b.iter(|| master_run(&file, &out)));
        let _ = std::fs::remove_file(&file);
    }
    group.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

fn benches(c: &mut Criterion) {
    let dir = std::env::temp_dir().join(format!("rollfit-bench-master-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("isotherms.csv");
    isotherms_csv(&file);
    let out = dir.join("master");
    let run = || master_run(&file, &out);
    let mut group = c.benchmark_group("master");
    group.sample_size(10);
    group.bench_function("20_isotherms_x_30_points", |b| b.iter(run));
    group.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(master, benches, large);
criterion_main!(master);
