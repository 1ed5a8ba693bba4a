//! The TA Instruments TRIOS "LIMS" text export (docs/ARCHITECTURE.md,
//! "Contract", "DMA files").
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
//! The text is decoded by [`crate::text_file`] (UTF-8, UTF-16, Latin-1).
//!
//! A cut-off export is refused, not read in part: each step's `Number of
//! points` must match its `Data point` rows (a file cut between rows, or
//! inside the `Variables` line of a later step, would otherwise read as
//! fewer isotherms without a word), and a file whose last line inside a
//! step has no line break is taken as cut inside that line (TRIOS ends
//! every line with one; a number cut short still parses).

use std::path::Path;

use super::form::{FieldNames, FormRead, RawPoint};
use super::point::{DmaOptions, ModulusKind};
use super::vocabulary::Quantity;
use crate::error::parts::count_mismatch;
use crate::error::{CellRef, ColumnRef, IoError, SkippedStep, StepRef};

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
    fn label(&self) -> StepRef {
        StepRef {
            name: self.name.map(str::to_string),
            line: self.line,
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

/// The blocks of a LIMS text.
struct Scan<'a> {
    steps: Vec<Step<'a>>,
    /// `Instrument type`.
    instrument: Option<&'a str>,
    /// The text ends inside a `[Step]` block.
    in_step: bool,
    /// The last line's number.
    last_line: usize,
}

/// A needed variable of one step: its field index, name and conversion
/// to SI (factor, offset).
struct Field {
    index: usize,
    name: String,
    factor: f64,
    offset: f64,
}

impl Field {
    fn reference(&self) -> ColumnRef {
        ColumnRef::numbered(self.index + 1, &self.name)
    }
}

/// Parses the LIMS text of `path`.
pub(crate) fn parse(path: &Path, text: &str, options: &DmaOptions) -> Result<FormRead, IoError> {
    let scan = scan(path, text)?;
    check_whole(path, text, &scan)?;
    let mut warnings = Vec::new();
    let kind = decide_kind(path, &scan.steps, scan.instrument, options, &mut warnings)?;
    let mut points = Vec::new();
    let mut names = None;
    let mut skipped = Vec::new();
    for step in scan.steps.iter().filter(|s| !s.rows.is_empty()) {
        match read_step(path, step)? {
            Ok((mut step_points, step_names)) => {
                points.append(&mut step_points);
                names.get_or_insert(step_names);
            }
            Err(skip) => skipped.push(skip),
        }
    }
    let Some(names) = names else {
        let path = path.to_path_buf();
        return Err(if skipped.is_empty() {
            err!("{}: TRIOS export without data points", path.display())
        } else {
            err!(
                "{}: no step has the variables needed (Angular frequency or Frequency, Storage modulus, \
         Loss modulus): {}",
                path.display(),
                skipped
                    .iter()
                    .map(ToString::to_string)
                    .collect::<Vec<_>>()
                    .join("; ")
            )
        });
    };
    for s in skipped {
        warnings.push(format!(
            "{}: {s} lacks Angular frequency, Storage modulus or Loss modulus: skipped",
            path.display()
        ));
    }
    Ok(FormRead {
        points,
        kind,
        names,
        warnings,
        preamble: Vec::new(),
    })
}

/// The `[Step]` blocks and the instrument type of `text`.
fn scan<'a>(path: &Path, text: &'a str) -> Result<Scan<'a>, IoError> {
    let mut scan = Scan {
        steps: Vec::new(),
        instrument: None,
        in_step: false,
        last_line: 0,
    };
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        scan.last_line = line;
        let trimmed = raw.trim();
        if trimmed.starts_with('[') && trimmed.ends_with(']') {
            scan.in_step = trimmed == "[Step]";
            if scan.in_step {
                scan.steps.push(Step {
                    line,
                    ..Step::default()
                });
            }
            continue;
        }
        let fields: Vec<&str> = raw.split('\t').collect();
        let key = fields[0].trim();
        if !scan.in_step {
            if key == "Instrument type" && fields.len() > 1 {
                scan.instrument = Some(fields[1].trim());
            }
            continue;
        }
        let step = scan.steps.last_mut().expect("in a step");
        match key {
            "Step name" => step.name = fields.get(1).map(|s| s.trim()),
            "Variables" => step.variables = Some((line, fields)),
            "Units" => step.units = Some((line, fields)),
            "Data point" => step.rows.push((line, fields)),
            "Number of points" => {
                let value = fields.get(1).map_or("", |s| s.trim());
                let count = value.parse().map_err(|_| {
                    err!(
                        "{}, line {line}: {step}: Number of points \"{text}\" is not a count",
                        path.display(),
                        step = step.label(),
                        text = value
                    )
                })?;
                step.declared = Some((line, count));
            }
            _ => {}
        }
    }
    Ok(scan)
}

