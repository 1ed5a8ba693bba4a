//! The rows below the header of measured data (docs/ARCHITECTURE.md,
//! "Contract", "Measured data"), read into a [`DataTable`]: each value
//! converted to SI and checked against the fit library's ranges
//! (`rollfit_fit::data`), rows with an empty or NaN cell in a column read
//! skipped with one warning, blank rows and trailing empty cells ignored,
//! and what the reading decided (titles above the header, a units row,
//! the delimiter, decimal commas, each column's name and unit) said in
//! notes.

use rollfit_fit::data::{MIN_RELATIVE_SIGMA, column_requirement};

use super::DataTable;
use super::cell::{Cell, Row, number};
use super::header_row::{self, Column, NamedColumns, classify};
use super::quantity::Quantity;
use super::source::Source;
use crate::error::IoError;
use crate::error::data::missing_columns;
use crate::error::data::quoted_list;
use crate::error::data::why_positive;
use crate::error::data::{delimiter_name, key_list};
use crate::units::Conversion;
use rollfit_fit::data::SIGMA_REQUIREMENT;

/// The table of `rows` with its header at position `header` (None: no
/// header found, an error about the first row); `notes` so far (the
/// encoding, the sheet).
///
/// The rows are taken as they come: only those down to the one below the
/// header (a units row, perhaps) are kept, and each row below is read into
/// its values and dropped, so that a logger's file of a million rows never
/// lives as cells at once.
pub(super) fn table(
    source: &Source,
    rows: impl IntoIterator<Item = Row>,
    header: Option<usize>,
    mut notes: Vec<String>,
) -> Result<DataTable, IoError> {
    let mut rows = rows.into_iter();
    let Some(header) = header else {
        let first = rows.find(|r| !r.is_blank()).ok_or(err!(
            "the file is empty: expected a header row (v, mu, optionally sigma and T) and data rows"
        ))?;
        return Err(no_header(source, &first));
    };
    // The header, the rows above it and the one below.
    let head: Vec<Row> = rows.by_ref().take(header + 2).collect();
    let first = head.iter().position(|r| !r.is_blank()).ok_or(err!(
        "the file is empty: expected a header row (v, mu, optionally sigma and T) and data rows"
    ))?;
    let Some(header_row) = head.get(header) else {
        return Err(err!(
            "the file is empty: expected a header row (v, mu, optionally sigma and T) and data rows"
        ));
    };
    if header > first {
        let titles = head[first..header].iter().filter(|r| !r.is_blank()).count();
        notes.push(format!(
            "header on {}; the {titles} {}{} above it (titles) ignored",
            source.row(header_row.number),
            source.row_word(),
            if titles == 1 { "" } else { "s" }
        ));
    }
    let (mut columns, units) = header_row::columns(source, &head[header..])?;
    let mut start = header + 1;
    if let Some(units) = units {
        start += 1;
        notes.push(format!(
            "units from {}, below the header",
            source.row(head[header + 1].number)
        ));
        for (column, unit) in columns.iter_mut().zip(units) {
            if let Some(unit) = unit {
                column.1 = Some(unit);
            }
        }
    }
    // Whether the speed column gave no unit, before the units are applied.
    let unitless_speed = columns
        .iter()
        .find(|(c, unit)| c.quantity == Quantity::Speed && unit.is_none())
        .map(|(c, _)| c.raw.clone());
    let (columns, column_notes) = with_units(columns);
    let below = head[start.min(head.len())..].iter().cloned().chain(rows);
    let read = read_rows(source, below, header_row, &columns)?;
    notes.extend(delimiter_note(source, read.decimal_commas));
    notes.extend(column_notes);
    let mut table = finish(source, &columns, read, notes)?;
    if let Some(raw) = unitless_speed {
        table.warnings.extend(speed_in_mm_hint(&raw, &table.speeds));
    }
    Ok(table)
}

/// The median speed above which a column without a unit was probably
/// written in mm/s: rolling rigs run at µm/s to about 1 m/s (faster, the
/// rubber heats up; the fit warns of that apart), while 1–1000 mm/s is the
/// usual range of a rig that logs in mm/s. Such data, read as m/s, sit
/// three decades too high and fail as a poor fit with no word of the unit.
pub const MM_PER_S_MEDIAN: f64 = 1.0;

/// The hint of a speed column `raw` without a unit whose median speed is
/// above [`MM_PER_S_MEDIAN`] m/s (as the radius gets one for mm).
fn speed_in_mm_hint(raw: &str, speeds: &[f64]) -> Option<String> {
    let mut sorted = speeds.to_vec();
    sorted.sort_by(f64::total_cmp);
    let median = match sorted.len() {
        0 => return None,
        n if n % 2 == 1 => sorted[n / 2],
        n => 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]),
    };
    (median > MM_PER_S_MEDIAN).then(|| {
        format!(
            "the median speed of column {raw:?}, which gives no unit, is {median} m/s (rolling \
             rigs run below about 1 m/s) — mm/s? name the column `v_mm_s` or `speed (mm/s)` \
             ({median} mm/s = {} m/s)",
            median * 1e-3
        )
    })
}

