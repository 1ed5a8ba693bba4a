//! The fit: μ(v) measurements → the master curve E*(ω) as a Prony series
//! (Persson 2010, Appendix B), by `rollfit_fit::fit`, the driver `rollfit
//! fit` runs.
//!
//! Settings arrive as keywords spelled as in a scene's `[fit]` table and go
//! one by one through `rollfit_fit::FitSettings::set`, the one parser of
//! the scene, the manifests and the flags, over the scene's own `[fit]`
//! (as `rollfit fit`'s flags go over it); the scale anchors `E0`, `E_at`
//! and `contact_radius` replace the scene's. `FitParams::check` validates
//! the whole against the rolling set-up. A bad value raises `ValueError`
//! with the text `rollfit fit` prints after "command line: --KEY: " (or
//! "scene file …: " for the scene's own).
//!
//! The fit runs on a worker thread with the GIL released; the calling
//! thread waits for it and checks for signals every 100 ms, so Ctrl-C
//! raises `KeyboardInterrupt` at once, and sets the fit's
//! `rollfit_fit::Cancel` flag, which ends the worker at its next solver
//! run.
//!
//! With DMA isotherms (the keyword `dma`, a path relative to the current
//! folder, or the scene file's `[fit] dma`, relative to its folder) the fit
//! is the joint fit of both: the file is read by
//! `rollfit_report::master_input::joint::read`, as `rollfit fit --dma` reads it, and the
//! result's `joint` is fit.json's `joint` record.
//!
//! The result keeps the report and the fit folder's three files encoded
//! by `rollfit_io::fit_dir::FitFiles`, the encoder `rollfit fit` uses:
//! `save(dir)` writes the same folder, `to_dict()` is fit.json.
//!
//! ## References
//! - B.N.J. Persson, Eur. Phys. J. E 33 (2010) 327, Appendix B.

#![allow(non_snake_case)] // T, E0, E_at: the names of the data and the scene file.

use std::path::PathBuf;
use std::sync::{Mutex, mpsc};
use std::time::Duration;

use num_complex::Complex64;
use numpy::PyArray1;
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyString};
use rollfit_fit::{
    Cancel, FitError, FitReport, FitSettings, Measurements, ScaleAnchor, SettingValue,
    ValidFitParams,
};
use rollfit_io::fit_dir::{FitFiles, FitInput, Measured};
use rollfit_io::output;
use rollfit_model::{Prony, ViscoelasticModulus};

use crate::convert::{
    Floats, array, floats, io_error, json_to_python, modulus_at, tan_delta_at, value_error,
    value_error_text,
};
use crate::scene::PyScene;

/// How long the waiting thread sleeps between checks for Ctrl-C.
const SIGNAL_CHECK: Duration = Duration::from_millis(100);

/// What fit.json's `input` names when the data came as arrays.
const FROM_PYTHON: &str = "<python>";

/// A keyword's value, owned, as a front door found it.
enum Value {
    Text(String),
    Number(f64),
    Integer(i64),
    Boolean(bool),
    Numbers(Vec<f64>),
}

impl Value {
    fn of(value: &Bound<'_, PyAny>) -> Option<Value> {
        if value.is_instance_of::<PyBool>() {
            return value.extract::<bool>().ok().map(Value::Boolean);
        }
        if value.is_instance_of::<PyInt>() {
            return value.extract::<i64>().ok().map(Value::Integer);
        }
        if value.is_instance_of::<PyFloat>() {
            return value.extract::<f64>().ok().map(Value::Number);
        }
        if value.is_instance_of::<PyString>() {
            return value.extract::<String>().ok().map(Value::Text);
        }
        if let Ok(list) = value.extract::<Vec<f64>>() {
            return Some(Value::Numbers(list));
        }
        // NumPy scalars.
        if let Ok(i) = value.extract::<i64>() {
            return Some(Value::Integer(i));
        }
        value.extract::<f64>().ok().map(Value::Number)
    }

