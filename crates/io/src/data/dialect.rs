//! The dialect of a delimited text table, as labs and instruments write it
//! (docs/ARCHITECTURE.md, "Contract", "Measured data" and "DMA files"):
//! which of `,`, `;` or tab separates the cells, which line is the header
//! (title lines above it skipped), and whether a number may have a decimal
//! comma. One detection for measured data ([`super::text`]) and DMA CSV
//! (`crate::dma::csv_form`), so that a file a user exports from one
//! spreadsheet reads alike in both.
//!
//! The rule: the header is the first line, above the first line of
//! numbers, that the reader's own vocabulary recognises (a speed and a
//! friction column; a frequency, a storage and a loss modulus), the cells
//! split by one delimiter; of the delimiters giving a header, the one
//! giving the widest header wins, ties in the order tab, `;`, `,` (a
//! comma inside a cell is likelier than a tab or a semicolon). Lines above
//! the header that are not `#` comments are titles. Decimal commas are read
//! where a comma cannot separate cells (`;` or tab, or a workbook); in a
//! comma-separated file `1,5` is refused, not guessed. The German and
//! French spreadsheet defaults (Excel's "CSV (semicolon)", LibreOffice's
//! locale export) write exactly `;` with decimal commas.
//!
//! The search stops at the first line of numbers, and lines are split one
//! at a time: detection costs at most three passes over the file, never
//! more memory than one line's cells.

use super::cell::{Cell, Row, is_comment_or_blank};
pub(crate) use super::source::decimal_comma;

/// The delimiters tried, in order of preference on a tie.
pub(crate) const DELIMITERS: [char; 3] = ['\t', ';', ','];

/// One line of a text: its number from 1 (as an editor counts: CR, LF and
/// CRLF each end a line), where it starts (byte offset) and its text
/// without the line end.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Line<'t> {
    pub number: u64,
    pub start: usize,
    pub text: &'t str,
}

/// The lines of a text, `#` comments and blank lines left out.
#[derive(Debug, Clone)]
pub(crate) struct Lines<'t> {
    text: &'t str,
    /// Where the next line starts; past the end when done.
    next: usize,
    number: u64,
}

/// The lines of `text` (see [`Line`]), comments and blank lines left out.
pub(crate) fn lines(text: &str) -> Lines<'_> {
    Lines {
        text,
        next: 0,
        number: 0,
    }
}

impl<'t> Iterator for Lines<'t> {
    type Item = Line<'t>;

    fn next(&mut self) -> Option<Line<'t>> {
        let bytes = self.text.as_bytes();
        while self.next <= bytes.len() {
            let start = self.next;
            let end = bytes[start..]
                .iter()
                .position(|&b| b == b'\n' || b == b'\r')
                .map_or(bytes.len(), |n| start + n);
            self.number += 1;
            self.next = match bytes.get(end) {
                Some(b'\r') if bytes.get(end + 1) == Some(&b'\n') => end + 2,
                Some(_) => end + 1,
                None => bytes.len() + 1,
            };
            let text = &self.text[start..end];
            if !is_comment_or_blank(text) {
                return Some(Line {
                    number: self.number,
                    start,
                    text,
                });
            }
        }
        None
    }
}

/// A header found: the delimiter, the header's line and its index among
/// the lines searched.
pub(crate) struct Found<'t> {
    pub delimiter: char,
    pub index: usize,
    pub line: Line<'t>,
}

/// The header of `lines` and its delimiter by the rule of the module doc;
/// `is_header` is the reader's vocabulary. None when no delimiter gives
/// one.
pub(crate) fn detect<'t>(
    lines: impl Iterator<Item = Line<'t>> + Clone,
    is_header: impl Fn(&Row) -> bool,
) -> Option<Found<'t>> {
    let mut best: Option<(Found, usize)> = None;
    for delimiter in DELIMITERS {
        let rows = lines.clone().map(|line| {
            let row = Row {
                number: line.number,
                cells: split_line(line.text, delimiter),
            };
            (line, row)
        });
        let Some((index, (line, row))) =
            header_index(rows, |(_, row): &(Line, Row)| row, &is_header)
        else {
            continue;
        };
        let width = row.cells.iter().filter(|c| !c.is_empty()).count();
        if best.as_ref().is_none_or(|b| width > b.1) {
            let found = Found {
                delimiter,
                index,
                line,
            };
            best = Some((found, width));
        }
    }
    best.map(|b| b.0)
}

