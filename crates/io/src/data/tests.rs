//! The measured-data reader on text: delimiters, decimal commas,
//! encodings, header names and units, skipped rows, and the messages of
//! what it refuses.

use super::headers;
use super::text::parse_bytes;
use super::*;
use crate::chain;
use crate::error::IoError;

fn parse_str(text: &str) -> Result<DataTable, IoError> {
    parse_bytes(text.as_bytes().to_vec())
}

/// The warnings of `t` but the hint that unitless speeds above 1 m/s may
/// be mm/s (these tests' speeds of 1, 2, 3 are only numbers).
fn warnings_but_mm(t: &DataTable) -> Vec<String> {
    t.warnings
        .iter()
        .filter(|w| !w.contains("mm/s?"))
        .cloned()
        .collect()
}

fn message(text: &str) -> String {
    chain(&parse_str(text).unwrap_err())
}

#[test]
fn reads_comments_extra_columns_repeats_and_unsorted_rows() {
    let t = parse_str(
        "# measured 2024\nv,mu,sigma,mu_exact\n1e-3,0.05,5e-4,0.051\n# again\n1e-4, 0.02, 2e-4, 0.02\n1e-3,0.052,5e-4,0.051\n",
    )
    .unwrap();
    assert_eq!(t.speeds, vec![1e-3, 1e-4, 1e-3]);
    assert_eq!(t.friction, vec![0.05, 0.02, 0.052]);
    assert_eq!(t.sigma, Some(vec![5e-4, 2e-4, 5e-4]));
    assert_eq!(t.temperature, None);
    assert_eq!(t.lines, vec![3, 5, 6]);
    assert!(t.notes.is_empty() && t.warnings.is_empty(), "{t:?}");
    let t = parse_str("v,mu\n1e-3,0.05\n1e-2,0.06\n1e-1,0.07\n1,0.08\n1,0.081\n").unwrap();
    assert_eq!(t.measurements().unwrap().len(), 5);
    let t = parse_str("\n# a\n#b\nv,mu\n\n1,0.1\n  # c\n\n2,0.2\n").unwrap();
    assert_eq!(t.lines, vec![6, 9]);
    let m = message("#\nv,mu\n# c\n\n1,0.1\n# d\n2,x\n");
    assert!(m.contains("line 7") && m.contains("\"x\""), "{m}");
    let t = parse_str("mu,T,v\n0.1,-20,1\n0.2,40,2\n").unwrap();
    assert_eq!(t.speeds, vec![1.0, 2.0]);
    assert_eq!(t.temperature, Some(vec![-20.0, 40.0]));
    assert_eq!(t.sigma, None);
    assert_eq!(t.temperatures(), vec![-20.0, 40.0]);
}

#[test]
fn errors_name_the_line_and_column() {
    let m = message("v,mu\n1e-3,0.05\nabc,0.1\n");
    assert!(
        m.contains("line 3: column `v`: \"abc\" is not a number"),
        "{m}"
    );
    let m = message("v;COF\n1e-3;0,05\n1e-3;1.2.3\n");
    assert!(
        m.contains("line 3: column `COF` (mu): \"1.2.3\" is not a number"),
        "{m}"
    );
    let m = message("v;mu\n1e-3;1.234,5\n");
    assert!(m.contains("line 2") && m.contains("thousands"), "{m}");
    let m = message("# c\nv,mu\n1e-3,0.05\n1e-2,-0.1\n");
    assert!(
        m.contains("line 4") && m.contains("`mu`") && m.contains("greater than zero"),
        "{m}"
    );
    let m = message("v,mu,sigma\n1e-3,0.05,0\n");
    assert!(m.contains("line 2") && m.contains("`sigma`"), "{m}");
    let m = message("v,mu\n0,0.05\n");
    assert!(m.contains("line 2") && m.contains("`v` = 0"), "{m}");
    let m = message("velocity (mm/s);mu\n-0,5;0,05\n");
    assert!(
        m.contains("line 2: column `velocity (mm/s)` (v) = -0,5: must be greater than zero"),
        "{m}"
    );
    let m = message("v,mu\n1,inf\n");
    assert!(
        m.contains("line 2: column `mu`: \"inf\" is not a finite number"),
        "{m}"
    );
}

