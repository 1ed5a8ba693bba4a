//! The batch manifest of `rollfit batch` (TOML; docs/ARCHITECTURE.md,
//! "Contract", "Commands", and "Data flow", `batch`): which fits to run.
//!
//! ```toml
//! [defaults]              # optional: the settings below
//! starts = 1
//! [[entry]]
//! name = "hn-rubber"      # unique, [A-Za-z0-9._-]+: the result folder
//! scene = "hn-rubber.toml"
//! data = "hn-rubber.csv"
//! # sheet = "Run 1"     # optional: the sheet of a workbook data file
//! # dma = "dma.csv"     # optional: a joint fit with these DMA isotherms
//! # optional: method, lambda, seed, starts, terms, physics, dma_sigma,
//! # friction_factor
//! ```
//!
//! Paths are relative to the manifest's folder: `scene`, `data` and `dma`
//! (an entry's own, else `[defaults]`'s, the DMA file of a joint fit,
//! which overrides the scene's `[fit] dma`). The settings are those of the
//! `fit` flags (`--method`, `--lambda`, `--seed`, `--starts`, `--terms`,
//! `--physics`, `--dma-sigma`, `--friction-factor`), spelled as in a
//! scene's `[fit]` and read by the same parser,
//! [`FitSettings::set`] (through the scene reader's `fit_settings`):
//! names and `"auto"` as strings, numbers as numbers (or as strings, e.g.
//! `terms = "2/decade"`).
//!
//! Everything is checked before a fit runs: TOML syntax, unknown keys and
//! bad setting values (syntax and range, [`FitSettings::check`]) while
//! deserializing (toml then points at the line),
//! then what serde cannot see — missing keys, names, duplicates, files that
//! do not exist. Every message names the entry (by name, else by its
//! position) and its line; [`load`] puts the manifest's path before it.
//! Only the
//! contents of the scene and data files are left to the fits themselves: a
//! broken scene fails its own entry, not the batch.

use std::fmt;
use std::ops::Range;
use std::path::{Path, PathBuf};

use rollfit_fit::FitSettings;
use serde::Deserialize;
use serde::de::{Deserializer, MapAccess, Visitor};
use toml::Spanned;

use crate::error::manifest::problem_list;
use crate::error::{EntryProblem, EntryRef, IoError, TomlPlace};
use crate::scene::fit_settings::{Key, TableSettings, join};

/// The settings a manifest takes: those of the `fit` flags.
const SETTINGS: [&str; 8] = [
    "method",
    "lambda",
    "seed",
    "starts",
    "terms",
    "physics",
    "dma_sigma",
    "friction_factor",
];

/// The keys of `[defaults]`: the DMA file, then the settings.
const DEFAULTS_KEYS: [&str; 9] = join(["dma"], SETTINGS);

/// The keys of an `[[entry]]`: its own, then the settings.
const ENTRY_KEYS: [&str; 13] = join(["name", "scene", "data", "sheet", "dma"], SETTINGS);

/// A checked manifest.
#[derive(Debug, Clone)]
pub struct Manifest {
    /// `[defaults]` (all unset without the table).
    pub defaults: FitSettings,
    /// The entries in file order.
    pub entries: Vec<Entry>,
}

/// One fit of the batch.
#[derive(Debug, Clone)]
pub struct Entry {
    /// Position in the manifest, counting from 0 (what `--shard` divides).
    pub index: usize,
    /// Unique name: the result folder.
    pub name: String,
    /// The scene file, resolved against the manifest's folder.
    pub scene: PathBuf,
    /// The data file, resolved against the manifest's folder.
    pub data: PathBuf,
    /// The sheet of a workbook data file (None: the first).
    pub sheet: Option<String>,
    /// The DMA file of a joint fit (the entry's `dma`, else `[defaults]`'s),
    /// resolved against the manifest's folder; None: the scene's `[fit]
    /// dma`, if any.
    pub dma: Option<PathBuf>,
    /// The entry's own settings (over the defaults and the flags).
    pub settings: FitSettings,
    /// The entry as messages name it: `entry "a" (1 of 3, line 4)`.
    pub place: EntryRef,
    /// The line of each key written in the entry's table.
    pub key_lines: Vec<(String, usize)>,
}

impl Entry {
    /// Where the entry sets `key`: `entry "a" (1 of 3, line 4), line 7`
    /// (without the second line when the key's cannot be found).
    pub fn key_place(&self, key: &str) -> String {
        match self.key_lines.iter().find(|(k, _)| k == key) {
            Some((_, line)) => format!("{}, line {line}", self.place),
            None => self.place.to_string(),
        }
    }
}

