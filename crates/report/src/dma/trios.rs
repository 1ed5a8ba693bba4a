//! The TA Instruments TRIOS "LIMS" text export.
//!
//! A tab-separated text in `[Section]` blocks: `[Version]` first (which is
//! how it is recognised, not by the extension), then header, sample,
//! geometry, procedure and parameter sections (`key<TAB>value` lines; the
//! instrument type is `Instrument type` under `[Parameters: File
//! Parameters]`), then one `[Step]` per procedure step holding
//!
//! ```text
//! Step name<TAB>Frequency sweep (20.0 °C)
//! Variables<TAB>Temperature<TAB>Angular frequency<TAB>…<TAB>Storage modulus<TAB>Loss modulus
//! Units<TAB>°C<TAB>rad/s<TAB>…<TAB>MPa<TAB>MPa
//! Data point<TAB>20.01<TAB>0.628<TAB>…<TAB>1.25<TAB>0.31
//! ```
//!
//! Field k of a `Data point` row is the k-th variable. Used: `Angular
//! frequency` (or `Frequency`), `Storage modulus`, `Loss modulus` and, if
//! present, `Temperature` (else the temperature in the step name); other
//! variables (there are dozens, some not numbers) are ignored. Units are
//! the file's: Pa, kPa, MPa, GPa; rad/s or Hz; °C, K or °F. Steps without
//! data points (conditioning) are skipped silently, steps whose data lack
//! the needed variables with a warning.
//!
//! Shear or tensile: TRIOS calls both G′ and E′ "Storage modulus". A
//! rotational rheometer measures torque, so torque variables (`Oscillation
//! torque`, `Torque`) mean shear; an `Oscillation force` without torque
//! means a linear (tensile, bending, compression) DMA; failing both, the
//! instrument type decides (ARES, DHR, AR rheometers: shear; RSA, DMA 850,
//! Q800: tensile). [`DmaOptions::kind`] overrides, and the decision is
//! reported among the warnings so the user sees it.
//!
//! TRIOS writes UTF-8, but older versions and Windows tools write UTF-16
//! (with a byte-order mark) or Latin-1 (° as byte 0xB0): [`decode`] reads
//! all three.
//!
//! A cut-off export is refused, not read in part: each step's `Number of
//! points` must match its `Data point` rows (a file cut between rows, or
//! inside the `Variables` line of a later step, would otherwise read as
//! fewer isotherms without a word), and a file whose last line inside a
//! step has no line break is taken as cut inside that line (TRIOS ends
//! every line with one; a number cut short still parses).

use std::f64::consts::PI;
use std::path::Path;

use super::{DmaOptions, FieldNames, ModulusKind, RawPoint};
use crate::error::ReportError;

/// What the TRIOS reader found.
pub(crate) struct TriosFile {
    pub points: Vec<RawPoint>,
    pub kind: ModulusKind,
    pub names: FieldNames,
    pub warnings: Vec<String>,
}

/// Text of a file: UTF-16 when it starts with a byte-order mark, UTF-8
/// when valid (a UTF-8 mark dropped), Latin-1 when nothing in it is UTF-8
/// beyond ASCII.
///
/// Refused, with the line and byte offset: a UTF-16 file with an unpaired
/// surrogate or an odd number of bytes (cut off), and invalid UTF-8 in a
/// file that is UTF-8 elsewhere or says so with its mark: that is damage
/// or two encodings spliced, and reading it as Latin-1 would quietly turn
/// every "°C" of it into "Â°C".
pub(crate) fn decode(path: &Path, bytes: &[u8]) -> Result<String, ReportError> {
    let utf16 = |little: bool| -> Result<String, ReportError> {
        let body = &bytes[2..];
        let units = body.chunks_exact(2).map(|c| {
            if little {
                u16::from_le_bytes([c[0], c[1]])
            } else {
                u16::from_be_bytes([c[0], c[1]])
            }
        });
        let mut text = String::with_capacity(body.len() / 2);
        let mut unit = 0usize;
        for c in char::decode_utf16(units) {
            match c {
                Ok(c) => {
                    text.push(c);
                    unit += c.len_utf16();
                }
                Err(e) => {
                    return Err(ReportError::line(
                        path,
                        text.matches('\n').count() + 1,
                        format!(
                            "not UTF-16 although the file starts with a UTF-16 byte-order mark: unpaired surrogate 0x{:04X} at byte offset {}",
                            e.unpaired_surrogate(),
                            2 + 2 * unit
                        ),
                    ));
                }
            }
        }
        if body.len() % 2 == 1 {
            return Err(ReportError::line(
                path,
                text.matches('\n').count() + 1,
                format!(
                    "UTF-16 file (byte-order mark) with an odd number of bytes ({}): the last character is cut off at byte offset {}; the file looks truncated",
                    bytes.len(),
                    bytes.len() - 1
                ),
            ));
        }
        Ok(text)
    };
    match bytes {
        [0xFF, 0xFE, ..] => utf16(true),
        [0xFE, 0xFF, ..] => utf16(false),
        _ => {
            let marked = bytes.starts_with(&[0xEF, 0xBB, 0xBF]);
            let body = if marked { &bytes[3..] } else { bytes };
            match std::str::from_utf8(body) {
                Ok(text) => Ok(text.to_string()),
                Err(e) => {
                    let offset = (bytes.len() - body.len()) + e.valid_up_to();
                    if marked {
                        Err(ReportError::encoding(
                            path,
                            bytes,
                            offset,
                            "invalid UTF-8 in a file marked UTF-8 (byte-order mark)",
                        ))
                    } else if body.utf8_chunks().any(|c| !c.valid().is_ascii()) {
                        Err(ReportError::encoding(
                            path,
                            bytes,
                            offset,
                            "invalid UTF-8 in a file that is UTF-8 elsewhere (damaged, or pieces in two encodings)",
                        ))
                    } else {
                        Ok(body.iter().map(|&b| char::from(b)).collect())
                    }
                }
            }
        }
    }
}

