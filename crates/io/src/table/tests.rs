//! The modulus-table reader: the plain form, every DMA form, the refusals
//! and their messages, and the contact-map explanation.

use std::f64::consts::PI;
use std::path::Path;

use super::*;
use crate::chain;

fn parse_str(text: &str) -> Result<ModulusTable, IoError> {
    parse(text)
}

fn message(text: &str) -> String {
    chain(&parse_str(text).unwrap_err())
}

#[test]
fn reads_omega_and_hertz_with_comments_and_extra_columns() {
    let t = parse_str("# master curve\nomega,E_storage,E_loss,tan_delta\n1,2e6,1e5,0.05\n# mid\n10, 3e6, 2e5, 0.07\n").unwrap();
    assert_eq!(t.omega, vec![1.0, 10.0]);
    assert_eq!(t.storage, vec![2e6, 3e6]);
    assert_eq!(t.loss, vec![1e5, 2e5]);
    let t = parse_str("f,E_loss,E_storage\n1,1e5,2e6\n2,1e5,2e6\n").unwrap();
    assert!((t.omega[0] - 2.0 * PI).abs() < 1e-15);
    assert_eq!(t.storage[1], 2e6);
}

#[test]
fn errors_name_the_line_and_column() {
    let m = message("omega,E_storage,E_loss\n1,2e6,1e5\n10,abc,2e5\n");
    assert!(
        m.contains("line 3") && m.contains("E_storage") && m.contains("abc"),
        "{m}"
    );
    let m = message("omega,E_storage,E_loss\n1,2e6,1e5\n1,2e6,2e5\n");
    assert!(m.contains("line 3") && m.contains("increasing"), "{m}");
    let m = message("omega,E_storage,E_loss\n1,2e6,1e5\n2,2e6,0\n");
    assert!(
        m.contains("line 3") && m.contains("E_loss") && m.contains("greater than zero"),
        "{m}"
    );
    let m = message("omega,E_storage,E_loss\n1,2e6,nan\n2,2e6,1\n");
    assert!(m.contains("line 2") && m.contains("finite"), "{m}");
}

#[test]
fn lines_are_counted_below_comments_blank_lines_and_in_crlf_files() {
    for (text, line) in [
        ("omega,E_storage,E_loss\n1,2e6,1e5\n# mid\n10,abc,2e5\n", 4),
        ("omega,E_storage,E_loss\r\n1,2e6,1e5\r\n10,abc,2e5\r\n", 3),
        ("omega,E_storage,E_loss\n1,2e6,1e5\n\n\n10,abc,2e5\n", 5),
        (
            "# a\n# b\nomega,E_storage,E_loss\n1,2e6,1e5\n10,abc,2e5\n",
            5,
        ),
    ] {
        let m = message(text);
        assert!(m.starts_with(&format!("line {line}: ")), "{text:?}: {m}");
    }
    let t =
        parse_str("# a\r\nomega,E_storage,E_loss\r\n1,2e6,1e5\r\n# b\r\n\r\n2,2e6,1e5").unwrap();
    assert_eq!(t.lines, vec![3, 6]);
}

#[test]
fn rejects_empty_and_incomplete_tables() {
    assert!(message("").contains("empty"));
    assert!(message("# nothing\n").contains("empty"));
    assert!(message("omega,E_storage,E_loss\n").contains("0 data row"));
    assert!(message("omega,E_storage\n1,2\n").contains("E_loss"));
    assert!(message("w,E_storage,E_loss\n1,2,3\n").contains("frequency column"));
    assert!(message("omega,f,E_storage,E_loss\n1,2,3,4\n").contains("both"));
    assert!(message("f,G_storage,G_loss\n1,2,3\n").contains("2(1 + ν) G"));
    assert!(message("omega,E_storage,E_loss\n1,2,3\n2,3\n").contains("malformed row"));
}

// ------------------------------------------------------ every DMA form

/// A folder of its own under the system's temporary folder, removed on
/// drop.
struct TempDir(std::path::PathBuf);

