//! The one decoder of input files: bytes → text, with a note on each
//! reading other than plain UTF-8, and errors naming the line and byte
//! offset of what cannot be read (docs/ARCHITECTURE.md, "DMA files",
//! "Text"). Two strictnesses ([`Encodings`]):
//! - [`Encodings::Any`], for exports (measured data, DMA files, tables):
//!   UTF-16 after a byte-order mark, UTF-8 when valid (a mark dropped),
//!   else Latin-1 when nothing in it is UTF-8 beyond ASCII (`°` as 0xB0).
//!   A UTF-16 file whose text ends with a line break followed by one odd
//!   byte (an export that wrote one byte too many) is read without it.
//!   Refused: an unpaired surrogate, an odd byte count cutting a line, and
//!   invalid UTF-8 in a file that is UTF-8 elsewhere or says so with its
//!   mark — damage, or two encodings spliced, which read as Latin-1 would
//!   quietly turn every "°C" into "Â°C".
//! - [`Encodings::Utf8`], for what a user writes (scene file, manifest:
//!   [`read_utf8`]) and what rollfit writes (the fit folder).

use std::fmt::Display;
use std::path::Path;

use crate::error::found_byte;
use crate::error::{InvalidText, IoError};
use crate::input_file::read_input;

/// Which encodings a file may be in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Encodings {
    /// UTF-8, UTF-16 with a byte-order mark, or Latin-1 (the module doc).
    Any,
    /// UTF-8 only.
    Utf8,
}

/// A file's text and the notes on how it was read (without its name).
pub(crate) struct Text {
    pub text: String,
    pub notes: Vec<String>,
}

/// Bytes that are not text: where (line from 1) and what.
pub(crate) struct Undecodable {
    line: usize,
    detail: String,
}

impl Undecodable {
    /// The error "`file`, line L: what".
    pub(crate) fn in_file(self, file: impl Display) -> IoError {
        err!("{file}, line {}: {}", self.line, self.detail)
    }

    /// The error "line L: what", for a reader whose caller names the file.
    pub(crate) fn in_lines(self) -> IoError {
        err!("line {}: {}", self.line, self.detail)
    }
}

/// The text of `bytes` (a whole file, taken so that valid UTF-8 becomes
/// text without a copy) in `encodings`.
pub(crate) fn decode(bytes: Vec<u8>, encodings: Encodings) -> Result<Text, Undecodable> {
    let (text, mut notes) = match (encodings, bytes.as_slice()) {
        (Encodings::Any, [0xFF, 0xFE, ..] | [0xFE, 0xFF, ..]) => utf16(&bytes)?,
        (Encodings::Any, _) => eight_bit(bytes)?,
        (Encodings::Utf8, _) => (strict_utf8(bytes)?, Vec::new()),
    };
    // Classic Mac OS line ends: read as line breaks (the lines are
    // numbered as an editor numbers them), but worth saying.
    if text.contains('\r') && !text.contains('\n') {
        notes.push("lines end with CR only (classic Mac OS): read as line breaks".to_string());
    }
    Ok(Text { text, notes })
}

/// The text of an exported file at `path` ([`Encodings::Any`]), already
/// read as `bytes`; errors and notes start with the file's name.
pub(crate) fn decode_file(path: &Path, bytes: Vec<u8>) -> Result<Text, IoError> {
    let Text { text, notes } =
        decode(bytes, Encodings::Any).map_err(|bad| bad.in_file(path.display()))?;
    let notes = notes
        .into_iter()
        .map(|note| format!("{}: {note}", path.display()))
        .collect();
    Ok(Text { text, notes })
}

/// The text of `path`, a `kind` of file a user writes ("scene file",
/// "manifest"), which must be UTF-8; an error names the file and, for
/// bytes that are not UTF-8, the line, the byte offset in the file and the
/// byte itself, and says to save it as UTF-8.
pub fn read_utf8(path: &Path, kind: &'static str) -> Result<String, IoError> {
    let bytes = read_input(path, kind, |source| {
        err!("cannot read {kind} {}", path.display())
            .in_file(path)
            .system(source)
    })?;
    let decoded = decode(bytes, Encodings::Utf8).map_err(|mut bad| {
        bad.detail.push_str("; save the file as UTF-8 text");
        bad.in_file(format_args!("{kind} {}", path.display()))
    })?;
    Ok(decoded.text)
}

/// The text of a file that must be UTF-8 (what rollfit writes), or an
/// error naming the line and byte offset of the first invalid byte.
pub(crate) fn read_utf8_file(path: &Path) -> Result<String, IoError> {
    let bytes = read_input(path, "result file", |source| {
        err!("{}: {source}", path.display()).system(source)
    })?;
    let decoded = decode(bytes, Encodings::Utf8).map_err(|bad| bad.in_file(path.display()))?;
    Ok(decoded.text)
}

/// UTF-8 or nothing.
fn strict_utf8(bytes: Vec<u8>) -> Result<String, Undecodable> {
    String::from_utf8(bytes).map_err(|e| {
        let offset = e.utf8_error().valid_up_to();
        let problem = if e.utf8_error().error_len().is_none() {
            InvalidText::CutCharacter
        } else {
            InvalidText::NotUtf8
        };
        invalid(e.as_bytes(), offset, problem)
    })
}