/// Whether `text` is a LIMS export: its first non-blank line is
/// `[Version]` or names the LIMS export format.
pub(crate) fn is_lims(text: &str) -> bool {
    text.lines()
        .map(str::trim)
        .find(|l| !l.is_empty())
        .is_some_and(|l| l == "[Version]" || l.contains("LIMS export"))
}

/// One `[Step]` block.
#[derive(Default)]
struct Step<'a> {
    /// Line of `[Step]`.
    line: usize,
    name: Option<&'a str>,
    /// (line, count) of `Number of points`.
    declared: Option<(usize, usize)>,
    variables: Option<(usize, Vec<&'a str>)>,
    units: Option<(usize, Vec<&'a str>)>,
    rows: Vec<(usize, Vec<&'a str>)>,
}

impl Step<'_> {
    fn label(&self) -> String {
        match self.name {
            Some(name) => format!("step \"{name}\" (line {})", self.line),
            None => format!("step at line {}", self.line),
        }
    }

    fn variable(&self, names: &[&str]) -> Option<usize> {
        let (_, variables) = self.variables.as_ref()?;
        names.iter().find_map(|n| {
            variables
                .iter()
                .position(|v| v.trim().eq_ignore_ascii_case(n))
        })
    }
}

/// A needed variable of one step: its field index, name and conversion
/// to SI (factor, offset).
struct Field {
    index: usize,
    name: String,
    factor: f64,
    offset: f64,
}

/// Parses the LIMS text of `path`.
pub(crate) fn parse(
    path: &Path,
    text: &str,
    options: &DmaOptions,
) -> Result<TriosFile, ReportError> {
    let mut steps: Vec<Step> = Vec::new();
    let mut instrument: Option<&str> = None;
    let mut in_step = false;
    let mut last_line = 0;
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        last_line = line;
        let trimmed = raw.trim();
        if trimmed.starts_with('[') && trimmed.ends_with(']') {
            in_step = trimmed == "[Step]";
            if in_step {
                steps.push(Step {
                    line,
                    ..Step::default()
                });
            }
            continue;
        }
        let fields: Vec<&str> = raw.split('\t').collect();
        let key = fields[0].trim();
        if !in_step {
            if key == "Instrument type" && fields.len() > 1 {
                instrument = Some(fields[1].trim());
            }
            continue;
        }
        let step = steps.last_mut().expect("in a step");
        match key {
            "Step name" => step.name = fields.get(1).map(|s| s.trim()),
            "Variables" => step.variables = Some((line, fields)),
            "Units" => step.units = Some((line, fields)),
            "Data point" => step.rows.push((line, fields)),
            "Number of points" => {
                let value = fields.get(1).map_or("", |s| s.trim());
                let count = value.parse().map_err(|_| {
                    ReportError::line(
                        path,
                        line,
                        format!(
                            "{}: Number of points \"{value}\" is not a count",
                            step.label()
                        ),
                    )
                })?;
                step.declared = Some((line, count));
            }
            _ => {}
        }
    }
    for step in &steps {
        let Some((line, declared)) = step.declared else {
            continue;
        };
        let found = step.rows.len();
        if found != declared {
            let rows = match (step.rows.first(), step.rows.last()) {
                (Some((first, _)), Some((last, _))) => {
                    format!("{found} data point rows follow (lines {first} to {last})")
                }
                _ => "the step is without data points".to_string(),
            };
            let why = if found < declared {
                format!(
                    "rows are missing: the file looks truncated (it ends at line {last_line}) or was edited"
                )
            } else {
                "the file was edited or steps were merged".to_string()
            };
            return Err(ReportError::line(
                path,
                line,
                format!(
                    "{}: Number of points says {declared}, but {rows}; {why}",
                    step.label()
                ),
            ));
        }
    }
    let cut =
        !text.ends_with(['\n', '\r']) && text.lines().last().is_some_and(|l| !l.trim().is_empty());
    if in_step && cut {
        let step = steps.last().expect("in a step");
        return Err(ReportError::line(
            path,
            last_line,
            format!(
                "the file ends inside {} without a line break after this line: the export looks cut off in the middle of it (a row or a number may be incomplete); if the file is complete, end it with a line break",
                step.label()
            ),
        ));
    }

    let mut warnings = Vec::new();
    let kind = decide_kind(path, &steps, instrument, options, &mut warnings)?;
    let mut points = Vec::new();
    let mut names = None;
    let mut skipped = Vec::new();
    for step in steps.iter().filter(|s| !s.rows.is_empty()) {
        let (Some(vars), Some(units)) = (&step.variables, &step.units) else {
            return Err(ReportError::line(
                path,
                step.line,
                format!(
                    "{} has data points but no Variables and Units lines",
                    step.label()
                ),
            ));
        };
        let omega = step.variable(&["Angular frequency"]).map(|i| (i, true));
        let omega = omega.or_else(|| step.variable(&["Frequency"]).map(|i| (i, false)));
        let storage = step.variable(&["Storage modulus"]);
        let loss = step.variable(&["Loss modulus"]);
        let (Some((omega, angular)), Some(storage), Some(loss)) = (omega, storage, loss) else {
            skipped.push(format!(
                "{} (its variables: {})",
                step.label(),
                vars.1[1..].join(", ")
            ));
            continue;
        };
        let unit = |i: usize| units.1.get(i).map_or("", |u| u.trim());
        let field = |i: usize, table: &[(&str, f64, f64)], what: &str| {
            let name = vars.1[i].trim().to_string();
            let u = unit(i);
            table
                .iter()
                .find(|t| t.0 == u)
                .map(|t| Field {
                    index: i,
                    name: name.clone(),
                    factor: t.1,
                    offset: t.2,
                })
                .ok_or_else(|| {
                    let known: Vec<&str> = table.iter().map(|t| t.0).collect();
                    ReportError::line(
                        path,
                        units.0,
                        format!(
                            "{}: {what} variable \"{name}\" (column {}) has unit \"{u}\"; known units: {}",
                            step.label(),
                            i + 1,
                            known.join(", ")
                        ),
                    )
                })
        };
        let frequency_units: &[(&str, f64, f64)] = if angular {
            &[("rad/s", 1.0, 0.0), ("Hz", 2.0 * PI, 0.0)]
        } else {
            &[("Hz", 2.0 * PI, 0.0), ("rad/s", 1.0, 0.0)]
        };
        let modulus_units: &[(&str, f64, f64)] = &[
            ("Pa", 1.0, 0.0),
            ("kPa", 1e3, 0.0),
            ("MPa", 1e6, 0.0),
            ("GPa", 1e9, 0.0),
        ];
        let temperature_units: &[(&str, f64, f64)] = &[
            ("°C", 1.0, 0.0),
            ("C", 1.0, 0.0),
            ("K", 1.0, -273.15),
            ("°F", 5.0 / 9.0, -32.0 * 5.0 / 9.0),
        ];
        let omega = field(omega, frequency_units, "frequency")?;
        let storage = field(storage, modulus_units, "storage")?;
        let loss = field(loss, modulus_units, "loss")?;
        let temperature = step
            .variable(&["Temperature"])
            .map(|i| field(i, temperature_units, "temperature"))
            .transpose()?;
        let step_temperature = step.name.and_then(temperature_in_name);
        for (line, row) in &step.rows {
            let value = |f: &Field| -> Result<f64, ReportError> {
                let text = row.get(f.index).map_or("", |s| s.trim());
                let v: f64 = text.parse().map_err(|_| {
                    ReportError::line(
                        path,
                        *line,
                        format!(
                            "column {} ({}): \"{text}\" is not a number",
                            f.index + 1,
                            f.name
                        ),
                    )
                })?;
                if !v.is_finite() {
                    return Err(ReportError::line(
                        path,
                        *line,
                        format!(
                            "column {} ({}): {text} is not a finite number",
                            f.index + 1,
                            f.name
                        ),
                    ));
                }
                Ok(v * f.factor + f.offset)
            };
            points.push(RawPoint {
                line: *line,
                omega: value(&omega)?,
                storage: value(&storage)?,
                loss: value(&loss)?,
                temperature: match &temperature {
                    Some(t) => Some(value(t)?),
                    None => step_temperature,
                },
            });
        }
        let label = |f: &Field| format!("column {} ({})", f.index + 1, f.name);
        names.get_or_insert(FieldNames {
            omega: label(&omega),
            storage: label(&storage),
            loss: label(&loss),
        });
    }
    let Some(names) = names else {
        return Err(ReportError::format(
            path,
            if skipped.is_empty() {
                "TRIOS export without data points".to_string()
            } else {
                format!(
                    "no step has the variables needed (Angular frequency or Frequency, Storage modulus, Loss modulus): {}",
                    skipped.join("; ")
                )
            },
        ));
    };
    for s in skipped {
        warnings.push(format!(
            "{}: {s} lacks Angular frequency, Storage modulus or Loss modulus: skipped",
            path.display()
        ));
    }
    Ok(TriosFile {
        points,
        kind,
        names,
        warnings,
    })
}

