//! Wavelength sampling: which wavelengths a path carries and with what density.
//!
//! A [`WavelengthDistribution`] is a density p(lambda) over a [`WavelengthRange`]; a
//! [`WavelengthPackage`] is what a path carries: `C` wavelengths drawn from it by one of
//! the [`PackageScheme`]s of hero wavelength sampling (Wilkie, Nawaz, Droske, Weidlich and
//! Hanika, "Hero wavelength spectral sampling", CGF 33(4), 2014), with the per-lane
//! density that makes `(1/C) sum_j L(lambda_j) / pdf_j` the balance-heuristic estimator.

mod distribution;
mod package;
mod range;
mod reradiation;

pub use distribution::{VISIBLE_CENTER_NM, VISIBLE_SHARPNESS, WavelengthDistribution};
pub use package::{MAX_PACKAGE_SIZE, PackageScheme, WavelengthPackage, spectral_mis_weights};
pub use range::WavelengthRange;
pub use reradiation::{ReradiationSample, ReradiationSampler};
