//! One master-curve pipeline over isotherms of any kind: the settings
//! checked against the isotherms, the curve built, T_ref resolved. What
//! differs between kinds is the pluggable part, [`Superposed`]: frequency
//! sweeps are shifted in log ω and fitted as E′ and E″
//! ([`super::build_master_curve`]); relaxation and creep runs are shifted
//! in log t and fitted as E(t), or through the series' exact creep
//! compliance as D(t) ([`super::relaxation::build_time_master`]).
//!
//! Before this step every kind is grouped by temperature
//! ([`super::grouping`]) and has its repeated abscissae averaged
//! ([`super::repeats`]) in the same way.

use super::isotherm::{Isotherm, Sweep};
use super::relaxation::{RelaxationIsotherm, RelaxationMaster, TimeQuantity, build_time_master};
use super::{MasterCurve, MasterSettings, ShiftFactors, ValidMasterSettings, build_master_curve};
use crate::error::FitError;

/// An isotherm kind the pipeline superposes: its checks, its numerics and
/// the master curve they give.
pub trait Superposed: Sweep {
    /// What else the kind's numerics need: nothing for frequency sweeps,
    /// the measured quantity (E(t) or D(t)) for time-domain runs.
    type Measured: Copy;
    /// The master curve built.
    type Master;
    /// The settings checked against `isotherms` before any numerics run.
    fn check(
        settings: &MasterSettings,
        isotherms: &[Self],
        measured: Self::Measured,
    ) -> Result<ValidMasterSettings, FitError>;
    /// The master curve of `isotherms`.
    fn build(
        isotherms: &[Self],
        measured: Self::Measured,
        settings: &ValidMasterSettings,
    ) -> Result<Self::Master, FitError>;
    /// Its shift factors.
    fn shift(master: &Self::Master) -> &ShiftFactors;
}

impl Superposed for Isotherm {
    type Measured = ();
    type Master = MasterCurve;

    fn check(
        settings: &MasterSettings,
        isotherms: &[Self],
        (): (),
    ) -> Result<ValidMasterSettings, FitError> {
        settings.check(isotherms)
    }

    fn build(
        isotherms: &[Self],
        (): (),
        settings: &ValidMasterSettings,
    ) -> Result<MasterCurve, FitError> {
        build_master_curve(isotherms, settings)
    }

    fn shift(master: &MasterCurve) -> &ShiftFactors {
        &master.shift
    }
}

impl Superposed for RelaxationIsotherm {
    type Measured = TimeQuantity;
    type Master = RelaxationMaster;

    fn check(
        settings: &MasterSettings,
        isotherms: &[Self],
        quantity: TimeQuantity,
    ) -> Result<ValidMasterSettings, FitError> {
        settings.check_time(isotherms, quantity)
    }

    fn build(
        isotherms: &[Self],
        quantity: TimeQuantity,
        settings: &ValidMasterSettings,
    ) -> Result<RelaxationMaster, FitError> {
        build_time_master(isotherms, quantity, settings)
    }

    fn shift(master: &RelaxationMaster) -> &ShiftFactors {
        &master.shift
    }
}

/// A master curve and the settings it was built with.
#[derive(Debug, Clone)]
pub struct Built<M> {
    /// The checked settings, T_ref resolved to the curve's.
    pub settings: ValidMasterSettings,
    /// Shift factors, shifted points and the Prony series.
    pub master: M,
}

/// Why the pipeline stopped: the settings do not suit the isotherms, or
/// the numerics refused them. Front ends place the two differently (the
/// second "in the master curve").
#[derive(Debug)]
pub enum PipelineError {
    /// [`Superposed::check`] refused.
    Settings(FitError),
    /// [`Superposed::build`] refused.
    Build(FitError),
}

/// The master curve of `isotherms` (grouped and averaged): settings
/// checked, curve built, T_ref resolved.
pub fn build<S: Superposed>(
    isotherms: &[S],
    measured: S::Measured,
    settings: &MasterSettings,
) -> Result<Built<S::Master>, PipelineError> {
    let valid = S::check(settings, isotherms, measured).map_err(PipelineError::Settings)?;
    let master = S::build(isotherms, measured, &valid).map_err(PipelineError::Build)?;
    Ok(Built {
        settings: valid.resolved(S::shift(&master)),
        master,
    })
}
