//! sin, cos, asin and atan2 of an f32, written so that a loop over lanes that calls them
//! vectorizes (as `exp_lane` is for the wavelength density): libm's functions are calls
//! per lane with branches on the argument, which LLVM cannot turn into SIMD instructions,
//! and the warps a path samples with (cosine hemisphere, spherical triangle) call them at
//! every vertex.
//!
//! Each is Cephes' single-precision construction (S. L. Moshier, *Methods and Programs
//! for Mathematical Functions*, 1989; `sinf.c`, `asinf.c`, `atanf.c`): a reduction of the
//! argument to a short interval, a minimax polynomial there, and the reduction undone,
//! with every branch of the original made a select so that all lanes run the same
//! instructions. The result depends only on the argument (no libm, no platform), so
//! images no longer differ by the host's libm either. Accuracy, measured against f64 in
//! the tests: a relative error within 2 (asin: 2.5) f32 epsilons (2^-23), or 2^-24
//! absolute near zeros of sin and cos.

use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// 1.5 * 2^23: adding it to |y| < 2^22 leaves no fraction bits, so the sum is y rounded
/// to an integer (`f32::round` is a libm call without SSE4.1 and stops vectorization).
const ROUNDING: f32 = 12_582_912.0;

/// pi / 2 in three parts whose products with a quadrant count q < 2^15 are exact (the
/// leading parts have few mantissa bits): Cephes' DP1-DP3 for pi / 4, doubled.
const HALF_PI_1: f32 = 1.570_312_5;
const HALF_PI_2: f32 = 4.837_513e-4;
const HALF_PI_3: f32 = 7.549_79e-8;

/// Arguments beyond which the reduction above is no longer exact: sin and cos stay in
/// [-1, 1] but lose accuracy (no path draws angles anywhere near this).
pub const SIN_COS_EXACT_BELOW: f32 = 16_384.0;

/// Larger arguments are reduced as this one (the rounding above needs |y| < 2^22).
const SIN_COS_LARGEST: f32 = 4_194_304.0;

/// (sin x, cos x), each within 2 epsilons relative (or 2^-24 absolute near its zeros) for
/// |x| below [`SIN_COS_EXACT_BELOW`]; in [-1, 1] for every finite x; NaN for NaN or
/// infinite x, as `f32::sin_cos`.
#[inline(always)]
pub fn sin_cos(x: f32) -> (f32, f32) {
    let a = x.abs().min(SIN_COS_LARGEST);
    // The nearest quadrant q and the remainder r = a - q pi/2 in [-pi/4, pi/4].
    let shifted = a * std::f32::consts::FRAC_2_PI + ROUNDING;
    let q = shifted - ROUNDING;
    let quadrant = shifted.to_bits().wrapping_sub(ROUNDING.to_bits());
    let r = ((a - q * HALF_PI_1) - q * HALF_PI_2) - q * HALF_PI_3;
    let z = r * r;
    let s = ((-1.951_529_6e-4 * z + 8.332_161e-3) * z - 1.666_665_5e-1) * z * r + r;
    let c = ((2.443_315_7e-5 * z - 1.388_731_6e-3) * z + 4.166_664_6e-2) * z * z - 0.5 * z + 1.0;
    // Odd quadrants swap the two; quadrants 2 and 3 negate sin, 1 and 2 negate cos; sin is
    // odd in x.
    let swap = quadrant & 1 == 1;
    let (sin, cos) = if swap { (c, s) } else { (s, c) };
    let sin_sign = ((quadrant & 2) << 30) ^ (x.to_bits() & 0x8000_0000);
    let cos_sign = (quadrant.wrapping_add(1) & 2) << 30;
    let sin = f32::from_bits(sin.to_bits() ^ sin_sign);
    let cos = f32::from_bits(cos.to_bits() ^ cos_sign);
    // The polynomials overshoot 1 by an ulp at most; far beyond the exact range the
    // remainder is not reduced at all.
    if x.is_finite() {
        (sin.clamp(-1.0, 1.0), cos.clamp(-1.0, 1.0))
    } else {
        (f32::NAN, f32::NAN)
    }
}

/// asin of `x` clamped to [-1, 1] (so within [-pi/2, pi/2]), within 2.5 epsilons
/// relative; NaN for NaN.
#[inline(always)]
pub fn asin(x: f32) -> f32 {
    let a = x.abs().min(1.0);
    // Near 1, asin a = pi/2 - 2 asin(sqrt((1 - a) / 2)), whose argument is at most 1/2.
    let large = a > 0.5;
    let z = if large { 0.5 * (1.0 - a) } else { a * a };
    let s = if large { z.sqrt() } else { a };
    let p = ((((4.216_32e-2 * z + 2.418_131e-2) * z + 4.547_002_6e-2) * z + 7.495_300_3e-2) * z
        + 1.666_675_2e-1)
        * z
        * s
        + s;
    let r = if large { FRAC_PI_2 - (p + p) } else { p };
    r.copysign(x)
}

