//! Reader for modulus tables: a measured master curve of Young's modulus,
//! the material of `model = "table"`.
//!
//! Plain format: a CSV with a header row, then one row per frequency.
//! Columns: a frequency, either `omega` (rad/s) or `f` (Hz), and
//! `E_storage`, `E_loss` (Pa). Other columns (e.g. `tan_delta` in a
//! `modulus.csv` written by `rollfit fit`) are ignored. Lines starting with
//! `#` are comments. Frequencies must be positive and strictly increasing,
//! moduli positive: the model interpolates in log–log, where zero and
//! negative values have no place.
//!
//! Every other form the DMA reader accepts ([`rollfit_io::dma`]) is read
//! by it, so that the formats are defined once: shear columns `G_storage`,
//! `G_loss` (E = 2(1+ν)G with the scene's ν), unit-suffixed names
//! (`omega_rad_s`, `f_Hz`, `G_storage_kPa`, `E_loss_MPa`, `T_C`, `T_K`), a
//! temperature column, and the TA TRIOS LIMS text export. The header
//! decides: a CSV whose header has `omega` or `f`, `E_storage` and `E_loss`
//! and no temperature column (`T`, `T_C`, `T_K`) is a plain table (read
//! exactly as before); anything else goes to the DMA reader. From there:
//! - a table is one master curve: a file with several temperatures
//!   (isotherms within 0.5 K) is refused, naming them; one temperature
//!   is read as the master curve at that temperature;
//! - rows are sorted by frequency (sweeps often run downwards), and a
//!   frequency given twice is refused, naming both lines;
//! - a point with E″ ≤ 0 is dropped (not refused), named in
//!   [`ModulusTable::notes`] with its line.
//!
//! The model checks the same things again; checking here as well is what
//! lets an error name the line of the file. [`explain_contact_map`] turns
//! the model's contact-map error into the table lines that cause it.

use std::f64::consts::PI;
use std::path::Path;

use anyhow::{Context, Result, anyhow, bail, ensure};
use rollfit_io::csv_columns::{self, csv_line};
use rollfit_io::dma::{DmaData, DmaOptions, ModulusKind, isotherms};

/// A master curve as read: angular frequency (rad/s), storage and loss
/// Young's moduli (Pa), in increasing frequency.
#[derive(Debug, Clone, PartialEq)]
pub struct ModulusTable {
    /// Angular frequencies ω, rad/s, strictly increasing.
    pub omega: Vec<f64>,
    /// Storage modulus E′(ω), Pa.
    pub storage: Vec<f64>,
    /// Loss modulus E″(ω), Pa.
    pub loss: Vec<f64>,
    /// The file line (from 1) of each row, for messages.
    pub lines: Vec<usize>,
    /// How the file was read where that is worth saying (shear moduli
    /// converted with ν, the one temperature of the file) and what was
    /// left out (points with E″ ≤ 0, with their lines): the DMA reader's
    /// notes and warnings, each naming the file. Empty for a plain table.
    pub notes: Vec<String>,
}

/// Reads and checks the modulus table at `path`, in any form described in
/// the module documentation; errors name the file (and the line where
/// there is one). `poisson` (the scene's `[substrate] poisson`) converts
/// shear moduli and is used only for them; `kind` overrides the shear or
/// tensile decision for a TRIOS export (a CSV says it with its column
/// names).
pub fn read_with(path: &Path, poisson: f64, kind: Option<ModulusKind>) -> Result<ModulusTable> {
    let bytes = std::fs::read(path)
        .with_context(|| format!("cannot read modulus table {}", path.display()))?;
    // Text that is not UTF-8 (a Latin-1 or UTF-16 export) is the DMA
    // reader's: it decodes both.
    let text = std::str::from_utf8(&bytes).ok();
    if let Some(text) = text
        && is_plain(text)
    {
        return parse(text).with_context(|| format!("modulus table {}", path.display()));
    }
    // master.csv of `rollfit master`: every DMA point moved to the
    // reference, the isotherm of each in `T`, scattered where isotherms
    // overlap. Its smooth curve is modulus.csv beside it.
    let shifted_points = text
        .and_then(header_names)
        .is_some_and(|h| h.iter().any(|n| n == "omega_measured"));
    read_dma(path, poisson, kind, shifted_points)
}

/// Column names the DMA reader reads and the plain reader does not (see
/// `rollfit_io::dma::csv_form`): shear moduli, a temperature, and
/// unit-suffixed spellings, including the contradictory `omega_Hz` and
/// `f_rad_s` it refuses with a message saying why.
fn is_dma_column(name: &str) -> bool {
    const MODULI: [&str; 4] = ["E_storage", "E_loss", "G_storage", "G_loss"];
    const PA: [&str; 4] = ["Pa", "kPa", "MPa", "GPa"];
    let suffixed = |base: &str, units: &[&str]| {
        name.strip_prefix(base)
            .and_then(|rest| rest.strip_prefix('_'))
            .is_some_and(|unit| units.contains(&unit))
    };
    matches!(name, "G_storage" | "G_loss" | "T")
        || MODULI.iter().any(|base| suffixed(base, &PA))
        || suffixed("omega", &["rad_s", "Hz"])
        || suffixed("f", &["Hz", "rad_s"])
        || suffixed("T", &["C", "K"])
}

/// The header row of the CSV `text` (comments skipped), or `None` when
/// there is none to read.
fn header_names(text: &str) -> Option<Vec<String>> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let header = reader.headers().ok()?;
    Some(header.iter().map(str::to_string).collect())
}

