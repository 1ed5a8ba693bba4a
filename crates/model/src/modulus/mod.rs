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
//! low-frequency behaviour of the loss modulus, E″ ≈ ℓ ω^p with 0 < p ≤ 1
//! (p = 1 and ℓ = lim E″(ω)/ω for a solid with a longest relaxation time),
//! for the low-speed asymptote and the friction quadrature's tail bound.
//!
//! Models:
//! - [`StandardLinearSolid`]: Persson (2010), Eq. (12).
//! - [`Prony`]: Prony series, Eq. (B2), with derivatives in its parameters.
//! - [`HavriliakNegami`]: E1 + (E0 − E1)/(1 + (iωτ)^α)^β, a broad transition
//!   with power-law wings (Havriliak & Negami 1967); E″ ∝ ω^α at low ω.
//! - [`TabulatedModulus`]: a measured master curve, interpolated in log–log.
//! - [`Shifted`]: time–temperature superposition, E(ω, T) = b_T E(ω a_T, T_ref),
//!   with the vertical factor b_T of [`VerticalShift`] (1 unless given).
//!
//! # References
//! - B.N.J. Persson, "Rolling friction for hard cylinder and sphere on
//!   viscoelastic solid", Eur. Phys. J. E 33 (2010) 327–333.
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley 1980
//!   (Prony series, WLF shift).
//! - S. Havriliak, S. Negami, "A complex plane representation of dielectric
//!   and mechanical relaxation processes in some polymers", Polymer 8 (1967)
//!   161–210.

mod havriliak_negami;
mod prony;
mod shift;
mod sls;
mod table;
mod vertical;
mod wlf_arrhenius;

pub use havriliak_negami::HavriliakNegami;
pub use prony::Prony;
pub use shift::{Arrhenius, FreeShift, GAS_CONSTANT, Shifted, Wlf, ZERO_CELSIUS};
pub use sls::StandardLinearSolid;
pub use table::TabulatedModulus;
pub use vertical::{MAX_EXPANSION, VerticalShift};
pub use wlf_arrhenius::WlfArrhenius;

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

    /// lim_{ω→0} E″(ω)/ω in Pa·s (zero if the loss vanishes faster than ω,
    /// infinite if slower, see [`Self::loss_exponent_at_zero`]).
    fn loss_slope_at_zero(&self) -> f64;

    /// The exponent p of the low-frequency loss, E″(ω) ∝ ω^p as ω → 0, with
    /// 0 < p ≤ 1. A solid whose relaxation times are bounded has p = 1 (the
    /// default); a power-law spectrum such as Havriliak–Negami has p < 1,
    /// and then μ(v) ∝ v^p at low speed instead of Eq. (18)'s μ ∝ v. The
    /// friction quadrature bounds its low-frequency tail with it.
    fn loss_exponent_at_zero(&self) -> f64 {
        1.0
    }

    /// The coefficient ℓ of the low-frequency loss, E″(ω) ≈ ℓ ω^p as ω → 0
    /// (Pa·s^p, p = [`Self::loss_exponent_at_zero`]); it sets the low-speed
    /// asymptote μ ∝ ℓ v^p.
    ///
    /// The default is [`Self::loss_slope_at_zero`] for p = 1. For p < 1 it
    /// reads E″/ω^p three decades below [`Self::structure_range`], where
    /// the power law holds to the structure range's accuracy: that keeps
    /// wrappers such as [`Shifted`] right without their own formula. Models
    /// with a closed form override it.
    fn low_frequency_loss_coefficient(&self) -> f64 {
        let p = self.loss_exponent_at_zero();
        if p >= 1.0 {
            return self.loss_slope_at_zero();
        }
        let omega = 1e-3 * self.structure_range().0;
        self.modulus(omega).im / omega.powf(p)
    }

    /// The angular-frequency interval (rad/s) that holds the modulus's
    /// structure: below it E* follows its low-frequency limit
    /// (E′ ≈ const, E″ ∝ ω^p) and above it its high-frequency limit
    /// (E′ ≈ const, E″ a power law, ∝ 1/ω for a Prony series) to within a
    /// small relative error. The friction
    /// quadrature uses it to decide where its tails begin.
    fn structure_range(&self) -> (f64, f64);

    /// For a modulus with a positive relaxation spectrum (Prony series,
    /// standard linear solid): its glassy modulus E1 = sup |E*|. Such a
    /// solid also has L(ω) ≤ L′(0)·ω, which bounds the friction integrand
    /// without sampling. `None` (the default) makes the friction code sample.
    fn relaxation_bound(&self) -> Option<f64> {
        None
    }

    /// The angular frequencies (rad/s, increasing) at which E*(ω) stops
    /// being analytic: the rows of a table, where the pieces of its
    /// interpolant meet (and, at the first and last, the terminal power
    /// laws begin). Empty (the default) for the closed-form models. The
    /// friction quadrature splits its integral there, because a
    /// polynomial interpolating the integrand across such a point loses
    /// its order.
    fn knots(&self) -> Vec<f64> {
        Vec::new()
    }

    /// For a modulus interpolated from data (a table): the same data
    /// interpolated by a rule of higher order
    /// ([`TabulatedModulus::interpolation_comparison`]), whose difference
    /// from this modulus — and from μ of this modulus — estimates the
    /// interpolation error. `None` (the default) for the closed-form models.
    fn comparison_modulus(&self) -> Option<Box<dyn ViscoelasticModulus>> {
        None
    }
}

/// A pointer to a modulus is the modulus: `Box` and `Arc` for owned and
/// shared materials, `&` for scenes built around a borrowed one (the rungs
/// of crate::ladder evaluate the caller's material without a copy).
macro_rules! modulus_through_pointer {
    ($($pointer:ty),*) => {$(
        impl<M: ViscoelasticModulus + ?Sized> ViscoelasticModulus for $pointer {
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
            fn loss_exponent_at_zero(&self) -> f64 {
                (**self).loss_exponent_at_zero()
            }
            fn low_frequency_loss_coefficient(&self) -> f64 {
                (**self).low_frequency_loss_coefficient()
            }
            fn structure_range(&self) -> (f64, f64) {
                (**self).structure_range()
            }
            fn relaxation_bound(&self) -> Option<f64> {
                (**self).relaxation_bound()
            }
            fn knots(&self) -> Vec<f64> {
                (**self).knots()
            }
            fn comparison_modulus(&self) -> Option<Box<dyn ViscoelasticModulus>> {
                (**self).comparison_modulus()
            }
        }
    )*};
}

modulus_through_pointer!(Box<M>, std::sync::Arc<M>, &M);

/// tan δ = E″/E′ of a complex modulus.
pub fn tan_delta(e: Complex64) -> f64 {
    e.im / e.re
}