/// atan2(y, x): the angle of (x, y) in [-pi, pi], within 2 epsilons relative, with the signs of zeros
/// read as `f32::atan2` reads them; both infinite gives the diagonal's angle, NaN in
/// either gives NaN.
#[inline(always)]
pub fn atan2(y: f32, x: f32) -> f32 {
    let (ax, ay) = (x.abs(), y.abs());
    // atan of t = min / max in [0, 1], then reflected: pi/2 - angle when |y| > |x|.
    let steep = ay > ax;
    let (num, den) = if steep { (ax, ay) } else { (ay, ax) };
    // 0 / 0 (the origin) and inf / inf (a diagonal at infinity) read as 0 and 1.
    let t = if num == den {
        if den == 0.0 { 0.0 } else { 1.0 }
    } else {
        num / den
    };
    // Beyond tan(pi/8), atan t = pi/4 + atan((t - 1) / (t + 1)).
    let far = t > 0.414_213_57;
    let base = if far { FRAC_PI_4 } else { 0.0 };
    let t = if far { (t - 1.0) / (t + 1.0) } else { t };
    let z = t * t;
    let angle = base
        + ((((8.053_744_5e-2 * z - 1.387_768_6e-1) * z + 1.997_771_1e-1) * z - 3.333_295e-1)
            * z
            * t
            + t);
    let angle = if steep { FRAC_PI_2 - angle } else { angle };
    // The left half plane, including x = -0, reflects the angle about pi/2.
    let angle = if x.is_sign_negative() {
        PI - angle
    } else {
        angle
    };
    let angle = if x.is_nan() || y.is_nan() {
        f32::NAN
    } else {
        angle
    };
    angle.copysign(y)
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::{SIN_COS_EXACT_BELOW, asin, atan2, sin_cos};

    /// The error of `got` against the exact `want` in f32 epsilons relative to `want`
    /// (2^-25 absolute at least: two of them are 2^-24 near zero).
    fn ulps(got: f32, want: f64) -> f64 {
        let unit = (want.abs() * f64::from(f32::EPSILON)).max(2f64.powi(-25));
        (f64::from(got) - want).abs() / unit
    }

    #[test]
    fn sin_cos_within_two_ulp() {
        let mut worst = 0.0f64;
        for i in 0..=2_000_000 {
            let x = -20.0 + i as f32 * 40.0 / 2_000_000.0;
            let (s, c) = sin_cos(x);
            let (ws, wc) = f64::from(x).sin_cos();
            worst = worst.max(ulps(s, ws)).max(ulps(c, wc));
        }
        for x in [1000.0f32, 4096.5, 12_345.678, SIN_COS_EXACT_BELOW * 0.999] {
            let (s, c) = sin_cos(x);
            let (ws, wc) = f64::from(x).sin_cos();
            worst = worst.max(ulps(s, ws)).max(ulps(c, wc));
        }
        assert!(worst <= 2.0, "worst error {worst} ulp");
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        assert!(sin_cos(-0.0).0.is_sign_negative());
    }

    #[test]
    fn asin_within_two_ulp() {
        let mut worst = 0.0f64;
        for i in 0..=2_000_000 {
            let x = -1.0 + i as f32 * 2.0 / 2_000_000.0;
            worst = worst.max(ulps(asin(x), f64::from(x).asin()));
        }
        assert!(worst <= 2.5, "worst error {worst} ulp");
        assert_eq!(asin(1.0), std::f32::consts::FRAC_PI_2);
        assert_eq!(asin(2.0), std::f32::consts::FRAC_PI_2);
        assert_eq!(asin(-0.0).to_bits(), (-0.0f32).to_bits());
    }

    #[test]
    fn atan2_within_two_ulp() {
        let mut worst = 0.0f64;
        for i in 0..=1000 {
            for j in 0..=1000 {
                let y = -3.0 + i as f32 * 6.0 / 1000.0;
                let x = -3.0 + j as f32 * 6.0 / 1000.0;
                worst = worst.max(ulps(atan2(y, x), f64::from(y).atan2(f64::from(x))));
            }
        }
        for (y, x) in [(1e-30f32, 1.0f32), (1.0, 1e-30), (1e30, -1.0), (3.0, 3.0)] {
            worst = worst.max(ulps(atan2(y, x), f64::from(y).atan2(f64::from(x))));
        }
        assert!(worst <= 2.0, "worst error {worst} ulp");
        for (y, x) in [(0.0f32, 0.0f32), (0.0, -0.0), (-0.0, -0.0), (-0.0, 0.0)] {
            assert_eq!(
                atan2(y, x).to_bits(),
                y.atan2(x).to_bits(),
                "atan2({y}, {x})"
            );
        }
    }

    fn any_f32() -> impl Strategy<Value = f32> {
        prop_oneof![
            any::<f32>(),
            Just(f32::INFINITY),
            Just(f32::NEG_INFINITY),
            Just(-0.0f32),
            Just(0.0f32),
            Just(f32::MIN_POSITIVE),
            Just(1e-45f32),
            Just(f32::MAX),
            -1e4f32..1e4,
        ]
    }

    proptest! {
        /// Any finite input gives values in range; NaN and infinities as the standard
        /// functions give them.
        #[test]
        fn total(x in any_f32(), y in any_f32()) {
            let (s, c) = sin_cos(x);
            if x.is_finite() {
                prop_assert!((-1.0..=1.0).contains(&s) && (-1.0..=1.0).contains(&c), "sin_cos({}) = ({}, {})", x, s, c);
            } else {
                prop_assert!(s.is_nan() && c.is_nan());
            }
            let a = asin(x);
            if x.is_nan() {
                prop_assert!(a.is_nan());
            } else {
                prop_assert!(a.abs() <= std::f32::consts::FRAC_PI_2, "asin({}) = {}", x, a);
            }
            let t = atan2(y, x);
            if x.is_nan() || y.is_nan() {
                prop_assert!(t.is_nan());
            } else {
                prop_assert!(t.abs() <= std::f32::consts::PI, "atan2({}, {}) = {}", y, x, t);
                prop_assert!(ulps(t, f64::from(y).atan2(f64::from(x))) <= 2.0, "atan2({}, {}) = {}", y, x, t);
            }
        }
    }
}
