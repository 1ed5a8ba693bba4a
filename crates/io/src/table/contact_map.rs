//! What the model's contact-map error means in a modulus table (docs/
//! ARCHITECTURE.md, "Where each equation lives": the tabulated master
//! curve): the dynamic contact size r ∝ |E*|^(−1/n) needs ω·r(ω) to
//! increase, which a table whose |E*| rises faster than ω^n between
//! neighbouring rows (scatter of overlapping isotherms) breaks. The
//! explanation names those rows by their file lines.

use std::path::Path;

use super::ModulusTable;

/// What the model's contact-map error
/// (`rollfit_model::ModelError::ContactMapNotIncreasing`: "the contact map
/// ω·a(ω) is not increasing at ω = … rad/s (the modulus rises faster than
/// ω^n)") means in `table`, read from `path`: the rows
/// whose frequencies bracket `omega`, the neighbouring rows within a
/// decade of it between which |E*| rises faster than ω^`exponent` (the
/// five nearest, in increasing ω, with their ω and |E*|; failing any, the
/// steepest rows nearby), and what to do.
///
/// `omega` is the table's frequency, rad/s: for a material shifted to a
/// temperature that is the model's ω times a_T. `exponent` is n of the
/// contact size r ∝ |E*|^(−1/n): 3 for a sphere, 2 for a cylinder.
pub fn explain_contact_map(table: &ModulusTable, path: &Path, omega: f64, exponent: f64) -> String {
    /// How many steep row pairs are listed.
    const LISTED_PAIRS: usize = 5;
    let rows = table.omega.len();
    let abs: Vec<f64> = table
        .storage
        .iter()
        .zip(&table.loss)
        .map(|(s, l)| s.hypot(*l))
        .collect();
    let line = |i: usize| table.lines.get(i).copied().unwrap_or(0);
    let row = |i: usize| {
        format!(
            "line {} (ω = {:.3e} rad/s, |E*| = {:.3e} Pa)",
            line(i),
            table.omega[i],
            abs[i]
        )
    };
    let mut text = format!(
        "modulus table {}: the contact map fails at ω = {omega:.3e} rad/s",
        path.display()
    );
    let above = table.omega.partition_point(|&w| w <= omega);
    text.push_str(&match above {
        _ if rows == 0 => String::new(),
        0 => format!(", below the first row, {}", row(0)),
        k if k == rows && table.omega[k - 1] < omega => {
            format!(", above the last row, {}", row(k - 1))
        }
        k if table.omega[k - 1] == omega || k == rows => format!(", at {}", row(k - 1)),
        k => format!(", between {} and {}", row(k - 1), row(k)),
    });

    // The log–log slope of |E*| between neighbouring rows i and i + 1,
    // and how far (in ln ω) that interval lies from ω.
    let ln_omega = omega.ln();
    let slope = |i: usize| (abs[i + 1] / abs[i]).ln() / (table.omega[i + 1] / table.omega[i]).ln();
    let distance = |i: usize| {
        let (lo, hi) = (table.omega[i].ln(), table.omega[i + 1].ln());
        (lo - ln_omega).max(ln_omega - hi).max(0.0)
    };
    let pair = |i: usize| {
        format!(
            "\n  line {} → line {}: ω {:.3e} → {:.3e} rad/s, |E*| {:.3e} → {:.3e} Pa \
             (log–log slope {:.1})",
            line(i),
            line(i + 1),
            table.omega[i],
            table.omega[i + 1],
            abs[i],
            abs[i + 1],
            slope(i)
        )
    };
    let intervals = 0..rows.saturating_sub(1);
    let steep: Vec<usize> = intervals.clone().filter(|&i| slope(i) > exponent).collect();
    let mut near: Vec<usize> = steep
        .iter()
        .copied()
        .filter(|&i| distance(i) <= 10f64.ln())
        .collect();
    near.sort_by(|&a, &b| distance(a).total_cmp(&distance(b)));
    if near.is_empty() {
        // The interpolant's slope at a row may reach three times a chord's:
        // scatter steepens it between rows that are not steep themselves.
        let mut nearby: Vec<usize> = intervals
            .filter(|&i| distance(i) <= 10f64.ln() && slope(i) > 0.0)
            .collect();
        nearby.sort_by(|&a, &b| slope(b).total_cmp(&slope(a)));
        text.push_str(&format!(
            ". No neighbouring rows within a decade of it rise faster than ω^{exponent}, but \
             the curve interpolated between them does (scatter steepens it: its slope at a row \
             may reach three times the chords'){}",
            if nearby.is_empty() {
                String::new()
            } else {
                "; the steepest rows nearby:".to_string()
            }
        ));
        for &i in nearby.iter().take(3) {
            text.push_str(&pair(i));
        }
    } else {
        text.push_str(&format!(
            ". There |E*| rises faster than ω^{exponent} between neighbouring rows, faster than \
             the dynamic contact size can follow (r ∝ |E*|^(−1/{exponent})):"
        ));
        // The nearest ones, listed in the table's order.
        let mut listed: Vec<usize> = near.iter().copied().take(LISTED_PAIRS).collect();
        listed.sort_unstable();
        for &i in &listed {
            text.push_str(&pair(i));
        }
        let more = near.len().saturating_sub(LISTED_PAIRS);
        if more > 0 {
            text.push_str(&format!("\n  and {more} more pair(s) within a decade"));
        }
        if steep.len() > near.len() {
            text.push_str(&format!(
                "\n  ({} such pair(s) in the whole table)",
                steep.len()
            ));
        }
    }
    text.push_str(
        "\nSmooth or bin the table (overlapping isotherms scatter), or give the isotherms \
         themselves with [material] model = \"dma\", file = \"…\", which fits a smooth causal \
         Prony series.",
    );
    text
}
