//! The values of a fit that lie beyond the window the data determine
//! (fit.json's `extrapolated`).
//!
//! A Prony series E*(ω) = E0 + Σ H_k iωτ_k/(1 + iωτ_k) has E′ increasing
//! in ω, from its static modulus E0 (ω → 0) to its glassy modulus
//! E1 = E0 + Σ H_k (ω → ∞). Inside the window [ω_min, ω_max] the data fix
//! E* to its bands; beyond it the series continues as its terms happen to
//! lie, which the data do not constrain. So E0 is a result only where the
//! curve has reached its low plateau inside the window, E′(ω_min) − E0 ≤
//! 2σ(E′(ω_min)), and E1 only where E1 − E′(ω_max) ≤ 2σ(E′(ω_max)).
//! Otherwise each is an extrapolation, and monotonicity gives the bound the
//! data do set: E0 ≤ E′(ω_min) + 2σ and E1 ≥ E′(ω_max) − 2σ (2σ of the
//! reported band at the window's end). Extrapolations are reported with
//! that one-sided interval and never judge a fit
//! ([`rollfit_model::plausibility::fitted_material_warnings`]); the spectrum's own ends,
//! the terms outside the window, are the model record's `determined`.

use serde::Serialize;

use crate::analysis::ModulusPoint;

/// One value of the fit beyond its window.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Extrapolation {
    /// "E0" (ω → 0) or "E1" (ω → ∞).
    pub quantity: &'static str,
    /// The fitted value, Pa.
    pub value: f64,
    /// The window's end it lies beyond, rad/s.
    pub omega_edge: f64,
    /// E′ at that end, Pa.
    #[serde(rename = "E_storage_edge")]
    pub storage_edge: f64,
    /// Lower end of the 2σ interval the data give, Pa (None: unbounded
    /// below by the data).
    pub low: Option<f64>,
    /// Upper end of the 2σ interval the data give, Pa (None: unbounded
    /// above by the data).
    pub high: Option<f64>,
    /// What the data say of it, in words.
    pub reason: String,
}

/// The extrapolated static and glassy moduli `e0`, `e1` (Pa) of a fit whose
/// reported `curve` (with its 1σ bands) spans the window the data
/// determine.
pub fn extrapolations(e0: f64, e1: f64, curve: &[ModulusPoint]) -> Vec<Extrapolation> {
    let (Some(first), Some(last)) = (curve.first(), curve.last()) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let two_sigma = |p: &ModulusPoint| 2.0 * p.storage_sigma;
    if first.storage - e0 > two_sigma(first) {
        let high = first.storage + two_sigma(first);
        out.push(Extrapolation {
            quantity: "E0",
            value: e0,
            omega_edge: first.omega,
            storage_edge: first.storage,
            low: None,
            high: Some(high),
            reason: format!(
                "E0 = {e0:.3e} Pa is the Prony series' limit ω → 0, beyond the window the data \
                 determine, where E′ has not levelled off (E′ = {:.3e} Pa at ω = {:.3e} rad/s): \
                 the data say only E0 ≤ {high:.3e} Pa (2σ); a measurement at lower frequency \
                 or higher temperature, or a static modulus (the anchor E0), would determine it",
                first.storage, first.omega
            ),
        });
    }
    if e1 - last.storage > two_sigma(last) {
        let low = (last.storage - two_sigma(last)).max(0.0);
        out.push(Extrapolation {
            quantity: "E1",
            value: e1,
            omega_edge: last.omega,
            storage_edge: last.storage,
            low: Some(low),
            high: None,
            reason: format!(
                "E1 = {e1:.3e} Pa is the Prony series' limit ω → ∞, beyond the window the data \
                 determine, where E′ has not levelled off (E′ = {:.3e} Pa at ω = {:.3e} rad/s): \
                 the data say only E1 ≥ {low:.3e} Pa (2σ); a measurement at higher frequency \
                 or lower temperature would determine it",
                last.storage, last.omega
            ),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use rollfit_model::{Prony, ViscoelasticModulus};

    fn point(prony: &Prony, omega: f64, relative_sigma: f64) -> ModulusPoint {
        let e = prony.modulus(omega);
        ModulusPoint {
            omega,
            storage: e.re,
            loss: e.im,
            tan_delta: e.im / e.re,
            magnitude: e.norm(),
            storage_sigma: relative_sigma * e.re,
            loss_sigma: relative_sigma * e.im,
            tan_delta_sigma: relative_sigma * e.im / e.re,
            magnitude_sigma: relative_sigma * e.norm(),
        }
    }

    /// One relaxation time τ = 1 s: E′ = E0 + H (ωτ)²/(1 + (ωτ)²).
    #[test]
    fn limits_beyond_the_window_are_extrapolations_with_their_bound() {
        let prony = Prony::new(1e9, vec![1e9 - 1e3], vec![1.0]).unwrap();
        let m = |curve: &[ModulusPoint]| {
            extrapolations(prony.static_modulus(), prony.glassy_modulus(), curve)
        };
        // Window 0.1 … 10 rad/s: E′ = 9.9e6 … 9.9e8, each beyond 2σ
        // (0.4 %) of its limit.
        let curve = [point(&prony, 0.1, 0.002), point(&prony, 10.0, 0.002)];
        let x = m(&curve);
        assert_eq!(x.len(), 2, "{x:#?}");
        assert_eq!(x[0].quantity, "E0");
        let e_low = prony.modulus(0.1).re;
        assert!((x[0].high.unwrap() / (1.004 * e_low) - 1.0).abs() < 1e-12);
        assert!(x[0].low.is_none() && x[0].reason.contains("E0 ≤"));
        assert_eq!(x[1].quantity, "E1");
        let e_high = prony.modulus(10.0).re;
        assert!((x[1].low.unwrap() / (0.996 * e_high) - 1.0).abs() < 1e-12);
        // A window reaching both plateaus (1e-5 … 1e5 rad/s): none.
        let curve = [point(&prony, 1e-5, 0.002), point(&prony, 1e5, 0.002)];
        assert!(m(&curve).is_empty());
    }
}
