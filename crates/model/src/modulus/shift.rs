//! Time–temperature superposition: the modulus at temperature T is the
//! reference master curve at a shifted frequency,
//!
//! E*(ω, T) = E*_ref(ω a_T),
//!
//! with the shift factor a_T (dimensionless, a_{T_ref} = 1). Convention:
//! a_T < 1 (log10 a_T < 0) above T_ref, so a warmer solid is softer at a
//! given frequency: its whole curve moves to higher frequencies by 1/a_T.
//! Because μ(v) depends on the modulus only through E*(qv) (the dynamic
//! contact size through |E*| as well, the static one through E(0), which a
//! shift leaves alone), the friction curve moves the same way:
//! μ(v, T) = μ_ref(v a_T).
//!
//! With a vertical factor b_T (Ferry ch. 11: the modulus of the rubbery
//! network is proportional to ρT, so the reduced modulus is
//! E T_ref ρ_ref/(T ρ); laws and tables in [`super::VerticalShift`]),
//!
//! E*(ω, T) = b_T E*_ref(ω a_T).
//!
//! The friction curve then moves and changes: with ν fixed, Eqs. (11) and
//! (17) see the modulus only through L = E″_eff/|E_eff|², which b_T divides,
//! and the Hertz size, which depends on load/|E|; the prefactor is the
//! load. So μ(v; b E, F) = μ(v; E, F/b): a stiffer solid rolls like the
//! same solid under a lighter load (the same holds for the exact contact,
//! whose pressure scales with the load and whose strain with p/E).
//!
//! Shift factors:
//! - Williams–Landel–Ferry, [`Wlf`]:
//!   log10 a_T = −C1 (T − T_ref)/(C2 + T − T_ref),
//!   C1 dimensionless, C2 in K, temperatures in °C. The form diverges at
//!   T = T_ref − C2 and is meaningless below; evaluating there is an error.
//!   With C1 = 8.86, C2 = 101.6 K (WLF's "universal" constants, meant for
//!   T_ref ≈ T_g + 50 K) and T_ref = 20 °C, 10 K cooler gives
//!   log10 a_T = 0.97 and 10 K warmer −0.79: the paper's remark that about
//!   10 °C less moves μ(v) by about one decade.
//! - Arrhenius, [`Arrhenius`]:
//!   log10 a_T = E_a/(R ln 10) · (1/T − 1/T_ref), temperatures in kelvin
//!   inside the formula (°C + 273.15 outside it), E_a the activation
//!   energy in J/mol, R = 8.314462618 J/(mol K). The law of secondary
//!   relaxations and of polymers well below or far above T_g, where WLF's
//!   free-volume form does not hold; it has no divergence.
//! - free shifts, [`FreeShift`]: one log10 a_T per measured temperature, e.g.
//!   fitted freely. T_ref counts as listed, with log10 a_T = 0. At a listed
//!   temperature the listed value is returned exactly; between two listed
//!   temperatures log10 a_T is interpolated linearly in T; outside the
//!   listed range [T_lo, T_hi] (T_ref included) evaluating is an error: the
//!   list says nothing about the material there, and extrapolating a shift
//!   that is not WLF-like would be a guess. Linear in T because it is the
//!   simplest rule exact at the listed points and never leaves the range of
//!   its two neighbours; for shifts that follow WLF with the constants
//!   above, listed every 10 K from 0 to 40 °C, it is within 0.035 decades
//!   of WLF in between.
//!
//! [`Shifted`] wraps a reference modulus with one shift factor a_T and a
//! vertical factor b_T (1 unless [`Shifted::with_vertical`]):
//! - E*(ω) = b_T E*_ref(ω a_T);
//! - dE*/d ln ω = b_T (dE*_ref/d ln ω)(ω a_T): a frequency scaling does not
//!   change log slopes;
//! - E(0) = b_T E_ref(0); lim E″/ω = b_T a_T · lim E″_ref/ω;
//! - structure range [ω_lo/a_T, ω_hi/a_T];
//! - relaxation bound (sup |E*| of a positive spectrum) times b_T.
//!
//! # References
//! - M.L. Williams, R.F. Landel, J.D. Ferry, "The temperature dependence of
//!   relaxation mechanisms in amorphous polymers and other glass-forming
//!   liquids", J. Am. Chem. Soc. 77 (1955) 3701–3707.
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley 1980,
//!   Ch. 11.
//! - B.N.J. Persson, "Rolling friction for hard cylinder and sphere on
//!   viscoelastic solid", Eur. Phys. J. E 33 (2010) 327–333.

