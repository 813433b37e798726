#![doc = include_str!("../README.md")]
//!
//! ## In detail
//!
//! RGB to smooth spectra with the model of W. Jakob and J. Hanika, "A low-dimensional
//! function space for efficient spectral upsampling", Computer Graphics Forum 38(2), 2019:
//! f(l) = S(c0 l^2 + c1 l + c2), S(x) = 1/2 + x / (2 sqrt(1 + x^2)).
//!
//! ## What is here
//! - [`sigmoid`]: S and its derivative, stable for every input (no overflow at |x| > 1e154,
//!   no cancellation for large negative x), in f64 and f32, and a lane form for packages.
//! - [`SigmoidPolynomial`]: the spectrum, implementing `prism_spectrum::Spectrum`.
//! - [`FitContext`]: the exact fitter. Levenberg-Marquardt on the CIELAB residual with an
//!   analytic Jacobian (§4 of the paper minimizes the same objective with a numerical
//!   one), on the CIE 1931 1 nm tables of prism-spectrum.
//! - [`RgbSpectrum`]: albedo, unbounded and illuminant kinds with documented policies for
//!   black, grey, out-of-gamut, above-one and non-finite input.
//! - [`CoefficientTable`]: precomputed tables in the paper's layout (largest channel,
//!   smoothstep-remapped brightness, two ratios), fitted in parallel with warm starts,
//!   with trilinear, batch and refined lookups and a versioned, checksummed file format.
//!
//! ## Where things are
//!
//! RGB to spectrum (Jakob and Hanika 2019): the stable sigmoid, sigmoid-polynomial spectra,
//! the exact fitter, RGB spectrum kinds, coefficient tables (`shipped`: the 32^3 linear
//! sRGB table embedded in the crate, feature `srgb-table`, so sRGB never needs a fit;
//! `table`: fit and single lookups; `table_batch`: batch lookups with four colours in SSE2
//! lanes, bit-identical; `lanes`: the four-float node arithmetic) and their file format.
//!
//! Key types: `SigmoidPolynomial`, `FitContext`, `RgbSpectrum`, `RgbKind`,
//! `CoefficientTable`.
//!
//! ## Why it is designed so
//! - **Fit in normalized wavelength.** The optimizer works with t = (l - 360) / 470, where
//!   the three coefficients have similar magnitudes and the normal equations are well
//!   conditioned; coefficients are converted to nanometres only at the end.
//! - **Exact where exactness is possible.** Black is the zero spectrum and greys are
//!   constants by construction; RGB is taken relative to the illuminant's tabulated white,
//!   so RGB (1, 1, 1) is exactly the perfect reflector.
//! - **A table layout chosen by measurement** (`docs/upsample-accuracy.md`): against
//!   rgb2spec's layout, smoothstep-remapped ratio axes, interpolation in the axis
//!   parameter, and coefficients premultiplied by sqrt(brightness) cut the largest 64^3
//!   error from 0.43 to 0.04 dE2000 at the same size.
//!
//! Default tables are fitted on first use and cached by the command line (`--table auto`;
//! this crate touches no files).
//!
//! ## Speed
//! A lone lookup is a chain of dependent steps about a hundred cycles long, so its time
//! is latency: ~40 ns by criterion (from 80 before its axis inverses were tabulated on the
//! float's exponent bits). [`CoefficientTable::lookup_many`] converts many colours at
//! ~21 ns each, the same spectra bit for bit, by taking four colours through the front of
//! the chain in SSE2 lanes. docs/upsample-accuracy.md has the measurements and what was
//! tried.
//!
//! ## References
//! - W. Jakob, J. Hanika, CGF 38(2), 2019, §3 (model), §4 (optimization), §5 (tables).
//! - M. Pharr, W. Jakob, G. Humphreys, *PBR* 4th ed., §4.6.6 (RGB spectra kinds).

pub mod error;
mod fit;
mod lanes;
mod model;
mod rgb;
pub mod sigmoid;
mod table;
mod table_batch;

pub use error::UpsampleError;
pub use fit::{Fit, FitContext, denormalize, normalize};
pub use model::{SigmoidPolynomial, inverse_sigmoid};
pub use rgb::{RgbKind, RgbSpectrum, normalized_illuminant};
pub use table::{CoefficientTable, FitStatistics};
mod shipped;
mod table_file;
pub use shipped::SHIPPED_RESOLUTION;
pub use table::TableSpace;
pub use table_file::FORMAT_VERSION;
