//! Plausibility warnings: inputs and results that run without error but that the
//! theory does not cover, or that no laboratory would produce — most often a
//! number in the wrong unit (a radius in mm, a modulus in MPa). Each warning
//! explains the physics and names the scene key (or data column) to check.
//! They are warnings, not errors: an unusual experiment may be right.
//!
//! # The checks and their thresholds
//!
//! 1. **Contact not small** — the Hertz contact size (sphere radius
//!    r = (3 F R/(4 |E_eff|))^⅓, cylinder half-width a = (4 f R/(π |E_eff|))^½,
//!    E_eff = E/(1 − ν²)) above [`MAX_CONTACT_RATIO`] = R/3 at any speed. The
//!    theory (Persson 2010) takes the Hertz pressure of a paraboloid on a
//!    half-space, valid only for contacts small against the body (Johnson
//!    1985, §4.2). The modulus is the one the scene's contact rule uses:
//!    |E(ω)| at the probed frequency ω ≈ v/r (solved self-consistently,
//!    starting from the static contact, the largest) for `size = "dynamic"`,
//!    E(0) for `"static"`. Why R/3: Sneddon's exact load on a sphere,
//!    F = F_Hertz [1 + (2/5)(a/R)² + …], departs from Hertz by 4 % at
//!    a/R = 1/3 (1.5 % in the contact radius at a given load), and Tabor's
//!    representative strain 0.2 a/R is then 7 %, still within the linear
//!    range of an unfilled rubber. R/5 (2 % error) was considered, but
//!    ordinary experiments sit above it: the bundled 5 mm ball at 1 N on a
//!    2 MPa rubber has r0 = 0.22 R, a ¼-inch ball at 1 N r0 = 0.30 R; a
//!    warning there would only teach users to ignore warnings.
//! 2. **Strains not small** — the static mean pressure p_a (sphere
//!    F/(π r0²), cylinder f/(2 a0)) above the static modulus E0. p_a/E0 is the
//!    strain scale at low speed, where the rubber is softest; above 1,
//!    linear viscoelasticity, on which the theory rests, fails. (At higher
//!    speeds the strain is p/|E(ω)|, smaller, so the static contact is the
//!    worst case; comparing a high-speed pressure with E0 would be wrong.)
//!    For Hertz contact p_a/E_eff = (4/3π)·r0/R (sphere), (π/8)·a0/R
//!    (cylinder), so this fires only for contacts far beyond check 1; it
//!    states the second failure that comes with them.
//! 3. **μ above [`MAX_FRICTION`] = 0.5**, measured ([`input_warnings`]) or
//!    predicted ([`predicted_friction_warnings`]). Rolling friction of a
//!    hard ball on rubber is normally ≤ 0.1. The pressure centroid lies
//!    x̄ = μR ahead of the axis (Persson 2010, Section 4) and inside the
//!    contact, so μ ≤ r/R: μ > 0.5 needs a contact wider than R/2. Measured,
//!    that points at sliding-friction data or a wrong column; predicted, at
//!    a contact far outside the theory.
//! 4. **Modulus outside any viscoelastic solid** — below
//!    [`MIN_RUBBER_MODULUS`] = 10 kPa (the softest commercial elastomers,
//!    e.g. silicone gels, are some 10–100 kPa; ordinary rubbers 1–10 MPa)
//!    or above [`MAX_GLASSY_MODULUS`] = 100 GPa (glassy polymers and filled
//!    compounds are 1–10 GPa; 100 GPa is nearer the steel ball itself): for
//!    a given material E0 and E1, for a fitted one |E| inside the window the
//!    data determine (below). A fitted value there has compensated
//!    an input in the wrong unit (μ scales roughly like tan δ·|E|^(−1/3) and
//!    through the contact size with R and the load) or the weakly determined
//!    modulus scale has drifted: check the radius and load units and give a
//!    scale anchor. A given value there is most likely in the wrong unit.
//! 5. **Speeds above [`MAX_ISOTHERMAL_SPEED`] = 10 m/s** — the theory is
//!    isothermal. The flash temperature of a fast moving heat source μ F v
//!    on a contact of size a is ΔT ≈ 0.3 (μ F v/(a k))·(κ/(v a))^½ (Jaeger
//!    1942): with μ = 0.05, F = 1 N, a = 1 mm and rubber's k = 0.2 W/(m K),
//!    κ = 1e-7 m²/s that is about 1 K at 1 m/s and 3 K at 10 m/s, growing as
//!    √v and accumulating on a track rolled over repeatedly; near the glass
//!    transition the modulus shifts by about a third of a decade per kelvin
//!    (WLF with its universal constants, C1/C2 = 17.4/51.6 K). Above 10 m/s
//!    isothermal results are doubtful; below it heating is minor for
//!    ordinary loads.
//! 6. **Implausible inputs on their own** — a lab tribometer rolls steel
//!    balls of 1–25 mm radius under 0.01–1000 N; rollers (up to conveyor
//!    idlers, R ≈ 0.1 m) carry up to about 1e4 N/m. The bounds leave a wide
//!    margin around that and flag unit slips (a factor 1000):
//!    radius above [`MAX_RADIUS`] = 0.5 m (a radius in mm read as m) or below
//!    [`MIN_RADIUS`] = 10 µm (colloidal probes, where roughness and adhesion,
//!    not Hertz, set the contact); a sphere load above [`MAX_SPHERE_LOAD`] =
//!    1e4 N (ten times the largest lab load; on the largest lab ball,
//!    R = 25 mm, it gives even a glassy polymer, |E| = 1 GPa, a contact of
//!    R/5); a cylinder load per length above [`MAX_CYLINDER_LOAD`] = 1e6 N/m
//!    (a hundred times a heavy conveyor idler's; with a 25 mm roller on the
//!    same glassy polymer it gives a half-width of R/5).
//!
//! **A fitted material is judged where the data determine it**
//! ([`fitted_material_warnings`]): inside the window [ω_min, ω_max] of the
//! fit (at the reduced speeds v·a_T of a temperature set). The contact
//! frequency of check 1 and the contact and strain of check 2 at each
//! measured speed use |E| at that frequency taken into the window; check 4
//! takes |E| inside the window against 1e4 … 1e11 Pa, the range of real
//! viscoelastic solids (soft elastomers to glassy polymers and filled
//! compounds). E0 and E1 are the Prony series' limits ω → 0 and ω → ∞;
//! beyond the window they are extrapolations (fit.json's `extrapolated`,
//! with the bound the window gives), warned about, never a broken
//! assumption: a stiff polymer whose window starts at |E| = 1e8 Pa may
//! extrapolate to an E0 of a few kPa that no datum sees. Under
//! `size = "static"` the model's contact is E0's, and so is the check's.
//!
//! Which input a contact, pressure or μ warning names: the radius or the
//! load if either is implausible on its own (check 6), else the modulus if
//! it is softer than any rubber (check 4), else the load — a plausible load
//! that is too high for this body on a solid this soft (the modulus, given
//! or fitted, is mentioned as the alternative).
//!
//! All computations run in logarithms and every number is printed through a
//! guard: inputs such as load = 1e308 give finite text, never NaN or a
//! panic.
//!
//! # References
//! - K.L. Johnson, *Contact Mechanics*, Cambridge University Press 1985,
//!   §4.2 (Hertz theory: contact small against the radii, small strains,
//!   half-space).
//! - B.N.J. Persson, "Rolling friction for hard cylinder and sphere on
//!   viscoelastic solid", Eur. Phys. J. E 33 (2010): the small-contact
//!   (Hertz, linear viscoelastic half-space) assumption, Eqs. (9), (14);
//!   the pressure centroid x̄ = μR, Section 4.
//! - I.N. Sneddon, Int. J. Eng. Sci. 3, 47 (1965): the exact load of a
//!   spherical (not paraboloidal) indenter.
//! - D. Tabor, *The Hardness of Metals*, Oxford 1951: the representative
//!   strain 0.2 a/R.
//! - J.C. Jaeger, Proc. R. Soc. N.S.W. 76, 203 (1942): moving heat sources.
//! - M.L. Williams, R.F. Landel, J.D. Ferry, J. Am. Chem. Soc. 77, 3701
//!   (1955): the WLF equation.

