//! The table that ships with the crate is the table the fitter makes, and it upsamples as
//! accurately as its resolution promises.
#![cfg(feature = "srgb-table")]

use prism_spectrum::color::RgbSpaceId;
use prism_spectrum::colorimetry::{Lab, Observer, ciede2000, reflectance_xyz};
use prism_upsample::{CoefficientTable, FitContext, SHIPPED_RESOLUTION};

fn srgb_context() -> FitContext {
    let srgb = RgbSpaceId::Srgb;
    FitContext::new(srgb.space(), &srgb.illuminant()).unwrap()
}

#[test]
fn the_shipped_srgb_table_is_a_fresh_fit() {
    let shipped =
        CoefficientTable::shipped(RgbSpaceId::Srgb).expect("srgb-table is a default feature");
    let context = srgb_context();
    assert!(shipped.space().matches(&context));
    assert_eq!(shipped.resolution(), SHIPPED_RESOLUTION);
    let (fresh, _) = CoefficientTable::fit(&context, SHIPPED_RESOLUTION, &|_| {}).unwrap();
    // Bit-identical on the machine that wrote it; elsewhere a libm may round differently,
    // so compare what matters: the spectra the two tables give, on a grid of colours.
    let mut worst = 0.0f64;
    for i in 0..=10 {
        for j in 0..=10 {
            for k in 0..=10 {
                let rgb = [i as f64 / 10.0, j as f64 / 10.0, k as f64 / 10.0];
                let (a, b) = (shipped.lookup(rgb), fresh.lookup(rgb));
                for lambda in (360..=830).step_by(10) {
                    use prism_spectrum::Spectrum;
                    let l = f64::from(lambda);
                    worst = worst.max((a.evaluate(l) - b.evaluate(l)).abs());
                }
            }
        }
    }
    assert!(worst < 1e-4, "shipped and fresh tables differ by {worst}");
}

#[test]
fn shipped_lookups_stay_far_below_a_visible_difference() {
    let shipped = CoefficientTable::shipped(RgbSpaceId::Rec709).unwrap();
    let context = srgb_context();
    let illuminant = RgbSpaceId::Srgb.illuminant();
    let white = context.white();
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut uniform = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut sum, mut max) = (0.0, 0.0f64);
    let count = 500u32;
    for _ in 0..count {
        let rgb = [uniform(), uniform(), uniform()];
        let target = Lab::from_xyz(context.rgb_xyz(rgb), white);
        let spectrum = shipped.lookup(rgb);
        let got = Lab::from_xyz(
            reflectance_xyz(&spectrum, &illuminant, Observer::Cie1931).unwrap(),
            white,
        );
        let de = ciede2000(target, got);
        sum += de;
        max = max.max(de);
    }
    // docs/upsample-accuracy.md: 32^3 trilinear, mean 0.032, max 0.18 over 20 134 colours.
    let mean = sum / f64::from(count);
    assert!(mean < 0.06 && max < 0.3, "mean {mean} max {max}");
}