    fn setting(&self) -> SettingValue<'_> {
        match self {
            Value::Text(t) => SettingValue::Text(t),
            Value::Number(x) => SettingValue::Number(*x),
            Value::Integer(i) => SettingValue::Integer(*i),
            Value::Boolean(b) => SettingValue::Boolean(*b),
            Value::Numbers(v) => SettingValue::Numbers(v.clone()),
        }
    }
}

/// A pair of numbers given as a dict with the scene file's keys or as a
/// tuple in that order.
fn pair(key: &str, value: &Bound<'_, PyAny>, names: [&str; 2]) -> PyResult<(f64, f64)> {
    let usage = || {
        value_error_text(format!(
            "fit setting `{key}`: expected {{\"{}\": …, \"{}\": …}} or a pair of numbers",
            names[0], names[1]
        ))
    };
    if let Ok(dict) = value.cast::<PyDict>() {
        let get = |name: &str| -> PyResult<f64> {
            dict.get_item(name)?
                .ok_or_else(usage)?
                .extract::<f64>()
                .map_err(|_| usage())
        };
        if dict.len() != 2 {
            return Err(usage());
        }
        return Ok((get(names[0])?, get(names[1])?));
    }
    value.extract::<(f64, f64)>().map_err(|_| usage())
}

/// The scale anchor of a keyword `E0`, `E_at` or `contact_radius`.
fn anchor(key: &str, value: &Bound<'_, PyAny>) -> PyResult<ScaleAnchor> {
    Ok(match key {
        "E0" => ScaleAnchor::StaticModulus(value.extract::<f64>().map_err(|_| {
            value_error_text("fit setting `E0`: expected the static Young's modulus, Pa")
        })?),
        "E_at" => {
            let (omega, modulus) = pair(key, value, ["omega", "E"])?;
            ScaleAnchor::ModulusAt { omega, modulus }
        }
        _ => {
            let (speed, radius) = pair(key, value, ["v", "r"])?;
            ScaleAnchor::ContactRadius { speed, radius }
        }
    })
}

/// A setting keyword's value; None for a joint fit's keyword given as
/// None ("not given", the stubs' default). The path of `dma` may be a
/// pathlib.Path.
fn keyword_value(key: &str, value: &Bound<'_, PyAny>) -> PyResult<Option<Value>> {
    if value.is_none() && matches!(key, "dma" | "dma_sigma" | "friction_factor") {
        return Ok(None);
    }
    let path = (key == "dma" && !value.is_instance_of::<PyString>())
        .then(|| value.extract::<PathBuf>().ok())
        .flatten()
        .map(|p| Value::Text(p.display().to_string()));
    path.or_else(|| Value::of(value)).map(Some).ok_or_else(|| {
        value_error_text(format!(
            "fit setting `{key}`: expected text, a number, true/false or a list of numbers"
        ))
    })
}