use std::fmt;

use num_complex::Complex64;

use crate::contact::{Shape, ln_mean_pressure};
use crate::scene::RollingSetup;

/// Largest contact size (sphere radius, cylinder half-width) relative to the
/// body's radius R that the theory is trusted at.
pub const MAX_CONTACT_RATIO: f64 = 1.0 / 3.0;
/// Largest plausible rolling-friction coefficient.
pub const MAX_FRICTION: f64 = 0.5;
/// Smallest plausible Young's modulus |E| of a viscoelastic solid (the
/// softest elastomers, silicone gels), Pa.
pub const MIN_RUBBER_MODULUS: f64 = 1e4;
/// Largest plausible Young's modulus |E| of a viscoelastic solid (glassy
/// polymers and filled compounds reach 1e10 Pa), Pa.
pub const MAX_GLASSY_MODULUS: f64 = 1e11;
/// Largest speed at which the isothermal theory is trusted, m/s.
pub const MAX_ISOTHERMAL_SPEED: f64 = 10.0;
/// Largest plausible radius of a rolling body, m.
pub const MAX_RADIUS: f64 = 0.5;
/// Smallest plausible radius of a rolling body, m.
pub const MIN_RADIUS: f64 = 1e-5;
/// Largest plausible load on a sphere, N.
pub const MAX_SPHERE_LOAD: f64 = 1e4;
/// Largest plausible load per length on a cylinder, N/m.
pub const MAX_CYLINDER_LOAD: f64 = 1e6;

/// One plausibility warning.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Warning {
    /// The scene key (e.g. `geometry.radius`, `geometry.load`, `material`,
    /// `fit.E0`) or data column (`mu`) to check; `None` when no input is
    /// to blame (a caveat of the theory, such as high speed).
    pub key: Option<&'static str>,
    /// The explanation, one paragraph, naming the key.
    pub message: String,
    /// The model's assumption a material breaks (checks 1, 2 and 4: "small
    /// contact", "small strain", [`SOLID_MODULUS`]); a fit whose material
    /// breaks one is judged "invalid", not merely warned about.
    pub assumption: Option<&'static str>,
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

