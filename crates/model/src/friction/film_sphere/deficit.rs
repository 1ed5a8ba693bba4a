//! The film correction Δ of a sphere on a film: the outer integral over
//! s = ln ω of (ω/v)² L(ω) D(x, z), with the inner integral D of
//! [`crate::kernel::film_sphere`] at every node (the method and its error
//! shares are in the parent module's documentation).

use std::cell::{Cell, RefCell};

use num_complex::Complex64;

use super::{Budget, MAX_EVALUATIONS, MAX_INNER_PANELS, MAX_OUTER_PANELS, MAX_OUTER_WIDTH};
use crate::contact::ContactSize;
use crate::error::ModelError;
use crate::kernel::film_sphere::{FILM_CUTOFF, SPAN, deficit, panel_breaks};
use crate::kernel::gauss_kronrod::{Failure, Targets, integrate_keeping_panels};
use crate::modulus::ViscoelasticModulus;
use crate::scene::Scene;

/// Everything the Δ integrand needs besides s.
pub(super) struct Deficit<'a, M> {
    pub(super) material: &'a M,
    /// 1 − ν².
    pub(super) plane_strain: f64,
    pub(super) poisson: f64,
    /// K(1 − ν²) in r³ = K(1 − ν²)/|E| (dynamic rule), m³·Pa.
    pub(super) size_constant: f64,
    /// r0 for the static rule, m.
    pub(super) static_size: Option<f64>,
    /// Static contact radius r0, m.
    pub(super) r0: f64,
    /// Speed v, m/s.
    pub(super) v: f64,
    /// Film thickness d, m.
    pub(super) d: f64,
    /// Integrand evaluations spent so far (all passes).
    pub(super) evaluations: Cell<usize>,
}

/// Δ/C and the outer panels it was summed on.
pub(super) struct DeficitIntegral {
    pub(super) value: f64,
    pub(super) panels: Vec<(f64, f64)>,
    /// Width s_max − s_lo of the outer interval (for the D floors).
    pub(super) span: f64,
}

