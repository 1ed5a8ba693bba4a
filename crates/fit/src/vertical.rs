//! Vertical factors in a temperature-set fit: with a scene's
//! `[material.shift]` carrying b_T (a table or the density law,
//! [`rollfit_model::VerticalShift`]), the master curve E*_ref is fitted at
//! T_ref and the modulus at each measured temperature is
//!
//! E*(ω, T) = b_T E*_ref(ω a_T).
//!
//! Method. With ν fixed, Eqs. (11) and (17) see the modulus through
//! L = E″_eff/|E_eff|² (divided by b), the Hertz size (a function of
//! load/|E|) and the load prefactor, so
//!
//! μ(v; b E, F) = μ(v; E, F/b)
//!
//! exactly (checked in `model/tests/vertical_factor.rs` to a few ulps).
//! A row measured at T is therefore the master curve at v a_T under the
//! load F/b_T: the objective keeps its parameters (the Prony series at
//! T_ref and the shift), its Jacobian keeps its form (∂μ/∂p and ∂μ/∂ln v of
//! the scene with that load), and only the load differs between groups of
//! rows. This module groups the rows by their load factor 1/b_T and
//! evaluates each group with its own scene; the shift law itself
//! (`crate::shift`) is untouched.
//!
//! Only a temperature set uses b_T: a single temperature's fit recovers
//! the modulus at that temperature. A temperature set with vertical
//! factors and `physics = "exact"` is refused ([`refuse_exact`]): the
//! defect correction's exact solves would need the same load per row.
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, Ch. 11.
//! - B.N.J. Persson, "Rolling friction for hard cylinder and sphere on
//!   viscoelastic solid", Eur. Phys. J. E 33 (2010) 327–333.

use rollfit_model::{FrictionJacobian, Geometry, Prony, Scene, VerticalShift};

use crate::data::Measurements;
use crate::error::FitError;
use crate::params::{RollingSetup, ValidFitParams};
use crate::shift::distinct_temperatures;

/// The rows of a temperature set grouped by their load factor 1/b_T.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct LoadGroups {
    /// (load factor 1/b_T, rows), factors distinct.
    groups: Vec<(f64, Vec<usize>)>,
    rows: usize,
}

/// The key a vertical rule came from, for messages.
fn key(vertical: &VerticalShift) -> &'static str {
    match vertical {
        VerticalShift::Table(_) => "log_bT",
        VerticalShift::Density { .. } => "vertical",
    }
}

impl LoadGroups {
    /// The groups of `data`'s rows under `vertical` (None without vertical
    /// factors or a temperature column: every row at the scene's load). A
    /// temperature where b_T is undefined (outside a table) is an error
    /// naming the key.
    pub(crate) fn of(
        data: &Measurements,
        vertical: Option<&VerticalShift>,
    ) -> Result<Option<LoadGroups>, FitError> {
        let (Some(vertical), Some(temps)) = (vertical, data.temperature()) else {
            return Ok(None);
        };
        let mut groups: Vec<(f64, Vec<usize>)> = Vec::new();
        for (i, &t) in temps.iter().enumerate() {
            let factor = load_factor(Some(vertical), t)?;
            // Rows of one temperature share a factor bit for bit.
            match groups.iter_mut().find(|(f, _)| *f == factor) {
                Some((_, rows)) => rows.push(i),
                None => groups.push((factor, vec![i])),
            }
        }
        Ok(Some(LoadGroups {
            groups,
            rows: temps.len(),
        }))
    }

    /// μ at `speeds` (one per row), each group from `scene_at(its load
    /// factor)`.
    pub(crate) fn friction_sweep(
        &self,
        scene_at: impl Fn(f64) -> Result<Scene<Prony>, FitError>,
        speeds: &[f64],
    ) -> Result<Vec<f64>, FitError> {
        let mut mu = vec![0.0; self.rows];
        for (factor, rows) in &self.groups {
            let at: Vec<f64> = rows.iter().map(|&i| speeds[i]).collect();
            let part = scene_at(*factor)?.friction_sweep(&at)?;
            for (&i, m) in rows.iter().zip(part) {
                mu[i] = m;
            }
        }
        Ok(mu)
    }