/// Whether `text` is for the plain reader: its header names a plain column
/// (`omega`, `f`, `E_storage`, `E_loss`) and none that only the DMA reader
/// reads (so that a plain table with a column missing or misspelt gets the
/// plain reader's message, as before). A text without a header is the
/// plain reader's to refuse, with its message; a TRIOS export's first line
/// names no plain column.
fn is_plain(text: &str) -> bool {
    let Some(header) = header_names(text) else {
        return true;
    };
    let plain = |name: &String| matches!(name.as_str(), "omega" | "f" | "E_storage" | "E_loss");
    header.iter().all(String::is_empty)
        || (header.iter().any(plain) && !header.iter().any(|h| is_dma_column(h)))
}

/// A message of the DMA reader in the words of a scene file: the DMA
/// reader serves `rollfit compare` and `report`, where ν is the fit's and
/// the modulus kind a command-line flag; here they are `[substrate]
/// poisson` and `[material] modulus`. (A rewording the DMA reader's text
/// no longer matches is left as it is: still true, in the other words.)
fn in_scene_words(message: &str) -> String {
    message
        .replace("(the fit's)", "([substrate] poisson)")
        .replace("--dma-modulus shear", "[material] modulus = \"shear\"")
        .replace("--dma-modulus young", "[material] modulus = \"young\"")
}

/// A temperature as a message shows it: to 0.1 K (an isotherm's mean,
/// within a controller's scatter), without trailing zeros.
fn celsius(t: f64) -> String {
    // + 0.0: −0.02 °C shows as 0, not −0.
    format!("{} °C", (t * 10.0).round() / 10.0 + 0.0)
}

/// Reads a file of the DMA forms and makes one master curve of it;
/// `shifted_points`: the file looks like the master.csv of `rollfit
/// master`, which a refusal then says.
fn read_dma(
    path: &Path,
    poisson: f64,
    kind: Option<ModulusKind>,
    shifted_points: bool,
) -> Result<ModulusTable> {
    let file = path.display();
    // ν matters only for shear moduli: a bad ν is refused only then, and
    // named as the scene's (the DMA reader would call it the fit's).
    let usable = poisson > -1.0 && poisson <= 0.5;
    let options = DmaOptions { kind, wlf: None };
    let data = DmaData::read(path, if usable { poisson } else { 0.5 }, &options)
        .map_err(|e| anyhow!("modulus table {}", in_scene_words(&e.to_string())))?;
    if !usable && data.kind == ModulusKind::Shear {
        bail!(
            "modulus table {file}: holds shear moduli G′, G″; converting them to Young's \
             moduli (E = 2(1+ν)G) needs [substrate] poisson in (−1, 0.5], not {poisson}"
        );
    }
    let isotherms = isotherms(&data.points);
    if isotherms.len() > 1 {
        // With a few isotherms each is named with its lines; a whole
        // temperature programme by its temperatures.
        let listed: Vec<String> = if isotherms.len() <= 6 {
            isotherms
                .iter()
                .map(|i| {
                    let lines = i.points.iter().map(|&k| data.lines[k]);
                    format!(
                        "{} ({} point(s), lines {}–{})",
                        celsius(i.temperature),
                        i.points.len(),
                        lines.clone().min().unwrap_or(0),
                        lines.max().unwrap_or(0)
                    )
                })
                .collect()
        } else {
            isotherms.iter().map(|i| celsius(i.temperature)).collect()
        };
        let advice = if shifted_points {
            "This looks like the master.csv of `rollfit master` (column omega_measured): \
             its points scatter where the isotherms overlap; give the smooth master curve \
             beside it, modulus.csv, as the table instead"
                .to_string()
        } else {
            format!(
                "Use [material] model = \"dma\", file = \"…\" to shift the isotherms into a \
                 master curve, or build one with `rollfit master {file}`"
            )
        };
        bail!(
            "modulus table {file}: {} temperatures: {}; a table is one master curve at one \
             temperature. {advice}",
            isotherms.len(),
            listed.join(", ")
        );
    }

    // How the file was read first, then what was left out.
    let mut notes: Vec<String> = data.notes.iter().map(|m| in_scene_words(m)).collect();
    if let Some(isotherm) = isotherms.first() {
        notes.push(format!(
            "{file}: all points at {}: read as the master curve at that temperature \
             ([material.shift] T_ref, if given, should be it)",
            celsius(isotherm.temperature)
        ));
    }
    notes.extend(data.warnings.iter().map(|m| in_scene_words(m)));

    let mut order: Vec<usize> = (0..data.points.len()).collect();
    order.sort_by(|&a, &b| data.points[a].omega.total_cmp(&data.points[b].omega));
    for pair in order.windows(2) {
        let (a, b) = (&data.points[pair[0]], &data.points[pair[1]]);
        if b.omega <= a.omega {
            let (first, second) = (
                data.lines[pair[0]].min(data.lines[pair[1]]),
                data.lines[pair[0]].max(data.lines[pair[1]]),
            );
            bail!(
                "modulus table {file}, lines {first} and {second}: the same frequency \
                 ω = {} rad/s twice; a master curve has one modulus per frequency: remove \
                 or average the repeated rows",
                a.omega
            );
        }
    }
    ensure!(
        order.len() >= 2,
        "modulus table {file}: the table has {} usable data row(s): at least two frequencies \
         are needed to interpolate",
        order.len()
    );
    Ok(ModulusTable {
        omega: order.iter().map(|&k| data.points[k].omega).collect(),
        storage: order.iter().map(|&k| data.points[k].storage).collect(),
        loss: order.iter().map(|&k| data.points[k].loss).collect(),
        lines: order.iter().map(|&k| data.lines[k]).collect(),
        notes,
    })
}

/// The largest accepted E′ or E″, Pa: above any solid's modulus, and small
/// enough that the contact map ω·a(ω) built from the table stays finite.
const MAX_MODULUS: f64 = 1e13;