/// Refuses a cut-off export: a step whose rows are not as many as its
/// `Number of points`, a last line inside a step without a line break.
fn check_whole(path: &Path, text: &str, scan: &Scan) -> Result<(), IoError> {
    for step in &scan.steps {
        let Some((line, declared)) = step.declared else {
            continue;
        };
        let found = step.rows.len();
        if found != declared {
            let rows = match (step.rows.first(), step.rows.last()) {
                (Some((first, _)), Some((last, _))) => Some((*first, *last)),
                _ => None,
            };
            return Err(err!(
                "{}, line {line}: {step}: Number of points says {declared}, but {}",
                path.display(),
                count_mismatch(declared, found, rows, scan.last_line),
                step = step.label()
            ));
        }
    }
    let cut =
        !text.ends_with(['\n', '\r']) && text.lines().last().is_some_and(|l| !l.trim().is_empty());
    if scan.in_step && cut {
        let step = scan.steps.last().expect("in a step");
        return Err(err!(
            "{}, line {line}: the file ends inside {step} without a line break after this line: the \
         export looks cut off in the middle of it (a row or a number may be incomplete); if the \
         file is complete, end it with a line break",
            path.display(),
            line = scan.last_line,
            step = step.label()
        ));
    }
    Ok(())
}

/// What a step with data gives: its points and the names of their fields,
/// or the step as skipped when it lacks a needed variable.
type StepRead = Result<(Vec<RawPoint>, FieldNames), SkippedStep>;

/// The points of a step with data (see [`StepRead`]).
fn read_step(path: &Path, step: &Step) -> Result<StepRead, IoError> {
    let (Some(vars), Some(units)) = (&step.variables, &step.units) else {
        return Err(err!(
            "{}, line {line}: {step} has data points but no Variables and Units lines",
            path.display(),
            line = step.line,
            step = step.label()
        ));
    };
    let omega = step.variable(&["Angular frequency"]).map(|i| (i, true));
    let omega = omega.or_else(|| step.variable(&["Frequency"]).map(|i| (i, false)));
    let storage = step.variable(&["Storage modulus"]);
    let loss = step.variable(&["Loss modulus"]);
    let (Some((omega, angular)), Some(storage), Some(loss)) = (omega, storage, loss) else {
        return Ok(Err(SkippedStep {
            step: step.label(),
            variables: vars.1[1..].iter().map(|v| v.to_string()).collect(),
        }));
    };
    let field = |i: usize, quantity: Quantity, name_of: &'static str| {
        let name = vars.1[i].trim().to_string();
        let unit = units.1.get(i).map_or("", |u| u.trim());
        match quantity.unit(unit) {
            Some((factor, offset)) => Ok(Field {
                index: i,
                name,
                factor,
                offset,
            }),
            None => Err(err!(
                "{}, line {line}: {step}: {name_of} variable \"{variable}\" (column {number}) has unit \
     \"{unit}\"; known units: {}",
                path.display(),
                quantity.known(),
                line = units.0,
                number = i + 1,
                step = step.label(),
                variable = name
            )),
        }
    };
    let frequency = if angular {
        Quantity::Omega
    } else {
        Quantity::Frequency
    };
    let omega = field(omega, frequency, "frequency")?;
    let storage = field(storage, Quantity::Storage(None), "storage")?;
    let loss = field(loss, Quantity::Loss(None), "loss")?;
    let temperature = step
        .variable(&["Temperature"])
        .map(|i| field(i, Quantity::Temperature, "temperature"))
        .transpose()?;
    let step_temperature = step.name.and_then(temperature_in_name);
    let mut points = Vec::with_capacity(step.rows.len());
    for (line, row) in &step.rows {
        let value = |f: &Field| cell(path, *line, row, f);
        points.push(RawPoint {
            line: *line,
            omega: value(&omega)?,
            storage: value(&storage)?,
            loss: value(&loss)?,
            temperature: match &temperature {
                Some(t) => Some(value(t)?),
                None => step_temperature,
            },
            step: None,
        });
    }
    let names = FieldNames {
        omega: omega.reference(),
        storage: storage.reference(),
        loss: loss.reference(),
    };
    Ok(Ok((points, names)))
}

