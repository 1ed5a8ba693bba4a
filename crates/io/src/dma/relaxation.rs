//! The time-domain forms of a DMA file (docs/ARCHITECTURE.md,
//! "Contract", "DMA files"): a CSV of the relaxation modulus E(t) or G(t)
//! against the time t since a step of strain, or of the creep compliance
//! J(t) (shear) or D(t) (tensile) against the time since a step of stress,
//! optionally at several temperatures T. A header line, then one point per line; `#` lines are
//! comments; other columns are ignored. The dialect is the frequency
//! form's ([`super::csv_form`]): `,`, `;` or tab between the cells, title
//! lines above the header, decimal commas with `;` or tab.
//!
//! | quantity    | columns (first is canonical)                 | units (default first)      |
//! |-------------|----------------------------------------------|----------------------------|
//! | time        | `t`, `time` (any case)                       | `s`, `ms`, `min`, `h`      |
//! | Young's     | `E_relax`, `E(t)`, `E_t`, `E`                | `Pa`, `kPa`, `MPa`, `GPa`  |
//! | shear       | `G_relax`, `G(t)`, `G_t`, `G`                | `Pa`, `kPa`, `MPa`, `GPa`  |
//! | shear creep | `J_creep`, `J(t)`, `J_t`, `J`, `Creep Compliance`, `Shear Creep Compliance` | `1/Pa`, `1/MPa`, `MPa^-1`, `µm²/N`, `cm²/dyn`, … ([`crate::units::compliance_unit`]) |
//! | tensile creep | `D_creep`, `D(t)`, `D_t`, `D`, `Tensile Creep Compliance` | as shear creep |
//! | temperature | `T`, `temperature` (any case), optional      | `C` (or `°C`), `K`         |
//!
//! A unit follows the name after an underscore, or in parentheses or
//! brackets: `t_s`, `time (s)`, `t [min]`, `E_relax_MPa`, `E(t) (MPa)`,
//! `G [kPa]`, `T_K`, `T (°C)`. `t` and `T` are told apart by case (time and
//! temperature); `E`, `G` are case-sensitive as everywhere in rollfit.
//! `Creep Compliance` does not say whether the test was in shear or in
//! tension: it is read as shear (a rheometer's J(t)) unless
//! `--dma-modulus young` says tensile. A file is this form when its header
//! has a time and a relaxation-modulus or creep-compliance column and no
//! frequency column (`omega…`, `f`, `f_…`): a frequency
//! sweep's reader ([`super::csv_form`]) is unchanged.
//!
//! Shear moduli become Young's with E(t) = 2(1 + ν) G(t) (ν
//! frequency-independent, as for E*(ω): [`super`]), and a shear creep
//! compliance tensile with D(t) = J(t)/(2(1 + ν)). Checks: t in
//! [1e-30, 1e30] s and E(t) in (0, 1e13] Pa, every number finite, T in (−273.15, 1000] °C, all rows
//! with a temperature or none; within each isotherm (grouped as the
//! frequency form's, [`super::isotherms`]) the times increase in file
//! order, else the two lines are named. A creep compliance D(t) is in
//! (0, 1] 1/Pa and never falls with time (every linear viscoelastic
//! solid's creep compliance rises from the step of stress, Ferry ch. 3):
//! a point more than [`COMPLIANCE_FALL`] below an earlier point of its
//! isotherm — far beyond a DMA's scatter — is refused naming both lines
//! and the column.

use std::path::{Path, PathBuf};

use rollfit_fit::master::relaxation::TimeQuantity;

pub use super::time_isotherms::{COMPLIANCE_FALL, RelaxationPoint, groups, time_isotherms};

use super::header::Column;
use super::point::ModulusKind;
use super::time_isotherms::check_isotherms;
use crate::columns::{D_CREEP, E_RELAX, G_RELAX, J_CREEP, TIME};
use crate::csv_columns::LineIndex;
use crate::error::field_count_tail;
use crate::error::{ColumnRef, IoError};
use crate::units;