/// Checks of the rolling set-up and the speeds alone (checks 5 and 6) and,
/// given measured friction coefficients `friction` (one per speed), of μ
/// (check 3).
pub fn input_warnings(
    setup: &RollingSetup,
    speeds: &[f64],
    friction: Option<&[f64]>,
) -> Vec<Warning> {
    let mut out = Vec::new();
    if let Some((key, text)) = implausible_radius(setup) {
        out.push(warning(key, text));
    }
    if let Some((key, text)) = implausible_load(setup) {
        out.push(warning(key, text));
    }
    let fast: Vec<f64> = speeds
        .iter()
        .copied()
        .filter(|&v| v > MAX_ISOTHERMAL_SPEED)
        .collect();
    if let Some(top) = fast.iter().copied().reduce(f64::max) {
        out.push(Warning {
            key: None,
            assumption: None,
            message: format!(
                "{} of {} speeds are above {} m/s (up to {} m/s): the theory is isothermal, \
                 but at such speeds frictional heating of the contact (a few kelvin per pass, \
                 growing as √v and accumulating on a track) shifts a rubber's modulus by about \
                 a third of a decade per kelvin near its glass transition; μ there is doubtful",
                fast.len(),
                speeds.len(),
                num(MAX_ISOTHERMAL_SPEED),
                num(top)
            ),
        });
    }
    if let Some(mu) = friction
        && let Some(high) = high_friction(speeds, mu)
    {
        out.push(Warning {
            key: Some("mu"),
            assumption: None,
            message: format!(
                "the measured μ reaches {} at v = {} m/s (above {} at {} of {} points): rolling \
                 friction of a hard {} on rubber is normally ≤ 0.1, and since the pressure \
                 centroid x̄ = μR lies inside the contact, μ > {} needs a contact wider than R/2, \
                 outside the theory; are these sliding-friction data, or is the mu column \
                 something else (a force in N, a percentage)?",
                num(high.max),
                num(high.speed),
                num(MAX_FRICTION),
                high.count,
                mu.len(),
                body(setup.geometry.shape),
                num(MAX_FRICTION)
            ),
        });
    }
    out
}

mod material;

pub use material::{SOLID_MODULUS, fitted_material_warnings, material_warnings};

/// Check 3 for friction coefficients the model predicted (`mu`, one per
/// speed) from a material with static modulus `static_modulus` (Pa),
/// `fitted` or given.
pub fn predicted_friction_warnings(
    setup: &RollingSetup,
    speeds: &[f64],
    mu: &[f64],
    static_modulus: f64,
    fitted: bool,
) -> Vec<Warning> {
    let Some(high) = high_friction(speeds, mu) else {
        return Vec::new();
    };
    let softest = Softest {
        modulus: static_modulus,
        label: "E0".into(),
    };
    let (key, advice) = blame(setup, &softest, fitted);
    vec![warning(
        key,
        format!(
            "the predicted μ reaches {} at v = {} m/s (above {}{}): rolling friction of a hard \
             {} on rubber is normally ≤ 0.1, and since the pressure centroid x̄ = μR lies \
             inside the contact, μ > {} means a contact wider than R/2 — far outside the \
             small-contact theory the prediction comes from; {advice}",
            num(high.max),
            num(high.speed),
            num(MAX_FRICTION),
            of_speeds(high.count, mu.len()),
            body(setup.geometry.shape),
            num(MAX_FRICTION)
        ),
    )]
}

// ------------------------------------------------------------- helpers

/// The modulus a contact or strain warning names as the possible trace of
/// a unit slip.
struct Softest {
    /// Pa.
    pub modulus: f64,
    /// "E0", or "|E| at ω = … rad/s".
    pub label: String,
}

fn warning(key: &'static str, message: String) -> Warning {
    Warning {
        key: Some(key),
        message,
        assumption: None,
    }
}

/// A warning that the material breaks the model's `assumption`.
fn broken(assumption: &'static str, w: Warning) -> Warning {
    Warning {
        assumption: Some(assumption),
        ..w
    }
}

/// Radius and load finite and positive, Poisson's ratio below 1: the
/// contact formulas make sense (invalid inputs are errors elsewhere).
fn usable(setup: &RollingSetup) -> bool {
    let g = setup.geometry;
    let nu = setup.substrate.poisson;
    g.radius.is_finite()
        && g.radius > 0.0
        && g.load.is_finite()
        && g.load > 0.0
        && nu.is_finite()
        && nu.abs() < 1.0
}