/// Values no measurement reaches, which would overflow the weighted
/// residuals (μ = 1e300 and σ = 1e-300 once gave an infinite
/// objective and a fit.json with null in it).
#[test]
fn values_outside_a_rolling_measurement_are_refused() {
    let m = message("v,mu\n1e-3,0.01\n1e-2,1e300\n");
    assert!(
        m.contains("line 3: column `mu` = 1e300: must be below 10"),
        "{m}"
    );
    let m = message("v,mu,sigma\n1e-3,0.01,1e-300\n");
    assert!(
        m.contains("line 2: column `sigma` = 1e-300: must be at least 1e-9 of the row's mu"),
        "{m}"
    );
    let m = message("v,mu\n1e300,0.01\n");
    assert!(
        m.contains("line 2: column `v` = 1e300: must be at most 1000 m/s"),
        "{m}"
    );
    let m = message("v_mm_s,mu\n2e9,0.01\n");
    assert!(
        m.contains("line 2: column `v_mm_s` (v) = 2e9 (2e6 v in SI): must be at most 1000 m/s"),
        "{m}"
    );
    let m = message("v,mu,T\n1e-3,0.01,-300\n");
    assert!(
        m.contains("line 2: column `T` = -300: must be above absolute zero"),
        "{m}"
    );
}

#[test]
fn rejects_missing_columns_and_empty_data() {
    let m = message("# c\nv,friction\n1,0.1\n");
    assert!(
        m.contains("line 2 (header): no friction column (mu, µ, COF, friction coefficient")
            && m.contains("found \"v\", \"friction\" (delimiter ',')"),
        "{m}"
    );
    assert!(message("").contains("empty"));
    assert!(message("# only a comment\n").contains("empty"));
    assert!(message("v,mu\n").contains("no data rows"));
    assert!(message("v,mu\n# c\n").contains("no data rows"));
    let m = message("v,mu,v\n1,2,3\n");
    assert!(
        m.contains("two speed columns, \"v\" (column 1) and \"v\" (column 3)"),
        "{m}"
    );
    let m = message("v,mu\n# c\n1,0.1\n2\n");
    assert!(m.contains("line 4: malformed row"), "{m}");
}

#[test]
fn missing_columns_list_the_columns_found_with_the_delimiter() {
    let m = message("# c\n\nSpeed;Force (N)\n1;2\n");
    assert!(
        m.contains(
            "line 3 (header): no friction column (mu, µ, COF, friction coefficient, \
             coefficient of friction, …); found \"Speed\", \"Force (N)\" (delimiter ';')"
        ),
        "{m}"
    );
    let m = message("time\tforce\n1\t2\n");
    assert!(
        m.contains("line 1 (header): no speed column (v, velocity, speed")
            && m.contains("and no friction column")
            && m.contains("found \"time\", \"force\" (delimiter tab)"),
        "{m}"
    );
    // No header among the title lines: the first line is listed.
    let m = message("Measurement 2024-03-01\nx;y\n1;2\n");
    assert!(
        m.contains("line 1 (header): no speed column")
            && m.contains("found \"Measurement 2024-03-01\""),
        "{m}"
    );
}

