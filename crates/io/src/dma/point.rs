//! The values of a DMA file (docs/ARCHITECTURE.md, "Contract", "DMA
//! files"): one point as Young's moduli, which modulus the file held, the
//! DMA's own WLF shift, and the options of reading and shifting.

/// One DMA point. In [`super::DmaData::points`] as measured; moved to a fit's
/// reference state (by the report crate) `omega` is the reduced frequency
/// ω a_T and `temperature` still the measured one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DmaPoint {
    /// Angular frequency, rad/s.
    pub omega: f64,
    /// Young's storage modulus E′, Pa.
    pub storage: f64,
    /// Young's loss modulus E″, Pa.
    pub loss: f64,
    /// Temperature, °C, when the file gives one.
    pub temperature: Option<f64>,
}

impl DmaPoint {
    /// tan δ = E″/E′.
    pub fn tan_delta(&self) -> f64 {
        self.loss / self.storage
    }

    /// |E*| = √(E′² + E″²), Pa.
    pub fn abs_modulus(&self) -> f64 {
        self.storage.hypot(self.loss)
    }
}

/// Which modulus a file held: Young's (tensile, bending, compression DMA)
/// or shear (torsion, parallel plates, shear sandwich).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModulusKind {
    /// E′, E″.
    Young,
    /// G′, G″, converted with E = 2(1+ν)G.
    Shear,
}

impl ModulusKind {
    /// "young" or "shear", as in compare.json and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            ModulusKind::Young => "young",
            ModulusKind::Shear => "shear",
        }
    }
}

/// What a DMA's WLF shift is given as, for messages.
pub const WLF_USAGE: &str =
    "expected T_REF,C1,C2: reference temperature (°C), C1, C2 (K), e.g. 20,8.86,101.6";

/// The DMA's own WLF shift: log10 a_T = −C1 (T − T_ref)/(C2 + T − T_ref),
/// temperatures in °C, C2 in K.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DmaWlf {
    /// °C.
    pub t_ref: f64,
    /// Dimensionless.
    pub c1: f64,
    /// K.
    pub c2: f64,
}

impl DmaWlf {
    /// The DMA's WLF shift from T_ref (°C), C1 and C2 (K): finite numbers
    /// with C1 > 0 and C2 > 0. The error says what is wrong (the command line puts
    /// the text it was given before it, the Python module the argument).
    pub fn new(t_ref: f64, c1: f64, c2: f64) -> Result<DmaWlf, String> {
        if !(t_ref.is_finite() && c1.is_finite() && c2.is_finite()) {
            return Err(format!("the numbers must be finite; {WLF_USAGE}"));
        }
        // As a scene's [material.shift]: a_T falls as T rises.
        if c1 <= 0.0 {
            return Err(format!(
                "C1 = {c1}: must be a finite number greater than zero"
            ));
        }
        if c2 <= 0.0 {
            return Err(format!(
                "C2 = {c2} K must be positive (WLF diverges at T = T_REF − C2)"
            ));
        }
        Ok(DmaWlf { t_ref, c1, c2 })
    }

    /// log10 a_T at `t` (°C), or `None` at and below the divergence
    /// T = T_ref − C2, where the WLF form means nothing.
    pub fn log_shift_at(&self, t: f64) -> Option<f64> {
        let dt = t - self.t_ref;
        (self.c2 + dt > 0.0).then(|| -self.c1 * dt / (self.c2 + dt))
    }
}

/// How to read and shift a DMA file beyond what the file says.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DmaOptions {
    /// Overrides the shear/tensile decision for a TRIOS file, and says it
    /// for files whose column names do not (`Storage Modulus`).
    pub kind: Option<ModulusKind>,
    /// The DMA's own WLF constants; when given they shift the DMA
    /// temperatures instead of the fit's shift.
    pub wlf: Option<DmaWlf>,
    /// The unit of moduli a file gives none for (name, pascals per unit:
    /// [`super::modulus_unit`]); default Pa.
    pub modulus_unit: Option<(&'static str, f64)>,
}
