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

/// A density of a sampled value narrowed to f32 for the render hot path. A positive f64
/// density never becomes 0 (which would make the sample unusable): values below f32's
/// smallest normal number (1.2e-38) are raised to it. Such densities belong to events of
/// probability below ~1e-30, so the bias this introduces is of that order.
pub fn density_f32(pdf: f64) -> f32 {
    if pdf > 0.0 {
        (pdf as f32).clamp(f32::MIN_POSITIVE, f32::MAX)
    } else {
        0.0
    }
}

/// The largest f64 below 1.
pub const ONE_MINUS_EPSILON: f64 = 1.0 - f64::EPSILON / 2.0;