/// Fits the master curve E*(ω) to measured μ(v): speeds v (m/s), friction
/// coefficients mu, optional standard deviations sigma of μ and
/// temperatures T (°C; several make a temperature set). Settings as in a
/// scene's [fit] table (method, lambda, seed, starts, terms,
/// max_evaluations, tolerance, E1_max, shift, T_ref, cross_check, physics,
/// terms_per_decade, tau, dma, dma_sigma, friction_factor; anchors E0
/// (Pa), E_at = {"omega": rad/s, "E": Pa}, contact_radius = {"v": m/s,
/// "r": m}) override the scene's; shift is "auto" (the default: the law
/// the data support), "wlf", "arrhenius" or "free". dma (a path, relative
/// to the current folder; else the scene file's [fit] dma) makes the fit
/// a joint fit with those DMA isotherms.
/// data_file names the data in fit.json (default "<python>").
#[pyfunction]
#[pyo3(signature = (scene, v, mu, sigma = None, T = None, *, data_file = None, **settings))]
#[allow(clippy::too_many_arguments)]
pub fn fit(
    py: Python<'_>,
    scene: &PyScene,
    v: Floats<'_>,
    mu: Floats<'_>,
    sigma: Option<Floats<'_>>,
    T: Option<Floats<'_>>,
    data_file: Option<String>,
    settings: Option<&Bound<'_, PyDict>>,
) -> PyResult<FitResult> {
    let mut params = scene.params.clone();
    let mut given = FitSettings::default();
    let mut anchors = Vec::new();
    for (key, value) in settings.into_iter().flat_map(|d| d.iter()) {
        let key: String = key.extract()?;
        if matches!(key.as_str(), "E0" | "E_at" | "contact_radius") {
            anchors.push(key.clone());
            params.anchor = Some(anchor(&key, &value)?);
            continue;
        }
        if let Some(owned) = keyword_value(&key, &value)? {
            given
                .set(&key, owned.setting())
                .map_err(|e| value_error(&e))?;
        }
    }
    if anchors.len() > 1 {
        return Err(value_error_text(format!(
            "give one scale anchor, not {}",
            anchors.join(", ")
        )));
    }
    given.check().map_err(|e| value_error(&e))?;
    given.apply(&mut params);
    let t_ref = params.shift.t_ref;

    let speeds = floats(&v)?;
    let friction = floats(&mu)?;
    let sigma = sigma.as_ref().map(floats).transpose()?;
    let temperature = T.as_ref().map(floats).transpose()?;
    let data = Measurements::new(
        speeds.clone(),
        friction.clone(),
        sigma.clone(),
        temperature.clone(),
    )
    .map_err(|e| value_error(&e))?;
    let valid = params
        .check(scene.setup)
        .map_err(|e| match (&e, &scene.source) {
            (FitError::InvalidSetting { key, .. }, _) if given.gives(key) => value_error(&e),
            (_, Some(path)) => value_error_text(format!("scene file {path}: {e}")),
            (_, None) => value_error(&e),
        })?;
    let valid = with_dma(scene, &given, valid, t_ref)?;

    // The fit on a worker thread; this one waits with the GIL released and
    // wakes every SIGNAL_CHECK to let Python handle Ctrl-C.
    let cancel = Cancel::new();
    let valid = valid.with_cancel(cancel.clone());
    let (send, receive) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = send.send(rollfit_fit::fit(&data, &valid));
    });
    // A Mutex makes the receiver shareable with the detached closure; only
    // this thread ever locks it.
    let receive = Mutex::new(receive);
    let wait = || match receive.lock() {
        Ok(r) => r.recv_timeout(SIGNAL_CHECK),
        Err(poisoned) => poisoned.into_inner().recv_timeout(SIGNAL_CHECK),
    };
    let report = loop {
        match py.detach(wait) {
            Ok(result) => break result.map_err(|e| value_error(&e))?,
            Err(mpsc::RecvTimeoutError::Timeout) => {
                if let Err(interrupt) = py.check_signals() {
                    cancel.cancel();
                    return Err(interrupt);
                }
            }
            Err(mpsc::RecvTimeoutError::Disconnected) => {
                return Err(value_error_text(
                    "the fit's worker thread ended without a result",
                ));
            }
        }
    };

    let measured = Measured {
        speeds: &speeds,
        friction: &friction,
        sigma: sigma.as_deref(),
        temperature: temperature.as_deref(),
    };
    let input = FitInput {
        scene: scene.source.clone().unwrap_or_else(|| FROM_PYTHON.into()),
        data: data_file.unwrap_or_else(|| FROM_PYTHON.into()),
        temperature: measured.single_temperature(),
        rollfit_version: env!("CARGO_PKG_VERSION"),
    };
    let files = FitFiles::encode(&report, &measured, &input).map_err(|e| io_error(&e))?;
    let m = &report.model;
    let master = Prony::new(m.glassy_modulus, m.strengths.clone(), m.tau.clone())
        .map_err(|e| value_error(&e))?;
    Ok(FitResult {
        report,
        files,
        master,
    })
}