/// UTF-8 (its mark dropped, with a note), else Latin-1 where nothing is
/// UTF-8 beyond ASCII (with a note naming the first line that is not
/// UTF-8); the refusals of the module doc.
fn eight_bit(mut bytes: Vec<u8>) -> Result<(String, Vec<String>), Undecodable> {
    const MARK: [u8; 3] = [0xEF, 0xBB, 0xBF];
    let marked = bytes.starts_with(&MARK);
    let skipped = if marked { MARK.len() } else { 0 };
    let body = &bytes[skipped..];
    match std::str::from_utf8(body) {
        Ok(_) => {
            bytes.drain(..skipped);
            let notes = marked.then(|| "UTF-8 byte-order mark ignored".to_string());
            // Checked just above.
            Ok((
                String::from_utf8(bytes).unwrap_or_default(),
                notes.into_iter().collect(),
            ))
        }
        Err(e) => {
            let offset = skipped + e.valid_up_to();
            if marked {
                Err(invalid(&bytes, offset, InvalidText::InvalidAfterMark))
            } else if body.utf8_chunks().any(|c| !c.valid().is_ascii()) {
                Err(invalid(&bytes, offset, InvalidText::MixedEncodings))
            } else {
                let (line, _) = line_and_column(&bytes, offset);
                let note =
                    format!("not UTF-8 text (line {line} is not): read as Latin-1 (ISO 8859-1)");
                Ok((bytes.iter().map(|&b| char::from(b)).collect(), vec![note]))
            }
        }
    }
}

/// UTF-16 text after its byte-order mark, with the notes of the mark and
/// of a stray byte after its last line break.
fn utf16(bytes: &[u8]) -> Result<(String, Vec<String>), Undecodable> {
    let little = bytes[0] == 0xFF;
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
                return Err(Undecodable {
                    line: text.matches('\n').count() + 1,
                    detail: format!(
                        "not UTF-16 although the file starts with a UTF-16 byte-order mark: \
                         unpaired surrogate 0x{:04X} at byte offset {}",
                        e.unpaired_surrogate(),
                        2 + 2 * unit
                    ),
                });
            }
        }
    }
    let order = if little { "little" } else { "big" };
    let mut notes = vec![format!("read as UTF-16 ({order}-endian byte-order mark)")];
    if body.len() % 2 == 1 {
        if !text.ends_with(['\n', '\r']) {
            return Err(Undecodable {
                line: text.matches('\n').count() + 1,
                detail: format!(
                    "UTF-16 file (byte-order mark) with an odd number of bytes ({}): the last \
                     character is cut off at byte offset {}; the file looks truncated",
                    bytes.len(),
                    bytes.len() - 1
                ),
            });
        }
        notes.push(format!(
            "one stray byte after the last line (byte offset {}) ignored",
            bytes.len() - 1
        ));
    }
    Ok((text, notes))
}

/// Bytes that are not text in the file's encoding, at `offset` of
/// `bytes` (the whole file).
fn invalid(bytes: &[u8], offset: usize, problem: InvalidText) -> Undecodable {
    let (line, byte_in_line) = line_and_column(bytes, offset);
    Undecodable {
        line,
        detail: format!(
            "{problem}: {} at byte offset {offset} (byte {byte_in_line} of the line)",
            found_byte(bytes.get(offset).copied())
        ),
    }
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

    /// The same text in every encoding the exports use reads the same,
    /// each reading noted; a UTF-8-only file refuses all but UTF-8.
    #[test]
    fn every_encoding_reads_the_same_text() {
        let text = "T (°C);E\r\n20;1,5\r\n";
        let latin1: Vec<u8> = text.chars().map(|c| c as u8).collect();
        let mut marked = vec![0xEF, 0xBB, 0xBF];
        marked.extend(text.as_bytes());
        let utf16 = |little: bool, stray: bool| {
            let mut bytes = if little {
                vec![0xFF, 0xFE]
            } else {
                vec![0xFE, 0xFF]
            };
            for unit in text.encode_utf16() {
                bytes.extend(if little {
                    unit.to_le_bytes()
                } else {
                    unit.to_be_bytes()
                });
            }
            if stray {
                bytes.push(0);
            }
            bytes
        };
        for (bytes, note) in [
            (text.as_bytes().to_vec(), None),
            (marked, Some("UTF-8 byte-order mark ignored")),
            (
                latin1.clone(),
                Some("not UTF-8 text (line 1 is not): read as Latin-1 (ISO 8859-1)"),
            ),
            (utf16(true, false), Some("little-endian")),
            (utf16(false, false), Some("big-endian")),
            (utf16(true, true), Some("one stray byte")),
        ] {
            let read = decode(bytes, Encodings::Any).ok().unwrap();
            assert_eq!(read.text, text);
            match note {
                None => assert!(read.notes.is_empty(), "{:?}", read.notes),
                Some(note) => assert!(read.notes.iter().any(|n| n.contains(note))),
            }
        }
        let bad = decode(latin1, Encodings::Utf8).err().unwrap();
        assert_eq!(
            format!("{:#}", bad.in_lines()),
            "line 1: not UTF-8: byte 0xB0 at byte offset 3 (byte 4 of the line)"
        );
        let cr = decode(b"a\rb\r".to_vec(), Encodings::Any).ok().unwrap();
        assert!(cr.notes[0].contains("CR only"), "{:?}", cr.notes);
    }
}
