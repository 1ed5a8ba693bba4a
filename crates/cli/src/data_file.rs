//! Reader for measured rolling friction (docs/ARCHITECTURE.md, "Contract",
//! "Measured data"): a table with a header row naming a speed column and a
//! friction column, optionally the standard deviation of μ and the
//! temperature; other columns are ignored, so the output of
//! `rollfit forward --noise` (v, mu, sigma, mu_exact, ...) and mu.csv of a
//! fit (v, mu_measured, ...) are read directly.
//!
//! What labs write is read as it is:
//!
//! - Text (CSV) with `,`, `;` or tab between the columns, detected from the
//!   header; with `;` or tab, numbers may have decimal commas (`0,0123`, the
//!   European spreadsheet export). A comma-delimited file with decimal
//!   commas is ambiguous and refused. UTF-8 (a byte-order mark is ignored),
//!   UTF-16 with a byte-order mark, and, when the file is not UTF-8,
//!   Latin-1. Lines starting with `#` are comments; lines before the header
//!   that are not (titles such as `Measurement 2024-03-01`) are skipped: the
//!   header is the first line naming both a speed and a friction column.
//! - Workbooks (.xlsx, .xlsm, .xlsb, .xls, .ods; see the `workbook` module): the
//!   first sheet, or the one `--sheet` names; numbers or numeric text.
//! - Header names (see the `headers` module): the speed `v`, `velocity`, `speed`,
//!   `rolling speed`, with a unit in brackets, parentheses or after an
//!   underscore (`velocity (mm/s)`, `speed [m/s]`, `v_um_s`: m/s, cm/s,
//!   mm/s, µm/s, nm/s, per s, ms, min or h); the friction `mu`, `µ`, `COF`,
//!   `friction coefficient` (dimensionless, or in %); its standard deviation
//!   `sigma`, `std`, `sd`, `mu_std`, `sigma_mu`, `COF std`; the temperature
//!   `T`, `temperature`, `T_C`, `T (°C)`, `T_K`, `T (K)`, `T_F` (a lone
//!   lowercase `t` is time and ignored). Case, spaces, underscores and
//!   brackets do not matter. A row right below the header holding only
//!   units (`mm/s;-`) gives the units of the columns whose names have none.
//!   Values are converted to m/s and °C; every conversion and every name
//!   other than the canonical `v`, `mu`, `sigma`, `T` is stated in
//!   [`DataTable::notes`]. A speed or temperature unit not understood, or two
//!   columns of one quantity, are errors.
//! - Rows with an empty or NaN cell (`NaN`, `nan`, `NA`, `n/a`, `#N/A`,
//!   `null`, `-`, or a spreadsheet error such as `#DIV/0!`) in any column
//!   read — v, mu, and sigma or T when the file has them — are skipped, with
//!   one warning listing their lines in [`DataTable::warnings`]; a row
//!   without a sigma has no weight, and one without a T no place in a
//!   temperature set. Rows and trailing columns that are entirely empty
//!   (`v;mu;;`, `;;;`) are ignored silently.
//!
//! Every other value must be a finite number; v, mu and sigma must be
//! greater than zero (the default weights are relative, 1/μ²). Repeated
//! speeds and unsorted rows are normal in real data and kept as they are, in
//! file order. Errors name the line (for a workbook the sheet and the cell)
//! and the column, and when a column is missing list the columns found; the
//! caller adds the file name.

mod headers;
mod workbook;

use std::path::Path;

use anyhow::{Context, Result, bail, ensure};
use rollfit_fit::Measurements;
use rollfit_fit::data::{MIN_RELATIVE_SIGMA, SIGMA_REQUIREMENT, column_requirement};
use rollfit_io::csv_text;

use headers::{Conversion, Header, Quantity};

/// A measurement as read, in file order, with the file line of each row.
#[derive(Debug, Clone, PartialEq)]
pub struct DataTable {
    /// Speeds v, m/s.
    pub speeds: Vec<f64>,
    /// Friction coefficients μ.
    pub friction: Vec<f64>,
    /// Standard deviations of μ, when the file has a `sigma` column.
    pub sigma: Option<Vec<f64>>,
    /// Temperatures, °C, when the file has a `T` column.
    pub temperature: Option<Vec<f64>>,
    /// The file line of each row (for a workbook its row number), for
    /// messages.
    pub lines: Vec<u64>,
    /// How the file was read, one sentence each (no prefix, no file name):
    /// encoding, sheet, header line, delimiter and decimal commas, and each
    /// column's name and unit conversion.
    pub notes: Vec<String>,
    /// What was left out (rows with empty or NaN cells), one sentence each.
    pub warnings: Vec<String>,
}

impl DataTable {
    /// The validated measurements of the fit library.
    pub fn measurements(&self) -> Result<Measurements> {
        Measurements::new(
            self.speeds.clone(),
            self.friction.clone(),
            self.sigma.clone(),
            self.temperature.clone(),
        )
        .map_err(|e| anyhow::anyhow!("{e}"))
    }

    /// The distinct temperatures of a `T` column, in order of appearance.
    pub fn temperatures(&self) -> Vec<f64> {
        let mut distinct: Vec<f64> = Vec::new();
        for &t in self.temperature.iter().flatten() {
            if !distinct.contains(&t) {
                distinct.push(t);
            }
        }
        distinct
    }
}

/// Reads and checks the measurement at `path` (text, or the first sheet of
/// a workbook); errors name the file.
pub fn read(path: &Path) -> Result<DataTable> {
    read_sheet(path, None)
}

/// Reads and checks the measurement at `path`; `sheet` names the sheet of
/// a workbook (default: the first), and is an error for a text file.
/// Errors name the file.
pub fn read_sheet(path: &Path, sheet: Option<&str>) -> Result<DataTable> {
    let bytes =
        std::fs::read(path).with_context(|| format!("cannot open data file {}", path.display()))?;
    let context = || format!("data file {}", path.display());
    if workbook::is_workbook(path, &bytes) {
        return workbook::parse(path, bytes, sheet).with_context(context);
    }
    if let Some(sheet) = sheet {
        bail!(
            "data file {}: a sheet ({sheet:?}) was given, but the file is text, not a workbook \
             (.xlsx, .xlsm, .xlsb, .xls, .ods)",
            path.display()
        );
    }
    parse_bytes(&bytes).with_context(context)
}