impl TempDir {
    fn new(name: &str) -> TempDir {
        let path =
            std::env::temp_dir().join(format!("rollfit-table-file-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&path);
        std::fs::create_dir_all(&path).unwrap();
        TempDir(path)
    }

    fn write(&self, name: &str, text: &str) -> std::path::PathBuf {
        let path = self.0.join(name);
        std::fs::write(&path, text).unwrap();
        path
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A standard linear solid, Young's (E′, E″) in Pa at ω rad/s.
fn sls(omega: f64) -> (f64, f64) {
    let (e0, e1, tau) = (2e6, 2e8, 1e-2);
    let x = omega * tau;
    let d = 1.0 + x * x;
    (e0 + (e1 - e0) * x * x / d, (e1 - e0) * x / d)
}

const OMEGAS: [f64; 5] = [0.5, 3.0, 20.0, 150.0, 900.0];

fn relative(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

fn assert_same_curve(name: &str, t: &ModulusTable, reference: &ModulusTable) {
    assert_eq!(t.omega.len(), reference.omega.len(), "{name}");
    for i in 0..t.omega.len() {
        for (a, b, what) in [
            (t.omega[i], reference.omega[i], "ω"),
            (t.storage[i], reference.storage[i], "E′"),
            (t.loss[i], reference.loss[i], "E″"),
        ] {
            assert!(relative(a, b) < 1e-12, "{name}: row {i}: {what} {a} vs {b}");
        }
    }
}

/// The equivalent TRIOS LIMS export of a rotational rheometer: shear
/// moduli (G = E/3) in MPa and kPa, one isotherm with ±0.02 K of
/// controller scatter, the sweep running down in frequency as
/// instruments run it.
fn trios_shear(temperatures: &[f64]) -> String {
    let mut text = String::from(
        "[Version]\nTA Instruments LIMS export format version\t0\n[Header]\n\
         Document ID\trollfit table test\n[Parameters]\n[Parameters: File Parameters]\n\
         Instrument type\tAresG2\n",
    );
    for &t in temperatures {
        text.push_str(&format!(
            "[Step]\nStep name\tFrequency sweep ({t:.1} °C)\nNumber of points\t{}\n\
             Variables\tTemperature\tAngular frequency\tOscillation torque\t\
             Storage modulus\tLoss modulus\tTan(delta)\n\
             Units\t°C\trad/s\tµN.m\tMPa\tkPa\t\n",
            OMEGAS.len()
        ));
        for (k, &omega) in OMEGAS.iter().enumerate().rev() {
            let (s, l) = sls(omega);
            let scatter = [0.01, -0.01, 0.02, 0.0, -0.02][k];
            text.push_str(&format!(
                "Data point\t{}\t{omega:e}\t100\t{:e}\t{:e}\t{:e}\n",
                t + scatter,
                s / 3e6,
                l / 3e3,
                l / s
            ));
        }
    }
    text
}

#[test]
fn every_dma_form_gives_the_plain_tables_curve() {
    let dir = TempDir::new("forms");
    let rows = |row: &dyn Fn(f64, f64, f64) -> String| -> String {
        OMEGAS
            .iter()
            .map(|&w| {
                let (s, l) = sls(w);
                row(w, s, l) + "\n"
            })
            .collect()
    };
    let plain = dir.write(
        "plain.csv",
        &format!(
            "omega,E_storage,E_loss\n{}",
            rows(&|w, s, l| format!("{w:e},{s:e},{l:e}"))
        ),
    );
    let reference = read(&plain, 0.5, None).unwrap();
    assert_eq!(reference.lines, vec![2, 3, 4, 5, 6]);
    assert!(reference.notes.is_empty(), "{:?}", reference.notes);

    // Shear with unit suffixes, in Hz, with a comment above the header.
    let shear = dir.write(
        "shear.csv",
        &format!(
            "# G from a parallel-plate rheometer\nf_Hz,G_storage_kPa,G_loss_kPa\n{}",
            rows(&|w, s, l| format!("{:e},{:e},{:e}", w / (2.0 * PI), s / 3e3, l / 3e3))
        ),
    );
    let t = read(&shear, 0.5, None).unwrap();
    assert_same_curve("shear.csv", &t, &reference);
    assert_eq!(t.lines, vec![3, 4, 5, 6, 7]);
    assert!(
        t.notes
            .iter()
            .any(|n| n.contains("ν = 0.5") && n.contains("[substrate] poisson")),
        "{:?}",
        t.notes
    );

    // One temperature in a T column, the sweep running downwards.
    let mut text = String::from("T,omega,E_storage,E_loss\n");
    for &w in OMEGAS.iter().rev() {
        let (s, l) = sls(w);
        text.push_str(&format!("23,{w:e},{s:e},{l:e}\n"));
    }
    let one_t = dir.write("one_t.csv", &text);
    let t = read(&one_t, 0.5, None).unwrap();
    assert_same_curve("one_t.csv", &t, &reference);
    assert_eq!(t.lines, vec![6, 5, 4, 3, 2]);
    assert!(
        t.notes.iter().any(|n| n.contains("all points at 23 °C")),
        "{:?}",
        t.notes
    );

    // TRIOS: shear from the torque variable, one isotherm.
    let trios = dir.write("sweep.txt", &trios_shear(&[20.0]));
    let t = read(&trios, 0.5, None).unwrap();
    assert_same_curve("sweep.txt", &t, &reference);
    let mut data_lines: Vec<usize> = trios_shear(&[20.0])
        .lines()
        .enumerate()
        .filter(|(_, l)| l.starts_with("Data point"))
        .map(|(i, _)| i + 1)
        .collect();
    data_lines.reverse();
    assert_eq!(t.lines, data_lines);
    // Shear from the torque variable, said in the scene's words.
    assert!(
        t.notes.iter().any(|n| n.contains("shear")
            && n.contains("Oscillation torque")
            && n.contains("[material] modulus = \"young\"")),
        "{:?}",
        t.notes
    );
    // Neither torque nor force nor a known instrument: the file cannot
    // say, and the error names the scene's key.
    let unknown = trios_shear(&[20.0])
        .replace("AresG2", "Mystery 9000")
        .replace("Oscillation torque", "Displacement");
    let m = chain(&read(&dir.write("unknown.txt", &unknown), 0.5, None).unwrap_err());
    assert!(
        m.contains("unknown.txt") && m.contains("[material] modulus = \"shear\""),
        "{m}"
    );
    // The override reads the same file as Young's moduli (3× less).
    let t = read(&trios, 0.5, Some(ModulusKind::Young)).unwrap();
    assert!(relative(3.0 * t.storage[0], reference.storage[0]) < 1e-12);

    // ν other than ½ for shear: E = 2(1 + ν) G.
    let t = read(&shear, 0.3, None).unwrap();
    assert!(relative(t.loss[2], reference.loss[2] * 2.6 / 3.0) < 1e-12);
}

#[test]
fn the_header_decides_the_reader() {
    for (header, plain) in [
        ("omega,E_storage,E_loss", true),
        ("f,E_loss,E_storage,tan_delta", true),
        // A fit's modulus.csv.
        (
            "omega,E_storage,E_loss,tan_delta,abs_E,E_storage_sigma,E_loss_sigma",
            true,
        ),
        // Incomplete or misspelt plain tables keep the plain messages.
        ("omega,E_storage", true),
        ("w,E_storage,E_loss", true),
        ("omega,f,E_storage,E_loss", true),
        ("omega,E_storage,E_loss,T", false),
        ("T_K,omega,E_storage,E_loss", false),
        ("f,G_storage,G_loss", false),
        ("omega_rad_s,E_storage,E_loss", false),
        ("omega,E_storage_MPa,E_loss_MPa", false),
        ("f_rad_s,E_storage,E_loss", false),
        ("[Version]", false),
        ("freq,storage,loss", false),
    ] {
        assert_eq!(
            is_plain(&format!("# c\n{header}\n1,2,3\n")),
            plain,
            "{header:?}"
        );
    }
    // No header at all: the plain reader's "empty".
    assert!(is_plain("") && is_plain("# nothing\n") && is_plain("\n\n"));
}

#[test]
fn poisson_matters_only_for_shear_moduli() {
    let dir = TempDir::new("poisson");
    let shear = dir.write("g.csv", "omega,G_storage,G_loss\n1,1e6,1e5\n10,2e6,2e5\n");
    let m = chain(&read(&shear, 0.7, None).unwrap_err());
    assert!(
        m.contains("g.csv") && m.contains("[substrate] poisson") && m.contains("0.7"),
        "{m}"
    );
    let young = dir.write(
        "e.csv",
        "omega,E_storage_MPa,E_loss_MPa\n1,1,0.1\n10,2,0.2\n",
    );
    let t = read(&young, 0.7, None).unwrap();
    assert_eq!(t.storage, vec![1e6, 2e6]);
}

#[test]
fn several_temperatures_are_refused_naming_them() {
    let dir = TempDir::new("isotherms");
    let mut text = String::from("T_C,omega,E_storage,E_loss\n");
    for (t, w) in [
        (20.0, 1.0),
        (20.2, 10.0),
        (40.0, 1.0),
        (40.0, 10.0),
        (60.0, 1.0),
    ] {
        let (s, l) = sls(w);
        text.push_str(&format!("{t},{w},{s:e},{l:e}\n"));
    }
    let path = dir.write("isotherms.csv", &text);
    let m = chain(&read(&path, 0.5, None).unwrap_err());
    for fragment in [
        "isotherms.csv",
        "3 temperatures",
        "20.1 °C (2 point(s), lines 2–3)",
        "40 °C (2 point(s), lines 4–5)",
        "60 °C (1 point(s), lines 6–6)",
        "[material] model = \"dma\"",
        "rollfit master",
    ] {
        assert!(m.contains(fragment), "{fragment:?} not in {m}");
    }
    // The shifted points of `rollfit master`: its modulus.csv is meant.
    let path = dir.write(
        "master.csv",
        "omega,E_storage,E_loss,tan_delta,T,omega_measured\n\
         1,2e6,2e5,0.1,20,1\n2,2e6,2e5,0.1,40,20\n",
    );
    let m = chain(&read(&path, 0.5, None).unwrap_err());
    assert!(
        m.contains("2 temperatures") && m.contains("modulus.csv"),
        "{m}"
    );
    // The same in a TRIOS export, temperatures from the Temperature
    // variable.
    let path = dir.write("isotherms.txt", &trios_shear(&[20.0, 40.0]));
    let m = chain(&read(&path, 0.5, None).unwrap_err());
    assert!(
        m.contains("2 temperatures: 20 °C") && m.contains("40 °C"),
        "{m}"
    );
}

#[test]
fn a_repeated_frequency_is_refused_naming_both_lines() {
    let dir = TempDir::new("repeated");
    let path = dir.write(
        "g.csv",
        "omega,G_storage,G_loss\n10,2e6,2e5\n1,1e6,1e5\n# again\n10,2.1e6,2.2e5\n",
    );
    let m = chain(&read(&path, 0.5, None).unwrap_err());
    assert!(
        m.contains("g.csv, lines 2 and 5") && m.contains("ω = 10"),
        "{m}"
    );
    // The plain reader as before: the second line, in file order.
    let path = dir.write("e.csv", "omega,E_storage,E_loss\n1,2e6,1e5\n1,2e6,2e5\n");
    let m = chain(&read(&path, 0.5, None).unwrap_err());
    assert!(m.contains("line 3") && m.contains("line 2"), "{m}");
}

#[test]
fn a_point_without_loss_is_dropped_with_its_line() {
    let dir = TempDir::new("dropped");
    let path = dir.write(
        "g.csv",
        "omega,G_storage_MPa,G_loss_MPa\n1,1,0.1\n10,2,-0.03\n100,3,0.4\n",
    );
    let t = read(&path, 0.5, None).unwrap();
    assert_eq!(t.omega, vec![1.0, 100.0]);
    assert_eq!(t.lines, vec![2, 4]);
    assert!(
        t.notes
            .iter()
            .any(|n| n.contains("line 3") && n.contains("dropped")),
        "{:?}",
        t.notes
    );
    // Too few left to interpolate.
    let path = dir.write("one.csv", "omega,G_storage,G_loss\n1,1e6,1e5\n10,2e6,0\n");
    let m = chain(&read(&path, 0.5, None).unwrap_err());
    assert!(m.contains("1 usable data row"), "{m}");
}

#[test]
fn dma_errors_name_the_table_and_line() {
    let dir = TempDir::new("errors");
    let path = dir.write("g.csv", "omega,G_storage,G_loss\n1,1e6,1e5\n10,abc,2e5\n");
    let m = chain(&read(&path, 0.5, None).unwrap_err());
    assert!(
        m.starts_with("modulus table ") && m.contains("g.csv, line 3") && m.contains("abc"),
        "{m}"
    );
    let m = chain(&read(&dir.0.join("absent.csv"), 0.5, None).unwrap_err());
    assert!(m.contains("cannot read modulus table"), "{m}");
}

// ------------------------------------------------- the contact map

/// A broad rubber: Prony series of Young's modulus, E′, E″ in Pa.
fn broad_rubber(omega: f64) -> (f64, f64) {
    let e0 = 3e6;
    let terms = [
        (1e-8, 5e8),
        (1e-7, 4e8),
        (1e-6, 3e8),
        (1e-5, 2e8),
        (1e-4, 1e8),
        (1e-3, 4e7),
        (1e-2, 1.5e7),
        (1e-1, 5e6),
    ];
    terms.iter().fold((e0, 0.0), |(s, l), &(tau, h)| {
        let x = omega * tau;
        let d = 1.0 + x * x;
        (s + h * x * x / d, l + h * x / d)
    })
}

/// The file lines of the row pairs an explanation lists
/// ("  line A → line B: …").
fn listed_pairs(text: &str) -> Vec<(usize, usize)> {
    text.lines()
        .filter_map(|l| {
            let rest = l.strip_prefix("  line ")?;
            let (a, rest) = rest.split_once(" → line ")?;
            let (b, _) = rest.split_once(':')?;
            Some((a.parse().ok()?, b.parse().ok()?))
        })
        .collect()
}

#[test]
fn noisy_overlapping_isotherms_fail_the_contact_map_at_lines_the_explanation_names() {
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;
    use rand_distr::{Distribution, StandardNormal};
    use rollfit_model::{ContactSize, Geometry, Scene, Shape, Substrate, TabulatedModulus};

    // Nine isotherms of 0.1 … 100 rad/s, 5 points a decade, 10 K apart,
    // shifted by WLF (each overlaps its neighbours by a decade or
    // more), with 4 % scatter in E′ and E″: concatenated and sorted,
    // as a user builds a "master curve" by hand.
    let mut rng = ChaCha8Rng::seed_from_u64(20240611);
    let mut rows = Vec::new();
    for t in (-3..=5).map(|k| 10.0 * f64::from(k)) {
        let log_a_t = -8.86 * (t - 20.0) / (101.6 + t - 20.0);
        for k in 0..16 {
            let omega = 10f64.powf(-1.0 + f64::from(k) / 5.0 + log_a_t);
            let (s, l) = broad_rubber(omega);
            let z1: f64 = StandardNormal.sample(&mut rng);
            let z2: f64 = StandardNormal.sample(&mut rng);
            rows.push((omega, s * (1.0 + 0.04 * z1), l * (1.0 + 0.04 * z2)));
        }
    }
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut text = String::from("# nine isotherms, shifted and sorted\nomega,E_storage,E_loss\n");
    for (w, s, l) in &rows {
        text.push_str(&format!("{w:e},{s:e},{l:e}\n"));
    }
    let dir = TempDir::new("contact-map");
    let path = dir.write("master.csv", &text);
    let table = read(&path, 0.5, None).unwrap();
    assert_eq!(table.lines[0], 3);

    // The model refuses it, naming a frequency.
    let scene = Scene::new(
        Geometry {
            shape: Shape::Sphere,
            radius: 5e-3,
            load: 10.0,
        },
        Substrate {
            poisson: 0.5,
            film_thickness: None,
        },
        ContactSize::Dynamic,
        TabulatedModulus::new(
            table.omega.clone(),
            table.storage.clone(),
            table.loss.clone(),
        )
        .unwrap(),
    )
    .unwrap();
    let speeds: Vec<f64> = (0..=16)
        .map(|k| 10f64.powf(-8.0 + 0.5 * f64::from(k)))
        .collect();
    let error = scene.friction_sweep(&speeds).unwrap_err();
    let rollfit_model::ModelError::ContactMapNotIncreasing { omega, exponent } = error else {
        panic!("{error}")
    };
    assert_eq!(exponent, 3.0);

    let explained = explain_contact_map(&table, &path, omega, 3.0);
    // The rows bracketing ω.
    let k = table.omega.partition_point(|&w| w <= omega);
    assert!(0 < k && k < table.omega.len(), "{omega} outside the table");
    assert!(
        explained.contains(&format!(
            "between line {} (ω = {:.3e} rad/s",
            table.lines[k - 1],
            table.omega[k - 1]
        )) && explained.contains(&format!("and line {} (", table.lines[k])),
        "{explained}"
    );
    // The steep pairs: neighbours in the table, |E*| rising faster than
    // ω³ between them, within a decade of ω; the five nearest, in the
    // table's order.
    let abs = |i: usize| table.storage[i].hypot(table.loss[i]);
    let slope = |i: usize| (abs(i + 1) / abs(i)).ln() / (table.omega[i + 1] / table.omega[i]).ln();
    let distance = |i: usize| {
        let (lo, hi) = (table.omega[i].ln(), table.omega[i + 1].ln());
        (lo - omega.ln()).max(omega.ln() - hi).max(0.0)
    };
    let mut expected: Vec<usize> = (0..table.omega.len() - 1)
        .filter(|&i| slope(i) > 3.0 && distance(i) <= 10f64.ln())
        .collect();
    expected.sort_by(|&a, &b| distance(a).total_cmp(&distance(b)));
    assert!(!expected.is_empty(), "no steep pair near ω = {omega}");
    expected.truncate(5);
    expected.sort_unstable();
    let expected: Vec<(usize, usize)> = expected
        .iter()
        .map(|&i| (table.lines[i], table.lines[i + 1]))
        .collect();
    assert_eq!(listed_pairs(&explained), expected, "{explained}");
    // In this file (sorted, one header and one comment line) row i is
    // on line i + 3: the pairs are consecutive lines.
    assert!(expected.iter().all(|&(a, b)| b == a + 1));
    assert!(
        explained.contains("Smooth or bin the table")
            && explained.contains("[material] model = \"dma\""),
        "{explained}"
    );
}

#[test]
fn the_explanation_places_any_frequency() {
    let table = ModulusTable {
        omega: vec![1.0, 2.0, 4.0, 8.0],
        storage: vec![1e6, 1e6, 1.2e6, 1.3e6],
        loss: vec![1e5, 1e5, 1e5, 1e5],
        lines: vec![2, 3, 5, 6],
        notes: Vec::new(),
    };
    let path = Path::new("t.csv");
    let text = explain_contact_map(&table, path, 0.5, 3.0);
    assert!(
        text.contains("below the first row, line 2 (ω = 1.000e0"),
        "{text}"
    );
    let text = explain_contact_map(&table, path, 9.0, 3.0);
    assert!(text.contains("above the last row, line 6"), "{text}");
    let text = explain_contact_map(&table, path, 2.0, 3.0);
    assert!(text.contains("at line 3 (ω = 2.000e0"), "{text}");
    // Nothing steep between rows: the interpolant is blamed, the
    // steepest rows nearby listed.
    let text = explain_contact_map(&table, path, 3.0, 3.0);
    assert!(
        text.contains("between line 3")
            && text.contains("and line 5")
            && text.contains("No neighbouring rows")
            && text.contains("  line 3 → line 5:"),
        "{text}"
    );
    // A cylinder's n = 2.
    let steep = ModulusTable {
        storage: vec![1e6, 1e6, 5e6, 5e6],
        ..table
    };
    let text = explain_contact_map(&steep, path, 3.0, 2.0);
    assert!(
        text.contains("faster than ω^2") && listed_pairs(&text) == vec![(3, 5)],
        "{text}"
    );
}

/// A table whose E′ falls as ω rises is no modulus and
/// is refused at its first row beyond scatter, naming both rows; scatter
/// of a few per cent is read.
#[test]
fn a_storage_modulus_falling_with_frequency_is_refused_naming_the_rows() {
    let dir = TempDir::new("falling");
    let falling = dir.write(
        "falling.csv",
        "# E' reversed\nomega,E_storage,E_loss\n0.1,1e8,1e6\n1,9e7,1e6\n10,5e7,1e6\n100,1e6,1e6\n",
    );
    let m = chain(&read(&falling, 0.5, None).unwrap_err());
    assert!(
        m.contains(
            "falling.csv, line 5: E_storage = 5.0000e7 Pa at ω = 1.0000e1 rad/s is 50 % below \
             E_storage = 1.0000e8 Pa at line 3 (ω = 1.0000e-1 rad/s): the storage modulus of a \
             viscoelastic solid rises with frequency"
        ),
        "{m}"
    );
    // Scatter: a 15 % dip below the peak, then rising again, is read.
    let scatter = dir.write(
        "scatter.csv",
        "omega,E_storage,E_loss\n0.1,1e6,1e5\n1,1.2e6,1e5\n10,1.03e6,1e5\n100,2e6,1e5\n",
    );
    assert!(read(&scatter, 0.5, None).is_ok());
}