/// Check 6 for the radius: (key, explanation).
fn implausible_radius(setup: &RollingSetup) -> Option<(&'static str, String)> {
    let r = setup.geometry.radius;
    let shown = num(r);
    if r > MAX_RADIUS {
        // The number as typed, read as mm: "6.35 mm = 6.35e-3 m".
        let in_m = if shown.contains('e') || shown.contains(' ') {
            format!("{:e}", r / 1000.0)
        } else {
            format!("{shown}e-3")
        };
        Some((
            "geometry.radius",
            format!(
                "geometry.radius = {shown} m is implausibly large for a lab body (balls and \
                 rollers are 1–25 mm, above {} m there is no rolling tribometer) — was it given \
                 in mm? ({shown} mm = {in_m} m)",
                num(MAX_RADIUS)
            ),
        ))
    } else if r > 0.0 && r < MIN_RADIUS {
        Some((
            "geometry.radius",
            format!(
                "geometry.radius = {shown} m is implausibly small for a rolling body (lab balls \
                 and rollers are 1–25 mm; below {} m roughness and adhesion, not Hertz, set \
                 the contact) — check its unit (m)",
                num(MIN_RADIUS)
            ),
        ))
    } else {
        None
    }
}

/// Check 6 for the load: (key, explanation).
fn implausible_load(setup: &RollingSetup) -> Option<(&'static str, String)> {
    let g = setup.geometry;
    let (limit, unit, usual) = match g.shape {
        Shape::Sphere => (
            MAX_SPHERE_LOAD,
            "N",
            "lab tribometers load balls with 0.01–1000 N",
        ),
        Shape::Cylinder => (
            MAX_CYLINDER_LOAD,
            "N/m",
            "rollers up to conveyor idlers carry up to about 1e4 N/m",
        ),
    };
    (g.load > limit).then(|| {
        (
            "geometry.load",
            format!(
                "geometry.load = {} {unit} is implausibly large ({usual}; the bound is {} \
                 {unit}) — check its unit ({})",
                num(g.load),
                num(limit),
                match g.shape {
                    Shape::Sphere => "N for a sphere",
                    Shape::Cylinder => "N/m, load per length, for a cylinder",
                }
            ),
        )
    })
}

/// The input a contact, pressure or μ warning names, with advice (see the
/// module doc).
fn blame(setup: &RollingSetup, softest: &Softest, fitted: bool) -> (&'static str, String) {
    if let Some(input) = implausible_radius(setup).or_else(|| implausible_load(setup)) {
        return input;
    }
    let g = setup.geometry;
    let unit = match g.shape {
        Shape::Sphere => "N",
        Shape::Cylinder => "N/m",
    };
    let static_modulus = softest.modulus;
    let soft = static_modulus.is_finite() && static_modulus < MIN_RUBBER_MODULUS;
    match (soft, fitted) {
        (true, true) => (
            "fit.E0",
            format!(
                "the fitted {} = {} Pa is softer than any viscoelastic solid, and this number \
                 points at a unit slip: check the units of geometry.radius (m) and \
                 geometry.load ({unit}), and anchor the modulus scale in [fit] (E0, E_at or \
                 contact_radius)",
                softest.label,
                sig(static_modulus)
            ),
        ),
        (true, false) => (
            "material",
            format!(
                "the modulus in [material] (E0 = {} Pa) is softer than any rubber — check its \
                 unit (Pa, not MPa)",
                sig(static_modulus)
            ),
        ),
        (false, _) => (
            "geometry.load",
            format!(
                "check geometry.load = {} {unit}: too high for this {} of R = {} m on a solid \
                 this soft (lower it, or check its unit){}",
                num(g.load),
                body(g.shape),
                num(g.radius),
                if fitted {
                    "; or the fitted modulus is too soft — anchor its scale in [fit] (E0, E_at \
                     or contact_radius)"
                } else {
                    "; or check the modulus in [material] (Pa)"
                }
            ),
        ),
    }
}

/// ln of the mean Hertz pressure (Pa) for a contact of size exp(`ln_size`).
fn ln_pressure(setup: &RollingSetup, ln_size: f64) -> f64 {
    let g = setup.geometry;
    ln_mean_pressure(g.shape, g.load, ln_size)
}

/// The contact at one speed: ln of its size and the modulus that set it
/// ([`RollingSetup::ln_contact_at`]).
fn contact_at(
    setup: &RollingSetup,
    modulus: &dyn Fn(f64) -> Complex64,
    static_modulus: f64,
    speed: f64,
) -> (f64, f64) {
    setup.ln_contact_at(&|omega| modulus(omega).norm(), static_modulus, speed)
}

/// The worst speed of check 1 and how many speeds fail it.
struct LargeContact {
    speed: f64,
    size: f64,
    modulus: f64,
    omega: f64,
    count: usize,
}

fn large_contact(
    setup: &RollingSetup,
    speeds: &[f64],
    modulus: &dyn Fn(f64) -> Complex64,
    static_modulus: f64,
) -> Option<LargeContact> {
    let ln_limit = setup.geometry.radius.ln() + MAX_CONTACT_RATIO.ln();
    let mut worst: Option<(f64, f64, f64)> = None;
    let mut count = 0;
    for &v in speeds.iter().filter(|v| v.is_finite() && **v > 0.0) {
        let (ln_r, e) = contact_at(setup, modulus, static_modulus, v);
        if ln_r > ln_limit {
            count += 1;
            if worst.is_none_or(|(_, w, _)| ln_r > w) {
                worst = Some((v, ln_r, e));
            }
        }
    }
    let (speed, ln_r, e) = worst?;
    Some(LargeContact {
        speed,
        size: ln_r.exp(),
        modulus: e,
        omega: (speed.ln() - ln_r).exp(),
        count,
    })
}

