//! Workbooks written by tests with the zip crate: the few XML parts
//! calamine needs (.xlsx: content types, workbook, relations, sheets with
//! inline strings; .ods: content.xml), no binary fixtures. Used by the
//! io crate's workbook and DMA tests and by the command-line tests.

use std::io::{Cursor, Write};

use zip::write::SimpleFileOptions;

/// The spreadsheet name of the column `index` (from 0): A, …, Z, AA, ….
fn letter(index: usize) -> String {
    let mut n = index + 1;
    let mut out = Vec::new();
    while n > 0 {
        let r = (n - 1) % 26;
        out.push(b'A' + r as u8);
        n = (n - 1) / 26;
    }
    out.reverse();
    String::from_utf8(out).unwrap()
}

/// A cell of a test sheet.
#[derive(Clone, Copy)]
pub enum X<'a> {
    /// A number.
    N(f64),
    /// Text.
    S(&'a str),
    /// A spreadsheet error value (#DIV/0!).
    Error,
    /// A formula without a saved result (as a program that does not
    /// compute writes it), without its `=`.
    F(&'a str),
    /// Nothing.
    E,
}

/// A row of text cells.
pub fn texts<'a>(cells: &[&'a str]) -> Vec<X<'a>> {
    cells.iter().map(|c| X::S(c)).collect()
}

