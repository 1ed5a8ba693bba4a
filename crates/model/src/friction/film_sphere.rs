//! Film under a sphere. PLACEHOLDER: not yet implemented.

use super::setup::Setup;
use crate::error::ModelError;
use crate::modulus::ViscoelasticModulus;
use crate::scene::Scene;

pub(super) fn friction<M: ViscoelasticModulus>(
    _scene: &Scene<M>,
    _setup: &Setup,
    _v: f64,
    _thickness: f64,
) -> Result<f64, ModelError> {
    Err(ModelError::Evaluation(
        "a film under a sphere is not yet supported".into(),
    ))
}
