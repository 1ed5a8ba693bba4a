//! Checks 1, 2 and 4 of [`super`]: a material given in the scene, or a
//! fit's material judged where the data determine it (the module doc of
//! [`super`], "A fitted material is judged where the data determine it").

use num_complex::Complex64;

use super::{
    MAX_CONTACT_RATIO, MAX_GLASSY_MODULUS, MIN_RUBBER_MODULUS, Softest, Warning, blame, broken,
    contact_at, implausible_load, implausible_radius, large_contact, ln_pressure, num, of_speeds,
    sig, size_name, usable, warning,
};
use crate::contact::ContactSize;
use crate::scene::RollingSetup;

/// Checks of a material given in the scene's `[material]` (or fitted, when
/// `fitted`, and judged on the whole frequency axis; a fit's own material
/// is judged where the data determine it, [`fitted_material_warnings`]):
/// checks 1, 2 and 4. `modulus` is Young's E*(ω) (Pa, ω in rad/s),
/// `static_modulus` E0 and `glassy_modulus` E1 (Pa).
pub fn material_warnings(
    setup: &RollingSetup,
    speeds: &[f64],
    modulus: &dyn Fn(f64) -> Complex64,
    static_modulus: f64,
    glassy_modulus: f64,
    fitted: bool,
) -> Vec<Warning> {
    let material = Material {
        modulus,
        static_modulus,
        glassy_modulus,
        fitted,
        window: None,
    };
    material_checks(setup, speeds, &material)
}

/// Checks 1, 2 and 4 of a fitted material, judged where the data
/// determine it: `window` = [ω_min, ω_max] (rad/s, at the reference state
/// of `speeds`, the reduced speeds v·a_T). The modulus at a contact
/// frequency outside the window is taken at the window's nearer end (the
/// Prony series beyond it is an extrapolation the data do not fix), the
/// modulus range is that of |E| inside the window, and E0 or E1 outside
/// the plausible range is an extrapolation, warned about but never an
/// assumption the fit breaks. Under `size = "static"` the contact is
/// E0's, as the model computes it.
pub fn fitted_material_warnings(
    setup: &RollingSetup,
    speeds: &[f64],
    modulus: &dyn Fn(f64) -> Complex64,
    static_modulus: f64,
    glassy_modulus: f64,
    window: [f64; 2],
) -> Vec<Warning> {
    let material = Material {
        modulus,
        static_modulus,
        glassy_modulus,
        fitted: true,
        window: Some(window),
    };
    material_checks(setup, speeds, &material)
}

/// A material under check.
struct Material<'m> {
    /// Young's E*(ω), Pa.
    modulus: &'m dyn Fn(f64) -> Complex64,
    /// E0, Pa.
    static_modulus: f64,
    /// E1, Pa.
    glassy_modulus: f64,
    /// Fitted (warnings point at the anchor) or given.
    fitted: bool,
    /// Where a fitted modulus is determined, rad/s; None: everywhere.
    window: Option<[f64; 2]>,
}

impl Material<'_> {
    /// E*(ω), ω taken into the window.
    fn at(&self, omega: f64) -> Complex64 {
        match self.window {
            Some([lo, hi]) if omega.is_finite() => (self.modulus)(omega.clamp(lo, hi)),
            _ => (self.modulus)(omega),
        }
    }

    /// The smallest and largest |E| (Pa) inside the window, each with its
    /// ω (rad/s), on a grid of ten points per decade.
    fn window_range(&self, [lo, hi]: [f64; 2]) -> Option<((f64, f64), (f64, f64))> {
        if !(lo > 0.0 && hi >= lo && hi.is_finite()) {
            return None;
        }
        let decades = (hi / lo).log10();
        let n = ((10.0 * decades).ceil() as usize).clamp(1, 400);
        let mut low = (f64::INFINITY, lo);
        let mut high = (f64::NEG_INFINITY, lo);
        for k in 0..=n {
            let omega = lo * 10f64.powf(decades * k as f64 / n as f64);
            let e = (self.modulus)(omega).norm();
            if !e.is_finite() {
                continue;
            }
            if e < low.0 {
                low = (e, omega);
            }
            if e > high.0 {
                high = (e, omega);
            }
        }
        low.0.is_finite().then_some((low, high))
    }
}

