//! A validated rolling-contact scene: geometry, substrate, contact-size rule
//! and material. Building one checks every parameter, so the friction code
//! behind it never sees a negative radius, a Poisson ratio above ½ or a NaN.

use crate::contact::{
    ContactSize, Shape, hertz_contact_size, ln_hertz_contact_size, mean_pressure,
};
use crate::error::{ModelError, PoissonOutOfRange, require_positive};
use crate::modulus::ViscoelasticModulus;

/// Accepted radii R, m: a nanometre (below it no continuum contact exists)
/// to a kilometre (beyond it the ratios of contact size to R underflow).
pub const RADIUS_RANGE: (f64, f64) = (1e-9, 1e3);

/// Accepted loads on a sphere, N: a nanonewton (the forces of the smallest
/// colloidal-probe rolling experiments; below it a continuum contact of a
/// body of at least a nanometre carries too little to measure) to 1e8 N,
/// four decades above the heaviest plausible rolling load (`plausibility`
/// warns from 1e4 N; crane wheels carry about 1e6 N). Outside these the
/// numerics fail without naming the load (1e-300 N: "friction quadrature
/// needs too many nodes"; 1e300 N: a contact of 1e97 m).
pub const SPHERE_LOAD_RANGE: (f64, f64) = (1e-9, 1e8);

/// Accepted loads per length on a cylinder, N/m: a micronewton per metre
/// (a nanonewton on a millimetre roller, the sphere's floor) to 1e10 N/m,
/// four decades above the plausible bound (`plausibility` warns from
/// 1e6 N/m).
pub const CYLINDER_LOAD_RANGE: (f64, f64) = (1e-6, 1e10);

/// Accepted film thicknesses d, m: a nanometre (a few molecular layers;
/// below it a film is no continuum) to a kilometre, the radius's range.
/// No bound relative to the radius is needed: films of 1e-12 R and of
/// 1e12 R solve (measured: a 1 nm film under a 1 km sphere and cylinder, a
/// 1 km film under a 1 nm sphere); 1e-300 m took 17 s to fail in the
/// contact map.
pub const THICKNESS_RANGE: (f64, f64) = (1e-9, 1e3);

/// Poisson's ratios ν rollfit accepts, 0 ≤ ν ≤ ½, at every entry point (a
/// scene's `[substrate] poisson`, `master --poisson`, the DMA and table
/// readers converting shear moduli, fit.json, Python): the range of the
/// solids it models and the one every solver takes. Isotropic elasticity
/// allows −1 < ν ≤ ½, but ν < 0 is an auxetic foam, never a rubber, and the
/// exact contact solvers need ν ≥ 0 (their half-space and strip
/// influence functions); so one rule, not one per solver.
pub const POISSON_RANGE: (f64, f64) = (0.0, 0.5);

/// `poisson` if it lies in [`POISSON_RANGE`] (NaN does not), else the
/// error every entry point shows.
pub fn check_poisson(poisson: f64) -> Result<f64, PoissonOutOfRange> {
    if (POISSON_RANGE.0..=POISSON_RANGE.1).contains(&poisson) {
        Ok(poisson)
    } else {
        Err(PoissonOutOfRange { value: poisson })
    }
}

/// Default relative tolerance of the friction quadrature.
pub const DEFAULT_TOLERANCE: f64 = 1e-6;

/// Rolling body and load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry {
    /// Sphere or cylinder.
    pub shape: Shape,
    /// Radius R of the body, m.
    pub radius: f64,
    /// Load: F_N in N (sphere) or f_N in N/m (cylinder).
    pub load: f64,
}

/// The viscoelastic solid's elastic constants that are not in E*(ω).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Substrate {
    /// Poisson's ratio ν, 0 ≤ ν ≤ ½, frequency-independent.
    pub poisson: f64,
    /// Thickness d (m) of a film bonded to a rigid base; `None` for a half-space.
    pub film_thickness: Option<f64>,
}

/// The rolling set-up: everything of a scene but the material (what a fit
/// works in, and what the plausibility checks judge a material in).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollingSetup {
    /// Body and load.
    pub geometry: Geometry,
    /// Poisson's ratio and film.
    pub substrate: Substrate,
    /// Contact-size rule.
    pub contact: ContactSize,
}

impl RollingSetup {
    /// 1 − ν².
    fn plane_strain_factor(&self) -> f64 {
        1.0 - self.substrate.poisson * self.substrate.poisson
    }

    /// ln of the Hertz contact size (m) for Young's modulus `modulus` (Pa)
    /// ([`ln_hertz_contact_size`] of E_eff = E/(1 − ν²)), finite for any
    /// positive finite radius and load.
    pub fn ln_contact_size(&self, modulus: f64) -> f64 {
        let g = self.geometry;
        let ln_e_eff = modulus.ln() - self.plane_strain_factor().ln();
        ln_hertz_contact_size(g.shape, g.radius, g.load, ln_e_eff)
    }

