//! RGB to spectra (Jakob and Hanika 2019's sigmoid polynomials), vectorized in Rust over
//! arrays of colours with the GIL released.

use std::sync::Arc;

use numpy::PyArrayDyn;
use prism_upsample::{
    CoefficientTable, FitContext, RgbKind, RgbSpectrum, UpsampleError, normalized_illuminant,
};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rayon::prelude::*;

use crate::arrays::{rows_to_array, triples};
use crate::colour::space_of;
use crate::spectrum::{Kind, Spectrum};

/// How an RGB colour is read, and how it is fitted.
struct Upsampler {
    context: FitContext,
    kind: RgbKind,
    illuminant: Option<Arc<prism_spectrum::spectra::DenselySampled>>,
    table: Option<Arc<CoefficientTable>>,
}

impl Upsampler {
    fn new(space: &str, kind: &str, method: &str) -> PyResult<Self> {
        let id = space_of(space)?;
        let error = |e: UpsampleError| PyValueError::new_err(e.to_string());
        let context = FitContext::new(id.space(), &id.illuminant()).map_err(error)?;
        let kind = match kind {
            "reflectance" | "albedo" => RgbKind::Albedo,
            "unbounded" => RgbKind::Unbounded,
            "illuminant" | "emission" => RgbKind::Illuminant,
            other => {
                return Err(PyValueError::new_err(format!(
                    "kind '{other}': expected reflectance, unbounded or illuminant"
                )));
            }
        };
        let illuminant = match kind {
            RgbKind::Illuminant => Some(normalized_illuminant(&id.illuminant()).map_err(error)?),
            _ => None,
        };
        let table = match method {
            "exact" => None,
            "table" => Some(CoefficientTable::shipped(id).ok_or_else(|| {
                PyValueError::new_err(format!(
                    "method 'table': no coefficient table ships for '{}' (use method='exact')",
                    id.name()
                ))
            })?),
            other => {
                return Err(PyValueError::new_err(format!(
                    "method '{other}': expected exact or table"
                )));
            }
        };
        Ok(Self {
            context,
            kind,
            illuminant,
            table,
        })
    }

    fn fit(&self, rgb: [f64; 3]) -> Result<RgbSpectrum, UpsampleError> {
        match &self.table {
            None => RgbSpectrum::fit(&self.context, rgb, self.kind, self.illuminant.clone()),
            Some(table) => RgbSpectrum::from_table(
                table,
                &self.context,
                rgb,
                self.kind,
                self.illuminant.clone(),
                0,
            ),
        }
    }
}

/// The coefficients of `spectrum`'s sigmoid polynomial (-inf or inf in c2 for black or
/// white, where no polynomial is needed), then its scale.
fn coefficients(spectrum: &RgbSpectrum) -> [f64; 4] {
    let [c0, c1, c2] = match spectrum.shape() {
        Some(shape) => shape.coefficients,
        None => [0.0, 0.0, f64::NEG_INFINITY],
    };
    [c0, c1, c2, spectrum.scale()]
}

/// Sigmoid-polynomial coefficients (c0, c1, c2: f(l) = S(c0 l^2 + c1 l + c2), l in nm) for
/// an array of linear RGB colours of shape (..., 3). `kind` is reflectance (the default:
/// values in [0, 1]), unbounded or illuminant; those two return (..., 4), the fourth
/// value the scale the sigmoid is multiplied by. `method` is exact (a fit per colour) or
/// table (the shipped table's lookup, sRGB only). A colour that is not one (NaN, negative
/// reflectance...) is a ValueError naming it.
#[pyfunction]
#[pyo3(signature = (rgb, space = "srgb", kind = "reflectance", method = "exact"))]
pub fn upsample<'py>(
    py: Python<'py>,
    rgb: &Bound<'py, PyAny>,
    space: &str,
    kind: &str,
    method: &str,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let upsampler = Upsampler::new(space, kind, method)?;
    let (rows, leading) = triples(rgb, "rgb")?;
    let width = if upsampler.kind == RgbKind::Albedo {
        3
    } else {
        4
    };
    let fitted: Result<Vec<[f64; 4]>, String> = py.detach(|| {
        rows.par_iter()
            .map(|&c| {
                upsampler
                    .fit(c)
                    .map(|s| coefficients(&s))
                    .map_err(|e| format!("rgb {c:?}: {e}"))
            })
            .collect()
    });
    let fitted = fitted.map_err(PyValueError::new_err)?;
    let flat = fitted.iter().flat_map(|c| c[..width].to_vec()).collect();
    rows_to_array(py, flat, &leading, width)
}

/// One RGB colour as a `prism.Spectrum` (see `upsample` for `space`, `kind`, `method`).
#[pyfunction]
#[pyo3(signature = (rgb, space = "srgb", kind = "reflectance", method = "exact"))]
pub fn upsample_spectrum(
    rgb: &Bound<'_, PyAny>,
    space: &str,
    kind: &str,
    method: &str,
) -> PyResult<Spectrum> {
    let upsampler = Upsampler::new(space, kind, method)?;
    let (rows, leading) = triples(rgb, "rgb")?;
    if !leading.is_empty() {
        return Err(PyValueError::new_err(format!(
            "upsample_spectrum takes one colour of shape (3,), got {:?} (use upsample for arrays)",
            [leading, vec![3]].concat()
        )));
    }
    let c = rows[0];
    let spectrum = upsampler
        .fit(c)
        .map_err(|e| PyValueError::new_err(format!("rgb {c:?}: {e}")))?;
    Ok(Spectrum::new(
        Kind::Rgb(spectrum),
        format!("{kind} rgb({}, {}, {}) in {space}", c[0], c[1], c[2]),
    ))
}