/// Accepted angular frequencies, rad/s: wider than any master curve, far
/// inside the floating-point range the contact map needs.
const OMEGA_RANGE: (f64, f64) = (1e-30, 1e30);

/// Which kind of frequency the table gives.
#[derive(Clone, Copy)]
enum Frequency {
    /// `omega`, rad/s.
    Angular,
    /// `f`, Hz.
    Hertz,
}

/// Parses and checks a plain modulus table (the CSV text of a file).
pub fn parse(text: &str) -> Result<ModulusTable> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let header = csv_columns::header(&mut reader, "omega or f, E_storage, E_loss")?;
    let position = |name: &str| header.iter().position(|h| h == name);
    let (frequency_column, frequency) = match (position("omega"), position("f")) {
        (Some(i), None) => (i, Frequency::Angular),
        (None, Some(i)) => (i, Frequency::Hertz),
        (Some(_), Some(_)) => {
            bail!("the header has both `omega` (rad/s) and `f` (Hz): keep one frequency column")
        }
        (None, None) => bail!(
            "the header has no frequency column: expected `omega` (rad/s) or `f` (Hz), found {}",
            csv_columns::list(&header)
        ),
    };
    let mut columns = [frequency_column, 0, 0];
    for (slot, name) in columns.iter_mut().skip(1).zip(["E_storage", "E_loss"]) {
        *slot = match position(name) {
            Some(i) => i,
            None if header.iter().any(|h| h.starts_with("G_")) => bail!(
                "the header has no `{name}` column: a material table holds Young's moduli \
                 E_storage, E_loss (Pa); convert shear moduli with E = 2(1 + ν) G"
            ),
            None => bail!(
                "the header has no `{name}` column (Pa); found {}",
                csv_columns::list(&header)
            ),
        };
    }
    let names = [
        header[frequency_column].to_string(),
        "E_storage".into(),
        "E_loss".into(),
    ];

    let mut table = ModulusTable {
        omega: Vec::new(),
        storage: Vec::new(),
        loss: Vec::new(),
        lines: Vec::new(),
        notes: Vec::new(),
    };
    let mut previous_line = 0;
    for record in reader.records() {
        let record = record.context("malformed row")?;
        // Counted as the DMA reader counts (comments, blank lines, CRLF).
        let line = csv_line(text, record.position()) as u64;
        let mut values = [0.0; 3];
        for ((value, &column), name) in values.iter_mut().zip(&columns).zip(&names) {
            *value = csv_columns::finite(&record, column, line, name)?;
            ensure!(
                *value > 0.0,
                "line {line}: column `{name}` = {value}: must be greater than zero \
                 (the table is interpolated in log-log)"
            );
        }
        for (value, name) in values.iter().zip(&names).skip(1) {
            ensure!(
                *value <= MAX_MODULUS,
                "line {line}: column `{name}` = {value:e}: above 1e13 Pa, stiffer than any solid \
                 (diamond: about 1.2e12 Pa); is the column in Pa?"
            );
        }
        let omega = match frequency {
            Frequency::Angular => values[0],
            Frequency::Hertz => 2.0 * PI * values[0],
        };
        ensure!(
            (OMEGA_RANGE.0..=OMEGA_RANGE.1).contains(&omega),
            "line {line}: frequency {} = {:e}: outside 1e-30 … 1e30 rad/s, beyond any master \
             curve",
            names[0],
            values[0]
        );
        if let Some(&last) = table.omega.last() {
            ensure!(
                omega > last,
                "line {line}: frequency {} = {} does not exceed the one on line {previous_line}: \
                 rows must be in strictly increasing frequency",
                names[0],
                values[0]
            );
        }
        table.omega.push(omega);
        table.storage.push(values[1]);
        table.loss.push(values[2]);
        table.lines.push(line as usize);
        previous_line = line;
    }
    ensure!(
        table.omega.len() >= 2,
        "the table has {} data row(s): at least two frequencies are needed to interpolate",
        table.omega.len()
    );
    Ok(table)
}

