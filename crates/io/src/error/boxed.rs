//! The two causes of [`super::IoError`] with the most context, boxed in
//! their variants so that every `Result<_, IoError>` stays small.

use std::path::PathBuf;

use thiserror::Error;

use super::data::{CellRef, RowRef};
use super::parts::{ColumnRef, StepRef};

/// Two columns for one quantity in a DMA CSV (`f` and `omega`, or
/// `E_storage` and `E_storage_MPa`).
#[derive(Debug, Error)]
#[error(
    "{}, {line}: two {quantity} columns, {first} and {second}: keep one{}",
    path.display(),
    if *quantity == "frequency" { " (f in Hz or omega in rad/s)" } else { "" }
)]
pub struct DuplicateQuantity {
    /// The DMA file.
    pub path: PathBuf,
    /// The header's line or row.
    pub line: RowRef,
    /// "frequency", "temperature" or the modulus column's base name.
    pub quantity: &'static str,
    /// The first column.
    pub first: ColumnRef,
    /// The second column.
    pub second: ColumnRef,
}

/// A TRIOS variable in a unit rollfit does not know.
#[derive(Debug, Error)]
#[error(
    "{}, line {line}: {step}: {quantity} variable \"{variable}\" (column {number}) has unit \
     \"{unit}\"; known units: {}",
    path.display(),
    known.join(", ")
)]
pub struct UnknownUnit {
    /// The TRIOS file.
    pub path: PathBuf,
    /// Line of `Units`.
    pub line: usize,
    /// The step.
    pub step: StepRef,
    /// "frequency", "storage", "loss" or "temperature".
    pub quantity: &'static str,
    /// The variable's name.
    pub variable: String,
    /// Its column, from 1.
    pub number: usize,
    /// The unit found.
    pub unit: String,
    /// The units known for the quantity.
    pub known: Vec<&'static str>,
}

/// A DMA column in a unit not known, from its name (`E' [psi]`) or a
/// units row below the header.
#[derive(Debug, Error)]
#[error(
    "{}, {cell}: column {column:?}: unit {unit:?} not known for {quantity}; known: {known}",
    path.display()
)]
pub struct DmaUnknownUnit {
    /// The DMA file.
    pub path: PathBuf,
    /// The header's or the units row's cell.
    pub cell: CellRef,
    /// The header as written.
    pub column: String,
    /// "a frequency", "a modulus", "a temperature".
    pub quantity: &'static str,
    /// The unit as written.
    pub unit: String,
    /// The units known, for the message.
    pub known: &'static str,
}