/// Checks 1, 2 and 4 of `m` (see [`material_warnings`] and
/// [`fitted_material_warnings`]).
fn material_checks(setup: &RollingSetup, speeds: &[f64], m: &Material<'_>) -> Vec<Warning> {
    let mut out = Vec::new();
    let g = setup.geometry;
    let (static_modulus, fitted) = (m.static_modulus, m.fitted);
    let e0_ok = static_modulus.is_finite() && static_modulus > 0.0;
    let range = m.window.and_then(|w| m.window_range(w));
    // The modulus a unit slip would show in: E0, or for a fit judged in
    // its window the smallest |E| there.
    let softest = match range {
        Some(((e, omega), _)) => Softest {
            modulus: e,
            label: format!("|E| at ω = {} rad/s", sig(omega)),
        },
        None => Softest {
            modulus: static_modulus,
            label: "E0".into(),
        },
    };
    if e0_ok && usable(setup) {
        let at = |omega: f64| m.at(omega);
        if let Some(large) = large_contact(setup, speeds, &at, static_modulus) {
            let (size, symbol) = size_name(g.shape);
            let at = match setup.contact {
                ContactSize::Dynamic => format!(
                    "with |E| = {} Pa at ω ≈ v/{symbol} = {} rad/s",
                    sig(large.modulus),
                    sig(large.omega)
                ),
                ContactSize::Static => format!("with E(0) = {} Pa", sig(large.modulus)),
            };
            let (key, advice) = blame(setup, &softest, fitted);
            out.push(broken(
                "small contact",
                warning(
                    key,
                    format!(
                        "the Hertz contact {size} {symbol} = {} m at v = {} m/s ({at}) is larger \
                     than R/3 = {} m (R = {} m){}: the theory assumes a contact small against \
                     the body (Hertz pressure on a half-space), so μ there is unreliable; {advice}",
                        sig(large.size),
                        num(large.speed),
                        sig(g.radius * MAX_CONTACT_RATIO),
                        num(g.radius),
                        of_speeds(large.count, speeds.len()),
                    ),
                ),
            ));
        }
        if let Some(w) = large_strain(setup, speeds, m, &softest) {
            out.push(w);
        }
    }
    match (m.window, range) {
        (Some(window), Some((low, high))) => {
            out.extend(window_modulus(setup, window, low, high));
            out.extend(extrapolated_moduli(m, window));
        }
        _ => {
            if e0_ok && static_modulus < MIN_RUBBER_MODULUS {
                out.push(soft_rubber(setup, static_modulus, fitted));
            }
            if m.glassy_modulus > MAX_GLASSY_MODULUS {
                out.push(stiff_glass(setup, m.glassy_modulus, fitted));
            }
        }
    }
    out
}

