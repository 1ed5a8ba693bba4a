//! The text of a DMA file (docs/ARCHITECTURE.md, "Contract", "DMA
//! files"): TRIOS writes UTF-8, but older versions and Windows tools write
//! UTF-16 (with a byte-order mark) or Latin-1 (° as byte 0xB0); [`decode`]
//! reads all three, for both forms.

use std::path::Path;

use crate::error::{InvalidText, IoError};
use crate::text_file::invalid_text;

/// Text of a file: UTF-16 when it starts with a byte-order mark, UTF-8
/// when valid (a UTF-8 mark dropped), Latin-1 when nothing in it is UTF-8
/// beyond ASCII.
///
/// A UTF-16 file with an odd number of bytes whose text ends with a line
/// break has one stray byte after its last line (an export that wrote one
/// byte too many): the byte is dropped and [`decode_noted`] says so.
///
/// Refused, with the line and byte offset: a UTF-16 file with an unpaired
/// surrogate or an odd number of bytes cut off inside a line, and invalid UTF-8 in a
/// file that is UTF-8 elsewhere or says so with its mark: that is damage
/// or two encodings spliced, and reading it as Latin-1 would quietly turn
/// every "°C" of it into "Â°C".
pub fn decode(path: &Path, bytes: &[u8]) -> Result<String, IoError> {
    decode_noted(path, bytes).map(|(text, _)| text)
}

/// [`decode`], with a note on how the text was read where it was not
/// plain UTF-8: the byte-order mark, Latin-1, a stray byte dropped.
pub fn decode_noted(path: &Path, bytes: &[u8]) -> Result<(String, Vec<String>), IoError> {
    let (text, mut notes) = decode_marked(path, bytes)?;
    // Classic Mac OS line ends: read as line breaks (the lines are
    // numbered as an editor numbers them), but worth saying.
    if text.contains('\r') && !text.contains('\n') {
        notes.push(format!(
            "{}: lines end with CR only (classic Mac OS): read as line breaks",
            path.display()
        ));
    }
    Ok((text, notes))
}

/// [`decode_noted`] without the note on line ends.
fn decode_marked(path: &Path, bytes: &[u8]) -> Result<(String, Vec<String>), IoError> {
    let note = |what: &str| vec![format!("{}: {what}", path.display())];
    match bytes {
        [0xFF, 0xFE, ..] | [0xFE, 0xFF, ..] => {
            let little = bytes[0] == 0xFF;
            let (text, stray) = utf16(path, bytes, little)?;
            let order = if little { "little" } else { "big" };
            let mut notes = note(&format!("read as UTF-16 ({order}-endian byte-order mark)"));
            if stray {
                notes.extend(note(&format!(
                    "one stray byte after the last line (byte offset {}) ignored",
                    bytes.len() - 1
                )));
            }
            Ok((text, notes))
        }
        [0xEF, 0xBB, 0xBF, ..] => Ok((
            decode_8bit(path, bytes)?,
            note("UTF-8 byte-order mark ignored"),
        )),
        _ => {
            let text = decode_8bit(path, bytes)?;
            let latin = std::str::from_utf8(bytes).is_err();
            let notes = if latin {
                note("not UTF-8: read as Latin-1 (ISO 8859-1)")
            } else {
                Vec::new()
            };
            Ok((text, notes))
        }
    }
}

/// UTF-8 (its mark dropped), else Latin-1 where nothing is UTF-8 beyond
/// ASCII; the refusals of [`decode`].
fn decode_8bit(path: &Path, bytes: &[u8]) -> Result<String, IoError> {
    let marked = bytes.starts_with(&[0xEF, 0xBB, 0xBF]);
    let body = if marked { &bytes[3..] } else { bytes };
    match std::str::from_utf8(body) {
        Ok(text) => Ok(text.to_string()),
        Err(e) => {
            let offset = (bytes.len() - body.len()) + e.valid_up_to();
            if marked {
                Err(invalid_text(
                    path,
                    bytes,
                    offset,
                    InvalidText::InvalidAfterMark,
                ))
            } else if body.utf8_chunks().any(|c| !c.valid().is_ascii()) {
                Err(invalid_text(
                    path,
                    bytes,
                    offset,
                    InvalidText::MixedEncodings,
                ))
            } else {
                Ok(body.iter().map(|&b| char::from(b)).collect())
            }
        }
    }
}

/// UTF-16 text after its byte-order mark, little- or big-endian, and
/// whether a stray byte after its last line break was left out.
fn utf16(path: &Path, bytes: &[u8], little: bool) -> Result<(String, bool), IoError> {
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
                return Err(err!(
                    "{}, line {line}: not UTF-16 although the file starts with a UTF-16 byte-order mark: \
         unpaired surrogate 0x{unit:04X} at byte offset {offset}",
                    path.display(),
                    line = text.matches('\n').count() + 1,
                    offset = 2 + 2 * unit,
                    unit = e.unpaired_surrogate()
                ));
            }
        }
    }
    let odd = body.len() % 2 == 1;
    if odd && text.ends_with(['\n', '\r']) {
        return Ok((text, true));
    }
    if odd {
        return Err(err!(
            "{}, line {line}: UTF-16 file (byte-order mark) with an odd number of bytes ({length}): \
         the last character is cut off at byte offset {offset}; the file looks truncated",
            path.display(),
            length = bytes.len(),
            line = text.matches('\n').count() + 1,
            offset = bytes.len() - 1
        ));
    }
    Ok((text, false))
}