use num_complex::Complex64;

use super::ViscoelasticModulus;
use crate::error::{ModelError, require_positive};

/// WLF shift: log10 a_T = −C1 (T − T_ref)/(C2 + T − T_ref); temperatures in °C.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wlf {
    /// Reference temperature, °C.
    pub t_ref: f64,
    /// C1 (dimensionless).
    pub c1: f64,
    /// C2, K.
    pub c2: f64,
}

impl Wlf {
    /// Validated WLF constants: `t_ref` (°C) finite, `c1` and `c2` (K)
    /// finite and greater than zero.
    pub fn new(t_ref: f64, c1: f64, c2: f64) -> Result<Self, ModelError> {
        if !t_ref.is_finite() {
            return Err(ModelError::parameter(
                "T_ref",
                t_ref,
                "must be a finite temperature in °C",
            ));
        }
        require_positive("C1", c1)?;
        require_positive("C2", c2)?;
        Ok(Wlf { t_ref, c1, c2 })
    }

    /// log10 a_T at temperature `t` (°C). An error for a non-finite `t` and
    /// for t ≤ T_ref − C2, where C2 + T − T_ref ≤ 0 and the WLF form diverges.
    pub fn log10_shift(&self, t: f64) -> Result<f64, ModelError> {
        if !t.is_finite() {
            return Err(ModelError::parameter(
                "T",
                t,
                "must be a finite temperature in °C",
            ));
        }
        let dt = t - self.t_ref;
        let denominator = self.c2 + dt;
        // NaN only from a hand-built Wlf with non-finite fields.
        if denominator.is_nan() || denominator <= 0.0 {
            return Err(ModelError::WlfBeyondPole {
                temperature: t,
                denominator,
                c2: self.c2,
                t_ref: self.t_ref,
            });
        }
        Ok(-self.c1 * dt / denominator)
    }
}

/// The molar gas constant R, J/(mol K) (exact since the 2019 SI).
pub const GAS_CONSTANT: f64 = 8.314_462_618;

/// 0 °C in kelvin.
pub const ZERO_CELSIUS: f64 = 273.15;

/// Arrhenius shift: log10 a_T = E_a/(R ln 10) (1/T − 1/T_ref), T in K
/// inside the formula; temperatures given in °C.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arrhenius {
    /// Reference temperature, °C.
    pub t_ref: f64,
    /// Activation energy E_a, J/mol.
    pub activation_energy: f64,
}

impl Arrhenius {
    /// Validated constants: `t_ref` (°C) finite and above absolute zero,
    /// `activation_energy` (J/mol) finite and greater than zero.
    pub fn new(t_ref: f64, activation_energy: f64) -> Result<Self, ModelError> {
        if !(t_ref.is_finite() && t_ref > -ZERO_CELSIUS) {
            return Err(ModelError::parameter(
                "T_ref",
                t_ref,
                "must be a finite temperature in °C above absolute zero",
            ));
        }
        require_positive("E_a", activation_energy)?;
        Ok(Arrhenius {
            t_ref,
            activation_energy,
        })
    }

    /// log10 a_T at temperature `t` (°C); an error for a non-finite `t` or
    /// one at or below absolute zero.
    pub fn log10_shift(&self, t: f64) -> Result<f64, ModelError> {
        if !(t.is_finite() && t > -ZERO_CELSIUS) {
            return Err(ModelError::parameter(
                "T",
                t,
                "must be a finite temperature in °C above absolute zero",
            ));
        }
        let slope = self.activation_energy / (GAS_CONSTANT * std::f64::consts::LN_10);
        Ok(slope * (1.0 / (t + ZERO_CELSIUS) - 1.0 / (self.t_ref + ZERO_CELSIUS)))
    }
}

/// Free per-temperature shift factors: log10 a_T listed for each measured
/// temperature (°C) relative to a reference temperature T_ref (°C).
///
/// The rule (module documentation): exact at listed temperatures and at
/// T_ref (log10 a_T = 0), linear in T between neighbouring ones, an error
/// outside the listed range. This is the only free-shift rule of the code
/// base; front ends build a `FreeShift` rather than interpolating
/// themselves.
#[derive(Debug, Clone, PartialEq)]
pub struct FreeShift {
    t_ref: f64,
    entries: Vec<(f64, f64)>,
    /// What the list holds: log10 a_T, or log10 b_T for a table of
    /// vertical factors ([`super::VerticalShift`]), which follows the same
    /// rule; it names the quantity in messages.
    factor: Factor,
    /// The entries and, unless listed, (T_ref, 0), sorted by temperature:
    /// the knots of the interpolation.
    knots: Vec<(f64, f64)>,
}

