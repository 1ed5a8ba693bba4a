//! mu.csv and modulus.csv read back (docs/ARCHITECTURE.md, "Contract",
//! "Fit folder"): numeric CSV tables with named columns, `#` lines
//! skipped, the contract's columns required ([`super::columns`]) and the
//! others optional.

use std::path::{Path, PathBuf};

use super::columns::{
    E_LOSS, E_LOSS_SIGMA, E_STORAGE, E_STORAGE_SIGMA, EXACT_CORRECTION, MU_FIT, MU_MEASURED, OMEGA,
    SIGMA, T, TAN_DELTA, TAN_DELTA_SIGMA, V, V_REDUCED,
};
use crate::csv_columns::LineIndex;
use crate::error::field_count_tail;
use crate::error::{CellRef, ColumnRef, IoError};
use crate::text_file::read_utf8_file;

/// One row of mu.csv.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrictionRow {
    /// Rolling speed, m/s.
    pub speed: f64,
    /// Measured μ.
    pub mu_measured: f64,
    /// Fitted μ.
    pub mu_fit: f64,
    /// Standard deviation of the measured μ, when known.
    pub sigma: Option<f64>,
    /// Temperature, °C (temperature sets).
    pub temperature: Option<f64>,
    /// v·a_T, m/s (temperature sets).
    pub reduced_speed: Option<f64>,
    /// μ_exact/μ_approx at the fitted modulus (fits with
    /// `physics = "exact"`).
    pub exact_correction: Option<f64>,
}

/// One row of modulus.csv: the master curve over the window with bands.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModulusRow {
    /// rad/s.
    pub omega: f64,
    /// E′, Pa.
    pub storage: f64,
    /// E″, Pa.
    pub loss: f64,
    /// tan δ.
    pub tan_delta: f64,
    /// 1σ of E′, Pa.
    pub storage_sigma: Option<f64>,
    /// 1σ of E″, Pa.
    pub loss_sigma: Option<f64>,
    /// 1σ of tan δ.
    pub tan_delta_sigma: Option<f64>,
}

/// Reads mu.csv at `path`.
pub(super) fn read_friction(path: &Path) -> Result<Vec<FrictionRow>, IoError> {
    let table = Table::read(path)?;
    let v = table.require(V)?;
    let measured = table.require(MU_MEASURED)?;
    let fitted = table.require(MU_FIT)?;
    let sigma = table.find(SIGMA);
    let temperature = table.find(T);
    let reduced = table.find(V_REDUCED);
    let correction = table.find(EXACT_CORRECTION);
    table
        .rows
        .iter()
        .map(|(line, row)| {
            if row[v] <= 0.0 {
                return Err(err!(
                    "{}, line {line}: column {column}: {value} is not a positive speed",
                    path.display(),
                    column = V,
                    line = *line,
                    value = row[v]
                ));
            }
            Ok(FrictionRow {
                speed: row[v],
                mu_measured: row[measured],
                mu_fit: row[fitted],
                sigma: sigma.map(|i| row[i]),
                temperature: temperature.map(|i| row[i]),
                reduced_speed: reduced.map(|i| row[i]),
                exact_correction: correction.map(|i| row[i]),
            })
        })
        .collect()
}

/// Reads modulus.csv at `path`.
pub(super) fn read_modulus(path: &Path) -> Result<Vec<ModulusRow>, IoError> {
    let table = Table::read(path)?;
    let omega = table.require(OMEGA)?;
    let storage = table.require(E_STORAGE)?;
    let loss = table.require(E_LOSS)?;
    let tan_delta = table.require(TAN_DELTA)?;
    let storage_sigma = table.find(E_STORAGE_SIGMA);
    let loss_sigma = table.find(E_LOSS_SIGMA);
    let tan_delta_sigma = table.find(TAN_DELTA_SIGMA);
    let mut previous = 0.0;
    table
        .rows
        .iter()
        .map(|(line, row)| {
            if row[omega] <= previous {
                return Err(err!("{}, line {line}: column {column}: {value} does not increase (frequencies must be \
         positive and ascending)", path.display(), column = OMEGA, line = *line, value = row[omega]));
            }
            previous = row[omega];
            Ok(ModulusRow {
                omega: row[omega],
                storage: row[storage],
                loss: row[loss],
                tan_delta: row[tan_delta],
                storage_sigma: storage_sigma.map(|i| row[i]),
                loss_sigma: loss_sigma.map(|i| row[i]),
                tan_delta_sigma: tan_delta_sigma.map(|i| row[i]),
            })
        })
        .collect()
}

/// A numeric CSV with named columns: '#' lines skipped, line numbers kept.
struct Table {
    path: PathBuf,
    header: Vec<String>,
    /// (line number, values) per data row.
    rows: Vec<(usize, Vec<f64>)>,
}

impl Table {
    fn read(path: &Path) -> Result<Table, IoError> {
        let text = read_utf8_file(path)?;
        Table::parse(path, &text)
    }

    fn parse(path: &Path, text: &str) -> Result<Table, IoError> {
        let mut reader = crate::csv_columns::reader(text, false, true);
        let lines = LineIndex::new(text);
        let mut header: Option<Vec<String>> = None;
        let mut rows = Vec::new();
        for record in reader.records() {
            let record = record.map_err(|error| {
                err!(
                    "{}, line {line}: not CSV: {error}",
                    path.display(),
                    line = lines.csv_line(error.position())
                )
            })?;
            let line = lines.csv_line(record.position());
            if record.iter().all(str::is_empty) {
                continue;
            }
            let Some(names) = &header else {
                header = Some(record.iter().map(str::to_string).collect());
                continue;
            };
            rows.push((line, Table::row(path, line, names, &record)?));
        }
        let Some(header) = header else {
            return Err(err!("{}: empty: no header line", path.display()));
        };
        if rows.is_empty() {
            return Err(err!("{}: no data rows below the header", path.display()));
        }
        Ok(Table {
            path: path.to_path_buf(),
            header,
            rows,
        })
    }

    /// The numbers of the record on line `line` under the header `names`.
    fn row(
        path: &Path,
        line: usize,
        names: &[String],
        record: &csv::StringRecord,
    ) -> Result<Vec<f64>, IoError> {
        if record.len() != names.len() {
            return Err(err!(
                "{}, line {line}: {found} fields, but the header has {expected} columns{}",
                path.display(),
                field_count_tail(&[], false),
                expected = names.len(),
                found = record.len()
            ));
        }
        let mut values = Vec::with_capacity(record.len());
        for (name, field) in names.iter().zip(record.iter()) {
            let value: f64 = field.parse().map_err(|_| {
                err!(
                    "{}, {cell}: {column}: \"{text}\" is not a number",
                    path.display(),
                    cell = CellRef::line(line),
                    column = ColumnRef::named(name),
                    text = field
                )
            })?;
            if !value.is_finite() {
                return Err(err!(
                    "{}, {cell}: {column}: {text} is not a finite number",
                    path.display(),
                    cell = CellRef::line(line),
                    column = ColumnRef::named(name),
                    text = field
                ));
            }
            values.push(value);
        }
        Ok(values)
    }

    /// The index of column `name`, if present.
    fn find(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    /// The index of column `name`, or an error naming the header.
    fn require(&self, name: &'static str) -> Result<usize, IoError> {
        self.find(name).ok_or_else(|| {
            err!(
                "{}: no column `{name}` (the header has: {})",
                self.path.display(),
                self.header.clone().join(", ")
            )
        })
    }
}