/// Accepted times since the step of strain, s: the reciprocal of the
/// frequency form's accepted ω (1e-30 … 1e30 rad/s).
const TIME_RANGE: (f64, f64) = (1e-30, 1e30);

/// A relaxation or creep file read, its moduli as Young's in Pa or its
/// compliances as tensile in 1/Pa.
#[derive(Debug, Clone)]
pub struct RelaxationData {
    /// The file.
    pub path: PathBuf,
    /// Relaxation or creep.
    pub quantity: TimeQuantity,
    /// The points in file order.
    pub points: Vec<RelaxationPoint>,
    /// The file line (from 1) of each point.
    pub lines: Vec<usize>,
    /// What the file held (before conversion to Young's or tensile).
    pub kind: ModulusKind,
    /// How the file was read where the file said so (shear converted).
    pub notes: Vec<String>,
}

/// What a column holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Quantity {
    Time,
    Young,
    Shear,
    /// J(t), or a creep compliance whose name says no kind.
    ShearCompliance,
    TensileCompliance,
    Temperature,
}

/// The spellings of each quantity: (name, case-sensitive), longest first
/// where one is the start of another.
const SPELLINGS: [(Quantity, &[(&str, bool)]); 6] = [
    (Quantity::Time, &[("time", false), (TIME, true)]),
    (
        Quantity::Young,
        &[(E_RELAX, true), ("E(t)", true), ("E_t", true), ("E", true)],
    ),
    (
        Quantity::Shear,
        &[(G_RELAX, true), ("G(t)", true), ("G_t", true), ("G", true)],
    ),
    (
        Quantity::ShearCompliance,
        &[
            (J_CREEP, true),
            ("J(t)", true),
            ("J_t", true),
            ("J", true),
            ("Shear Creep Compliance", false),
            ("Creep Compliance", false),
        ],
    ),
    (
        Quantity::TensileCompliance,
        &[
            (D_CREEP, true),
            ("D(t)", true),
            ("D_t", true),
            ("D", true),
            ("Tensile Creep Compliance", false),
        ],
    ),
    (
        Quantity::Temperature,
        &[("temperature", false), ("T", true)],
    ),
];

/// The factor and offset to SI (s, Pa, 1/Pa, °C) of `unit` for a column
/// of `quantity`.
fn unit_factor(quantity: Quantity, unit: &str) -> Option<(f64, f64)> {
    let factor = |f: Option<f64>| f.map(|f| (f, 0.0));
    match quantity {
        Quantity::Time => factor(units::seconds_per(unit)),
        Quantity::Young | Quantity::Shear => factor(units::modulus_unit(unit).map(|(_, pa)| pa)),
        Quantity::ShearCompliance | Quantity::TensileCompliance => {
            factor(units::compliance_unit(unit))
        }
        Quantity::Temperature => {
            units::temperature_unit(unit).map(|u| u.conversion.factor_offset())
        }
    }
}

/// The unit of a name's tail after its base: "" (the default: s, Pa,
/// 1/Pa, °C), `_X`, `(X)`, `[X]` (spaces allowed before a bracket), X a
/// unit of `quantity`.
fn unit_of(tail: &str, quantity: Quantity) -> Option<(f64, f64)> {
    let tail = tail.trim_start();
    let unit = if tail.is_empty() {
        return Some((1.0, 0.0));
    } else if let Some(u) = tail.strip_prefix('_') {
        u
    } else if let Some(u) = tail.strip_prefix('(').and_then(|u| u.strip_suffix(')')) {
        u.trim()
    } else {
        tail.strip_prefix('[')?.strip_suffix(']')?.trim()
    };
    unit_factor(quantity, unit)
}

/// What column `name` holds, with its map to SI.
fn recognise(name: &str) -> Option<(Quantity, f64, f64)> {
    for (quantity, spellings) in SPELLINGS {
        for &(base, exact) in spellings {
            let Some(head) = name.get(..base.len()) else {
                continue;
            };
            let matches = if exact {
                head == base
            } else {
                head.eq_ignore_ascii_case(base)
            };
            if matches && let Some((factor, offset)) = unit_of(&name[base.len()..], quantity) {
                return Some((quantity, factor, offset));
            }
        }
    }
    None
}