/// What the model's contact-map error
/// (`rollfit_model::ModelError::ContactMapNotIncreasing`: "the contact map
/// ω·a(ω) is not increasing at ω = … rad/s (the modulus rises faster than
/// ω^n)") means in `table`, read from `path`: the rows
/// whose frequencies bracket `omega`, the neighbouring rows within a
/// decade of it between which |E*| rises faster than ω^`exponent` (the
/// five nearest, in increasing ω, with their ω and |E*|; failing any, the
/// steepest rows nearby), and what to do.
///
/// `omega` is the table's frequency, rad/s: for a material shifted to a
/// temperature that is the model's ω times a_T. `exponent` is n of the
/// contact size r ∝ |E*|^(−1/n): 3 for a sphere, 2 for a cylinder.
pub fn explain_contact_map(table: &ModulusTable, path: &Path, omega: f64, exponent: f64) -> String {
    /// How many steep row pairs are listed.
    const LISTED_PAIRS: usize = 5;
    let rows = table.omega.len();
    let abs: Vec<f64> = table
        .storage
        .iter()
        .zip(&table.loss)
        .map(|(s, l)| s.hypot(*l))
        .collect();
    let line = |i: usize| table.lines.get(i).copied().unwrap_or(0);
    let row = |i: usize| {
        format!(
            "line {} (ω = {:.3e} rad/s, |E*| = {:.3e} Pa)",
            line(i),
            table.omega[i],
            abs[i]
        )
    };
    let mut text = format!(
        "modulus table {}: the contact map fails at ω = {omega:.3e} rad/s",
        path.display()
    );
    let above = table.omega.partition_point(|&w| w <= omega);
    text.push_str(&match above {
        _ if rows == 0 => String::new(),
        0 => format!(", below the first row, {}", row(0)),
        k if k == rows && table.omega[k - 1] < omega => {
            format!(", above the last row, {}", row(k - 1))
        }
        k if table.omega[k - 1] == omega || k == rows => format!(", at {}", row(k - 1)),
        k => format!(", between {} and {}", row(k - 1), row(k)),
    });

    // The log–log slope of |E*| between neighbouring rows i and i + 1,
    // and how far (in ln ω) that interval lies from ω.
    let ln_omega = omega.ln();
    let slope = |i: usize| (abs[i + 1] / abs[i]).ln() / (table.omega[i + 1] / table.omega[i]).ln();
    let distance = |i: usize| {
        let (lo, hi) = (table.omega[i].ln(), table.omega[i + 1].ln());
        (lo - ln_omega).max(ln_omega - hi).max(0.0)
    };
    let pair = |i: usize| {
        format!(
            "\n  line {} → line {}: ω {:.3e} → {:.3e} rad/s, |E*| {:.3e} → {:.3e} Pa \
             (log–log slope {:.1})",
            line(i),
            line(i + 1),
            table.omega[i],
            table.omega[i + 1],
            abs[i],
            abs[i + 1],
            slope(i)
        )
    };
    let intervals = 0..rows.saturating_sub(1);
    let steep: Vec<usize> = intervals.clone().filter(|&i| slope(i) > exponent).collect();
    let mut near: Vec<usize> = steep
        .iter()
        .copied()
        .filter(|&i| distance(i) <= 10f64.ln())
        .collect();
    near.sort_by(|&a, &b| distance(a).total_cmp(&distance(b)));
    if near.is_empty() {
        // The interpolant's slope at a row may reach three times a chord's:
        // scatter steepens it between rows that are not steep themselves.
        let mut nearby: Vec<usize> = intervals
            .filter(|&i| distance(i) <= 10f64.ln() && slope(i) > 0.0)
            .collect();
        nearby.sort_by(|&a, &b| slope(b).total_cmp(&slope(a)));
        text.push_str(&format!(
            ". No neighbouring rows within a decade of it rise faster than ω^{exponent}, but \
             the curve interpolated between them does (scatter steepens it: its slope at a row \
             may reach three times the chords'){}",
            if nearby.is_empty() {
                String::new()
            } else {
                "; the steepest rows nearby:".to_string()
            }
        ));
        for &i in nearby.iter().take(3) {
            text.push_str(&pair(i));
        }
    } else {
        text.push_str(&format!(
            ". There |E*| rises faster than ω^{exponent} between neighbouring rows, faster than \
             the dynamic contact size can follow (r ∝ |E*|^(−1/{exponent})):"
        ));
        // The nearest ones, listed in the table's order.
        let mut listed: Vec<usize> = near.iter().copied().take(LISTED_PAIRS).collect();
        listed.sort_unstable();
        for &i in &listed {
            text.push_str(&pair(i));
        }
        let more = near.len().saturating_sub(LISTED_PAIRS);
        if more > 0 {
            text.push_str(&format!("\n  and {more} more pair(s) within a decade"));
        }
        if steep.len() > near.len() {
            text.push_str(&format!(
                "\n  ({} such pair(s) in the whole table)",
                steep.len()
            ));
        }
    }
    text.push_str(
        "\nSmooth or bin the table (overlapping isotherms scatter), or give the isotherms \
         themselves with [material] model = \"dma\", file = \"…\", which fits a smooth causal \
         Prony series.",
    );
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse_str(text: &str) -> Result<ModulusTable> {
        parse(text)
    }

    fn message(text: &str) -> String {
        format!("{:#}", parse_str(text).unwrap_err())
    }

    #[test]
    fn reads_omega_and_hertz_with_comments_and_extra_columns() {
        let t = parse_str("# master curve\nomega,E_storage,E_loss,tan_delta\n1,2e6,1e5,0.05\n# mid\n10, 3e6, 2e5, 0.07\n").unwrap();
        assert_eq!(t.omega, vec![1.0, 10.0]);
        assert_eq!(t.storage, vec![2e6, 3e6]);
        assert_eq!(t.loss, vec![1e5, 2e5]);
        let t = parse_str("f,E_loss,E_storage\n1,1e5,2e6\n2,1e5,2e6\n").unwrap();
        assert!((t.omega[0] - 2.0 * PI).abs() < 1e-15);
        assert_eq!(t.storage[1], 2e6);
    }

    #[test]
    fn errors_name_the_line_and_column() {
        let m = message("omega,E_storage,E_loss\n1,2e6,1e5\n10,abc,2e5\n");
        assert!(
            m.contains("line 3") && m.contains("E_storage") && m.contains("abc"),
            "{m}"
        );
        let m = message("omega,E_storage,E_loss\n1,2e6,1e5\n1,2e6,2e5\n");
        assert!(m.contains("line 3") && m.contains("increasing"), "{m}");
        let m = message("omega,E_storage,E_loss\n1,2e6,1e5\n2,2e6,0\n");
        assert!(
            m.contains("line 3") && m.contains("E_loss") && m.contains("greater than zero"),
            "{m}"
        );
        let m = message("omega,E_storage,E_loss\n1,2e6,nan\n2,2e6,1\n");
        assert!(m.contains("line 2") && m.contains("finite"), "{m}");
    }

    #[test]
    fn lines_are_counted_below_comments_blank_lines_and_in_crlf_files() {
        for (text, line) in [
            ("omega,E_storage,E_loss\n1,2e6,1e5\n# mid\n10,abc,2e5\n", 4),
            ("omega,E_storage,E_loss\r\n1,2e6,1e5\r\n10,abc,2e5\r\n", 3),
            ("omega,E_storage,E_loss\n1,2e6,1e5\n\n\n10,abc,2e5\n", 5),
            (
                "# a\n# b\nomega,E_storage,E_loss\n1,2e6,1e5\n10,abc,2e5\n",
                5,
            ),
        ] {
            let m = message(text);
            assert!(m.starts_with(&format!("line {line}: ")), "{text:?}: {m}");
        }
        let t = parse_str("# a\r\nomega,E_storage,E_loss\r\n1,2e6,1e5\r\n# b\r\n\r\n2,2e6,1e5")
            .unwrap();
        assert_eq!(t.lines, vec![3, 6]);
    }

    #[test]
    fn rejects_empty_and_incomplete_tables() {
        assert!(message("").contains("empty"));
        assert!(message("# nothing\n").contains("empty"));
        assert!(message("omega,E_storage,E_loss\n").contains("0 data row"));
        assert!(message("omega,E_storage\n1,2\n").contains("E_loss"));
        assert!(message("w,E_storage,E_loss\n1,2,3\n").contains("frequency column"));
        assert!(message("omega,f,E_storage,E_loss\n1,2,3,4\n").contains("both"));
        assert!(message("f,G_storage,G_loss\n1,2,3\n").contains("2(1 + ν) G"));
        assert!(message("omega,E_storage,E_loss\n1,2,3\n2,3\n").contains("malformed row"));
    }

    // ------------------------------------------------------ every DMA form

    /// A folder of its own under the system's temporary folder, removed on
    /// drop.
    struct TempDir(std::path::PathBuf);

    impl TempDir {
        fn new(name: &str) -> TempDir {
            let path = std::env::temp_dir()
                .join(format!("rollfit-table-file-{}-{name}", std::process::id()));
            let _ = std::fs::remove_dir_all(&path);
            std::fs::create_dir_all(&path).unwrap();
            TempDir(path)
        }

        fn write(&self, name: &str, text: &str) -> std::path::PathBuf {
            let path = self.0.join(name);
            std::fs::write(&path, text).unwrap();
            path
        }
    }

    impl Drop for TempDir {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    /// A standard linear solid, Young's (E′, E″) in Pa at ω rad/s.
    fn sls(omega: f64) -> (f64, f64) {
        let (e0, e1, tau) = (2e6, 2e8, 1e-2);
        let x = omega * tau;
        let d = 1.0 + x * x;
        (e0 + (e1 - e0) * x * x / d, (e1 - e0) * x / d)
    }

    const OMEGAS: [f64; 5] = [0.5, 3.0, 20.0, 150.0, 900.0];

    fn relative(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    fn assert_same_curve(name: &str, t: &ModulusTable, reference: &ModulusTable) {
        assert_eq!(t.omega.len(), reference.omega.len(), "{name}");
        for i in 0..t.omega.len() {
            for (a, b, what) in [
                (t.omega[i], reference.omega[i], "ω"),
                (t.storage[i], reference.storage[i], "E′"),
                (t.loss[i], reference.loss[i], "E″"),
            ] {
                assert!(relative(a, b) < 1e-12, "{name}: row {i}: {what} {a} vs {b}");
            }
        }
    }

    /// The equivalent TRIOS LIMS export of a rotational rheometer: shear
    /// moduli (G = E/3) in MPa and kPa, one isotherm with ±0.02 K of
    /// controller scatter, the sweep running down in frequency as
    /// instruments run it.
    fn trios_shear(temperatures: &[f64]) -> String {
        let mut text = String::from(
            "[Version]\nTA Instruments LIMS export format version\t0\n[Header]\n\
             Document ID\trollfit table test\n[Parameters]\n[Parameters: File Parameters]\n\
             Instrument type\tAresG2\n",
        );
        for &t in temperatures {
            text.push_str(&format!(
                "[Step]\nStep name\tFrequency sweep ({t:.1} °C)\nNumber of points\t{}\n\
                 Variables\tTemperature\tAngular frequency\tOscillation torque\t\
                 Storage modulus\tLoss modulus\tTan(delta)\n\
                 Units\t°C\trad/s\tµN.m\tMPa\tkPa\t\n",
                OMEGAS.len()
            ));
            for (k, &omega) in OMEGAS.iter().enumerate().rev() {
                let (s, l) = sls(omega);
                let scatter = [0.01, -0.01, 0.02, 0.0, -0.02][k];
                text.push_str(&format!(
                    "Data point\t{}\t{omega:e}\t100\t{:e}\t{:e}\t{:e}\n",
                    t + scatter,
                    s / 3e6,
                    l / 3e3,
                    l / s
                ));
            }
        }
        text
    }

    #[test]
    fn every_dma_form_gives_the_plain_tables_curve() {
        let dir = TempDir::new("forms");
        let rows = |row: &dyn Fn(f64, f64, f64) -> String| -> String {
            OMEGAS
                .iter()
                .map(|&w| {
                    let (s, l) = sls(w);
                    row(w, s, l) + "\n"
                })
                .collect()
        };
        let plain = dir.write(
            "plain.csv",
            &format!(
                "omega,E_storage,E_loss\n{}",
                rows(&|w, s, l| format!("{w:e},{s:e},{l:e}"))
            ),
        );
        let reference = read_with(&plain, 0.5, None).unwrap();
        assert_eq!(reference.lines, vec![2, 3, 4, 5, 6]);
        assert!(reference.notes.is_empty(), "{:?}", reference.notes);

        // Shear with unit suffixes, in Hz, with a comment above the header.
        let shear = dir.write(
            "shear.csv",
            &format!(
                "# G from a parallel-plate rheometer\nf_Hz,G_storage_kPa,G_loss_kPa\n{}",
                rows(&|w, s, l| format!("{:e},{:e},{:e}", w / (2.0 * PI), s / 3e3, l / 3e3))
            ),
        );
        let t = read_with(&shear, 0.5, None).unwrap();
        assert_same_curve("shear.csv", &t, &reference);
        assert_eq!(t.lines, vec![3, 4, 5, 6, 7]);
        assert!(
            t.notes
                .iter()
                .any(|n| n.contains("ν = 0.5") && n.contains("[substrate] poisson")),
            "{:?}",
            t.notes
        );

        // One temperature in a T column, the sweep running downwards.
        let mut text = String::from("T,omega,E_storage,E_loss\n");
        for &w in OMEGAS.iter().rev() {
            let (s, l) = sls(w);
            text.push_str(&format!("23,{w:e},{s:e},{l:e}\n"));
        }
        let one_t = dir.write("one_t.csv", &text);
        let t = read_with(&one_t, 0.5, None).unwrap();
        assert_same_curve("one_t.csv", &t, &reference);
        assert_eq!(t.lines, vec![6, 5, 4, 3, 2]);
        assert!(
            t.notes.iter().any(|n| n.contains("all points at 23 °C")),
            "{:?}",
            t.notes
        );

        // TRIOS: shear from the torque variable, one isotherm.
        let trios = dir.write("sweep.txt", &trios_shear(&[20.0]));
        let t = read_with(&trios, 0.5, None).unwrap();
        assert_same_curve("sweep.txt", &t, &reference);
        let mut data_lines: Vec<usize> = trios_shear(&[20.0])
            .lines()
            .enumerate()
            .filter(|(_, l)| l.starts_with("Data point"))
            .map(|(i, _)| i + 1)
            .collect();
        data_lines.reverse();
        assert_eq!(t.lines, data_lines);
        // Shear from the torque variable, said in the scene's words.
        assert!(
            t.notes.iter().any(|n| n.contains("shear")
                && n.contains("Oscillation torque")
                && n.contains("[material] modulus = \"young\"")),
            "{:?}",
            t.notes
        );
        // Neither torque nor force nor a known instrument: the file cannot
        // say, and the error names the scene's key.
        let unknown = trios_shear(&[20.0])
            .replace("AresG2", "Mystery 9000")
            .replace("Oscillation torque", "Displacement");
        let m = format!(
            "{:#}",
            read_with(&dir.write("unknown.txt", &unknown), 0.5, None).unwrap_err()
        );
        assert!(
            m.contains("unknown.txt") && m.contains("[material] modulus = \"shear\""),
            "{m}"
        );
        // The override reads the same file as Young's moduli (3× less).
        let t = read_with(&trios, 0.5, Some(ModulusKind::Young)).unwrap();
        assert!(relative(3.0 * t.storage[0], reference.storage[0]) < 1e-12);

        // ν other than ½ for shear: E = 2(1 + ν) G.
        let t = read_with(&shear, 0.3, None).unwrap();
        assert!(relative(t.loss[2], reference.loss[2] * 2.6 / 3.0) < 1e-12);
    }

    #[test]
    fn the_header_decides_the_reader() {
        for (header, plain) in [
            ("omega,E_storage,E_loss", true),
            ("f,E_loss,E_storage,tan_delta", true),
            // A fit's modulus.csv.
            (
                "omega,E_storage,E_loss,tan_delta,abs_E,E_storage_sigma,E_loss_sigma",
                true,
            ),
            // Incomplete or misspelt plain tables keep the plain messages.
            ("omega,E_storage", true),
            ("w,E_storage,E_loss", true),
            ("omega,f,E_storage,E_loss", true),
            ("omega,E_storage,E_loss,T", false),
            ("T_K,omega,E_storage,E_loss", false),
            ("f,G_storage,G_loss", false),
            ("omega_rad_s,E_storage,E_loss", false),
            ("omega,E_storage_MPa,E_loss_MPa", false),
            ("f_rad_s,E_storage,E_loss", false),
            ("[Version]", false),
            ("freq,storage,loss", false),
        ] {
            assert_eq!(
                is_plain(&format!("# c\n{header}\n1,2,3\n")),
                plain,
                "{header:?}"
            );
        }
        // No header at all: the plain reader's "empty".
        assert!(is_plain("") && is_plain("# nothing\n") && is_plain("\n\n"));
    }

    #[test]
    fn poisson_matters_only_for_shear_moduli() {
        let dir = TempDir::new("poisson");
        let shear = dir.write("g.csv", "omega,G_storage,G_loss\n1,1e6,1e5\n10,2e6,2e5\n");
        let m = format!("{:#}", read_with(&shear, 0.7, None).unwrap_err());
        assert!(
            m.contains("g.csv") && m.contains("[substrate] poisson") && m.contains("0.7"),
            "{m}"
        );
        let young = dir.write(
            "e.csv",
            "omega,E_storage_MPa,E_loss_MPa\n1,1,0.1\n10,2,0.2\n",
        );
        let t = read_with(&young, 0.7, None).unwrap();
        assert_eq!(t.storage, vec![1e6, 2e6]);
    }

    #[test]
    fn several_temperatures_are_refused_naming_them() {
        let dir = TempDir::new("isotherms");
        let mut text = String::from("T_C,omega,E_storage,E_loss\n");
        for (t, w) in [
            (20.0, 1.0),
            (20.2, 10.0),
            (40.0, 1.0),
            (40.0, 10.0),
            (60.0, 1.0),
        ] {
            let (s, l) = sls(w);
            text.push_str(&format!("{t},{w},{s:e},{l:e}\n"));
        }
        let path = dir.write("isotherms.csv", &text);
        let m = format!("{:#}", read_with(&path, 0.5, None).unwrap_err());
        for fragment in [
            "isotherms.csv",
            "3 temperatures",
            "20.1 °C (2 point(s), lines 2–3)",
            "40 °C (2 point(s), lines 4–5)",
            "60 °C (1 point(s), lines 6–6)",
            "[material] model = \"dma\"",
            "rollfit master",
        ] {
            assert!(m.contains(fragment), "{fragment:?} not in {m}");
        }
        // The shifted points of `rollfit master`: its modulus.csv is meant.
        let path = dir.write(
            "master.csv",
            "omega,E_storage,E_loss,tan_delta,T,omega_measured\n\
             1,2e6,2e5,0.1,20,1\n2,2e6,2e5,0.1,40,20\n",
        );
        let m = format!("{:#}", read_with(&path, 0.5, None).unwrap_err());
        assert!(
            m.contains("2 temperatures") && m.contains("modulus.csv"),
            "{m}"
        );
        // The same in a TRIOS export, temperatures from the Temperature
        // variable.
        let path = dir.write("isotherms.txt", &trios_shear(&[20.0, 40.0]));
        let m = format!("{:#}", read_with(&path, 0.5, None).unwrap_err());
        assert!(
            m.contains("2 temperatures: 20 °C") && m.contains("40 °C"),
            "{m}"
        );
    }

    #[test]
    fn a_repeated_frequency_is_refused_naming_both_lines() {
        let dir = TempDir::new("repeated");
        let path = dir.write(
            "g.csv",
            "omega,G_storage,G_loss\n10,2e6,2e5\n1,1e6,1e5\n# again\n10,2.1e6,2.2e5\n",
        );
        let m = format!("{:#}", read_with(&path, 0.5, None).unwrap_err());
        assert!(
            m.contains("g.csv, lines 2 and 5") && m.contains("ω = 10"),
            "{m}"
        );
        // The plain reader as before: the second line, in file order.
        let path = dir.write("e.csv", "omega,E_storage,E_loss\n1,2e6,1e5\n1,2e6,2e5\n");
        let m = format!("{:#}", read_with(&path, 0.5, None).unwrap_err());
        assert!(m.contains("line 3") && m.contains("line 2"), "{m}");
    }

    #[test]
    fn a_point_without_loss_is_dropped_with_its_line() {
        let dir = TempDir::new("dropped");
        let path = dir.write(
            "g.csv",
            "omega,G_storage_MPa,G_loss_MPa\n1,1,0.1\n10,2,-0.03\n100,3,0.4\n",
        );
        let t = read_with(&path, 0.5, None).unwrap();
        assert_eq!(t.omega, vec![1.0, 100.0]);
        assert_eq!(t.lines, vec![2, 4]);
        assert!(
            t.notes
                .iter()
                .any(|n| n.contains("line 3") && n.contains("dropped")),
            "{:?}",
            t.notes
        );
        // Too few left to interpolate.
        let path = dir.write("one.csv", "omega,G_storage,G_loss\n1,1e6,1e5\n10,2e6,0\n");
        let m = format!("{:#}", read_with(&path, 0.5, None).unwrap_err());
        assert!(m.contains("1 usable data row"), "{m}");
    }

    #[test]
    fn dma_errors_name_the_table_and_line() {
        let dir = TempDir::new("errors");
        let path = dir.write("g.csv", "omega,G_storage,G_loss\n1,1e6,1e5\n10,abc,2e5\n");
        let m = format!("{:#}", read_with(&path, 0.5, None).unwrap_err());
        assert!(
            m.starts_with("modulus table ") && m.contains("g.csv, line 3") && m.contains("abc"),
            "{m}"
        );
        let m = format!(
            "{:#}",
            read_with(&dir.0.join("absent.csv"), 0.5, None).unwrap_err()
        );
        assert!(m.contains("cannot read modulus table"), "{m}");
    }

    // ------------------------------------------------- the contact map

    /// A broad rubber: Prony series of Young's modulus, E′, E″ in Pa.
    fn broad_rubber(omega: f64) -> (f64, f64) {
        let e0 = 3e6;
        let terms = [
            (1e-8, 5e8),
            (1e-7, 4e8),
            (1e-6, 3e8),
            (1e-5, 2e8),
            (1e-4, 1e8),
            (1e-3, 4e7),
            (1e-2, 1.5e7),
            (1e-1, 5e6),
        ];
        terms.iter().fold((e0, 0.0), |(s, l), &(tau, h)| {
            let x = omega * tau;
            let d = 1.0 + x * x;
            (s + h * x * x / d, l + h * x / d)
        })
    }

    /// The file lines of the row pairs an explanation lists
    /// ("  line A → line B: …").
    fn listed_pairs(text: &str) -> Vec<(usize, usize)> {
        text.lines()
            .filter_map(|l| {
                let rest = l.strip_prefix("  line ")?;
                let (a, rest) = rest.split_once(" → line ")?;
                let (b, _) = rest.split_once(':')?;
                Some((a.parse().ok()?, b.parse().ok()?))
            })
            .collect()
    }

    #[test]
    fn noisy_overlapping_isotherms_fail_the_contact_map_at_lines_the_explanation_names() {
        use rand::SeedableRng;
        use rand_chacha::ChaCha8Rng;
        use rand_distr::{Distribution, StandardNormal};
        use rollfit_model::{ContactSize, Geometry, Scene, Shape, Substrate, TabulatedModulus};

        // Nine isotherms of 0.1 … 100 rad/s, 5 points a decade, 10 K apart,
        // shifted by WLF (each overlaps its neighbours by a decade or
        // more), with 4 % scatter in E′ and E″: concatenated and sorted,
        // as a user builds a "master curve" by hand.
        let mut rng = ChaCha8Rng::seed_from_u64(20240611);
        let mut rows = Vec::new();
        for t in (-3..=5).map(|k| 10.0 * f64::from(k)) {
            let log_a_t = -8.86 * (t - 20.0) / (101.6 + t - 20.0);
            for k in 0..16 {
                let omega = 10f64.powf(-1.0 + f64::from(k) / 5.0 + log_a_t);
                let (s, l) = broad_rubber(omega);
                let z1: f64 = StandardNormal.sample(&mut rng);
                let z2: f64 = StandardNormal.sample(&mut rng);
                rows.push((omega, s * (1.0 + 0.04 * z1), l * (1.0 + 0.04 * z2)));
            }
        }
        rows.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut text =
            String::from("# nine isotherms, shifted and sorted\nomega,E_storage,E_loss\n");
        for (w, s, l) in &rows {
            text.push_str(&format!("{w:e},{s:e},{l:e}\n"));
        }
        let dir = TempDir::new("contact-map");
        let path = dir.write("master.csv", &text);
        let table = read_with(&path, 0.5, None).unwrap();
        assert_eq!(table.lines[0], 3);

        // The model refuses it, naming a frequency.
        let scene = Scene::new(
            Geometry {
                shape: Shape::Sphere,
                radius: 5e-3,
                load: 10.0,
            },
            Substrate {
                poisson: 0.5,
                film_thickness: None,
            },
            ContactSize::Dynamic,
            TabulatedModulus::new(
                table.omega.clone(),
                table.storage.clone(),
                table.loss.clone(),
            )
            .unwrap(),
        )
        .unwrap();
        let speeds: Vec<f64> = (0..=16)
            .map(|k| 10f64.powf(-8.0 + 0.5 * f64::from(k)))
            .collect();
        let error = scene.friction_sweep(&speeds).unwrap_err();
        let rollfit_model::ModelError::ContactMapNotIncreasing { omega, exponent } = error else {
            panic!("{error}")
        };
        assert_eq!(exponent, 3.0);

        let explained = explain_contact_map(&table, &path, omega, 3.0);
        // The rows bracketing ω.
        let k = table.omega.partition_point(|&w| w <= omega);
        assert!(0 < k && k < table.omega.len(), "{omega} outside the table");
        assert!(
            explained.contains(&format!(
                "between line {} (ω = {:.3e} rad/s",
                table.lines[k - 1],
                table.omega[k - 1]
            )) && explained.contains(&format!("and line {} (", table.lines[k])),
            "{explained}"
        );
        // The steep pairs: neighbours in the table, |E*| rising faster than
        // ω³ between them, within a decade of ω; the five nearest, in the
        // table's order.
        let abs = |i: usize| table.storage[i].hypot(table.loss[i]);
        let slope =
            |i: usize| (abs(i + 1) / abs(i)).ln() / (table.omega[i + 1] / table.omega[i]).ln();
        let distance = |i: usize| {
            let (lo, hi) = (table.omega[i].ln(), table.omega[i + 1].ln());
            (lo - omega.ln()).max(omega.ln() - hi).max(0.0)
        };
        let mut expected: Vec<usize> = (0..table.omega.len() - 1)
            .filter(|&i| slope(i) > 3.0 && distance(i) <= 10f64.ln())
            .collect();
        expected.sort_by(|&a, &b| distance(a).total_cmp(&distance(b)));
        assert!(!expected.is_empty(), "no steep pair near ω = {omega}");
        expected.truncate(5);
        expected.sort_unstable();
        let expected: Vec<(usize, usize)> = expected
            .iter()
            .map(|&i| (table.lines[i], table.lines[i + 1]))
            .collect();
        assert_eq!(listed_pairs(&explained), expected, "{explained}");
        // In this file (sorted, one header and one comment line) row i is
        // on line i + 3: the pairs are consecutive lines.
        assert!(expected.iter().all(|&(a, b)| b == a + 1));
        assert!(
            explained.contains("Smooth or bin the table")
                && explained.contains("[material] model = \"dma\""),
            "{explained}"
        );
    }

    #[test]
    fn the_explanation_places_any_frequency() {
        let table = ModulusTable {
            omega: vec![1.0, 2.0, 4.0, 8.0],
            storage: vec![1e6, 1e6, 1.2e6, 1.3e6],
            loss: vec![1e5, 1e5, 1e5, 1e5],
            lines: vec![2, 3, 5, 6],
            notes: Vec::new(),
        };
        let path = Path::new("t.csv");
        let text = explain_contact_map(&table, path, 0.5, 3.0);
        assert!(
            text.contains("below the first row, line 2 (ω = 1.000e0"),
            "{text}"
        );
        let text = explain_contact_map(&table, path, 9.0, 3.0);
        assert!(text.contains("above the last row, line 6"), "{text}");
        let text = explain_contact_map(&table, path, 2.0, 3.0);
        assert!(text.contains("at line 3 (ω = 2.000e0"), "{text}");
        // Nothing steep between rows: the interpolant is blamed, the
        // steepest rows nearby listed.
        let text = explain_contact_map(&table, path, 3.0, 3.0);
        assert!(
            text.contains("between line 3")
                && text.contains("and line 5")
                && text.contains("No neighbouring rows")
                && text.contains("  line 3 → line 5:"),
            "{text}"
        );
        // A cylinder's n = 2.
        let steep = ModulusTable {
            storage: vec![1e6, 1e6, 5e6, 5e6],
            ..table
        };
        let text = explain_contact_map(&steep, path, 3.0, 2.0);
        assert!(
            text.contains("faster than ω^2") && listed_pairs(&text) == vec![(3, 5)],
            "{text}"
        );
    }
}
