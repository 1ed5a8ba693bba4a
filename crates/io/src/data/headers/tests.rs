//! Which quantity and unit header cells name.

use super::*;
use crate::units::Conversion;

fn column(raw: &str) -> (Quantity, Option<(String, Conversion)>) {
    match classify(raw) {
        Header::Column { quantity, unit } => (quantity, unit.map(|u| (u.label, u.conversion))),
        other => panic!("{raw:?}: {other:?}"),
    }
}

fn scale(pow10: i32, divisor: f64) -> Conversion {
    Conversion::Scale { pow10, divisor }
}

#[test]
fn speed_names_and_units() {
    for raw in [
        "v",
        "V",
        "velocity",
        "Speed",
        "rolling speed",
        "Rolling_Speed",
        "vel",
    ] {
        assert_eq!(column(raw), (Quantity::Speed, None), "{raw}");
    }
    let cases = [
        ("v_m_s", "m/s", 0, 1.0),
        ("v_mm_s", "mm/s", -3, 1.0),
        ("v_um_s", "µm/s", -6, 1.0),
        ("v_µm_s", "µm/s", -6, 1.0),
        ("velocity (mm/s)", "mm/s", -3, 1.0),
        ("speed_um_s", "µm/s", -6, 1.0),
        ("speed [m/s]", "m/s", 0, 1.0),
        ("Speed (m/s)", "m/s", 0, 1.0),
        ("rolling speed (mm/s)", "mm/s", -3, 1.0),
        ("Velocity [µm/s]", "µm/s", -6, 1.0),
        ("v (μm/s)", "µm/s", -6, 1.0),
        ("v [cm/s]", "cm/s", -2, 1.0),
        ("v (nm/s)", "nm/s", -9, 1.0),
        ("v (mm/min)", "mm/min", -3, 60.0),
        ("speed (m/min)", "m/min", 0, 60.0),
        ("v (m/h)", "m/h", 0, 3600.0),
        ("v (mm/ms)", "mm/ms", 0, 1.0),
        ("v [m s-1]", "m/s", 0, 1.0),
        ("v [mm s^-1]", "mm/s", -3, 1.0),
        ("v (mm·s⁻¹)", "mm/s", -3, 1.0),
        ("v/(mm/s)", "mm/s", -3, 1.0),
        ("speed mm/s", "mm/s", -3, 1.0),
        ("speed in mm/s", "mm/s", -3, 1.0),
        ("v_mm_per_s", "mm/s", -3, 1.0),
        ("Speed(mm/s)", "mm/s", -3, 1.0),
    ];
    for (raw, label, pow10, divisor) in cases {
        assert_eq!(
            column(raw),
            (
                Quantity::Speed,
                Some((label.to_string(), scale(pow10, divisor)))
            ),
            "{raw}"
        );
    }
    for (raw, unit) in [
        ("v_furlong_s", "furlong/s"),
        ("speed (furlong/fortnight)", "furlong/fortnight"),
        ("v (V)", "V"),
    ] {
        assert_eq!(
            classify(raw),
            Header::BadUnit {
                quantity: Quantity::Speed,
                unit: unit.into()
            },
            "{raw}"
        );
    }
    for raw in [
        "v_reduced",
        "velocity profile",
        "v2",
        "vx (mm/s)",
        "(mm/s)",
        "",
    ] {
        assert_eq!(classify(raw), Header::Other, "{raw}");
    }
}

#[test]
fn friction_sigma_and_temperature_names() {
    for raw in [
        "mu",
        "MU",
        "µ",
        "μ",
        "COF",
        "cof",
        "friction coefficient",
        "friction_coefficient",
        "Friction Coefficient (-)",
        "Coefficient of friction",
        "µ [-]",
        "mu_measured",
    ] {
        assert_eq!(column(raw), (Quantity::Friction, None), "{raw}");
    }
    assert_eq!(
        column("COF (%)"),
        (Quantity::Friction, Some(("%".into(), scale(-2, 1.0))))
    );
    for raw in [
        "sigma",
        "std",
        "sd",
        "mu_std",
        "sigma_mu",
        "COF std",
        "µ std",
        "Std. Dev.",
        "SD (-)",
    ] {
        assert_eq!(column(raw), (Quantity::Sigma, None), "{raw}");
    }
    for raw in ["T", "temperature", "Temp"] {
        assert_eq!(column(raw), (Quantity::Temperature, None), "{raw}");
    }
    let celsius = Some(("°C".to_string(), Conversion::NONE));
    let kelvin = Some(("K".to_string(), Conversion::Kelvin));
    let fahrenheit = Some(("°F".to_string(), Conversion::Fahrenheit));
    for (raw, unit) in [
        ("T_C", &celsius),
        ("T (°C)", &celsius),
        ("T [°C]", &celsius),
        ("temperature (C)", &celsius),
        ("Temperature [degC]", &celsius),
        ("t_C", &celsius),
        ("T_K", &kelvin),
        ("T (K)", &kelvin),
        ("temperature [kelvin]", &kelvin),
        ("T_F", &fahrenheit),
        ("T (°F)", &fahrenheit),
    ] {
        assert_eq!(column(raw), (Quantity::Temperature, unit.clone()), "{raw}");
    }
    for raw in [
        "t",
        "t (s)",
        "T [min]",
        "time",
        "mu_exact",
        "mu_low_speed",
        "T_ref",
    ] {
        assert_eq!(classify(raw), Header::Other, "{raw}");
    }
    for (raw, quantity) in [
        ("mu (N)", Quantity::Friction),
        ("sigma (%)", Quantity::Sigma),
        ("T (R)", Quantity::Temperature),
    ] {
        assert!(
            matches!(classify(raw), Header::BadUnit { quantity: q, .. } if q == quantity),
            "{raw}"
        );
    }
}