#[test]
fn each_delimiter_and_decimal_commas() {
    let expected = (vec![1e-3, 2.5e-2], vec![0.05, 0.125]);
    for (text, note) in [
        ("v,mu\n1e-3,0.05\n0.025,0.125\n", None),
        (
            "v;mu\n1e-3;0.05\n0.025;0.125\n",
            Some("columns separated by ';'"),
        ),
        (
            "v;mu\n1e-3;0,05\n0,025;0,125\n",
            Some("columns separated by ';', decimal commas read as decimal points"),
        ),
        (
            "v\tmu\n1e-3\t0,05\n0,025\t0,125\n",
            Some("columns separated by tab, decimal commas read as decimal points"),
        ),
        (
            "v\tmu\n1E-03\t0.05\n2,5E-02\t0.125\n",
            Some("columns separated by tab, decimal commas read as decimal points"),
        ),
        (
            "\"v\";\"mu\"\n\"1e-3\";\"0,05\"\n\"0,025\";\"0,125\"\n",
            Some("columns separated by ';', decimal commas read as decimal points"),
        ),
    ] {
        let t = parse_str(text).unwrap_or_else(|e| panic!("{text:?}: {e:#}"));
        assert_eq!((t.speeds.clone(), t.friction.clone()), expected, "{text:?}");
        assert_eq!(
            t.notes,
            note.into_iter().map(String::from).collect::<Vec<_>>()
        );
    }
    // CR line endings (old Mac exports) and CRLF.
    for text in [
        "v;mu\r1e-3;0,05\r0,025;0,125\r",
        "v;mu\r\n1e-3;0,05\r\n0,025;0,125\r\n",
    ] {
        let t = parse_str(text).unwrap();
        assert_eq!((t.speeds, t.friction), expected, "{text:?}");
    }
}

#[test]
fn decimal_commas_in_a_comma_delimited_file_are_refused() {
    let m = message("v,mu\n0,001,0,05\n");
    assert!(
        m.contains("line 2: malformed row: 4 fields, the header (line 1) has 2")
            && m.contains("decimal commas (0,0123), a comma-delimited file is ambiguous"),
        "{m}"
    );
    let m = message("v,mu\n\"0,001\",\"0,05\"\n");
    assert!(
        m.contains(
            "line 2: column `v`: \"0,001\": a decimal comma in a comma-delimited file is ambiguous"
        ),
        "{m}"
    );
}

/// (header, cell) → value of the one column read, with the note.
fn one(header: &str, cell: &str) -> (DataTable, f64) {
    let quantity = headers::classify(header).quantity();
    let text = match quantity {
        Some(Quantity::Speed) => format!("{header};mu\n{cell};0,1\n"),
        Some(Quantity::Friction) => format!("v;{header}\n1;{cell}\n"),
        _ => format!("v;mu;{header}\n1;0,1;{cell}\n"),
    };
    let t = parse_str(&text).unwrap_or_else(|e| panic!("{text:?}: {e:#}"));
    let value = match quantity {
        Some(Quantity::Speed) => t.speeds[0],
        Some(Quantity::Friction) => t.friction[0],
        _ => t.temperature.as_ref().unwrap()[0],
    };
    (t, value)
}

