//! The pressure maps `rollfit forward -o OUT.csv` writes beside its CSV
//! where μ comes from the exact rolling contact (docs/ARCHITECTURE.md,
//! "Contract", "Pressure maps"): their file names and columns, defined once,
//! and their CSV text.
//!
//! Per map, at speed v (and, for a `[sweep] temperature`, at T):
//! `OUT-pressure-map-v<v>[-T<T>].csv` the pressure, `…-outline.csv` the
//! contact outline, `….png` and `….svg` its picture. v is written as the
//! CSV's numbers are (`1e-2`, the shortest digits that round-trip), T as
//! typed (`20`, `-5.5`).

use std::path::{Path, PathBuf};

use rollfit_model::exact::{ContactPressure, PressureMap};

use crate::csv_text;
use crate::error::IoError;

/// Position along the rolling direction from the body's axis, m (+: the
/// leading side, toward which the body rolls). Sphere: the cell's centre.
pub const X: &str = "x";
/// Position across the rolling direction, m (sphere only). In the pressure
/// file the cell's centre; in the outline the row's.
pub const Y: &str = "y";
/// Contact pressure, Pa: the cell's (sphere, constant over a square cell of
/// side the spacing of `x`), or p(x) (cylinder).
pub const PRESSURE: &str = "pressure";
/// Trailing edge of the contact, m from the axis (< 0 on the rolling axis).
pub const X_TRAILING: &str = "x_trailing";
/// Leading edge of the contact, m from the axis (> 0).
pub const X_LEADING: &str = "x_leading";

/// Columns of the sphere's pressure file: one row per cell in contact.
pub const SPHERE_PRESSURE_COLUMNS: [&str; 3] = [X, Y, PRESSURE];
/// Columns of the cylinder's pressure file: p(x) from the trailing to the
/// leading edge (plane strain: the same at every y).
pub const CYLINDER_PRESSURE_COLUMNS: [&str; 2] = [X, PRESSURE];
/// Columns of the sphere's outline: one row per row of cells in contact.
pub const SPHERE_OUTLINE_COLUMNS: [&str; 3] = [Y, X_TRAILING, X_LEADING];
/// Columns of the cylinder's outline: its two edges, one row.
pub const CYLINDER_OUTLINE_COLUMNS: [&str; 2] = [X_TRAILING, X_LEADING];

/// What is added to OUT's stem to name a map's files.
const STEM_INFIX: &str = "-pressure-map-v";
/// What follows the map's stem in its outline file's name.
const OUTLINE_SUFFIX: &str = "-outline";

/// The files of one pressure map beside the forward CSV.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PressureMapFiles {
    /// The pressure, CSV.
    pub pressure: PathBuf,
    /// The contact outline, CSV.
    pub outline: PathBuf,
    /// The picture, PNG.
    pub png: PathBuf,
    /// The picture, SVG.
    pub svg: PathBuf,
}

impl PressureMapFiles {
    /// The files of the map at speed `v` (m/s) and, for a sweep at a
    /// temperature, `temperature` (°C), beside the forward CSV `out`
    /// (`OUT.csv` → `OUT-pressure-map-v1e-2.csv`, …).
    pub fn beside(out: &Path, v: f64, temperature: Option<f64>) -> Self {
        let stem = out
            .file_stem()
            .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
        let mut map = format!("{stem}{STEM_INFIX}{}", csv_text::number(v));
        if let Some(t) = temperature {
            map += &format!("-T{t}");
        }
        let named = |suffix: &str, extension: &str| {
            out.with_file_name(format!("{map}{suffix}.{extension}"))
        };
        PressureMapFiles {
            pressure: named("", "csv"),
            outline: named(OUTLINE_SUFFIX, "csv"),
            png: named("", "png"),
            svg: named("", "svg"),
        }
    }

