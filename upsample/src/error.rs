//! The one error type of this crate.

use std::fmt;

/// Why an RGB colour could not be turned into a spectrum.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum UpsampleError {
    /// A component is NaN or infinite.
    NonFinite([f64; 3]),
    /// A colorimetric computation failed (for example an illuminant without luminance).
    Spectrum(prism_spectrum::SpectrumError),
    /// A table could not be built or read (the message names the problem).
    InvalidTable(String),
}

impl fmt::Display for UpsampleError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            UpsampleError::NonFinite(rgb) => write!(
                f,
                "RGB ({}, {}, {}) has a component that is not finite",
                rgb[0], rgb[1], rgb[2]
            ),
            UpsampleError::Spectrum(e) => e.fmt(f),
            UpsampleError::InvalidTable(msg) => write!(f, "invalid coefficient table: {msg}"),
        }
    }
}

impl std::error::Error for UpsampleError {}

impl From<prism_spectrum::SpectrumError> for UpsampleError {
    fn from(e: prism_spectrum::SpectrumError) -> Self {
        UpsampleError::Spectrum(e)
    }
}
