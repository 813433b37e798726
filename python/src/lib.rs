//! `prism` for Python: spectra evaluated on numpy arrays, colour conversions, RGB
//! upsampling vectorized in Rust, and renders of glTF scenes through the command line's own
//! code (`prism_cli`), so that an image from Python is the command line's to the bit.
//!
//! The Python side (`python/python/prism/`) re-exports this module `prism._prism` with type
//! stubs. Errors become Python exceptions with the crates' one-line messages:
//! `ValueError` for bad arguments, `prism.SceneError` for scenes that cannot be loaded or
//! rendered; a panic inside Rust becomes pyo3's `PanicException`, never a crash.

mod arrays;
mod colour;
mod render;
mod scene;
mod spectrum;
mod upsample;

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    prism,
    SceneError,
    PyException,
    "A scene that cannot be loaded or rendered (the message names the file and the reason)."
);

/// The native part of the `prism` package.
#[pymodule]
fn _prism(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SceneError", m.py().get_type::<SceneError>())?;
    m.add_class::<spectrum::Spectrum>()?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<render::Render>()?;
    m.add_function(wrap_pyfunction!(colour::xyz_to_rgb, m)?)?;
    m.add_function(wrap_pyfunction!(colour::rgb_to_xyz, m)?)?;
    m.add_function(wrap_pyfunction!(colour::spaces, m)?)?;
    m.add_function(wrap_pyfunction!(upsample::upsample, m)?)?;
    m.add_function(wrap_pyfunction!(upsample::upsample_spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(scene::load, m)?)?;
    m.add_function(wrap_pyfunction!(scene::load_mitsuba_xml, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(render::render, m)?)?;
    Ok(())
}
