//! The four quantities of measured data (docs/ARCHITECTURE.md, "Contract",
//! "Measured data"): speed, friction coefficient, its standard deviation
//! and temperature, with their canonical column names and how messages
//! name them and the spellings and units understood. Which header names
//! and units map to them is [`super::headers`]' and [`super::units`]'.

use crate::columns::MU;
use crate::fit_dir::columns::{SIGMA, T, V};

/// A quantity a measured-data file gives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// Rolling speed v, m/s.
    Speed,
    /// Friction coefficient μ.
    Friction,
    /// Standard deviation of μ.
    Sigma,
    /// Temperature, °C.
    Temperature,
}

impl Quantity {
    /// In the order of the columns of a [`super::DataTable`].
    pub const ALL: [Quantity; 4] = [
        Quantity::Speed,
        Quantity::Friction,
        Quantity::Sigma,
        Quantity::Temperature,
    ];

    /// The canonical column name (docs/ARCHITECTURE.md, "Contract",
    /// "Measured data"): the names a fit folder's mu.csv and the forward
    /// CSV write.
    pub fn key(self) -> &'static str {
        match self {
            Quantity::Speed => V,
            Quantity::Friction => MU,
            Quantity::Sigma => SIGMA,
            Quantity::Temperature => T,
        }
    }

    /// What the quantity is, for messages ("no speed column").
    pub fn what(self) -> &'static str {
        match self {
            Quantity::Speed => "speed",
            Quantity::Friction => "friction",
            Quantity::Sigma => "sigma (standard deviation of mu)",
            Quantity::Temperature => "temperature",
        }
    }

    /// The names understood, for messages.
    pub fn understood(self) -> &'static str {
        match self {
            Quantity::Speed => {
                "v, velocity, speed, rolling speed, with or without a unit: v, v_mm_s, \
                 velocity (mm/s), speed [m/s], …"
            }
            Quantity::Friction => "mu, µ, COF, friction coefficient, coefficient of friction, …",
            Quantity::Sigma => "sigma, std, sd, mu_std, sigma_mu, COF std, …",
            Quantity::Temperature => "T, temperature, T_C, T (°C), T_K, T [K], …",
        }
    }

    /// The SI unit of the values in a [`super::DataTable`] ("" for a
    /// dimensionless quantity).
    pub fn si_unit(self) -> &'static str {
        match self {
            Quantity::Speed => "m/s",
            Quantity::Temperature => "°C",
            Quantity::Friction | Quantity::Sigma => "",
        }
    }

    /// The units understood, for messages.
    pub fn units(self) -> &'static str {
        match self {
            Quantity::Speed => {
                "m/s, cm/s, mm/s, µm/s (um/s), nm/s, or any of these lengths per s, ms, min \
                 or h (mm/min, m/h); also written m s-1, mm·s⁻¹ or, after an underscore, v_mm_s"
            }
            Quantity::Temperature => "°C (C, degC, celsius), K (kelvin), °F (F, fahrenheit)",
            Quantity::Friction => "none (-, 1) or %",
            Quantity::Sigma => "none (-, 1)",
        }
    }

    /// The index of the quantity in [`Quantity::ALL`].
    pub fn index(self) -> usize {
        self as usize
    }
}