/// The value of field `f` in the `Data point` row on line `line`, in SI.
fn cell(path: &Path, line: usize, row: &[&str], f: &Field) -> Result<f64, IoError> {
    let text = row.get(f.index).map_or("", |s| s.trim());
    let v: f64 = text.parse().map_err(|_| {
        err!(
            "{}, {cell}: {column}: \"{text}\" is not a number",
            path.display(),
            cell = CellRef::line(line),
            column = f.reference(),
        )
    })?;
    if !v.is_finite() {
        return Err(err!(
            "{}, {cell}: {column}: {text} is not a finite number",
            path.display(),
            cell = CellRef::line(line),
            column = f.reference(),
        ));
    }
    Ok(v * f.factor + f.offset)
}

/// Shear or tensile, and a warning saying why (see the module doc).
fn decide_kind(
    path: &Path,
    steps: &[Step],
    instrument: Option<&str>,
    options: &DmaOptions,
    warnings: &mut Vec<String>,
) -> Result<ModulusKind, IoError> {
    let file = path.display();
    let read_as = |kind: ModulusKind| match kind {
        ModulusKind::Young => "Young's (tensile)",
        ModulusKind::Shear => "shear",
    };
    if let Some(kind) = options.kind {
        warnings.push(format!(
            "{file}: Storage and Loss modulus read as {} moduli, as asked (--dma-modulus {})",
            read_as(kind),
            kind.name()
        ));
        return Ok(kind);
    }
    let instrument_note = instrument.map_or(String::new(), |i| format!("; instrument type {i}"));
    let Some((kind, why)) = kind_of(steps, instrument) else {
        return Err(err!(
            "{}: cannot tell whether Storage and Loss modulus are shear (G) or tensile (E): no \
             torque or Oscillation force variable{instrument_note}; give --dma-modulus shear or \
             --dma-modulus young",
            path.display()
        ));
    };
    warnings.push(format!(
        "{file}: Storage and Loss modulus read as {} moduli ({why}{instrument_note}); give --dma-modulus {} if they are not",
        read_as(kind),
        match kind {
            ModulusKind::Young => "shear",
            ModulusKind::Shear => "young",
        }
    ));
    Ok(kind)
}

/// Shear or tensile from the steps' variables, then the instrument type,
/// with the reason; `None` when neither tells.
fn kind_of(steps: &[Step], instrument: Option<&str>) -> Option<(ModulusKind, String)> {
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
    if let Some(t) = torque {
        return Some((ModulusKind::Shear, format!("torque variable \"{t}\"")));
    }
    if let Some(f) = force {
        return Some((ModulusKind::Young, format!("\"{f}\" without torque")));
    }
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
        Some((ModulusKind::Shear, "a rotational rheometer".to_string()))
    } else if any(&["rsa", "dma", "q800"]) {
        Some((ModulusKind::Young, "a linear DMA".to_string()))
    } else {
        None
    }
}

/// The temperature in a step name such as "Frequency sweep (150.0 °C)", °C.
fn temperature_in_name(name: &str) -> Option<f64> {
    let start = name.rfind('(')?;
    let inner = name[start + 1..].strip_suffix(')')?.trim();
    inner.strip_suffix("°C")?.trim().parse().ok()
}
