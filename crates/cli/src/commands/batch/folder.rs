//! A batch's folder: its lock, the names its record claims, and whether
//! an entry's existing result still answers the entry (its inputs are
//! those fit.json names, unmodified since).

use std::path::Path;

use rollfit_io::fit_dir::columns::FIT_JSON;
use rollfit_io::fit_dir::digest::Digest;
use rollfit_io::manifest::Entry;

use anyhow::Result;
use rollfit_io::output;

use super::{BATCH_LOCK, Shard, summary_name};

/// The names a batch claims in its folder's record: every entry's folder
/// and the summary; with shards, every shard's summary, so that shards
/// writing the record at once agree on it.
pub(super) fn recorded_names(entries: &[Entry], shard: Option<Shard>) -> Vec<String> {
    let mut names: Vec<String> = entries.iter().map(|e| e.name.clone()).collect();
    match shard {
        None => names.push(summary_name(None)),
        Some(s) => names.extend((0..s.count).map(|index| {
            summary_name(Some(Shard {
                index,
                count: s.count,
            }))
        })),
    }
    names
}

/// Why an entry's existing result no longer answers it: each input of the
/// entry (scene, data, DMA file) that is another file than the one its
/// fit.json names, or that was modified after the fit.json was written.
/// Empty: the result stands (an unreadable fit.json is reported by the
/// summary row).
pub(super) fn changed_inputs(entry: &Entry, folder: &Path) -> Vec<String> {
    let Ok(digest) = Digest::read(folder) else {
        return Vec::new();
    };
    let modified = |path: &Path| std::fs::metadata(path).and_then(|m| m.modified()).ok();
    let written = modified(&folder.join(FIT_JSON));
    let recorded = digest.inputs;
    let mut changed = Vec::new();
    for (key, now, was) in [
        ("scene", Some(entry.scene.as_path()), recorded.scene),
        ("data", Some(entry.data.as_path()), recorded.data),
        ("dma", entry.dma.as_deref(), recorded.dma),
    ] {
        let Some(now) = now else { continue };
        let now_text = now.display().to_string();
        match was {
            Some(was) if was != now_text => {
                changed.push(format!("{key} was {was}, is now {now_text}"));
            }
            None if key == "dma" => {
                changed.push(format!("dma {now_text} is new: the result is no joint fit"));
            }
            _ => {
                if let (Some(now_time), Some(written)) = (modified(now), written)
                    && now_time > written
                {
                    changed.push(format!(
                        "{key} {now_text} was modified after the result was written"
                    ));
                }
            }
        }
    }
    changed
}

/// Takes DIR's lock and removes what killed runs left. Two batches writing
/// one folder would mix their results: a whole batch holds the folder's
/// lock alone, the shards of one share it and each holds its own. Taking it
/// also proves the folder writable before the first fit.
pub(super) fn lock_and_clean(
    dir: &Path,
    shard: Option<Shard>,
    entries: &[Entry],
) -> Result<Vec<output::FolderLock>> {
    let locks = match shard {
        None => vec![output::FolderLock::take(dir, BATCH_LOCK, true)?],
        Some(s) => vec![
            output::FolderLock::take(dir, BATCH_LOCK, false)?,
            output::FolderLock::take(
                dir,
                &format!(".rollfit-batch-{}-of-{}.lock", s.index, s.count),
                true,
            )?,
        ],
    };
    // What killed runs left: staging folders beside the entries, and
    // temporary files inside them.
    output::remove_stale(dir);
    for entry in entries {
        output::remove_stale(&dir.join(&entry.name));
    }
    Ok(locks)
}
