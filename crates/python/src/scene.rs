//! The rolling scene and μ(v): a hard sphere or cylinder of radius R (m)
//! under a load (N for a sphere, N/m for a cylinder) on a viscoelastic
//! solid of Poisson's ratio ν, optionally a film of thickness d (m) on a
//! rigid base, with the paper's contact-size rule ("dynamic": Hertz size
//! from |E_eff| at the local frequency, or "static": from E_eff(0)).
//!
//! μ(v) is `rollfit_model::Scene::friction_sweep` (Persson Eqs. 11/17,
//! every speed of a call on one shared σ-grid), with the GIL released;
//! μ with ∂μ/∂(E1, H_k) is `Scene::friction_with_gradient` on the
//! material's Prony form. A scene read from a file is the one `rollfit
//! forward` builds from it (`SceneFile::forward_setup`), so μ is the
//! forward CSV's `mu` bit for bit; its `[fit]` table is the one `rollfit
//! fit` reads (`SceneFile::fit_setup`).
//!
//! ## References
//! - B.N.J. Persson, Eur. Phys. J. E 33 (2010) 327, Eqs. (9), (11), (14), (17).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use num_complex::Complex64;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use rollfit_fit::{FitParams, RollingSetup};
use rollfit_io::scene::{self as scene_file, ContactName, DynScene, ForwardRung};
use rollfit_model::{ContactSize, Geometry, Prony, Scene, Shape, Substrate, ViscoelasticModulus};

use crate::convert::{
    Floats, array, complex_array, floats, io_error, speeds, value_error, value_error_text,
};
use crate::material::Material;

/// μ(v_i) and ∂μ(v_i)/∂p_j as NumPy arrays.
type MuAndJacobian<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray2<f64>>);

/// A rolling scene: body, load, substrate, contact-size rule and
/// (optionally) the material.
#[pyclass(name = "Scene", module = "rollfit", frozen)]
pub struct PyScene {
    /// Geometry, substrate and contact rule.
    pub(crate) setup: RollingSetup,
    /// The scene with its material (None without a material: a scene for
    /// fitting only).
    scene: Option<DynScene>,
    /// The material as a Prony series, where it is one: for the Jacobian.
    prony: Option<Scene<Prony>>,
    /// The Python material the scene was made with.
    material: Option<Py<Material>>,
    /// The fit's parameters before keyword settings: the scene file's
    /// `[fit]` (anchor, settings) and `[material]` start, or the defaults
    /// with the material's start.
    pub(crate) params: FitParams,
    /// The scene file, as given (fit.json's `input.scene`).
    pub(crate) source: Option<String>,
    /// `[fit] dma` of a scene file, resolved against its folder: the DMA
    /// isotherms of a joint fit, read when `fit` runs.
    pub(crate) dma: Option<PathBuf>,
    /// `[sweep]` speeds of a scene file, m/s.
    speeds: Option<Vec<f64>>,
    /// What the readers of a scene file's tables said.
    notes: Vec<String>,
}

fn shape_of(name: &str) -> PyResult<Shape> {
    match name {
        "sphere" => Ok(Shape::Sphere),
        "cylinder" => Ok(Shape::Cylinder),
        other => Err(value_error_text(format!(
            "shape: unknown shape {other:?} (use \"sphere\" or \"cylinder\")"
        ))),
    }
}

fn contact_of(name: &str) -> PyResult<ContactSize> {
    match name {
        "dynamic" => Ok(ContactSize::Dynamic),
        "static" => Ok(ContactSize::Static),
        other => Err(value_error_text(format!(
            "contact: unknown contact size {other:?} (use \"dynamic\" or \"static\"; the \
             exact, low-speed and auto rungs are `rollfit forward`'s)"
        ))),
    }
}

impl PyScene {
    /// The scene with a material, or the error a forward computation gives.
    fn with_material(&self) -> PyResult<&DynScene> {
        self.scene.as_ref().ok_or_else(|| {
            value_error_text("the scene has no material: give Scene(..., material=...)")
        })
    }
}