#[test]
fn header_aliases_and_unit_conversions() {
    let cases: [(&str, &str, f64, Option<&str>); 20] = [
        ("v", "0,5", 0.5, None),
        (
            "v_m_s",
            "0,5",
            0.5,
            Some("column \"v_m_s\" read as v in m/s"),
        ),
        (
            "v_mm_s",
            "12,5",
            0.0125,
            Some("column \"v_mm_s\" read as v in mm/s, converted to m/s (×1e-3)"),
        ),
        (
            "v_um_s",
            "3",
            3e-6,
            Some("column \"v_um_s\" read as v in µm/s, converted to m/s (×1e-6)"),
        ),
        (
            "velocity (mm/s)",
            "0,0123",
            1.23e-5,
            Some("column \"velocity (mm/s)\" read as v in mm/s, converted to m/s (×1e-3)"),
        ),
        ("speed_um_s", "1,5E+02", 1.5e-4, None),
        ("speed [m/s]", "2", 2.0, None),
        ("Speed (m/s)", "2", 2.0, None),
        ("rolling speed (mm/s)", "7", 7e-3, None),
        ("speed (cm/s)", "7", 7e-2, None),
        (
            "v (mm/min)",
            "6",
            1e-4,
            Some("column \"v (mm/min)\" read as v in mm/min, converted to m/s (×1e-3/60)"),
        ),
        (
            "speed",
            "3",
            3.0,
            Some("column \"speed\" read as v in m/s (no unit given)"),
        ),
        ("COF", "0,25", 0.25, Some("column \"COF\" read as mu")),
        ("µ", "0,25", 0.25, None),
        ("μ", "0,25", 0.25, None),
        ("friction coefficient", "0,25", 0.25, None),
        ("Friction Coefficient (-)", "0,25", 0.25, None),
        (
            "COF (%)",
            "25",
            0.25,
            Some("column \"COF (%)\" read as mu in %, converted to a fraction (×1e-2)"),
        ),
        (
            "T (K)",
            "293,15",
            20.0,
            Some("column \"T (K)\" read as T in K, converted to °C (−273.15)"),
        ),
        (
            "T_F",
            "68",
            20.0,
            Some("column \"T_F\" read as T in °F, converted to °C ((T − 32)·5/9)"),
        ),
    ];
    for (header, cell, value, note) in cases {
        let (t, read) = one(header, cell);
        assert_eq!(read, value, "{header}: {cell}");
        if let Some(note) = note {
            assert!(t.notes.iter().any(|n| n == note), "{header}: {:?}", t.notes);
        }
    }
    for (header, cell) in [
        ("T", "20"),
        ("T_C", "20"),
        ("T (°C)", "20"),
        ("T [°C]", "20"),
        ("temperature (C)", "20"),
        ("T_K", "293.15"),
        ("T (°F)", "68"),
    ] {
        assert_eq!(one(header, cell).1, 20.0, "{header}");
    }
    for header in ["sigma", "std", "sd", "mu_std", "sigma_mu", "COF std"] {
        let t = parse_str(&format!("v;mu;{header}\n1;0,5;0,01\n")).unwrap();
        assert_eq!(t.sigma, Some(vec![0.01]), "{header}");
    }
}

#[test]
fn unknown_units_and_two_columns_of_one_quantity() {
    let m = message("v_furlong_s,mu\n1,0.1\n");
    assert!(
        m.contains("line 1 (header): column \"v_furlong_s\": unknown speed unit \"furlong/s\"; units understood: m/s, cm/s, mm/s, µm/s"),
        "{m}"
    );
    let m = message("v,mu,T (R)\n1,0.1,500\n");
    assert!(
        m.contains("column \"T (R)\": unknown temperature unit \"R\"") && m.contains("K (kelvin)"),
        "{m}"
    );
    let m = message("v;mu;v_mm_s\n1;0,1;1000\n");
    assert!(
        m.contains("line 1 (header): two speed columns, \"v\" (column 1) and \"v_mm_s\" (column 3): keep one"),
        "{m}"
    );
    let m = message("v;COF;µ\n1;0,1;0,1\n");
    assert!(m.contains("two friction columns, \"COF\""), "{m}");
}

