//! `[material.shift]` and the time–temperature shift rules of a scene's
//! material (its own, or a DMA master curve's; docs/ARCHITECTURE.md,
//! "Contract", "Scene file").

use rollfit_model::VerticalShift;
use rollfit_model::modulus::{Arrhenius, FreeShift, Wlf, WlfArrhenius};
use serde::Deserialize;

use super::values::{Real, value_of};
use super::vertical::{VerticalLawName, VerticalPoint};
use crate::error::IoError;
use rollfit_fit::master::MasterCurve;
use rollfit_fit::master::pipeline::Built;

/// Shift model names as written in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ShiftKind {
    /// Williams–Landel–Ferry: T_ref, C1, C2.
    Wlf,
    /// One log10 a_T per temperature: T_ref, log_aT = [{T, log_aT}, ..].
    Free,
    /// Arrhenius: T_ref, E_a (J/mol).
    Arrhenius,
    /// WLF above T_g, Arrhenius below: T_ref, C1, C2, T_g, E_a.
    WlfArrhenius,
}

/// `[material.shift]`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShiftSection {
    /// "wlf", "free" or "arrhenius".
    pub model: ShiftKind,
    /// Reference temperature of `[material]`, °C.
    #[serde(rename = "T_ref")]
    pub t_ref: Real,
    /// WLF C1 (dimensionless).
    #[serde(rename = "C1")]
    pub c1: Option<Real>,
    /// WLF C2, K.
    #[serde(rename = "C2")]
    pub c2: Option<Real>,
    /// Free shift: log10 a_T at each listed temperature.
    #[serde(rename = "log_aT")]
    pub log_at: Option<Vec<ShiftPoint>>,
    /// Arrhenius activation energy, J/mol (for "wlf-arrhenius", below T_g).
    #[serde(rename = "E_a")]
    pub activation_energy: Option<Real>,
    /// The junction of "wlf-arrhenius", °C.
    #[serde(rename = "T_g")]
    pub t_junction: Option<Real>,
    /// Vertical factors as a table: log10 b_T at each listed temperature
    /// (`super::vertical`; any shift model).
    #[serde(rename = "log_bT")]
    pub log_bt: Option<Vec<VerticalPoint>>,
    /// Vertical factors by a law: "density", b_T = T ρ/(T_ref ρ_ref).
    pub vertical: Option<VerticalLawName>,
    /// The density law's volumetric expansion coefficient α_V, 1/K
    /// (default 0: ρ constant).
    pub expansion: Option<Real>,
}

/// One entry of a free shift.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShiftPoint {
    /// Temperature, °C.
    #[serde(rename = "T")]
    pub t: Real,
    /// log10 a_T at that temperature.
    #[serde(rename = "log_aT")]
    pub log_at: Real,
}

/// A validated time–temperature shift: the model's own objects, so that the
/// rule for a free shift (exact at listed temperatures, linear in T between
/// them, refused outside) lives in one place, `rollfit_model`.
#[derive(Debug)]
pub(crate) enum ShiftRule {
    Wlf(Wlf),
    Free(FreeShift),
    Arrhenius(Arrhenius),
    WlfArrhenius(WlfArrhenius),
}

impl ShiftRule {
    /// log10 a_T at `temperature` (°C), by the model's rule: WLF,
    /// Arrhenius, or a free shift interpolated linearly in T between its
    /// listed temperatures (T_ref included) and never extrapolated beyond
    /// them.
    pub fn log10_shift(&self, temperature: f64) -> Result<f64, IoError> {
        let model = |error| err!("{error}");
        let shift = match self {
            ShiftRule::Wlf(wlf) => wlf.log10_shift(temperature).map_err(model)?,
            ShiftRule::Arrhenius(law) => law.log10_shift(temperature).map_err(model)?,
            ShiftRule::WlfArrhenius(law) => law.log10_shift(temperature).map_err(model)?,
            // The only refusal for a finite temperature is one outside the
            // list, which the file can fix.
            ShiftRule::Free(free) => free.log10_shift(temperature).map_err(|error| {
                err!("{error}; add a `log_aT` entry at or beyond it, or use model = \"wlf\"")
            })?,
        };
        if !shift.is_finite() {
            return Err(err!(
                "log10 a_T at T = {temperature} °C is {shift}: the shift is not defined at this \
         temperature"
            ));
        }
        Ok(shift)
    }