/// The error of a file without a header: what `row`, its first row, does
/// not name.
fn no_header(source: &Source, row: &Row) -> IoError {
    let names = classify(row);
    let missing: Vec<Quantity> = [Quantity::Speed, Quantity::Friction]
        .into_iter()
        .filter(|q| !names.iter().any(|h| h.quantity() == Some(*q)))
        .collect();
    let delimiter = source.delimiter().map_or(String::new(), |d| {
        format!(" (delimiter {})", delimiter_name(d))
    });
    err!(
        "{} (header): {}; found {}{delimiter}",
        source.row(row.number),
        missing_columns(&missing),
        quoted_list(&row.names())
    )
}

/// The columns with their conversions, and a note for each column whose
/// name or unit is not the canonical one.
fn with_units(columns: NamedColumns) -> (Vec<Column>, Vec<String>) {
    let mut notes = Vec::new();
    let columns = columns
        .into_iter()
        .map(|(column, unit)| {
            let key = column.quantity.key();
            let raw = format!("{:?}", column.raw);
            match &unit {
                Some(u) if !u.conversion.is_identity() => notes.push(format!(
                    "column {raw} read as {key} in {}, converted to {} ({})",
                    u.label,
                    match column.quantity.si_unit() {
                        "" => "a fraction",
                        si => si,
                    },
                    u.conversion.describe()
                )),
                Some(u) if column.raw != key => {
                    notes.push(format!("column {raw} read as {key} in {}", u.label))
                }
                None if column.raw != key => {
                    let si = column.quantity.si_unit();
                    notes.push(if si.is_empty() {
                        format!("column {raw} read as {key}")
                    } else {
                        format!("column {raw} read as {key} in {si} (no unit given)")
                    })
                }
                _ => {}
            }
            Column {
                conversion: unit.map_or(Conversion::NONE, |u| u.conversion),
                ..column
            }
        })
        .collect();
    (columns, notes)
}

/// The delimiter of a text file other than `,`, and whether decimal commas
/// were read.
fn delimiter_note(source: &Source, decimal_commas: bool) -> Option<String> {
    match (source.delimiter(), decimal_commas) {
        (Some(','), _) | (None, false) => None,
        (Some(d), false) => Some(format!("columns separated by {}", delimiter_name(d))),
        (Some(d), true) => Some(format!(
            "columns separated by {}, decimal commas read as decimal points",
            delimiter_name(d)
        )),
        (None, true) => Some("decimal commas read as decimal points".into()),
    }
}

/// What the rows below the header hold.
struct Read {
    /// The values of each quantity, in the order of [`Quantity::ALL`].
    values: [Vec<f64>; 4],
    /// The line of each row kept.
    lines: Vec<u64>,
    /// The lines of the rows skipped.
    skipped: Vec<u64>,
    /// Which quantities had empty cells.
    skipped_in: [bool; 4],
    /// The first spreadsheet error of a skipped row, said in full.
    first_error: Option<String>,
    /// A decimal comma was read.
    decimal_commas: bool,
}

/// Reads `rows`, the rows below the header (and units row) `header_row`,
/// one at a time.
fn read_rows(
    source: &Source,
    rows: impl Iterator<Item = Row>,
    header_row: &Row,
    columns: &[Column],
) -> Result<Read, IoError> {
    let mut read = Read {
        values: Default::default(),
        lines: Vec::new(),
        skipped: Vec::new(),
        skipped_in: [false; 4],
        first_error: None,
        decimal_commas: false,
    };
    for row in rows {
        let row = &row;
        if row.is_blank() {
            continue;
        }
        check_width(source, row, header_row, columns)?;
        let values = read_row(source, row, columns, &mut read)?;
        let wanted = columns.iter().map(|c| c.quantity.index());
        if wanted.clone().any(|q| values[q].is_none()) {
            read.skipped.push(row.number);
            continue;
        }
        check_sigma(source, row, columns, &values)?;
        for q in wanted {
            read.values[q].extend(values[q]);
        }
        read.lines.push(row.number);
    }
    Ok(read)
}