    /// The contact at speed `speed` (m/s) under the set-up's rule, in
    /// logarithms: (ln of its size in m, the Young's modulus |E| in Pa that
    /// set it). `modulus` is |E*(ω)| (Pa, ω in rad/s) and `static_modulus`
    /// E0 (Pa). Static: E0's contact. Dynamic: the fixed point
    /// r = r_Hertz(|E(v/r)|), approached from the static contact (the
    /// largest) to 1e-6 in ln r; a contraction since |E| grows at most like
    /// ω (slope ≤ ½). A modulus that is not finite and positive at some ω
    /// ends the iteration at the last contact that was. (The model error's
    /// `dynamic_contact_size` iterates the same map on a [`Scene`], in
    /// linear terms and to 1e-9, for the estimate it feeds.)
    pub fn ln_contact_at(
        &self,
        modulus: &dyn Fn(f64) -> f64,
        static_modulus: f64,
        speed: f64,
    ) -> (f64, f64) {
        let mut e = static_modulus;
        let mut ln_r = self.ln_contact_size(e);
        if self.contact == ContactSize::Static {
            return (ln_r, e);
        }
        for _ in 0..50 {
            let omega = (speed.ln() - ln_r).exp();
            let next = modulus(omega);
            if !(next.is_finite() && next > 0.0) {
                break;
            }
            let ln_next = self.ln_contact_size(next);
            let settled = (ln_next - ln_r).abs() < 1e-6;
            (e, ln_r) = (next, ln_next);
            if settled {
                break;
            }
        }
        (ln_r, e)
    }
}

/// A validated scene: everything μ(v) depends on.
#[derive(Debug, Clone)]
pub struct Scene<M> {
    geometry: Geometry,
    substrate: Substrate,
    contact: ContactSize,
    material: M,
    tolerance: f64,
}

/// A film thickness d (m) inside [`THICKNESS_RANGE`], the rule of every
/// front door (a scene's `[substrate] thickness`, Python's `Scene`).
/// [`Scene::new`] itself takes any positive d: the film's physics depends
/// on d/a only, and the model's tests probe d/a from 1e-300 to 1e300.
pub fn check_film_thickness(d: f64) -> Result<(), ModelError> {
    require_positive("thickness", d)?;
    if (THICKNESS_RANGE.0..=THICKNESS_RANGE.1).contains(&d) {
        return Ok(());
    }
    Err(ModelError::parameter(
        "thickness",
        d,
        "must lie between 1e-9 m and 1000 m, a nanometre (below it a film is no continuum) and \
         a kilometre (is it in m?)",
    ))
}

/// The load's hard range ([`SPHERE_LOAD_RANGE`], [`CYLINDER_LOAD_RANGE`]),
/// the one rule every front door applies through [`Scene::new`].
pub fn check_load(shape: Shape, load: f64) -> Result<(), ModelError> {
    let (range, unit, what) = match shape {
        Shape::Sphere => (SPHERE_LOAD_RANGE, "N", "a force"),
        Shape::Cylinder => (CYLINDER_LOAD_RANGE, "N/m", "a force per length"),
    };
    if (range.0..=range.1).contains(&load) {
        return Ok(());
    }
    Err(ModelError::parameter(
        "load",
        load,
        &format!(
            "must lie between {:e} and {:e} {unit} for a {} ({what}; the smallest measurable \
             rolling load and four decades above the largest plausible one): is it in {unit}?",
            range.0,
            range.1,
            match shape {
                Shape::Sphere => "sphere",
                Shape::Cylinder => "cylinder",
            }
        ),
    ))
}

impl<M: ViscoelasticModulus> Scene<M> {
    /// Checks every parameter and builds the scene with the default tolerance.
    pub fn new(
        geometry: Geometry,
        substrate: Substrate,
        contact: ContactSize,
        material: M,
    ) -> Result<Self, ModelError> {
        require_positive("radius", geometry.radius)?;
        require_positive("load", geometry.load)?;
        check_poisson(substrate.poisson)?;
        if let Some(d) = substrate.film_thickness {
            require_positive("thickness", d)?;
        }
        check_load(geometry.shape, geometry.load)?;
        let e0 = material.static_modulus();
        require_positive("static modulus E(0)", e0)?;
        if !(RADIUS_RANGE.0..=RADIUS_RANGE.1).contains(&geometry.radius) {
            return Err(ModelError::parameter(
                "radius",
                geometry.radius,
                "must lie between 1e-9 m and 1000 m, a nanometre and a kilometre (is it in m?)",
            ));
        }
        let scene = Scene {
            geometry,
            substrate,
            contact,
            material,
            tolerance: DEFAULT_TOLERANCE,
        };
        // A load far outside any contact overflows (or underflows) the Hertz
        // contact's size or pressure; everything downstream would be ∞ or 0.
        let (size, pressure) = (scene.static_contact_size(), scene.static_mean_pressure());
        let usable = |x: f64| x.is_finite() && x > f64::MIN_POSITIVE;
        if !(usable(size) && usable(pressure)) {
            return Err(ModelError::parameter(
                "load",
                geometry.load,
                &format!(
                    "gives a static Hertz contact of size {size:e} m and mean pressure \
                     {pressure:e} Pa with radius {:e} m and E(0) = {e0:e} Pa, which a \
                     floating-point number cannot represent: check the load's unit",
                    geometry.radius
                ),
            ));
        }
        Ok(scene)
    }

