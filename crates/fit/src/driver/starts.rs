//! Where the solver runs on one τ grid start: the neutral start θ₀ (a flat
//! spectrum), spectra concentrated in a bump, and seeded perturbations of
//! the starting material.
//!
//! Results are deterministic for a given seed: the perturbations are
//! N(0, 1) draws in each log-parameter from ChaCha8 seeded with it.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

use crate::error::FitError;
use crate::parametrization::Parametrization;
use crate::params::ValidFitParams;
use crate::tau_grid::probed_band;
use crate::temperature_set::ShiftStart;

/// E1/E0 of the neutral start.
const START_RATIO: f64 = 1000.0;
/// Static modulus of the neutral start without anchor or start material, Pa.
const START_MODULUS: f64 = 1e6;

/// Centres of the bump starts, as fractions of the probed band in log ω.
const BUMP_CENTRES: [f64; 4] = [0.2, 0.4, 0.6, 0.8];

/// The neutral start θ₀: a flat spectrum with E1/E0 = [`START_RATIO`]
/// (bounded by E1_max) at the anchored, or starting, or
/// [`START_MODULUS`] scale; the starting material's E1/E0 when one is given.
pub(super) fn neutral_start(param: &Parametrization, params: &ValidFitParams) -> Vec<f64> {
    let e0 = match (params.anchor, &params.start) {
        (Some(a), _) if a.omega == 0.0 => a.modulus,
        (_, Some(s)) => s.static_modulus,
        _ => START_MODULUS,
    };
    let ratio = match &params.start {
        Some(s) => s.glassy_modulus / s.static_modulus,
        None => START_RATIO.min(0.5 * params.e1_max / e0).max(2.0),
    };
    let n = param.terms();
    let h = vec![e0 * (ratio - 1.0) / n as f64; n];
    param.theta_of(e0, &h)
}

/// The starts of the fits on one τ grid: the starting material's θ (warm,
/// or the neutral start), to which a temperature set's starting shift θ_s
/// is appended in every start.
pub(super) struct Starts<'s> {
    /// θ of the starting material.
    material: Vec<f64>,
    /// The temperature set's shift and its start.
    shift: Option<&'s ShiftStart>,
    /// The speeds whose probed band places the bumps: the data's, or the
    /// reduced speeds at the starting shift.
    range: (f64, f64),
}

impl<'s> Starts<'s> {
    /// From the material θ `material`, with the shift `shift` of a
    /// temperature set, on speeds (reduced at the starting shift) spanning
    /// `range`.
    pub(super) fn new(
        material: Vec<f64>,
        shift: Option<&'s ShiftStart>,
        range: (f64, f64),
    ) -> Self {
        Starts {
            material,
            shift,
            range,
        }
    }

    /// A material θ with the starting shift appended.
    fn with_shift(&self, material: Vec<f64>) -> Vec<f64> {
        match self.shift {
            Some(s) => material
                .into_iter()
                .chain(s.theta.iter().copied())
                .collect(),
            None => material,
        }
    }

    /// The starting material with the starting shift.
    pub(super) fn first(&self) -> Vec<f64> {
        self.with_shift(self.material.clone())
    }

    /// The bump starts of [`bump_starts`] around the starting material, with
    /// the starting shift.
    pub(super) fn bumps(&self, param: &Parametrization, params: &ValidFitParams) -> Vec<Vec<f64>> {
        bump_starts(param, params, self.range, &self.material)
            .into_iter()
            .map(|b| self.with_shift(b))
            .collect()
    }

    /// The restarts at the chosen λ, each with the stage that names it in
    /// the runs: the bumps (unless they already raced at the path's
    /// start), then the seeded perturbations of [`Starts::perturbations`].
    pub(super) fn restarts(
        &self,
        param: &Parametrization,
        params: &ValidFitParams,
        bumps_raced: bool,
    ) -> Result<Vec<(String, Vec<f64>)>, FitError> {
        let bumps = if bumps_raced {
            Vec::new()
        } else {
            self.bumps(param, params)
        };
        let mut others: Vec<(String, Vec<f64>)> = bumps
            .into_iter()
            .enumerate()
            .map(|(k, b)| (format!("bump start {}", k + 1), b))
            .collect();
        others.extend(
            self.perturbations(params)?
                .into_iter()
                .enumerate()
                .map(|(k, p)| (format!("random start {}", k + 1), p)),
        );
        Ok(others)
    }

    /// `params.starts − 1` seeded perturbations of the starting material
    /// (N(0, 1) in each log-parameter), with the starting shift.
    pub(super) fn perturbations(&self, params: &ValidFitParams) -> Result<Vec<Vec<f64>>, FitError> {
        let mut rng = ChaCha8Rng::seed_from_u64(params.seed);
        let normal = Normal::new(0.0, 1.0).map_err(|e| FitError::setting("seed", e.to_string()))?;
        Ok((1..params.starts)
            .map(|_| {
                // The material only: the starting shift is already close.
                self.with_shift(
                    self.material
                        .iter()
                        .map(|t| t + normal.sample(&mut rng))
                        .collect(),
                )
            })
            .collect())
    }
}

/// Starts whose spectrum is concentrated in a one-decade Gaussian bump in
/// log τ at [`BUMP_CENTRES`] of the probed band, with the E0 and E1 of
/// `material`. A flat start can settle where the terms a narrow truth needs
/// have died (with H = e^θ a small term's gradient vanishes); a three-term
/// Prony truth is fitted to χ²/N = 2600 from the flat start alone and to
/// 1.6 with these.
fn bump_starts(
    param: &Parametrization,
    params: &ValidFitParams,
    range: (f64, f64),
    material: &[f64],
) -> Vec<Vec<f64>> {
    let mapped = param.map(material);
    let e0 = mapped.static_modulus;
    let total = mapped.strengths.iter().sum::<f64>();
    let band = probed_band(&params.setup, range, e0, params.e1_max);
    let (lo, hi) = (band.0.log10(), band.1.log10());
    BUMP_CENTRES
        .iter()
        .map(|q| {
            let centre = lo + q * (hi - lo);
            let weights: Vec<f64> = param
                .tau()
                .iter()
                .map(|t| {
                    let x = (1.0 / t).log10() - centre;
                    // Floor: every term stays alive (ln H finite).
                    (-0.5 * x * x).exp().max(1e-9)
                })
                .collect();
            let sum: f64 = weights.iter().sum();
            let h: Vec<f64> = weights.iter().map(|w| total * w / sum).collect();
            param.theta_of(e0, &h)
        })
        .collect()
}
