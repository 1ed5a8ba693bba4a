//! The boundary between Rust and Python: errors become `ValueError` with
//! the text the command line prints after "error: " (the error and its
//! causes, joined by ": "), and arrays cross as NumPy arrays.

use num_complex::Complex64;
use numpy::{PyArray1, PyArrayLike1};
use pyo3::exceptions::{PyOSError, PyTypeError, PyValueError};
use pyo3::prelude::*;

/// A 1-D float64 array argument (a list or any array-like of reals,
/// converted to float64). Complex values are refused: NumPy would drop
/// their imaginary parts with only a ComplexWarning, where the command
/// line reads no such number. pyo3 adds the argument's name ("complex
/// values: … while processing 'v'").
pub struct Floats<'py>(PyArrayLike1<'py, f64, numpy::AllowTypeChange>);

impl<'a, 'py> FromPyObject<'a, 'py> for Floats<'py> {
    type Error = PyErr;

    fn extract(ob: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        let numpy = ob.py().import("numpy")?;
        if numpy.call_method1("iscomplexobj", (ob,))?.is_truthy()? {
            return Err(PyTypeError::new_err(
                "complex values: give real numbers (the imaginary parts would be dropped)",
            ));
        }
        Ok(Floats(ob.extract()?))
    }
}

/// `ValueError` with an error's whole chain of causes.
pub fn value_error(error: &dyn std::error::Error) -> PyErr {
    PyValueError::new_err(rollfit_io::chain(error))
}

/// `ValueError` with a message.
pub fn value_error_text(text: impl Into<String>) -> PyErr {
    PyValueError::new_err(text.into())
}

/// An I/O error of rollfit_io: a file that cannot be read or written (an
/// error of kind [`rollfit_io::ErrorKind::System`]) is `OSError`, a file
/// whose content is wrong `ValueError`; both with the CLI's text.
pub fn io_error(error: &rollfit_io::IoError) -> PyErr {
    let text = rollfit_io::chain(error);
    match error.kind() {
        rollfit_io::ErrorKind::System => PyOSError::new_err(text),
        _ => PyValueError::new_err(text),
    }
}

/// The values of a 1-D array argument, copied (the array may change while
/// the GIL is released).
pub fn floats(array: &Floats<'_>) -> PyResult<Vec<f64>> {
    Ok(array.0.as_array().iter().copied().collect())
}

/// The speeds of argument `name` (m/s), each checked as the data reader
/// and a scene's `[sweep]` check them (`rollfit_fit::data::column_requirement`,
/// 1e-15 … 1000 m/s, finite).
pub fn speeds(name: &str, array: &Floats<'_>) -> PyResult<Vec<f64>> {
    let values = floats(array)?;
    for (i, &v) in values.iter().enumerate() {
        if let Some(requirement) = rollfit_fit::data::column_requirement("v", v) {
            return Err(value_error_text(format!("{name}[{i}] = {v:e}: {requirement}")));
        }
    }
    Ok(values)
}

/// A float64 NumPy array.
pub fn array<'py>(py: Python<'py>, values: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_vec(py, values)
}

/// A complex128 NumPy array.
pub fn complex_array<'py>(
    py: Python<'py>,
    values: Vec<Complex64>,
) -> Bound<'py, PyArray1<Complex64>> {
    PyArray1::from_vec(py, values)
}

/// JSON bytes as Python objects (`json.loads`): dicts, lists, floats that
/// are the written f64 exactly (the text is the shortest round-trip form).
pub fn json_to_python<'py>(py: Python<'py>, bytes: &[u8]) -> PyResult<Bound<'py, PyAny>> {
    let text = std::str::from_utf8(bytes).map_err(|e| value_error(&e))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// E*(ω) of `modulus` at each ω of `omega` (rad/s), as a complex array (Pa):
/// what every `.modulus(omega)` of the module returns.
pub fn modulus_at<'py>(
    py: Python<'py>,
    omega: &Floats<'py>,
    modulus: impl Fn(f64) -> Complex64,
) -> PyResult<Bound<'py, PyArray1<Complex64>>> {
    let omega = floats(omega)?;
    Ok(complex_array(
        py,
        omega.iter().map(|&w| modulus(w)).collect(),
    ))
}

/// tan δ = E″/E′ of `modulus` at each ω of `omega` (rad/s): what every
/// `.tan_delta(omega)` of the module returns.
pub fn tan_delta_at<'py>(
    py: Python<'py>,
    omega: &Floats<'py>,
    modulus: impl Fn(f64) -> Complex64,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let omega = floats(omega)?;
    Ok(array(
        py,
        omega
            .iter()
            .map(|&w| rollfit_model::modulus::tan_delta(modulus(w)))
            .collect(),
    ))
}