/// Whether a header names a frequency (the frequency form's reader then
/// takes the file).
fn is_frequency(name: &str) -> bool {
    name == "f" || name.starts_with("f_") || name.starts_with("omega")
}

/// The columns of a relaxation or creep header.
struct Header {
    width: usize,
    time: Column,
    /// The relaxation modulus or the creep compliance.
    value: Column,
    /// Which of them, and what the name says of its kind.
    quantity: Quantity,
    temperature: Option<Column>,
}

/// The header's relaxation columns; None when it is not a relaxation
/// header (no time column, or a frequency column).
fn header(path: &Path, line: usize, names: &[String]) -> Result<Option<Header>, IoError> {
    if names.iter().any(|n| is_frequency(n)) {
        return Ok(None);
    }
    let mut found: Vec<(Quantity, Column)> = Vec::new();
    for (index, name) in names.iter().enumerate() {
        if let Some((quantity, factor, offset)) = recognise(name) {
            found.push((
                quantity,
                Column {
                    index,
                    reference: ColumnRef::numbered(index + 1, name.as_str()),
                    factor,
                    offset,
                },
            ));
        }
    }
    let one = |which: &[Quantity], what: &'static str| -> Result<Option<Column>, IoError> {
        let mut of = found.iter().filter(|(q, _)| which.contains(q));
        match (of.next(), of.next()) {
            (Some(a), Some(b)) => Err(err!(
                "{}, line {line}: two {what} columns, {} and {}: keep one",
                path.display(),
                a.1.reference,
                b.1.reference
            )),
            (a, _) => Ok(a.map(|c| c.1.clone())),
        }
    };
    let Some(time) = one(&[Quantity::Time], "time")? else {
        return Ok(None);
    };
    const MODULI: [Quantity; 2] = [Quantity::Young, Quantity::Shear];
    const COMPLIANCES: [Quantity; 2] = [Quantity::ShearCompliance, Quantity::TensileCompliance];
    let modulus = one(&MODULI, "relaxation modulus")?;
    let compliance = one(&COMPLIANCES, "creep compliance")?;
    let value = match (modulus, compliance) {
        (Some(a), Some(b)) => {
            let (a, b) = if a.index < b.index { (a, b) } else { (b, a) };
            return Err(err!(
                "{}, line {line}: two {quantity} columns, {} and {}: keep one",
                path.display(),
                a.reference,
                b.reference,
                quantity = "relaxation modulus or creep compliance"
            ));
        }
        (Some(value), None) | (None, Some(value)) => value,
        (None, None) => {
            return Err(err!(
                "{}: a time column but no relaxation modulus: need E_relax (Young's) or G_relax \
         (shear), also spelled E(t), E_t, E, G(t), G_t, G, in Pa or with a unit such as \
         E_relax_MPa or \"E(t) (MPa)\"; or a creep compliance, J(t) or \"Creep Compliance\" \
         (shear), D(t) or \"Tensile Creep Compliance\" (tensile), in 1/Pa or with a unit \
         such as \"J (1/MPa)\" (the header has: {})",
                path.display(),
                names.to_vec().join(", ")
            ));
        }
    };
    let quantity = found
        .iter()
        .find(|(_, c)| c.index == value.index)
        .map_or(Quantity::Young, |(q, _)| *q);
    Ok(Some(Header {
        width: names.len(),
        time,
        value,
        quantity,
        temperature: one(&[Quantity::Temperature], "temperature")?,
    }))
}

