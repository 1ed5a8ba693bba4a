//! `rollfit master` on a stress-relaxation file (E(t) or G(t) against t,
//! several temperatures) or a creep file (J(t) or D(t)): the isotherms
//! superposed in log t with the shift machinery of the frequency sweeps
//! (t_r = t/a_T), a smooth Prony series E(t) = E0 + Σ H_k e^(−t/τ_k)
//! fitted to the master curve — to E(t), or through its exact creep
//! compliance to D(t) (`rollfit_fit::master::relaxation`) — and the same
//! material.toml.
//!
//! Writes, to DIR as a whole (nothing on an error):
//! - master.csv: every point at the reference state — t (t/a_T, s),
//!   E_relax (Young's, Pa, divided by b_T) or D_creep (tensile, 1/Pa,
//!   times b_T), T (°C), t_measured (s);
//! - shift.csv: as for frequency sweeps;
//! - relaxation.csv: the series' E(t) over the data's reduced times, t,
//!   E_relax;
//! - creep.csv (creep files): the series' exact creep compliance over the
//!   same times, t, D_creep;
//! - modulus.csv: the same series as E′, E″, tan δ over ω = 1/t of the
//!   data's reduced times (omega, E_storage, E_loss, tan_delta);
//! - material.toml: as for frequency sweeps;
//! - master.json: `domain` = "time", `time_range`, `omega_range`, the shift
//!   keys of a frequency master.json, `quantity` ("relaxation" or
//!   "creep"), `prony` with `method` and `misfit_relaxation` (or
//!   `misfit_creep`, RMS log10 D, decades);
//! - master.png and master.svg: E(t/a_T) of the isotherms with the series,
//!   each point's misfit and the shift factors (`super::pictures`).
//!
//! No Kramers–Kronig floor (E(t) has no second component to check
//! against), and no van Gurp–Palmen plot (no phase angle).

use anyhow::{Context, Result};
use rollfit_fit::master::quality::MasterQuality;
use rollfit_fit::master::relaxation::TimeQuantity;
use rollfit_io::columns::{D_CREEP, E_RELAX, TIME, TIME_MEASURED};
use rollfit_io::fit_dir::columns::{MODULUS_COLUMNS, MODULUS_CSV, T};
use rollfit_io::{csv_text, output};
use rollfit_model::ViscoelasticModulus;
use rollfit_report::master_input::time::{self, RelaxationBuilt};
use serde::Serialize;

use super::shift_out::{ShiftJson, headline, shift_csv, shift_text};
use super::{Args, CURVE_PER_DECADE};
use crate::stdout;

/// Runs `rollfit master` on a relaxation file (DIR already checked).
pub(super) fn run(args: &Args, settings: &rollfit_fit::master::MasterSettings) -> Result<()> {
    let (poisson, whose) = crate::commands::compare::poisson_source(args.poisson);
    let input = args.files.input(&args.dma, None, args.dma_modulus);
    let built = time::build(&input, poisson, settings)?;
    let creep = built.data.quantity == TimeQuantity::Creep;
    if args.dma_modulus.is_some() && !creep {
        eprintln!(
            "warning: --dma-modulus applies to TRIOS files; a relaxation file says Young's or \
             shear with its column name (E_relax or G_relax): ignored"
        );
    }
    for note in &built.data.notes {
        eprintln!("note: {}", note.replace("(the fit's)", whose));
    }
    let shift = &built.master.shift;
    if shift.shifts.len() > 1 {
        eprintln!("note: shift law {}: {}", shift.law.name(), shift.reason);
    } else {
        eprintln!("note: {}", shift.reason);
    }
    for warning in &built.master.warnings {
        eprintln!("warning: {warning}");
    }
    // No Kramers–Kronig floor for E(t): the shifts and the series' misfit
    // are judged.
    let quality = built.master.quality();
    super::gate(&quality, args)?;
    super::strict_gate(&built.master.shift, args)?;
    let files = encode(&built, poisson, &quality)?;
    let named: Vec<(&str, &[u8])> = files.iter().map(|(n, b)| (*n, b.as_slice())).collect();
    output::replace_folder(&args.output, output::Writer::Master, args.force, &named)?;
    stdout::write_stdout(summary(&built).as_bytes())?;
    eprintln!("wrote {}", args.output.display());
    Ok(())
}

/// The reduced times of the data, and `count` + 1 log-spaced times over
/// them.
fn times(built: &RelaxationBuilt) -> Vec<f64> {
    let points = &built.master.points;
    let (lo, hi) = (
        points[0].reduced_time,
        points[points.len() - 1].reduced_time,
    );
    let decades = (hi / lo).log10().max(0.0);
    let count = ((decades * CURVE_PER_DECADE).ceil() as usize).max(2);
    (0..=count)
        .map(|j| lo * (hi / lo).powf(j as f64 / count as f64))
        .collect()
}