    /// The same scene with another requested relative tolerance of μ
    /// (between 1e-12 and 1e-2).
    pub fn with_tolerance(mut self, tolerance: f64) -> Result<Self, ModelError> {
        if !(tolerance.is_finite() && (1e-12..=1e-2).contains(&tolerance)) {
            return Err(ModelError::parameter(
                "tolerance",
                tolerance,
                "must lie between 1e-12 and 1e-2",
            ));
        }
        self.tolerance = tolerance;
        Ok(self)
    }

    /// Geometry (shape, radius, load).
    pub fn geometry(&self) -> &Geometry {
        &self.geometry
    }

    /// Substrate (Poisson's ratio, film thickness).
    pub fn substrate(&self) -> &Substrate {
        &self.substrate
    }

    /// The scene without its material.
    pub fn rolling_setup(&self) -> RollingSetup {
        RollingSetup {
            geometry: self.geometry,
            substrate: self.substrate,
            contact: self.contact,
        }
    }

    /// Contact-size rule.
    pub fn contact(&self) -> ContactSize {
        self.contact
    }

    /// The material's complex modulus.
    pub fn material(&self) -> &M {
        &self.material
    }

    /// Requested relative tolerance of μ.
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }

    /// 1 − ν², the factor between Young's and the effective modulus.
    pub fn plane_strain_factor(&self) -> f64 {
        1.0 - self.substrate.poisson * self.substrate.poisson
    }

    /// Static effective modulus E_eff(0) = E(0)/(1 − ν²), Pa.
    pub fn static_effective_modulus(&self) -> f64 {
        self.material.static_modulus() / self.plane_strain_factor()
    }

    /// Static Hertz contact size (m): r0 for a sphere, a0 for a cylinder.
    pub fn static_contact_size(&self) -> f64 {
        let g = &self.geometry;
        hertz_contact_size(g.shape, g.radius, g.load, self.static_effective_modulus())
    }

    /// Mean Hertz pressure p_a (Pa) of the static contact.
    pub fn static_mean_pressure(&self) -> f64 {
        let g = &self.geometry;
        mean_pressure(g.shape, g.load, self.static_contact_size())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The dynamic contact of a modulus |E| = E0 (1 + ω τ) solves
    /// r = r_Hertz(|E(v/r)|), checked by substitution into the linear
    /// Hertz law; the static rule gives E0's contact.
    #[test]
    fn the_dynamic_contact_is_the_fixed_point() {
        let (e0, tau, nu) = (2e6, 1e-3, 0.5);
        let modulus = |omega: f64| e0 * (1.0 + omega * tau);
        let factor = 1.0 - nu * nu;
        for shape in [Shape::Sphere, Shape::Cylinder] {
            let mut setup = RollingSetup {
                geometry: Geometry {
                    shape,
                    radius: 0.005,
                    load: 1.0,
                },
                substrate: Substrate {
                    poisson: nu,
                    film_thickness: None,
                },
                contact: ContactSize::Dynamic,
            };
            let g = setup.geometry;
            for speed in [1e-6, 1e-2, 1.0] {
                let (ln_r, e) = setup.ln_contact_at(&modulus, e0, speed);
                let omega = speed / ln_r.exp();
                let r = hertz_contact_size(shape, g.radius, g.load, modulus(omega) / factor);
                assert!(
                    (r.ln() - ln_r).abs() < 1e-5,
                    "{shape:?} v = {speed}: {r} vs {ln_r}"
                );
                assert!(
                    (e / modulus(omega) - 1.0).abs() < 1e-5,
                    "{shape:?} v = {speed}"
                );
            }
            setup.contact = ContactSize::Static;
            let (ln_r, e) = setup.ln_contact_at(&modulus, e0, 1.0);
            assert_eq!(e, e0);
            let r0 = hertz_contact_size(shape, g.radius, g.load, e0 / factor);
            assert!((ln_r.exp() / r0 - 1.0).abs() < 1e-13, "{shape:?}");
        }
    }
}