impl FreeShift {
    /// Two temperatures closer than this (K) are the same temperature: it
    /// absorbs decimal round-off (20.1 written as 20.099999999999998) while
    /// being far below any temperature a measurement can distinguish.
    pub const TEMPERATURE_TOLERANCE: f64 = 1e-9;

    /// |log10 a_T| allowed at T_ref (round-off of a value meant to be 0).
    const REFERENCE_TOLERANCE: f64 = 1e-12;

    /// Builds a validated list from the reference temperature `t_ref` (°C)
    /// and `(T, log10 a_T)` pairs (°C, decades) in any order. The list must
    /// not be empty, every value must be finite, the temperatures distinct,
    /// and an entry at T_ref, if present, must have log10 a_T = 0. Errors
    /// name the entry (counted from 0).
    pub fn new(t_ref: f64, entries: Vec<(f64, f64)>) -> Result<Self, ModelError> {
        Self::listed(t_ref, entries, Factor::Horizontal)
    }

    /// [`Self::new`] for a list of `factor`.
    pub(super) fn listed(
        t_ref: f64,
        entries: Vec<(f64, f64)>,
        factor: Factor,
    ) -> Result<Self, ModelError> {
        let name = factor.list();
        let quantity = factor.quantity();
        if !t_ref.is_finite() {
            return Err(ModelError::parameter(
                "T_ref",
                t_ref,
                "must be a finite temperature in °C",
            ));
        }
        if entries.is_empty() {
            return Err(ModelError::table(name, "no temperatures listed"));
        }
        for (i, &(t, log_a)) in entries.iter().enumerate() {
            if !t.is_finite() {
                return Err(ModelError::table(
                    name,
                    format!("entry {i}: T = {t} is not a finite temperature"),
                ));
            }
            if !log_a.is_finite() {
                return Err(ModelError::table(
                    name,
                    format!("entry {i} (T = {t} °C): {quantity} = {log_a} is not a finite number"),
                ));
            }
            if let Some(j) = entries[..i]
                .iter()
                .position(|&(tj, _)| same_temperature(t, tj))
            {
                return Err(ModelError::table(
                    name,
                    format!(
                        "entry {i}: T = {t} °C is listed before as entry {j} (T = {} °C); \
                         each temperature may have only one shift",
                        entries[j].0
                    ),
                ));
            }
            if same_temperature(t, t_ref) && log_a.abs() > Self::REFERENCE_TOLERANCE {
                return Err(ModelError::table(
                    name,
                    format!(
                        "entry {i}: T = {t} °C is the reference temperature, so {quantity} \
                         must be 0, not {log_a}"
                    ),
                ));
            }
        }
        let mut knots = entries.clone();
        if !knots.iter().any(|&(t, _)| same_temperature(t, t_ref)) {
            knots.push((t_ref, 0.0));
        }
        // Distinct by more than the tolerance (checked above), so the
        // interpolation never divides by a vanishing temperature step.
        knots.sort_by(|a, b| a.0.total_cmp(&b.0));
        Ok(FreeShift {
            t_ref,
            entries,
            factor,
            knots,
        })
    }

    /// The reference temperature, °C.
    pub fn t_ref(&self) -> f64 {
        self.t_ref
    }

    /// The `(T, log10 a_T)` pairs (°C, decades) in the order given.
    pub fn entries(&self) -> &[(f64, f64)] {
        &self.entries
    }

    /// The temperatures (°C) at which log10 a_T is defined: from the lowest
    /// to the highest of the listed temperatures and T_ref.
    pub fn temperature_range(&self) -> (f64, f64) {
        // `new` refuses an empty list and adds T_ref, so there is a first
        // and a last knot; the fallback only keeps this free of panics.
        match (self.knots.first(), self.knots.last()) {
            (Some(&(lo, _)), Some(&(hi, _))) => (lo, hi),
            _ => (self.t_ref, self.t_ref),
        }
    }

