//! Unit tests of the output module: atomic files, folder swaps, stale
//! temporaries and locks.

use std::fs;
use std::path::{Path, PathBuf};

use super::*;

#[test]
fn atomic_write_replaces_and_cleans_up() {
    let dir = std::env::temp_dir().join(format!("rollfit-output-unit-{}", std::process::id()));
    let path = dir.join("sub").join("out.csv");
    write_atomically(&path, b"first").unwrap();
    write_atomically(&path, b"second").unwrap();
    assert_eq!(fs::read(&path).unwrap(), b"second");
    let names: Vec<_> = fs::read_dir(dir.join("sub"))
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, vec![std::ffi::OsString::from("out.csv")]);
    assert!(write_atomically(&dir, b"x").is_err());
    fs::remove_dir_all(&dir).unwrap();
}

fn folder(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rollfit-output-{tag}-{}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn a_folder_is_replaced_as_a_whole() {
    let root = folder("replace");
    let dir = root.join("fit");
    replace_folder(
        &dir,
        Writer::Fit,
        false,
        &[("fit.json", b"1"), ("mu.csv", b"a")],
    )
    .unwrap();
    add_files(&dir, Writer::Fit, &[("friction.png", b"old picture")]).unwrap();
    fs::write(dir.join("sample-photo.png"), b"mine").unwrap();
    fs::write(dir.join("notes.txt"), b"mine").unwrap();
    fs::write(dir.join(".mu.csv.4194304-0.tmp"), b"left by a killed 0.1").unwrap();
    replace_folder(
        &dir,
        Writer::Fit,
        false,
        &[("fit.json", b"2"), ("modulus.csv", b"b")],
    )
    .unwrap();
    // The recorded files of the old fit go (its picture with them), the
    // user's stay, whatever their names look like.
    assert_eq!(
        names(&dir),
        [
            RECORD_FILE,
            "fit.json",
            "modulus.csv",
            "notes.txt",
            "sample-photo.png"
        ]
    );
    assert_eq!(fs::read(dir.join("fit.json")).unwrap(), b"2");
    assert_eq!(
        fs::read_to_string(dir.join(RECORD_FILE)).unwrap(),
        "{\n  \"written_by\": \"fit\",\n  \"files\": [\n    \"fit.json\",\n    \"modulus.csv\"\n  ]\n}\n"
    );
    assert_eq!(names(&root), ["fit"]);
    // Another command's folder is refused, and replaced with `force`.
    let m = format!(
        "{:#}",
        replace_folder(&dir, Writer::Master, false, &[("master.json", b"m")]).unwrap_err()
    );
    assert!(
        m.contains("holds the results of `rollfit fit` (fit.json, modulus.csv)"),
        "{m}"
    );
    replace_folder(&dir, Writer::Master, true, &[("master.json", b"m")]).unwrap();
    assert_eq!(
        names(&dir),
        [RECORD_FILE, "master.json", "notes.txt", "sample-photo.png"]
    );
    // A user's file under a name the command writes is never overwritten.
    let m = format!(
        "{:#}",
        replace_folder(&dir, Writer::Fit, true, &[("notes.txt", b"x")]).unwrap_err()
    );
    assert!(
        m.contains("holds notes.txt, which rollfit did not write there"),
        "{m}"
    );
    // A name near the file system's limit still leaves room for the
    // temporary one.
    let long = root.join("x".repeat(250));
    replace_folder(&long, Writer::Fit, false, &[("fit.json", b"3")]).unwrap();
    write_atomically(&long.join("y".repeat(250)), b"4").unwrap();
    fs::remove_dir_all(&root).unwrap();
}

#[test]
fn only_a_dead_writer_s_leftovers_are_removed() {
    let dir = folder("stale");
    // pid 0 is never a process of ours; 4194304 is above Linux's pid_max.
    let own = format!(".rollfit-{}-7.tmp", std::process::id());
    for name in [
        ".rollfit-4194304-0.tmp",
        ".rollfit-4194304-1.old.tmp",
        own.as_str(),
    ] {
        fs::create_dir(dir.join(name)).unwrap();
    }
    fs::write(dir.join(".mu.csv.4194304-3.tmp"), b"x").unwrap();
    fs::write(dir.join("keep.tmp"), b"x").unwrap();
    let removed = remove_stale(&dir);
    if cfg!(target_os = "linux") {
        assert_eq!(removed, 3);
        assert_eq!(names(&dir), [own.as_str(), "keep.tmp"]);
    }
    fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_taken_lock_is_refused_naming_the_holder() {
    let dir = folder("lock");
    let held = FolderLock::take(&dir, ".rollfit-batch.lock", true).unwrap();
    // A second open file description conflicts even within one process.
    let m = format!(
        "{:#}",
        FolderLock::take(&dir, ".rollfit-batch.lock", true)
            .err()
            .unwrap()
    );
    assert!(m.contains("is being written by another rollfit run"), "{m}");
    assert!(FolderLock::take(&dir, ".rollfit-batch.lock", false).is_err());
    drop(held);
    let a = FolderLock::take(&dir, ".rollfit-batch.lock", false).unwrap();
    let b = FolderLock::take(&dir, ".rollfit-batch.lock", false).unwrap();
    assert!(FolderLock::take(&dir, ".rollfit-batch.lock", true).is_err());
    drop((a, b));
    fs::remove_dir_all(&dir).unwrap();
}
