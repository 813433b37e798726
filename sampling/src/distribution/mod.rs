//! Distributions to sample from tabulated functions.

mod alias;
mod piecewise_constant;
mod piecewise_constant_2d;
mod piecewise_linear;

pub use alias::AliasTable;
pub use piecewise_constant::{PiecewiseConstant1D, Sample1D};
pub use piecewise_constant_2d::{PiecewiseConstant2D, Sample2D};
pub use piecewise_linear::PiecewiseLinear1D;

/// `u` moved into [0, 1): NaN becomes 0, values at or above 1 become the largest f64
/// below 1. Every sampling routine starts here, so no input can index out of range.
pub(crate) fn clamp_unit(u: f64) -> f64 {
    if u.is_nan() || u < 0.0 {
        0.0
    } else {
        u.min(ONE_MINUS_EPSILON)
    }
}

/// The largest f64 below 1.
pub const ONE_MINUS_EPSILON: f64 = 1.0 - f64::EPSILON / 2.0;