    /// μ and its derivatives at `speeds` (one per row), each group from
    /// `scene_at(its load factor)`, in the rows' order.
    pub(crate) fn friction_with_gradient(
        &self,
        scene_at: impl Fn(f64) -> Result<Scene<Prony>, FitError>,
        speeds: &[f64],
    ) -> Result<FrictionJacobian, FitError> {
        let mut out: Option<FrictionJacobian> = None;
        for (factor, rows) in &self.groups {
            let at: Vec<f64> = rows.iter().map(|&i| speeds[i]).collect();
            let part = scene_at(*factor)?.friction_with_gradient(&at)?;
            let np = part.parameter_count;
            let whole = out.get_or_insert_with(|| FrictionJacobian {
                mu: vec![0.0; self.rows],
                jacobian: vec![0.0; self.rows * np],
                parameter_count: np,
                d_ln_speed: vec![0.0; self.rows],
            });
            for (k, &i) in rows.iter().enumerate() {
                whole.mu[i] = part.mu[k];
                whole.d_ln_speed[i] = part.d_ln_speed[k];
                whole.jacobian[i * np..(i + 1) * np]
                    .copy_from_slice(&part.jacobian[k * np..(k + 1) * np]);
            }
        }
        out.ok_or_else(|| FitError::setting("data", "no rows to evaluate"))
    }
}

/// The scene of `setup` for `prony` at the quadrature `tolerance`, under
/// the set-up's load times `load_factor` (1/b_T of a row's temperature,
/// [`load_factor`]): by μ(v; b E, F) = μ(v; E, F/b) the friction of the
/// modulus b_T E*_ref at the set-up's load. Public so that a report draws
/// the fitted μ(v) of a temperature set as the fit computes it.
pub fn scene_under_load(
    setup: &RollingSetup,
    prony: Prony,
    tolerance: f64,
    load_factor: f64,
) -> Result<Scene<Prony>, FitError> {
    let geometry = Geometry {
        load: setup.geometry.load * load_factor,
        ..setup.geometry
    };
    Ok(Scene::new(geometry, setup.substrate, setup.contact, prony)?.with_tolerance(tolerance)?)
}

/// What a fit with vertical factors says about them (None without):
/// log10 b_T at each measured temperature of `data`; an error naming the
/// key where b_T is undefined.
pub(crate) fn note(
    data: &Measurements,
    vertical: Option<&VerticalShift>,
) -> Result<Option<String>, FitError> {
    let (Some(v), Some(_)) = (vertical, data.temperature()) else {
        return Ok(None);
    };
    let values = distinct_temperatures(data)
        .iter()
        .map(|&t| Ok(format!("{:.4} at {t} °C", log10_factor(Some(v), t)? + 0.0)))
        .collect::<Result<Vec<_>, FitError>>()?;
    Ok(Some(format!(
        "vertical factors from [material.shift] `{}` taken as known, E*(ω, T) = b_T E*_ref(ω a_T): \
         log10 b_T = {}; the master curve is at T_ref (compare and report --dma move DMA data \
         horizontally only)",
        key(v),
        values.join(", ")
    )))
}

/// `physics = "exact"` refused for a temperature set with vertical
/// factors (a single temperature ignores them).
pub(crate) fn refuse_exact(rows: &Measurements, params: &ValidFitParams) -> Result<(), FitError> {
    match &params.shift.vertical {
        Some(v) if distinct_temperatures(rows).len() > 1 => Err(FitError::setting(
            "physics",
            format!(
                "\"exact\" does not take vertical factors b_T (`{}` in [material.shift]) for a \
                 temperature set; use \"approximate\", or remove the vertical factors",
                key(v)
            ),
        )),
        _ => Ok(()),
    }
}

/// The load factor 1/b_T at `t` (°C) under `vertical` (1 without): the
/// factor of the set-up's load under which the master curve gives the
/// friction at `t` ([`scene_under_load`]). An error naming the key where
/// b_T is undefined or gives no usable factor.
pub fn load_factor(vertical: Option<&VerticalShift>, t: f64) -> Result<f64, FitError> {
    let log_b = log10_factor(vertical, t)?;
    let factor = 10f64.powf(-log_b);
    match vertical {
        Some(v) if !factor.is_normal() => Err(FitError::setting(
            key(v),
            format!("log10 b_T = {log_b} at T = {t} °C gives no usable factor"),
        )),
        _ => Ok(factor),
    }
}

