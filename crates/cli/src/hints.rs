//! Hints for files given in the wrong place: a data table where
//! a scene belongs, a scene where data belong, a DMA file where a fit
//! folder belongs. The readers' own errors stay as they are (a TOML parse
//! error at line 1 is true of a CSV); a hint is put in front of them when
//! the files, by their names and first lines, look like what the other
//! argument wants. Only a failed read asks for a hint, so a correct
//! command never pays for one.

use std::io::Read;
use std::path::Path;

/// What a file given on the command line looks like.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Looks {
    /// A scene (or manifest): TOML.
    Toml,
    /// A table of numbers: measured data or a DMA file, text or workbook.
    Table,
    /// A folder (a fit's result).
    Folder,
    /// Neither, or not readable.
    Unknown,
}

/// Extensions of tables: the text forms the readers take and workbooks.
const TABLE_EXTENSIONS: [&str; 8] = ["csv", "tsv", "txt", "dat", "xlsx", "xlsm", "xls", "ods"];

/// How much of a file is read to judge it.
const PEEK: u64 = 4096;

/// What `path` looks like: a folder; else by its first lines when they
/// are text (a `[section]` or `key = value` line is TOML, a line of
/// delimited cells a table), else by its extension.
pub fn looks(path: &Path) -> Looks {
    if path.is_dir() {
        return Looks::Folder;
    }
    let mut head = Vec::new();
    // Only a regular file is opened: opening a FIFO blocks (the reader
    // has refused it already, io::input_file).
    if path.metadata().is_ok_and(|m| m.is_file())
        && let Ok(file) = std::fs::File::open(path)
    {
        let _ = file.take(PEEK).read_to_end(&mut head);
    }
    // A read cut inside a character is judged on the whole characters.
    let text = match std::str::from_utf8(&head) {
        Ok(text) => Some(text),
        Err(e) if e.error_len().is_none() => std::str::from_utf8(&head[..e.valid_up_to()]).ok(),
        Err(_) => None,
    };
    if let Some(kind) = text.and_then(looks_of_text) {
        return kind;
    }
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match extension.as_deref() {
        Some("toml") => Looks::Toml,
        Some(e) if TABLE_EXTENSIONS.contains(&e) => Looks::Table,
        _ => Looks::Unknown,
    }
}

/// TOML or a table by the first line that is neither blank nor a comment.
/// A partial last line (cut by [`PEEK`]) is judged too: a line is short.
fn looks_of_text(text: &str) -> Option<Looks> {
    let line = text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with('#'))?;
    if line.starts_with('[') && line.ends_with(']') {
        return Some(Looks::Toml);
    }
    if let Some((key, _)) = line.split_once('=')
        && !key.trim().is_empty()
        && !key.contains([',', ';', '\t'])
    {
        return Some(Looks::Toml);
    }
    line.contains([',', ';', '\t']).then_some(Looks::Table)
}

/// The hint for a scene at `scene` that could not be read, with the data
/// at `data`; `usage` shows the right order ("rollfit fit SCENE.toml
/// DATA.csv").
pub fn for_scene(scene: &Path, data: &Path, usage: &str) -> Option<String> {
    if looks(scene) != Looks::Table {
        return None;
    }
    Some(if looks(data) == Looks::Toml {
        format!(
            "the scene and the data look swapped ({} is a table, {} a scene): the scene comes \
             first: {usage}",
            scene.display(),
            data.display()
        )
    } else {
        format!(
            "{} looks like a data table, not a scene (TOML): the scene comes first: {usage}",
            scene.display()
        )
    })
}

/// The hint for data at `data` that could not be read: a scene given
/// where the data belong.
pub fn for_data(data: &Path, usage: &str) -> Option<String> {
    (looks(data) == Looks::Toml).then(|| {
        format!(
            "{} looks like a scene (TOML), not measured data: the data file comes second: {usage}",
            data.display()
        )
    })
}

