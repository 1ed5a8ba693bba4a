//! Vertical factors of time–temperature superposition: the modulus at
//! temperature T is the reference master curve, shifted in frequency by
//! a_T ([`super::shift`]) and scaled by b_T,
//!
//! E*(ω, T) = b_T E*_ref(ω a_T),   b_{T_ref} = 1.
//!
//! Why b_T: the modulus of an entropic network is proportional to the
//! number of strands per volume times kT, so a master curve is built from
//! reduced moduli E(ω, T) T_ref ρ_ref/(T ρ) (Ferry ch. 11, Eq. 11-2);
//! measured isotherms often need an empirical b_T as well (Dealy & Plazek
//! 2009). Two forms:
//!
//! - **Table** ([`VerticalShift::table`]): log10 b_T listed per
//!   temperature, as `rollfit master --vertical` measures it. The rule of a
//!   free shift ([`FreeShift`]): T_ref counts as listed with log10 b_T = 0,
//!   a listed temperature gives its value exactly, log10 b_T is linear in T
//!   between neighbours, and a temperature outside the listed range
//!   (T_ref included) is an error — extrapolating measured factors would
//!   be a guess.
//! - **Density law** ([`VerticalShift::density`]): Ferry's
//!   b_T = T ρ(T)/(T_ref ρ_ref), temperatures in kelvin. The density
//!   follows from a constant volumetric expansion coefficient
//!   α_V = (1/V) dV/dT (1/K): V = V_ref exp(α_V (T − T_ref)), so
//!   ρ/ρ_ref = exp(−α_V (T − T_ref)) and
//!   log10 b_T = log10(T/T_ref) − α_V (T − T_ref)/ln 10.
//!   α_V = 0 (the default of a scene) keeps ρ constant: b_T = T/T_ref.
//!   For rubbers above T_g α_V ≈ 6–7·10⁻⁴ 1/K, which nearly cancels the
//!   T/T_ref factor near room temperature (at T_ref = 20 °C, 20 K warmer:
//!   log10(313.15/293.15) = 0.0287, α_V ΔT/ln 10 = 0.0056 for 6.5·10⁻⁴).
//!   Defined at every temperature above absolute zero.
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, Ch. 11 (reduced variables, the factor T ρ/(T_ref ρ_ref)).
//! - J. Dealy, D. Plazek, "Time-temperature superposition — a users
//!   guide", Rheology Bulletin 78(2) (2009) 16–31.

use super::shift::{Factor, FreeShift, ZERO_CELSIUS};
use crate::error::ModelError;

/// Largest |α_V| accepted, 1/K: ten times that of any rubber; a larger
/// value is a unit slip (per cent, or a linear coefficient in ppm).
pub const MAX_EXPANSION: f64 = 1e-2;

/// The vertical factor b_T of a material, as a function of temperature.
#[derive(Debug, Clone, PartialEq)]
pub enum VerticalShift {
    /// log10 b_T listed per temperature (see the module documentation).
    Table(FreeShift),
    /// b_T = T ρ(T)/(T_ref ρ_ref) with ρ/ρ_ref = exp(−α_V (T − T_ref)).
    Density {
        /// Reference temperature, °C.
        t_ref: f64,
        /// Volumetric expansion coefficient α_V, 1/K.
        expansion: f64,
    },
}

impl VerticalShift {
    /// A table from the reference temperature `t_ref` (°C) and
    /// `(T, log10 b_T)` pairs (°C, decades) in any order; the checks of
    /// [`FreeShift::new`] (finite values, distinct temperatures, 0 at
    /// T_ref), with errors naming the entry (counted from 0).
    pub fn table(t_ref: f64, entries: Vec<(f64, f64)>) -> Result<Self, ModelError> {
        FreeShift::listed(t_ref, entries, Factor::Vertical).map(VerticalShift::Table)
    }

    /// The density law at `t_ref` (°C, above absolute zero) with the
    /// volumetric expansion coefficient `expansion` (1/K, finite, 0 ≤ α_V
    /// ≤ [`MAX_EXPANSION`]).
    pub fn density(t_ref: f64, expansion: f64) -> Result<Self, ModelError> {
        if !(t_ref.is_finite() && t_ref > -ZERO_CELSIUS) {
            return Err(ModelError::parameter(
                "T_ref",
                t_ref,
                "must be a finite temperature in °C above absolute zero",
            ));
        }
        if !(expansion.is_finite() && (0.0..=MAX_EXPANSION).contains(&expansion)) {
            return Err(ModelError::parameter(
                "expansion",
                expansion,
                "must be a volumetric expansion coefficient (1/K) from 0 to 0.01; rubbers have \
                 about 6.5e-4",
            ));
        }
        Ok(VerticalShift::Density { t_ref, expansion })
    }

