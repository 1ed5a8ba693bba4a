//! How far μ(v) of a tabulated modulus can be trusted: the table's own
//! interpolation error carried through to μ.
//!
//! Between its rows a table is an interpolant, and μ is an integral over
//! the modulus at every frequency, so μ inherits the interpolation error,
//! whatever the quadrature's tolerance. It is estimated from the data
//! alone: with E_c the same rows interpolated by slopes of one order higher
//! ([`crate::modulus::TabulatedModulus::interpolation_comparison`]),
//!
//!   ε_μ(v) = |μ[E_c](v)/μ[E](v) − 1|,
//!
//! the leading term of μ's error when the table samples a smooth master
//! curve (E's error is O(H³) in the knot spacing H and dominated by its
//! slopes, E_c's is O(H⁴)). It measures interpolation only: noise in the
//! rows and the terminal behaviour assumed outside the table are not in it.
//!
//! # References
//! - J. Stoer, R. Bulirsch, *Introduction to Numerical Analysis*, 3rd ed.,
//!   Springer 2002, §2.1.3 (error of Hermite interpolation), §3.3 (error
//!   estimates from two rules of different order).

use crate::error::ModelError;
use crate::modulus::ViscoelasticModulus;
use crate::scene::Scene;

impl<M: ViscoelasticModulus> Scene<M> {
    /// For a material interpolated from a table: the estimated relative
    /// error ε_μ of each μ(`speeds`[i]) = `mu`[i] that comes from the
    /// table's interpolation (module documentation), computed with the
    /// scene's quadrature and tolerance. `None` for a closed-form material.
    pub fn table_interpolation_error(
        &self,
        speeds: &[f64],
        mu: &[f64],
    ) -> Result<Option<Vec<f64>>, ModelError> {
        let Some(comparison) = self.material().comparison_modulus() else {
            return Ok(None);
        };
        let scene = Scene::new(
            *self.geometry(),
            *self.substrate(),
            self.contact(),
            comparison,
        )?
        .with_tolerance(self.tolerance())?;
        let mu_comparison = scene.friction_sweep(speeds)?;
        Ok(Some(
            mu.iter()
                .zip(mu_comparison)
                .map(|(m, c)| (c / m - 1.0).abs())
                .collect(),
        ))
    }
}