#[test]
fn empty_and_nan_cells_skip_rows_with_one_warning() {
    let text = "v;mu\n1;0,1\n2;0,2\n3;0,3\n4;0,4\n5;0,5\n;0,6\n7;0,7\n8;0,8\n9;0,9\n10;1\n11;NaN\nn/a;1,2\n14;1,4\n";
    let t = parse_str(text).unwrap();
    assert_eq!(
        t.speeds,
        [1.0, 2.0, 3.0, 4.0, 5.0, 7.0, 8.0, 9.0, 10.0, 14.0]
    );
    assert_eq!(
        warnings_but_mm(&t),
        ["skipped 3 rows with empty or NaN cells in v or mu: lines 7, 12, 13"]
    );
    assert_eq!(t.lines.len(), t.speeds.len());
    // NA, #N/A (not a comment), null, -: no value; sigma and T too.
    let t = parse_str(
        "v;mu;sigma;T\n1;0,1;0,01;20\n#N/A;0,1;0,01;20\n2;NA;0,01;20\n3;0,3;;20\n4;0,4;0,04;null\n5;0,5;-;20\n6;0,6;0,06;20\n",
    )
    .unwrap();
    assert_eq!(t.speeds, [1.0, 6.0]);
    assert_eq!(t.sigma, Some(vec![0.01, 0.06]));
    assert_eq!(t.temperature, Some(vec![20.0, 20.0]));
    assert_eq!(
        warnings_but_mm(&t),
        ["skipped 5 rows with empty or NaN cells in v, mu, sigma or T: lines 3, 4, 5, 6, 7"]
    );
    let t = parse_str("v,mu\n1e-3,0.05\nnan,0.1\n").unwrap();
    assert_eq!(
        t.warnings,
        ["skipped 1 row with empty or NaN cells in v: line 3"]
    );
    let m = message("v,mu,T\n1,0.1,\n");
    assert!(
        m.contains("no data rows left: every row has an empty or NaN cell in T (line 2)"),
        "{m}"
    );
    // Text is still an error, before the row could be skipped.
    let m = message("v;mu\nabc;\n");
    assert!(
        m.contains("line 2: column `v`: \"abc\" is not a number"),
        "{m}"
    );
}

#[test]
fn trailing_empty_columns_and_rows_of_an_excel_export() {
    let t = parse_str("v;mu;;\n1;0,1;;\n2;0,2;;\n;;;\n;;;\n").unwrap();
    assert_eq!(t.speeds, [1.0, 2.0]);
    assert!(warnings_but_mm(&t).is_empty(), "{:?}", t.warnings);
    let t = parse_str("v;mu;;\n1;0,1\n").unwrap();
    assert_eq!(t.friction, [0.1]);
    let m = message("v;mu\n1;0,1;5\n");
    assert!(
        m.contains("line 2: malformed row: 3 fields, the header (line 1) has 2")
            && !m.contains("ambiguous"),
        "{m}"
    );
}

#[test]
fn byte_order_mark_latin1_and_utf16() {
    let t = parse_str("\u{feff}v;mu\n1;0,1\n").unwrap();
    assert_eq!(t.speeds, [1.0]);
    assert_eq!(t.notes[0], "UTF-8 byte-order mark ignored");

    let mut latin1 = b"v;mu;T (".to_vec();
    latin1.push(0xB0);
    latin1.extend(b"C)\n1;0,1;25\n");
    let t = parse_bytes(latin1.clone()).unwrap();
    assert_eq!(t.temperature, Some(vec![25.0]));
    assert!(
        t.notes
            .iter()
            .any(|n| n == "not UTF-8 text (line 1 is not): read as Latin-1 (ISO 8859-1)"),
        "{:?}",
        t.notes
    );
    assert!(
        t.notes
            .iter()
            .any(|n| n == "column \"T (°C)\" read as T in °C"),
        "{:?}",
        t.notes
    );

    let mut utf16 = vec![0xFF, 0xFE];
    for unit in "v\tµ\r\n1\t0,1\r\n".encode_utf16() {
        utf16.extend(unit.to_le_bytes());
    }
    let t = parse_bytes(utf16.clone()).unwrap();
    assert_eq!((t.speeds, t.friction), (vec![1.0], vec![0.1]));
    assert!(t.notes[0].contains("UTF-16"), "{:?}", t.notes);
}

#[test]
fn title_lines_before_the_header() {
    let t = parse_str(
        "Measurement 2024-03-01\nOperator: A. B.; sample 3\n\n# comment\nSpeed (mm/s);COF;Force (N)\n1;0,1;2\n2;0,2;2\n",
    )
    .unwrap();
    assert_eq!(t.speeds, [1e-3, 2e-3]);
    assert_eq!(t.lines, [6, 7]);
    assert!(
        t.notes
            .iter()
            .any(|n| n == "header on line 5; the 2 lines above it (titles) ignored"),
        "{:?}",
        t.notes
    );
}

