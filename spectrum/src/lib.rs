#![doc = include_str!("../README.md")]
//!
//! ## In detail
//!
//! Spectra and colorimetry for spectral rendering, usable on its own: the leaf crate of
//! [prism](https://github.com/prism-render/prism), with no dependencies.
//!
//! ## What is here
//! - [`Spectrum`]: a function of wavelength (nm), with representations in [`spectra`]:
//!   [`spectra::Constant`], [`spectra::PiecewiseLinear`] (irregular tables, CSV),
//!   [`spectra::DenselySampled`] (1 nm), [`spectra::Gaussian`], [`spectra::Blackbody`]
//!   (Planck's law, absolute or peak-normalized).
//! - [`SampledWavelengths`] and [`SampledSpectrum`]: what a path carries, `N` wavelengths
//!   with their densities and one value per lane; a sampled spectrum becomes colour only
//!   together with its wavelengths ([`SampledSpectrum::to_xyz`]).
//! - [`colorimetry`]: CIE 1931 and 1964 observers, XYZ of emission and of reflectance,
//!   xy and uv, CIELAB, CIEDE2000, CCT (Ohno 2013).
//! - [`illuminant`]: CIE A, D50, D55, D65, D75, E, F1-F12 and daylight at any CCT.
//! - [`color`]: RGB colour spaces defined by primaries and white (sRGB, Rec.709, Display
//!   P3, DCI-P3, Rec.2020, ACES2065-1, ACEScg, ProPhoto, Adobe RGB, or your own),
//!   chromatic adaptation (Bradford, CAT02, von Kries), transfer functions, tone mapping.
//! - [`optics`]: photon energy, photometry, Sellmeier and Cauchy indices, Abbe numbers as
//!   glTF `KHR_materials_dispersion` defines them, a glass catalogue, measured metals.
//!
//! ## Where things are
//!
//! Spectra and colorimetry: CIE observers and illuminants (embedded tables with
//! provenance), blackbody, XYZ, xy/uv, CIELAB, CIEDE2000, CCT, RGB colour spaces, chromatic
//! adaptation, transfer functions, tone mapping, photon energy, photometry, IOR models,
//! glass and metal catalogues.
//!
//! Key types: `Spectrum`, `SampledWavelengths<N>`, `SampledSpectrum<N>`, `PiecewiseLinear`,
//! `Blackbody`, `Observer`, `Xyz`, `Lab`, `RgbColorSpace`, `Sellmeier`, `ComplexIor`.
//!
//! ## Why it is designed so
//! - **`f64` for colorimetry, `f32` lanes for rendering.** [`Spectrum::evaluate`] works in
//!   `f64` so that chromaticities match independent references to 1e-5 and better;
//!   [`Spectrum::sample`] hands the renderer `f32` lanes.
//! - **Every integral is the same sum.** Tristimulus values are sums over the 1 nm grid
//!   360-830 nm of the CIE tables; coarser tables are interpolated linearly and are zero
//!   outside their range. Tests hold the crate to colour-science computed with the same
//!   convention, so a difference is a bug, not a convention.
//! - **Errors, not NaN.** Constructors validate (a negative temperature, an unsorted table,
//!   a Sellmeier pole inside its range, collinear primaries are errors), and every
//!   evaluation returns a finite number for every input, which property tests check at
//!   zero, subnormals, huge values and range ends.
//! - **Data lives with provenance.** Tables are generated from their sources by
//!   `tools/generate_tables_and_fixtures.py` and listed in `data/PROVENANCE.md`; tests
//!   prove the embedded tables equal the source.
//!
//! ## References
//! - CIE 015:2018, *Colorimetry*, 4th ed.: §7 (tristimulus values), §8.2 (CIELAB), §9
//!   (CCT), §4.1 (daylight), Tables 1-2, 5, 6, 10.
//! - G. Sharma, W. Wu, E. N. Dalal, Color Res. Appl. 30(1), 21-30, 2005 (CIEDE2000).
//! - Y. Ohno, "Practical use and calculation of CCT and Duv", LEUKOS 10(1), 2014, §3.
//! - SMPTE RP 177-1993 §3.3 (normalized primary matrix).
//! - M. Pharr, W. Jakob, G. Humphreys, *Physically Based Rendering*, 4th ed., §4.4-4.6
//!   (blackbodies, sampled spectra, colour).
//! - Khronos, `KHR_materials_dispersion` (Abbe number to Cauchy).
//!
//! ## Example
//! ```
//! use prism_spectrum::colorimetry::{luminous_xyz_normalized, Observer};
//! use prism_spectrum::spectra::Blackbody;
//!
//! let body = Blackbody::normalized(6504.0)?;
//! let xy = luminous_xyz_normalized(&body, Observer::Cie1931)?.chromaticity()?;
//! assert!((xy.x - 0.3135).abs() < 1e-3);
//! # Ok::<(), prism_spectrum::SpectrumError>(())
//! ```

pub mod color;
pub mod colorimetry;
pub mod constants;
mod data;
mod error;
pub mod illuminant;
pub mod optics;
mod sampled;
pub mod spectra;
mod spectrum;

pub use error::{Readable, SpectrumError};
pub use sampled::{SampledSpectrum, SampledWavelengths, saturating_f32};
pub use spectrum::Spectrum;

#[doc(hidden)]
/// Raw embedded tables, exposed only so the integration tests can compare them with their
/// source; not part of the public API.
pub mod __tables {
    pub use crate::data::*;
}
