//! Mitsuba 3's render test: a per-pixel z-test of a render against a reference mean and
//! the reference's per-sample variance, Šidák-corrected over the pixels. It is the test
//! of Mitsuba's own render suite (`test_render` and `z_test` in
//! src/render/tests/test_renders.py of mitsuba-renderer/mitsuba3), kept as it is there so
//! that a scene passes here exactly when it would pass there:
//!
//! - both images and the variance go from linear sRGB to XYZ by the same matrix;
//! - the variance is floored at 1e-4;
//! - z = |mean - reference| sqrt(spp / variance), p = 2 (1 - Phi(z));
//! - a pixel channel passes when p > alpha = 1 - (1 - significance)^(1 / pixels);
//! - the render passes when at least 99.75% of the pixels' channels pass.

use prism_spectrum::color::RgbSpaceId;

use super::compare::ChannelImage;
use crate::error::RenderError;

/// The significance level of Mitsuba's suite.
pub const MITSUBA_SIGNIFICANCE: f64 = 0.01;

/// The share of pixel channels that must pass, as Mitsuba's suite asks.
pub const MITSUBA_PASS_SHARE: f64 = 0.9975;

/// The outcome of [`z_test`].
#[derive(Debug, Clone, PartialEq)]
pub struct ZTest {
    /// Pixels tested.
    pub pixels: usize,
    /// The Šidák-corrected level each pixel channel is tested at.
    pub alpha: f64,
    /// The smallest p-value, and where: (x, y, channel 0-2 of X, Y, Z).
    pub min_p: (f64, usize, usize, usize),
    /// Pixel channels whose p-value exceeds `alpha`.
    pub passed: usize,
    /// Whether the render passes: `passed` >= 99.75% of 3 x `pixels`.
    pub accepted: bool,
    /// Per channel (X, Y, Z): the image's mean over the reference's (None where the
    /// reference's mean is 0), the first thing to read of a failure.
    pub mean_ratio: [Option<f64>; 3],
}

/// Tests `image` (the mean of `spp` samples per pixel) against `reference` and the
/// reference's per-sample `variance`, all linear sRGB with channels R, G, B of one size.
///
/// # Errors
///
/// [`RenderError::Comparison`] when the sizes differ, a channel is missing, a sample is
/// not finite, or `spp` is 0.
pub fn z_test(
    image: &ChannelImage,
    reference: &ChannelImage,
    variance: &ChannelImage,
    spp: u64,
    significance: f64,
) -> Result<ZTest, RenderError> {
    let bad = RenderError::Comparison;
    if spp == 0 {
        return Err(bad("a z-test needs at least one sample per pixel".into()));
    }
    if !(significance > 0.0 && significance < 1.0) {
        return Err(bad(format!("significance {significance} is not in (0, 1)")));
    }
    let (w, h) = (reference.width, reference.height);
    for (which, img) in [("image", image), ("variance", variance)] {
        if (img.width, img.height) != (w, h) {
            return Err(bad(format!(
                "sizes differ: the {which} is {}x{}, the reference {w}x{h}",
                img.width, img.height
            )));
        }
    }
    let pixels = w * h;
    if pixels == 0 {
        return Err(bad("the reference has no pixels".into()));
    }
    let xyz = |img: &ChannelImage, which: &str| -> Result<Vec<[f64; 3]>, RenderError> {
        let channel = |name: &str| {
            img.channels
                .iter()
                .find(|(n, _)| n == name)
                .map(|(_, v)| v)
                .ok_or_else(|| bad(format!("the {which} has no channel {name}")))
        };
        let (r, g, b) = (channel("R")?, channel("G")?, channel("B")?);
        let space = RgbSpaceId::Srgb.space();
        (0..pixels)
            .map(|i| {
                let rgb = [r[i], g[i], b[i]].map(f64::from);
                if rgb.iter().any(|v| !v.is_finite()) {
                    return Err(bad(format!(
                        "the {which} has a non-finite sample at pixel ({}, {})",
                        i % w,
                        i / w
                    )));
                }
                Ok(space.rgb_to_xyz(rgb).to_array())
            })
            .collect()
    };
    let (mean, refs, var) = (
        xyz(image, "image")?,
        xyz(reference, "reference")?,
        xyz(variance, "variance")?,
    );
    let alpha = 1.0 - (1.0 - significance).powf(1.0 / pixels as f64);
    let spp = spp as f64;
    let mut passed = 0;
    let mut min_p = (f64::INFINITY, 0, 0, 0);
    let (mut sums, mut ref_sums) = ([0.0; 3], [0.0; 3]);
    for i in 0..pixels {
        for c in 0..3 {
            let z = (mean[i][c] - refs[i][c]).abs() * (spp / var[i][c].max(1e-4)).sqrt();
            let p = erfc(z / std::f64::consts::SQRT_2);
            if p > alpha {
                passed += 1;
            }
            if p < min_p.0 {
                min_p = (p, i % w, i / w, c);
            }
            sums[c] += mean[i][c];
            ref_sums[c] += refs[i][c];
        }
    }
    Ok(ZTest {
        pixels,
        alpha,
        min_p,
        passed,
        accepted: passed as f64 >= MITSUBA_PASS_SHARE * 3.0 * pixels as f64,
        mean_ratio: std::array::from_fn(|c| (ref_sums[c] != 0.0).then(|| sums[c] / ref_sums[c])),
    })
}