/// Reads and checks the manifest at `path`; every error names `path`.
pub fn load(path: &Path) -> Result<Manifest, IoError> {
    let text = crate::text_file::read_utf8(path, "manifest")?;
    let base = path.parent().unwrap_or(Path::new(""));
    check(&text, base).map_err(|e| {
        err!("manifest {}", path.display())
            .in_file(path)
            .caused_by(e)
    })
}

/// Parses and checks manifest text; `base` is the folder relative paths
/// start from.
pub fn parse(text: &str, base: &Path) -> Result<Manifest, IoError> {
    check(text, base)
}

/// [`parse`], with the manifest's own error.
fn check(text: &str, base: &Path) -> Result<Manifest, IoError> {
    let raw: RawManifest = toml::from_str(text).map_err(|error| {
        let place = error.span().and_then(|span| locate_entry(text, span.start));
        let place = place.map_or(String::new(), |p| format!("{p}: "));
        err!("{place}{}", error.to_string().trim_end())
    })?;
    let (defaults, default_dma) = raw.defaults.map(|d| (d.0, d.1)).unwrap_or_default();
    if raw.entry.is_empty() {
        return Err(err!(
            "no entries: list each fit as an [[entry]] with a name, a scene and a data file (see the \
         docs/user-guide.md, \"Batches\")"
        ));
    }
    let entries = check_entries(text, base, raw.entry, default_dma.as_ref())?;
    Ok(Manifest { defaults, entries })
}

/// The entries, checked: names, duplicates, files.
fn check_entries(
    text: &str,
    base: &Path,
    raw_entries: Vec<Spanned<RawEntry>>,
    default_dma: Option<&Spanned<String>>,
) -> Result<Vec<Entry>, IoError> {
    let total = raw_entries.len();
    let mut problems = Vec::new();
    let mut entries = Vec::new();
    // (lower-cased name, its entry) of the names seen so far.
    let mut seen: Vec<(String, EntryRef)> = Vec::new();
    for (index, spanned) in raw_entries.into_iter().enumerate() {
        let line = line_of(text, spanned.span().start);
        let mut raw_entry = spanned.into_inner();
        let name = raw_entry.name.as_ref().map(|n| n.get_ref().clone());
        let who = describe(index, total, name.as_deref(), line);
        let mut complete = true;
        match &name {
            None => {
                problems.push(EntryProblem::MissingName { entry: who.clone() });
                complete = false;
            }
            Some(name) => {
                if let Err(why) = check_name(name) {
                    problems.push(EntryProblem::BadName {
                        entry: who.clone(),
                        name: name.clone(),
                        why,
                    });
                    complete = false;
                } else {
                    let key = name.to_lowercase();
                    if let Some((_, first)) = seen.iter().find(|(k, _)| *k == key) {
                        problems.push(EntryProblem::DuplicateName {
                            entry: who.clone(),
                            first: first.clone(),
                            same: first.to_string().contains(&format!("{name:?}")),
                        });
                        complete = false;
                    } else {
                        seen.push((key, who.clone()));
                    }
                }
            }
        }
        let mut file = |key: &'static str, value: &Option<Spanned<String>>| match value {
            None => {
                problems.push(EntryProblem::MissingFile {
                    entry: who.clone(),
                    key,
                });
                None
            }
            Some(value) => {
                let path = base.join(value.get_ref());
                let at = line_of(text, value.span().start);
                if path.is_file() {
                    Some(path)
                } else {
                    problems.push(EntryProblem::NoSuchFile {
                        entry: who.clone(),
                        line: at,
                        key,
                        exists: path.exists(),
                        path,
                    });
                    None
                }
            }
        };
        let scene = file("scene", &raw_entry.scene);
        let data = file("data", &raw_entry.data);
        let dma = match raw_entry.dma.as_ref().or(default_dma) {
            Some(dma) => match file("dma", &Some(dma.clone())) {
                Some(path) => Some(path),
                None => {
                    complete = false;
                    None
                }
            },
            None => None,
        };
        if let (true, Some(name), Some(scene), Some(data)) = (complete, name, scene, data) {
            entries.push(Entry {
                index,
                name,
                scene,
                data,
                sheet: raw_entry.sheet.take(),
                dma,
                settings: std::mem::take(&mut raw_entry.settings),
                key_lines: key_lines(text, line),
                place: who,
            });
        }
    }
    if !problems.is_empty() {
        return Err(err!("{}", problem_list(&problems)));
    }
    Ok(entries)
}

