//! End-to-end tests of the pressure maps `rollfit forward -o OUT.csv`
//! writes where μ comes from the exact rolling contact: the
//! files beside the CSV, their columns, the load the pressure carries, the
//! outline against the edges of the μ CSV, and `--pressure-map` input that
//! is refused before any output is written.
//!
//! Each exact sphere speed costs about 0.7 s (two grids): the sphere scene
//! has three speeds and asks for one map beside the default one.

use crate::common;

use std::ffi::OsStr;
use std::path::Path;
use std::process::Output;

use common::{Table, TempDir, assert_failure, rollfit, text};

/// The paper's Fig. 2 solid (standard linear solid, E1/E0 = 10, τ = 1 s,
/// ν = 0) under a sphere (R = 1 cm, 0.15 N; r0 = 1.04 mm) or a cylinder
/// (100 N/m), three speeds around the friction maximum.
fn scene(shape: &str, size: &str) -> String {
    let load = if shape == "sphere" { 0.15 } else { 100.0 };
    format!(
        "[geometry]\nshape = \"{shape}\"\nradius = 0.01\nload = {load}\n\n\
         [substrate]\npoisson = 0.0\n\n[contact]\n{size}\n\n\
         [material]\nmodel = \"sls\"\nE0 = 1e6\nE1 = 1e7\ntau = 1.0\n\n\
         [sweep]\nv = [1e-4, 1e-3, 1e-2]\n"
    )
}

fn forward(args: &[&OsStr]) -> Output {
    let mut all = vec![OsStr::new("forward")];
    all.extend_from_slice(args);
    rollfit(&all)
}

fn run_ok(scene: &Path, out: &Path, extra: &[&str]) -> String {
    let mut args = vec![scene.as_os_str(), OsStr::new("-o"), out.as_os_str()];
    args.extend(extra.iter().map(OsStr::new));
    let result = forward(&args);
    let stderr = text(&result.stderr);
    assert!(result.status.success(), "{stderr}");
    stderr
}

/// The four files of the map at `v` (as the CSV writes it) beside
/// `dir/forward.csv`: pressure, outline, PNG, SVG.
fn map_files(dir: &Path, v: &str) -> [std::path::PathBuf; 4] {
    let stem = format!("forward-pressure-map-v{v}");
    [
        dir.join(format!("{stem}.csv")),
        dir.join(format!("{stem}-outline.csv")),
        dir.join(format!("{stem}.png")),
        dir.join(format!("{stem}.svg")),
    ]
}

/// The row of the μ CSV at speed `v`.
fn row_at(table: &Table, v: f64) -> usize {
    table
        .column("v")
        .iter()
        .position(|&s| s == v)
        .expect("the sweep has that speed")
}

/// `size = "exact"` for a sphere: a map at the speed of the largest μ
/// (1e-3 m/s) and one asked for; the cells' pressures carry the load
/// (h² Σ p = F), their centroid is μR to within the solution's error
/// estimate, every cell lies inside its row of the outline, and the row
/// on the rolling axis has the μ CSV's edges, trailing < 0 < leading.
#[test]
fn exact_sphere_writes_its_pressure_maps() {
    let dir = TempDir::new("sphere");
    let path = dir.write("ball.toml", scene("sphere", "size = \"exact\""));
    let out = dir.path().join("forward.csv");
    let stderr = run_ok(&path, &out, &["--pressure-map", "3e-3"]);
    assert!(
        stderr.contains("pressure map at v = 1e-3 m/s (largest sampled exact μ)"),
        "{stderr}"
    );
    assert!(stderr.contains("pressure map at v = 3e-3 m/s (--pressure-map)"));
    let mu_table = Table::read(&out);
    let i = row_at(&mu_table, 1e-3);
    let mu = mu_table.column("mu");
    assert!(mu.iter().all(|&m| m <= mu[i]), "1e-3 m/s has the largest μ");
    let error = mu_table.column("error_estimate")[i];

    for v in ["1e-3", "3e-3"] {
        for file in map_files(dir.path(), v) {
            let size = std::fs::metadata(&file).map_or(0, |m| m.len());
            assert!(size > 100, "{} missing or empty", file.display());
        }
    }
    let [pressure, outline, _, svg] = map_files(dir.path(), "1e-3");
    let cells = Table::read(&pressure);
    assert_eq!(cells.header, ["x", "y", "pressure"]);
    let rows = Table::read(&outline);
    assert_eq!(rows.header, ["y", "x_trailing", "x_leading"]);
    assert!(
        std::fs::read_to_string(svg)
            .unwrap()
            .contains("v = 1.000e-3 m/s")
    );

    let (x, y, p) = (
        cells.column("x"),
        cells.column("y"),
        cells.column("pressure"),
    );
    assert!(p.iter().all(|&p| p > 0.0));
    // The cell side: the smallest step between cell centres along x.
    let mut xs = x.clone();
    xs.sort_by(f64::total_cmp);
    xs.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    let h = xs
        .windows(2)
        .map(|w| w[1] - w[0])
        .fold(f64::INFINITY, f64::min);
    let load = h * h * p.iter().sum::<f64>();
    assert!((load / 0.15 - 1.0).abs() < 1e-5, "h² Σ p = {load} N");
    let centroid = x.iter().zip(&p).map(|(x, p)| x * p).sum::<f64>() / p.iter().sum::<f64>();
    assert!(
        (centroid / 0.01 - mu[i]).abs() <= error * mu[i] * 1.001,
        "centroid/R = {} against μ = {} ± {error}",
        centroid / 0.01,
        mu[i]
    );

    let (row_y, trailing, leading) = (
        rows.column("y"),
        rows.column("x_trailing"),
        rows.column("x_leading"),
    );
    for k in 0..x.len() {
        let r = row_y
            .iter()
            .position(|&ry| (ry - y[k]).abs() < 0.5 * h)
            .expect("every cell's row is in the outline");
        assert!(trailing[r] < x[k] && x[k] < leading[r], "cell {k} outside");
    }
    let axis = (0..row_y.len())
        .min_by(|&a, &b| row_y[a].abs().total_cmp(&row_y[b].abs()))
        .unwrap();
    assert!(trailing[axis] < 0.0 && 0.0 < leading[axis]);
    let edges = (
        mu_table.column("contact_trailing_edge")[i],
        mu_table.column("contact_leading_edge")[i],
    );
    assert_eq!((trailing[axis], leading[axis]), edges);
}

