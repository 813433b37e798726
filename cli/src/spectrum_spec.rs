//! Parsing of the spectrum descriptions users type on the command line: a named spectrum
//! (prism-spectrum's syntax, shared with scene files) or a CSV file.

use prism_spectrum::Spectrum;
use prism_spectrum::spectra::{
    Extrapolation, NAMED_SPECTRUM_FORMS, NamedSpectrum, PiecewiseLinear,
};

/// Turns a named spectrum (`blackbody:T`, `illuminant:NAME`, ...) or a CSV path into a
/// spectrum. Errors name the input and what was expected.
pub fn parse(spec: &str) -> Result<Box<dyn Spectrum>, String> {
    if NamedSpectrum::is_named(spec) {
        return Ok(Box::new(
            NamedSpectrum::parse(spec).map_err(|e| e.to_string())?,
        ));
    }
    let path = std::path::Path::new(spec);
    if !path.exists() {
        return Err(format!(
            "'{spec}' is neither a spectrum description nor an existing file (expected {NAMED_SPECTRUM_FORMS}, or a two-column CSV file (nm, value))"
        ));
    }
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read '{spec}': {e}"))?;
    let table = PiecewiseLinear::from_csv_str(&text, Extrapolation::Zero)
        .map_err(|e| format!("'{spec}': {e}"))?;
    Ok(Box::new(table))
}