/// A name that can be a result folder on any system: [A-Za-z0-9._-]+, not
/// starting with a dot (hidden; "." and ".." are not folders of their own),
/// and not the name of a summary file.
fn check_name(name: &str) -> Result<(), String> {
    if name.is_empty() {
        return Err("is empty".into());
    }
    if let Some(c) = name
        .chars()
        .find(|c| !(c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-')))
    {
        return Err(format!(
            "contains {c:?}: use letters A-Z, a-z, digits and '.', '_', '-' (the name is a folder)"
        ));
    }
    if name.starts_with('.') {
        return Err("starts with '.': the name is a folder and must not be hidden".into());
    }
    if name.starts_with("summary") && name.ends_with(".csv") {
        return Err("is reserved for the batch summary files".into());
    }
    Ok(())
}

/// "entry "NAME" (K of N, line L)" or "entry K of N (line L)".
fn describe(index: usize, total: usize, name: Option<&str>, line: usize) -> EntryRef {
    EntryRef {
        index,
        total,
        name: name.map(str::to_string),
        line,
    }
}

/// The 1-based line of byte `offset`.
/// The `key = value` lines of the table whose header is on line `header`
/// (from 1), up to the next header: (key, line).
fn key_lines(text: &str, header: usize) -> Vec<(String, usize)> {
    text.lines()
        .enumerate()
        .skip(header)
        .map(|(i, l)| (i + 1, l.trim()))
        .take_while(|(_, l)| !l.starts_with('['))
        .filter_map(|(line, l)| {
            let (key, _) = l.split_once('=')?;
            let key = key.trim().trim_matches('"');
            (!key.is_empty() && !key.starts_with('#')).then(|| (key.to_string(), line))
        })
        .collect()
}

fn line_of(text: &str, offset: usize) -> usize {
    let offset = offset.min(text.len());
    text.as_bytes()[..offset]
        .iter()
        .filter(|b| **b == b'\n')
        .count()
        + 1
}

/// The entry a toml error at byte `offset` lies in, described for a
/// message; None outside every entry.
fn locate_entry(text: &str, offset: usize) -> Option<TomlPlace> {
    #[derive(Deserialize)]
    struct Outline {
        defaults: Option<Spanned<toml::Value>>,
        #[serde(default)]
        entry: Vec<Spanned<toml::Value>>,
    }
    match toml::from_str::<Outline>(text) {
        Ok(outline) => {
            if outline
                .defaults
                .is_some_and(|d| contains(&d.span(), offset))
            {
                return Some(TomlPlace::Defaults);
            }
            let total = outline.entry.len();
            let (index, entry) = outline
                .entry
                .iter()
                .enumerate()
                .find(|(_, e)| contains(&e.span(), offset))?;
            let name = entry.get_ref().get("name").and_then(toml::Value::as_str);
            Some(TomlPlace::Entry(describe(
                index,
                total,
                name,
                line_of(text, entry.span().start),
            )))
        }
        // A syntax error: the [[entry]] header above it, by its number.
        Err(_) => {
            let mut start = 0;
            let mut current = None;
            let mut count = 0;
            for (i, line) in text.split_inclusive('\n').enumerate() {
                if start > offset {
                    break;
                }
                let trimmed = line.trim();
                if let Some(header) = trimmed
                    .strip_prefix("[[")
                    .and_then(|t| t.split("]]").next())
                {
                    count += 1;
                    current = (header.trim() == "entry").then_some((count, i + 1));
                } else if trimmed.starts_with('[') {
                    current = None;
                }
                start += line.len();
            }
            current.map(|(number, line)| TomlPlace::EntryHeader { number, line })
        }
    }
}

fn contains(span: &Range<usize>, offset: usize) -> bool {
    span.start <= offset && offset < span.end
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawManifest {
    defaults: Option<Defaults>,
    #[serde(default)]
    entry: Vec<Spanned<RawEntry>>,
}

/// `[defaults]`: the settings and the DMA file of every entry without one.
struct Defaults(FitSettings, Option<Spanned<String>>);

impl<'de> Deserialize<'de> for Defaults {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct DefaultsVisitor;
        impl<'de> Visitor<'de> for DefaultsVisitor {
            type Value = Defaults;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("struct RawSettings")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Defaults, A::Error> {
                let mut settings = TableSettings::new("");
                let mut dma = None;
                while let Some(key) = map.next_key_seed(Key(&DEFAULTS_KEYS))? {
                    match key {
                        "dma" => dma = Some(map.next_value()?),
                        setting => map.next_value_seed(settings.value_of(setting))?,
                    }
                }
                Ok(Defaults(settings.finish(), dma))
            }
        }
        deserializer.deserialize_map(DefaultsVisitor)
    }
}

/// An `[[entry]]` as written: its own keys and its settings, each setting
/// parsed and range-checked as it is read.
#[derive(Default)]
struct RawEntry {
    name: Option<Spanned<String>>,
    scene: Option<Spanned<String>>,
    data: Option<Spanned<String>>,
    sheet: Option<String>,
    dma: Option<Spanned<String>>,
    settings: FitSettings,
}

impl<'de> Deserialize<'de> for RawEntry {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct EntryVisitor;
        impl<'de> Visitor<'de> for EntryVisitor {
            type Value = RawEntry;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("struct RawEntry")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<RawEntry, A::Error> {
                let mut entry = RawEntry::default();
                let mut settings = TableSettings::new("");
                while let Some(key) = map.next_key_seed(Key(&ENTRY_KEYS))? {
                    match key {
                        "name" => entry.name = Some(map.next_value()?),
                        "scene" => entry.scene = Some(map.next_value()?),
                        "data" => entry.data = Some(map.next_value()?),
                        "sheet" => entry.sheet = Some(map.next_value()?),
                        "dma" => entry.dma = Some(map.next_value()?),
                        setting => map.next_value_seed(settings.value_of(setting))?,
                    }
                }
                entry.settings = settings.finish();
                Ok(entry)
            }
        }
        deserializer.deserialize_map(EntryVisitor)
    }
}

#[cfg(test)]
mod tests {
    use rollfit_fit::{FitError, Lambda, SettingValue, TermRule};

    use super::*;

    #[test]
    fn names() {
        for good in ["a", "hn-rubber", "T_20.5", "A-1_b.c"] {
            assert!(check_name(good).is_ok(), "{good}");
        }
        for bad in [
            "",
            "a b",
            "a/b",
            "..",
            ".",
            ".x",
            "ä",
            "summary.csv",
            "summary-0-of-2.csv",
        ] {
            assert!(check_name(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn layers_and_checks() {
        let mut top = FitSettings::default();
        top.set("lambda", SettingValue::Number(1.0)).unwrap();
        let mut below = FitSettings::default();
        below.set("lambda", SettingValue::Text("auto")).unwrap();
        below.set("starts", SettingValue::Integer(2)).unwrap();
        let both = top.over(&below);
        assert_eq!(both.lambda, Some(Lambda::Fixed(1.0)));
        assert_eq!(both.starts, Some(2));
        assert_eq!(both.method, None);
        assert!(both.check().is_ok());
        let mut zero = FitSettings::default();
        zero.set("starts", SettingValue::Integer(0)).unwrap();
        assert!(matches!(
            zero.check(),
            Err(FitError::InvalidSetting { key, .. }) if key == "starts"
        ));
    }

    /// A manifest's settings are read by the fit library's parser and
    /// checked as they are read: the message names the key and its line.
    #[test]
    fn settings_are_parsed_and_checked_where_written() {
        let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data");
        let entry =
            "[[entry]]\nname = \"a\"\nscene = \"hn-rubber.toml\"\ndata = \"hn-rubber.csv\"\n";
        let manifest = parse(
            &format!("[defaults]\nterms = \"3/decade\"\nseed = \"4\"\n{entry}lambda = \"auto\"\n"),
            &base,
        )
        .unwrap();
        assert_eq!(manifest.defaults.terms, Some(TermRule::PerDecade(3.0)));
        assert_eq!(manifest.defaults.seed, Some(4));
        assert_eq!(manifest.entries[0].settings.lambda, Some(Lambda::Auto));
        for (setting, fragments) in [
            ("terms = \"x/decade\"", &["`terms`", "per decade"][..]),
            ("terms = 500", &["`terms`", "use 2 to 200"][..]),
            ("starts = true", &["`starts`", "whole number"][..]),
            ("lambda = nan", &["`lambda`", "finite"][..]),
            ("method = [1.0]", &["`method`", "expected text"][..]),
            (
                "physics = \"exakt\"",
                &["`physics`", "\"approximate\" or \"exact\""][..],
            ),
            ("physics = 1", &["`physics`", "expected text"][..]),
        ] {
            let err = crate::chain(&parse(&format!("{entry}{setting}\n"), &base).unwrap_err());
            assert!(err.contains("entry \"a\" (1 of 1, line 1)"), "{err}");
            assert!(err.contains("line 5"), "{err}");
            for fragment in fragments {
                assert!(err.contains(fragment), "{fragment:?} in {err}");
            }
        }
        // terms_per_decade is the scene's alias of terms; the manifest
        // takes the settings of the flags, spelled once.
        let err =
            crate::chain(&parse(&format!("{entry}terms_per_decade = 2\n"), &base).unwrap_err());
        assert!(err.contains("unknown field `terms_per_decade`"), "{err}");
    }

    /// `dma` (an entry's own, else `[defaults]`'s) is resolved against the
    /// manifest's folder and must exist; the joint settings are settings.
    #[test]
    fn dma_of_an_entry_and_of_the_defaults() {
        let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data");
        let entry = |name: &str| {
            format!(
                "[[entry]]\nname = \"{name}\"\nscene = \"hn-rubber-tset.toml\"\n\
                 data = \"hn-rubber-tset.csv\"\n"
            )
        };
        let text = format!(
            "[defaults]\ndma = \"hn-rubber-dma-isotherms.csv\"\ndma_sigma = 0.02\n{}{}\
             dma = \"hn-rubber-dma.csv\"\nfriction_factor = \"free\"\n",
            entry("a"),
            entry("b")
        );
        let read = parse(&text, &base).unwrap();
        assert_eq!(
            read.entries[0].dma.as_deref(),
            Some(base.join("hn-rubber-dma-isotherms.csv").as_path())
        );
        assert_eq!(
            read.entries[1].dma.as_deref(),
            Some(base.join("hn-rubber-dma.csv").as_path())
        );
        assert_eq!(read.defaults.dma_sigma, Some(0.02));
        assert_eq!(
            read.entries[1].settings.friction_factor,
            Some(rollfit_fit::FrictionFactor::Free)
        );
        assert!(parse(&entry("c"), &base).unwrap().entries[0].dma.is_none());
        let err = crate::chain(
            &parse(&format!("{}dma = \"absent.csv\"\n", entry("a")), &base).unwrap_err(),
        );
        for fragment in [
            "entry \"a\"",
            "line 5",
            "dma file",
            "absent.csv",
            "does not exist",
        ] {
            assert!(err.contains(fragment), "{fragment:?} in {err}");
        }
        let err = crate::chain(
            &parse(
                &format!("{}friction_factor = \"kappa\"\n", entry("a")),
                &base,
            )
            .unwrap_err(),
        );
        assert!(
            err.contains("`friction_factor`") && err.contains("line 5"),
            "{err}"
        );
    }

    #[test]
    fn sheet_of_an_entry() {
        let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data");
        let text = "[[entry]]\nname = \"a\"\nscene = \"hn-rubber.toml\"\ndata = \"hn-rubber.csv\"\n\
                    sheet = \"Run 1\"\n[[entry]]\nname = \"b\"\nscene = \"hn-rubber.toml\"\n\
                    data = \"hn-rubber.csv\"\n";
        let manifest = parse(text, &base).unwrap();
        assert_eq!(manifest.entries[0].sheet.as_deref(), Some("Run 1"));
        assert_eq!(manifest.entries[1].sheet, None);
    }

    #[test]
    fn lines_and_entries() {
        let text = "[defaults]\nstarts = 1\n\n[[entry]]\nname = \"a\"\n[[entry]]\nname = \"b\"\n";
        assert_eq!(line_of(text, 0), 1);
        assert_eq!(line_of(text, text.find("name = \"b\"").unwrap()), 7);
        let b = text.find("\"b\"").unwrap();
        assert_eq!(
            locate_entry(text, b).map(|p| p.to_string()).as_deref(),
            Some("entry \"b\" (2 of 2, line 6)")
        );
        assert_eq!(
            locate_entry(text, 12).map(|p| p.to_string()).as_deref(),
            Some("[defaults]")
        );
        // A syntax error: the entry by its number.
        let broken = text.replace("\"b\"", "\"b");
        let at = broken.find("\"b").unwrap();
        assert_eq!(
            locate_entry(&broken, at).map(|p| p.to_string()).as_deref(),
            Some("entry 2 (line 6)")
        );
    }
}
