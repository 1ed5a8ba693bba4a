//! Materials: the complex Young's modulus E*(ω) = E′ + iE″ (Pa) of the
//! solid, as the model crate defines it (`rollfit_model::modulus`, the
//! engineering sign convention, E″ ≥ 0 for ω > 0). Each Python class wraps
//! one model constructor, which owns the parameter ranges; nothing here
//! evaluates a modulus but through `ViscoelasticModulus`.
//!
//! - `SLS(E0, E1, tau)`: the standard linear solid, Persson Eq. (12).
//! - `Prony(E1, H, tau)`: E*(ω) = E1 − Σ H_k/(1 + iωτ_k), Eq. (B2).
//! - `HavriliakNegami(E0, E1, tau, alpha, beta)`:
//!   E*(ω) = E1 + (E0 − E1)/(1 + (iωτ)^α)^β.
//! - `Table(omega, E_storage, E_loss)`: a tabulated master curve,
//!   monotone cubic in log–log, terminal behaviour outside.
//!
//! ## References
//! - B.N.J. Persson, Eur. Phys. J. E 33 (2010) 327, Eqs. (12), (B2).
//! - S. Havriliak, S. Negami, Polymer 8 (1967) 161.

#![allow(non_snake_case)] // E0, E1, H: the paper's names, as keywords in Python.

use std::sync::Arc;

use num_complex::Complex64;
use numpy::PyArray1;
use pyo3::prelude::*;
use rollfit_fit::StartMaterial;
use rollfit_model::{
    HavriliakNegami, Prony, StandardLinearSolid, TabulatedModulus, ViscoelasticModulus,
};

use crate::convert::{Floats, floats, modulus_at, tan_delta_at, value_error};

/// A viscoelastic solid: its complex Young's modulus E*(ω), Pa.
#[pyclass(subclass, module = "rollfit")]
pub struct Material {
    /// E*(ω).
    pub(crate) modulus: Arc<dyn ViscoelasticModulus>,
    /// The same solid as a Prony series, where it is one (SLS, Prony):
    /// what μ's Jacobian is taken with respect to.
    pub(crate) prony: Option<Prony>,
    /// E0 and E1 as a fit's starting point (SLS, Prony), as a scene's
    /// `[material]` gives them.
    pub(crate) start: Option<StartMaterial>,
    /// For `repr`.
    description: String,
}

impl Material {
    fn new(
        modulus: Arc<dyn ViscoelasticModulus>,
        prony: Option<Prony>,
        start: Option<StartMaterial>,
        description: String,
    ) -> Material {
        Material {
            modulus,
            prony,
            start,
            description,
        }
    }
}

#[pymethods]
impl Material {
    /// E*(ω) = E′ + iE″ (Young's, Pa) at each angular frequency ω (rad/s,
    /// ≥ 0), as a complex128 array.
    fn modulus<'py>(
        &self,
        py: Python<'py>,
        omega: Floats<'py>,
    ) -> PyResult<Bound<'py, PyArray1<Complex64>>> {
        modulus_at(py, &omega, |w| self.modulus.modulus(w))
    }

    /// tan δ = E″/E′ at each ω (rad/s).
    fn tan_delta<'py>(
        &self,
        py: Python<'py>,
        omega: Floats<'py>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        tan_delta_at(py, &omega, |w| self.modulus.modulus(w))
    }

    /// The static (rubbery) modulus E(0), Pa.
    #[getter]
    fn static_modulus(&self) -> f64 {
        self.modulus.static_modulus()
    }

    fn __repr__(&self) -> String {
        self.description.clone()
    }
}

/// The standard linear solid (Persson Eq. 12): rubbery modulus E0 (Pa),
/// glassy modulus E1 (Pa), relaxation time tau (s).
#[pyclass(extends = Material, name = "SLS", module = "rollfit")]
pub struct Sls {
    /// Pa.
    #[pyo3(get)]
    E0: f64,
    /// Pa.
    #[pyo3(get)]
    E1: f64,
    /// s.
    #[pyo3(get)]
    tau: f64,
}

#[pymethods]
impl Sls {
    #[new]
    fn new(E0: f64, E1: f64, tau: f64) -> PyResult<PyClassInitializer<Self>> {
        let sls = StandardLinearSolid::new(E0, E1, tau).map_err(|e| value_error(&e))?;
        let prony = sls.to_prony();
        let start = StartMaterial {
            static_modulus: E0,
            glassy_modulus: E1,
        };
        let description = format!("SLS(E0={E0:e}, E1={E1:e}, tau={tau:e})");
        Ok(PyClassInitializer::from(Material::new(
            Arc::new(sls),
            Some(prony),
            Some(start),
            description,
        ))
        .add_subclass(Sls { E0, E1, tau }))
    }
}

