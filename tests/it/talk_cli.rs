//! End-to-end tests of a tool that talks: progress bars on a
//! terminal and never in a pipe, with the same results either way; hints
//! for swapped files and speeds in mm/s; whose ν `master` used.
//!
//! The terminal is a pseudo-terminal made by util-linux's `script`; where
//! it is missing the terminal half is skipped, said on stderr, and the
//! pipe half still runs.

use crate::common;

use std::ffi::OsStr;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

use common::{TempDir, assert_failure, rollfit, small_scene, snapshot, text};

/// The workspace (tests run in crates/cli).
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn fig2_cylinder() -> String {
    fs::read_to_string(root().join("data/paper-fig2-cylinder.toml")).unwrap()
}

/// `rollfit ARGS` under a pseudo-terminal (stdout and stderr both on it):
/// what the terminal showed, or None without `script`.
fn on_a_terminal(args: &[&str], env: &[(&str, &str)]) -> Option<String> {
    let binary = env!("CARGO_BIN_EXE_rollfit");
    // The test's own paths hold no quote or space (temporary folders).
    let line = std::iter::once(binary)
        .chain(args.iter().copied())
        .collect::<Vec<_>>()
        .join(" ");
    let mut command = Command::new("script");
    command
        .args(["-qec", &line, "/dev/null"])
        .env("TERM", "xterm")
        .env_remove("ROLLFIT_PROGRESS");
    for (key, value) in env {
        command.env(key, value);
    }
    // The exit status is not asked: what is shown is checked, and the
    // files written are compared.
    let out = command.output().ok()?;
    Some(text(&out.stdout))
}

/// Says that the terminal half of a test was skipped, where cargo test
/// shows it (a write to stderr itself is not captured).
fn skipped(test: &str) {
    let _ = std::io::Write::write_all(
        &mut std::io::stderr(),
        format!("{test}: terminal half skipped: `script` (util-linux) not installed\n").as_bytes(),
    );
}

/// What a progress bar leaves in text: its name, its cells and the ANSI
/// sequence that clears the line before it is redrawn.
fn has_bar(output: &str, what: &str) -> bool {
    output.contains(what) && output.contains('░') && output.contains("\x1b[2K")
}

/// Whether text through a pipe is free of any trace of a bar.
fn no_bar(output: &str) -> bool {
    !output.contains('░') && !output.contains('\r') && !output.contains("\x1b[")
}