/// One cell of a row.
#[derive(Debug, Clone, PartialEq)]
enum Cell {
    Empty,
    /// Text as written, trimmed (never empty).
    Text(String),
    /// A number of a workbook cell.
    Number(f64),
    /// A workbook's error value (#DIV/0!, #N/A): no value.
    Missing,
    /// Something else of a workbook (a boolean, a date), described.
    Other(String),
}

impl Cell {
    fn text(text: &str) -> Cell {
        let text = text.trim();
        if text.is_empty() {
            Cell::Empty
        } else {
            Cell::Text(text.to_string())
        }
    }

    fn is_empty(&self) -> bool {
        *self == Cell::Empty
    }

    /// The cell as a header name.
    fn name(&self) -> String {
        match self {
            Cell::Text(t) => t.clone(),
            Cell::Number(x) => x.to_string(),
            Cell::Empty | Cell::Missing => String::new(),
            Cell::Other(what) => what.clone(),
        }
    }

    /// Whether the cell holds a number or no value (a data row's cell).
    fn is_numeric(&self) -> bool {
        match self {
            Cell::Number(_) | Cell::Missing => true,
            Cell::Text(t) => no_value(t) || t.replace(',', ".").parse::<f64>().is_ok(),
            Cell::Empty | Cell::Other(_) => false,
        }
    }
}

/// A row of the file (comments and blank lines left out) with its line or
/// row number.
#[derive(Debug, Clone)]
struct Row {
    number: u64,
    cells: Vec<Cell>,
}

impl Row {
    fn is_blank(&self) -> bool {
        self.cells.iter().all(Cell::is_empty)
    }

    /// A row of numbers: data, not a header or a title.
    fn is_numeric(&self) -> bool {
        !self.is_blank() && self.cells.iter().all(|c| c.is_empty() || c.is_numeric())
    }
}

/// Where the rows come from, for messages.
enum Source {
    Text { delimiter: char },
    Sheet { name: String },
}

impl Source {
    /// "line 7", "sheet \"Run 1\", row 7".
    fn row(&self, number: u64) -> String {
        match self {
            Source::Text { .. } => format!("line {number}"),
            Source::Sheet { name } => format!("sheet {name:?}, row {number}"),
        }
    }

    /// "line 7", "sheet \"Run 1\", cell B7".
    fn cell(&self, number: u64, column: usize) -> String {
        match self {
            Source::Text { .. } => format!("line {number}"),
            Source::Sheet { name } => {
                format!(
                    "sheet {name:?}, cell {}{number}",
                    workbook::column_letter(column)
                )
            }
        }
    }

    /// "column 3", "column C".
    fn column(&self, column: usize) -> String {
        match self {
            Source::Text { .. } => format!("column {}", column + 1),
            Source::Sheet { .. } => format!("column {}", workbook::column_letter(column)),
        }
    }

    /// "lines 7, 12", "sheet \"Run 1\", rows 7, 12".
    fn rows(&self, numbers: &[u64]) -> String {
        const SHOWN: usize = 20;
        let mut list: Vec<String> = numbers.iter().take(SHOWN).map(u64::to_string).collect();
        if numbers.len() > SHOWN {
            list.push(format!("… ({} in all)", numbers.len()));
        }
        let plural = if numbers.len() == 1 { "" } else { "s" };
        match self {
            Source::Text { .. } => format!("line{plural} {}", list.join(", ")),
            Source::Sheet { name } => format!("sheet {name:?}, row{plural} {}", list.join(", ")),
        }
    }

    /// What follows the list of columns found: " (delimiter ';')".
    fn found_suffix(&self) -> String {
        match self {
            Source::Text { delimiter } => format!(" (delimiter {})", delimiter_name(*delimiter)),
            Source::Sheet { .. } => String::new(),
        }
    }

    /// Whether `0,5` is a number: not with a comma between the columns.
    fn decimal_comma(&self) -> bool {
        !matches!(self, Source::Text { delimiter: ',' })
    }
}

fn delimiter_name(delimiter: char) -> &'static str {
    match delimiter {
        '\t' => "tab",
        ';' => "';'",
        _ => "','",
    }
}

/// The delimiters tried, in order of preference on a tie.
const DELIMITERS: [char; 3] = ['\t', ';', ','];

/// Parses and checks a text measurement.
fn parse_bytes(bytes: &[u8]) -> Result<DataTable> {
    let mut notes = Vec::new();
    let text = decode(bytes, &mut notes)?;
    let text = text.replace("\r\n", "\n").replace('\r', "\n");
    let lines: Vec<(u64, &str)> = text
        .split('\n')
        .enumerate()
        .filter(|(_, line)| !is_comment_or_blank(line))
        .map(|(i, line)| (i as u64 + 1, line))
        .collect();
    ensure!(
        !lines.is_empty(),
        "the file is empty: expected a header row (v, mu, optionally sigma and T) and data rows"
    );
    let split = |delimiter: char| -> Vec<Row> {
        lines
            .iter()
            .map(|&(number, line)| Row {
                number,
                cells: split_line(line, delimiter),
            })
            .collect()
    };
    // The delimiter that gives a header; of several, the widest header.
    let mut best: Option<(char, Vec<Row>, usize, usize)> = None;
    for delimiter in DELIMITERS {
        let rows = split(delimiter);
        if let Some(header) = find_header(&rows) {
            let width = rows[header].cells.iter().filter(|c| !c.is_empty()).count();
            if best.as_ref().is_none_or(|b| width > b.3) {
                best = Some((delimiter, rows, header, width));
            }
        }
    }
    let (delimiter, rows, header) = match best {
        Some((delimiter, rows, header, _)) => (delimiter, rows, Some(header)),
        None => {
            let first = lines[0].1;
            let delimiter = DELIMITERS
                .into_iter()
                .max_by_key(|d| first.matches(*d).count())
                .unwrap_or(',');
            (delimiter, split(delimiter), None)
        }
    };
    table(&Source::Text { delimiter }, &rows, header, notes)
}