/// Check 2: strains p_a/E above 1. Given materials (and fits under
/// `size = "static"`): the static contact against E0 (the worst case: the
/// rubber is softest there). A fit judged in its window: the contact at
/// each measured (reduced) speed against |E| at its frequency, the
/// modulus taken into the window.
fn large_strain(
    setup: &RollingSetup,
    speeds: &[f64],
    m: &Material<'_>,
    softest: &Softest,
) -> Option<Warning> {
    let e0 = m.static_modulus;
    let origin = if m.fitted { "fitted" } else { "given" };
    let (key, advice) = blame(setup, softest, m.fitted);
    let dynamic = m.window.is_some() && setup.contact == ContactSize::Dynamic;
    if !dynamic {
        let ln_p = ln_pressure(setup, setup.ln_contact_size(e0));
        return (ln_p > e0.ln()).then(|| {
            broken(
                "small strain",
                warning(
                    key,
                    format!(
                        "the mean contact pressure p_a = {} Pa of the static Hertz contact exceeds \
                     the {origin} static modulus E0 = {} Pa: strains of order p_a/E0 > 1 are \
                     not small, and linear viscoelasticity, on which the theory rests, fails; \
                     {advice}",
                        sig(ln_p.exp()),
                        sig(e0)
                    ),
                ),
            )
        });
    }
    let at = |omega: f64| m.at(omega);
    let mut worst: Option<(f64, f64, f64, f64)> = None;
    for &v in speeds.iter().filter(|v| v.is_finite() && **v > 0.0) {
        let (ln_r, e) = contact_at(setup, &at, e0, v);
        let excess = ln_pressure(setup, ln_r) - e.ln();
        if excess > 0.0 && worst.is_none_or(|w| excess > w.0) {
            worst = Some((excess, v, ln_pressure(setup, ln_r).exp(), e));
        }
    }
    let (_, v, p, e) = worst?;
    Some(broken(
        "small strain",
        warning(
            key,
            format!(
                "the mean contact pressure p_a = {} Pa of the Hertz contact at v = {} m/s exceeds \
                 the fitted |E| = {} Pa there: strains of order p_a/|E| > 1 are not small, and \
                 linear viscoelasticity, on which the theory rests, fails; {advice}",
                sig(p),
                num(v),
                sig(e)
            ),
        ),
    ))
}

/// Check 4 inside the window a fit determines: |E| there (`low`, `high`:
/// the smallest and largest, each with its ω) outside any viscoelastic
/// solid's, an assumption the fitted material breaks.
fn window_modulus(
    setup: &RollingSetup,
    [lo, hi]: [f64; 2],
    low: (f64, f64),
    high: (f64, f64),
) -> Vec<Warning> {
    let mut out = Vec::new();
    let window = format!("ω = {} … {} rad/s", sig(lo), sig(hi));
    if low.0 < MIN_RUBBER_MODULUS {
        out.push(outside_any_solid(
            setup,
            (
                "fit.E0",
                "this number points at a unit slip: check geometry.radius (m) and geometry.load \
                 (N for a sphere, N/m for a cylinder), and anchor the modulus scale in [fit] (E0, \
                 E_at or contact_radius)",
            ),
            low,
            &window,
            format!(
                "below any viscoelastic solid's (the softest elastomers start near {} Pa)",
                num(MIN_RUBBER_MODULUS)
            ),
        ));
    }
    if high.0 > MAX_GLASSY_MODULUS {
        out.push(outside_any_solid(
            setup,
            (
                "fit.E1_max",
                "this number points at a unit slip: check geometry.radius (m) and geometry.load, \
                 and anchor the modulus scale in [fit] (E0, E_at or contact_radius)",
            ),
            high,
            &window,
            format!(
                "above any viscoelastic solid's (glassy polymers and filled compounds reach 1e10 \
                 Pa; {} Pa is nearer the steel ball itself)",
                num(MAX_GLASSY_MODULUS)
            ),
        ));
    }
    out
}

