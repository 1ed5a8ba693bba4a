//! Reading an input file whole, bounded: the one way every reader (data,
//! DMA files, tables, scenes, manifests, fit folders) gets a file's bytes.
//!
//! Every reader parses a file held in memory, so a file without end
//! (/dev/zero) or a huge one would grow the process until the machine
//! fails. So the file is first looked at (`std::fs::metadata`, which
//! follows a symbolic link to what it names): a regular file above the
//! limit is refused unopened, as is anything but a regular file or a pipe
//! (devices, sockets, folders). A pipe — `rollfit fit <(make-scene)
//! data.csv`, a named pipe, or `-` for the standard input — is read as it
//! comes; it cannot state its size, so the read, like every read, stops
//! one byte past the limit: a pipe, a file that grows while it is read,
//! or one that states a size it does not hold (/proc) is refused there
//! instead of read on. A pipe can be read once; its bytes are kept for a
//! second read of the same name within the run.
//!
//! The limit is [`DEFAULT_LIMIT`] (1 GiB, far above any measurement or DMA
//! export seen: a 60-isotherm DMA CSV is 3.5 MB), or what the variable
//! [`LIMIT_VARIABLE`] says: bytes, or a number with K, M, G or T (powers
//! of 1024). It is read at each file, so a test or a script can set it
//! for one run (docs/ARCHITECTURE.md, "Contract", "Input files").

use std::fs::FileType as SystemFileType;
use std::io::{IsTerminal, Read};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use crate::error::IoError;

/// The environment variable that sets the size limit of an input file.
pub const LIMIT_VARIABLE: &str = "ROLLFIT_MAX_INPUT_BYTES";

/// The size limit of an input file without [`LIMIT_VARIABLE`]: 1 GiB.
pub const DEFAULT_LIMIT: u64 = 1 << 30;

/// What was found where a regular file was wanted.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileType {
    Folder,
    Fifo,
    CharacterDevice,
    BlockDevice,
    Socket,
    /// The standard input when it is a terminal or a device.
    Terminal,
    /// Anything else the system knows that is no regular file.
    Other,
}

/// The refusal of a file that is `$what`: no regular file, so its size
/// cannot be known before it is read.
macro_rules! sizeless {
    ($what:literal) => {
        concat!(
            "is ",
            $what,
            ", not a regular file; rollfit reads files whose size it can know — save the data \
             to a file first"
        )
    };
}

impl FileType {
    /// The message's tail: what the file is, and what to do.
    pub(crate) fn refusal(self) -> &'static str {
        match self {
            FileType::Folder => "is a folder, not a file; name a file inside it",
            FileType::Fifo => sizeless!("a FIFO (named pipe)"),
            FileType::CharacterDevice => sizeless!("a character device (such as /dev/zero)"),
            FileType::BlockDevice => sizeless!("a block device"),
            FileType::Socket => sizeless!("a socket"),
            FileType::Terminal => {
                "is a terminal or a device; `-` reads a file or a command's output piped into \
                 rollfit (`rollfit fit - data.csv < scene.toml`)"
            }
            FileType::Other => sizeless!("something else"),
        }
    }

    /// What `file_type` is, `None` for a regular file.
    fn of(file_type: SystemFileType) -> Option<FileType> {
        if file_type.is_file() {
            return None;
        }
        if file_type.is_dir() {
            return Some(FileType::Folder);
        }
        #[cfg(unix)]
        {
            use std::os::unix::fs::FileTypeExt;
            if file_type.is_fifo() {
                return Some(FileType::Fifo);
            }
            if file_type.is_char_device() {
                return Some(FileType::CharacterDevice);
            }
            if file_type.is_block_device() {
                return Some(FileType::BlockDevice);
            }
            if file_type.is_socket() {
                return Some(FileType::Socket);
            }
        }
        Some(FileType::Other)
    }
}