/// log10 b_T at `t` (°C) under `vertical` (0 without), as a fit setting's
/// error when undefined there.
pub(crate) fn log10_factor(vertical: Option<&VerticalShift>, t: f64) -> Result<f64, FitError> {
    match vertical {
        None => Ok(0.0),
        Some(v) => v
            .log10_factor(t)
            .map_err(|e| FitError::setting(key(v), e.to_string())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::{FitParams, Physics, ShiftSettings, example_setup};

    fn table() -> VerticalShift {
        VerticalShift::table(20.0, vec![(0.0, -0.1), (40.0, 0.1)]).unwrap()
    }

    fn params(t_ref: Option<f64>, physics: Physics) -> FitParams {
        FitParams {
            shift: ShiftSettings {
                t_ref,
                vertical: Some(table()),
                ..ShiftSettings::default()
            },
            physics,
            ..FitParams::default()
        }
    }

    fn refusal(p: FitParams) -> String {
        match p.check(example_setup()) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("accepted"),
        }
    }

    /// b_T = 1 at its own T_ref: the fit must be at that temperature; the
    /// exact physics does not take vertical factors for a temperature set.
    #[test]
    fn settings_are_checked_naming_the_key() {
        assert!(
            params(Some(20.0), Physics::Approximate)
                .check(example_setup())
                .is_ok()
        );
        for t_ref in [Some(25.0), None] {
            let m = refusal(params(t_ref, Physics::Approximate));
            assert!(
                m.contains("T_ref") && m.contains("relative to T_ref = 20 °C"),
                "{m}"
            );
        }
        let exact = params(Some(20.0), Physics::Exact)
            .check(example_setup())
            .unwrap();
        let speeds: Vec<f64> = (0..8).map(|i| 10f64.powi(i % 4 - 4)).collect();
        let set = |temps: Vec<f64>| {
            Measurements::new(speeds.clone(), vec![0.01; 8], None, Some(temps)).unwrap()
        };
        let two = set(vec![0.0, 0.0, 0.0, 0.0, 40.0, 40.0, 40.0, 40.0]);
        let m = refuse_exact(&two, &exact).unwrap_err().to_string();
        assert!(m.contains("physics") && m.contains("log_bT"), "{m}");
        assert!(refuse_exact(&set(vec![40.0; 8]), &exact).is_ok());
    }

    /// Rows group by temperature; a temperature outside the table is
    /// refused naming `log_bT`.
    #[test]
    fn rows_group_by_their_load_factor() {
        let speeds: Vec<f64> = (0..12).map(|i| 10f64.powi(i % 4 - 4)).collect();
        let temps: Vec<f64> = (0..12).map(|i| [0.0, 20.0, 40.0][i / 4]).collect();
        let data = Measurements::new(speeds.clone(), vec![0.01; 12], None, Some(temps)).unwrap();
        let groups = LoadGroups::of(&data, Some(&table())).unwrap().unwrap();
        let expected = [
            (10f64.powf(0.1), vec![0, 1, 2, 3]),
            (1.0, vec![4, 5, 6, 7]),
            (10f64.powf(-0.1), vec![8, 9, 10, 11]),
        ];
        assert_eq!(groups.groups.len(), 3);
        for ((f, rows), (g, expected_rows)) in groups.groups.iter().zip(&expected) {
            assert!((f / g - 1.0).abs() < 1e-15);
            assert_eq!(rows, expected_rows);
        }
        assert!(LoadGroups::of(&data, None).unwrap().is_none());
        let hot = Measurements::new(speeds, vec![0.01; 12], None, Some(vec![50.0; 12])).unwrap();
        let m = LoadGroups::of(&hot, Some(&table()))
            .unwrap_err()
            .to_string();
        assert!(m.contains("log_bT") && m.contains("T = 50 °C"), "{m}");
    }
}