/// The hint for a fit folder at `dir` that could not be read, with an
/// optional DMA file `dma` beside it (`compare`).
pub fn for_fit_folder(dir: &Path, dma: Option<&Path>, usage: &str) -> Option<String> {
    let swapped = dma.is_some_and(|d| looks(d) == Looks::Folder);
    match looks(dir) {
        Looks::Table if swapped => Some(format!(
            "the fit folder and the DMA file look swapped: the fit folder comes first: {usage}"
        )),
        Looks::Table | Looks::Toml => Some(format!(
            "{} is a file, not the folder `rollfit fit` wrote: {usage}",
            dir.display()
        )),
        Looks::Folder | Looks::Unknown => None,
    }
}

/// The hint for a DMA file at `dma` that could not be read: a scene or a
/// fit folder given in its place.
pub fn for_dma(dma: &Path, usage: &str) -> Option<String> {
    match looks(dma) {
        Looks::Toml => Some(format!(
            "{} looks like a scene (TOML), not a DMA file: {usage}",
            dma.display()
        )),
        Looks::Folder => Some(format!(
            "{} is a folder, not a DMA file: {usage}",
            dma.display()
        )),
        Looks::Table | Looks::Unknown => None,
    }
}

/// `result` with `hint` (if any) in front of its error.
pub fn with_hint<T>(
    result: anyhow::Result<T>,
    hint: impl FnOnce() -> Option<String>,
) -> anyhow::Result<T> {
    result.map_err(|error| match hint() {
        Some(hint) => error.context(hint),
        None => error,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn toml_and_tables_by_their_first_line() {
        let toml = "# a scene\n\n[geometry]\nshape = \"sphere\"\n";
        assert_eq!(looks_of_text(toml), Some(Looks::Toml));
        assert_eq!(looks_of_text("title = \"x\"\n"), Some(Looks::Toml));
        assert_eq!(looks_of_text("v,mu\n0.1,0.01\n"), Some(Looks::Table));
        assert_eq!(looks_of_text("v;mu\n0,1;0,01\n"), Some(Looks::Table));
        assert_eq!(looks_of_text("v\tmu\n"), Some(Looks::Table));
        // A header cell with `=` is still a table's.
        assert_eq!(looks_of_text("v,mu=f(v)\n"), Some(Looks::Table));
        assert_eq!(looks_of_text("hello\n"), None);
        assert_eq!(looks_of_text("\n# only comments\n"), None);
    }

    #[test]
    fn swapped_files_are_named() {
        let dir = std::env::temp_dir().join(format!("rollfit-hints-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let scene = dir.join("scene.toml");
        let data = dir.join("data.csv");
        std::fs::write(&scene, "[geometry]\nshape = \"sphere\"\n").unwrap();
        std::fs::write(&data, "v,mu\n0.1,0.01\n").unwrap();
        let usage = "rollfit fit SCENE.toml DATA.csv";
        let swapped = for_scene(&data, &scene, usage).unwrap();
        assert!(
            swapped.contains("look swapped") && swapped.ends_with(usage),
            "{swapped}"
        );
        // A table where the scene belongs, data not a scene: still said.
        let alone = for_scene(&data, &data, usage).unwrap();
        assert!(
            alone.contains("looks like a data table, not a scene"),
            "{alone}"
        );
        // A scene that fails for its own reasons gets no hint.
        assert_eq!(for_scene(&scene, &data, usage), None);
        assert!(
            for_data(&scene, usage)
                .unwrap()
                .contains("looks like a scene (TOML)")
        );
        assert_eq!(for_data(&data, usage), None);
        let compare = "rollfit compare DIR DMA.csv";
        let swapped = for_fit_folder(&data, Some(&dir), compare).unwrap();
        assert!(swapped.contains("look swapped"), "{swapped}");
        assert_eq!(for_fit_folder(&dir, Some(&data), compare), None);
        assert!(for_dma(&scene, "rollfit master DMA.csv").is_some());
        assert_eq!(for_dma(&data, "rollfit master DMA.csv"), None);
        // A workbook is judged by its extension.
        let book = dir.join("data.xlsx");
        std::fs::write(&book, b"PK\x03\x04\xd0\xcf binary").unwrap();
        assert_eq!(looks(&book), Looks::Table);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