impl<M: ViscoelasticModulus> Deficit<'_, M> {
    pub(super) fn new(scene: &Scene<M>, v: f64, d: f64) -> Deficit<'_, M> {
        let g = scene.geometry();
        let plane_strain = scene.plane_strain_factor();
        Deficit {
            material: scene.material(),
            plane_strain,
            poisson: scene.substrate().poisson,
            size_constant: 0.75 * g.load * g.radius * plane_strain,
            static_size: match scene.contact() {
                ContactSize::Static => Some(scene.static_contact_size()),
                ContactSize::Dynamic => None,
            },
            r0: scene.static_contact_size(),
            v,
            d,
            evaluations: Cell::new(0),
        }
    }

    /// Contact radius r(ω), m, and loss compliance L(ω), 1/Pa, from E*(ω).
    pub(super) fn material_part(&self, e: Complex64) -> (f64, f64) {
        let loss = -self.plane_strain * (1.0 / e).im;
        let r = match self.static_size {
            Some(r0) => r0,
            None => (self.size_constant / e.norm()).cbrt(),
        };
        (r, loss)
    }

    /// x = ω r/v, z = ω d/v, (ω/v)² (1/m²) and L (1/Pa) at s = ln ω.
    pub(super) fn point(&self, s: f64, e: Complex64) -> (f64, f64, f64, f64) {
        let omega = s.exp();
        let (r, loss) = self.material_part(e);
        // e^{s − ln v} rather than ω/v: neither factor under- or overflows.
        let scaled = (s - self.v.ln()).exp();
        (
            omega * r / self.v,
            omega * self.d / self.v,
            scaled * scaled,
            loss,
        )
    }

    /// The range [s_lo, s_max] of s = ln ω the integral needs: above
    /// s_max the film no longer matters (ω d/v > FILM_CUTOFF), below s_lo
    /// the tail bound is within its share of `budget`.
    fn limits(&self, kappa: f64, p: f64, budget: &Budget) -> Result<(f64, f64), ModelError> {
        let (v, d) = (self.v, self.d);
        let ln_v = v.ln();
        // In logarithms: Z v/d itself can overflow for extreme inputs.
        let s_max = FILM_CUTOFF.ln() + ln_v - d.ln();
        // Lower limit from the tail bound, in logarithms so that no
        // intermediate under- or overflows for extreme v.
        let a = (2.0 * FILM_CUTOFF).ln() + ln_v - d.ln();
        let ln_tail = |s: f64| {
            let q = 2.0 + p;
            (kappa / 9.0).ln() + p * ln_v + q * (s - ln_v) + ((a - s) / q + 1.0 / (q * q)).ln()
        };
        let mut s_lo = s_max - 1.0;
        let mut steps = 0;
        while kappa > 0.0 && ln_tail(s_lo) > budget.tail.ln() {
            s_lo -= 1.0;
            steps += 1;
            if steps > 2000 {
                return Err(ModelError::FilmTailUnbounded);
            }
        }
        // ω = e^s must stay a normal binary64 number on [s_lo, s_max].
        if !(s_lo > -700.0 && s_max < 700.0) {
            return Err(ModelError::FilmFrequenciesOutOfRange {
                speed: v,
                thickness: d,
            });
        }
        Ok((s_lo, s_max))
    }

    /// The initial outer panels on [s_lo, s_max]; refuses up front a film
    /// whose integral the budgets cannot pay for.
    fn outer_breaks(&self, s_lo: f64, s_max: f64) -> Result<Vec<f64>, ModelError> {
        let (v, d) = (self.v, self.d);
        // Initial panels: width ≤ 1 in s, and ≤ SPAN in x (D oscillates in x
        // with period π once x ≳ 1). r ≤ r0 since |E| ≥ E0, so x ≤ ω r0/v.
        let r0_over_v = self.r0 / v;
        let mut breaks = vec![s_lo];
        let mut s = s_lo;
        while s < s_max {
            let x_up = s.exp() * r0_over_v;
            let width = MAX_OUTER_WIDTH.min((1.0 + SPAN / x_up).ln());
            s = (s + width).min(s_max);
            breaks.push(s);
            if breaks.len() > MAX_OUTER_PANELS {
                return Err(self.too_thin());
            }
        }
        // Refuse up front what the evaluation budget cannot pay for: even
        // without refinement each outer panel needs 15 inner integrals of
        // at least their initial panels. Counted on the breaks (x ≤ ω r0/v).
        let mut inner_breaks = Vec::new();
        let mut estimate = 0usize;
        for &s in &breaks[..breaks.len() - 1] {
            let omega = s.exp();
            if panel_breaks(
                omega * r0_over_v,
                omega * d / v,
                MAX_INNER_PANELS,
                &mut inner_breaks,
            )
            .is_none()
            {
                return Err(self.too_thin());
            }
            estimate += 15 * 15 * inner_breaks.len().saturating_sub(1);
        }
        if estimate > MAX_EVALUATIONS {
            return Err(self.too_thin());
        }
        Ok(breaks)
    }

    /// Δ/C = ∫ ds (ω/v)² L D with the error shares of `budget` (absolute,
    /// in these integral units).
    pub(super) fn integral(
        &self,
        kappa: f64,
        p: f64,
        budget: &Budget,
    ) -> Result<DeficitIntegral, ModelError> {
        let (s_lo, s_max) = self.limits(kappa, p, budget)?;
        let breaks = self.outer_breaks(s_lo, s_max)?;
        let span = s_max - s_lo;
        // The first inner failure (None: the evaluation budget ran out).
        let inner_failure: RefCell<Option<Option<Failure>>> = RefCell::new(None);
        let scratch = RefCell::new(Vec::new());
        let integrand = |s: f64| -> [f64; 1] {
            let (x, z, scaled_sq, loss) = self.point(s, self.material.modulus(s.exp()));
            let weight = scaled_sq * loss;
            // Absolute floor for D: the final panels' Kronrod weights are
            // positive and sum to `span`, so even if every node erred by its
            // floor the outer sum would move by at most `inner_floor`.
            let floor = budget.inner_floor / (span * weight);
            if self.evaluations.get() > MAX_EVALUATIONS {
                inner_failure.borrow_mut().get_or_insert(None);
                return [f64::NAN];
            }
            let mut scratch = scratch.borrow_mut();
            let relative = budget.inner_relative;
            match deficit(
                x,
                z,
                self.poisson,
                relative,
                floor,
                MAX_INNER_PANELS,
                &mut scratch,
            ) {
                Ok(dd) => {
                    self.evaluations
                        .set(self.evaluations.get() + dd.evaluations);
                    [weight * dd.value[0]]
                }
                Err(e) => {
                    inner_failure.borrow_mut().get_or_insert(Some(e));
                    [f64::NAN]
                }
            }
        };
        let result = integrate_keeping_panels(
            integrand,
            &breaks,
            Targets {
                absolute: [budget.outer],
                relative: 0.0,
            },
            MAX_OUTER_PANELS,
        );
        if let Some(failure) = inner_failure.into_inner() {
            return Err(match failure {
                None | Some(Failure::PanelLimit { .. }) => self.too_thin(),
                Some(other) => ModelError::FilmIntegralFailed {
                    which: "inner film",
                    detail: format!("{other:?}"),
                },
            });
        }
        match result {
            Ok((integral, panels)) => Ok(DeficitIntegral {
                value: integral.value[0],
                panels,
                span,
            }),
            Err(Failure::PanelLimit { .. }) => Err(self.too_thin()),
            Err(other) => Err(ModelError::FilmIntegralFailed {
                which: "film correction",
                detail: format!("{other:?}"),
            }),
        }
    }

    /// The error for a film too thin compared with the contact to integrate
    /// within the budgets.
    pub(super) fn too_thin(&self) -> ModelError {
        ModelError::FilmTooThin {
            thickness_in_radii: self.d / self.r0,
            thickness: self.d,
            max_evaluations: MAX_EVALUATIONS,
            max_panels: MAX_INNER_PANELS,
        }
    }
}
