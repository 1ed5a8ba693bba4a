//! The header of measured data (docs/ARCHITECTURE.md, "Contract",
//! "Measured data"): the first row, above any row of numbers, that names a
//! speed and a friction column (rows above it are titles); the columns it
//! names, each with its unit ([`super::headers`]); and a units row right
//! below it (`mm/s;-;°C`, no number, a speed unit under the speed column),
//! which gives the units of the columns whose names have none. Refused: a
//! unit not understood, two columns of one quantity.

use super::cell::{Cell, Row};
use super::headers::{self, Header};
use super::quantity::Quantity;
use super::source::Source;
use crate::error::data::column_of;
use crate::error::{ColumnName, IoError};
use crate::units::{Conversion, Unit, speed_unit};

/// What each cell of `row` names as a header.
pub(super) fn classify(row: &Row) -> Vec<Header> {
    row.cells
        .iter()
        .map(|c| headers::classify(&c.name()))
        .collect()
}

/// Whether `row` names a speed and a friction column: the header.
pub(super) fn is_header(row: &Row) -> bool {
    let names = classify(row);
    let has = |q: Quantity| names.iter().any(|h| h.quantity() == Some(q));
    has(Quantity::Speed) && has(Quantity::Friction)
}

/// The index of the header row of a sheet: the first row naming a speed
/// and a friction column, searched until the first row of numbers.
pub(super) fn find_header(rows: &[Row]) -> Option<usize> {
    super::dialect::header_index(rows, |row| *row, is_header).map(|(i, _)| i)
}

/// A column read: where, its header as written, what and in which unit.
pub(super) struct Column {
    pub index: usize,
    pub raw: String,
    pub quantity: Quantity,
    pub conversion: Conversion,
}

impl Column {
    /// The column as messages name it.
    pub fn name(&self) -> ColumnName {
        ColumnName {
            header: self.raw.clone(),
            quantity: self.quantity,
        }
    }
}

/// The columns of a header, each with the unit its name gives, in the
/// order of [`Quantity::ALL`].
pub(super) type NamedColumns = Vec<(Column, Option<Unit>)>;

/// The units of a units row, one per column of [`NamedColumns`] (`None`
/// where the column's name gives one, or the row none).
pub(super) type RowUnits = Vec<Option<Unit>>;

/// The columns named by `rows[0]` (the header), each with its unit, and the
/// units of a units row `rows[1]` if it is one. Errors: a unit not
/// understood, two columns of one quantity.
pub(super) fn columns(
    source: &Source,
    rows: &[Row],
) -> Result<(NamedColumns, Option<RowUnits>), IoError> {
    let row = &rows[0];
    let mut columns: NamedColumns = Vec::new();
    for (index, (cell, header)) in row.cells.iter().zip(classify(row)).enumerate() {
        let raw = cell.name();
        let (quantity, unit) = match header {
            Header::Other => continue,
            Header::BadUnit { quantity, unit } => {
                return Err(err!(
                    "{row} (header): column {header:?}: unknown {} unit {unit:?}; units understood: {}",
                    quantity.what(),
                    quantity.units(),
                    header = raw,
                    row = source.row(row.number)
                ));
            }
            Header::Column { quantity, unit } => (quantity, unit),
        };
        if let Some((other, _)) = columns.iter().find(|(c, _)| c.quantity == quantity) {
            return Err(err!(
                "{row} (header): two {} columns, {first:?} ({}) and {second:?} ({}): keep one",
                quantity.what(),
                column_of(&source.row(row.number), other.index),
                column_of(&source.row(row.number), index),
                first = other.raw,
                row = source.row(row.number),
                second = raw
            ));
        }
        columns.push((
            Column {
                index,
                raw,
                quantity,
                conversion: Conversion::NONE,
            },
            unit,
        ));
    }
    columns.sort_by_key(|(c, _)| c.quantity.index());
    let units = rows
        .get(1)
        .and_then(|next| units_row(source, next, &columns))
        .transpose()?;
    Ok((columns, units))
}

/// The units of a row of units right below the header (`mm/s;-;°C`), for
/// the columns whose names give none; None if `row` is not one (it must
/// hold no number and a speed unit under the speed column).
fn units_row(
    source: &Source,
    row: &Row,
    columns: &NamedColumns,
) -> Option<Result<RowUnits, IoError>> {
    let number = |c: &Cell| match c {
        Cell::Number(_) => true,
        Cell::Text(t) => t.replace(',', ".").parse::<f64>().is_ok(),
        _ => false,
    };
    if row.cells.iter().any(number) {
        return None;
    }
    let text = |index: usize| match row.cells.get(index) {
        Some(Cell::Text(t)) => t.trim_matches(['(', ')', '[', ']']).trim().to_string(),
        _ => String::new(),
    };
    let speed = columns
        .iter()
        .find(|(c, _)| c.quantity == Quantity::Speed)?;
    if speed_unit(&text(speed.0.index)).is_none() {
        // A unit in brackets under the speed column is a units row with a
        // unit not understood, not a row of data that is not a number.
        let bracketed = match row.cells.get(speed.0.index) {
            Some(Cell::Text(t)) => {
                let t = t.trim();
                (t.starts_with('[') && t.ends_with(']')) || (t.starts_with('(') && t.ends_with(')'))
            }
            _ => false,
        };
        return bracketed.then(|| {
            Err(err!(
                "{cell}: column {header:?}: unknown {} unit {unit:?} in the units row; units \
         understood: {}",
                speed.0.quantity.what(),
                speed.0.quantity.units(),
                cell = source.cell(row.number, speed.0.index),
                header = speed.0.raw,
                unit = text(speed.0.index)
            ))
        });
    }
    let mut units = Vec::new();
    for (column, named) in columns {
        let written = text(column.index);
        let Ok(unit) = headers::unit_cell(column.quantity, &written) else {
            return Some(Err(err!(
                "{cell}: column {header:?}: unknown {} unit {unit:?} in the units row; units \
         understood: {}",
                column.quantity.what(),
                column.quantity.units(),
                cell = source.cell(row.number, column.index),
                header = column.raw,
                unit = written
            )));
        };
        units.push(if named.is_some() { None } else { unit });
    }
    Some(Ok(units))
}