/// The first of `items` whose row (`row` of it) `is_header`, searched
/// until the first row of numbers, with its index: the header of a text
/// or a sheet, below its title rows.
pub(crate) fn header_index<T>(
    items: impl IntoIterator<Item = T>,
    row: impl for<'a> Fn(&'a T) -> &'a Row,
    is_header: impl Fn(&Row) -> bool,
) -> Option<(usize, T)> {
    items
        .into_iter()
        .take_while(|item| !row(item).is_numeric())
        .enumerate()
        .find(|(_, item)| is_header(row(item)))
}

/// The delimiter of a line that is no header the reader knows (to name
/// its cells in the message): the one it holds most of.
pub(crate) fn likeliest(line: &str) -> char {
    DELIMITERS
        .into_iter()
        .max_by_key(|d| line.matches(*d).count())
        .unwrap_or(',')
}

/// The cells of a text line: separated by `delimiter`, each trimmed, with
/// double quotes around a cell removed (`""` in a quoted cell is `"`).
pub(crate) fn split_line(line: &str, delimiter: char) -> Vec<Cell> {
    let mut cells = Vec::new();
    let mut current = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        if quoted {
            if c == '"' {
                if chars.peek() == Some(&'"') {
                    current.push('"');
                    chars.next();
                } else {
                    quoted = false;
                }
            } else {
                current.push(c);
            }
        } else if c == delimiter {
            cells.push(Cell::text(&current));
            current.clear();
        } else if c == '"' && current.trim().is_empty() {
            current.clear();
            quoted = true;
        } else {
            current.push(c);
        }
    }
    cells.push(Cell::text(&current));
    // A row lives as long as the file's checks: no spare capacity per row.
    cells.shrink_to_fit();
    cells
}

/// The delimiter of a text (a DMA CSV or relaxation file) and the byte where its header starts, by the
/// shared dialect detection ([`detect`]) with `is_header`; None
/// for a text without a line. Without a header the vocabulary knows, the
/// first line, split by the delimiter it holds most of.
pub(crate) fn dialect_of(
    text: &str,
    is_header: impl Fn(&Row) -> bool,
) -> Option<(char, usize, Option<Found<'_>>)> {
    let all = lines(text);
    let found = detect(all.clone(), is_header);
    let (delimiter, start) = match &found {
        Some(found) => (found.delimiter, found.line.start),
        None => {
            let first = all.clone().next()?;
            (likeliest(first.text), first.start)
        }
    };
    Some((delimiter, start, found))
}

/// `text` with the cells of each line split at runs of spaces (or tabs)
/// instead of one delimiter, rejoined by tabs: a table aligned for the
/// eye. Line ends and `#` comments are kept as they are, so line numbers
/// stay the file's. None when no line has two cells so split.
pub(crate) fn aligned(text: &str) -> Option<String> {
    let mut out = String::with_capacity(text.len());
    let mut split = false;
    for piece in text.split_inclusive(['\n', '\r']) {
        let body = piece.trim_end_matches(['\n', '\r']);
        if is_comment_or_blank(body) {
            out.push_str(body);
        } else {
            let cells: Vec<&str> = body.split_whitespace().collect();
            split |= cells.len() > 1;
            out.push_str(&cells.join("\t"));
        }
        out.push_str(&piece[body.len()..]);
    }
    split.then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Line numbers and starts as an editor counts them, over CR, LF and
    /// CRLF, with comments and blank lines skipped but counted.
    #[test]
    fn lines_are_numbered_as_an_editor_counts() {
        let text = "a\r\n# c\rb\n\nc";
        let got: Vec<(u64, usize, &str)> =
            lines(text).map(|l| (l.number, l.start, l.text)).collect();
        assert_eq!(got, [(1, 0, "a"), (3, 7, "b"), (5, 10, "c")]);
    }

    /// The widest header wins; a title line above it is skipped; the
    /// search stops at the first row of numbers.
    #[test]
    fn the_delimiter_is_the_one_giving_the_widest_header() {
        let named = |row: &Row| row.names().iter().any(|n| n == "x") && row.cells.len() > 1;
        let found = detect(lines("Title, 2024\nx;y,z;w\n1;2,5;3\n"), named).unwrap();
        assert_eq!(
            (found.delimiter, found.index, found.line.number),
            (';', 1, 2)
        );
        assert!(detect(lines("1;2\nx;y\n"), named).is_none());
        assert_eq!(
            aligned("# a  b\r\n x   y\r\n  1  2.5\r").as_deref(),
            Some("# a  b\r\nx\ty\r\n1\t2.5\r")
        );
        assert_eq!(likeliest("a;b;c,d"), ';');
    }
}