fn args<'a>(list: &'a [&'a str]) -> Vec<&'a OsStr> {
    list.iter().map(OsStr::new).collect()
}

/// A cylinder of the paper's Fig. 2 on the exact rung at a few speeds:
/// milliseconds a speed.
fn exact_cylinder(tmp: &TempDir) -> String {
    let scene = fig2_cylinder()
        .replace("size = \"dynamic\"", "size = \"exact\"")
        .replace("count = 91", "count = 12");
    tmp.write("cylinder.toml", &scene).display().to_string()
}

/// A bar of exact solves on a terminal, none through a pipe, and the same
/// files either way; `ROLLFIT_PROGRESS=never` hides it on a terminal.
#[test]
fn forward_exact_shows_progress_on_a_terminal_only() {
    let tmp = TempDir::new("forward");
    let scene = exact_cylinder(&tmp);
    let out = |name: &str| tmp.path().join(name).display().to_string();
    let piped = rollfit(&args(&["forward", &scene, "-o", &out("pipe/mu.csv")]));
    let stderr = text(&piped.stderr);
    assert!(piped.status.success(), "{stderr}");
    assert!(no_bar(&stderr), "a bar in a pipe:\n{stderr:?}");
    let Some(shown) = on_a_terminal(&["forward", &scene, "-o", &out("tty/mu.csv")], &[]) else {
        return skipped("forward_exact_shows_progress_on_a_terminal_only");
    };
    assert!(has_bar(&shown, "/12 exact solves"), "no bar:\n{shown:?}");
    // Everything written is the same; the maps' names carry the folder.
    let (pipe, tty) = (
        snapshot(&tmp.path().join("pipe")),
        snapshot(&tmp.path().join("tty")),
    );
    assert_eq!(
        pipe.keys().collect::<Vec<_>>(),
        tty.keys().collect::<Vec<_>>()
    );
    for (name, bytes) in &pipe {
        assert!(tty[name] == *bytes, "{} differs with a bar", name.display());
    }
    let hidden = on_a_terminal(
        &["forward", &scene, "-o", &out("never/mu.csv")],
        &[("ROLLFIT_PROGRESS", "never")],
    )
    .unwrap();
    assert!(
        !hidden.contains('░') && !hidden.contains("\x1b["),
        "{hidden:?}"
    );
}

/// fit.json without its wall times, which differ from run to run.
fn without_wall_times(dir: &Path) -> String {
    fs::read_to_string(dir.join("fit.json"))
        .unwrap()
        .lines()
        .filter(|l| !l.contains("wall_time_s"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// An exact-physics fit counts its exact solves on a terminal, prints no
/// bar into a pipe, and writes the same fit either way.
#[test]
fn exact_physics_fit_counts_its_solves_on_a_terminal_only() {
    let tmp = TempDir::new("fit");
    let scene = fig2_cylinder().replace("count = 91", "count = 16") + "\n[fit]\nE0 = 1e6\n";
    let scene = tmp.write("cylinder.toml", &scene).display().to_string();
    let data = tmp.path().join("cylinder.csv").display().to_string();
    let made = rollfit(&args(&[
        "forward", &scene, "--noise", "0.01", "--seed", "1", "-o", &data,
    ]));
    assert!(made.status.success(), "{}", text(&made.stderr));
    let fit = |dir: &str| {
        let dir = tmp.path().join(dir).display().to_string();
        let list = [
            "fit",
            &scene,
            &data,
            "--physics",
            "exact",
            "-o",
            &dir,
            "--allow-poor-fit",
        ];
        (list.map(str::to_string), dir)
    };
    let (list, pipe_dir) = fit("pipe");
    let piped = rollfit(&list.iter().map(OsStr::new).collect::<Vec<_>>());
    let stderr = text(&piped.stderr);
    assert!(piped.status.success(), "{stderr}");
    assert!(no_bar(&stderr), "a bar in a pipe:\n{stderr:?}");
    let (list, tty_dir) = fit("tty");
    let Some(shown) = on_a_terminal(&list.iter().map(String::as_str).collect::<Vec<_>>(), &[])
    else {
        return skipped("exact_physics_fit_counts_its_solves_on_a_terminal_only");
    };
    assert!(has_bar(&shown, " exact solves, "), "no bar:\n{shown:?}");
    // The count of solves planned grows from 0 as the sweeps are planned.
    let planned = shown.split(" exact solves, ").filter_map(|before| {
        let count = before.rsplit(' ').next()?;
        count.split_once('/')?.1.parse::<usize>().ok()
    });
    assert!(
        planned.max().unwrap_or(0) > 0,
        "no solve planned:\n{shown:?}"
    );
    // The stages are named while they run.
    for stage in [
        "approximate fit",
        "exact sweep 1",
        "refit 1",
        "exact sweep 2",
    ] {
        assert!(shown.contains(stage), "{stage}:\n{shown:?}");
    }
    for name in ["mu.csv", "modulus.csv"] {
        let read = |dir: &str| fs::read(Path::new(dir).join(name)).unwrap();
        assert!(
            read(&pipe_dir) == read(&tty_dir),
            "{name} differs with a bar"
        );
    }
    assert_eq!(
        without_wall_times(Path::new(&pipe_dir)),
        without_wall_times(Path::new(&tty_dir))
    );
}

/// Swapped scene and data, a scene where data belong, a DMA file where the
/// fit folder belongs and a scene where a DMA file belongs: each error
/// starts with what to do.
#[test]
fn swapped_files_get_a_hint() {
    let tmp = TempDir::new("swapped");
    let scene = tmp.write("scene.toml", small_scene(9));
    let data = tmp.write(
        "data.csv",
        "v,mu\n1e-6,0.01\n1e-5,0.02\n1e-4,0.03\n1e-3,0.02\n",
    );
    let fit_dir = tmp.path().join("fit");
    let fit = |first: &Path, second: &Path| {
        rollfit(&[
            OsStr::new("fit"),
            first.as_os_str(),
            second.as_os_str(),
            OsStr::new("-o"),
            fit_dir.as_os_str(),
        ])
    };
    let stderr = assert_failure(
        &fit(&data, &scene),
        &[
            "the scene and the data look swapped",
            "the scene comes first: rollfit fit SCENE.toml DATA.csv",
        ],
    );
    // The reader's own words stay, after the hint.
    assert!(stderr.contains("TOML parse error"), "{stderr}");
    assert_failure(
        &fit(&scene, &scene),
        &[
            "looks like a scene (TOML), not measured data",
            "the data file comes second",
        ],
    );
    assert!(!fit_dir.exists());
    let dma = root().join("data/hn-rubber-dma.csv");
    let committed = root().join("examples/fits/hn-rubber");
    let out = rollfit(&[
        OsStr::new("compare"),
        dma.as_os_str(),
        committed.as_os_str(),
    ]);
    assert_failure(
        &out,
        &["look swapped: the fit folder comes first: rollfit compare DIR DMA.csv"],
    );
    let out = rollfit(&[
        OsStr::new("master"),
        scene.as_os_str(),
        OsStr::new("-o"),
        tmp.path().join("master").as_os_str(),
    ]);
    assert_failure(&out, &["looks like a scene (TOML), not a DMA file"]);
}

/// Speeds in mm/s under a plain `speed` header: a warning that says so and
/// names the spellings that carry the unit; none when the unit is given.
#[test]
fn speeds_in_mm_per_s_without_a_unit_are_questioned() {
    let tmp = TempDir::new("mm");
    let scene = tmp.write("scene.toml", small_scene(9));
    let rows: String = (0..9)
        .map(|i| {
            format!(
                "{},{}\n",
                10f64.powf(0.3 * i as f64),
                0.01 + 0.001 * i as f64
            )
        })
        .collect();
    let run = |header: &str| {
        let data = tmp.write("mm.csv", format!("{header},mu\n{rows}"));
        let out = rollfit(&[
            OsStr::new("fit"),
            scene.as_os_str(),
            data.as_os_str(),
            OsStr::new("-o"),
            tmp.path().join("fit").as_os_str(),
        ]);
        text(&out.stderr)
    };
    let stderr = run("speed");
    assert!(
        stderr.contains("warning: data file")
            && stderr.contains("mm/s? name the column `v_mm_s` or `speed (mm/s)`"),
        "{stderr}"
    );
    let stderr = run("speed (mm/s)");
    assert!(!stderr.contains("mm/s?"), "{stderr}");
}

/// `master` says whose ν converted shear moduli: no fit is involved.
#[test]
fn master_names_whose_poisson_ratio_it_used() {
    let tmp = TempDir::new("nu");
    let master = |extra: &[&str]| {
        let dir = tmp.path().join("master").display().to_string();
        let dma = root().join("data/hn-rubber-dma.csv").display().to_string();
        let mut list = vec!["master", &dma, "-o", &dir];
        list.extend(extra);
        let out = rollfit(&args(&list));
        let stderr = text(&out.stderr);
        assert!(out.status.success(), "{stderr}");
        stderr
    };
    let stderr = master(&[]);
    assert!(
        stderr.contains("ν = 0.5 (the default; --poisson sets another)")
            && !stderr.contains("the fit's"),
        "{stderr}"
    );
    let stderr = master(&["--poisson", "0.45"]);
    assert!(stderr.contains("ν = 0.45 (--poisson)"), "{stderr}");
}

/// A batch counts its entries on a terminal, with those not ok, and in a
/// pipe prints one line per entry; an entry whose data file is a scene
/// fails with the hint in the manifest's words.
#[test]
fn batch_counts_entries_on_a_terminal_and_lines_in_a_pipe() {
    let tmp = TempDir::new("batch");
    let scene = tmp
        .write("scene.toml", small_scene(9))
        .display()
        .to_string();
    let data = tmp.path().join("data.csv").display().to_string();
    let made = rollfit(&args(&["forward", &scene, "--noise", "0.01", "-o", &data]));
    assert!(made.status.success(), "{}", text(&made.stderr));
    let manifest = tmp.write(
        "batch.toml",
        "[[entry]]\nname = \"good\"\nscene = \"scene.toml\"\ndata = \"data.csv\"\n\n\
         [[entry]]\nname = \"swapped\"\nscene = \"scene.toml\"\ndata = \"scene.toml\"\n",
    );
    let manifest = manifest.display().to_string();
    let out = |name: &str| tmp.path().join(name).display().to_string();
    let piped = rollfit(&args(&["batch", &manifest, "-o", &out("pipe"), "-j", "1"]));
    let stderr = text(&piped.stderr);
    assert!(!piped.status.success(), "{stderr}");
    assert!(no_bar(&stderr), "a bar in a pipe:\n{stderr:?}");
    assert!(
        stderr.contains("[1/2] good: ok") && stderr.contains("[2/2] swapped: failed"),
        "{stderr}"
    );
    let summary = fs::read_to_string(tmp.path().join("pipe/summary.csv")).unwrap();
    assert!(
        summary.contains("looks like a scene (TOML), not measured data")
            && summary.contains("in the manifest, scene = \"\"SCENE.toml\"\" and data"),
        "{summary}"
    );
    let Some(shown) = on_a_terminal(&["batch", &manifest, "-o", &out("tty"), "-j", "1"], &[])
    else {
        return skipped("batch_counts_entries_on_a_terminal_and_lines_in_a_pipe");
    };
    assert!(has_bar(&shown, "/2 fits, "), "no bar:\n{shown:?}");
    // An entry not ok is printed above the bar at once (the bar's own
    // last frame may be skipped by its rate limit).
    assert!(shown.contains("swapped: failed — "), "{shown:?}");
}