/// A Prony series (Persson Eq. B2): E*(ω) = E1 − Σ H_k/(1 + iωτ_k), glassy
/// modulus E1 (Pa), strengths H_k ≥ 0 (Pa), relaxation times tau_k (s).
#[pyclass(extends = Material, name = "Prony", module = "rollfit")]
pub struct PronySeries {
    /// Pa.
    #[pyo3(get)]
    E1: f64,
    /// Pa.
    #[pyo3(get)]
    H: Vec<f64>,
    /// s.
    #[pyo3(get)]
    tau: Vec<f64>,
}

#[pymethods]
impl PronySeries {
    #[new]
    fn new(E1: f64, H: Floats<'_>, tau: Floats<'_>) -> PyResult<PyClassInitializer<Self>> {
        let (h, tau) = (floats(&H)?, floats(&tau)?);
        let prony = Prony::new(E1, h.clone(), tau.clone()).map_err(|e| value_error(&e))?;
        // As a scene's `[material]` gives the start (rollfit_io, material.rs).
        let start = StartMaterial {
            static_modulus: E1 - h.iter().sum::<f64>(),
            glassy_modulus: E1,
        };
        let description = format!("Prony(E1={E1:e}, {} terms)", h.len());
        Ok(PyClassInitializer::from(Material::new(
            Arc::new(prony.clone()),
            Some(prony),
            Some(start),
            description,
        ))
        .add_subclass(PronySeries { E1, H: h, tau }))
    }
}

/// The Havriliak–Negami solid: E*(ω) = E1 + (E0 − E1)/(1 + (iωτ)^α)^β with
/// 0 < E0 < E1 (Pa), tau > 0 (s), 0 < alpha, beta ≤ 1.
#[pyclass(extends = Material, name = "HavriliakNegami", module = "rollfit")]
pub struct HavriliakNegamiSolid {
    /// Pa.
    #[pyo3(get)]
    E0: f64,
    /// Pa.
    #[pyo3(get)]
    E1: f64,
    /// s.
    #[pyo3(get)]
    tau: f64,
    #[pyo3(get)]
    alpha: f64,
    #[pyo3(get)]
    beta: f64,
}

#[pymethods]
impl HavriliakNegamiSolid {
    #[new]
    fn new(
        E0: f64,
        E1: f64,
        tau: f64,
        alpha: f64,
        beta: f64,
    ) -> PyResult<PyClassInitializer<Self>> {
        let hn = HavriliakNegami::new(E0, E1, tau, alpha, beta).map_err(|e| value_error(&e))?;
        let description = format!(
            "HavriliakNegami(E0={E0:e}, E1={E1:e}, tau={tau:e}, alpha={alpha}, beta={beta})"
        );
        Ok(
            PyClassInitializer::from(Material::new(Arc::new(hn), None, None, description))
                .add_subclass(HavriliakNegamiSolid {
                    E0,
                    E1,
                    tau,
                    alpha,
                    beta,
                }),
        )
    }
}

/// A tabulated master curve: angular frequencies omega (rad/s, increasing),
/// Young's storage and loss moduli E_storage, E_loss (Pa); a monotone cubic
/// in log–log between the points, the terminal behaviour of a solid
/// outside (E′ constant, E″ ∝ ω below, ∝ 1/ω above).
#[pyclass(extends = Material, name = "Table", module = "rollfit")]
pub struct Table {
    /// rad/s.
    #[pyo3(get)]
    omega: Vec<f64>,
    /// Pa.
    #[pyo3(get)]
    E_storage: Vec<f64>,
    /// Pa.
    #[pyo3(get)]
    E_loss: Vec<f64>,
}

#[pymethods]
impl Table {
    #[new]
    fn new(
        omega: Floats<'_>,
        E_storage: Floats<'_>,
        E_loss: Floats<'_>,
    ) -> PyResult<PyClassInitializer<Self>> {
        let (omega, storage, loss) = (floats(&omega)?, floats(&E_storage)?, floats(&E_loss)?);
        let table = TabulatedModulus::new(omega.clone(), storage.clone(), loss.clone())
            .map_err(|e| value_error(&e))?;
        let description = format!("Table({} points)", omega.len());
        Ok(
            PyClassInitializer::from(Material::new(Arc::new(table), None, None, description))
                .add_subclass(Table {
                    omega,
                    E_storage: storage,
                    E_loss: loss,
                }),
        )
    }
}
