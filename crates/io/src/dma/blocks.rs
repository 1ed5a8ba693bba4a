//! The result blocks of an Anton Paar RheoCompass export: one file holding
//! several results (one per test temperature), each a block
//!
//! ```text
//! Result:  Frequency sweep 20C-cooling
//! Interval and data points:  1  13
//! Interval data:  Point No.  Angular Frequency  Storage Modulus  Loss Modulus  Temperature
//!                            [rad/s]            [Pa]             [Pa]          [°C]
//!                 1          100                1,23E+06         4,56E+05      20,01
//! ```
//!
//! (tab-separated, UTF-16, decimal commas after a German locale) below
//! `Project:` and `Test:` lines. Each block is read as a CSV text of its
//! own ([`super::csv_form`]: the header found below its title lines, the
//! bracketed units row, the columns it does not know ignored) and becomes
//! one isotherm; its temperature comes from its T column, else from its
//! `Result:` line (`20C-cooling` is 20 °C, [`super::stated_temperature`]).
//!
//! A block's text keeps the file's line numbering: the lines above it are
//! left empty (their line ends kept) and those below it cut, so every
//! message names the file's line.

/// The first words of the lines that end a block; `Result:` also starts
/// one.
const BOUNDARIES: [&str; 3] = ["Result:", "Test:", "Project:"];

/// The texts of the result blocks of `text` (see the module doc), in file
/// order; None when `text` is no RheoCompass export: no `Result:` line
/// followed by an `Interval` line.
pub(crate) fn result_blocks(text: &str) -> Option<Vec<String>> {
    let lines: Vec<crate::data::dialect::Line> = crate::data::dialect::lines(text).collect();
    let starts_with = |line: &crate::data::dialect::Line, word: &str| {
        line.text
            .trim_start_matches('\u{feff}')
            .trim_start()
            .starts_with(word)
    };
    let first = lines.iter().position(|l| starts_with(l, "Result:"))?;
    if !lines[first..].iter().any(|l| starts_with(l, "Interval")) {
        return None;
    }
    let mut blocks = Vec::new();
    let mut start: Option<usize> = None;
    for line in &lines {
        if BOUNDARIES.iter().any(|w| starts_with(line, w)) {
            if let Some(from) = start.take() {
                blocks.push(block(text, from, line.start));
            }
            if starts_with(line, "Result:") {
                start = Some(line.start);
            }
        }
    }
    if let Some(from) = start {
        blocks.push(block(text, from, text.len()));
    }
    Some(blocks)
}

/// The bytes `from..to` of `text`, after as many empty lines as `text` has
/// before `from` (their line ends as written).
fn block(text: &str, from: usize, to: usize) -> String {
    let mut out: String = text[..from]
        .chars()
        .filter(|&c| c == '\n' || c == '\r')
        .collect();
    out.push_str(&text[from..to]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two results below a test: two blocks, each keeping the file's line
    /// numbers, the `Test:` line in neither; a text without `Result:` and
    /// `Interval` lines is no export.
    #[test]
    fn blocks_keep_the_files_line_numbers() {
        let text = "Test:\tFS\r\nResult:\tA 20C\r\nInterval data:\tx\r\n1\r\n\r\n\
                    Result:\tB 30C\r\nInterval data:\tx\r\n2\r\n";
        let blocks = result_blocks(text).unwrap();
        assert_eq!(blocks.len(), 2);
        assert_eq!(
            blocks[0],
            "\r\nResult:\tA 20C\r\nInterval data:\tx\r\n1\r\n\r\n"
        );
        assert!(blocks[1].starts_with("\r\n\r\n\r\n\r\n\r\nResult:\tB 30C"));
        assert!(result_blocks("Result: 20C\nf,E\n").is_none());
        assert!(result_blocks("f,E_storage\n1,2\n").is_none());
    }
}