    /// log10 a_T at temperature `t` (°C): the listed value at a listed
    /// temperature (0 at T_ref), linear in T between listed temperatures,
    /// and an error for a non-finite `t` or one outside
    /// [`Self::temperature_range`].
    pub fn log10_shift(&self, t: f64) -> Result<f64, ModelError> {
        if !t.is_finite() {
            return Err(ModelError::parameter(
                "T",
                t,
                "must be a finite temperature in °C",
            ));
        }
        // Listed temperatures first, so that they are returned exactly and
        // round-off in `t` (within the tolerance) does not count as outside.
        if let Some(&(_, log_a)) = self.knots.iter().find(|k| same_temperature(k.0, t)) {
            return Ok(log_a);
        }
        // The first knot above `t`; it has a knot below it exactly when `t`
        // lies inside the range.
        let above = self.knots.partition_point(|k| k.0 < t);
        let below = above.checked_sub(1).and_then(|i| self.knots.get(i));
        match (below, self.knots.get(above)) {
            (Some(&(t0, a0)), Some(&(t1, a1))) => Ok(a0 + (a1 - a0) * (t - t0) / (t1 - t0)),
            _ => {
                let (lo, hi) = self.temperature_range();
                let listed: Vec<String> = self
                    .knots
                    .iter()
                    .map(|&(tk, _)| {
                        if same_temperature(tk, self.t_ref) {
                            format!("{tk} (T_ref)")
                        } else {
                            tk.to_string()
                        }
                    })
                    .collect();
                let (temperature, lowest, highest, listed) = (t, lo, hi, listed.join(", "));
                Err(match self.factor {
                    Factor::Horizontal => ModelError::OutsideFreeShift {
                        temperature,
                        lowest,
                        highest,
                        listed,
                    },
                    Factor::Vertical => ModelError::OutsideVerticalTable {
                        temperature,
                        lowest,
                        highest,
                        listed,
                    },
                })
            }
        }
    }
}

/// The quantity a [`FreeShift`] lists.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Factor {
    /// log10 a_T: a free shift.
    Horizontal,
    /// log10 b_T: a table of vertical factors.
    Vertical,
}

impl Factor {
    /// The list's name in messages.
    fn list(self) -> &'static str {
        match self {
            Factor::Horizontal => "free shift",
            Factor::Vertical => "vertical factors",
        }
    }

    /// The listed quantity in messages.
    fn quantity(self) -> &'static str {
        match self {
            Factor::Horizontal => "log10 a_T",
            Factor::Vertical => "log10 b_T",
        }
    }
}

/// Temperatures (°C) equal to within [`FreeShift::TEMPERATURE_TOLERANCE`].
fn same_temperature(a: f64, b: f64) -> bool {
    (a - b).abs() <= FreeShift::TEMPERATURE_TOLERANCE
}

/// E(ω, T) = b_T E_ref(ω a_T): a modulus at reference temperature, shifted.
#[derive(Debug, Clone, PartialEq)]
pub struct Shifted<M> {
    inner: M,
    log10_a_t: f64,
    shift_factor: f64,
    log10_b_t: f64,
    vertical_factor: f64,
}

/// 10^`log10`, refused unless `log10` is finite and the power a normal
/// binary64 number (|log10| below about 307); `name` names the key.
fn power_of_ten(name: &str, log10: f64) -> Result<f64, ModelError> {
    let factor = 10f64.powf(log10);
    if !log10.is_finite() {
        return Err(ModelError::parameter(
            name,
            log10,
            "must be a finite number",
        ));
    }
    if !factor.is_normal() {
        return Err(ModelError::parameter(
            name,
            log10,
            &format!("must give a representable factor 10^{name} (|{name}| < 307)"),
        ));
    }
    Ok(factor)
}

impl<M: ViscoelasticModulus> Shifted<M> {
    /// Wraps `inner` (the modulus at T_ref) with shift factor 10^`log10_a_t`
    /// and no vertical factor. `log10_a_t` must be finite and
    /// 10^`log10_a_t` a normal binary64 number (|log10 a_T| below about
    /// 307).
    pub fn new(inner: M, log10_a_t: f64) -> Result<Self, ModelError> {
        let shift_factor = power_of_ten("log10_aT", log10_a_t)?;
        Ok(Shifted {
            inner,
            log10_a_t,
            shift_factor,
            log10_b_t: 0.0,
            vertical_factor: 1.0,
        })
    }

