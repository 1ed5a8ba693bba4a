//! The vertical factors of `[material.shift]` (docs/ARCHITECTURE.md,
//! "Contract", "Scene file"): E*(ω, T) = b_T E*_ref(ω a_T), b_T from
//!
//! - a table, `log_bT = [{ T = 0.0, log_bT = -0.03 }, ..]` (log10 b_T per
//!   temperature, °C; T_ref counts as listed with 0; linear in T between
//!   listed temperatures; a temperature outside them is refused), as
//!   `rollfit master --vertical` writes it;
//! - or a law, `vertical = "density"`: b_T = T ρ(T)/(T_ref ρ_ref) (Ferry
//!   ch. 11, T in K), with `expansion` the volumetric expansion coefficient
//!   α_V (1/K; default 0, ρ constant).
//!
//! Either goes with every shift model; neither means b_T = 1. The rules
//! are the model's ([`rollfit_model::VerticalShift`]); a `dma` material's
//! b_T, found from its isotherms with `vertical = true`, is the table of
//! its master curve.

use rollfit_model::VerticalShift;
use serde::Deserialize;

use super::values::Real;
use crate::error::IoError;
use rollfit_fit::master::MasterCurve;
use rollfit_fit::master::pipeline::Built;

/// Vertical-factor law names as written in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum VerticalLawName {
    /// b_T = T ρ(T)/(T_ref ρ_ref).
    Density,
}

/// One entry of a table of vertical factors.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VerticalPoint {
    /// Temperature, °C.
    #[serde(rename = "T")]
    pub t: Real,
    /// log10 b_T at that temperature.
    #[serde(rename = "log_bT")]
    pub log_bt: Real,
}

/// The vertical factors of a `[material.shift]` section (None: b_T = 1),
/// after checking that at most one form is given and `expansion` (α_V,
/// 1/K) only with the density law. `t_ref` in °C.
pub(crate) fn rule(
    t_ref: f64,
    log_bt: Option<&[VerticalPoint]>,
    law: Option<VerticalLawName>,
    expansion: Option<f64>,
) -> Result<Option<VerticalShift>, IoError> {
    match (log_bt, law, expansion) {
        (Some(_), Some(_), _) => Err(err!(
            "give the vertical factors either as a table `log_bT = [{{ T = .., log_bT = .. }}, ..]` \
         or as the law vertical = \"density\", not both"
        )),
        (Some(_), None, Some(_)) | (None, None, Some(_)) => Err(err!(
            "`expansion` (the volumetric expansion coefficient, 1/K) belongs to vertical = \
         \"density\"; add it, or remove `expansion`"
        )),
        (Some(listed), None, None) => {
            let entries = listed.iter().map(|p| (p.t.0, p.log_bt.0)).collect();
            // The model's "entry i" is the i-th element of `log_bT`.
            VerticalShift::table(t_ref, entries)
                .map(Some)
                .map_err(|error| err!("`log_bT`: {error}"))
        }
        (None, Some(VerticalLawName::Density), expansion) => {
            VerticalShift::density(t_ref, expansion.unwrap_or(0.0))
                .map(Some)
                .map_err(|error| err!("{error}"))
        }
        (None, None, None) => Ok(None),
    }
}

/// The vertical factors of a DMA master curve built with `vertical = true`
/// (None without them, or for one isotherm): its measured log10 b_T as a
/// table about its T_ref.
pub(super) fn of_master(built: &Built<MasterCurve>) -> Result<Option<VerticalShift>, IoError> {
    let shift = &built.master.shift;
    if !built.settings.vertical() || shift.shifts.len() < 2 {
        return Ok(None);
    }
    let entries = shift
        .shifts
        .iter()
        .map(|s| (s.temperature, s.log_vertical))
        .collect();
    VerticalShift::table(shift.t_ref, entries)
        .map(Some)
        .map_err(|error| err!("the DMA master curve's shift: {error}"))
}

