//! Reading a text file as UTF-8, with the place of the first invalid byte
//! in the error: std's own message ("stream did not contain valid UTF-8")
//! names neither line nor byte.
//!
//! Two wordings: [`read_utf8`] for the inputs a user writes (scene file,
//! manifest; docs/ARCHITECTURE.md, "Contract", "Scene file"), which names
//! the kind of file and says to save it as UTF-8; `read_utf8_file` for
//! what rollfit wrote (the fit folder), which names the file and line only.
//! DMA exports come in other encodings too and are decoded by
//! [`crate::dma`].

use std::path::Path;

use crate::error::found_byte;
use crate::error::{InvalidText, IoError};
use crate::input_file::read_input;

/// The text of `path`, a `kind` of file ("scene file", "manifest"); an
/// error names the file and, for bytes that are not UTF-8, the line, the
/// byte offset in the file and the byte itself.
pub fn read_utf8(path: &Path, kind: &'static str) -> Result<String, IoError> {
    let bytes = read_input(path, kind, |source| {
        err!("cannot read {kind} {}", path.display())
            .in_file(path)
            .system(source)
    })?;
    String::from_utf8(bytes).map_err(|e| {
        let bytes = e.as_bytes();
        let offset = e.utf8_error().valid_up_to();
        let (line, byte_in_line) = line_and_column(bytes, offset);
        err!(
            "{kind} {}, line {line}: not UTF-8: byte 0x{byte:02X} at byte offset {offset} (byte \
         {byte_in_line} of the line); save the file as UTF-8 text",
            path.display(),
            byte = bytes[offset]
        )
    })
}

/// The text of a file that must be UTF-8 (what rollfit writes), or an
/// error naming the line and byte offset of the first invalid byte.
pub(crate) fn read_utf8_file(path: &Path) -> Result<String, IoError> {
    let bytes = read_input(path, "result file", |source| {
        err!("{}: {source}", path.display()).system(source)
    })?;
    String::from_utf8(bytes).map_err(|e| {
        let offset = e.utf8_error().valid_up_to();
        let problem = if e.utf8_error().error_len().is_none() {
            InvalidText::CutCharacter
        } else {
            InvalidText::NotUtf8
        };
        invalid_text(path, e.as_bytes(), offset, problem)
    })
}

/// Bytes that are not text in the file's encoding, at `offset` of
/// `bytes` (the whole file).
pub(crate) fn invalid_text(
    path: &Path,
    bytes: &[u8],
    offset: usize,
    problem: InvalidText,
) -> IoError {
    let (line, byte_in_line) = line_and_column(bytes, offset);
    err!(
        "{}, line {line}: {problem}: {} at byte offset {offset} (byte {byte_in_line} of the line)",
        path.display(),
        found_byte(bytes.get(offset).copied())
    )
}

/// The line (from 1) of byte `offset` and its place in the line (from 1).
fn line_and_column(bytes: &[u8], offset: usize) -> (usize, usize) {
    let before = &bytes[..offset.min(bytes.len())];
    let line_start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    (line, offset - line_start + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn invalid_bytes_are_located() {
        let dir = std::env::temp_dir().join(format!("rollfit-text-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("s.toml");
        std::fs::write(&path, b"[geometry]\nshape = \"sphere\" \xff\n").unwrap();
        let m = format!("{:#}", read_utf8(&path, "scene file").unwrap_err());
        assert!(
            m.contains(
                "s.toml, line 2: not UTF-8: byte 0xFF at byte offset 28 (byte 18 of the line)"
            ),
            "{m}"
        );
        std::fs::write(&path, "radius = 0.005 # µm? no: m\n").unwrap();
        assert!(read_utf8(&path, "scene file").is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
