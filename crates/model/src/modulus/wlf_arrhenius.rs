//! The shift of an amorphous polymer through its glass transition: WLF
//! above a junction temperature T_g, Arrhenius below, continuous at T_g.
//!
//! With f(T) = −C1 (T − T_ref)/(C2 + T − T_ref) for T ≥ T_g and
//! f(T) = f(T_g) + E_a/(R ln 10) (1/T − 1/T_g) below (T in K inside the
//! formula), log10 a_T = f(T) − f(T_ref), so that a_{T_ref} = 1 wherever
//! T_ref lies. WLF's free-volume form holds above T_g; below it the
//! frozen-in free volume leaves an activated process (Ferry ch. 11). The
//! slope may jump at T_g; the value does not.
//!
//! # References
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley 1980,
//!   ch. 11.

use super::shift::{Arrhenius, Wlf, ZERO_CELSIUS};
use crate::error::ModelError;

/// WLF above `t_junction`, Arrhenius below; temperatures in °C.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WlfArrhenius {
    wlf: Wlf,
    /// The junction T_g, °C.
    t_junction: f64,
    below: Arrhenius,
}

impl WlfArrhenius {
    /// Validated constants: WLF's (`t_ref` °C, `c1`, `c2` K, positive, with
    /// C2 + T_g − T_ref > 0 so that WLF is defined at the junction), the
    /// junction `t_junction` (°C, above absolute zero) and the activation
    /// energy below it (J/mol, positive).
    pub fn new(
        t_ref: f64,
        c1: f64,
        c2: f64,
        t_junction: f64,
        activation_energy: f64,
    ) -> Result<Self, ModelError> {
        let wlf = Wlf::new(t_ref, c1, c2)?;
        if !(t_junction.is_finite() && t_junction > -ZERO_CELSIUS) {
            return Err(ModelError::parameter(
                "T_g",
                t_junction,
                "must be a finite temperature in °C above absolute zero",
            ));
        }
        // WLF must be defined at the junction, where the branches meet.
        wlf.log10_shift(t_junction)?;
        let below = Arrhenius::new(t_junction, activation_energy)?;
        Ok(WlfArrhenius {
            wlf,
            t_junction,
            below,
        })
    }

    /// Reference temperature, °C.
    pub fn t_ref(&self) -> f64 {
        self.wlf.t_ref
    }

    /// The junction T_g, °C.
    pub fn t_junction(&self) -> f64 {
        self.t_junction
    }

    /// f(T) of the module doc.
    fn shape(&self, t: f64) -> Result<f64, ModelError> {
        if t >= self.t_junction {
            self.wlf.log10_shift(t)
        } else {
            Ok(self.wlf.log10_shift(self.t_junction)? + self.below.log10_shift(t)?)
        }
    }

    /// log10 a_T at `t` (°C): an error for a non-finite `t`, one at or
    /// below absolute zero, or one where WLF diverges.
    pub fn log10_shift(&self, t: f64) -> Result<f64, ModelError> {
        Ok(self.shape(t)? - self.shape(self.wlf.t_ref)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// WLF above the junction, Arrhenius's slope below, continuous at T_g,
    /// 0 at T_ref on either side of the junction.
    #[test]
    fn branches_meet_at_the_junction() {
        let law = WlfArrhenius::new(20.0, 8.86, 101.6, -20.0, 2e5).unwrap();
        let wlf = Wlf::new(20.0, 8.86, 101.6).unwrap();
        for t in [-20.0, 0.0, 40.0] {
            assert!((law.log10_shift(t).unwrap() - wlf.log10_shift(t).unwrap()).abs() < 1e-12);
        }
        let arrhenius = Arrhenius::new(-20.0, 2e5).unwrap();
        let below = law.log10_shift(-40.0).unwrap() - law.log10_shift(-20.0).unwrap();
        assert!((below - arrhenius.log10_shift(-40.0).unwrap()).abs() < 1e-12);
        let eps = 1e-9;
        assert!(
            (law.log10_shift(-20.0 - eps).unwrap() - law.log10_shift(-20.0).unwrap()).abs() < 1e-6
        );
        let cold_ref = WlfArrhenius::new(-40.0, 8.86, 101.6, -20.0, 2e5).unwrap();
        assert_eq!(cold_ref.log10_shift(-40.0).unwrap(), 0.0);
        assert!(WlfArrhenius::new(20.0, 8.86, 30.0, -20.0, 2e5).is_err());
    }
}