#[test]
fn a_units_row_below_the_header() {
    let t = parse_str("Speed;COF;Temperature\n(mm/s);[-];°C\n1;0,1;20\n").unwrap();
    assert_eq!(t.speeds, [1e-3]);
    assert_eq!(t.temperature, Some(vec![20.0]));
    assert!(
        t.notes
            .iter()
            .any(|n| n == "units from line 2, below the header")
            && t.notes
                .iter()
                .any(|n| n == "column \"Speed\" read as v in mm/s, converted to m/s (×1e-3)"),
        "{:?}",
        t.notes
    );
    let m = message("Speed;COF;T\nmm/s;-;R\n1;0,1;20\n");
    assert!(
        m.contains("line 2: column \"T\": unknown temperature unit \"R\" in the units row"),
        "{m}"
    );
}

#[test]
fn forward_output_and_time_columns() {
    let t = parse_str(
        "v,mu,sigma,mu_exact,mu_low_speed,contact_size_static,mean_pressure_static,centroid_shift,gt_alpha,T\n\
         1e-3,0.05,5e-4,0.051,0.04,1e-3,2e5,1e-5,0.1,20\n",
    )
    .unwrap();
    assert_eq!(
        (t.speeds, t.friction, t.sigma, t.temperature),
        (vec![1e-3], vec![0.05], Some(vec![5e-4]), Some(vec![20.0]))
    );
    assert!(t.notes.is_empty(), "{:?}", t.notes);
    // A lowercase t is time; so is "t (s)".
    let t = parse_str("t,v,mu\n0,1,0.1\n").unwrap();
    assert_eq!(t.temperature, None);
    let t = parse_str("t (s);v;mu;T\n0;1;0,1;25\n").unwrap();
    assert_eq!(t.temperature, Some(vec![25.0]));
    // mu.csv of a fit reads as data.
    let t = parse_str("v,mu_measured,mu_fit,sigma,residual\n1e-3,0.05,0.051,5e-4,0.02\n").unwrap();
    assert_eq!(t.friction, [0.05]);
}

/// Speeds in mm/s under a header without a unit read as m/s, three decades
/// too fast: a median above 1 m/s earns a hint naming the two spellings
/// that carry the unit, and both spellings are read as mm/s.
#[test]
fn a_unitless_speed_column_with_fast_speeds_hints_at_mm_per_s() {
    let rows = "5,0.01\n20,0.02\n100,0.03\n400,0.02\n";
    let hint = |t: &DataTable| t.warnings.iter().find(|w| w.contains("mm/s?")).cloned();
    let plain = parse_str(&format!("speed,mu\n{rows}")).unwrap();
    let warning = hint(&plain).expect("a hint for speeds of 5–400 \"m/s\"");
    assert!(
        warning.contains("the median speed of column \"speed\", which gives no unit, is 60 m/s")
            && warning.contains("name the column `v_mm_s` or `speed (mm/s)`"),
        "{warning}"
    );
    assert!(hint(&parse_str(&format!("v,mu\n{rows}")).unwrap()).is_some());
    // The spellings the hint proposes are read as mm/s, and give no hint.
    for header in ["v_mm_s,mu", "speed (mm/s),mu", "speed,mu\nmm/s,-"] {
        let table = parse_str(&format!("{header}\n{rows}")).unwrap();
        for (v, want) in table.speeds.iter().zip([5e-3, 20e-3, 0.1, 0.4]) {
            assert!((v / want - 1.0).abs() < 1e-12, "{header}: {v} for {want}");
        }
        assert_eq!(hint(&table), None, "{header}");
    }
    // A unit in m/s is the user's word: no hint, however fast.
    assert_eq!(
        hint(&parse_str(&format!("v (m/s),mu\n{rows}")).unwrap()),
        None
    );
    // Ordinary speeds in m/s without a unit: no hint.
    let slow = parse_str("speed,mu\n0.005,0.01\n0.02,0.02\n0.1,0.03\n0.4,0.02\n").unwrap();
    assert_eq!(hint(&slow), None);
}