    /// The files in the order they are written.
    pub fn all(&self) -> [&Path; 4] {
        [&self.pressure, &self.outline, &self.png, &self.svg]
    }
}

/// The two CSV files of a map, encoded.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PressureMapCsv {
    /// The pressure file.
    pub pressure: Vec<u8>,
    /// The outline file.
    pub outline: Vec<u8>,
}

/// The CSV text of `map`'s pressure and outline; refuses a number that is
/// not finite, naming its column and row.
pub fn encode(map: &PressureMap) -> Result<PressureMapCsv, IoError> {
    Ok(match &map.pressure {
        ContactPressure::Cells { cells, outline, .. } => PressureMapCsv {
            pressure: csv_text::csv_bytes(
                &SPHERE_PRESSURE_COLUMNS,
                cells.iter().map(|&(x, y, p)| vec![x, y, p]),
            )?,
            outline: csv_text::csv_bytes(
                &SPHERE_OUTLINE_COLUMNS,
                outline.iter().map(|&(y, a, b)| vec![y, a, b]),
            )?,
        },
        ContactPressure::Profile {
            points,
            trailing_edge,
            leading_edge,
        } => PressureMapCsv {
            pressure: csv_text::csv_bytes(
                &CYLINDER_PRESSURE_COLUMNS,
                points.iter().map(|&(x, p)| vec![x, p]),
            )?,
            outline: csv_text::csv_bytes(
                &CYLINDER_OUTLINE_COLUMNS,
                [vec![*trailing_edge, *leading_edge]],
            )?,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_are_named_after_the_csv_speed_and_temperature() {
        let files = PressureMapFiles::beside(Path::new("out/forward.csv"), 0.01, None);
        assert_eq!(
            files.pressure,
            Path::new("out/forward-pressure-map-v1e-2.csv")
        );
        assert_eq!(
            files.outline,
            Path::new("out/forward-pressure-map-v1e-2-outline.csv")
        );
        assert_eq!(files.png, Path::new("out/forward-pressure-map-v1e-2.png"));
        assert_eq!(files.svg, Path::new("out/forward-pressure-map-v1e-2.svg"));
        let warm = PressureMapFiles::beside(Path::new("f.csv"), 3.5e-4, Some(-5.5));
        assert_eq!(warm.pressure, Path::new("f-pressure-map-v3.5e-4-T-5.5.csv"));
    }

    #[test]
    fn a_cylinder_map_has_no_y_and_one_outline_row() {
        let map = PressureMap {
            speed: 1e-3,
            mu: 1e-2,
            error_estimate: 1e-6,
            static_contact_size: 1e-3,
            load: 100.0,
            pressure: ContactPressure::Profile {
                points: vec![(-1e-3, 0.0), (0.0, 5e4), (1.2e-3, 0.0)],
                trailing_edge: -1e-3,
                leading_edge: 1.2e-3,
            },
        };
        let csv = encode(&map).unwrap();
        assert_eq!(
            String::from_utf8(csv.pressure).unwrap(),
            "x,pressure\n-1e-3,0e0\n0e0,5e4\n1.2e-3,0e0\n"
        );
        assert_eq!(
            String::from_utf8(csv.outline).unwrap(),
            "x_trailing,x_leading\n-1e-3,1.2e-3\n"
        );
    }

    #[test]
    fn a_sphere_map_refuses_a_pressure_that_is_not_finite() {
        let map = PressureMap {
            speed: 1e-3,
            mu: 1e-2,
            error_estimate: 1e-4,
            static_contact_size: 1e-3,
            load: 0.15,
            pressure: ContactPressure::Cells {
                cell: 1e-4,
                cells: vec![(0.0, 0.0, 1e5), (1e-4, 0.0, f64::NAN)],
                outline: vec![(0.0, -5e-5, 1.5e-4)],
            },
        };
        let error = encode(&map).unwrap_err().to_string();
        assert!(error.contains("pressure"), "{error}");
    }
}
