//! `rollfit compare` (being written).

use std::path::PathBuf;

use anyhow::{Result, bail};

/// Arguments of `rollfit compare`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Fit result folder.
    pub dir: PathBuf,
}

/// Runs the command.
pub fn run(_args: &Args) -> Result<()> {
    bail!("not built yet")
}
