//! Scenes of the model crate built in one call: the tests vary one or two
//! of shape, size, load, Poisson ratio, film and contact rule, and spell
//! out only those.

use rollfit_model::{ContactSize, Geometry, Prony, Scene, Shape, Substrate, ViscoelasticModulus};

/// A scene of the given shape, radius (m), load (N or N/m), Poisson ratio,
/// film thickness and contact rule, at the default tolerance.
pub fn scene<M: ViscoelasticModulus>(
    shape: Shape,
    radius: f64,
    load: f64,
    nu: f64,
    film: Option<f64>,
    contact: ContactSize,
    material: M,
) -> Scene<M> {
    Scene::new(
        Geometry {
            shape,
            radius,
            load,
        },
        Substrate {
            poisson: nu,
            film_thickness: film,
        },
        contact,
        material,
    )
    .unwrap()
}

/// A 5 mm ball under 1 N or roller under 200 N/m on an incompressible
/// solid (optionally a film of that thickness), at `tolerance`.
pub fn ball_or_roller(
    shape: Shape,
    contact: ContactSize,
    film: Option<f64>,
    material: Prony,
    tolerance: f64,
) -> Scene<Prony> {
    let load = if shape == Shape::Sphere { 1.0 } else { 200.0 };
    scene(shape, 0.005, load, 0.5, film, contact, material)
        .with_tolerance(tolerance)
        .unwrap()
}
