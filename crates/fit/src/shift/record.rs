//! The record of a fitted shift, as fit.json holds it under `shift`.

use serde::{Serialize, Serializer};

use super::temperatures::SAME_TEMPERATURE;

/// The time–temperature shift of a temperature set (docs/ARCHITECTURE.md,
/// "Conventions"): E*(ω, T) = E*(ω a_T, T_ref).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "model", rename_all = "lowercase")]
pub enum ShiftRecord {
    /// WLF: log10 a_T = −C1 (T − T_ref)/(C2 + T − T_ref).
    Wlf {
        /// Reference temperature, °C.
        #[serde(rename = "T_ref")]
        t_ref: f64,
        /// C1 (dimensionless).
        #[serde(rename = "C1")]
        c1: f64,
        /// C2, K.
        #[serde(rename = "C2")]
        c2: f64,
        /// 1σ of C1 from the curvature of V (null when not finite).
        #[serde(rename = "C1_sigma", serialize_with = "finite_or_null")]
        c1_sigma: f64,
        /// 1σ of C2, K (null when not finite).
        #[serde(rename = "C2_sigma", serialize_with = "finite_or_null")]
        c2_sigma: f64,
        /// log10 a_T at each measured temperature (from C1, C2).
        #[serde(rename = "log_aT")]
        log_shift: Vec<LogShift>,
    },
    /// Arrhenius: log10 a_T = E_a/(R ln 10) (1/T − 1/T_ref), T in K; the
    /// keys are those of a scene's `[material.shift] model = "arrhenius"`.
    Arrhenius {
        /// Reference temperature, °C.
        #[serde(rename = "T_ref")]
        t_ref: f64,
        /// Activation energy E_a, J/mol.
        #[serde(rename = "E_a")]
        activation_energy: f64,
        /// 1σ of E_a, J/mol (null when not finite).
        #[serde(rename = "E_a_sigma", serialize_with = "finite_or_null")]
        activation_energy_sigma: f64,
        /// log10 a_T at each measured temperature (from E_a).
        #[serde(rename = "log_aT")]
        log_shift: Vec<LogShift>,
    },
    /// One free log10 a_T per temperature, 0 at T_ref.
    Free {
        /// Reference temperature, °C (one of the measured temperatures).
        #[serde(rename = "T_ref")]
        t_ref: f64,
        /// log10 a_T per measured temperature.
        #[serde(rename = "log_aT")]
        log_shift: Vec<LogShift>,
    },
}

impl ShiftRecord {
    /// T_ref, °C.
    pub fn t_ref(&self) -> f64 {
        match self {
            ShiftRecord::Wlf { t_ref, .. }
            | ShiftRecord::Arrhenius { t_ref, .. }
            | ShiftRecord::Free { t_ref, .. } => *t_ref,
        }
    }

    /// log10 a_T at temperature `t` (°C), when `t` is one of the set's.
    pub fn log_shift_at(&self, t: f64) -> Option<f64> {
        self.log_shifts()
            .iter()
            .find(|s| (s.temperature - t).abs() <= SAME_TEMPERATURE)
            .map(|s| s.log_shift)
    }

    /// log10 a_T per measured temperature.
    pub fn log_shifts(&self) -> &[LogShift] {
        match self {
            ShiftRecord::Wlf { log_shift, .. }
            | ShiftRecord::Arrhenius { log_shift, .. }
            | ShiftRecord::Free { log_shift, .. } => log_shift,
        }
    }

    /// Widens every σ by the smoothing bias, as the bands of the master
    /// curve are ([`crate::analysis`]): the change of each value in
    /// `other`, the same shift fitted with a tenth of the smoothness
    /// weight, added in quadrature.
    pub(crate) fn add_bias(&mut self, other: &ShiftRecord) {
        let add = |sigma: &mut f64, bias: f64| *sigma = sigma.hypot(bias);
        for (mine, theirs) in self.log_shifts_mut().iter_mut().zip(other.log_shifts()) {
            add(&mut mine.log_shift_sigma, theirs.log_shift - mine.log_shift);
        }
        match (self, other) {
            (
                ShiftRecord::Wlf {
                    c1,
                    c2,
                    c1_sigma,
                    c2_sigma,
                    ..
                },
                ShiftRecord::Wlf {
                    c1: c1_other,
                    c2: c2_other,
                    ..
                },
            ) => {
                add(c1_sigma, c1_other - *c1);
                add(c2_sigma, c2_other - *c2);
            }
            (
                ShiftRecord::Arrhenius {
                    activation_energy,
                    activation_energy_sigma,
                    ..
                },
                ShiftRecord::Arrhenius {
                    activation_energy: other_energy,
                    ..
                },
            ) => add(activation_energy_sigma, other_energy - *activation_energy),
            _ => {}
        }
    }

    fn log_shifts_mut(&mut self) -> &mut [LogShift] {
        match self {
            ShiftRecord::Wlf { log_shift, .. }
            | ShiftRecord::Arrhenius { log_shift, .. }
            | ShiftRecord::Free { log_shift, .. } => log_shift,
        }
    }

    /// The law's name as fit.json writes it under `model`.
    pub fn model_name(&self) -> &'static str {
        match self {
            ShiftRecord::Wlf { .. } => "wlf",
            ShiftRecord::Arrhenius { .. } => "arrhenius",
            ShiftRecord::Free { .. } => "free",
        }
    }

    /// The law's constants by their key in fit.json (each must be finite;
    /// their σ may not be, and are written as null).
    pub(crate) fn constants(&self) -> Vec<(&'static str, f64)> {
        match self {
            ShiftRecord::Wlf { t_ref, c1, c2, .. } => vec![
                ("shift.T_ref", *t_ref),
                ("shift.C1", *c1),
                ("shift.C2", *c2),
            ],
            ShiftRecord::Arrhenius {
                t_ref,
                activation_energy,
                ..
            } => vec![("shift.T_ref", *t_ref), ("shift.E_a", *activation_energy)],
            ShiftRecord::Free { t_ref, .. } => vec![("shift.T_ref", *t_ref)],
        }
    }
}

/// A σ as fit.json writes it: the number when finite, else null (an
/// undetermined parameter; JSON has no ∞).
fn finite_or_null<S: Serializer>(value: &f64, serializer: S) -> Result<S::Ok, S::Error> {
    if value.is_finite() {
        serializer.serialize_f64(*value)
    } else {
        serializer.serialize_none()
    }
}

/// log10 a_T at one temperature.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LogShift {
    /// Temperature, °C.
    #[serde(rename = "T")]
    pub temperature: f64,
    /// log10 a_T.
    #[serde(rename = "log_aT")]
    pub log_shift: f64,
    /// 1σ of log10 a_T (0 at T_ref of a free shift; not finite, written as
    /// null, where the data do not determine the shift).
    #[serde(rename = "log_aT_sigma", serialize_with = "finite_or_null")]
    pub log_shift_sigma: f64,
}
