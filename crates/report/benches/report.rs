//! The report of a 15-term fit (target: under 1 s): the fitted μ(v) on a
//! dense grid under the fit's scene, every picture in PNG and SVG plus the
//! HTML page, from the fit directory on disk.
//!
//! The fit directory is benches/fixtures/hn-rubber-15, written by
//! `rollfit fit data/hn-rubber.toml data/hn-rubber.csv --terms 15 -o
//! crates/report/benches/fixtures/hn-rubber-15`.

use std::path::Path;

use criterion::{Criterion, criterion_group, criterion_main};
use rollfit_io::FitDir;
use rollfit_report::fitted_friction::{FittedLine, RollingScene};
use rollfit_report::html::report_html;
use rollfit_report::plot::pictures;

fn report(c: &mut Criterion) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/fixtures/hn-rubber-15");
    let fit = FitDir::read(&dir).expect("the fixture fit reads");
    assert_eq!(fit.summary.model.tau.len(), 15);
    let scene_path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/hn-rubber.toml");
    let (setup, params) = rollfit_io::scene::load(&scene_path)
        .and_then(|s| s.fit_setup())
        .expect("the example scene reads");
    let scene = RollingScene::new(setup, &params);
    assert!(matches!(FittedLine::of(&fit, &scene), FittedLine::Dense(_)));
    let mut group = c.benchmark_group("report");
    group.sample_size(10);
    group.bench_function("fifteen_terms", |b| {
        b.iter(|| {
            let fit = FitDir::read(&dir).unwrap();
            let line = FittedLine::of(&fit, &scene);
            let all = pictures(&fit, &[], &line).unwrap();
            report_html(&fit, &all, None)
        })
    });
    group.finish();
}

criterion_group!(benches, report);
criterion_main!(benches);