/// Refuses a row with a value beyond the header's columns, or one that
/// ends before a column read.
fn check_width(
    source: &Source,
    row: &Row,
    header_row: &Row,
    columns: &[Column],
) -> Result<(), IoError> {
    let width = header_row.cells.len();
    let extra = row.cells.get(width..).unwrap_or_default();
    if extra.iter().any(|c| !c.is_empty()) {
        return Err(err!(
            "{row}: malformed row: {fields} fields, the header ({header_row}) has {width}{}",
            if !source.decimal_comma() {
                "; if the numbers have decimal commas (0,0123), a comma-delimited file is \
             ambiguous: export with ';' as the delimiter, or with decimal points"
            } else {
                ""
            },
            fields = row.cells.len() - row.trailing_empty(),
            header_row = source.row(header_row.number),
            row = source.row(row.number)
        ));
    }
    let needed = columns.iter().map(|c| c.index + 1).max().unwrap_or(0);
    if row.cells.len() < needed {
        return Err(err!(
            "{row}: malformed row: {fields} field{}, the header ({header_row}) has {width}",
            if row.cells.len() == 1 { "" } else { "s" },
            fields = row.cells.len(),
            header_row = source.row(header_row.number),
            row = source.row(row.number)
        ));
    }
    Ok(())
}

/// The values of `row` in SI, in the order of [`Quantity::ALL`] (None for
/// an empty or NaN cell, marked in `read.skipped_in`), each checked
/// against its quantity's range.
fn read_row(
    source: &Source,
    row: &Row,
    columns: &[Column],
    read: &mut Read,
) -> Result<[Option<f64>; 4], IoError> {
    let mut values = [None; 4];
    for column in columns {
        let at = || (source.cell(row.number, column.index), column.name());
        let cell = &row.cells[column.index];
        let Some(number) = number(cell, source, &mut read.decimal_commas, &at)? else {
            read.skipped_in[column.quantity.index()] = true;
            if let (Cell::Error(error), None) = (cell, &read.first_error) {
                let (cell, name) = at();
                read.first_error = Some(format!(
                    "{cell}: column {name}: the cell holds the Excel error {error}"
                ));
            }
            continue;
        };
        let value = column.conversion.apply(number.value, &number.decimal);
        if let Some(requirement) = column_requirement(column.quantity.key(), value) {
            let (cell, column_name) = at();
            return Err(err!(
                "{cell}: column {column} = {text}{}: {requirement}{}",
                if !column.conversion.is_identity() && value > 0.0 {
                    format!(" ({value:e} {} in SI)", column_name.quantity.key())
                } else {
                    String::new()
                },
                why_positive(column_name.quantity, value),
                column = column_name,
                text = number.shown
            ));
        }
        values[column.quantity.index()] = Some(value);
    }
    Ok(values)
}

/// Refuses a standard deviation too small against its row's μ.
fn check_sigma(
    source: &Source,
    row: &Row,
    columns: &[Column],
    values: &[Option<f64>; 4],
) -> Result<(), IoError> {
    if let (Some(sigma), Some(mu)) = (
        values[Quantity::Sigma.index()],
        values[Quantity::Friction.index()],
    ) && sigma < MIN_RELATIVE_SIGMA * mu
    {
        let column = columns
            .iter()
            .find(|c| c.quantity == Quantity::Sigma)
            .expect("a sigma value comes from a sigma column");
        return Err(err!(
            "{cell}: column {column} = {sigma:e}: {SIGMA_REQUIREMENT}",
            cell = source.cell(row.number, column.index),
            column = column.name()
        ));
    }
    Ok(())
}

/// The table of what was read, with the warning about skipped rows.
fn finish(
    source: &Source,
    columns: &[Column],
    read: Read,
    notes: Vec<String>,
) -> Result<DataTable, IoError> {
    let mut warnings = Vec::new();
    if !read.skipped.is_empty() {
        let quantities: Vec<Quantity> = Quantity::ALL
            .into_iter()
            .filter(|q| read.skipped_in[q.index()])
            .collect();
        let n = read.skipped.len();
        warnings.push(format!(
            "skipped {n} row{} with empty or NaN cells in {}: {}{}",
            if n == 1 { "" } else { "s" },
            key_list(&quantities),
            source.rows(&read.skipped),
            read.first_error
                .as_ref()
                .map_or(String::new(), |e| format!("; the first error: {e}"))
        ));
        if read.lines.is_empty() {
            return Err(err!(
                "no data rows left: every row has an empty or NaN cell in {} ({rows}): nothing to fit",
                key_list(&quantities),
                rows = source.rows(&read.skipped)
            ));
        }
    }
    if read.lines.is_empty() {
        return Err(err!(
            "the file has a header but no data rows: nothing to fit"
        ));
    }
    let [speeds, friction, sigma, temperature] = read.values;
    let has = |q: Quantity| columns.iter().any(|c| c.quantity == q);
    Ok(DataTable {
        speeds,
        friction,
        sigma: has(Quantity::Sigma).then_some(sigma),
        temperature: has(Quantity::Temperature).then_some(temperature),
        lines: read.lines,
        notes,
        warnings,
    })
}
