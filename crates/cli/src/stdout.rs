//! Writing a command's table or CSV to stdout (docs/ARCHITECTURE.md,
//! "Contract", "Commands"); files are written through
//! [`rollfit_io::output`].

use std::io::{self, Write};

use anyhow::{Context, Result};

/// Writes `bytes` to stdout. A closed pipe (e.g. `rollfit forward s.toml |
/// head`) is the reader's choice, not an error.
pub fn write_stdout(bytes: &[u8]) -> Result<()> {
    let mut stdout = io::stdout().lock();
    match stdout.write_all(bytes).and_then(|()| stdout.flush()) {
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Ok(()),
        result => result.context("cannot write to stdout"),
    }
}