/// The text of `bytes`: UTF-8 (without a byte-order mark), UTF-16 with a
/// byte-order mark, else Latin-1 (with a note).
fn decode(bytes: &[u8], notes: &mut Vec<String>) -> Result<String> {
    let utf16 = |rest: &[u8], unit: fn([u8; 2]) -> u16| -> Result<String> {
        ensure!(
            rest.len().is_multiple_of(2),
            "the file starts with a UTF-16 byte-order mark but has an odd number of bytes"
        );
        let units: Vec<u16> = rest.chunks(2).map(|c| unit([c[0], c[1]])).collect();
        String::from_utf16(&units).context("the file is not valid UTF-16 text")
    };
    if let Some(rest) = bytes.strip_prefix(&[0xEF, 0xBB, 0xBF]) {
        return Ok(decode_8bit(rest, notes));
    }
    if let Some(rest) = bytes.strip_prefix(&[0xFF, 0xFE]) {
        notes.push("read as UTF-16 (little-endian byte-order mark)".into());
        return utf16(rest, u16::from_le_bytes);
    }
    if let Some(rest) = bytes.strip_prefix(&[0xFE, 0xFF]) {
        notes.push("read as UTF-16 (big-endian byte-order mark)".into());
        return utf16(rest, u16::from_be_bytes);
    }
    Ok(decode_8bit(bytes, notes))
}

fn decode_8bit(bytes: &[u8], notes: &mut Vec<String>) -> String {
    match std::str::from_utf8(bytes) {
        Ok(text) => text.to_string(),
        Err(e) => {
            let line = bytes[..e.valid_up_to()]
                .iter()
                .filter(|&&b| b == b'\n')
                .count()
                + 1;
            notes.push(format!(
                "not UTF-8 text (line {line} is not): read as Latin-1 (ISO 8859-1)"
            ));
            bytes.iter().map(|&b| char::from(b)).collect()
        }
    }
}

/// A `#` comment or a blank line (a line starting with a spreadsheet error
/// value such as `#N/A` is data).
fn is_comment_or_blank(line: &str) -> bool {
    let line = line.trim();
    line.is_empty() || (line.starts_with('#') && !starts_with_error_value(line))
}

const ERROR_VALUES: [&str; 7] = [
    "#n/a", "#div/0!", "#value!", "#ref!", "#name?", "#num!", "#null!",
];

fn starts_with_error_value(text: &str) -> bool {
    let lower = text.to_lowercase();
    ERROR_VALUES.iter().any(|e| lower.starts_with(e))
}

/// A cell that holds no value: NaN, NA, n/a, null, -, a spreadsheet error.
fn no_value(text: &str) -> bool {
    let lower = text.trim().to_lowercase();
    matches!(
        lower.as_str(),
        "nan" | "-nan" | "+nan" | "na" | "n/a" | "n.a." | "null" | "none" | "-" | "--" | "—"
    ) || ERROR_VALUES.contains(&lower.as_str())
}

/// The cells of a text line: separated by `delimiter`, each trimmed, with
/// double quotes around a cell removed (`""` in a quoted cell is `"`).
fn split_line(line: &str, delimiter: char) -> Vec<Cell> {
    let mut cells = Vec::new();
    let mut current = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        if quoted {
            if c == '"' {
                if chars.peek() == Some(&'"') {
                    current.push('"');
                    chars.next();
                } else {
                    quoted = false;
                }
            } else {
                current.push(c);
            }
        } else if c == delimiter {
            cells.push(Cell::text(&current));
            current.clear();
        } else if c == '"' && current.trim().is_empty() {
            current.clear();
            quoted = true;
        } else {
            current.push(c);
        }
    }
    cells.push(Cell::text(&current));
    cells
}

/// What each cell of `row` names as a header.
fn classify(row: &Row) -> Vec<Header> {
    row.cells
        .iter()
        .map(|c| headers::classify(&c.name()))
        .collect()
}

/// The index of the header row: the first row naming a speed and a
/// friction column, searched until the first row of numbers.
fn find_header(rows: &[Row]) -> Option<usize> {
    for (i, row) in rows.iter().enumerate() {
        if row.is_numeric() {
            return None;
        }
        let names = classify(row);
        let has = |q: Quantity| names.iter().any(|h| h.quantity() == Some(q));
        if has(Quantity::Speed) && has(Quantity::Friction) {
            return Some(i);
        }
    }
    None
}

/// A column read: where, its header as written, what and in which unit.
struct Column {
    index: usize,
    raw: String,
    quantity: Quantity,
    conversion: Conversion,
}

impl Column {
    /// "`v`", "`velocity (mm/s)` (v)".
    fn display(&self) -> String {
        let key = self.quantity.key();
        if self.raw == key {
            format!("`{key}`")
        } else {
            format!("`{}` ({key})", self.raw)
        }
    }
}

/// The columns found in `rows` as a list for messages: `"a", "b"`.
fn found(row: &Row) -> String {
    let names: Vec<String> = row
        .cells
        .iter()
        .filter(|c| !c.is_empty())
        .map(|c| format!("{:?}", c.name()))
        .collect();
    names.join(", ")
}

