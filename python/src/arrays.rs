//! numpy arrays in and out: any array-like (lists, any dtype numpy can cast to float64,
//! any strides) becomes a float64 array; results are new float64 arrays.

use numpy::ndarray::{ArrayD, IxDyn};
use numpy::{IntoPyArray, PyArrayDyn, PyReadonlyArrayDyn};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// `value` as a float64 array (numpy.asarray(value, dtype=float64)), owned.
pub fn f64_array(value: &Bound<'_, PyAny>, what: &str) -> PyResult<ArrayD<f64>> {
    let numpy = value.py().import("numpy")?;
    let float64 = numpy.getattr("float64")?;
    let array = numpy
        .call_method1("asarray", (value, float64))
        .map_err(|e| PyValueError::new_err(format!("{what}: not an array of numbers ({e})")))?;
    let array: PyReadonlyArrayDyn<f64> = array.extract()?;
    Ok(array.as_array().to_owned())
}

/// An (..., 3) array as rows of three, and the leading shape; a ValueError otherwise.
pub fn triples(value: &Bound<'_, PyAny>, what: &str) -> PyResult<(Vec<[f64; 3]>, Vec<usize>)> {
    let array = f64_array(value, what)?;
    let shape = array.shape().to_vec();
    if shape.last() != Some(&3) {
        return Err(PyValueError::new_err(format!(
            "{what}: expected an array of shape (..., 3), got {shape:?}"
        )));
    }
    let rows = array
        .as_standard_layout()
        .as_slice()
        .unwrap_or_default()
        .chunks_exact(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    Ok((rows, shape[..shape.len() - 1].to_vec()))
}

/// Rows of `width` values as an array of shape `leading` + (width,).
pub fn rows_to_array<'py>(
    py: Python<'py>,
    rows: Vec<f64>,
    leading: &[usize],
    width: usize,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let mut shape = leading.to_vec();
    shape.push(width);
    let array = ArrayD::from_shape_vec(IxDyn(&shape), rows)
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(array.into_pyarray(py))
}