/// `valid` as a joint fit with the DMA file of the keyword `dma` (relative
/// to the current folder) or of the scene file's `[fit] dma`; unchanged
/// without either. A file without temperatures is taken at `t_ref`.
fn with_dma(
    scene: &PyScene,
    given: &FitSettings,
    valid: ValidFitParams,
    t_ref: Option<f64>,
) -> PyResult<ValidFitParams> {
    let (path, keyword) = match (&given.dma, &scene.dma) {
        (Some(path), _) => (PathBuf::from(path), true),
        (None, Some(path)) => (path.clone(), false),
        (None, None) => return Ok(valid),
    };
    if !path.is_file() {
        let whose = if keyword {
            "dma is relative to the current folder".to_string()
        } else {
            format!(
                "[fit] dma is relative to the folder of scene file {}",
                scene.source.as_deref().unwrap_or("?")
            )
        };
        let what = if path.exists() {
            "is not a file"
        } else {
            "does not exist"
        };
        return Err(PyOSError::new_err(format!(
            "DMA file {} {what} ({whose})",
            path.display()
        )));
    }
    let read = rollfit_report::master_input::joint::read(&path, scene.setup.substrate.poisson, t_ref)
        .map_err(|e| io_error(&e))?;
    valid.with_dma(read.rows).map_err(|e| value_error(&e))
}

/// A measurement file read as `rollfit fit` reads it (text or workbook,
/// header aliases, units converted): a dict with "v" (m/s), "mu", "sigma"
/// and "T" (°C; None where the file has no such column), "notes" and
/// "warnings".
#[pyfunction]
#[pyo3(signature = (path, sheet = None))]
pub fn read_data<'py>(
    py: Python<'py>,
    path: PathBuf,
    sheet: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let table = rollfit_io::data::read_sheet(&path, sheet.as_deref()).map_err(|e| io_error(&e))?;
    let dict = PyDict::new(py);
    dict.set_item("v", array(py, table.speeds))?;
    dict.set_item("mu", array(py, table.friction))?;
    dict.set_item("sigma", table.sigma.map(|s| array(py, s)))?;
    dict.set_item("T", table.temperature.map(|t| array(py, t)))?;
    dict.set_item("notes", table.notes)?;
    dict.set_item("warnings", table.warnings)?;
    Ok(dict)
}

/// The result of `rollfit.fit`: the master curve E*(ω) as a Prony series
/// with its determined window, bands, shift, warnings, and the fit folder.
#[pyclass(module = "rollfit", frozen)]
pub struct FitResult {
    pub(crate) report: FitReport,
    pub(crate) files: FitFiles,
    master: Prony,
}

impl FitResult {
    /// fit.json as encoded.
    fn fit_json(&self) -> &[u8] {
        self.files.named()[2].1
    }
}

