//! Reading a text input (scene, manifest) as UTF-8, with the place of the
//! first invalid byte in the error: std's own message ("stream did not
//! contain valid UTF-8") names neither line nor byte.

use std::path::Path;

use anyhow::{Context, Result, bail};

/// The text of `path`, a `kind` of file ("scene file", "manifest"); an
/// error names the file and, for bytes that are not UTF-8, the line, the
/// byte offset in the file and the byte itself.
pub fn read_utf8(path: &Path, kind: &str) -> Result<String> {
    let bytes =
        std::fs::read(path).with_context(|| format!("cannot read {kind} {}", path.display()))?;
    match String::from_utf8(bytes) {
        Ok(text) => Ok(text),
        Err(e) => {
            let bytes = e.as_bytes();
            let at = e.utf8_error().valid_up_to();
            let line_start = bytes[..at]
                .iter()
                .rposition(|&b| b == b'\n')
                .map_or(0, |i| i + 1);
            let line = 1 + bytes[..at].iter().filter(|&&b| b == b'\n').count();
            bail!(
                "{kind} {}, line {line}: not UTF-8: byte 0x{:02X} at byte offset {at} (byte {} \
                 of the line); save the file as UTF-8 text",
                path.display(),
                bytes[at],
                at - line_start + 1
            )
        }
    }
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
