//! Parsing of the spectrum descriptions users type on the command line.

use prism_spectrum::Spectrum;
use prism_spectrum::illuminant::{StandardIlluminant, daylight};
use prism_spectrum::spectra::{Blackbody, Constant, Extrapolation, Gaussian, PiecewiseLinear};

/// The forms `parse` accepts, for error messages and help.
pub const SPEC_FORMS: &str = "blackbody:T, illuminant:NAME, daylight:CCT, \
gaussian:CENTER_NM:FWHM_NM, constant:V, or a two-column CSV file (nm, value)";

/// Turns `blackbody:T`, `illuminant:NAME`, `daylight:CCT`, `gaussian:C:W`, `constant:V` or
/// a CSV path into a spectrum. Blackbodies are peak-normalized (only their colour matters
/// here). Errors name the input and what was expected.
pub fn parse(spec: &str) -> Result<Box<dyn Spectrum>, String> {
    let number = |text: &str, what: &str| -> Result<f64, String> {
        text.trim()
            .parse::<f64>()
            .map_err(|_| format!("'{spec}': {what} '{text}' is not a number"))
    };
    let with_context = |e: prism_spectrum::SpectrumError| format!("'{spec}': {e}");
    if let Some((kind, rest)) = spec.split_once(':') {
        match kind.to_ascii_lowercase().as_str() {
            "blackbody" => {
                let t = number(rest, "temperature")?;
                return Ok(Box::new(Blackbody::normalized(t).map_err(with_context)?));
            }
            "illuminant" => {
                let ill = StandardIlluminant::from_name(rest).map_err(with_context)?;
                return Ok(Box::new(ill.spectrum()));
            }
            "daylight" => {
                let t = number(rest, "CCT")?;
                return Ok(Box::new(daylight(t).map_err(with_context)?));
            }
            "gaussian" => {
                let (center, fwhm) = rest
                    .split_once(':')
                    .ok_or_else(|| format!("'{spec}': expected gaussian:CENTER_NM:FWHM_NM"))?;
                let g = Gaussian::new(number(center, "centre")?, number(fwhm, "FWHM")?, 1.0)
                    .map_err(with_context)?;
                return Ok(Box::new(g));
            }
            "constant" => {
                let v = number(rest, "value")?;
                return Ok(Box::new(Constant::new(v).map_err(with_context)?));
            }
            _ => {}
        }
    }
    let path = std::path::Path::new(spec);
    if !path.exists() {
        return Err(format!(
            "'{spec}' is neither a spectrum description nor an existing file (expected {SPEC_FORMS})"
        ));
    }
    let text = std::fs::read_to_string(path).map_err(|e| format!("cannot read '{spec}': {e}"))?;
    let table = PiecewiseLinear::from_csv_str(&text, Extrapolation::Zero).map_err(with_context)?;
    Ok(Box::new(table))
}
