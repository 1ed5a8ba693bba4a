//! A table's E′ must not fall as ω rises. The storage modulus of a causal
//! linear viscoelastic solid is E′(ω) = E0 + Σ H_k ω²τ_k²/(1 + ω²τ_k²),
//! each term rising with ω, so E′ never falls; a table whose E′ falls
//! clearly is no modulus (columns swapped, frequencies in the wrong unit
//! or order, a shear and a Young's column mixed) and would be interpolated
//! into friction without a word.
//!
//! Measured tables scatter: overlapping isotherms sorted into one table
//! carry a few per cent each, and on a flat rubbery plateau a later point
//! may lie below an earlier one by up to about four times that
//! (tests/table: 4 % scatter). So a row is refused only when its E′ lies
//! more than [`FALL_TOLERANCE`] below the largest E′ at any lower
//! frequency: far beyond scatter, and the fall of any table that is not a
//! master curve at all.

use std::path::Path;

use super::ModulusTable;
use crate::error::IoError;

/// The relative fall of E′ below its running maximum that is refused.
pub(super) const FALL_TOLERANCE: f64 = 0.2;

/// Refuses `table` (read from `path`) at its first row whose E′ lies more
/// than [`FALL_TOLERANCE`] below the largest E′ before it, naming both rows.
pub(super) fn check(path: &Path, table: &ModulusTable) -> Result<(), IoError> {
    let mut peak = 0;
    for (row, &storage) in table.storage.iter().enumerate() {
        if storage > table.storage[peak] {
            peak = row;
        } else if storage < (1.0 - FALL_TOLERANCE) * table.storage[peak] {
            let line = |i: usize| table.lines.get(i).copied().unwrap_or(i + 1);
            return Err(err!(
                "modulus table {}, line {line}: E_storage = {storage:.4e} Pa at ω = {omega:.4e} rad/s is \
         {:.0} % below E_storage = {peak_storage:.4e} Pa at line {peak_line} (ω = \
         {peak_omega:.4e} rad/s): the storage modulus of a viscoelastic solid rises with \
         frequency (every relaxation term adds H ω²τ²/(1+ω²τ²)), and a fall of more than 20 % is \
         no measurement scatter; check that the columns are E_storage and E_loss, the \
         frequencies in the unit the header names, and the rows one material at one temperature",
                path.display(),
                100.0 * (1.0 - storage / table.storage[peak]),
                line = line(row),
                omega = table.omega[row],
                peak_line = line(peak),
                peak_omega = table.omega[peak],
                peak_storage = table.storage[peak]
            ));
        }
    }
    Ok(())
}
