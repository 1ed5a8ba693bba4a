//! Input files without end
//! (/dev/zero) and files above the size limit are refused at once, naming
//! the file and why, before they are read (crates/io/src/input_file.rs);
//! pipes and the standard input are read up to the limit; Poisson's ratio
//! has one range at every entry point.
//!
//! The time each refusal takes is measured only as a guard against a hang
//! (/dev/zero grew to 12 GB): the bound is
//! generous and is no speed target.

use crate::common;

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::{Duration, Instant};

use common::{TempDir, assert_failure};

/// Far above the refusal's few milliseconds, far below a hang.
const HANG_GUARD: Duration = Duration::from_secs(10);

/// The bundled example's file in data/.
fn bundled(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(name)
}

/// Runs the binary with `args` and the environment `env`, and checks it
/// ends within [`HANG_GUARD`].
fn run_with(env: &[(&str, &str)], args: &[&dyn AsRef<OsStr>]) -> Output {
    let mut command = Command::new(env!("CARGO_BIN_EXE_rollfit"));
    command.args(args.iter().map(|a| a.as_ref()));
    for (key, value) in env {
        command.env(key, value);
    }
    command.env_remove("ROLLFIT_PROGRESS");
    let started = Instant::now();
    let output = command.output().expect("cannot start the rollfit binary");
    assert!(
        started.elapsed() < HANG_GUARD,
        "took {:?}: {}",
        started.elapsed(),
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

fn run(args: &[&dyn AsRef<OsStr>]) -> Output {
    run_with(&[], args)
}

const ENDLESS: &str = "is a character device (such as /dev/zero), not a regular file; rollfit reads \
                       files whose size it can know — save the data to a file first";

#[cfg(unix)]
#[test]
fn master_of_dev_zero_is_refused_at_once() {
    let dir = TempDir::new("zero-master");
    let out = dir.path().join("master");
    let output = run(&[&"master", &"/dev/zero", &"-o", &out]);
    assert_failure(&output, &["DMA file /dev/zero", ENDLESS]);
    assert!(!out.exists());
}

#[cfg(unix)]
#[test]
fn fit_of_dev_zero_as_data_is_refused_at_once() {
    let dir = TempDir::new("zero-fit");
    let out = dir.path().join("fit");
    let output = run(&[
        &"fit",
        &bundled("hn-rubber.toml"),
        &"/dev/zero",
        &"-o",
        &out,
    ]);
    assert_failure(&output, &["data file /dev/zero", ENDLESS]);
    assert!(!out.exists());
}

#[cfg(unix)]
#[test]
fn a_scene_whose_material_file_is_dev_zero_is_refused_at_once() {
    let dir = TempDir::new("zero-scene");
    for model in ["table", "dma"] {
        let scene = dir.write(
            &format!("{model}.toml"),
            format!(
                "[geometry]\nshape = \"sphere\"\nradius = 0.005\nload = 1.0\n\n\
                 [material]\nmodel = \"{model}\"\nfile = \"/dev/zero\"\n\n\
                 [sweep]\nv_min = 1e-6\nv_max = 1e-2\ncount = 5\n"
            ),
        );
        let output = run(&[&"forward", &scene]);
        assert_failure(&output, &["/dev/zero", ENDLESS]);
    }
}

/// A FIFO made with mkfifo; `None` where there is no mkfifo.
fn fifo(dir: &TempDir, name: &str) -> Option<PathBuf> {
    let path = dir.path().join(name);
    let made = Command::new("mkfifo").arg(&path).status().ok()?;
    made.success().then_some(path)
}

/// Starts a writer of `source` into the FIFO `pipe` (`cat source >
/// pipe`, as a shell's `<(…)` does), to be killed once the run ended.
fn writer(source: &Path, pipe: &Path) -> std::process::Child {
    Command::new("sh")
        .arg("-c")
        .arg("cat \"$0\" > \"$1\"")
        .arg(source)
        .arg(pipe)
        .spawn()
        .expect("cannot start sh")
}

/// A pipe as scene, data or DMA file (`rollfit fit <(make-scene)
/// data.csv`) is read as it comes; the answer is the one of the same
/// file saved. A pipe above the size limit is refused naming the limit.
#[test]
fn a_pipe_is_read_as_the_file_it_carries() {
    let dir = TempDir::new("fifo");
    let Some(pipe) = fifo(&dir, "pipe.toml") else {
        eprintln!("no mkfifo: skipped");
        return;
    };
    let fit = |scene: &dyn AsRef<OsStr>, out: &str, env: &[(&str, &str)]| {
        let mut feed = writer(&bundled("hn-rubber.toml"), &pipe);
        let output = run_with(
            env,
            &[
                &"fit",
                scene,
                &bundled("hn-rubber.csv"),
                &"-o",
                &dir.path().join(out),
            ],
        );
        let _ = feed.kill();
        let _ = feed.wait();
        output
    };
    let output = fit(&pipe, "piped", &[]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let output = fit(&bundled("hn-rubber.toml"), "saved", &[]);
    assert!(output.status.success());
    let mu = |out: &str| std::fs::read(dir.path().join(out).join("mu.csv")).unwrap();
    assert_eq!(mu("piped"), mu("saved"));

    let output = fit(&pipe, "limited", &[("ROLLFIT_MAX_INPUT_BYTES", "100")]);
    assert_failure(
        &output,
        &[
            "scene file",
            "pipe.toml",
            "holds more than the limit of 100 bytes",
        ],
    );
    assert!(!dir.path().join("limited").exists());
}

/// `-` reads the standard input (a pipe or a redirected file), for the
/// scene of `fit` and the DMA file of `master`; a device there is refused.
#[cfg(unix)]
#[test]
fn standard_input_is_read_for_a_dash() {
    use std::io::Write;
    use std::process::Stdio;
    let dir = TempDir::new("stdin");
    let out = dir.path().join("fit");
    let mut child = Command::new(env!("CARGO_BIN_EXE_rollfit"))
        .args([
            OsStr::new("fit"),
            OsStr::new("-"),
            bundled("hn-rubber.csv").as_os_str(),
        ])
        .args([OsStr::new("-o"), out.as_os_str()])
        .stdin(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let scene = std::fs::read(bundled("hn-rubber.toml")).unwrap();
    child.stdin.take().unwrap().write_all(&scene).unwrap();
    let output = child.wait_with_output().unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(out.join("fit.json").is_file());

    let master = |stdin: Stdio| {
        Command::new(env!("CARGO_BIN_EXE_rollfit"))
            .args(["master", "-", "-o"])
            .arg(dir.path().join("master"))
            .stdin(stdin)
            .output()
            .unwrap()
    };
    let file = std::fs::File::open(bundled("hn-rubber-dma-isotherms.csv")).unwrap();
    let output = master(Stdio::from(file));
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let zero = std::fs::File::open("/dev/zero").unwrap();
    let output = master(Stdio::from(zero));
    assert_failure(&output, &["DMA file -", "is a terminal or a device"]);
}

#[test]
fn a_file_over_the_limit_is_refused_naming_the_limit_and_its_variable() {
    let dir = TempDir::new("limit");
    let out = dir.path().join("fit");
    let limit = [("ROLLFIT_MAX_INPUT_BYTES", "1000")];
    let data = bundled("hn-rubber.csv");
    let size = std::fs::metadata(&data).unwrap().len();
    assert!(size > 1000);
    // The scene is under the limit; the data are not.
    let scene = dir.write(
        "scene.toml",
        "[geometry]\nshape = \"sphere\"\nradius = 0.005\nload = 1.0\n",
    );
    let output = run_with(&limit, &[&"fit", &scene, &data, &"-o", &out]);
    assert_failure(
        &output,
        &[
            "data file ",
            "hn-rubber.csv is ",
            &format!("{size} bytes"),
            "more than the limit of 1000 bytes on an input file; set ROLLFIT_MAX_INPUT_BYTES to \
             raise it (e.g. ROLLFIT_MAX_INPUT_BYTES=4G)",
        ],
    );
    assert!(!out.exists());
    let output = run_with(
        &limit,
        &[&"master", &bundled("hn-rubber-dma.csv"), &"-o", &out],
    );
    assert_failure(
        &output,
        &["DMA file ", "hn-rubber-dma.csv is ", "1000 bytes"],
    );
    // Raised with a suffix, the same data are read.
    let output = run_with(
        &[("ROLLFIT_MAX_INPUT_BYTES", "2M")],
        &[&"master", &bundled("hn-rubber-dma.csv"), &"-o", &out],
    );
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

#[test]
fn a_malformed_limit_is_refused_naming_the_variable() {
    let dir = TempDir::new("bad-limit");
    let out = dir.path().join("fit");
    for value in ["lots", "1.5G", "0", "-1"] {
        let output = run_with(
            &[("ROLLFIT_MAX_INPUT_BYTES", value)],
            &[
                &"fit",
                &bundled("hn-rubber.toml"),
                &bundled("hn-rubber.csv"),
                &"-o",
                &out,
            ],
        );
        assert_failure(
            &output,
            &[
                "hn-rubber.toml",
                &format!(
                    "ROLLFIT_MAX_INPUT_BYTES = {value:?} is not a size: give bytes (1000000) or a number with K, M, G or T"
                ),
            ],
        );
        assert!(!out.exists());
    }
}

/// Item 10: one range of Poisson's ratio, [0, 0.5], at every entry point,
/// with one message naming the key or flag.
const POISSON_RANGE: &str = "outside [0, 0.5]: Poisson's ratio of rubber is 0.5 (incompressible)";

#[test]
fn poisson_below_0_or_above_half_is_refused_alike_in_a_scene_and_by_master() {
    let dir = TempDir::new("poisson");
    for nu in ["-0.3", "0.7"] {
        let scene = dir.write(
            "scene.toml",
            format!(
                "[geometry]\nshape = \"sphere\"\nradius = 0.005\nload = 1.0\n\n\
                 [substrate]\npoisson = {nu}\n\n\
                 [material]\nmodel = \"sls\"\nE0 = 1e6\nE1 = 1e8\ntau = 1e-3\n\n\
                 [sweep]\nv_min = 1e-6\nv_max = 1e-2\ncount = 3\n"
            ),
        );
        let output = run(&[&"forward", &scene]);
        assert_failure(
            &output,
            &[
                "scene.toml",
                &format!("[substrate]: poisson = {nu} {POISSON_RANGE}"),
            ],
        );
        let out = dir.path().join("master");
        let output = run(&[
            &"master",
            &bundled("hn-rubber-dma.csv"),
            &"--poisson",
            &nu,
            &"-o",
            &out,
        ]);
        let stderr = assert_failure(
            &output,
            &[&format!(
                "invalid value '{nu}' for '--poisson <POISSON>': poisson = {nu} {POISSON_RANGE}"
            )],
        );
        assert_eq!(output.status.code(), Some(2), "{stderr}");
        assert!(!out.exists());
    }
}
