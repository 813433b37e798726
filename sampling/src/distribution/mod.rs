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

/// Whether `x` is positive and finite: a density a sample can be divided by, or a distance
/// a ray can travel. Written on the bits (positive subnormals to f32::MAX are the bit
/// patterns 1..=0x7f7f_ffff) because LLVM turns `x > 0.0 && x.is_finite()` into a
/// floating-point class test, which baseline x86-64 lowers to some twenty integer
/// instructions; this is two.
#[inline]
pub fn positive_finite(x: f32) -> bool {
    x.to_bits().wrapping_sub(1) < 0x7f7f_ffff
}

/// The largest f64 below 1.
pub const ONE_MINUS_EPSILON: f64 = 1.0 - f64::EPSILON / 2.0;

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::positive_finite;

    #[test]
    fn positive_finite_at_the_edges() {
        for x in [f32::MIN_POSITIVE, 1e-45, 1.0, f32::MAX] {
            assert!(positive_finite(x), "{x:e}");
        }
        for x in [
            0.0,
            -0.0,
            -1e-45,
            -1.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ] {
            assert!(!positive_finite(x), "{x:e}");
        }
        assert!(!positive_finite(-f32::NAN));
    }

    proptest! {
        /// Every bit pattern: the same answer as the comparisons it replaces.
        #[test]
        fn positive_finite_is_the_comparison(bits in any::<u32>()) {
            let x = f32::from_bits(bits);
            prop_assert_eq!(positive_finite(x), x > 0.0 && x.is_finite());
        }
    }
}
