//! Colour conversions between CIE XYZ and the linear RGB spaces prism knows.

use numpy::PyArrayDyn;
use prism_spectrum::color::RgbSpaceId;
use prism_spectrum::colorimetry::Xyz;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::arrays::{rows_to_array, triples};

/// The RGB space named `name`, or a ValueError listing the names.
pub fn space_of(name: &str) -> PyResult<RgbSpaceId> {
    RgbSpaceId::from_name(name).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// Converts CIE XYZ to linear RGB in `space`, over an array of any shape (..., 3).
#[pyfunction]
#[pyo3(signature = (xyz, space = "srgb"))]
pub fn xyz_to_rgb<'py>(
    py: Python<'py>,
    xyz: &Bound<'py, PyAny>,
    space: &str,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let space = space_of(space)?.space();
    let (rows, leading) = triples(xyz, "xyz")?;
    let out: Vec<f64> = rows
        .into_iter()
        .flat_map(|[x, y, z]| space.xyz_to_rgb(Xyz::new(x, y, z)))
        .collect();
    rows_to_array(py, out, &leading, 3)
}

/// Converts linear RGB in `space` to CIE XYZ, over an array of any shape (..., 3).
#[pyfunction]
#[pyo3(signature = (rgb, space = "srgb"))]
pub fn rgb_to_xyz<'py>(
    py: Python<'py>,
    rgb: &Bound<'py, PyAny>,
    space: &str,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let space = space_of(space)?.space();
    let (rows, leading) = triples(rgb, "rgb")?;
    let out: Vec<f64> = rows
        .into_iter()
        .flat_map(|rgb| space.rgb_to_xyz(rgb).to_array())
        .collect();
    rows_to_array(py, out, &leading, 3)
}

/// The names of the RGB spaces (`space=` everywhere).
#[pyfunction]
pub fn spaces() -> Vec<&'static str> {
    RgbSpaceId::ALL.map(RgbSpaceId::name).to_vec()
}