#[pymethods]
impl FitResult {
    /// The recovered E*(ω) = E′ + iE″ (Young's, Pa, at the reference state)
    /// at each ω (rad/s).
    fn modulus<'py>(
        &self,
        py: Python<'py>,
        omega: Floats<'py>,
    ) -> PyResult<Bound<'py, PyArray1<Complex64>>> {
        modulus_at(py, &omega, |w| self.master.modulus(w))
    }

    /// The recovered tan δ = E″/E′ at each ω (rad/s).
    fn tan_delta<'py>(
        &self,
        py: Python<'py>,
        omega: Floats<'py>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        tan_delta_at(py, &omega, |w| self.master.modulus(w))
    }

    /// The 1σ bands at each ω (rad/s): a dict of arrays "E_storage",
    /// "E_loss" (Pa), "tan_delta", "abs_E" (Pa), each the fitted value, and
    /// the same names with "_sigma" (1σ, bias included), interpolated in
    /// ln ω between modulus.csv's points; NaN outside the determined window.
    fn band<'py>(&self, py: Python<'py>, omega: Floats<'py>) -> PyResult<Bound<'py, PyDict>> {
        let omega = floats(&omega)?;
        let points: Vec<Option<rollfit_fit::ModulusPoint>> =
            omega.iter().map(|&w| self.report.band_at(w)).collect();
        let column = |f: fn(&rollfit_fit::ModulusPoint) -> f64| {
            array(
                py,
                points
                    .iter()
                    .map(|p| p.as_ref().map_or(f64::NAN, f))
                    .collect(),
            )
        };
        let dict = PyDict::new(py);
        dict.set_item("omega", array(py, omega.clone()))?;
        dict.set_item("E_storage", column(|p| p.storage))?;
        dict.set_item("E_loss", column(|p| p.loss))?;
        dict.set_item("tan_delta", column(|p| p.tan_delta))?;
        dict.set_item("abs_E", column(|p| p.magnitude))?;
        dict.set_item("E_storage_sigma", column(|p| p.storage_sigma))?;
        dict.set_item("E_loss_sigma", column(|p| p.loss_sigma))?;
        dict.set_item("tan_delta_sigma", column(|p| p.tan_delta_sigma))?;
        dict.set_item("abs_E_sigma", column(|p| p.magnitude_sigma))?;
        Ok(dict)
    }

    /// modulus.csv as a dict of arrays: omega (rad/s), E_storage, E_loss
    /// (Pa), tan_delta, abs_E (Pa) and their 1σ, 10 points per decade over
    /// the determined window.
    #[getter]
    fn curve<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        let names = rollfit_io::fit_dir::columns::MODULUS_COLUMNS;
        for (k, name) in names.iter().enumerate() {
            let values = self.report.curve.iter().map(|p| p.values()[k]).collect();
            dict.set_item(*name, array(py, values))?;
        }
        Ok(dict)
    }

    /// The window the data determine, (ω_min, ω_max) in rad/s.
    #[getter]
    fn window(&self) -> (f64, f64) {
        (self.report.window.omega_min, self.report.window.omega_max)
    }

    /// The window the speeds probe, (ω_min, ω_max) in rad/s.
    #[getter]
    fn probed_window(&self) -> (f64, f64) {
        (
            self.report.probed_window.omega_min,
            self.report.probed_window.omega_max,
        )
    }

    /// A temperature set's shift as in fit.json ("model" "wlf", "arrhenius"
    /// or "free", "T_ref", C1, C2 in K or E_a in J/mol, and log10 a_T with
    /// its 1σ, None where undetermined, per temperature), None otherwise.
    #[getter]
    fn shift<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let all = json_to_python(py, self.fit_json())?;
        all.call_method1("get", ("shift",))
    }

    /// A joint fit's account of its DMA and rolling parts, as in fit.json's
    /// `joint` (each part's χ² joint and alone, the compatibility test, κ
    /// if fitted, the DMA points with the joint curve), None without DMA
    /// data.
    #[getter]
    fn joint<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let all = json_to_python(py, self.fit_json())?;
        all.call_method1("get", ("joint",))
    }

    /// Things the user must know (fit.json's `warnings`).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.report.warnings.clone()
    }

    /// Whether the final solver run converged.
    #[getter]
    fn converged(&self) -> bool {
        self.report.converged
    }

    /// μ of the fit at the data's speeds (mu.csv's mu_fit).
    #[getter]
    fn mu_fit<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, self.report.mu_fit.clone())
    }

    /// fit.json's content as a dict.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json_to_python(py, self.fit_json())
    }

    /// Writes the fit folder `rollfit fit` writes: dir/fit.json,
    /// dir/modulus.csv and dir/mu.csv, replacing the folder as a whole
    /// (created if missing). Unlike `rollfit fit`, an unconverged or poor
    /// fit is written too (marked in fit.json); check `converged` and
    /// `to_dict()["fit_quality"]`.
    fn save(&self, dir: PathBuf) -> PyResult<()> {
        output::replace_folder(&dir, output::Writer::Fit, false, &self.files.named())
            .map_err(|e| io_error(&e))
    }

    fn __repr__(&self) -> String {
        format!(
            "FitResult({} terms, window {:.3e} … {:.3e} rad/s, converged={})",
            self.report.terms.count,
            self.report.window.omega_min,
            self.report.window.omega_max,
            // Python's spelling of a bool.
            if self.report.converged {
                "True"
            } else {
                "False"
            }
        )
    }
}
