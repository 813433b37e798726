//! The exact fitter: accuracy over the sRGB cube, convergence from any start, and the
//! policies of the spectrum kinds.

use prism_spectrum::Spectrum;
use prism_spectrum::color::RgbSpaceId;
use prism_spectrum::colorimetry::{Lab, Observer, ciede2000, reflectance_xyz};
use prism_spectrum::illuminant::StandardIlluminant;
use prism_upsample::{FitContext, RgbKind, RgbSpectrum, normalized_illuminant};

fn srgb_context() -> FitContext {
    FitContext::new(
        RgbSpaceId::Srgb.space(),
        &StandardIlluminant::D65.spectrum(),
    )
    .unwrap()
}

/// CIEDE2000 between the target RGB and the colour of `spectrum` under D65, both through
/// prism-spectrum's colorimetry (independent of the fitter's own Lab code).
fn round_trip_de(context: &FitContext, rgb: [f64; 3], spectrum: &impl Spectrum) -> f64 {
    let d65 = StandardIlluminant::D65.spectrum();
    let xyz = reflectance_xyz(spectrum, &d65, Observer::Cie1931).unwrap();
    let white = context.white();
    ciede2000(
        Lab::from_xyz(xyz, white),
        Lab::from_xyz(context.rgb_xyz(rgb), white),
    )
}

/// The colours the issue names: a grid through the cube (corners, edges, faces), near
/// black and near white, and pseudo-random colours.
fn test_colours() -> Vec<[f64; 3]> {
    let mut colours = Vec::new();
    let steps = [
        0.0, 0.001, 0.01, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99, 0.999, 1.0,
    ];
    for &r in &steps {
        for &g in &steps {
            for &b in &steps {
                colours.push([r, g, b]);
            }
        }
    }
    let mut x = 0x2545_f491_4f6c_dd1du64;
    for _ in 0..500 {
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        colours.push([next(), next(), next()]);
    }
    colours
}

#[test]
fn exact_fits_meet_the_target_over_the_srgb_cube() {
    let context = srgb_context();
    let mut worst: (f64, [f64; 3]) = (0.0, [0.0; 3]);
    let mut total = 0.0;
    let colours = test_colours();
    for &rgb in &colours {
        let s = RgbSpectrum::fit(&context, rgb, RgbKind::Albedo, None).unwrap();
        let de = round_trip_de(&context, rgb, &s);
        total += de;
        if de > worst.0 {
            worst = (de, rgb);
        }
    }
    eprintln!(
        "exact fits: {} colours, mean dE2000 {:.2e}, max {:.2e} at {:?}",
        colours.len(),
        total / colours.len() as f64,
        worst.0,
        worst.1
    );
    assert!(worst.0 <= 0.01, "max dE2000 {} at {:?}", worst.0, worst.1);
}

#[test]
fn fits_converge_from_any_start() {
    let context = srgb_context();
    let mut x = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    for rgb in [
        [0.8, 0.1, 0.1],
        [0.05, 0.6, 0.3],
        [0.2, 0.3, 0.9],
        [0.9, 0.9, 0.2],
    ] {
        for _ in 0..20 {
            let start = [
                200.0 * next() - 100.0,
                200.0 * next() - 100.0,
                200.0 * next() - 100.0,
            ];
            let fit = context.fit(rgb, start);
            let de = round_trip_de(&context, rgb, &fit.spectrum);
            assert!(
                de <= 0.01,
                "{rgb:?} from {start:?}: dE {de} after {} iterations",
                fit.iterations
            );
        }
    }
}

#[test]
fn policies_for_special_inputs() {
    let context = srgb_context();
    // Black is exactly zero.
    let black = RgbSpectrum::fit(&context, [0.0; 3], RgbKind::Albedo, None).unwrap();
    assert!((360..=830).all(|l| black.evaluate(f64::from(l)) == 0.0));
    // Greys are exactly constant.
    for v in [0.001, 0.18, 0.5, 0.999, 1.0] {
        let grey = RgbSpectrum::fit(&context, [v; 3], RgbKind::Albedo, None).unwrap();
        let first = grey.evaluate(360.0);
        assert!((first - v).abs() < 1e-15, "{v}: {first}");
        assert!(
            (300..=1000).all(|l| grey.evaluate(f64::from(l)) == first),
            "{v} is not constant"
        );
    }
    // Non-finite input is an error; out-of-gamut and above-one are clamped and reported.
    assert!(RgbSpectrum::fit(&context, [f64::NAN, 0.0, 0.0], RgbKind::Albedo, None).is_err());
    assert!(
        RgbSpectrum::fit(
            &context,
            [f64::INFINITY, 0.0, 0.0],
            RgbKind::Unbounded,
            None
        )
        .is_err()
    );
    let negative = RgbSpectrum::fit(&context, [-0.2, 0.5, 0.5], RgbKind::Albedo, None).unwrap();
    assert!(negative.clamped());
    let bright = RgbSpectrum::fit(&context, [1.5, 0.5, 0.5], RgbKind::Albedo, None).unwrap();
    assert!(bright.clamped() && bright.max_value() <= 1.0);
    let in_range = RgbSpectrum::fit(&context, [0.3, 0.5, 0.5], RgbKind::Albedo, None).unwrap();
    assert!(!in_range.clamped());
}

#[test]
fn unbounded_values_keep_their_colour() {
    let context = srgb_context();
    for rgb in [
        [2.0, 1.0, 0.5],
        [30.0, 30.0, 30.0],
        [1e30, 1e29, 0.0],
        [5e-300, 1e-300, 0.0],
    ] {
        let s = RgbSpectrum::fit(&context, rgb, RgbKind::Unbounded, None).unwrap();
        assert!(s.max_value().is_finite() && s.evaluate(550.0).is_finite());
        let d65 = StandardIlluminant::D65.spectrum();
        let xyz = reflectance_xyz(&s, &d65, Observer::Cie1931).unwrap();
        let target = context.rgb_xyz(rgb);
        for (g, e) in xyz.to_array().iter().zip(target.to_array()) {
            assert!(
                (g - e).abs() <= 1e-3 * e.abs().max(target.y),
                "{rgb:?}: {xyz:?} vs {target:?}"
            );
        }
    }
}

#[test]
fn white_illuminant_emits_exactly_the_illuminant() {
    let context = srgb_context();
    let d65 = normalized_illuminant(&StandardIlluminant::D65.spectrum()).unwrap();
    let white =
        RgbSpectrum::fit(&context, [1.0; 3], RgbKind::Illuminant, Some(d65.clone())).unwrap();
    for l in (300..=1000).step_by(7) {
        assert_eq!(
            white.evaluate(f64::from(l)),
            d65.evaluate(f64::from(l)),
            "{l} nm"
        );
    }
}