/// Every file of DIR, encoded.
fn encode(
    built: &RelaxationBuilt,
    poisson: f64,
    quality: &MasterQuality,
) -> Result<Vec<(&'static str, Vec<u8>)>> {
    let master = &built.master;
    let prony = &master.fit.prony;
    let creep = master.quantity == TimeQuantity::Creep;
    let value = if creep { D_CREEP } else { E_RELAX };
    let master_csv = csv_text::csv_bytes(
        &[TIME, value, T, TIME_MEASURED],
        master
            .points
            .iter()
            .map(|p| vec![p.reduced_time, p.value, p.temperature, p.time]),
    )?;
    let grid = times(built);
    let relaxation_csv = csv_text::csv_bytes(
        &[TIME, E_RELAX],
        grid.iter().map(|&t| vec![t, prony.relaxation_modulus(t)]),
    )?;
    let creep_csv = if creep {
        let series = master.quantity.of_series(prony);
        Some(csv_text::csv_bytes(
            &[TIME, D_CREEP],
            grid.iter().map(|&t| vec![t, series(t)]),
        )?)
    } else {
        None
    };
    // ω = 1/t over the same range, ascending.
    let modulus_csv = csv_text::csv_bytes(
        &MODULUS_COLUMNS[..4],
        grid.iter().rev().map(|&t| {
            let e = prony.modulus(1.0 / t);
            vec![1.0 / t, e.re, e.im, e.im / e.re]
        }),
    )?;
    let mut json = serde_json::to_vec_pretty(&Summary::of(built, poisson, quality))
        .context("cannot format master.json")?;
    json.push(b'\n');
    let picture = super::pictures::relaxation(built, &grid, poisson, quality)?;
    Ok(vec![
        ("master.csv", master_csv),
        ("shift.csv", shift_csv(&master.shift)?),
        ("relaxation.csv", relaxation_csv),
        (MODULUS_CSV, modulus_csv),
        ("material.toml", built.material_file()?),
        ("master.json", json),
    ]
    .into_iter()
    .chain(creep_csv.map(|bytes| ("creep.csv", bytes)))
    .chain(picture)
    .collect())
}

/// master.json of a relaxation or creep file.
#[derive(Serialize)]
struct Summary {
    dma_file: String,
    dma_format: &'static str,
    /// "time": relaxation or creep isotherms.
    domain: &'static str,
    /// "relaxation" or "creep".
    quantity: &'static str,
    modulus_kind: &'static str,
    poisson: f64,
    #[serde(rename = "T_ref")]
    t_ref: f64,
    shift_law: &'static str,
    shift_law_asked: &'static str,
    shift_law_reason: String,
    vertical: bool,
    isotherms: usize,
    points: usize,
    /// Reduced times of the data, s.
    time_range: [f64; 2],
    /// 1/t over them, rad/s: where the series is determined.
    omega_range: [f64; 2],
    #[serde(flatten)]
    shift: ShiftJson,
    prony: PronySummary,
    /// The gate's verdict (the shifts alone).
    quality: MasterQuality,
    warnings: Vec<String>,
    notes: Vec<String>,
}

#[derive(Serialize)]
struct PronySummary {
    terms: usize,
    #[serde(rename = "E0")]
    static_modulus: f64,
    #[serde(rename = "E1")]
    glassy_modulus: f64,
    lambda: f64,
    /// How the series was fitted.
    method: &'static str,
    /// RMS log10 misfit of E(t), decades (relaxation files).
    #[serde(skip_serializing_if = "Option::is_none")]
    misfit_relaxation: Option<f64>,
    /// RMS log10 misfit of D(t) by the series' exact creep compliance,
    /// decades (creep files).
    #[serde(skip_serializing_if = "Option::is_none")]
    misfit_creep: Option<f64>,
    converged: bool,
}

impl Summary {
    fn of(built: &RelaxationBuilt, poisson: f64, quality: &MasterQuality) -> Summary {
        let m = &built.master;
        let (lo, hi) = (
            m.points[0].reduced_time,
            m.points[m.points.len() - 1].reduced_time,
        );
        Summary {
            dma_file: built.data.path.display().to_string(),
            dma_format: match m.quantity {
                TimeQuantity::Relaxation => "csv-relaxation",
                TimeQuantity::Creep => "csv-creep",
            },
            domain: "time",
            quantity: m.quantity.name(),
            modulus_kind: built.data.kind.name(),
            poisson,
            t_ref: built.settings.t_ref(),
            shift_law: m.shift.law.name(),
            shift_law_asked: built.settings.law().name(),
            shift_law_reason: m.shift.reason.clone(),
            vertical: built.settings.vertical(),
            isotherms: m.shift.shifts.len(),
            points: m.points.len(),
            time_range: [lo, hi],
            omega_range: [1.0 / hi, 1.0 / lo],
            shift: ShiftJson::of(&m.shift),
            prony: PronySummary {
                terms: m.fit.prony.relaxation_times().len(),
                static_modulus: m.fit.prony.static_modulus(),
                glassy_modulus: m.fit.prony.glassy_modulus(),
                lambda: m.fit.lambda,
                method: m.fit.method,
                misfit_relaxation: (m.quantity == TimeQuantity::Relaxation).then_some(m.fit.misfit),
                misfit_creep: (m.quantity == TimeQuantity::Creep).then_some(m.fit.misfit),
                converged: m.fit.converged,
            },
            quality: quality.clone(),
            warnings: m.warnings.clone(),
            notes: built.data.notes.clone(),
        }
    }
}

/// The readable summary of stdout.
fn summary(built: &RelaxationBuilt) -> String {
    let m = &built.master;
    let creep = m.quantity == TimeQuantity::Creep;
    let (title, values) = if creep {
        ("Creep", "compliances")
    } else {
        ("Relaxation", "moduli")
    };
    let mut out = format!(
        "{title} {} ({} {values}): {}\n",
        built.data.path.display(),
        built.data.kind.name(),
        headline(&m.shift, m.points.len(), &built.settings, " (t/a_T)")
    );
    out += &super::temperature_sources(&built.files);
    out += &shift_text(&m.shift);
    out += &super::shift_out::window_text(&m.shift, None, "", "");
    out += &format!(
        "Prony series: {} terms, λ = {:.3e}; RMS misfit {} {:.4} decades\n",
        m.fit.prony.relaxation_times().len(),
        m.fit.lambda,
        if creep {
            "D(t) (the series' exact creep compliance)"
        } else {
            "E(t)"
        },
        m.fit.misfit
    );
    if creep {
        out += &format!("Method: {}\n", m.fit.method);
    }
    out
}
