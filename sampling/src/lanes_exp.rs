//! exp of an f32, written so that LLVM vectorizes loops over lanes that call it.
//!
//! The visible-wavelength density needs one exponential per lane per path; libm's f64 exp
//! is a call per lane that LLVM cannot vectorize (measured: sampling packages of 8
//! wavelengths with it was a noticeable share of the Cornell box's instructions). This is
//! the classic Cody-Waite construction (as in Cephes' `expf`): x = n ln 2 + r with |r| <=
//! ln 2 / 2, exp(r) by its degree-6 Taylor polynomial (truncation error below 2e-8
//! relative), and 2^n built from the exponent bits. Every step is branch-free arithmetic on
//! each lane.

/// ln 2 split so that `n * LN2_HI` is exact for |n| < 2^9 (its low mantissa bits are zero).
const LN2_HI: f32 = 0.693_359_4;
const LN2_LO: f32 = -2.121_944_4e-4;
/// 1.5 * 2^23: adding it leaves no fraction bits, so the sum is rounded to an integer.
const ROUNDING: f32 = 12_582_912.0;

/// exp of `x`, to within 3e-7 relative (measured against f64 in the tests), for inputs
/// in [-87, 88]; inputs beyond are clamped to that range (so the result stays a normal,
/// finite f32), and NaN gives NaN.
#[inline(always)]
pub(crate) fn exp_lane(x: f32) -> f32 {
    let x = x.clamp(-87.0, 88.0);
    // Round to nearest by adding and removing 1.5 * 2^23 (exact for |y| < 2^22):
    // `f32::round` is a libm call without SSE4.1, and would stop vectorization.
    let shifted = x * std::f32::consts::LOG2_E + ROUNDING;
    let n = shifted - ROUNDING;
    let r = (x - n * LN2_HI) - n * LN2_LO;
    let p = 1.0
        + r * (1.0
            + r * (1.0 / 2.0
                + r * (1.0 / 6.0 + r * (1.0 / 24.0 + r * (1.0 / 120.0 + r * (1.0 / 720.0))))));
    // n is in [-126, 127] here, so n + 127 is a valid biased exponent. n is read off
    // the low bits of the shifted sum (1.5 * 2^23 + n is 0x4b40_0000 + n) rather than
    // by `n as i32`, whose saturating conversion kept LLVM from vectorizing the lanes.
    // A NaN lane keeps its NaN through p.
    let n_bits = shifted.to_bits().wrapping_sub(ROUNDING.to_bits());
    let scale = f32::from_bits(n_bits.wrapping_add(127) << 23);
    p * scale
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::exp_lane;

    fn relative_error(x: f32) -> f64 {
        let exact = f64::from(x).exp();
        (f64::from(exp_lane(x)) - exact).abs() / exact
    }

    #[test]
    fn matches_f64_exp_over_the_range() {
        let worst = (0..=350_000)
            .map(|i| -87.0 + i as f32 * 175.0 / 350_000.0)
            .map(relative_error)
            .fold(0.0, f64::max);
        assert!(worst < 3e-7, "worst relative error {worst:e}");
        assert_eq!(exp_lane(0.0), 1.0);
    }

    proptest! {
        /// Any input: finite and positive (NaN only from NaN), and clamped beyond the
        /// range.
        #[test]
        fn total(x in prop_oneof![any::<f32>(), Just(f32::INFINITY), Just(f32::NEG_INFINITY), Just(-0.0f32), Just(1e-45f32)]) {
            let y = exp_lane(x);
            if x.is_nan() {
                prop_assert!(y.is_nan());
            } else {
                prop_assert!(y.is_finite() && y > 0.0, "exp({}) = {}", x, y);
                let clamped = x.clamp(-87.0, 88.0);
                prop_assert!(relative_error(clamped) < 3e-7);
            }
        }
    }
}
