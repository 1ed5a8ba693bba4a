//! `rollfit`: rolling-friction measurements ↔ viscoelastic master curves
//! (Persson, Eur. Phys. J. E 33, 2010). See DESIGN.md §4 for the commands,
//! the scene file and the CSV columns other programs rely on.

mod commands;
mod output;
mod scene_file;
mod table_file;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Rolling friction on viscoelastic solids: predict μ(v) from a modulus, or
/// recover the modulus from μ(v).
#[derive(Debug, Parser)]
#[command(name = "rollfit", version)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Predict the friction coefficient μ(v) of a scene over its sweep of
    /// rolling speeds, as CSV.
    ///
    /// Columns: v (m/s), mu, mu_low_speed, contact_size_static (m),
    /// mean_pressure_static (Pa), centroid_shift (m), gt_alpha.
    Forward(commands::forward::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Forward(args) => commands::forward::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            // `{:#}` puts the whole context chain on one line: file, section, problem.
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}