    /// The same shift with the vertical factor b_T = 10^`log10_b_t`
    /// (finite, b_T a normal binary64 number): E*(ω) = b_T E*_ref(ω a_T).
    pub fn with_vertical(self, log10_b_t: f64) -> Result<Self, ModelError> {
        let vertical_factor = power_of_ten("log10_bT", log10_b_t)?;
        Ok(Shifted {
            log10_b_t,
            vertical_factor,
            ..self
        })
    }

    /// The modulus at the reference temperature.
    pub fn inner(&self) -> &M {
        &self.inner
    }

    /// log10 a_T.
    pub fn log10_shift(&self) -> f64 {
        self.log10_a_t
    }

    /// The shift factor a_T.
    pub fn shift_factor(&self) -> f64 {
        self.shift_factor
    }

    /// log10 b_T (0 without a vertical factor).
    pub fn log10_vertical(&self) -> f64 {
        self.log10_b_t
    }

    /// The vertical factor b_T.
    pub fn vertical_factor(&self) -> f64 {
        self.vertical_factor
    }
}

impl<M: ViscoelasticModulus> ViscoelasticModulus for Shifted<M> {
    fn modulus(&self, omega: f64) -> Complex64 {
        self.inner.modulus(omega * self.shift_factor) * self.vertical_factor
    }
    fn modulus_and_log_slope(&self, omega: f64) -> (Complex64, Complex64) {
        let (e, slope) = self.inner.modulus_and_log_slope(omega * self.shift_factor);
        (e * self.vertical_factor, slope * self.vertical_factor)
    }
    fn static_modulus(&self) -> f64 {
        self.inner.static_modulus() * self.vertical_factor
    }
    fn loss_slope_at_zero(&self) -> f64 {
        self.inner.loss_slope_at_zero() * self.shift_factor * self.vertical_factor
    }
    fn loss_exponent_at_zero(&self) -> f64 {
        self.inner.loss_exponent_at_zero()
    }
    fn structure_range(&self) -> (f64, f64) {
        let (a, b) = self.inner.structure_range();
        (a / self.shift_factor, b / self.shift_factor)
    }
    fn relaxation_bound(&self) -> Option<f64> {
        // Rescaling ω keeps sup |E*|, and L(ω) = L_ref(ω a_T) ≤ L′_ref(0) a_T ω
        // = L′(0) ω: both parts of the bound carry over. A vertical factor
        // multiplies sup |E*| by b_T and divides L and L′(0) alike.
        self.inner
            .relaxation_bound()
            .map(|bound| bound * self.vertical_factor)
    }
    fn knots(&self) -> Vec<f64> {
        self.inner
            .knots()
            .into_iter()
            .map(|w| w / self.shift_factor)
            .collect()
    }
    fn comparison_modulus(&self) -> Option<Box<dyn ViscoelasticModulus>> {
        self.inner.comparison_modulus().map(|inner| {
            Box::new(Shifted {
                inner,
                log10_a_t: self.log10_a_t,
                shift_factor: self.shift_factor,
                log10_b_t: self.log10_b_t,
                vertical_factor: self.vertical_factor,
            }) as Box<dyn ViscoelasticModulus>
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 100 kJ/mol between 20 and 30 °C: log10 a_T = −E_a ΔT/(R ln10 T T_ref)
    /// = −0.5878 (computed by hand from the formula), zero at T_ref,
    /// positive below it.
    #[test]
    fn arrhenius_by_hand() {
        let a = Arrhenius::new(20.0, 1e5).unwrap();
        let hand = -1e5 * 10.0 / (8.314462618 * 10f64.ln() * 303.15 * 293.15);
        assert!((a.log10_shift(30.0).unwrap() - hand).abs() < 1e-12);
        assert!((hand + 0.5878).abs() < 1e-4);
        assert_eq!(a.log10_shift(20.0).unwrap(), 0.0);
        assert!(a.log10_shift(0.0).unwrap() > 0.0);
        assert!(a.log10_shift(-300.0).is_err());
        assert!(Arrhenius::new(20.0, -1.0).is_err());
    }
    use crate::modulus::{Prony, StandardLinearSolid, TabulatedModulus};

    fn wlf() -> Wlf {
        Wlf::new(20.0, 8.86, 101.6).unwrap()
    }

    #[test]
    fn wlf_follows_its_formula_and_sign_convention() {
        let w = wlf();
        assert_eq!(w.log10_shift(20.0).unwrap(), 0.0);
        let above = w.log10_shift(50.0).unwrap();
        assert!((above - (-8.86 * 30.0 / 131.6)).abs() < 1e-15);
        // Warmer: a_T < 1; cooler: a_T > 1.
        assert!(above < 0.0);
        assert!(w.log10_shift(0.0).unwrap() > 0.0);
        // Far above T_ref the shift saturates at −C1.
        assert!((w.log10_shift(1e9).unwrap() + 8.86).abs() < 1e-6);
    }

    #[test]
    fn ten_kelvin_is_about_one_decade() {
        // The paper: about 10 °C less shifts μ(v) by about one decade.
        let w = wlf();
        let cooler = w.log10_shift(10.0).unwrap();
        let warmer = w.log10_shift(30.0).unwrap();
        assert!((cooler - 0.967).abs() < 1e-3, "{cooler}");
        assert!((warmer + 0.794).abs() < 1e-3, "{warmer}");
        // The loss peak of a solid moves by the same amount: 10 K cooler puts
        // it a decade lower in frequency (a stiffer, lossier solid at fixed ω).
        let sls = StandardLinearSolid::new(1e6, 1e8, 1.0).unwrap();
        let cold = Shifted::new(sls.clone(), cooler).unwrap();
        let peak = |m: &dyn ViscoelasticModulus| {
            (0..=6000)
                .map(|i| 10f64.powf(-2.0 + i as f64 * 1e-3))
                .max_by(|&a, &b| m.modulus(a).im.total_cmp(&m.modulus(b).im))
                .unwrap()
        };
        let shift_decades = (peak(&sls) / peak(&cold)).log10();
        assert!((shift_decades - cooler).abs() < 2e-3, "{shift_decades}");
        assert!(cold.modulus(10.0).norm() > sls.modulus(10.0).norm());
    }

    #[test]
    fn wlf_validation_and_divergence() {
        assert!(Wlf::new(f64::NAN, 8.86, 101.6).is_err());
        assert!(Wlf::new(f64::INFINITY, 8.86, 101.6).is_err());
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                Wlf::new(20.0, bad, 101.6),
                Err(ModelError::InvalidParameter { ref name, .. }) if name == "C1"
            ));
            assert!(matches!(
                Wlf::new(20.0, 8.86, bad),
                Err(ModelError::InvalidParameter { ref name, .. }) if name == "C2"
            ));
        }
        let w = wlf();
        // T_ref − C2 = −81.6 °C: the pole, and everything below it.
        for t in [-81.6, -90.0, -300.0] {
            match w.log10_shift(t) {
                Err(e @ ModelError::WlfBeyondPole { .. }) => {
                    let msg = e.to_string();
                    assert!(msg.contains(&format!("T = {t} °C")), "{msg}");
                    assert!(msg.contains("C2"), "{msg}");
                }
                other => panic!("{t}: {other:?}"),
            }
        }
        assert!(w.log10_shift(-81.5).unwrap() > 1000.0);
        assert!(w.log10_shift(f64::NAN).is_err());
    }

