//! # prism-upsample
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
//!
//! ## Why it is designed so
//! - **Fit in normalized wavelength.** The optimizer works with t = (l - 360) / 470, where
//!   the three coefficients have similar magnitudes and the normal equations are well
//!   conditioned; coefficients are converted to nanometres only at the end.
//! - **Exact where exactness is possible.** Black is the zero spectrum and greys are
//!   constants by construction, not by a fit that happens to come close.
//!
//! Not yet here (see the issue tracker): precomputed coefficient tables in the paper's
//! layout, their file format, trilinear and refined lookups, and the measured comparison
//! with rgb2spec.
//!
//! ## References
//! - W. Jakob, J. Hanika, CGF 38(2), 2019, §3 (model), §4 (optimization), §5 (tables).
//! - M. Pharr, W. Jakob, G. Humphreys, *PBR* 4th ed., §4.6.6 (RGB spectra kinds).

pub mod error;
mod fit;
mod model;
mod rgb;
pub mod sigmoid;
mod table;

pub use error::UpsampleError;
pub use fit::{Fit, FitContext, denormalize};
pub use model::{SigmoidPolynomial, inverse_sigmoid};
pub use rgb::{RgbKind, RgbSpectrum, normalized_illuminant};
pub use table::{CoefficientTable, FitStatistics};
mod table_file;
pub use table::TableSpace;
pub use table_file::FORMAT_VERSION;