/// The header row of a CSV text in the shared dialect
/// ([`crate::data::dialect::dialect_of`]: `,`, `;` or tab, title lines above
/// it): (line, names, delimiter, byte where the header starts), or None
/// without one.
fn header_row(text: &str) -> Option<(usize, Vec<String>, char, usize)> {
    let is_header = |row: &crate::data::cell::Row| {
        !matches!(
            header(Path::new(""), 0, &super::sheet::texts(row)),
            Ok(None)
        )
    };
    let (delimiter, start, _) = crate::data::dialect::dialect_of(text, is_header)?;
    let mut reader = crate::csv_columns::reader_with(&text[start..], false, true, delimiter);
    let index = LineIndex::new(text);
    for record in reader.records() {
        let record = record.ok()?;
        if record.iter().all(str::is_empty) {
            continue;
        }
        let line = index.csv_line_after(start, record.position());
        let names = record.iter().map(str::to_string).collect();
        return Some((line, names, delimiter, start));
    }
    None
}

/// The note a frequency sweep's reader gives for the names of `names`
/// read as a time column (`t`, `time`, with a unit), which it ignores.
pub(crate) fn ignored_time_columns(path: &Path, names: &[String]) -> Option<String> {
    let times: Vec<&str> = names
        .iter()
        .filter(|n| matches!(recognise(n), Some((Quantity::Time, ..))))
        .map(String::as_str)
        .collect();
    (!times.is_empty()).then(|| {
        format!(
            "{}: time column{} {} ignored: a file with a frequency column is read as a frequency \
             sweep (E′, E″ against ω); a stress-relaxation file has a time column and no \
             frequency column",
            path.display(),
            if times.len() == 1 { "" } else { "s" },
            times.join(", ")
        )
    })
}

/// Whether `text` is a relaxation file: its header has a time column and
/// no frequency column (the module doc). A header with a time column but
/// no modulus is one too (its reading then says what is missing).
pub fn is_relaxation(text: &str) -> bool {
    if super::trios::is_lims(text) {
        return false;
    }
    header_row(text)
        .is_some_and(|(line, names, ..)| !matches!(header(Path::new(""), line, &names), Ok(None)))
}

/// Whether the file at `path` is a relaxation file; false where it cannot
/// be read (the frequency form's reader then says why).
pub fn is_relaxation_file(path: &Path) -> bool {
    crate::input_file::read_input(path, "DMA file", |source| {
        err!("{}: {source}", path.display()).system(source)
    })
    .ok()
    .and_then(|bytes| crate::text_file::decode_file(path, bytes).ok())
    .is_some_and(|read| is_relaxation(&read.text))
}

impl RelaxationData {
    /// Reads a relaxation or creep file; shear moduli become Young's and
    /// shear compliances tensile with `poisson`.
    pub fn read(path: &Path, poisson: f64) -> Result<RelaxationData, IoError> {
        Self::read_as(path, poisson, None)
    }

    /// [`RelaxationData::read`], a creep compliance read as `kind` where
    /// given (`--dma-modulus`: shear J(t) or tensile D(t), whatever its
    /// name says); a relaxation file's kind is its column name's.
    pub fn read_as(
        path: &Path,
        poisson: f64,
        kind: Option<ModulusKind>,
    ) -> Result<RelaxationData, IoError> {
        rollfit_model::check_poisson(poisson).map_err(|problem| {
            err!(
                "{problem} (converting shear moduli of {} to Young's)",
                path.display()
            )
        })?;
        let bytes = crate::input_file::read_input(path, "DMA file", |source| {
            err!("{}: {source}", path.display()).system(source)
        })?;
        let text = crate::text_file::decode_file(path, bytes)?.text;
        parse(path, &text, poisson, kind)
    }
}