    /// The problem of an out-of-range or otherwise refused temperature.
    fn refusal(f: &FreeShift, t: f64) -> String {
        match f.log10_shift(t) {
            Err(e @ ModelError::OutsideFreeShift { .. }) => e.to_string(),
            Err(ModelError::InvalidParameter { name, .. }) => name,
            other => panic!("T = {t}: expected a refusal, got {other:?}"),
        }
    }

    #[test]
    fn free_shift_is_exact_at_listed_temperatures_and_linear_between() {
        // Listed out of order, T_ref among them.
        let f = FreeShift::new(20.0, vec![(40.0, -1.5), (0.0, 2.1), (20.0, 0.0)]).unwrap();
        assert_eq!(f.log10_shift(0.0).unwrap(), 2.1);
        assert_eq!(f.log10_shift(40.0).unwrap(), -1.5);
        assert_eq!(f.log10_shift(20.0).unwrap(), 0.0);
        // Round-off in a temperature is not a different temperature.
        assert_eq!(f.log10_shift(0.1 + 0.2 + 39.7).unwrap(), -1.5);
        assert_eq!(f.log10_shift(0.1 + 0.2 - 0.3).unwrap(), 2.1);
        // Linear in T between neighbours.
        assert!((f.log10_shift(10.0).unwrap() - 1.05).abs() < 1e-15);
        assert!((f.log10_shift(30.0).unwrap() + 0.75).abs() < 1e-15);
        assert!((f.log10_shift(35.0).unwrap() + 1.125).abs() < 1e-15);
        // Continuous at the listed temperatures.
        for (t, log_a) in [(0.0, 2.1), (20.0, 0.0), (40.0, -1.5)] {
            for dt in [-1e-6, 1e-6] {
                if let Ok(v) = f.log10_shift(t + dt) {
                    assert!((v - log_a).abs() < 1e-6, "{t} {dt}: {v}");
                }
            }
        }
        assert_eq!(f.temperature_range(), (0.0, 40.0));
        assert_eq!(f.t_ref(), 20.0);
        assert_eq!(f.entries(), &[(40.0, -1.5), (0.0, 2.1), (20.0, 0.0)]);
    }