/// Shear or tensile, and a warning saying why (see the module doc).
fn decide_kind(
    path: &Path,
    steps: &[Step],
    instrument: Option<&str>,
    options: &DmaOptions,
    warnings: &mut Vec<String>,
) -> Result<ModulusKind, ReportError> {
    let file = path.display();
    if let Some(kind) = options.kind {
        warnings.push(format!(
            "{file}: Storage and Loss modulus read as {} moduli, as asked (--dma-modulus {})",
            match kind {
                ModulusKind::Young => "Young's (tensile)",
                ModulusKind::Shear => "shear",
            },
            kind.name()
        ));
        return Ok(kind);
    }
    let variables: Vec<&str> = steps
        .iter()
        .filter_map(|s| s.variables.as_ref())
        .flat_map(|(_, v)| v[1..].iter().map(|n| n.trim()))
        .collect();
    let torque = variables
        .iter()
        .find(|v| v.to_ascii_lowercase().contains("torque"));
    let force = variables
        .iter()
        .find(|v| v.eq_ignore_ascii_case("Oscillation force"));
    let instrument_note = instrument.map_or(String::new(), |i| format!("; instrument type {i}"));
    let (kind, why) = if let Some(t) = torque {
        (ModulusKind::Shear, format!("torque variable \"{t}\""))
    } else if let Some(f) = force {
        (ModulusKind::Young, format!("\"{f}\" without torque"))
    } else {
        let lower = instrument.unwrap_or("").to_ascii_lowercase();
        let any = |names: &[&str]| names.iter().any(|n| lower.contains(n));
        if any(&[
            "ares",
            "dhr",
            "discovery hr",
            "ar-g2",
            "ar2000",
            "ar 2000",
            "hr-",
        ]) {
            (ModulusKind::Shear, "a rotational rheometer".to_string())
        } else if any(&["rsa", "dma", "q800"]) {
            (ModulusKind::Young, "a linear DMA".to_string())
        } else {
            return Err(ReportError::format(
                path,
                format!(
                    "cannot tell whether Storage and Loss modulus are shear (G) or tensile (E): no torque or Oscillation force variable{instrument_note}; give --dma-modulus shear or --dma-modulus young"
                ),
            ));
        }
    };
    warnings.push(format!(
        "{file}: Storage and Loss modulus read as {} moduli ({why}{instrument_note}); give --dma-modulus {} if they are not",
        match kind {
            ModulusKind::Young => "Young's (tensile)",
            ModulusKind::Shear => "shear",
        },
        match kind {
            ModulusKind::Young => "shear",
            ModulusKind::Shear => "young",
        }
    ));
    Ok(kind)
}

/// The temperature in a step name such as "Frequency sweep (150.0 °C)", °C.
fn temperature_in_name(name: &str) -> Option<f64> {
    let start = name.rfind('(')?;
    let inner = name[start + 1..].strip_suffix(')')?.trim();
    inner.strip_suffix("°C")?.trim().parse().ok()
}
