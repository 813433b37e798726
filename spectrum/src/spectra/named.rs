//! Spectra named in text, the one syntax the command line and scene descriptions share:
//! `blackbody:T`, `illuminant:NAME`, `daylight:CCT`, `gaussian:CENTER_NM:FWHM_NM`,
//! `constant:V`.

use crate::Spectrum;
use crate::error::SpectrumError;
use crate::illuminant::{StandardIlluminant, daylight};
use crate::spectra::{Blackbody, Constant, Gaussian, PiecewiseLinear};

/// The forms [`NamedSpectrum::parse`] accepts, for error messages and help.
pub const NAMED_SPECTRUM_FORMS: &str = "blackbody:T, illuminant:NAME, daylight:CCT, \
gaussian:CENTER_NM:FWHM_NM, constant:V";

/// A spectrum given by name. Blackbodies are peak-normalized (a named spectrum gives a
/// shape; its scale is the caller's), Gaussians have peak 1.
#[derive(Debug, Clone, PartialEq)]
pub enum NamedSpectrum {
    /// `blackbody:T`, Planck's law at T kelvin with peak 1.
    Blackbody(Blackbody),
    /// `illuminant:NAME` (CIE tables) or `daylight:CCT` (CIE daylight model).
    Table(PiecewiseLinear),
    /// `gaussian:CENTER_NM:FWHM_NM` with peak 1: narrow-band sources such as LEDs.
    Gaussian(Gaussian),
    /// `constant:V`.
    Constant(Constant),
}

impl NamedSpectrum {
    /// Whether `text` is written in one of the named forms (a known `kind:` prefix), so a
    /// caller can tell a malformed name from, say, a file path.
    pub fn is_named(text: &str) -> bool {
        text.split_once(':').is_some_and(|(kind, _)| {
            matches!(
                kind.to_ascii_lowercase().as_str(),
                "blackbody" | "illuminant" | "daylight" | "gaussian" | "constant"
            )
        })
    }

    /// Parses one of [`NAMED_SPECTRUM_FORMS`]. Errors name the input and what was
    /// expected.
    pub fn parse(text: &str) -> Result<Self, SpectrumError> {
        let malformed = |why: String| SpectrumError::InvalidTable(format!("'{text}': {why}"));
        let number = |part: &str, what: &str| -> Result<f64, SpectrumError> {
            part.trim()
                .parse::<f64>()
                .map_err(|_| malformed(format!("{what} '{part}' is not a number")))
        };
        let Some((kind, rest)) = text.split_once(':') else {
            return Err(malformed(format!("expected {NAMED_SPECTRUM_FORMS}")));
        };
        match kind.to_ascii_lowercase().as_str() {
            "blackbody" => Ok(Self::Blackbody(Blackbody::normalized(number(
                rest,
                "temperature",
            )?)?)),
            "illuminant" => Ok(Self::Table(StandardIlluminant::from_name(rest)?.spectrum())),
            "daylight" => Ok(Self::Table(daylight(number(rest, "CCT")?)?)),
            "gaussian" => {
                let (center, fwhm) = rest
                    .split_once(':')
                    .ok_or_else(|| malformed("expected gaussian:CENTER_NM:FWHM_NM".into()))?;
                Ok(Self::Gaussian(Gaussian::new(
                    number(center, "centre")?,
                    number(fwhm, "FWHM")?,
                    1.0,
                )?))
            }
            "constant" => Ok(Self::Constant(Constant::new(number(rest, "value")?)?)),
            _ => Err(malformed(format!(
                "unknown kind '{kind}' (expected {NAMED_SPECTRUM_FORMS})"
            ))),
        }
    }
}

impl Spectrum for NamedSpectrum {
    fn evaluate(&self, lambda_nm: f64) -> f64 {
        match self {
            Self::Blackbody(s) => s.evaluate(lambda_nm),
            Self::Table(s) => s.evaluate(lambda_nm),
            Self::Gaussian(s) => s.evaluate(lambda_nm),
            Self::Constant(s) => s.evaluate(lambda_nm),
        }
    }

    fn max_value(&self) -> f64 {
        match self {
            Self::Blackbody(s) => s.max_value(),
            Self::Table(s) => s.max_value(),
            Self::Gaussian(s) => s.max_value(),
            Self::Constant(s) => s.max_value(),
        }
    }
}