/// log10 b_T at `temperature` (°C); a temperature outside a table says
/// which key to extend.
pub(crate) fn log10_factor(rule: &VerticalShift, temperature: f64) -> Result<f64, IoError> {
    rule.log10_factor(temperature).map_err(|error| match rule {
        VerticalShift::Table(_) => {
            err!("{error}; add a `log_bT` entry at or beyond it, or use vertical = \"density\"")
        }
        VerticalShift::Density { .. } => err!("{error}"),
    })
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use rollfit_model::{Geometry, Scene, Shifted, StandardLinearSolid, ViscoelasticModulus};

    use super::super::forward::ForwardSetup;
    use super::super::parse;

    /// A sphere on a standard linear solid with a WLF shift about 20 °C;
    /// `vertical` goes into `[material.shift]`, `temperature` into `[sweep]`.
    fn scene(vertical: &str, temperature: &str) -> String {
        format!(
            "[geometry]\nshape = \"sphere\"\nradius = 0.01\nload = 0.15\n[material]\nmodel = \
             \"sls\"\nE0 = 1e6\nE1 = 1e7\ntau = 1\n[material.shift]\nmodel = \"wlf\"\nT_ref = \
             20.0\nC1 = 8.86\nC2 = 101.6\n{vertical}\n[sweep]\nv_min = 1e-6\nv_max = 1.0\ncount \
             = 7\ntemperature = {temperature}\n"
        )
    }

    fn setup(text: &str) -> Result<ForwardSetup, crate::IoError> {
        parse(text)?.forward_setup(Path::new("scene.toml"), &|_| {})
    }

    fn error(text: &str) -> String {
        match setup(text) {
            Err(e) => crate::chain(&e),
            Ok(_) => panic!("accepted:\n{text}"),
        }
    }

    const TABLE: &str = "log_bT = [{ T = 0.0, log_bT = -0.05 }, { T = 60.0, log_bT = 0.1 }]";

    /// Each block's modulus is b_T E_ref(ω a_T), b_T from the table (linear
    /// in T, 0 at T_ref) — checked against the reference solid directly —
    /// and μ equals μ of the unscaled shifted solid under the load / b_T.
    #[test]
    fn a_table_scales_each_block() {
        let s = setup(&scene(TABLE, "[0.0, 20.0, 40.0, 60.0]")).unwrap();
        let sls = StandardLinearSolid::new(1e6, 1e7, 1.0).unwrap();
        for (block, expected) in s.blocks.iter().zip([-0.05, 0.0, 0.05, 0.1]) {
            let shift = block.shift.unwrap();
            assert!((shift.log10_b_t - expected).abs() < 1e-15, "{shift:?}");
            let (a, b) = (10f64.powf(shift.log10_a_t), 10f64.powf(shift.log10_b_t));
            for w in [1e-3, 0.2, 30.0] {
                let got = block.scene.material().modulus(w);
                let direct = sls.modulus(w * a) * b;
                assert!((got - direct).norm() <= 1e-14 * direct.norm(), "{w}");
            }
            let lighter = Scene::new(
                Geometry {
                    load: 0.15 / b,
                    ..*block.scene.geometry()
                },
                *block.scene.substrate(),
                block.scene.contact(),
                Shifted::new(sls.clone(), shift.log10_a_t).unwrap(),
            )
            .unwrap();
            let (x, y) = (
                block.scene.friction_sweep(&s.speeds).unwrap(),
                lighter.friction_sweep(&s.speeds).unwrap(),
            );
            for (x, y) in x.iter().zip(&y) {
                assert!((x / y - 1.0).abs() < 1e-10, "{x} vs {y}");
            }
        }
    }

    #[test]
    fn the_density_law_is_t_over_t_ref_times_the_density_ratio() {
        let s = setup(&scene("vertical = \"density\"\nexpansion = 6.5e-4", "45.0")).unwrap();
        let expected = (318.15f64 / 293.15).log10() - 6.5e-4 * 25.0 / 10f64.ln();
        let got = s.blocks[0].shift.unwrap().log10_b_t;
        assert!((got - expected).abs() < 1e-15, "{got} vs {expected}");
        // ρ constant by default.
        let s = setup(&scene("vertical = \"density\"", "45.0")).unwrap();
        let got = s.blocks[0].shift.unwrap().log10_b_t;
        assert!((got - (318.15f64 / 293.15).log10()).abs() < 1e-15);
        // Without either form, b_T = 1.
        let s = setup(&scene("", "45.0")).unwrap();
        assert_eq!(s.blocks[0].shift.unwrap().log10_b_t, 0.0);
    }

    /// Every refusal names the section and the key.
    #[test]
    fn bad_vertical_factors_are_refused_naming_the_key() {
        for (vertical, fragments) in [
            (
                "log_bT = [{ T = 0.0, log_bT = 0.1 }]\nvertical = \"density\"",
                &["[material.shift]", "either as a table `log_bT", "not both"][..],
            ),
            (
                "expansion = 6e-4",
                &["[material.shift]", "`expansion`", "vertical = \"density\""],
            ),
            (
                "vertical = \"density\"\nexpansion = 0.5",
                &["[material.shift]", "expansion = 0.5", "1/K"],
            ),
            (
                "log_bT = [{ T = 0.0, log_bT = 0.1 }, { T = 0.0, log_bT = 0.2 }]",
                &["[material.shift]", "`log_bT`", "entry 1", "listed before"],
            ),
            (
                "log_bT = [{ T = 20.0, log_bT = 0.1 }]",
                &["`log_bT`", "reference temperature", "log10 b_T must be 0"],
            ),
            (
                "log_bT = [{ T = 0.0, log_bT = inf }]",
                &["log_bT", "finite"],
            ),
            (
                "vertical = \"volume\"",
                &["unknown variant `volume`", "density"],
            ),
            ("log_bT = [{ T = 0.0, b = 0.1 }]", &["unknown field `b`"]),
        ] {
            let message = error(&scene(vertical, "10.0"));
            for fragment in fragments {
                assert!(message.contains(fragment), "{fragment:?} in {message}");
            }
        }
        // Outside the table: the sweep's entry, the key to extend.
        let message = error(&scene(TABLE, "[10.0, 70.0]"));
        for fragment in [
            "[sweep] temperature[1] = 70",
            "no vertical factor for T = 70 °C",
            "0 to 60 °C",
            "add a `log_bT` entry",
        ] {
            assert!(message.contains(fragment), "{fragment:?} in {message}");
        }
    }
}