/// Check 4's warning for the fitted |E| = `at`.0 Pa at ω = `at`.1 rad/s
/// inside `window`, `beyond` any solid's range; it names the radius or the
/// load if either is implausible on its own, else `fallback` (key, advice).
fn outside_any_solid(
    setup: &RollingSetup,
    fallback: (&'static str, &str),
    at: (f64, f64),
    window: &str,
    beyond: String,
) -> Warning {
    let (key, advice) = implausible_radius(setup)
        .or_else(|| implausible_load(setup))
        .unwrap_or_else(|| (fallback.0, fallback.1.to_string()));
    broken(
        SOLID_MODULUS,
        warning(
            key,
            format!(
                "the fitted |E| = {} Pa at ω = {} rad/s, inside the window the data determine \
                 ({window}), is {beyond}; {advice}",
                sig(at.0),
                sig(at.1),
            ),
        ),
    )
}

/// E0 and E1 of a fit outside the plausible range but beyond its window:
/// the Prony series' limits ω → 0 and ω → ∞, extrapolations the data do
/// not fix; said, never judged.
fn extrapolated_moduli(m: &Material<'_>, [lo, hi]: [f64; 2]) -> Vec<Warning> {
    let mut out = Vec::new();
    let e0 = m.static_modulus;
    if e0.is_finite() && e0 > 0.0 && e0 < MIN_RUBBER_MODULUS {
        out.push(Warning {
            key: None,
            assumption: None,
            message: format!(
                "the fitted static modulus E0 = {} Pa is the Prony series' limit ω → 0, an \
                 extrapolation below the window the data determine (ω ≥ {} rad/s, where |E| = \
                 {} Pa): the data do not determine it and it does not judge the fit \
                 (fit.json's extrapolated)",
                sig(e0),
                sig(lo),
                sig((m.modulus)(lo).norm())
            ),
        });
    }
    if m.glassy_modulus > MAX_GLASSY_MODULUS {
        out.push(Warning {
            key: None,
            assumption: None,
            message: format!(
                "the fitted glassy modulus E1 = {} Pa is the Prony series' limit ω → ∞, an \
                 extrapolation above the window the data determine (ω ≤ {} rad/s, where |E| = \
                 {} Pa): the data do not determine it and it does not judge the fit \
                 (fit.json's extrapolated)",
                sig(m.glassy_modulus),
                sig(hi),
                sig((m.modulus)(hi).norm())
            ),
        });
    }
    out
}

/// The assumption check 4 names: the modulus of a viscoelastic solid.
pub const SOLID_MODULUS: &str = "viscoelastic solid's modulus";

/// Check 4's upper end for a given material (or a fit judged everywhere):
/// E1 (Pa) above any polymer's.
fn stiff_glass(setup: &RollingSetup, glassy_modulus: f64, fitted: bool) -> Warning {
    let origin = if fitted { "fitted" } else { "given" };
    let (key, advice) = match (implausible_radius(setup), implausible_load(setup), fitted) {
        (Some(input), _, _) | (None, Some(input), _) => input,
        (None, None, true) => (
            "fit.E1_max",
            "check the units of geometry.radius (m) and geometry.load, anchor the modulus \
             scale in [fit] (E0, E_at or contact_radius), and keep E1_max at most 1e10 Pa"
                .to_string(),
        ),
        (None, None, false) => (
            "material",
            "check the unit of the modulus in [material] (Pa)".to_string(),
        ),
    };
    warning(
        key,
        format!(
            "the {origin} glassy modulus E1 = {} Pa is above any polymer's (glassy polymers \
             are 1e9–1e10 Pa; {} Pa is nearer the steel ball itself); {advice}",
            sig(glassy_modulus),
            num(MAX_GLASSY_MODULUS)
        ),
    )
}

/// Check 4's lower end: E0 (Pa, `fitted` or given) below any rubber's.
fn soft_rubber(setup: &RollingSetup, static_modulus: f64, fitted: bool) -> Warning {
    let origin = if fitted { "fitted" } else { "given" };
    let (key, advice) = match (implausible_radius(setup), implausible_load(setup), fitted) {
        (Some(input), _, _) | (None, Some(input), _) => input,
        (None, None, true) => (
            "fit.E0",
            "check the units of geometry.radius (m) and geometry.load (N for a sphere, \
             N/m for a cylinder), and anchor the modulus scale in [fit] (E0, E_at or \
             contact_radius)"
                .to_string(),
        ),
        (None, None, false) => (
            "material",
            "check the unit of the modulus in [material] (Pa, not MPa)".to_string(),
        ),
    };
    broken(
        SOLID_MODULUS,
        warning(
            key,
            format!(
                "the {origin} static modulus E0 = {} Pa is below any rubber's (the softest \
             elastomers start near {} Pa, ordinary rubbers are 1e6–1e7 Pa){}; {advice}",
                sig(static_modulus),
                num(MIN_RUBBER_MODULUS),
                if fitted {
                    ": the fit has compensated for a wrong input, or the weakly determined \
                 modulus scale has drifted"
                } else {
                    ""
                }
            ),
        ),
    )
}