#[pymethods]
impl PyScene {
    /// A scene: shape "sphere" or "cylinder"; radius R (m); load (N for a
    /// sphere, N/m for a cylinder); Poisson's ratio (0 … 0.5); thickness d
    /// (m) of a film on a rigid base, or None for a half-space; contact
    /// "dynamic" or "static"; material (SLS, Prony, HavriliakNegami, Table;
    /// None for a scene used only to fit); tolerance, the relative accuracy
    /// of μ (default 1e-6).
    #[new]
    #[pyo3(signature = (*, shape, radius, load, poisson = 0.5, thickness = None, contact = "dynamic", material = None, tolerance = None))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        shape: &str,
        radius: f64,
        load: f64,
        poisson: f64,
        thickness: Option<f64>,
        contact: &str,
        material: Option<Py<Material>>,
        tolerance: Option<f64>,
    ) -> PyResult<Self> {
        if let Some(d) = thickness {
            rollfit_model::check_film_thickness(d).map_err(|e| value_error(&e))?;
        }
        let setup = RollingSetup {
            geometry: Geometry {
                shape: shape_of(shape)?,
                radius,
                load,
            },
            substrate: Substrate {
                poisson,
                film_thickness: thickness,
            },
            contact: contact_of(contact)?,
        };
        let mut params = FitParams::default();
        let (mut scene, mut prony) = (None, None);
        if let Some(m) = &material {
            let m = m.borrow(py);
            let modulus: Box<dyn ViscoelasticModulus> = Box::new(Arc::clone(&m.modulus));
            let mut built = Scene::new(setup.geometry, setup.substrate, setup.contact, modulus)
                .map_err(|e| value_error(&e))?;
            if let Some(t) = tolerance {
                built = built.with_tolerance(t).map_err(|e| value_error(&e))?;
            }
            if let Some(p) = &m.prony {
                let tol = built.tolerance();
                prony = Some(
                    Scene::new(setup.geometry, setup.substrate, setup.contact, p.clone())
                        .and_then(|s| s.with_tolerance(tol))
                        .map_err(|e| value_error(&e))?,
                );
            }
            params.start = m.start.clone();
            scene = Some(built);
        } else {
            // The model checks the set-up even without a material, as
            // `rollfit fit` does with a placeholder.
            let placeholder = rollfit_model::StandardLinearSolid::new(1.0, 2.0, 1.0)
                .map_err(|e| value_error(&e))?;
            Scene::new(setup.geometry, setup.substrate, setup.contact, placeholder)
                .map_err(|e| value_error(&e))?;
        }
        Ok(PyScene {
            setup,
            scene,
            prony,
            material,
            params,
            source: None,
            dma: None,
            speeds: None,
            notes: Vec::new(),
        })
    }

    /// The scene of a scene file (TOML, as `rollfit forward` and `rollfit
    /// fit` read it): [geometry], [substrate], [contact] (size "dynamic" or
    /// "static"), [material] (optional), [fit] (the fit's anchor and
    /// settings) and [sweep] (its speeds, `speeds`; its tolerance; one
    /// temperature at most).
    #[staticmethod]
    fn from_toml(path: PathBuf) -> PyResult<Self> {
        let file = scene_file::load(&path).map_err(|e| io_error(&e))?;
        let in_file =
            |text: String| value_error_text(format!("scene file {}: {text}", path.display()));
        match file.contact.size {
            None | Some(ContactName::Dynamic) | Some(ContactName::Static) => {}
            Some(other) => {
                let name = match other {
                    ContactName::Exact => "exact",
                    ContactName::LowSpeed => "low-speed",
                    _ => "auto",
                };
                return Err(in_file(format!(
                    "[contact] size = {name:?}: a Scene computes μ with the paper's rungs, \
                     \"dynamic\" or \"static\"; the exact, low-speed and auto rungs are `rollfit \
                     forward`'s"
                )));
            }
        }
        let (setup, params) = file
            .fit_setup()
            .map_err(|e| in_file(rollfit_io::chain(&e)))?;
        let notes = std::cell::RefCell::new(Vec::new());
        let note = |line: &str| notes.borrow_mut().push(line.to_string());
        let base_dir = path.parent().unwrap_or(Path::new(""));
        let (scene, speeds) = match (&file.material, &file.sweep) {
            (None, _) => (None, None),
            (Some(_), Some(_)) => {
                let forward = file
                    .forward_setup(&path, &note)
                    .map_err(|e| in_file(rollfit_io::chain(&e)))?;
                let speeds = forward.speeds;
                let mut blocks = forward.blocks;
                if blocks.len() != 1 {
                    return Err(in_file(format!(
                        "[sweep] temperature lists {} temperatures; a Scene is one solid at one \
                         temperature (give one temperature, or make one Scene per temperature)",
                        blocks.len()
                    )));
                }
                let block = blocks.remove(0);
                debug_assert!(matches!(block.rung, ForwardRung::Paper));
                (Some(block.scene), Some(speeds))
            }
            (Some(material), None) => {
                let modulus = material
                    .build(base_dir, &note)
                    .map_err(|e| in_file(rollfit_io::chain(&e)))?;
                let built = Scene::new(setup.geometry, setup.substrate, setup.contact, modulus)
                    .map_err(|e| in_file(rollfit_io::chain(&e)))?;
                (Some(built), None)
            }
        };
        // The Prony form for the Jacobian: only without a temperature shift,
        // whose material is not the section's series.
        let unshifted = file.sweep.as_ref().is_none_or(|s| s.temperature.is_none());
        let prony = match (&file.material, &scene) {
            (Some(material), Some(built)) if unshifted => material
                .as_prony(base_dir, &note)
                .map_err(|e| in_file(rollfit_io::chain(&e)))?
                .map(|p| {
                    Scene::new(setup.geometry, setup.substrate, setup.contact, p)
                        .and_then(|s| s.with_tolerance(built.tolerance()))
                })
                .transpose()
                .map_err(|e| in_file(rollfit_io::chain(&e)))?,
            _ => None,
        };
        Ok(PyScene {
            setup,
            scene,
            prony,
            material: None,
            params,
            source: Some(path.display().to_string()),
            dma: file.dma_file(base_dir),
            speeds,
            notes: notes.into_inner(),
        })
    }

    /// μ at each speed v (m/s, positive, increasing), as a float64 array:
    /// Persson Eq. (11) (cylinder) or (17) (sphere), all speeds on one
    /// shared grid; the GIL is released while it runs.
    fn mu<'py>(&self, py: Python<'py>, v: Floats<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let scene = self.with_material()?;
        let speeds = speeds("v", &v)?;
        let mu = py
            .detach(|| scene.friction_sweep(&speeds))
            .map_err(|e| value_error(&e))?;
        Ok(array(py, mu))
    }

    /// (μ, J): μ at each speed v (m/s) and its Jacobian J[i, j] =
    /// ∂μ(v_i)/∂p_j (1/Pa) with respect to the Prony parameters p = (E1,
    /// H_1, …, H_n) of the material (an SLS is its one-term series), in
    /// one pass; the GIL is released while it runs.
    fn mu_and_jacobian<'py>(
        &self,
        py: Python<'py>,
        v: Floats<'py>,
    ) -> PyResult<MuAndJacobian<'py>> {
        self.with_material()?;
        let scene = self.prony.as_ref().ok_or_else(|| {
            value_error_text(
                "mu_and_jacobian needs a material that is a Prony series (SLS, Prony, or a \
                 scene file's \"sls\", \"prony\" or \"dma\" material without a temperature)",
            )
        })?;
        let speeds = speeds("v", &v)?;
        let result = py
            .detach(|| scene.friction_with_gradient(&speeds))
            .map_err(|e| value_error(&e))?;
        let (n, np) = (result.mu.len(), result.parameter_count);
        let jacobian = array(py, result.jacobian)
            .reshape([n, np])
            .map_err(|e| value_error_text(e.to_string()))?;
        Ok((array(py, result.mu), jacobian))
    }

    /// The scene's material E*(ω) (Young's, Pa; shifted to the [sweep]
    /// temperature of a scene file) at each ω (rad/s).
    fn modulus<'py>(
        &self,
        py: Python<'py>,
        omega: Floats<'py>,
    ) -> PyResult<Bound<'py, PyArray1<Complex64>>> {
        let scene = self.with_material()?;
        let omega = floats(&omega)?;
        Ok(complex_array(
            py,
            omega.iter().map(|&w| scene.material().modulus(w)).collect(),
        ))
    }

    /// The [sweep] speeds of a scene file (m/s), None otherwise.
    #[getter]
    fn speeds<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        self.speeds.clone().map(|s| array(py, s))
    }

    /// The material the scene was made with (None for a scene file's).
    #[getter]
    fn material(&self, py: Python<'_>) -> Option<Py<Material>> {
        self.material.as_ref().map(|m| m.clone_ref(py))
    }

    /// "sphere" or "cylinder".
    #[getter]
    fn shape(&self) -> &'static str {
        match self.setup.geometry.shape {
            Shape::Sphere => "sphere",
            Shape::Cylinder => "cylinder",
        }
    }

    /// Radius R, m.
    #[getter]
    fn radius(&self) -> f64 {
        self.setup.geometry.radius
    }

    /// Load: N (sphere) or N/m (cylinder).
    #[getter]
    fn load(&self) -> f64 {
        self.setup.geometry.load
    }

    /// Poisson's ratio ν.
    #[getter]
    fn poisson(&self) -> f64 {
        self.setup.substrate.poisson
    }

    /// Film thickness d (m), None for a half-space.
    #[getter]
    fn thickness(&self) -> Option<f64> {
        self.setup.substrate.film_thickness
    }

    /// Relative tolerance of μ.
    #[getter]
    fn tolerance(&self) -> Option<f64> {
        self.scene.as_ref().map(|s| s.tolerance())
    }

    /// What the readers of a scene file's tables said (`note:` lines of
    /// the CLI).
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.notes.clone()
    }

    fn __repr__(&self) -> String {
        let g = &self.setup.geometry;
        format!(
            "Scene(shape={:?}, radius={:e}, load={:e}, poisson={}{})",
            self.shape(),
            g.radius,
            g.load,
            self.setup.substrate.poisson,
            self.source
                .as_ref()
                .map(|s| format!(", file={s:?}"))
                .unwrap_or_default()
        )
    }
}
