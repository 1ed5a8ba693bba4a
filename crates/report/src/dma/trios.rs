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
/// when valid (a UTF-8 mark dropped), Latin-1 otherwise.
pub(crate) fn decode(bytes: &[u8]) -> String {
    let utf16 = |little: bool| {
        let units: Vec<u16> = bytes[2..]
            .chunks_exact(2)
            .map(|c| {
                if little {
                    u16::from_le_bytes([c[0], c[1]])
                } else {
                    u16::from_be_bytes([c[0], c[1]])
                }
            })
            .collect();
        String::from_utf16_lossy(&units)
    };
    match bytes {
        [0xFF, 0xFE, ..] => utf16(true),
        [0xFE, 0xFF, ..] => utf16(false),
        _ => {
            let bytes = bytes.strip_prefix(&[0xEF, 0xBB, 0xBF]).unwrap_or(bytes);
            match std::str::from_utf8(bytes) {
                Ok(text) => text.to_string(),
                Err(_) => bytes.iter().map(|&b| char::from(b)).collect(),
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
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
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
            _ => {}
        }
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