/// The largest μ above [`MAX_FRICTION`], where, and how many are above.
struct HighFriction {
    max: f64,
    speed: f64,
    count: usize,
}

fn high_friction(speeds: &[f64], mu: &[f64]) -> Option<HighFriction> {
    let mut high: Option<HighFriction> = None;
    for (&v, &m) in speeds.iter().zip(mu) {
        // NaN compares false: skipped.
        if m > MAX_FRICTION {
            let h = high.get_or_insert(HighFriction {
                max: m,
                speed: v,
                count: 0,
            });
            h.count += 1;
            if m > h.max {
                (h.max, h.speed) = (m, v);
            }
        }
    }
    high
}

/// " at 3 of 41 speeds", or "" for a single speed.
fn of_speeds(count: usize, total: usize) -> String {
    if total > 1 {
        format!(" at {count} of {total} speeds")
    } else {
        String::new()
    }
}

fn body(shape: Shape) -> &'static str {
    match shape {
        Shape::Sphere => "ball",
        Shape::Cylinder => "roller",
    }
}

/// ("radius", "r") or ("half-width", "a").
fn size_name(shape: Shape) -> (&'static str, &'static str) {
    match shape {
        Shape::Sphere => ("radius", "r"),
        Shape::Cylinder => ("half-width", "a"),
    }
}