    /// The rule of a master curve's shift (None for one isotherm).
    pub(super) fn of_master(built: &Built<MasterCurve>) -> Result<Option<ShiftRule>, IoError> {
        use rollfit_fit::master::ShiftLaw;
        let shift = &built.master.shift;
        if shift.shifts.len() < 2 {
            return Ok(None);
        }
        let t_ref = shift.t_ref;
        let model = |error| err!("the DMA master curve's shift: {error}");
        Ok(Some(match shift.law {
            ShiftLaw::Wlf => {
                let w = shift
                    .wlf
                    .ok_or(err!("{law} fit missing", law = "WLF").internal())?;
                ShiftRule::Wlf(Wlf::new(t_ref, w.c1, w.c2).map_err(model)?)
            }
            ShiftLaw::Arrhenius => {
                let a = shift
                    .arrhenius
                    .ok_or(err!("{law} fit missing", law = "Arrhenius").internal())?;
                ShiftRule::Arrhenius(Arrhenius::new(t_ref, a.activation_energy).map_err(model)?)
            }
            ShiftLaw::WlfArrhenius => {
                let w = shift
                    .wlf_arrhenius
                    .ok_or(err!("{law} fit missing", law = "WLF–Arrhenius").internal())?;
                ShiftRule::WlfArrhenius(
                    WlfArrhenius::new(t_ref, w.c1, w.c2, w.t_junction, w.activation_energy)
                        .map_err(model)?,
                )
            }
            ShiftLaw::Free | ShiftLaw::Auto => ShiftRule::Free(
                FreeShift::new(
                    t_ref,
                    shift
                        .shifts
                        .iter()
                        .map(|s| (s.temperature, s.log_shift))
                        .collect(),
                )
                .map_err(model)?,
            ),
        }))
    }
}

impl ShiftSection {
    /// Checks that exactly the keys of the chosen shift model are present
    /// and builds the model's shift from them; the model checks the values
    /// (positive WLF constants, distinct and finite free-shift entries).
    pub(super) fn rule(&self) -> Result<ShiftRule, IoError> {
        let model = |error| err!("{error}");
        match self.model {
            ShiftKind::Wlf => {
                if self.c1.is_none() || self.c2.is_none() {
                    return Err(err!(
                        "model \"wlf\" needs the keys `C1` and `C2` (and `T_ref`)"
                    ));
                }
                if self.log_at.is_some()
                    || self.activation_energy.is_some()
                    || self.t_junction.is_some()
                {
                    return Err(err!(
                        "keys `log_aT`, `E_a` and `T_g` do not belong to model \"wlf\" (it takes T_ref, C1, C2)"
                    ));
                }
                // The model names the offending key (T_ref, C1 or C2).
                let wlf =
                    Wlf::new(self.t_ref.0, value_of(self.c1), value_of(self.c2)).map_err(model)?;
                Ok(ShiftRule::Wlf(wlf))
            }
            ShiftKind::Arrhenius => {
                if self.c1.is_some()
                    || self.c2.is_some()
                    || self.log_at.is_some()
                    || self.t_junction.is_some()
                {
                    return Err(err!(
                        "keys `C1`, `C2`, `T_g` and `log_aT` do not belong to model \"arrhenius\" (it takes T_ref, \
         E_a)"
                    ));
                }
                let energy = self.activation_energy.ok_or(err!(
                    "model \"arrhenius\" needs the key `E_a`, the activation energy in J/mol"
                ))?;
                let law = Arrhenius::new(self.t_ref.0, energy.0).map_err(model)?;
                Ok(ShiftRule::Arrhenius(law))
            }
            ShiftKind::WlfArrhenius => {
                let (Some(c1), Some(c2), Some(t_g), Some(energy)) =
                    (self.c1, self.c2, self.t_junction, self.activation_energy)
                else {
                    return Err(err!(
                        "model \"wlf-arrhenius\" needs the keys `C1`, `C2` (WLF about T_ref, above T_g), `T_g` \
         (the junction, °C) and `E_a` (J/mol, below T_g), and `T_ref`"
                    ));
                };
                if self.log_at.is_some() {
                    return Err(err!(
                        "key `log_aT` does not belong to model \"wlf-arrhenius\" (it takes T_ref, C1, C2, T_g, E_a)"
                    ));
                }
                let law =
                    WlfArrhenius::new(self.t_ref.0, c1.0, c2.0, t_g.0, energy.0).map_err(model)?;
                Ok(ShiftRule::WlfArrhenius(law))
            }
            ShiftKind::Free => {
                if self.c1.is_some()
                    || self.c2.is_some()
                    || self.activation_energy.is_some()
                    || self.t_junction.is_some()
                {
                    return Err(err!(
                        "keys `C1`, `C2`, `T_g` and `E_a` do not belong to model \"free\" (it takes T_ref, log_aT)"
                    ));
                }
                let listed = self.log_at.as_deref().ok_or(err!("model \"free\" needs the key `log_aT`, one entry per measured temperature, e.g. log_aT \
         = [{{ T = 0.0, log_aT = 2.1 }}, {{ T = 40.0, log_aT = -1.3 }}]"))?;
                let entries = listed.iter().map(|p| (p.t.0, p.log_at.0)).collect();
                // The model's "entry i" is the i-th element of `log_aT`.
                let free = FreeShift::new(self.t_ref.0, entries)
                    .map_err(|error| err!("`log_aT`: {error}"))?;
                Ok(ShiftRule::Free(free))
            }
        }
    }

    /// The section's vertical factors (None: b_T = 1), checked as
    /// [`super::vertical::rule`] says.
    pub(crate) fn vertical_rule(&self) -> Result<Option<VerticalShift>, IoError> {
        super::vertical::rule(
            self.t_ref.0,
            self.log_bt.as_deref(),
            self.vertical,
            self.expansion.map(|r| r.0),
        )
    }

    /// Checks the section by building its shift and vertical factors.
    pub(super) fn check(&self) -> Result<(), IoError> {
        self.rule()?;
        self.vertical_rule().map(|_| ())
    }
}
