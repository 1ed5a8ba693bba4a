//! `rollfit`: rolling-friction measurements ↔ viscoelastic master curves
//! (Persson, Eur. Phys. J. E 33, 2010). See docs/ARCHITECTURE.md,
//! "Contract", for the commands, the scene file and the CSV columns other
//! programs rely on.

// The doc comments of this crate are its command-line help (clap derives
// `--help` from them), written for a terminal: `[fit]` names a TOML table
// and `<name>` a placeholder, not an intra-doc link or an HTML tag.
// Escaping them would print the escapes in the help.
#![allow(rustdoc::broken_intra_doc_links, rustdoc::invalid_html_tags)]

mod commands;
mod hints;
mod progress;
mod stdout;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Rolling friction on viscoelastic solids: predict μ(v) from a modulus, or
/// recover the modulus from μ(v).
///
/// Input files (scenes, data, DMA files, modulus tables, manifests, fit
/// folders) are read whole: each must be a regular file (not a FIFO or a
/// device such as /dev/zero) of at most 1 GiB. The environment variable
/// ROLLFIT_MAX_INPUT_BYTES sets another limit, in bytes or with K, M, G or
/// T (powers of 1024): ROLLFIT_MAX_INPUT_BYTES=4G.
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
    /// mean_pressure_static (Pa), centroid_shift (m), gt_alpha. With
    /// --noise REL (a synthetic measurement): v, mu (noisy), sigma,
    /// mu_exact, then the same columns from mu_low_speed on. When [sweep]
    /// sets a temperature, a last column T (°C); a list of temperatures
    /// (a synthetic temperature set) gives one block of rows per
    /// temperature, in the listed order.
    Forward(commands::forward::Args),
    /// Recover the master curve E*(ω) from measured μ(v) (Persson 2010,
    /// Appendix B).
    ///
    /// Reads the scene's [geometry], [substrate], [contact], optional
    /// [material] (starting point) and [fit] (scale anchor, settings) and a
    /// table (CSV, `;` or tab, decimal commas, unit-suffixed headers) or
    /// workbook with columns v (m/s), mu, optional sigma and T. Writes
    /// DIR/fit.json, DIR/modulus.csv (omega, E_storage, E_loss, tan_delta,
    /// abs_E and their bands, over the window the data determine) and
    /// DIR/mu.csv (v, mu_measured, mu_fit, [sigma], residual). Exits
    /// non-zero if the fit did not converge, unless --allow-unconverged, or
    /// if it does not describe the data (fit_quality poor), unless
    /// --allow-poor-fit.
    Fit(commands::fit::Args),
    /// Run many fits in parallel: one per entry of a manifest.
    ///
    /// The manifest (TOML) lists [[entry]] tables with a name, a scene and a
    /// data file (paths relative to the manifest's folder) and optional
    /// settings (method, lambda, seed, starts, terms; defaults in
    /// [defaults]). Each entry writes what `rollfit fit` writes to
    /// DIR/<name>/; DIR/summary.csv has one row per entry (entry, status,
    /// objective, misfit_per_point, omega_min, omega_max, wall_time_s,
    /// converged, C1, C2, message). Entries with an existing
    /// DIR/<name>/fit.json are skipped unless --force, so running the same
    /// command again resumes a batch; --shard i/n spreads it over machines.
    /// Exits non-zero if an entry failed, did not converge (unless
    /// --allow-unconverged) or converged to a fit that does not describe its
    /// data (status "poor", unless --allow-poor-fit).
    Batch(commands::batch::Args),
    /// Draw the pictures of a fit and write DIR/report.html.
    ///
    /// Reads what `rollfit fit` wrote to DIR and writes, as PNG and SVG:
    /// friction (μ(v) with relative residuals), master_curve (E′, E″ and
    /// tan δ with the window and 1σ bands, DMA points with --dma), spectrum
    /// (H_k against τ_k, undetermined terms marked), convergence (V against
    /// evaluations per run), and for a temperature set master_friction (μ
    /// against v·a_T) and shift (log a_T against T); friction then shows μ
    /// per T in one colour each.
    /// report.html holds them all inline, with the fit's table and, with
    /// --dma, the comparison (also written to DIR/compare.json).
    Report(commands::report::Args),
    /// Compare the recovered master curve with DMA data.
    ///
    /// Prints, and writes to DIR/compare.json, the errors of tan δ, |E|,
    /// E′ and E″ over the overlap of the fit's window and the DMA
    /// frequencies, and how well a causal (Prony) model fits the DMA data
    /// themselves (dma_kk_misfit_storage, dma_kk_misfit_loss).
    Compare(commands::compare::Args),
    /// Build a master curve from DMA isotherms by time–temperature
    /// superposition, and the material a scene can use.
    ///
    /// Reads a DMA file (CSV, TRIOS LIMS export or a workbook such as an
    /// Eplexor Excel export; shear or Young's),
    /// finds the shift factors a_T from the overlap of neighbouring
    /// isotherms in log E′ and log tan δ (and b_T with --vertical), fits
    /// WLF or Arrhenius to them with standard errors, and fits a smooth
    /// causal Prony series to the shifted E′ and E″. Writes DIR/master.csv
    /// (omega, E_storage, E_loss, tan_delta, T, omega_measured),
    /// DIR/shift.csv (T, log_aT, log_aT_measured, log_bT, points),
    /// DIR/modulus.csv (the series: omega, E_storage, E_loss, tan_delta),
    /// DIR/material.toml ([material] model = "prony" with
    /// [material.shift]), DIR/master.json and DIR/master.{png,svg}.
    Master(commands::master::Args),
    /// Measure speed against accuracy: the forward model's rungs and
    /// quadrature tolerances, and the fitting methods and their budgets.
    ///
    /// Writes DIR/forward.csv (rung, tolerance, time_per_mu_s,
    /// max_rel_error, rms_rel_error), DIR/fit.csv (method, max_evaluations,
    /// wall_time_s, evaluations, tan_delta_rms_rel, converged) and the
    /// charts DIR/forward.{png,svg} and DIR/fit.{png,svg}.
    Bench(commands::bench::Args),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match &cli.command {
        Command::Forward(args) => commands::forward::run(args),
        Command::Fit(args) => commands::fit::run(args),
        Command::Batch(args) => commands::batch::run(args),
        Command::Report(args) => commands::report::run(args),
        Command::Compare(args) => commands::compare::run(args),
        Command::Master(args) => commands::master::run(args),
        Command::Bench(args) => commands::bench::run(args),
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

#[cfg(test)]
mod tests {
    //! Negative numbers as users type them: `--T-ref -5`, not
    //! only `--T-ref=-5`. clap reads a word starting with `-` as a flag
    //! unless the option allows hyphen values; every option that takes a
    //! number allows them, so its own parser judges the value (a range
    //! message instead of "unexpected argument '-5'"). `allow_hyphen_values`
    //! rather than `allow_negative_numbers`: the latter's test of a number
    //! rejects `-5e-3` and lists such as `-5,11.6,79.9`.

    use std::any::TypeId;
    use std::path::PathBuf;

    use clap::{CommandFactory, Parser};
    use rollfit_fit::{FrictionFactor, Method, Physics, ShiftKind};

    use super::{Cli, Command};

    /// Every option of every command that takes a value allows hyphen
    /// values, except those whose value cannot be a number: paths, names
    /// (sheet, solver, physics, shift law, friction factor, unit) and fixed
    /// choices.
    #[test]
    fn every_numeric_option_takes_a_leading_minus() {
        let not_numbers = [
            TypeId::of::<PathBuf>(),
            TypeId::of::<String>(),
            TypeId::of::<Method>(),
            TypeId::of::<Physics>(),
            TypeId::of::<ShiftKind>(),
            TypeId::of::<FrictionFactor>(),
            // `master --units`: a unit's name with its factor to pascals.
            TypeId::of::<(&'static str, f64)>(),
        ];
        let cli = Cli::command();
        let mut checked = 0;
        for command in cli.get_subcommands() {
            for arg in command.get_opts() {
                let parser = arg.get_value_parser();
                let kind = parser.type_id();
                if not_numbers.iter().any(|t| kind == *t) || !arg.get_possible_values().is_empty() {
                    continue;
                }
                assert!(
                    arg.is_allow_hyphen_values_set(),
                    "rollfit {} --{}: a numeric option without allow_hyphen_values",
                    command.get_name(),
                    arg.get_long().unwrap_or_default()
                );
                checked += 1;
            }
        }
        assert!(checked >= 10, "only {checked} numeric options found");
    }

    #[test]
    fn negative_values_parse_as_typed() {
        let cli = Cli::try_parse_from([
            "rollfit",
            "master",
            "dma.csv",
            "--T-ref",
            "-5",
            "--vertical",
        ])
        .unwrap();
        let Command::Master(args) = cli.command else {
            panic!("not master")
        };
        assert_eq!(args.t_ref, Some(-5.0));
        assert!(args.vertical);
        let cli =
            Cli::try_parse_from(["rollfit", "master", "dma.csv", "--T-ref", "-2.5e1"]).unwrap();
        let Command::Master(args) = cli.command else {
            panic!("not master")
        };
        assert_eq!(args.t_ref, Some(-25.0));
        let cli =
            Cli::try_parse_from(["rollfit", "report", "fit", "--dma-wlf", "-5,11.6,79.9"]).unwrap();
        let Command::Report(args) = cli.command else {
            panic!("not report")
        };
        let wlf = args.dma_flags.dma_wlf.expect("--dma-wlf parsed");
        assert_eq!((wlf.t_ref, wlf.c1, wlf.c2), (-5.0, 11.6, 79.9));
        // A negative value where none is allowed is the option's own
        // message, not "unexpected argument".
        let error = Cli::try_parse_from(["rollfit", "master", "dma.csv", "--poisson", "-0.1"]);
        if let Err(error) = error {
            assert_ne!(
                error.kind(),
                clap::error::ErrorKind::UnknownArgument,
                "{error}"
            );
        }
        let error = Cli::try_parse_from(["rollfit", "fit", "s.toml", "d.csv", "--seed", "-1"])
            .expect_err("a negative seed");
        assert_eq!(
            error.kind(),
            clap::error::ErrorKind::ValueValidation,
            "{error}"
        );
    }
}
