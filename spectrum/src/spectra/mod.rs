//! Concrete spectrum representations.

mod blackbody;
mod constant;
mod dense;
mod gaussian;
mod named;
mod piecewise_linear;

pub use blackbody::{Blackbody, Normalization, planck_radiance};
pub use constant::Constant;
pub use dense::DenselySampled;
pub use gaussian::Gaussian;
pub use named::{NAMED_SPECTRUM_FORMS, NamedSpectrum};
pub use piecewise_linear::{Extrapolation, PiecewiseLinear};
