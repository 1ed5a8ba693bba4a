//! Speed of `rollfit master` (issue 15's target: 20 isotherms × 30 points
//! in at most 1 s), timed as a user meets it: the whole process, from
//! reading the DMA file to the written folder with its picture. The file
//! is synthetic: a broad rubber (Havriliak–Negami) under WLF C1 = 9,
//! C2 = 110 K, −30…65 °C every 5 K, 30 frequencies over 0.1…100 rad/s
//! each, 1 % noise, shear moduli.

use std::path::Path;
use std::process::Command;

use criterion::{Criterion, criterion_group, criterion_main};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use rollfit_model::{HavriliakNegami, ViscoelasticModulus};

fn isotherms_csv(path: &Path) {
    let master = HavriliakNegami::new(2e6, 2e9, 1e-3, 0.55, 0.4).unwrap();
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

fn benches(c: &mut Criterion) {
    let dir = std::env::temp_dir().join(format!("rollfit-bench-master-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("isotherms.csv");
    isotherms_csv(&file);
    let out = dir.join("master");
    let run = || {
        let status = Command::new(env!("CARGO_BIN_EXE_rollfit"))
            .arg("master")
            .arg(&file)
            .arg("-o")
            .arg(&out)
            .output()
            .unwrap();
        assert!(
            status.status.success(),
            "{}",
            String::from_utf8_lossy(&status.stderr)
        );
    };
    let mut group = c.benchmark_group("master");
    group.sample_size(10);
    group.bench_function("20_isotherms_x_30_points", |b| b.iter(run));
    group.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(master, benches);
criterion_main!(master);