/// Parses the text of a relaxation or creep file (the module doc); `kind`
/// as [`RelaxationData::read_as`].
pub fn parse(
    path: &Path,
    text: &str,
    poisson: f64,
    kind: Option<ModulusKind>,
) -> Result<RelaxationData, IoError> {
    let (line, names, delimiter, start) =
        header_row(text).ok_or_else(|| err!("{}: empty: no header line", path.display()))?;
    let Some(header) = header(path, line, &names)? else {
        return Err(err!(
            "{}: no frequency column: need `omega` (rad/s) or `f` (Hz), optionally with a unit \
         suffix such as omega_rad_s or f_Hz (the header has: {}); stress-relaxation data (`t` \
         and `E_relax` or `G_relax`) are read by `rollfit master` and `rollfit compare`",
            path.display(),
            names.join(", ")
        ));
    };
    let (quantity, kind) = match (header.quantity, kind) {
        (Quantity::Shear, _) => (TimeQuantity::Relaxation, ModulusKind::Shear),
        (Quantity::ShearCompliance | Quantity::TensileCompliance, Some(kind)) => {
            (TimeQuantity::Creep, kind)
        }
        (Quantity::ShearCompliance, None) => (TimeQuantity::Creep, ModulusKind::Shear),
        (Quantity::TensileCompliance, None) => (TimeQuantity::Creep, ModulusKind::Young),
        _ => (TimeQuantity::Relaxation, ModulusKind::Young),
    };
    // E = 2(1+ν)G, so D = J/(2(1+ν)).
    let factor = match (quantity, kind) {
        (_, ModulusKind::Young) => 1.0,
        (TimeQuantity::Relaxation, ModulusKind::Shear) => 2.0 * (1.0 + poisson),
        (TimeQuantity::Creep, ModulusKind::Shear) => 1.0 / (2.0 * (1.0 + poisson)),
    };
    let mut header = header;
    let units_line = units_row(text, start, delimiter, &names, &mut header);
    let mut points = Vec::new();
    let mut lines = Vec::new();
    let mut reader = crate::csv_columns::reader_with(&text[start..], false, true, delimiter);
    let index = LineIndex::new(text);
    let decimal_comma = crate::data::dialect::decimal_comma(delimiter);
    for record in reader.records() {
        let record = record.map_err(|error| {
            err!(
                "{}, line {line}: not CSV: {error}",
                path.display(),
                line = index.csv_line_after(start, error.position())
            )
        })?;
        let at = index.csv_line_after(start, record.position());
        if at <= line || Some(at) == units_line || record.iter().all(str::is_empty) {
            continue;
        }
        points.push(row(
            path,
            (at, decimal_comma),
            &header,
            &record,
            (quantity, factor),
        )?);
        lines.push(at);
    }
    if points.is_empty() {
        return Err(err!("{}: no data rows below the header", path.display()));
    }
    check_isotherms(path, (quantity, &header.value.reference), &points, &lines)?;
    let notes = match (quantity, kind) {
        (_, ModulusKind::Young) => Vec::new(),
        (TimeQuantity::Relaxation, ModulusKind::Shear) => vec![format!(
            "{}: shear relaxation modulus G(t) converted to Young's with E = 2(1+ν)G, ν = {poisson} (the fit's)",
            path.display()
        )],
        (TimeQuantity::Creep, ModulusKind::Shear) => vec![format!(
            "{}: shear creep compliance J(t) ({}) converted to tensile with D = J/(2(1+ν)), ν = \
             {poisson} (the fit's)",
            path.display(),
            header.value.reference
        )],
    };
    Ok(RelaxationData {
        path: path.to_path_buf(),
        quantity,
        points,
        lines,
        kind,
        notes,
    })
}

