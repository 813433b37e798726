//! `prism.Spectrum`: a spectrum of the scene format (named, tabulated, or an upsampled
//! colour), evaluated at numpy arrays of wavelengths, integrated to XYZ, and exchanged with
//! colour-science's `SpectralDistribution`.

use std::sync::Arc;

use numpy::{IntoPyArray, PyArrayDyn};
use prism_spectrum::Spectrum as _;
use prism_spectrum::colorimetry::{Observer, emission_xyz};
use prism_spectrum::spectra::{Extrapolation, NamedSpectrum, PiecewiseLinear};
use prism_upsample::RgbSpectrum;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyString;

use crate::arrays::f64_array;

/// What a `prism.Spectrum` holds.
#[derive(Clone)]
pub enum Kind {
    Named(NamedSpectrum),
    Table(PiecewiseLinear),
    Rgb(RgbSpectrum),
}

impl Kind {
    fn evaluate(&self, nm: f64) -> f64 {
        match self {
            Kind::Named(s) => s.evaluate(nm),
            Kind::Table(s) => s.evaluate(nm),
            Kind::Rgb(s) => s.evaluate(nm),
        }
    }
}

impl prism_spectrum::Spectrum for Kind {
    fn evaluate(&self, lambda_nm: f64) -> f64 {
        Kind::evaluate(self, lambda_nm)
    }
    fn max_value(&self) -> f64 {
        match self {
            Kind::Named(s) => s.max_value(),
            Kind::Table(s) => s.max_value(),
            Kind::Rgb(s) => s.max_value(),
        }
    }
}

/// A spectrum: values per wavelength in nanometres.
///
/// Make one with `Spectrum.named("illuminant:D65")` (every named form of the scene format),
/// `Spectrum.from_samples(wavelengths, values)` (piecewise linear, zero outside), or
/// `prism.upsample_spectrum(rgb)`. Call it with wavelengths to evaluate it.
#[pyclass(module = "prism", frozen)]
#[derive(Clone)]
pub struct Spectrum {
    pub kind: Arc<Kind>,
    description: String,
}

impl Spectrum {
    /// What the spectrum is: a named spectrum's name, or a short description.
    pub fn description(&self) -> &str {
        &self.description
    }

    pub fn new(kind: Kind, description: String) -> Self {
        Self {
            kind: Arc::new(kind),
            description,
        }
    }
}

fn observer_of(name: &str) -> PyResult<Observer> {
    Observer::from_name(name).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// `value` as a spectrum: a `prism.Spectrum`, a named spectrum's string, or anything with
/// `.wavelengths` and `.values` (a colour-science `SpectralDistribution`).
pub fn as_spectrum(value: &Bound<'_, PyAny>) -> PyResult<Spectrum> {
    if let Ok(s) = value.extract::<Spectrum>() {
        return Ok(s);
    }
    if value.is_instance_of::<PyString>() {
        return Spectrum::named(&value.extract::<String>()?);
    }
    if let (Ok(w), Ok(v)) = (value.getattr("wavelengths"), value.getattr("values")) {
        return Spectrum::from_samples(&w, &v);
    }
    Err(PyValueError::new_err(format!(
        "expected a prism.Spectrum, a named spectrum or an object with .wavelengths and .values, got {}",
        value.get_type().name()?
    )))
}

#[pymethods]
impl Spectrum {
    /// `Spectrum(value)`: a named spectrum's string, a `prism.Spectrum`, or anything with
    /// `.wavelengths` and `.values` (a colour-science `SpectralDistribution`).
    #[new]
    fn py_new(value: &Bound<'_, PyAny>) -> PyResult<Self> {
        as_spectrum(value)
    }

    /// A named spectrum of the scene format: `blackbody:T`, `illuminant:NAME`,
    /// `daylight:CCT`, ... (a ValueError lists the forms).
    #[staticmethod]
    pub fn named(name: &str) -> PyResult<Self> {
        let s = NamedSpectrum::parse(name).map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(Self::new(Kind::Named(s), name.to_string()))
    }

    /// A piecewise-linear spectrum through (wavelengths[i], values[i]), nm, increasing
    /// wavelengths, zero outside them.
    #[staticmethod]
    pub fn from_samples(
        wavelengths: &Bound<'_, PyAny>,
        values: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let w = f64_array(wavelengths, "wavelengths")?;
        let v = f64_array(values, "values")?;
        if w.ndim() != 1 || v.ndim() != 1 {
            return Err(PyValueError::new_err(format!(
                "wavelengths and values must be one-dimensional (shapes {:?} and {:?})",
                w.shape(),
                v.shape()
            )));
        }
        let n = w.len();
        let table = PiecewiseLinear::new(
            w.into_raw_vec_and_offset().0,
            v.into_raw_vec_and_offset().0,
            Extrapolation::Zero,
        )
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(Self::new(Kind::Table(table), format!("{n} samples")))
    }

    /// A spectrum from anything with `.wavelengths` and `.values` (a colour-science
    /// `SpectralDistribution`).
    #[staticmethod]
    pub fn from_colour(distribution: &Bound<'_, PyAny>) -> PyResult<Self> {
        Self::from_samples(
            &distribution.getattr("wavelengths")?,
            &distribution.getattr("values")?,
        )
    }

    /// The values at `wavelengths` (nm; a number or an array of any shape): an array of
    /// the same shape.
    fn __call__<'py>(
        &self,
        py: Python<'py>,
        wavelengths: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        let w = f64_array(wavelengths, "wavelengths")?;
        let kind = self.kind.clone();
        let out = py.detach(move || w.mapv(|nm| kind.evaluate(nm)));
        Ok(out.into_pyarray(py))
    }

    /// The CIE XYZ of this spectrum as an emission (sum over 1 nm of the spectrum times the
    /// colour-matching functions of `observer`: cie1931 or cie1964).
    #[pyo3(signature = (observer = "cie1931"))]
    fn to_xyz(&self, observer: &str) -> PyResult<(f64, f64, f64)> {
        let [x, y, z] = emission_xyz(self.kind.as_ref(), observer_of(observer)?).to_array();
        Ok((x, y, z))
    }

    /// A colour-science `SpectralDistribution` of this spectrum from 360 to 830 nm in 1 nm
    /// steps (needs colour-science installed).
    fn to_colour<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let colour = py.import("colour")?;
        let wavelengths: Vec<f64> = (360..=830).map(f64::from).collect();
        let values: Vec<f64> = wavelengths
            .iter()
            .map(|&nm| self.kind.evaluate(nm))
            .collect();
        let numpy = py.import("numpy")?;
        let domain = numpy.call_method1("asarray", (wavelengths,))?;
        let data = numpy.call_method1("asarray", (values,))?;
        let kwargs = pyo3::types::PyDict::new(py);
        kwargs.set_item("domain", domain)?;
        kwargs.set_item("name", &self.description)?;
        colour
            .getattr("SpectralDistribution")?
            .call((data,), Some(&kwargs))
    }

    fn __repr__(&self) -> String {
        format!("Spectrum({})", self.description)
    }
}