/// The command-line name of the standard input: `-` reads the input
/// piped into rollfit.
pub const STANDARD_INPUT: &str = "-";

/// The bytes of the input file at `path`, a `kind` of file ("data file",
/// "DMA file"), read whole within the size limit (the module doc).
/// `unreadable` makes the system's error (no such file, no permission)
/// the reader's own, so that each keeps its wording.
pub fn read_input(
    path: &Path,
    kind: &'static str,
    unreadable: impl Fn(std::io::Error) -> IoError,
) -> Result<Vec<u8>, IoError> {
    let limit = limit().map_err(|value| {
        err!(
            "cannot read {kind} {}: {LIMIT_VARIABLE} = {value:?} is not a size: give bytes \
         (1000000) or a number with K, M, G or T (500M, 2G; powers of 1024), at least 1",
            path.display()
        )
    })?;
    let too_large = |size| {
        let kind = &kind;
        let path = &path.to_path_buf();
        let size = &size;
        let limit = &limit;
        err!(
            "{kind} {} {}; set {LIMIT_VARIABLE} to raise it (e.g. {LIMIT_VARIABLE}=4G)",
            path.display(),
            match size {
                Some(size) => format!(
                    "is {}, more than the limit of {} on an input file",
                    size_text(*size),
                    size_text(*limit)
                ),
                None => format!(
                    "holds more than the limit of {} on an input file (more than its stated size: it \
                 grew while read, or is no ordinary file)",
                    size_text(*limit)
                ),
            }
        )
    };
    let not_regular = |found: FileType| err!("{kind} {} {}", path.display(), found.refusal());
    if path.as_os_str() == STANDARD_INPUT {
        return streamed(path, || {
            let stdin = std::io::stdin();
            let metadata = standard_input_metadata().map_err(&unreadable)?;
            match FileType::of(metadata.file_type()) {
                None if metadata.len() > limit => Err(too_large(Some(metadata.len()))),
                None | Some(FileType::Fifo) if !stdin.is_terminal() => {
                    read_bounded(stdin.lock(), limit, &too_large, &unreadable, 0)
                }
                // A terminal would wait for typing; a device may never end.
                _ => Err(not_regular(FileType::Terminal)),
            }
        });
    }
    // Looked at before opening: what is neither a file nor a pipe is
    // refused unopened.
    let metadata = std::fs::metadata(path).map_err(&unreadable)?;
    match FileType::of(metadata.file_type()) {
        None => {}
        // A pipe (`<(make-scene)`, a named pipe) is read as it comes, up to
        // the limit; opening it waits for its writer.
        Some(FileType::Fifo) => {
            return streamed(path, || {
                let file = std::fs::File::open(path).map_err(&unreadable)?;
                read_bounded(file, limit, &too_large, &unreadable, 0)
            });
        }
        Some(found) => return Err(not_regular(found)),
    }
    if metadata.len() > limit {
        return Err(too_large(Some(metadata.len())));
    }
    let file = std::fs::File::open(path).map_err(&unreadable)?;
    // The stated size reserves the memory once; a wrong one costs only
    // the growth of the vector.
    let capacity = usize::try_from(metadata.len()).unwrap_or(0);
    read_bounded(file, limit, &too_large, &unreadable, capacity)
}

/// At most `limit` bytes of `source`: one byte more is refused as too
/// large (a file that grows while read, or states a size it does not
/// hold).
fn read_bounded(
    source: impl Read,
    limit: u64,
    too_large: &dyn Fn(Option<u64>) -> IoError,
    unreadable: &dyn Fn(std::io::Error) -> IoError,
    capacity: usize,
) -> Result<Vec<u8>, IoError> {
    let mut bytes = Vec::with_capacity(capacity);
    source
        .take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(unreadable)?;
    if bytes.len() as u64 > limit {
        return Err(too_large(None));
    }
    Ok(bytes)
}