    #[test]
    fn free_shift_counts_the_reference_temperature_as_listed() {
        // T_ref = 20 °C is not listed but known: log10 a_T = 0 there.
        let f = FreeShift::new(20.0, vec![(60.0, -3.0)]).unwrap();
        assert_eq!(f.log10_shift(20.0).unwrap(), 0.0);
        assert!((f.log10_shift(40.0).unwrap() + 1.5).abs() < 1e-15);
        assert_eq!(f.temperature_range(), (20.0, 60.0));
        // T_ref outside the listed temperatures widens the range.
        let f = FreeShift::new(20.0, vec![(-20.0, 4.0), (0.0, 2.0)]).unwrap();
        assert_eq!(f.temperature_range(), (-20.0, 20.0));
        assert!((f.log10_shift(10.0).unwrap() - 1.0).abs() < 1e-15);
        // A list holding T_ref only is defined at T_ref only.
        let f = FreeShift::new(20.0, vec![(20.0, 0.0)]).unwrap();
        assert_eq!(f.log10_shift(20.0).unwrap(), 0.0);
        assert!(f.log10_shift(20.5).is_err());
    }

    #[test]
    fn free_shift_refuses_outside_the_listed_range() {
        let f = FreeShift::new(20.0, vec![(0.0, 2.1), (40.0, -1.5)]).unwrap();
        for t in [-0.5, 40.001, -300.0, 1e6] {
            let msg = refusal(&f, t);
            assert!(msg.contains(&format!("T = {t} °C")), "{msg}");
            assert!(msg.contains("outside"), "{msg}");
            assert!(msg.contains("0 to 40 °C"), "{msg}");
            assert!(msg.contains("0, 20 (T_ref), 40"), "{msg}");
            assert!(msg.contains("not extrapolated"), "{msg}");
        }
        for t in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(refusal(&f, t), "T");
        }
    }

    #[test]
    fn free_shift_validation() {
        let problem = |t_ref: f64, e: Vec<(f64, f64)>| match FreeShift::new(t_ref, e) {
            Err(ModelError::InvalidTable { problem, .. }) => problem,
            other => panic!("{other:?}"),
        };
        assert!(FreeShift::new(f64::NAN, vec![(0.0, 0.0)]).is_err());
        assert!(problem(20.0, vec![]).contains("no temperatures"));
        assert!(problem(20.0, vec![(0.0, 1.0), (f64::NAN, 0.0)]).starts_with("entry 1: T = NaN"));
        assert!(problem(20.0, vec![(0.0, f64::INFINITY)]).starts_with("entry 0 (T = 0 °C)"));
        let msg = problem(20.0, vec![(0.0, 1.0), (40.0, -1.0), (0.0, 1.2)]);
        assert!(
            msg.starts_with("entry 2: T = 0 °C is listed before as entry 0"),
            "{msg}"
        );
        let msg = problem(20.0, vec![(0.0, 1.0), (20.0, 0.3)]);
        assert!(
            msg.starts_with("entry 1: T = 20 °C is the reference"),
            "{msg}"
        );
    }

    /// Every trait method of `Shifted` against the unshifted modulus, with
    /// the vertical factor 10^`log10_b_t`.
    fn check_shifted<M: ViscoelasticModulus + Clone>(reference: M, log10_a_t: f64, log10_b_t: f64) {
        let a_t = 10f64.powf(log10_a_t);
        let b_t = 10f64.powf(log10_b_t);
        let s = Shifted::new(reference.clone(), log10_a_t)
            .unwrap()
            .with_vertical(log10_b_t)
            .unwrap();
        assert_eq!(s.shift_factor(), a_t);
        assert_eq!(s.log10_shift(), log10_a_t);
        assert_eq!(s.vertical_factor(), b_t);
        assert_eq!(s.log10_vertical(), log10_b_t);
        for &w in &[0.0, 1e-5, 3e-2, 1.0, 7.0, 2e3, 1e7] {
            assert_eq!(s.modulus(w), reference.modulus(w * a_t) * b_t);
            let (e, slope) = s.modulus_and_log_slope(w);
            let (e_ref, slope_ref) = reference.modulus_and_log_slope(w * a_t);
            assert_eq!((e, slope), (e_ref * b_t, slope_ref * b_t));
            if w > 0.0 {
                // The log slope of the shifted curve, by finite differences.
                let h = 1e-6f64;
                let fd = (s.modulus(w * h.exp()) - s.modulus(w * (-h).exp())) / (2.0 * h);
                assert!((fd - slope).norm() < 1e-6 * e.norm(), "{w}");
            }
        }
        assert_eq!(s.static_modulus(), reference.static_modulus() * b_t);
        let slope0 = s.loss_slope_at_zero();
        assert!((slope0 / (b_t * a_t * reference.loss_slope_at_zero()) - 1.0).abs() < 1e-15);
        // lim E″/ω of the shifted curve, directly.
        let w = 1e-9 * s.structure_range().0;
        assert!((s.modulus(w).im / w / slope0 - 1.0).abs() < 1e-6);
        let (lo, hi) = reference.structure_range();
        assert_eq!(s.structure_range(), (lo / a_t, hi / a_t));
        assert_eq!(
            s.relaxation_bound(),
            reference.relaxation_bound().map(|e1| e1 * b_t)
        );
        // The bound's promise, sup |E*| ≤ bound, on the scaled curve.
        if let Some(bound) = s.relaxation_bound() {
            for i in 0..=80 {
                let w = 10f64.powf(-8.0 + 0.2 * f64::from(i));
                assert!(s.modulus(w).norm() <= bound * (1.0 + 1e-12), "{w}");
            }
        }
    }

    #[test]
    fn shifted_is_the_reference_at_scaled_frequency() {
        let sls = StandardLinearSolid::new(1e6, 1e8, 0.1).unwrap();
        let prony = Prony::new(1e8, vec![5e7, 3e7, 1.5e7], vec![1e-4, 1e-2, 1.0]).unwrap();
        let omega: Vec<f64> = (0..=50)
            .map(|i| 10f64.powf(-4.0 + 0.2 * i as f64))
            .collect();
        let e: Vec<Complex64> = omega.iter().map(|&w| sls.modulus(w)).collect();
        let table = TabulatedModulus::new(
            omega,
            e.iter().map(|z| z.re).collect(),
            e.iter().map(|z| z.im).collect(),
        )
        .unwrap();
        for (log_a, log_b) in [
            (-2.5, 0.0),
            (0.0, 0.0),
            (0.967, 0.0),
            (4.0, 0.0),
            (0.967, -0.05),
            (-2.5, 0.3),
        ] {
            check_shifted(sls.clone(), log_a, log_b);
            check_shifted(prony.clone(), log_a, log_b);
            check_shifted(table.clone(), log_a, log_b);
        }
        // Zero shift is the identity.
        let s = Shifted::new(sls.clone(), 0.0).unwrap();
        assert_eq!(s.modulus(3.0), sls.modulus(3.0));
        assert_eq!(s.inner(), &sls);
    }

    #[test]
    fn shifted_validation() {
        let sls = StandardLinearSolid::new(1e6, 1e8, 1.0).unwrap();
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 400.0, -400.0] {
            assert!(matches!(
                Shifted::new(sls.clone(), bad),
                Err(ModelError::InvalidParameter { ref name, .. }) if name == "log10_aT"
            ));
        }
        assert!(Shifted::new(sls.clone(), 300.0).is_ok());
        for bad in [f64::NAN, f64::INFINITY, 400.0, -400.0] {
            assert!(matches!(
                Shifted::new(sls.clone(), 0.0).unwrap().with_vertical(bad),
                Err(ModelError::InvalidParameter { ref name, .. }) if name == "log10_bT"
            ));
        }
    }
}