/// `size = "exact"` for a cylinder: the profile p(x) without y between the
/// μ CSV's edges, carrying the load per length; the outline is those two
/// edges.
#[test]
fn exact_cylinder_writes_its_pressure_profile() {
    let dir = TempDir::new("cylinder");
    let path = dir.write("roller.toml", scene("cylinder", "size = \"exact\""));
    let out = dir.path().join("forward.csv");
    run_ok(&path, &out, &[]);
    let mu_table = Table::read(&out);
    let i = row_at(&mu_table, 1e-3);
    let [pressure, outline, png, _] = map_files(dir.path(), "1e-3");
    assert!(std::fs::metadata(png).unwrap().len() > 1000);
    let profile = Table::read(&pressure);
    assert_eq!(profile.header, ["x", "pressure"]);
    let edges = Table::read(&outline);
    assert_eq!(edges.header, ["x_trailing", "x_leading"]);
    assert_eq!(edges.rows.len(), 1);
    let (a1, a2) = (edges.rows[0][0], edges.rows[0][1]);
    assert_eq!(a1, mu_table.column("contact_trailing_edge")[i]);
    assert_eq!(a2, mu_table.column("contact_leading_edge")[i]);
    assert!(a1 < 0.0 && 0.0 < a2);
    let (x, p) = (profile.column("x"), profile.column("pressure"));
    assert_eq!((x[0], *x.last().unwrap()), (a1, a2));
    let load: f64 = (1..x.len())
        .map(|k| 0.5 * (x[k] - x[k - 1]) * (p[k] + p[k - 1]))
        .sum();
    assert!((load / 100.0 - 1.0).abs() < 1e-3, "∫p dx = {load} N/m");
    // Only the largest-μ map without --pressure-map.
    let maps = std::fs::read_dir(dir.path())
        .unwrap()
        .filter(|e| {
            let name = e.as_ref().unwrap().file_name();
            name.to_string_lossy().contains("pressure-map")
        })
        .count();
    assert_eq!(maps, 4);
}

/// Files in `dir` other than the scene.
fn outputs(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| !n.ends_with(".toml"))
        .collect()
}

/// A speed that is not a positive finite number within the range of
/// `[sweep]` speeds, a map without `-o`, and a map of a scene without an
/// exact rolling contact are refused with a message naming the option,
/// before any computation and without any output.
#[test]
fn bad_pressure_map_requests_are_refused_without_output() {
    let dir = TempDir::new("bad");
    let exact = dir.write("ball.toml", scene("sphere", "size = \"exact\""));
    let out = dir.path().join("forward.csv");
    for bad in ["-1e-3", "0", "nan", "inf", "1e4", "fast"] {
        let result = forward(&[
            exact.as_os_str(),
            OsStr::new("-o"),
            out.as_os_str(),
            OsStr::new("--pressure-map"),
            OsStr::new(bad),
        ]);
        assert_failure(&result, &["--pressure-map", "m/s"]);
        assert_eq!(result.status.code(), Some(2), "usage error for {bad}");
        assert!(outputs(dir.path()).is_empty(), "{bad}: output written");
    }
    let result = forward(&[
        exact.as_os_str(),
        OsStr::new("--pressure-map"),
        OsStr::new("1e-3"),
    ]);
    assert_failure(&result, &["--output"]);
    assert_eq!(result.status.code(), Some(2));

    let dynamic = dir.write("dynamic.toml", scene("sphere", "size = \"dynamic\""));
    let result = forward(&[
        dynamic.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
        OsStr::new("--pressure-map"),
        OsStr::new("1e-3"),
    ]);
    assert_failure(
        &result,
        &["--pressure-map 0.001", "dynamic.toml", "size = \"exact\""],
    );
    assert_eq!(result.status.code(), Some(1));
    assert!(outputs(dir.path()).is_empty(), "output written");
}

/// `size = "auto"` writes the map where it used the exact rung: on the
/// cylinder at accuracy 1e-3, at every speed here, so at the largest μ.
#[test]
fn auto_writes_the_map_of_its_exact_rung() {
    let dir = TempDir::new("auto");
    let path = dir.write(
        "roller.toml",
        scene("cylinder", "size = \"auto\"\naccuracy = 1e-3"),
    );
    let out = dir.path().join("forward.csv");
    let stderr = run_ok(&path, &out, &[]);
    assert!(stderr.contains("exact rolling cylinder"), "{stderr}");
    for file in map_files(dir.path(), "1e-3") {
        assert!(file.is_file(), "{} missing", file.display());
    }
}