/// A number as given: its shortest round-trip digits, plain between 1e-3
/// and 1e6, else in e-notation; never "NaN" or "inf".
fn num(x: f64) -> String {
    if x.is_nan() {
        return "an undefined number".into();
    }
    if x.is_infinite() {
        return if x > 0.0 {
            "more than 1.8e308".into()
        } else {
            "less than -1.8e308".into()
        };
    }
    let a = x.abs();
    if a == 0.0 || (1e-3..1e6).contains(&a) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// A computed number to three significant digits, shown as by [`num`].
fn sig(x: f64) -> String {
    if !x.is_finite() {
        return num(x);
    }
    num(format!("{x:.2e}").parse().unwrap_or(x))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::ContactSize;
    use crate::{
        Geometry, HavriliakNegami, Prony, StandardLinearSolid, Substrate, ViscoelasticModulus,
    };

    fn setup(shape: Shape, radius: f64, load: f64, poisson: f64) -> RollingSetup {
        RollingSetup {
            geometry: Geometry {
                shape,
                radius,
                load,
            },
            substrate: Substrate {
                poisson,
                film_thickness: None,
            },
            contact: ContactSize::Dynamic,
        }
    }

    fn log_speeds(v_min: f64, v_max: f64, count: usize) -> Vec<f64> {
        let mut v: Vec<f64> = (0..count)
            .map(|i| v_min * (v_max / v_min).powf(i as f64 / (count - 1) as f64))
            .collect();
        v[count - 1] = v_max;
        v
    }

    /// data/hn-rubber.toml: 5 mm ball, 1 N, ν = 0.5, HN rubber.
    fn hn_rubber() -> HavriliakNegami {
        HavriliakNegami::new(2.0e6, 2.0e9, 1.0e-3, 0.55, 0.4).unwrap()
    }

    /// All checks of a material given (or fitted) in `setup`.
    fn all<M: ViscoelasticModulus>(
        setup: &RollingSetup,
        speeds: &[f64],
        material: &M,
        e1: f64,
        fitted: bool,
    ) -> Vec<Warning> {
        let modulus = |w: f64| material.modulus(w);
        let mut w = input_warnings(setup, speeds, None);
        w.extend(material_warnings(
            setup,
            speeds,
            &modulus,
            material.static_modulus(),
            e1,
            fitted,
        ));
        w
    }

    fn keys(warnings: &[Warning]) -> Vec<Option<&'static str>> {
        warnings.iter().map(|w| w.key).collect()
    }

    fn assert_clean_text(warnings: &[Warning]) {
        for w in warnings {
            for bad in ["NaN", "inf", "undefined"] {
                assert!(!w.message.contains(bad), "{bad} in {}", w.message);
            }
        }
    }

    /// The measured μ column of data/hn-rubber.csv.
    fn hn_rubber_data() -> (Vec<f64>, Vec<f64>) {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/hn-rubber.csv");
        let text = std::fs::read_to_string(path).unwrap();
        let mut lines = text.lines().filter(|l| !l.starts_with('#'));
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let (iv, imu) = (
            header.iter().position(|c| *c == "v").unwrap(),
            header.iter().position(|c| *c == "mu").unwrap(),
        );
        lines
            .map(|l| {
                let f: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
                (f[iv], f[imu])
            })
            .unzip()
    }

    #[test]
    fn bundled_examples_are_silent() {
        // data/hn-rubber.toml and its measurement data/hn-rubber.csv.
        let hn = setup(Shape::Sphere, 0.005, 1.0, 0.5);
        let speeds = log_speeds(1e-8, 1.0, 41);
        for fitted in [false, true] {
            let w = all(&hn, &speeds, &hn_rubber(), 2e9, fitted);
            assert!(w.is_empty(), "{w:#?}");
        }
        let (v, mu) = hn_rubber_data();
        assert_eq!(v.len(), 41);
        assert!(input_warnings(&hn, &v, Some(&mu)).is_empty());
        assert!(predicted_friction_warnings(&hn, &v, &mu, 2e6, true).is_empty());
        // data/example-sphere.toml.
        let prony = Prony::new(
            1.0e9,
            vec![5.0e8, 3.0e8, 1.2e8, 5.0e7, 1.8e7, 6.0e6, 2.5e6, 1.5e6],
            vec![1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1.0, 10.0, 100.0],
        )
        .unwrap();
        let w = all(&hn, &log_speeds(1e-6, 1.0, 41), &prony, 1e9, false);
        assert!(w.is_empty(), "{w:#?}");
        // data/paper-fig2-cylinder.toml and -sphere.toml (up to 10 m/s).
        let sls = StandardLinearSolid::new(1e6, 1e7, 1.0).unwrap();
        let speeds = log_speeds(1e-8, 10.0, 91);
        for paper in [
            setup(Shape::Cylinder, 0.01, 100.0, 0.0),
            setup(Shape::Sphere, 0.01, 0.15, 0.0),
        ] {
            let w = all(&paper, &speeds, &sls, 1e7, false);
            assert!(w.is_empty(), "{w:#?}");
        }
    }

    #[test]
    fn radius_in_mm_is_named_with_the_conversion() {
        // The issue: 6.35 typed for 6.35e-3, and the fit ran to E0 = 9.3 Pa.
        let wrong = setup(Shape::Sphere, 6.35, 1.0, 0.5);
        let fitted = StandardLinearSolid::new(9.3, 9.3e3, 1.0).unwrap();
        let w = all(&wrong, &log_speeds(1e-6, 1.0, 21), &fitted, 9.3e3, true);
        let radius: Vec<&Warning> = w
            .iter()
            .filter(|w| w.key == Some("geometry.radius"))
            .collect();
        // On its own (check 6) and as the cause of the soft fit (check 4).
        assert_eq!(radius.len(), 2, "{w:#?}");
        for w in radius {
            assert!(
                w.message
                    .contains("was it given in mm? (6.35 mm = 6.35e-3 m)")
            );
        }
        assert!(
            w.iter().any(|w| w.message.contains("E0 = 9.3 Pa")),
            "{w:#?}"
        );
        assert_clean_text(&w);
    }

    #[test]
    fn load_a_thousand_times_too_large_is_named() {
        // 1000 N instead of 1 N on the hn-rubber ball: r0 = 11 mm on R = 5 mm.
        let heavy = setup(Shape::Sphere, 0.005, 1000.0, 0.5);
        let speeds = log_speeds(1e-8, 1.0, 41);
        let w = all(&heavy, &speeds, &hn_rubber(), 2e9, false);
        let contact = w
            .iter()
            .find(|w| w.message.contains("contact radius"))
            .expect("a contact warning");
        assert_eq!(contact.key, Some("geometry.load"), "{contact:#?}");
        assert!(contact.message.contains("geometry.load = 1000 N"));
        assert!(contact.message.contains("R/3"));
        // The worst speed is the slowest (softest rubber, largest contact).
        assert!(contact.message.contains("at v = 1e-8 m/s"), "{contact}");
        assert_clean_text(&w);
    }

    #[test]
    fn contact_check_follows_the_contact_rule() {
        // Sphere at 30 N on the hn rubber: r0 = 3.5 mm > R/3 statically,
        // but the dynamic contact stiffens out of it at high speed.
        let mut s = setup(Shape::Sphere, 0.005, 30.0, 0.5);
        let hn = hn_rubber();
        let modulus = |w: f64| hn.modulus(w);
        let speeds = log_speeds(1e-8, 1.0, 41);
        let contact_message = |w: &[Warning]| {
            w.iter()
                .find(|w| w.message.contains("contact radius"))
                .map(|w| w.message.clone())
                .unwrap()
        };
        let dynamic = contact_message(&material_warnings(&s, &speeds, &modulus, 2e6, 2e9, false));
        s.contact = ContactSize::Static;
        let stat = contact_message(&material_warnings(&s, &speeds, &modulus, 2e6, 2e9, false));
        assert!(stat.contains("at 41 of 41 speeds"), "{stat}");
        assert!(!dynamic.contains("at 41 of 41 speeds"), "{dynamic}");
        assert!(dynamic.contains("ω ≈ v/r"), "{dynamic}");
        // Cylinder: half-width.
        let roller = setup(Shape::Cylinder, 0.01, 1e5, 0.0);
        let sls = StandardLinearSolid::new(1e6, 1e7, 1.0).unwrap();
        let w = all(&roller, &speeds, &sls, 1e7, false);
        let contact = w.iter().find(|w| w.message.contains("half-width a"));
        assert_eq!(contact.unwrap().key, Some("geometry.load"), "{w:#?}");
    }

    #[test]
    fn pressure_above_the_static_modulus_is_reported() {
        // 5000 N on the hn ball: r0 = 19 mm, p_a = 4.2 MPa > E0 = 2 MPa.
        let s = setup(Shape::Sphere, 0.005, 5000.0, 0.5);
        let w = all(&s, &[1e-6], &hn_rubber(), 2e9, false);
        let p = w
            .iter()
            .find(|w| w.message.contains("mean contact pressure"))
            .expect("a pressure warning");
        assert!(p.message.contains("E0 = 2e6 Pa"), "{p}");
        assert_eq!(p.key, Some("geometry.load"));
        // 300 N: r0 = 7.5 mm, contact too large, p_a = 1.7 MPa still below E0.
        let s = setup(Shape::Sphere, 0.005, 300.0, 0.5);
        let w = all(&s, &[1e-6], &hn_rubber(), 2e9, false);
        assert!(
            !w.iter()
                .any(|w| w.message.contains("mean contact pressure")),
            "{w:#?}"
        );
    }

    #[test]
    fn friction_above_one_half_is_reported() {
        let s = setup(Shape::Sphere, 0.005, 1.0, 0.5);
        let v = [1e-3, 1e-2, 1e-1];
        let w = input_warnings(&s, &v, Some(&[0.05, 0.8, 2.0]));
        assert_eq!(keys(&w), [Some("mu")]);
        assert!(
            w[0].message.contains("reaches 2 at v = 0.1 m/s"),
            "{}",
            w[0]
        );
        assert!(w[0].message.contains("2 of 3 points"), "{}", w[0]);
        assert!(w[0].message.contains("sliding"));
        assert!(input_warnings(&s, &v, Some(&[0.05, 0.5, f64::NAN])).is_empty());
        // Predicted (forward): names the load for a plausible rubber, the
        // modulus for one softer than any rubber.
        let w = predicted_friction_warnings(&s, &v, &[0.1, 10.0, 3.0], 2e6, false);
        assert_eq!(keys(&w), [Some("geometry.load")]);
        assert!(w[0].message.contains("R/2"), "{}", w[0]);
        let w = predicted_friction_warnings(&s, &v, &[0.1, 10.0, 3.0], 2.0, false);
        assert_eq!(keys(&w), [Some("material")]);
        let w = predicted_friction_warnings(&s, &v, &[0.1, 10.0, 3.0], 2.0, true);
        assert_eq!(keys(&w), [Some("fit.E0")]);
    }

    #[test]
    fn moduli_outside_any_rubber_are_reported() {
        let s = setup(Shape::Sphere, 0.005, 1.0, 0.5);
        let v = log_speeds(1e-6, 1.0, 11);
        let soft = StandardLinearSolid::new(2e3, 2e6, 1.0).unwrap();
        let w = all(&s, &v, &soft, 2e6, true);
        let e0 = w.iter().find(|w| w.message.contains("below any rubber"));
        assert_eq!(e0.unwrap().key, Some("fit.E0"), "{w:#?}");
        assert!(e0.unwrap().message.contains("anchor"));
        let w = all(&s, &v, &soft, 2e6, false);
        let e0 = w.iter().find(|w| w.message.contains("below any rubber"));
        assert_eq!(e0.unwrap().key, Some("material"), "{w:#?}");
        let stiff = StandardLinearSolid::new(2e6, 2e11, 1.0).unwrap();
        let w = all(&s, &v, &stiff, 2e11, true);
        assert_eq!(keys(&w), [Some("fit.E1_max")], "{w:#?}");
        assert!(w[0].message.contains("E1 = 2e11 Pa"), "{}", w[0]);
        // At the bounds: silent.
        let edge = StandardLinearSolid::new(1e4, 1e11, 1.0).unwrap();
        let big_ball = setup(Shape::Sphere, 0.025, 0.01, 0.5);
        assert!(all(&big_ball, &v, &edge, 1e11, true).is_empty());
    }

    /// The held-out stiff polymer: a window from 1e-8 to 1e3 rad/s where
    /// |E| runs from about 1e8 to 1e10 Pa, and an E0 of 1.66 kPa that only
    /// the Prony series' limit ω → 0 holds (its longest term, τ = 1e10 s,
    /// relaxes below the window). Judged in its window it breaks no
    /// assumption; judged on the whole axis it was "invalid" with advice
    /// about units that were right.
    #[test]
    fn a_fit_is_judged_inside_its_window() {
        let s = setup(Shape::Sphere, 0.005, 1.0, 0.5);
        let e0 = 1660.0;
        let stiff = Prony::new(1e10, vec![8.9e9, 1e9, 1e8 - e0], vec![1e-6, 1.0, 1e10]).unwrap();
        assert!((stiff.static_modulus() / e0 - 1.0).abs() < 1e-6);
        let modulus = |w: f64| stiff.modulus(w);
        let speeds = log_speeds(1e-12, 0.1, 45);
        let window = [1e-8, 1e3];
        let judged = fitted_material_warnings(&s, &speeds, &modulus, e0, 1e10, window);
        assert!(judged.iter().all(|w| w.assumption.is_none()), "{judged:#?}");
        let e0_note = judged
            .iter()
            .find(|w| w.message.contains("E0 = 1660 Pa"))
            .expect("the extrapolated E0 is said");
        assert!(e0_note.message.contains("extrapolation"), "{e0_note}");
        assert!(!e0_note.message.contains("units"), "{e0_note}");
        assert_clean_text(&judged);
        let everywhere = material_warnings(&s, &speeds, &modulus, e0, 1e10, true);
        assert!(
            everywhere
                .iter()
                .any(|w| w.assumption == Some(SOLID_MODULUS)),
            "{everywhere:#?}"
        );
    }

    /// A fit whose modulus inside its window is softer than any solid
    /// breaks the assumption, and the message names that |E| and its ω
    /// as the number that points at a unit slip.
    #[test]
    fn a_soft_window_is_invalid_and_named() {
        let s = setup(Shape::Sphere, 0.005, 1e-4, 0.5);
        let soft = StandardLinearSolid::new(2e3, 5e3, 1.0).unwrap();
        let modulus = |w: f64| soft.modulus(w);
        let w = fitted_material_warnings(
            &s,
            &log_speeds(1e-6, 1e-3, 11),
            &modulus,
            2e3,
            5e3,
            [1e-2, 1e2],
        );
        let broken: Vec<&Warning> = w.iter().filter(|w| w.assumption.is_some()).collect();
        assert_eq!(broken.len(), 1, "{w:#?}");
        let m = &broken[0].message;
        assert_eq!(broken[0].assumption, Some(SOLID_MODULUS));
        assert!(m.contains("|E| = 2"), "{m}");
        assert!(m.contains("at ω = 0.01 rad/s"), "{m}");
        assert!(m.contains("points at a unit slip"), "{m}");
        assert_eq!(broken[0].key, Some("fit.E0"));
    }

    #[test]
    fn high_speeds_are_reported() {
        let s = setup(Shape::Sphere, 0.005, 1.0, 0.5);
        assert!(input_warnings(&s, &[1.0, 10.0], None).is_empty());
        let w = input_warnings(&s, &[1.0, 10.0, 20.0, 50.0], None);
        assert_eq!(keys(&w), [None]);
        assert!(w[0].message.contains("2 of 4 speeds"), "{}", w[0]);
        assert!(w[0].message.contains("up to 50 m/s"), "{}", w[0]);
        assert!(w[0].message.contains("isothermal"));
    }

    #[test]
    fn implausible_inputs_alone_are_reported() {
        let v = [1e-3];
        let cases = [
            (
                setup(Shape::Sphere, 6e-6, 1.0, 0.5),
                "geometry.radius",
                "check its unit (m)",
            ),
            (
                setup(Shape::Sphere, 0.6, 1.0, 0.5),
                "geometry.radius",
                "0.6 mm = 0.6e-3 m",
            ),
            (
                setup(Shape::Sphere, 0.005, 2e4, 0.5),
                "geometry.load",
                "20000 N",
            ),
            (
                setup(Shape::Cylinder, 0.01, 2e6, 0.5),
                "geometry.load",
                "N/m",
            ),
        ];
        for (s, key, fragment) in cases {
            let w = input_warnings(&s, &v, None);
            assert_eq!(keys(&w), [Some(key)], "{w:#?}");
            assert!(w[0].message.contains(fragment), "{}", w[0]);
        }
        // Just inside the bounds.
        for s in [
            setup(Shape::Sphere, 1e-5, 1e4, 0.5),
            setup(Shape::Sphere, 0.5, 1.0, 0.5),
            setup(Shape::Cylinder, 0.01, 1e6, 0.5),
        ] {
            assert!(input_warnings(&s, &v, None).is_empty());
        }
    }

    #[test]
    fn extreme_inputs_give_finite_text() {
        let hn = hn_rubber();
        let modulus = |w: f64| hn.modulus(w);
        let nan = |_: f64| Complex64::new(f64::NAN, f64::NAN);
        let speeds = [f64::MIN_POSITIVE, 1e-6, 1.0, 1e308, f64::INFINITY, f64::NAN];
        for shape in [Shape::Sphere, Shape::Cylinder] {
            for (radius, load) in [
                (0.005, 1e308),
                (1e308, 1e308),
                (1e-300, 1e-300),
                (5e-3, 1.0),
            ] {
                let s = setup(shape, radius, load, 0.5);
                for m in [&modulus as &dyn Fn(f64) -> Complex64, &nan] {
                    for (e0, e1) in [(2e6, 2e9), (1e-300, 1e308), (f64::MAX, f64::INFINITY)] {
                        let mut w = input_warnings(&s, &speeds, Some(&[1e308; 6]));
                        w.extend(material_warnings(&s, &speeds, m, e0, e1, true));
                        w.extend(predicted_friction_warnings(
                            &s,
                            &speeds,
                            &[f64::INFINITY; 6],
                            e0,
                            false,
                        ));
                        assert_clean_text(&w);
                    }
                }
            }
        }
        // 1e308 N on a sphere: named, with the number as typed.
        let s = setup(Shape::Sphere, 0.005, 1e308, 0.5);
        let w = all(&s, &[1e-3], &hn, 2e9, false);
        assert!(w.iter().all(|w| w.key == Some("geometry.load")), "{w:#?}");
        assert!(w[0].message.contains("geometry.load = 1e308"), "{}", w[0]);
    }
}