/// The line of a units row right below the header (`s,MPa,°C,-`: no
/// number, and a unit of the relaxation vocabulary under a column read),
/// whose units it gives to `header`'s columns whose names carry none.
fn units_row(
    text: &str,
    start: usize,
    delimiter: char,
    names: &[String],
    header: &mut Header,
) -> Option<usize> {
    let mut reader = crate::csv_columns::reader_with(&text[start..], false, true, delimiter);
    let index = LineIndex::new(text);
    let mut records = reader
        .records()
        .filter_map(Result::ok)
        .filter(|r| !r.iter().all(str::is_empty));
    records.next()?;
    let row = records.next()?;
    let cells: Vec<String> = row
        .iter()
        .map(|c| {
            c.trim()
                .trim_matches(['[', ']', '(', ')'])
                .trim()
                .to_string()
        })
        .collect();
    if cells
        .iter()
        .any(|c| c.replace(',', ".").parse::<f64>().is_ok())
    {
        return None;
    }
    let mut any = false;
    let columns = [
        (Some(&mut header.time), Quantity::Time),
        (Some(&mut header.value), header.quantity),
        (header.temperature.as_mut(), Quantity::Temperature),
    ];
    for (column, quantity) in columns {
        let Some(column) = column else { continue };
        // A unit in the name wins over the units row: a recognised name
        // that is not a bare spelling carries one.
        let name = names[column.index].as_str();
        let named_unit = !SPELLINGS.iter().any(|(_, spellings)| {
            spellings.iter().any(|&(base, exact)| {
                if exact {
                    base == name
                } else {
                    base.eq_ignore_ascii_case(name)
                }
            })
        });
        let Some(unit) = cells.get(column.index) else {
            continue;
        };
        if let Some((factor, offset)) = unit_factor(quantity, unit) {
            any = true;
            if !named_unit {
                column.factor = factor;
                column.offset = offset;
            }
        }
    }
    any.then(|| index.csv_line_after(start, row.position()))
}

/// The point of the record on line `line`; `factor` turns the value
/// column into Young's or tensile.
fn row(
    path: &Path,
    (line, decimal_comma): (usize, bool),
    header: &Header,
    record: &csv::StringRecord,
    (quantity, factor): (TimeQuantity, f64),
) -> Result<RelaxationPoint, IoError> {
    if record.len() != header.width {
        return Err(err!(
            "{}, line {line}: {found} fields, but the header has {expected} columns{}",
            path.display(),
            field_count_tail(&[], false),
            expected = header.width,
            found = record.len()
        ));
    }
    let value = |c: &Column| -> Result<f64, IoError> {
        let v = c.number(path, line, &record[c.index], decimal_comma)?;
        Ok(v * c.factor + c.offset)
    };
    let time = value(&header.time)?;
    if time <= 0.0 {
        return Err(err!(
            "{}, line {line}: {column}: t = {value} s: times are counted from the step of strain \
         and must be positive",
            path.display(),
            column = header.time.reference,
            value = time
        ));
    }
    // The frequency form's ω range turned into times: far outside any
    // relaxation test, and beyond what the τ grid of the series spans
    // (a time of 1e300 s asks for hundreds of decades of terms).
    if !(TIME_RANGE.0..=TIME_RANGE.1).contains(&time) {
        return Err(err!(
            "{}, line {line}: {column}: t = {value:e} s is outside 1e-30 … 1e30 s, beyond any \
         relaxation measurement (is the time in s, or is the column a time at all?)",
            path.display(),
            column = header.time.reference,
            value = time
        ));
    }
    let measured = value(&header.value)? * factor;
    let column = || header.value.reference.clone();
    match quantity {
        TimeQuantity::Relaxation if !(measured > 0.0 && measured <= 1e13) => {
            return Err(err!(
                "{}, line {line}: {column}: E(t) = {value} Pa is not a modulus (it must be positive and \
         below 1e13 Pa)",
                path.display(),
                column = column(),
                value = measured
            ));
        }
        TimeQuantity::Creep if !(measured > 0.0 && measured <= 1.0) => {
            return Err(err!(
                "{}, line {line}: {column}: D(t) = {value} 1/Pa (tensile) is not a creep compliance (it \
         must be positive and below 1 1/Pa)",
                path.display(),
                column = column(),
                value = measured
            ));
        }
        _ => {}
    }
    let temperature = header.temperature.as_ref().map(&value).transpose()?;
    if let Some(t) = temperature
        && !(t > -273.15 && t <= 1000.0)
    {
        return Err(err!(
            "{}, line {line}: temperature {value} °C is out of range",
            path.display(),
            value = t
        ));
    }
    Ok(RelaxationPoint {
        time,
        value: measured,
        temperature,
    })
}
