//! DMA isotherms of the broad rubber as an Eplexor exports them, and the
//! same numbers as a plain CSV: the fixture of the round trips that read a
//! workbook and a CSV to one master curve (io's readers, the report crate's
//! master input).

use std::f64::consts::PI;

use crate::series::{Series, wlf};
use crate::workbook::{X, texts};

/// Isotherms of the broad rubber as an Eplexor measures them: (T °C, f Hz,
/// E′ MPa, E″ MPa), WLF about 20 °C, each sweep running down in frequency.
pub fn eplexor_points(temperatures: &[f64]) -> Vec<(f64, f64, f64, f64)> {
    let series = Series::broad_rubber();
    let mut points = Vec::new();
    for &t in temperatures {
        let a = 10f64.powf(wlf(t, 20.0, 8.86, 101.6));
        for i in (0..9).rev() {
            let f = 0.1 * 10f64.powf(3.0 * f64::from(i) / 8.0);
            let (storage, loss) = series.at(2.0 * PI * f * a);
            points.push((t, f, storage / 1e6, loss / 1e6));
        }
    }
    points
}

/// The Eplexor "Excel Export" layout: title and metadata rows, a names row,
/// a units row, then the points, with the instrument's other columns
/// (time, tan δ, |E*|) beside them. `g`: shear moduli (G′, G″).
pub fn eplexor_rows(points: &[(f64, f64, f64, f64)], g: bool) -> Vec<Vec<X<'static>>> {
    use X::*;
    let (storage, loss) = if g { ("G'", "G''") } else { ("E'", "E''") };
    let mut rows = vec![
        vec![S("EPLEXOR Excel Export")],
        vec![
            S("Sample"),
            S("HN rubber"),
            E,
            S("Thickness"),
            N(2.0),
            S("mm"),
        ],
        vec![],
        texts(&["No.", "t", "T", "f", storage, loss, "tan delta", "|E*|"]),
        texts(&[
            "[-]", "[s]", "[°C]", "[Hz]", "[MPa]", "[MPa]", "[-]", "[MPa]",
        ]),
    ];
    for (i, &(t, f, s, l)) in points.iter().enumerate() {
        rows.push(vec![
            N(i as f64 + 1.0),
            N(60.0 * i as f64),
            N(t),
            N(f),
            N(s),
            N(l),
            N(l / s),
            N(s.hypot(l)),
        ]);
    }
    rows
}

/// The same numbers as a CSV with the CSV reader's unit-suffixed names.
pub fn eplexor_csv(points: &[(f64, f64, f64, f64)]) -> String {
    let mut text = String::from("T_C,f_Hz,E_storage_MPa,E_loss_MPa\n");
    for &(t, f, s, l) in points {
        text += &format!("{t:e},{f:e},{s:e},{l:e}\n");
    }
    text
}
