//! The two modulus columns of a DMA row made the storage and loss moduli
//! M′, M″ (E or G) at the row's angular frequency ω, by the exact
//! relations of the complex modulus and the complex viscosity:
//!
//! M* = M′ + i M″ = |M*| e^{iδ}, tan δ = M″/M′,
//! η* = η′ − i η″ = M*/(iω), so G′ = ω η″, G″ = ω η′, |G*| = ω |η*|.
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley
//!   1980, Ch. 1 (Eqs. 1.9–1.20: the dynamic moduli, δ and η*).

/// How a row's two modulus columns (`storage` and `loss` of [`Header`])
/// become E′ and E″ (or G′, G″) at ω: the exact relations of the complex
/// modulus M* = M′ + i M″ = |M*| e^{iδ} and of the complex viscosity
/// η* = η′ − i η″ = M*/(iω) (Ferry, Ch. 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Moduli {
    /// M′ and M″ as written.
    Parts,
    /// |M*| and δ (rad): M′ = |M*| cos δ, M″ = |M*| sin δ.
    AbsPhase,
    /// |M*| and tan δ: M′ = |M*|/√(1 + tan²δ), M″ = M′ tan δ.
    AbsTan,
    /// M′ and tan δ: M″ = M′ tan δ.
    StorageTan,
    /// η′ and η″: G′ = ω η″, G″ = ω η′.
    ViscosityParts,
    /// |η*| and δ: |G*| = ω |η*|, then as [`Moduli::AbsPhase`].
    ViscosityAbsPhase,
    /// |η*| and tan δ: |G*| = ω |η*|, then as [`Moduli::AbsTan`].
    ViscosityAbsTan,
}

impl Moduli {
    /// (M′, M″) of the two columns' values `a`, `b` (SI) at `omega` (rad/s).
    pub fn convert(self, omega: f64, a: f64, b: f64) -> (f64, f64) {
        let abs_tan = |abs: f64, tan: f64| {
            let storage = abs / tan.hypot(1.0);
            (storage, storage * tan)
        };
        match self {
            Moduli::Parts => (a, b),
            Moduli::AbsPhase => (a * b.cos(), a * b.sin()),
            Moduli::AbsTan => abs_tan(a, b),
            Moduli::StorageTan => (a, a * b),
            Moduli::ViscosityParts => (omega * b, omega * a),
            Moduli::ViscosityAbsPhase => (omega * a * b.cos(), omega * a * b.sin()),
            Moduli::ViscosityAbsTan => abs_tan(omega * a, b),
        }
    }

    /// What the note says of the conversion (`None`: none).
    pub(super) fn said(self) -> Option<&'static str> {
        match self {
            Moduli::Parts => None,
            Moduli::AbsPhase => Some("from |M*| and δ: M′ = |M*| cos δ, M″ = |M*| sin δ"),
            Moduli::AbsTan => Some("from |M*| and tan δ: M′ = |M*|/√(1+tan²δ), M″ = M′ tan δ"),
            Moduli::StorageTan => Some("from M′ and tan δ: M″ = M′ tan δ"),
            Moduli::ViscosityParts => Some("from η′ and η″ at ω: G′ = ω η″, G″ = ω η′"),
            Moduli::ViscosityAbsPhase => {
                Some("from |η*| and δ at ω: G′ = ω |η*| cos δ, G″ = ω |η*| sin δ")
            }
            Moduli::ViscosityAbsTan => {
                Some("from |η*| and tan δ at ω: |G*| = ω |η*|, G′ = |G*|/√(1+tan²δ), G″ = G′ tan δ")
            }
        }
    }
}