fn zip_archive(parts: &[(&str, String)]) -> Vec<u8> {
    let mut zip = zip::ZipWriter::new(Cursor::new(Vec::new()));
    let options = SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    for (name, content) in parts {
        zip.start_file(*name, options).unwrap();
        zip.write_all(content.as_bytes()).unwrap();
    }
    zip.finish().unwrap().into_inner()
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// An .xlsx workbook of `sheets` (name, rows from A1).
pub fn xlsx(sheets: &[(&str, Vec<Vec<X>>)]) -> Vec<u8> {
    xlsx_with_stray(sheets, None)
}

/// An .xlsx workbook of `sheets` whose first sheet also holds the number
/// 1 in the cell `stray` (as `"XFD1048576"`, below and right of the rows):
/// a sheet whose extent is far larger than its data.
pub fn xlsx_with_stray(sheets: &[(&str, Vec<Vec<X>>)], stray: Option<&str>) -> Vec<u8> {
    const MAIN: &str = "http://schemas.openxmlformats.org/spreadsheetml/2006/main";
    const RELS: &str = "http://schemas.openxmlformats.org/package/2006/relationships";
    const DOC: &str = "http://schemas.openxmlformats.org/officeDocument/2006/relationships";
    let mut types = String::from(
        r#"<?xml version="1.0" encoding="UTF-8" standalone="yes"?><Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types"><Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/><Default Extension="xml" ContentType="application/xml"/><Override PartName="/xl/workbook.xml" ContentType="application/vnd.openxmlformats-officedocument.spreadsheetml.sheet.main+xml"/>"#,
    );
    let mut workbook = format!(r#"<workbook xmlns="{MAIN}" xmlns:r="{DOC}"><sheets>"#);
    let mut rels = format!(r#"<Relationships xmlns="{RELS}">"#);
    let mut parts = Vec::new();
    for (i, (name, rows)) in sheets.iter().enumerate() {
        let n = i + 1;
        types += &format!(
            r#"<Override PartName="/xl/worksheets/sheet{n}.xml" ContentType="application/vnd.openxmlformats-officedocument.spreadsheetml.worksheet+xml"/>"#
        );
        workbook += &format!(
            r#"<sheet name="{}" sheetId="{n}" r:id="rId{n}"/>"#,
            escape(name)
        );
        rels += &format!(
            r#"<Relationship Id="rId{n}" Type="{DOC}/worksheet" Target="worksheets/sheet{n}.xml"/>"#
        );
        let mut sheet = format!(r#"<worksheet xmlns="{MAIN}"><sheetData>"#);
        for (r, row) in rows.iter().enumerate() {
            sheet += &format!(r#"<row r="{}">"#, r + 1);
            for (c, x) in row.iter().enumerate() {
                let at = format!("{}{}", letter(c), r + 1);
                sheet += &match x {
                    X::N(v) => format!(r#"<c r="{at}"><v>{v:e}</v></c>"#),
                    X::S(s) => format!(
                        r#"<c r="{at}" t="inlineStr"><is><t>{}</t></is></c>"#,
                        escape(s)
                    ),
                    X::Error => format!(r#"<c r="{at}" t="e"><v>#DIV/0!</v></c>"#),
                    X::F(formula) => format!(r#"<c r="{at}"><f>{}</f></c>"#, escape(formula)),
                    X::E => String::new(),
                };
            }
            sheet += "</row>";
        }
        if let (0, Some(at)) = (i, stray) {
            let row: String = at.chars().filter(char::is_ascii_digit).collect();
            sheet += &format!(r#"<row r="{row}"><c r="{at}"><v>1</v></c></row>"#);
        }
        sheet += "</sheetData></worksheet>";
        parts.push((format!("xl/worksheets/sheet{n}.xml"), sheet));
    }
    types += "</Types>";
    workbook += "</sheets></workbook>";
    rels += "</Relationships>";
    let mut all = vec![
        ("[Content_Types].xml".to_string(), types),
        (
            "_rels/.rels".to_string(),
            format!(
                r#"<Relationships xmlns="{RELS}"><Relationship Id="rId1" Type="{DOC}/officeDocument" Target="xl/workbook.xml"/></Relationships>"#
            ),
        ),
        ("xl/workbook.xml".to_string(), workbook),
        ("xl/_rels/workbook.xml.rels".to_string(), rels),
    ];
    all.extend(parts);
    let all: Vec<(&str, String)> = all.iter().map(|(n, c)| (n.as_str(), c.clone())).collect();
    zip_archive(&all)
}

/// An .ods workbook of one sheet.
pub fn ods(name: &str, rows: Vec<Vec<X>>) -> Vec<u8> {
    let mut table = format!(r#"<table:table table:name="{}">"#, escape(name));
    for row in rows {
        table += "<table:table-row>";
        for x in row {
            table += &match x {
                X::N(v) => format!(
                    r#"<table:table-cell office:value-type="float" office:value="{v:e}"><text:p>{v}</text:p></table:table-cell>"#
                ),
                X::S(s) => format!(
                    r#"<table:table-cell office:value-type="string"><text:p>{}</text:p></table:table-cell>"#,
                    escape(s)
                ),
                X::Error | X::F(_) | X::E => "<table:table-cell/>".to_string(),
            };
        }
        table += "</table:table-row>";
    }
    table += "</table:table>";
    let content = format!(
        r#"<?xml version="1.0" encoding="UTF-8"?><office:document-content xmlns:office="urn:oasis:names:tc:opendocument:xmlns:office:1.0" xmlns:table="urn:oasis:names:tc:opendocument:xmlns:table:1.0" xmlns:text="urn:oasis:names:tc:opendocument:xmlns:text:1.0" office:version="1.2"><office:body><office:spreadsheet>{table}</office:spreadsheet></office:body></office:document-content>"#
    );
    let manifest = r#"<?xml version="1.0" encoding="UTF-8"?><manifest:manifest xmlns:manifest="urn:oasis:names:tc:opendocument:xmlns:manifest:1.0" manifest:version="1.2"><manifest:file-entry manifest:full-path="/" manifest:media-type="application/vnd.oasis.opendocument.spreadsheet"/><manifest:file-entry manifest:full-path="content.xml" manifest:media-type="text/xml"/></manifest:manifest>"#;
    zip_archive(&[
        (
            "mimetype",
            "application/vnd.oasis.opendocument.spreadsheet".to_string(),
        ),
        ("META-INF/manifest.xml", manifest.to_string()),
        ("content.xml", content),
    ])
}