/// The table of `rows` with its header at `header` (None: no header found,
/// an error about the first row).
fn table(
    source: &Source,
    rows: &[Row],
    header: Option<usize>,
    mut notes: Vec<String>,
) -> Result<DataTable> {
    let first = rows.iter().position(|r| !r.is_blank()).context(
        "the file is empty: expected a header row (v, mu, optionally sigma and T) and data rows",
    )?;
    let Some(header) = header else {
        let row = &rows[first];
        let names = classify(row);
        let missing: Vec<String> = [Quantity::Speed, Quantity::Friction]
            .into_iter()
            .filter(|q| !names.iter().any(|h| h.quantity() == Some(*q)))
            .map(|q| format!("no {} column ({})", q.what(), q.understood()))
            .collect();
        bail!(
            "{} (header): {}; found {}{}",
            source.row(row.number),
            missing.join(" and "),
            found(row),
            source.found_suffix()
        );
    };
    let header_row = &rows[header];
    if header > first {
        let titles = rows[first..header].iter().filter(|r| !r.is_blank()).count();
        let word = match source {
            Source::Text { .. } => "line",
            Source::Sheet { .. } => "row",
        };
        notes.push(format!(
            "header on {}; the {titles} {word}{} above it (titles) ignored",
            source.row(header_row.number),
            if titles == 1 { "" } else { "s" }
        ));
    }
    let (mut columns, units) = columns(source, &rows[header..])?;
    let mut start = header + 1;
    if let Some(units) = units {
        start += 1;
        notes.push(format!(
            "units from {}, below the header",
            source.row(rows[header + 1].number)
        ));
        for (column, unit) in columns.iter_mut().zip(units) {
            if let Some(unit) = unit {
                column.1 = Some(unit);
            }
        }
    }
    let mut column_notes = Vec::new();
    let columns: Vec<Column> = columns
        .into_iter()
        .map(|(column, unit)| {
            let key = column.quantity.key();
            let raw = format!("{:?}", column.raw);
            match &unit {
                Some(u) if !u.conversion.is_identity() => column_notes.push(format!(
                    "column {raw} read as {key} in {}, converted to {} ({})",
                    u.label,
                    match column.quantity.si_unit() {
                        "" => "a fraction",
                        si => si,
                    },
                    u.conversion.describe()
                )),
                Some(u) if column.raw != key => {
                    column_notes.push(format!("column {raw} read as {key} in {}", u.label))
                }
                None if column.raw != key => {
                    let si = column.quantity.si_unit();
                    column_notes.push(if si.is_empty() {
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

    let header_width = header_row.cells.len();
    let needed = columns.iter().map(|c| c.index + 1).max().unwrap_or(0);
    let mut values: [Vec<f64>; 4] = Default::default();
    let mut lines = Vec::new();
    let mut skipped = Vec::new();
    let mut skipped_in = [false; 4];
    let mut decimal_commas = false;
    for row in &rows[start..] {
        if row.is_blank() {
            continue;
        }
        let extra = row.cells.get(header_width..).unwrap_or_default();
        if extra.iter().any(|c| !c.is_empty()) {
            let ambiguous = if source.decimal_comma() {
                ""
            } else {
                "; if the numbers have decimal commas (0,0123), a comma-delimited file is \
                 ambiguous: export with ';' as the delimiter, or with decimal points"
            };
            bail!(
                "{}: malformed row: {} fields, the header ({}) has {header_width}{ambiguous}",
                source.row(row.number),
                row.cells.len() - trailing_empty(&row.cells),
                source.row(header_row.number)
            );
        }
        if row.cells.len() < needed {
            bail!(
                "{}: malformed row: {} field{}, the header ({}) has {header_width}",
                source.row(row.number),
                row.cells.len(),
                if row.cells.len() == 1 { "" } else { "s" },
                source.row(header_row.number)
            );
        }
        let mut read = [None; 4];
        for column in &columns {
            let at = || {
                format!(
                    "{}: column {}",
                    source.cell(row.number, column.index),
                    column.display()
                )
            };
            let Some(number) = number(&row.cells[column.index], source, &mut decimal_commas)
                .map_err(|why| anyhow::anyhow!("{}: {why}", at()))?
            else {
                skipped_in[column.quantity as usize] = true;
                continue;
            };
            let value = column.conversion.apply(number.value, &number.decimal);
            if let Some(requirement) = column_requirement(column.quantity.key(), value) {
                let why = match column.quantity {
                    _ if value > 0.0 => "",
                    Quantity::Friction => {
                        " (the fit weighs residuals relative to μ and needs μ > 0)"
                    }
                    Quantity::Sigma => {
                        " (a standard deviation of zero would give the point infinite weight)"
                    }
                    _ => "",
                };
                // A range bound on a converted value: show what it became.
                let converted = if column.conversion.is_identity() || value <= 0.0 {
                    String::new()
                } else {
                    format!(
                        " ({} {} in SI)",
                        csv_text::number(value),
                        column.quantity.key()
                    )
                };
                bail!("{} = {}{converted}: {requirement}{why}", at(), number.shown);
            }
            read[column.quantity as usize] = Some(value);
        }
        let wanted = columns.iter().map(|c| c.quantity as usize);
        if wanted.clone().any(|q| read[q].is_none()) {
            skipped.push(row.number);
            continue;
        }
        if let (Some(sigma), Some(mu)) = (
            read[Quantity::Sigma as usize],
            read[Quantity::Friction as usize],
        ) && sigma < MIN_RELATIVE_SIGMA * mu
        {
            let column = columns
                .iter()
                .find(|c| c.quantity == Quantity::Sigma)
                .expect("a sigma value comes from a sigma column");
            bail!(
                "{}: column {} = {}: {SIGMA_REQUIREMENT}",
                source.cell(row.number, column.index),
                column.display(),
                csv_text::number(sigma)
            );
        }
        for q in wanted {
            values[q].extend(read[q]);
        }
        lines.push(row.number);
    }

    if let Source::Text { delimiter } = source {
        match (*delimiter, decimal_commas) {
            (',', _) => {}
            (d, false) => notes.push(format!("columns separated by {}", delimiter_name(d))),
            (d, true) => notes.push(format!(
                "columns separated by {}, decimal commas read as decimal points",
                delimiter_name(d)
            )),
        }
    } else if decimal_commas {
        notes.push("decimal commas read as decimal points".into());
    }
    notes.extend(column_notes);
    let mut warnings = Vec::new();
    if !skipped.is_empty() {
        let keys: Vec<&str> = Quantity::ALL
            .into_iter()
            .filter(|q| skipped_in[*q as usize])
            .map(Quantity::key)
            .collect();
        let keys = match keys.split_last() {
            Some((last, [])) => last.to_string(),
            Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
            None => String::new(),
        };
        let n = skipped.len();
        warnings.push(format!(
            "skipped {n} row{} with empty or NaN cells in {keys}: {}",
            if n == 1 { "" } else { "s" },
            source.rows(&skipped)
        ));
        ensure!(
            !lines.is_empty(),
            "no data rows left: every row has an empty or NaN cell in {keys} ({}): nothing to fit",
            source.rows(&skipped)
        );
    }
    ensure!(
        !lines.is_empty(),
        "the file has a header but no data rows: nothing to fit"
    );
    let [speeds, friction, sigma, temperature] = values;
    let has = |q: Quantity| columns.iter().any(|c| c.quantity == q);
    Ok(DataTable {
        speeds,
        friction,
        sigma: has(Quantity::Sigma).then_some(sigma),
        temperature: has(Quantity::Temperature).then_some(temperature),
        lines,
        notes,
        warnings,
    })
}

/// The number of empty cells at the end of `cells`.
fn trailing_empty(cells: &[Cell]) -> usize {
    cells.iter().rev().take_while(|c| c.is_empty()).count()
}

/// The columns named by `rows[0]` (the header), each with its unit, and the
/// units of a units row `rows[1]` if it is one. Errors: a unit not
/// understood, two columns of one quantity.
#[allow(clippy::type_complexity)]
fn columns(
    source: &Source,
    rows: &[Row],
) -> Result<(
    Vec<(Column, Option<headers::Unit>)>,
    Option<Vec<Option<headers::Unit>>>,
)> {
    let row = &rows[0];
    let at = source.row(row.number);
    let mut columns: Vec<(Column, Option<headers::Unit>)> = Vec::new();
    for (index, (cell, header)) in row.cells.iter().zip(classify(row)).enumerate() {
        let raw = cell.name();
        let (quantity, unit) = match header {
            Header::Other => continue,
            Header::BadUnit { quantity, unit } => bail!(
                "{at} (header): column {raw:?}: unknown {} unit {unit:?}; units understood: {}",
                quantity.what(),
                quantity.units()
            ),
            Header::Column { quantity, unit } => (quantity, unit),
        };
        if let Some((other, _)) = columns.iter().find(|(c, _)| c.quantity == quantity) {
            bail!(
                "{at} (header): two {} columns, {:?} ({}) and {raw:?} ({}): keep one",
                quantity.what(),
                other.raw,
                source.column(other.index),
                source.column(index)
            );
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
    columns.sort_by_key(|(c, _)| c.quantity as usize);
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
    columns: &[(Column, Option<headers::Unit>)],
) -> Option<Result<Vec<Option<headers::Unit>>>> {
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
    headers::speed_unit(&text(speed.0.index))?;
    let mut units = Vec::new();
    for (column, named) in columns {
        let written = text(column.index);
        let unit = match headers::unit_cell(column.quantity, &written) {
            Ok(unit) => unit,
            Err(()) => {
                return Some(Err(anyhow::anyhow!(
                    "{}: column {:?}: unknown {} unit {written:?} in the units row; units \
                     understood: {}",
                    source.cell(row.number, column.index),
                    column.raw,
                    column.quantity.what(),
                    column.quantity.units()
                )));
            }
        };
        units.push(if named.is_some() { None } else { unit });
    }
    Some(Ok(units))
}

/// A number read from a cell: its value, its decimal text (for exact
/// powers of ten) and the text shown in messages.
struct Number {
    value: f64,
    decimal: String,
    shown: String,
}

/// The number in `cell`; None for no value (empty, NaN, NA, …); an error
/// (the reason, without the place) for anything else that is not a finite
/// number. Decimal commas are read where `source` allows them.
fn number(
    cell: &Cell,
    source: &Source,
    decimal_commas: &mut bool,
) -> Result<Option<Number>, String> {
    let (value, decimal, shown) = match cell {
        Cell::Empty | Cell::Missing => return Ok(None),
        Cell::Other(what) => return Err(format!("{what} is not a number")),
        Cell::Number(x) => (*x, format!("{x:e}"), x.to_string()),
        Cell::Text(text) => {
            if no_value(text) {
                return Ok(None);
            }
            let mut decimal = text.clone();
            if text.contains(',') {
                if !source.decimal_comma() {
                    return Err(format!(
                        "{text:?}: a decimal comma in a comma-delimited file is ambiguous; \
                         export with ';' as the delimiter, or with decimal points"
                    ));
                }
                if text.matches(',').count() > 1 || text.contains('.') {
                    return Err(format!(
                        "{text:?} is not a number (thousands separators are not understood)"
                    ));
                }
                decimal = text.replace(',', ".");
            }
            let value = decimal
                .parse::<f64>()
                .map_err(|_| format!("{text:?} is not a number"))?;
            if decimal != *text {
                *decimal_commas = true;
            }
            (value, decimal, text.clone())
        }
    };
    if !value.is_finite() {
        return Err(format!("{shown:?} is not a finite number"));
    }
    Ok(Some(Number {
        value,
        decimal,
        shown,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_str(text: &str) -> Result<DataTable> {
        parse_bytes(text.as_bytes())
    }

    fn message(text: &str) -> String {
        format!("{:#}", parse_str(text).unwrap_err())
    }

    #[test]
    fn reads_comments_extra_columns_repeats_and_unsorted_rows() {
        let t = parse_str(
            "# measured 2024\nv,mu,sigma,mu_exact\n1e-3,0.05,5e-4,0.051\n# again\n1e-4, 0.02, 2e-4, 0.02\n1e-3,0.052,5e-4,0.051\n",
        )
        .unwrap();
        assert_eq!(t.speeds, vec![1e-3, 1e-4, 1e-3]);
        assert_eq!(t.friction, vec![0.05, 0.02, 0.052]);
        assert_eq!(t.sigma, Some(vec![5e-4, 2e-4, 5e-4]));
        assert_eq!(t.temperature, None);
        assert_eq!(t.lines, vec![3, 5, 6]);
        assert!(t.notes.is_empty() && t.warnings.is_empty(), "{t:?}");
        let t = parse_str("v,mu\n1e-3,0.05\n1e-2,0.06\n1e-1,0.07\n1,0.08\n1,0.081\n").unwrap();
        assert_eq!(t.measurements().unwrap().len(), 5);
        let t = parse_str("\n# a\n#b\nv,mu\n\n1,0.1\n  # c\n\n2,0.2\n").unwrap();
        assert_eq!(t.lines, vec![6, 9]);
        let m = message("#\nv,mu\n# c\n\n1,0.1\n# d\n2,x\n");
        assert!(m.contains("line 7") && m.contains("\"x\""), "{m}");
        let t = parse_str("mu,T,v\n0.1,-20,1\n0.2,40,2\n").unwrap();
        assert_eq!(t.speeds, vec![1.0, 2.0]);
        assert_eq!(t.temperature, Some(vec![-20.0, 40.0]));
        assert_eq!(t.sigma, None);
        assert_eq!(t.temperatures(), vec![-20.0, 40.0]);
    }

    #[test]
    fn errors_name_the_line_and_column() {
        let m = message("v,mu\n1e-3,0.05\nabc,0.1\n");
        assert!(
            m.contains("line 3: column `v`: \"abc\" is not a number"),
            "{m}"
        );
        let m = message("v;COF\n1e-3;0,05\n1e-3;1.2.3\n");
        assert!(
            m.contains("line 3: column `COF` (mu): \"1.2.3\" is not a number"),
            "{m}"
        );
        let m = message("v;mu\n1e-3;1.234,5\n");
        assert!(m.contains("line 2") && m.contains("thousands"), "{m}");
        let m = message("# c\nv,mu\n1e-3,0.05\n1e-2,-0.1\n");
        assert!(
            m.contains("line 4") && m.contains("`mu`") && m.contains("greater than zero"),
            "{m}"
        );
        let m = message("v,mu,sigma\n1e-3,0.05,0\n");
        assert!(m.contains("line 2") && m.contains("`sigma`"), "{m}");
        let m = message("v,mu\n0,0.05\n");
        assert!(m.contains("line 2") && m.contains("`v` = 0"), "{m}");
        let m = message("velocity (mm/s);mu\n-0,5;0,05\n");
        assert!(
            m.contains("line 2: column `velocity (mm/s)` (v) = -0,5: must be greater than zero"),
            "{m}"
        );
        let m = message("v,mu\n1,inf\n");
        assert!(
            m.contains("line 2: column `mu`: \"inf\" is not a finite number"),
            "{m}"
        );
    }

    /// Values no measurement reaches, which would overflow the weighted
    /// residuals (issue 14: μ = 1e300 and σ = 1e-300 once gave an infinite
    /// objective and a fit.json with null in it).
    #[test]
    fn values_outside_a_rolling_measurement_are_refused() {
        let m = message("v,mu\n1e-3,0.01\n1e-2,1e300\n");
        assert!(
            m.contains("line 3: column `mu` = 1e300: must be below 10"),
            "{m}"
        );
        let m = message("v,mu,sigma\n1e-3,0.01,1e-300\n");
        assert!(
            m.contains("line 2: column `sigma` = 1e-300: must be at least 1e-9 of the row's mu"),
            "{m}"
        );
        let m = message("v,mu\n1e300,0.01\n");
        assert!(
            m.contains("line 2: column `v` = 1e300: must be at most 1000 m/s"),
            "{m}"
        );
        let m = message("v_mm_s,mu\n2e9,0.01\n");
        assert!(
            m.contains("line 2: column `v_mm_s` (v) = 2e9 (2e6 v in SI): must be at most 1000 m/s"),
            "{m}"
        );
        let m = message("v,mu,T\n1e-3,0.01,-300\n");
        assert!(
            m.contains("line 2: column `T` = -300: must be above absolute zero"),
            "{m}"
        );
    }

    #[test]
    fn rejects_missing_columns_and_empty_data() {
        let m = message("# c\nv,friction\n1,0.1\n");
        assert!(
            m.contains("line 2 (header): no friction column (mu, µ, COF, friction coefficient")
                && m.contains("found \"v\", \"friction\" (delimiter ',')"),
            "{m}"
        );
        assert!(message("").contains("empty"));
        assert!(message("# only a comment\n").contains("empty"));
        assert!(message("v,mu\n").contains("no data rows"));
        assert!(message("v,mu\n# c\n").contains("no data rows"));
        let m = message("v,mu,v\n1,2,3\n");
        assert!(
            m.contains("two speed columns, \"v\" (column 1) and \"v\" (column 3)"),
            "{m}"
        );
        let m = message("v,mu\n# c\n1,0.1\n2\n");
        assert!(m.contains("line 4: malformed row"), "{m}");
    }

    #[test]
    fn missing_columns_list_the_columns_found_with_the_delimiter() {
        let m = message("# c\n\nSpeed;Force (N)\n1;2\n");
        assert!(
            m.contains(
                "line 3 (header): no friction column (mu, µ, COF, friction coefficient, \
                 coefficient of friction, …); found \"Speed\", \"Force (N)\" (delimiter ';')"
            ),
            "{m}"
        );
        let m = message("time\tforce\n1\t2\n");
        assert!(
            m.contains("line 1 (header): no speed column (v, velocity, speed")
                && m.contains("and no friction column")
                && m.contains("found \"time\", \"force\" (delimiter tab)"),
            "{m}"
        );
        // No header among the title lines: the first line is listed.
        let m = message("Measurement 2024-03-01\nx;y\n1;2\n");
        assert!(
            m.contains("line 1 (header): no speed column")
                && m.contains("found \"Measurement 2024-03-01\""),
            "{m}"
        );
    }

    #[test]
    fn each_delimiter_and_decimal_commas() {
        let expected = (vec![1e-3, 2.5e-2], vec![0.05, 0.125]);
        for (text, note) in [
            ("v,mu\n1e-3,0.05\n0.025,0.125\n", None),
            (
                "v;mu\n1e-3;0.05\n0.025;0.125\n",
                Some("columns separated by ';'"),
            ),
            (
                "v;mu\n1e-3;0,05\n0,025;0,125\n",
                Some("columns separated by ';', decimal commas read as decimal points"),
            ),
            (
                "v\tmu\n1e-3\t0,05\n0,025\t0,125\n",
                Some("columns separated by tab, decimal commas read as decimal points"),
            ),
            (
                "v\tmu\n1E-03\t0.05\n2,5E-02\t0.125\n",
                Some("columns separated by tab, decimal commas read as decimal points"),
            ),
            (
                "\"v\";\"mu\"\n\"1e-3\";\"0,05\"\n\"0,025\";\"0,125\"\n",
                Some("columns separated by ';', decimal commas read as decimal points"),
            ),
        ] {
            let t = parse_str(text).unwrap_or_else(|e| panic!("{text:?}: {e:#}"));
            assert_eq!((t.speeds.clone(), t.friction.clone()), expected, "{text:?}");
            assert_eq!(
                t.notes,
                note.into_iter().map(String::from).collect::<Vec<_>>()
            );
        }
        // CR line endings (old Mac exports) and CRLF.
        for text in [
            "v;mu\r1e-3;0,05\r0,025;0,125\r",
            "v;mu\r\n1e-3;0,05\r\n0,025;0,125\r\n",
        ] {
            let t = parse_str(text).unwrap();
            assert_eq!((t.speeds, t.friction), expected, "{text:?}");
        }
    }

    #[test]
    fn decimal_commas_in_a_comma_delimited_file_are_refused() {
        let m = message("v,mu\n0,001,0,05\n");
        assert!(
            m.contains("line 2: malformed row: 4 fields, the header (line 1) has 2")
                && m.contains("decimal commas (0,0123), a comma-delimited file is ambiguous"),
            "{m}"
        );
        let m = message("v,mu\n\"0,001\",\"0,05\"\n");
        assert!(
            m.contains("line 2: column `v`: \"0,001\": a decimal comma in a comma-delimited file is ambiguous"),
            "{m}"
        );
    }

    /// (header, cell) → value of the one column read, with the note.
    fn one(header: &str, cell: &str) -> (DataTable, f64) {
        let quantity = headers::classify(header).quantity();
        let text = match quantity {
            Some(Quantity::Speed) => format!("{header};mu\n{cell};0,1\n"),
            Some(Quantity::Friction) => format!("v;{header}\n1;{cell}\n"),
            _ => format!("v;mu;{header}\n1;0,1;{cell}\n"),
        };
        let t = parse_str(&text).unwrap_or_else(|e| panic!("{text:?}: {e:#}"));
        let value = match quantity {
            Some(Quantity::Speed) => t.speeds[0],
            Some(Quantity::Friction) => t.friction[0],
            _ => t.temperature.as_ref().unwrap()[0],
        };
        (t, value)
    }

    #[test]
    fn header_aliases_and_unit_conversions() {
        let cases: [(&str, &str, f64, Option<&str>); 20] = [
            ("v", "0,5", 0.5, None),
            (
                "v_m_s",
                "0,5",
                0.5,
                Some("column \"v_m_s\" read as v in m/s"),
            ),
            (
                "v_mm_s",
                "12,5",
                0.0125,
                Some("column \"v_mm_s\" read as v in mm/s, converted to m/s (×1e-3)"),
            ),
            (
                "v_um_s",
                "3",
                3e-6,
                Some("column \"v_um_s\" read as v in µm/s, converted to m/s (×1e-6)"),
            ),
            (
                "velocity (mm/s)",
                "0,0123",
                1.23e-5,
                Some("column \"velocity (mm/s)\" read as v in mm/s, converted to m/s (×1e-3)"),
            ),
            ("speed_um_s", "1,5E+02", 1.5e-4, None),
            ("speed [m/s]", "2", 2.0, None),
            ("Speed (m/s)", "2", 2.0, None),
            ("rolling speed (mm/s)", "7", 7e-3, None),
            ("speed (cm/s)", "7", 7e-2, None),
            (
                "v (mm/min)",
                "6",
                1e-4,
                Some("column \"v (mm/min)\" read as v in mm/min, converted to m/s (×1e-3/60)"),
            ),
            (
                "speed",
                "3",
                3.0,
                Some("column \"speed\" read as v in m/s (no unit given)"),
            ),
            ("COF", "0,25", 0.25, Some("column \"COF\" read as mu")),
            ("µ", "0,25", 0.25, None),
            ("μ", "0,25", 0.25, None),
            ("friction coefficient", "0,25", 0.25, None),
            ("Friction Coefficient (-)", "0,25", 0.25, None),
            (
                "COF (%)",
                "25",
                0.25,
                Some("column \"COF (%)\" read as mu in %, converted to a fraction (×1e-2)"),
            ),
            (
                "T (K)",
                "293,15",
                20.0,
                Some("column \"T (K)\" read as T in K, converted to °C (−273.15)"),
            ),
            (
                "T_F",
                "68",
                20.0,
                Some("column \"T_F\" read as T in °F, converted to °C ((T − 32)·5/9)"),
            ),
        ];
        for (header, cell, value, note) in cases {
            let (t, read) = one(header, cell);
            assert_eq!(read, value, "{header}: {cell}");
            if let Some(note) = note {
                assert!(t.notes.iter().any(|n| n == note), "{header}: {:?}", t.notes);
            }
        }
        for (header, cell) in [
            ("T", "20"),
            ("T_C", "20"),
            ("T (°C)", "20"),
            ("T [°C]", "20"),
            ("temperature (C)", "20"),
            ("T_K", "293.15"),
            ("T (°F)", "68"),
        ] {
            assert_eq!(one(header, cell).1, 20.0, "{header}");
        }
        for header in ["sigma", "std", "sd", "mu_std", "sigma_mu", "COF std"] {
            let t = parse_str(&format!("v;mu;{header}\n1;0,5;0,01\n")).unwrap();
            assert_eq!(t.sigma, Some(vec![0.01]), "{header}");
        }
    }

    #[test]
    fn unknown_units_and_two_columns_of_one_quantity() {
        let m = message("v_furlong_s,mu\n1,0.1\n");
        assert!(
            m.contains("line 1 (header): column \"v_furlong_s\": unknown speed unit \"furlong/s\"; units understood: m/s, cm/s, mm/s, µm/s"),
            "{m}"
        );
        let m = message("v,mu,T (R)\n1,0.1,500\n");
        assert!(
            m.contains("column \"T (R)\": unknown temperature unit \"R\"")
                && m.contains("K (kelvin)"),
            "{m}"
        );
        let m = message("v;mu;v_mm_s\n1;0,1;1000\n");
        assert!(
            m.contains("line 1 (header): two speed columns, \"v\" (column 1) and \"v_mm_s\" (column 3): keep one"),
            "{m}"
        );
        let m = message("v;COF;µ\n1;0,1;0,1\n");
        assert!(m.contains("two friction columns, \"COF\""), "{m}");
    }

    #[test]
    fn empty_and_nan_cells_skip_rows_with_one_warning() {
        let text = "v;mu\n1;0,1\n2;0,2\n3;0,3\n4;0,4\n5;0,5\n;0,6\n7;0,7\n8;0,8\n9;0,9\n10;1\n11;NaN\nn/a;1,2\n14;1,4\n";
        let t = parse_str(text).unwrap();
        assert_eq!(
            t.speeds,
            [1.0, 2.0, 3.0, 4.0, 5.0, 7.0, 8.0, 9.0, 10.0, 14.0]
        );
        assert_eq!(
            t.warnings,
            ["skipped 3 rows with empty or NaN cells in v or mu: lines 7, 12, 13"]
        );
        assert_eq!(t.lines.len(), t.speeds.len());
        // NA, #N/A (not a comment), null, -: no value; sigma and T too.
        let t = parse_str(
            "v;mu;sigma;T\n1;0,1;0,01;20\n#N/A;0,1;0,01;20\n2;NA;0,01;20\n3;0,3;;20\n4;0,4;0,04;null\n5;0,5;-;20\n6;0,6;0,06;20\n",
        )
        .unwrap();
        assert_eq!(t.speeds, [1.0, 6.0]);
        assert_eq!(t.sigma, Some(vec![0.01, 0.06]));
        assert_eq!(t.temperature, Some(vec![20.0, 20.0]));
        assert_eq!(
            t.warnings,
            ["skipped 5 rows with empty or NaN cells in v, mu, sigma or T: lines 3, 4, 5, 6, 7"]
        );
        let t = parse_str("v,mu\n1e-3,0.05\nnan,0.1\n").unwrap();
        assert_eq!(
            t.warnings,
            ["skipped 1 row with empty or NaN cells in v: line 3"]
        );
        let m = message("v,mu,T\n1,0.1,\n");
        assert!(
            m.contains("no data rows left: every row has an empty or NaN cell in T (line 2)"),
            "{m}"
        );
        // Text is still an error, before the row could be skipped.
        let m = message("v;mu\nabc;\n");
        assert!(
            m.contains("line 2: column `v`: \"abc\" is not a number"),
            "{m}"
        );
    }

    #[test]
    fn trailing_empty_columns_and_rows_of_an_excel_export() {
        let t = parse_str("v;mu;;\n1;0,1;;\n2;0,2;;\n;;;\n;;;\n").unwrap();
        assert_eq!(t.speeds, [1.0, 2.0]);
        assert!(t.warnings.is_empty(), "{:?}", t.warnings);
        let t = parse_str("v;mu;;\n1;0,1\n").unwrap();
        assert_eq!(t.friction, [0.1]);
        let m = message("v;mu\n1;0,1;5\n");
        assert!(
            m.contains("line 2: malformed row: 3 fields, the header (line 1) has 2")
                && !m.contains("ambiguous"),
            "{m}"
        );
    }

    #[test]
    fn byte_order_mark_latin1_and_utf16() {
        let t = parse_str("\u{feff}v;mu\n1;0,1\n").unwrap();
        assert_eq!(t.speeds, [1.0]);
        assert!(!t.notes.iter().any(|n| n.contains("UTF")), "{:?}", t.notes);

        let mut latin1 = b"v;mu;T (".to_vec();
        latin1.push(0xB0);
        latin1.extend(b"C)\n1;0,1;25\n");
        let t = parse_bytes(&latin1).unwrap();
        assert_eq!(t.temperature, Some(vec![25.0]));
        assert!(
            t.notes
                .iter()
                .any(|n| n == "not UTF-8 text (line 1 is not): read as Latin-1 (ISO 8859-1)"),
            "{:?}",
            t.notes
        );
        assert!(
            t.notes
                .iter()
                .any(|n| n == "column \"T (°C)\" read as T in °C"),
            "{:?}",
            t.notes
        );

        let mut utf16 = vec![0xFF, 0xFE];
        for unit in "v\tµ\r\n1\t0,1\r\n".encode_utf16() {
            utf16.extend(unit.to_le_bytes());
        }
        let t = parse_bytes(&utf16).unwrap();
        assert_eq!((t.speeds, t.friction), (vec![1.0], vec![0.1]));
        assert!(t.notes[0].contains("UTF-16"), "{:?}", t.notes);
    }

    #[test]
    fn title_lines_before_the_header() {
        let t = parse_str(
            "Measurement 2024-03-01\nOperator: A. B.; sample 3\n\n# comment\nSpeed (mm/s);COF;Force (N)\n1;0,1;2\n2;0,2;2\n",
        )
        .unwrap();
        assert_eq!(t.speeds, [1e-3, 2e-3]);
        assert_eq!(t.lines, [6, 7]);
        assert!(
            t.notes
                .iter()
                .any(|n| n == "header on line 5; the 2 lines above it (titles) ignored"),
            "{:?}",
            t.notes
        );
    }

    #[test]
    fn a_units_row_below_the_header() {
        let t = parse_str("Speed;COF;Temperature\n(mm/s);[-];°C\n1;0,1;20\n").unwrap();
        assert_eq!(t.speeds, [1e-3]);
        assert_eq!(t.temperature, Some(vec![20.0]));
        assert!(
            t.notes
                .iter()
                .any(|n| n == "units from line 2, below the header")
                && t.notes
                    .iter()
                    .any(|n| n == "column \"Speed\" read as v in mm/s, converted to m/s (×1e-3)"),
            "{:?}",
            t.notes
        );
        let m = message("Speed;COF;T\nmm/s;-;R\n1;0,1;20\n");
        assert!(
            m.contains("line 2: column \"T\": unknown temperature unit \"R\" in the units row"),
            "{m}"
        );
    }

    #[test]
    fn forward_output_and_time_columns() {
        let t = parse_str(
            "v,mu,sigma,mu_exact,mu_low_speed,contact_size_static,mean_pressure_static,centroid_shift,gt_alpha,T\n\
             1e-3,0.05,5e-4,0.051,0.04,1e-3,2e5,1e-5,0.1,20\n",
        )
        .unwrap();
        assert_eq!(
            (t.speeds, t.friction, t.sigma, t.temperature),
            (vec![1e-3], vec![0.05], Some(vec![5e-4]), Some(vec![20.0]))
        );
        assert!(t.notes.is_empty(), "{:?}", t.notes);
        // A lowercase t is time; so is "t (s)".
        let t = parse_str("t,v,mu\n0,1,0.1\n").unwrap();
        assert_eq!(t.temperature, None);
        let t = parse_str("t (s);v;mu;T\n0;1;0,1;25\n").unwrap();
        assert_eq!(t.temperature, Some(vec![25.0]));
        // mu.csv of a fit reads as data.
        let t =
            parse_str("v,mu_measured,mu_fit,sigma,residual\n1e-3,0.05,0.051,5e-4,0.02\n").unwrap();
        assert_eq!(t.friction, [0.05]);
    }
}