/// The complementary error function by the Chebyshev-derived fit of Press et al.,
/// "Numerical Recipes in C" (2nd ed.), section 6.2 (`erfcc`): fractional error below
/// 1.2e-7 everywhere, ample for p-values compared at ~1e-6.
fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 2.0 / (2.0 + z);
    let poly = -z * z - 1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98
                                + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let r = t * poly.exp();
    if x >= 0.0 { r } else { 2.0 - r }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(w: usize, h: usize, rgb: impl Fn(usize) -> [f32; 3]) -> ChannelImage {
        let values: Vec<[f32; 3]> = (0..w * h).map(rgb).collect();
        ChannelImage {
            width: w,
            height: h,
            channels: ["R", "G", "B"]
                .iter()
                .enumerate()
                .map(|(c, n)| (n.to_string(), values.iter().map(|v| v[c]).collect()))
                .collect(),
        }
    }

    #[test]
    fn erfc_matches_known_values() {
        // erfc(0) = 1, erfc(1) = 0.157299207050285, erfc(3) = 2.20904969985854e-5,
        // erfc(-1) = 1.842700792949715 (Abramowitz and Stegun, table 7.1).
        for (x, want) in [
            (0.0, 1.0),
            (1.0, 0.157_299_207_050_285),
            (3.0, 2.209_049_699_858_54e-5),
            (-1.0, 1.842_700_792_949_715),
        ] {
            assert!((erfc(x) - want).abs() <= 1.2e-7 * want, "erfc({x})");
        }
    }

    #[test]
    fn a_render_within_its_noise_passes_and_a_biased_one_fails() {
        let (w, h) = (16, 16);
        let reference = image(w, h, |_| [0.5, 0.4, 0.3]);
        let variance = image(w, h, |_| [0.04, 0.04, 0.04]);
        // With 100 spp the mean's standard deviation is 0.02; a pixel pattern of
        // +-1 sigma passes, a 2% bias over all pixels (z = 0.5 each) passes too, but
        // a 10-sigma offset fails everywhere.
        let noisy = image(w, h, |i| {
            let s = if i % 2 == 0 { 0.02 } else { -0.02 };
            [0.5 + s, 0.4 - s, 0.3 + s]
        });
        let t = z_test(&noisy, &reference, &variance, 100, MITSUBA_SIGNIFICANCE).unwrap();
        assert!(t.accepted && t.passed == 3 * w * h, "{t:?}");
        let biased = image(w, h, |_| [0.7, 0.6, 0.5]);
        let t = z_test(&biased, &reference, &variance, 100, MITSUBA_SIGNIFICANCE).unwrap();
        assert!(!t.accepted && t.passed == 0, "{t:?}");
        assert!(t.mean_ratio[1].unwrap() > 1.3);
    }

    #[test]
    fn one_outlier_in_many_pixels_is_within_the_allowed_share() {
        let (w, h) = (32, 32);
        let reference = image(w, h, |_| [1.0, 1.0, 1.0]);
        let variance = image(w, h, |_| [1.0, 1.0, 1.0]);
        let render = image(w, h, |i| if i == 5 { [9.0; 3] } else { [1.0; 3] });
        let t = z_test(&render, &reference, &variance, 64, MITSUBA_SIGNIFICANCE).unwrap();
        assert!(t.accepted, "{t:?}");
        assert_eq!((t.min_p.1, t.min_p.2), (5, 0));
        assert!(t.passed < 3 * w * h);
    }

    #[test]
    fn mismatched_or_bad_inputs_are_errors() {
        let a = image(4, 4, |_| [1.0; 3]);
        let b = image(4, 2, |_| [1.0; 3]);
        assert!(z_test(&a, &b, &b, 10, 0.01).is_err());
        assert!(z_test(&a, &a, &a, 0, 0.01).is_err());
        assert!(z_test(&a, &a, &a, 10, 1.5).is_err());
        let nan = image(4, 4, |_| [f32::NAN; 3]);
        assert!(z_test(&nan, &a, &a, 10, 0.01).is_err());
    }
}