    /// The reference temperature, °C, where b_T = 1.
    pub fn t_ref(&self) -> f64 {
        match self {
            VerticalShift::Table(table) => table.t_ref(),
            VerticalShift::Density { t_ref, .. } => *t_ref,
        }
    }

    /// log10 b_T at temperature `t` (°C): an error for a non-finite `t`,
    /// for one at or below absolute zero (density law) or outside the
    /// listed temperatures (table).
    pub fn log10_factor(&self, t: f64) -> Result<f64, ModelError> {
        match self {
            VerticalShift::Table(table) => table.log10_shift(t),
            VerticalShift::Density { t_ref, expansion } => {
                if !(t.is_finite() && t > -ZERO_CELSIUS) {
                    return Err(ModelError::parameter(
                        "T",
                        t,
                        "must be a finite temperature in °C above absolute zero",
                    ));
                }
                let ratio = (t + ZERO_CELSIUS) / (t_ref + ZERO_CELSIUS);
                Ok(ratio.log10() - expansion * (t - t_ref) / std::f64::consts::LN_10)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The density law against Ferry's factor computed directly:
    /// b_T = (T/T_ref)·(ρ/ρ_ref), ρ = m/V with V = V_ref e^{α_V ΔT}.
    #[test]
    fn density_law_is_t_rho_over_t_ref_rho_ref() {
        for (t_ref, alpha) in [(20.0, 0.0), (20.0, 6.5e-4), (-40.0, 3e-4)] {
            let law = VerticalShift::density(t_ref, alpha).unwrap();
            assert_eq!(law.log10_factor(t_ref).unwrap(), 0.0);
            for t in [-60.0, -10.0, 0.0, 35.0, 120.0] {
                let volume_ratio = (alpha * (t - t_ref)).exp();
                let b = (t + 273.15) / (t_ref + 273.15) / volume_ratio;
                let got = 10f64.powf(law.log10_factor(t).unwrap());
                assert!(
                    (got / b - 1.0).abs() < 1e-14,
                    "{t_ref} {alpha} {t}: {got} vs {b}"
                );
            }
        }
        // The example of the module documentation.
        let law = VerticalShift::density(20.0, 6.5e-4).unwrap();
        let expected = (313.15f64 / 293.15).log10() - 6.5e-4 * 20.0 / 10f64.ln();
        assert!((law.log10_factor(40.0).unwrap() - expected).abs() < 1e-15);
        assert!((expected - (0.0287 - 0.0056)).abs() < 1e-4);
        assert!(law.log10_factor(-273.15).is_err());
        assert!(law.log10_factor(f64::NAN).is_err());
    }

    #[test]
    fn density_law_validation() {
        let name = |r: Result<VerticalShift, ModelError>| match r {
            Err(ModelError::InvalidParameter { name, .. }) => name,
            other => panic!("{other:?}"),
        };
        for bad in [-1e-4, 0.02, f64::NAN, f64::INFINITY] {
            assert_eq!(name(VerticalShift::density(20.0, bad)), "expansion");
        }
        for bad in [-300.0, f64::NAN] {
            assert_eq!(name(VerticalShift::density(bad, 0.0)), "T_ref");
        }
    }

    /// A table follows the free-shift rule, and its messages speak of
    /// log10 b_T and vertical factors, not of a_T.
    #[test]
    fn table_interpolates_and_names_its_quantity() {
        let table = VerticalShift::table(20.0, vec![(0.0, -0.04), (60.0, 0.08)]).unwrap();
        assert_eq!(table.t_ref(), 20.0);
        assert_eq!(table.log10_factor(20.0).unwrap(), 0.0);
        assert_eq!(table.log10_factor(60.0).unwrap(), 0.08);
        assert!((table.log10_factor(10.0).unwrap() + 0.02).abs() < 1e-15);
        assert!((table.log10_factor(40.0).unwrap() - 0.04).abs() < 1e-15);
        let outside = table.log10_factor(61.0).unwrap_err().to_string();
        assert!(
            outside.contains("no vertical factor for T = 61 °C"),
            "{outside}"
        );
        assert!(outside.contains("log10 b_T"), "{outside}");
        let bad = VerticalShift::table(20.0, vec![(0.0, f64::INFINITY)]).unwrap_err();
        let text = bad.to_string();
        assert!(text.contains("vertical factors"), "{text}");
        assert!(text.contains("log10 b_T = inf"), "{text}");
        let bad = VerticalShift::table(20.0, vec![(20.0, 0.1)]).unwrap_err();
        assert!(bad.to_string().contains("so log10 b_T must be 0"), "{bad}");
    }
}