/// The pipes read so far, by the name they were given: a pipe can be read
/// once, and a command may read an input twice (to tell a relaxation file
/// from frequency sweeps, then to read it), so the second read gets the
/// bytes of the first.
static STREAMED: Mutex<Vec<(PathBuf, Arc<Vec<u8>>)>> = Mutex::new(Vec::new());

/// The bytes of the pipe `path`: read by `read` the first time, kept for
/// every later read.
fn streamed(
    path: &Path,
    read: impl FnOnce() -> Result<Vec<u8>, IoError>,
) -> Result<Vec<u8>, IoError> {
    let mut kept = STREAMED
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner());
    if let Some((_, bytes)) = kept.iter().find(|(p, _)| p == path) {
        return Ok(bytes.as_ref().clone());
    }
    let bytes = read()?;
    kept.push((path.to_path_buf(), Arc::new(bytes.clone())));
    Ok(bytes)
}

/// What the standard input is (a pipe, a file, a terminal, a device).
fn standard_input_metadata() -> std::io::Result<std::fs::Metadata> {
    #[cfg(unix)]
    {
        use std::os::fd::AsFd;
        let fd = std::io::stdin().as_fd().try_clone_to_owned()?;
        std::fs::File::from(fd).metadata()
    }
    #[cfg(not(unix))]
    {
        Err(std::io::Error::new(
            std::io::ErrorKind::Unsupported,
            "standard input as a file is read on Unix only",
        ))
    }
}

/// The size limit of an input file: [`LIMIT_VARIABLE`] if set, else
/// [`DEFAULT_LIMIT`]; `Err` holds a value that is no size.
pub fn limit() -> Result<u64, String> {
    match std::env::var_os(LIMIT_VARIABLE) {
        None => Ok(DEFAULT_LIMIT),
        Some(value) => {
            let text = value.to_string_lossy();
            parse_limit(&text).ok_or_else(|| text.into_owned())
        }
    }
}

/// A size as [`LIMIT_VARIABLE`] gives it: bytes (`1000000`) or a number
/// with K, M, G or T, powers of 1024, optionally followed by `B` or `iB`
/// (`500M`, `2G`, `2GiB`); at least one byte. `None` for anything else.
pub fn parse_limit(text: &str) -> Option<u64> {
    let text = text.trim();
    let upper = text.to_ascii_uppercase();
    let stem = upper
        .strip_suffix("IB")
        .or_else(|| upper.strip_suffix('B'))
        .unwrap_or(&upper);
    let (digits, power) = match stem.chars().last()? {
        'K' => (&stem[..stem.len() - 1], 1),
        'M' => (&stem[..stem.len() - 1], 2),
        'G' => (&stem[..stem.len() - 1], 3),
        'T' => (&stem[..stem.len() - 1], 4),
        _ if stem.len() == upper.len() => (stem, 0),
        // "B" alone after a number: bytes; "iB" needs a prefix.
        _ if upper.ends_with("IB") => return None,
        _ => (stem, 0),
    };
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    let bytes = digits
        .parse::<u64>()
        .ok()?
        .checked_mul(1024u64.pow(power))?;
    (bytes > 0).then_some(bytes)
}

/// `bytes` for a reader: the count, and above 1 KiB the count in KiB,
/// MiB, GiB or TiB ("1073741824 bytes (1 GiB)").
pub(crate) fn size_text(bytes: u64) -> String {
    const UNITS: [&str; 4] = ["KiB", "MiB", "GiB", "TiB"];
    let mut value = bytes as f64;
    let mut unit = None;
    for name in UNITS {
        if value < 1024.0 {
            break;
        }
        value /= 1024.0;
        unit = Some(name);
    }
    match unit {
        None => format!("{bytes} bytes"),
        Some(unit) => {
            let short = format!("{value:.2}");
            let short = short.trim_end_matches('0').trim_end_matches('.');
            format!("{bytes} bytes ({short} {unit})")
        }
    }
}

#[cfg(test)]
mod tests;
