//! Complex Young's moduli E*(ω) of linear viscoelastic solids.
//!
//! Sign convention (fixed for the whole code base): engineering convention,
//! E*(ω) = E′(ω) + i E″(ω) with E″ ≥ 0 for ω > 0, tan δ = E″/E′ and
//! E*(−ω) = conj E*(ω). Every model here is evaluated for ω ≥ 0 only; the
//! friction integrals use the symmetry to fold negative frequencies.
//!
//! The friction model needs, besides E*(ω), its logarithmic slope
//! dE*/d ln ω (the dynamic contact size follows |E*| and the quadrature maps
//! frequency onto the contact variable ω·a(ω)), the static modulus E(0) and the
//! low-frequency slope of the loss modulus, lim E″(ω)/ω (for the low-speed
//! asymptote).
//!
//! Models:
//! - [`StandardLinearSolid`]: Persson (2010), Eq. (12).
//! - [`Prony`]: Prony series, Eq. (B2), with derivatives in its parameters.
//! - [`TabulatedModulus`]: a measured master curve, interpolated in log–log.
//! - [`Shifted`]: time–temperature superposition, E(ω, T) = E(ω a_T, T_ref).
//!
//! # References
//! - B.N.J. Persson, "Rolling friction for hard cylinder and sphere on
//!   viscoelastic solid", Eur. Phys. J. E 33 (2010) 327–333.
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley 1980
//!   (Prony series, WLF shift).

mod prony;
mod shift;
mod sls;
mod table;

pub use prony::Prony;
pub use shift::{FreeShift, Shifted, Wlf};
pub use sls::StandardLinearSolid;
pub use table::TabulatedModulus;

use num_complex::Complex64;

/// A complex Young's modulus E*(ω), Pa, as a function of angular frequency ω
/// (rad/s, ω ≥ 0), in the engineering sign convention.
pub trait ViscoelasticModulus: Send + Sync {
    /// E*(ω) in Pa for ω ≥ 0 rad/s.
    fn modulus(&self, omega: f64) -> Complex64;

    /// E*(ω) and its logarithmic slope dE*/d ln ω, both in Pa.
    fn modulus_and_log_slope(&self, omega: f64) -> (Complex64, Complex64);

    /// The static (rubbery) modulus E(0), Pa.
    fn static_modulus(&self) -> f64;

    /// lim_{ω→0} E″(ω)/ω in Pa·s (zero if the loss vanishes faster than ω).
    fn loss_slope_at_zero(&self) -> f64;

    /// The angular-frequency interval (rad/s) that holds the modulus's
    /// structure: below it E* follows its low-frequency limit
    /// (E′ ≈ const, E″ ∝ ω) and above it its high-frequency limit
    /// (E′ ≈ const, E″ ∝ 1/ω) to within a small relative error. The friction
    /// quadrature uses it to decide where its tails begin.
    fn structure_range(&self) -> (f64, f64);

    /// For a modulus with a positive relaxation spectrum (Prony series,
    /// standard linear solid): its glassy modulus E1 = sup |E*|. Such a
    /// solid also has L(ω) ≤ L′(0)·ω, which bounds the friction integrand
    /// without sampling. `None` (the default) makes the friction code sample.
    fn relaxation_bound(&self) -> Option<f64> {
        None
    }
}

impl<M: ViscoelasticModulus + ?Sized> ViscoelasticModulus for Box<M> {
    fn modulus(&self, omega: f64) -> Complex64 {
        (**self).modulus(omega)
    }
    fn modulus_and_log_slope(&self, omega: f64) -> (Complex64, Complex64) {
        (**self).modulus_and_log_slope(omega)
    }
    fn static_modulus(&self) -> f64 {
        (**self).static_modulus()
    }
    fn loss_slope_at_zero(&self) -> f64 {
        (**self).loss_slope_at_zero()
    }
    fn structure_range(&self) -> (f64, f64) {
        (**self).structure_range()
    }
    fn relaxation_bound(&self) -> Option<f64> {
        (**self).relaxation_bound()
    }
}

impl<M: ViscoelasticModulus + ?Sized> ViscoelasticModulus for std::sync::Arc<M> {
    fn modulus(&self, omega: f64) -> Complex64 {
        (**self).modulus(omega)
    }
    fn modulus_and_log_slope(&self, omega: f64) -> (Complex64, Complex64) {
        (**self).modulus_and_log_slope(omega)
    }
    fn static_modulus(&self) -> f64 {
        (**self).static_modulus()
    }
    fn loss_slope_at_zero(&self) -> f64 {
        (**self).loss_slope_at_zero()
    }
    fn structure_range(&self) -> (f64, f64) {
        (**self).structure_range()
    }
    fn relaxation_bound(&self) -> Option<f64> {
        (**self).relaxation_bound()
    }
}

/// tan δ = E″/E′ of a complex modulus.
pub fn tan_delta(e: Complex64) -> f64 {
    e.im / e.re
}
