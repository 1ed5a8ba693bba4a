//! `[material.shift]` and the time–temperature shift rules of a scene's
//! material (its own, or a DMA master curve's).

use anyhow::{Context, Result, anyhow, ensure};
use rollfit_model::ModelError;
use rollfit_model::modulus::{Arrhenius, FreeShift, Wlf};
use serde::Deserialize;

use super::values::{Real, value_of};
use crate::dma_master::DmaMaster;

/// Shift model names as written in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ShiftKind {
    /// Williams–Landel–Ferry: T_ref, C1, C2.
    Wlf,
    /// One log10 a_T per temperature: T_ref, log_aT = [{T, log_aT}, ..].
    Free,
    /// Arrhenius: T_ref, E_a (J/mol).
    Arrhenius,
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
    /// Arrhenius activation energy, J/mol.
    #[serde(rename = "E_a")]
    pub activation_energy: Option<Real>,
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
}

impl ShiftRule {
    /// log10 a_T at `temperature` (°C), by the model's rule: WLF,
    /// Arrhenius, or a free shift interpolated linearly in T between its
    /// listed temperatures (T_ref included) and never extrapolated beyond
    /// them.
    pub fn log10_shift(&self, temperature: f64) -> Result<f64> {
        let shift = match self {
            ShiftRule::Wlf(wlf) => wlf.log10_shift(temperature).map_err(|e| anyhow!("{e}"))?,
            ShiftRule::Arrhenius(law) => {
                law.log10_shift(temperature).map_err(|e| anyhow!("{e}"))?
            }
            // The only refusal for a finite temperature is one outside the
            // list, which the file can fix.
            ShiftRule::Free(free) => free.log10_shift(temperature).map_err(|e| {
                anyhow!("{e}; add a `log_aT` entry at or beyond it, or use model = \"wlf\"")
            })?,
        };
        ensure!(
            shift.is_finite(),
            "log10 a_T at T = {temperature} °C is {shift}: the shift is not defined at this temperature"
        );
        Ok(shift)
    }

    /// The rule of a master curve's shift (None for one isotherm).
    pub(super) fn of_master(built: &DmaMaster) -> Result<Option<ShiftRule>> {
        use rollfit_fit::master::ShiftLaw;
        let shift = &built.master.shift;
        if shift.shifts.len() < 2 {
            return Ok(None);
        }
        let t_ref = shift.t_ref;
        let model = |e: ModelError| anyhow!("the DMA master curve's shift: {e}");
        Ok(Some(match shift.law {
            ShiftLaw::Wlf => {
                let w = shift.wlf.context("WLF fit missing")?;
                ShiftRule::Wlf(Wlf::new(t_ref, w.c1, w.c2).map_err(model)?)
            }
            ShiftLaw::Arrhenius => {
                let a = shift.arrhenius.context("Arrhenius fit missing")?;
                ShiftRule::Arrhenius(Arrhenius::new(t_ref, a.activation_energy).map_err(model)?)
            }
            ShiftLaw::Free => ShiftRule::Free(
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
    pub(super) fn rule(&self) -> Result<ShiftRule> {
        match self.model {
            ShiftKind::Wlf => {
                ensure!(
                    self.c1.is_some() && self.c2.is_some(),
                    "model \"wlf\" needs the keys `C1` and `C2` (and `T_ref`)"
                );
                ensure!(
                    self.log_at.is_none() && self.activation_energy.is_none(),
                    "keys `log_aT` and `E_a` do not belong to model \"wlf\" (it takes T_ref, C1, C2)"
                );
                // The model names the offending key (T_ref, C1 or C2).
                let wlf = Wlf::new(self.t_ref.0, value_of(self.c1), value_of(self.c2))
                    .map_err(|e| anyhow!("{e}"))?;
                Ok(ShiftRule::Wlf(wlf))
            }
            ShiftKind::Arrhenius => {
                ensure!(
                    self.c1.is_none() && self.c2.is_none() && self.log_at.is_none(),
                    "keys `C1`, `C2` and `log_aT` do not belong to model \"arrhenius\" (it takes \
                     T_ref, E_a)"
                );
                let energy = self.activation_energy.context(
                    "model \"arrhenius\" needs the key `E_a`, the activation energy in J/mol",
                )?;
                let law = Arrhenius::new(self.t_ref.0, energy.0).map_err(|e| anyhow!("{e}"))?;
                Ok(ShiftRule::Arrhenius(law))
            }
            ShiftKind::Free => {
                ensure!(
                    self.c1.is_none() && self.c2.is_none() && self.activation_energy.is_none(),
                    "keys `C1`, `C2` and `E_a` do not belong to model \"free\" (it takes T_ref, \
                     log_aT)"
                );
                let listed = self.log_at.as_deref().context(
                    "model \"free\" needs the key `log_aT`, one entry per measured temperature, \
                     e.g. log_aT = [{ T = 0.0, log_aT = 2.1 }, { T = 40.0, log_aT = -1.3 }]",
                )?;
                let entries = listed.iter().map(|p| (p.t.0, p.log_at.0)).collect();
                // The model's "entry i" is the i-th element of `log_aT`.
                let free = rollfit_model::modulus::FreeShift::new(self.t_ref.0, entries)
                    .map_err(|e| anyhow!("`log_aT`: {e}"))?;
                Ok(ShiftRule::Free(free))
            }
        }
    }

    /// Checks the section by building its shift.
    pub(super) fn check(&self) -> Result<()> {
        self.rule().map(|_| ())
    }
}
