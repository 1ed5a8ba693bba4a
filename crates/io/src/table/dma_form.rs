//! A modulus table in a DMA form other than the plain one (docs/
//! ARCHITECTURE.md, "Contract", "DMA files": shear or unit-suffixed CSV
//! columns, a temperature column, a TRIOS export), read by
//! [`crate::dma::DmaData::read`] and made one master curve: one
//! temperature only, points sorted by frequency, no frequency twice, two
//! points at least. The DMA reader's messages and notes are said in the
//! scene's words ([`crate::error::table`]).

use std::path::Path;

use super::ModulusTable;
use crate::columns::OMEGA_MEASURED;
use rollfit_fit::master::grouping::group_temperatures;

use crate::dma::{DmaData, DmaOptions, ModulusKind};
use crate::error::IoError;

/// Reads a file of the DMA forms and makes one master curve of it;
/// `shifted_points`: the file looks like the master.csv of `rollfit
/// master`, which a refusal then says.
pub(super) fn read(
    path: &Path,
    poisson: f64,
    kind: Option<ModulusKind>,
    sheet: Option<&str>,
    shifted_points: bool,
) -> Result<ModulusTable, IoError> {
    // ν matters only for shear moduli: a bad ν is refused only then, and
    // named as the scene's (the DMA reader would call it the fit's).
    let usable = rollfit_model::check_poisson(poisson).is_ok();
    let options = DmaOptions {
        kind,
        ..DmaOptions::default()
    };
    let data = DmaData::read_sheet(path, if usable { poisson } else { 0.5 }, &options, sheet)
        .map_err(|e| err!("modulus table {}", in_scene_words(&e.to_string())))?;
    if !usable && data.kind == ModulusKind::Shear {
        return Err(err!(
            "modulus table {}: holds shear moduli G′, G″; converting them to Young's moduli \
         (E = 2(1+ν)G) needs [substrate] poisson in [0, 0.5], not {poisson}",
            path.display()
        ));
    }
    let isotherms = group_temperatures(data.points.iter().map(|p| p.temperature));
    if isotherms.len() > 1 {
        let isotherms: Vec<TableIsotherm> = isotherms
            .iter()
            .map(|i| {
                let lines = i.points.iter().map(|&k| data.lines[k]);
                TableIsotherm {
                    temperature: i.temperature,
                    points: i.points.len(),
                    lines: (lines.clone().min().unwrap_or(0), lines.max().unwrap_or(0)),
                }
            })
            .collect();
        return Err(err!(
            "modulus table {}: {} temperatures: {}; a table is one master curve at one \
             temperature. {}",
            path.display(),
            isotherms.len(),
            list_isotherms(&isotherms),
            advice(path, shifted_points)
        ));
    }

    // How the file was read first, then what was left out.
    let mut notes: Vec<String> = data.notes.iter().map(|m| in_scene_words(m)).collect();
    if let Some(isotherm) = isotherms.first() {
        notes.push(format!(
            "{}: all points at {}: read as the master curve at that temperature \
             ([material.shift] T_ref, if given, should be it)",
            path.display(),
            celsius(isotherm.temperature)
        ));
    }
    notes.extend(data.warnings.iter().map(|m| in_scene_words(m)));
    let order = sorted(path, &data)?;
    Ok(ModulusTable {
        omega: order.iter().map(|&k| data.points[k].omega).collect(),
        storage: order.iter().map(|&k| data.points[k].storage).collect(),
        loss: order.iter().map(|&k| data.points[k].loss).collect(),
        lines: order.iter().map(|&k| data.lines[k]).collect(),
        notes,
    })
}

/// The points of `data` in increasing frequency; refused with a frequency
/// twice or fewer than two points.
fn sorted(path: &Path, data: &DmaData) -> Result<Vec<usize>, IoError> {
    let mut order: Vec<usize> = (0..data.points.len()).collect();
    order.sort_by(|&a, &b| data.points[a].omega.total_cmp(&data.points[b].omega));
    for pair in order.windows(2) {
        let (a, b) = (&data.points[pair[0]], &data.points[pair[1]]);
        if b.omega <= a.omega {
            let (first, second) = (data.lines[pair[0]], data.lines[pair[1]]);
            return Err(err!(
                "modulus table {}, lines {} and {}: the same frequency ω = {omega} rad/s twice; a master \
         curve has one modulus per frequency: remove or average the repeated rows",
                path.display(),
                first.min(second),
                first.max(second),
                omega = a.omega
            ));
        }
    }
    if order.len() < 2 {
        return Err(err!(
            "modulus table {}: the table has {rows} usable data row(s): at least two frequencies \
         are needed to interpolate",
            path.display(),
            rows = order.len()
        ));
    }
    Ok(order)
}

/// One temperature of a table that holds several: its (mean) temperature,
/// points and first and last line.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct TableIsotherm {
    /// °C.
    temperature: f64,
    /// Points at it.
    points: usize,
    /// The first and last file line of its points.
    lines: (usize, usize),
}

/// A message of the DMA reader in the words of a scene file: the DMA
/// reader serves `rollfit compare` and `report`, where ν is the fit's and
/// the modulus kind a command-line flag; here they are `[substrate]
/// poisson` and `[material] modulus`. (A rewording the DMA reader's text
/// no longer matches is left as it is: still true, in the other words.)
fn in_scene_words(message: &str) -> String {
    message
        .replace("(the fit's)", "([substrate] poisson)")
        .replace("--dma-modulus shear", "[material] modulus = \"shear\"")
        .replace("--dma-modulus young", "[material] modulus = \"young\"")
}

/// A temperature as a message shows it: to 0.1 K (an isotherm's mean,
/// within a controller's scatter), without trailing zeros.
fn celsius(t: f64) -> String {
    // + 0.0: −0.02 °C shows as 0, not −0.
    format!("{} °C", (t * 10.0).round() / 10.0 + 0.0)
}

/// With a few isotherms each with its points and lines; a whole
/// temperature programme by its temperatures.
fn list_isotherms(isotherms: &[TableIsotherm]) -> String {
    let listed: Vec<String> = if isotherms.len() <= 6 {
        isotherms
            .iter()
            .map(|i| {
                format!(
                    "{} ({} point(s), lines {}–{})",
                    celsius(i.temperature),
                    i.points,
                    i.lines.0,
                    i.lines.1
                )
            })
            .collect()
    } else {
        isotherms.iter().map(|i| celsius(i.temperature)).collect()
    };
    listed.join(", ")
}

/// What to do with a table of several temperatures.
fn advice(path: &std::path::Path, shifted_points: bool) -> String {
    if shifted_points {
        format!(
            "This looks like the master.csv of `rollfit master` (column {OMEGA_MEASURED}): its \
             points scatter where the isotherms overlap; give the smooth master curve beside it, \
             modulus.csv, as the table instead"
        )
    } else {
        format!(
            "Use [material] model = \"dma\", file = \"…\" to shift the isotherms into a master \
             curve, or build one with `rollfit master {}`",
            path.display()
        )
    }
}
