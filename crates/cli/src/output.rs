//! Writing results: CSV text with full precision, written either to stdout or
//! atomically to a file.

use std::fs::{self, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use anyhow::{Context, Result, bail};

/// Formats a number so that parsing it back gives the same f64: `{:e}`
/// prints the shortest digits that round-trip, and the exponent form keeps
/// columns spanning many decades readable.
pub fn number(value: f64) -> String {
    format!("{value:e}")
}

/// CSV text (with a header row) from rows of numbers.
pub fn csv_bytes(header: &[&str], rows: impl IntoIterator<Item = Vec<f64>>) -> Result<Vec<u8>> {
    csv_text_bytes(
        header,
        rows.into_iter()
            .map(|row| row.into_iter().map(number).collect()),
    )
}

/// CSV text (with a header row) from rows of cells already formatted
/// (numbers by [`number`]).
pub fn csv_text_bytes(
    header: &[&str],
    rows: impl IntoIterator<Item = Vec<String>>,
) -> Result<Vec<u8>> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(header)?;
    for row in rows {
        writer.write_record(row)?;
    }
    writer.into_inner().context("cannot finish the CSV text")
}

/// Writes `bytes` to stdout. A closed pipe (e.g. `rollfit forward s.toml |
/// head`) is the reader's choice, not an error.
pub fn write_stdout(bytes: &[u8]) -> Result<()> {
    let mut stdout = io::stdout().lock();
    match stdout.write_all(bytes).and_then(|()| stdout.flush()) {
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Ok(()),
        result => result.context("cannot write to stdout"),
    }
}

/// Checks that `path` can name an output file (it is not a folder).
pub fn check_target(path: &Path) -> Result<()> {
    if path.is_dir() {
        bail!(
            "output {} is a folder; give a file name for the output",
            path.display()
        );
    }
    Ok(())
}

/// Writes `bytes` to `path` so that the file is either the complete new
/// content or untouched: the text goes to a temporary file in the same
/// folder (a rename is atomic only within one file system), which is then
/// renamed into place. Creates missing parent folders.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    let parent = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    fs::create_dir_all(&parent)
        .with_context(|| format!("cannot create the folder {}", parent.display()))?;
    check_target(path)?;
    let file_name = path
        .file_name()
        .with_context(|| format!("{} does not name a file", path.display()))?;

    let (temporary, mut file) = create_temporary(&parent, &file_name.to_string_lossy())?;
    let written = file
        .write_all(bytes)
        .and_then(|()| file.sync_all())
        .and_then(|()| {
            drop(file);
            fs::rename(&temporary, path)
        });
    if let Err(e) = written {
        let _ = fs::remove_file(&temporary);
        return Err(e).with_context(|| format!("cannot write {}", path.display()));
    }
    Ok(())
}

/// A new, exclusively created temporary file next to the target. The name
/// is hidden and ends in `.tmp` so that a crash leaves nothing that looks
/// like a result.
fn create_temporary(folder: &Path, name: &str) -> Result<(PathBuf, fs::File)> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let pid = std::process::id();
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let candidate = folder.join(format!(".{name}.{pid}-{n}.tmp"));
        match OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&candidate)
        {
            Ok(file) => return Ok((candidate, file)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists && n < 1000 => continue,
            Err(e) => {
                return Err(e).with_context(|| {
                    format!("cannot create a temporary file in {}", folder.display())
                });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_round_trip() {
        for v in [
            0.1,
            1e-8,
            10.0,
            1.0400419115259524e-3,
            123456789.123,
            f64::MIN_POSITIVE,
        ] {
            assert_eq!(number(v).parse::<f64>().unwrap(), v);
        }
        assert_eq!(number(1e-8), "1e-8");
    }

    #[test]
    fn csv_has_header_and_rows() {
        let bytes = csv_bytes(&["v", "mu"], vec![vec![1e-3, 0.5], vec![1.0, 0.25]]).unwrap();
        assert_eq!(
            String::from_utf8(bytes).unwrap(),
            "v,mu\n1e-3,5e-1\n1e0,2.5e-1\n"
        );
    }

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
}
