//! Extremes: every RGB input (0, 1, subnormals, 1e30, negative, NaN, inf) gives a finite
//! spectrum or a clear error; albedo spectra stay in [0, 1]; table lookups are continuous.

use std::sync::LazyLock;

use prism_spectrum::Spectrum;
use prism_spectrum::color::RgbSpaceId;
use prism_upsample::{CoefficientTable, FitContext, RgbKind, RgbSpectrum};
use proptest::prelude::*;

static CONTEXT: LazyLock<FitContext> = LazyLock::new(|| {
    FitContext::new(RgbSpaceId::Srgb.space(), &RgbSpaceId::Srgb.illuminant()).unwrap()
});
static TABLE: LazyLock<CoefficientTable> =
    LazyLock::new(|| CoefficientTable::fit(&CONTEXT, 16, &|_| {}).unwrap().0);

fn component() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(-0.0),
        Just(1.0),
        Just(5e-324),
        Just(f64::MIN_POSITIVE),
        Just(1e-30),
        Just(1e30),
        Just(3e38),
        Just(1e300),
        Just(f64::MAX),
        Just(-1e-3),
        Just(-1.0),
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        0.0..1.0f64,
        -2.0..3.0f64,
    ]
}

proptest! {
    #[test]
    fn every_input_is_finite_or_an_error(r in component(), g in component(), b in component(), kind in 0..2usize, lambda in 200.0..1200.0f64) {
        let rgb = [r, g, b];
        let kind = [RgbKind::Albedo, RgbKind::Unbounded][kind];
        match RgbSpectrum::fit(&CONTEXT, rgb, kind, None) {
            Ok(s) => {
                let v = s.evaluate(lambda);
                prop_assert!(v.is_finite() && v >= 0.0, "{rgb:?} -> {v}");
                prop_assert!(s.max_value().is_finite());
                if kind == RgbKind::Albedo {
                    prop_assert!(v <= 1.0);
                }
                // Unbounded colours are capped at half of f64's range (their scale is twice
                // the largest component).
                let clean = rgb.iter().all(|c| (0.0..=if kind == RgbKind::Albedo { 1.0 } else { f64::MAX / 2.0 }).contains(c));
                prop_assert_eq!(s.clamped(), !clean);
            }
            Err(_) => prop_assert!(rgb.iter().any(|c| !c.is_finite())),
        }
    }

    /// Table lookups are continuous: a small change of colour changes the spectrum a little.
    #[test]
    fn lookups_are_continuous(rgb in prop::array::uniform3(0.02..1.0f64), d in prop::array::uniform3(-1e-6..1e-6f64), lambda in 360.0..830.0f64) {
        let moved = [rgb[0] + d[0], rgb[1] + d[1], rgb[2] + d[2]];
        let (a, b) = (TABLE.lookup(rgb).evaluate(lambda), TABLE.lookup(moved).evaluate(lambda));
        prop_assert!((a - b).abs() < 1e-3, "{rgb:?}: {a} vs {b}");
        prop_assert!((0.0..=1.0).contains(&a));
    }

    /// Normalizing and denormalizing coefficients are inverse maps, both ways, to rounding
    /// relative to the polynomial's terms (the table stores nm, the fitter works in t).
    #[test]
    fn wavelength_normalization_round_trips(c in prop::array::uniform3(-1e3..1e3f64)) {
        use prism_upsample::{denormalize, normalize};
        let close = |a: [f64; 3], b: [f64; 3], scale: f64| {
            a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= 1e-12 * scale)
        };
        let back = normalize(denormalize(c));
        let terms = c.iter().map(|v| v.abs()).sum::<f64>();
        prop_assert!(close(back, c, terms), "{c:?} -> {back:?}");
        // As polynomials: the same value at every wavelength.
        let nm = denormalize(c);
        for lambda in [360.0, 555.0, 830.0] {
            let t = (lambda - 360.0) / 470.0;
            let (a, b) = ((c[0] * t + c[1]) * t + c[2], (nm[0] * lambda + nm[1]) * lambda + nm[2]);
            prop_assert!((a - b).abs() <= 1e-9 * terms, "{c:?} at {lambda}: {a} vs {b}");
        }
    }

    /// Batch lookups are the single lookups, bit for bit and in order, for any colours
    /// (extremes, ties between channels, black and greys included) and any count.
    #[test]
    fn batch_lookups_are_single_lookups(
        colours in prop::collection::vec(
            prop_oneof![
                prop::array::uniform3(component()),
                prop::array::uniform3(0.0..1.0f64),
                (0.0..1.0f64, 0usize..3).prop_map(|(v, tie)| {
                    let mut c = [v, v, v];
                    c[tie] = v * 0.5;
                    c
                }),
            ],
            0..40,
        )
    ) {
        let batch = TABLE.lookup_many(&colours);
        prop_assert_eq!(batch.len(), colours.len());
        for (colour, spectrum) in colours.iter().zip(&batch) {
            let single = TABLE.lookup(*colour).coefficients.map(f64::to_bits);
            prop_assert_eq!(spectrum.coefficients.map(f64::to_bits), single, "{:?}", colour);
        }
    }

    #[test]
    fn lookups_are_total(rgb in prop::array::uniform3(component())) {
        let c = TABLE.lookup_normalized(rgb);
        // Black (and anything clamping to it) has no sigmoid: -inf in c2 says so.
        prop_assert!(c.iter().all(|v| v.is_finite()) || c[2] == f64::NEG_INFINITY);
    }
}

static D65: LazyLock<std::sync::Arc<prism_spectrum::spectra::DenselySampled>> =
    LazyLock::new(|| {
        prism_upsample::normalized_illuminant(&RgbSpaceId::Srgb.illuminant()).unwrap()
    });

proptest! {
    /// The f32 lane evaluation renderers use agrees with the f64 definition for every
    /// kind, extreme inputs included, and stays finite (saturating at f32::MAX): within f32 rounding of the
    /// polynomial's terms (8 ulps of |c0| l^2 + |c1| l + |c2|, through the sigmoid's slope
    /// of at most 1/2; saturated colours have large, cancelling terms) plus 2e-6, relative
    /// to the spectrum's maximum.
    #[test]
    fn lane_evaluation_matches_the_definition(r in component(), g in component(), b in component(), kind in 0..3usize, l0 in 300.0..900.0f32, step in 0.0..40.0f32) {
        let kind = [RgbKind::Albedo, RgbKind::Unbounded, RgbKind::Illuminant][kind];
        let Ok(s) = RgbSpectrum::fit(&CONTEXT, [r, g, b], kind, Some(D65.clone())) else {
            return Ok(());
        };
        let lambda: [f32; 8] = std::array::from_fn(|i| l0 + step * i as f32);
        let lanes = s.evaluate_lanes(&lambda);
        let c = s.shape().map_or([0.0; 3], |p| p.coefficients);
        for (l, v) in lambda.iter().zip(lanes) {
            // Lanes saturate at f32's largest value.
            let want = s.evaluate(f64::from(*l)).min(f64::from(f32::MAX));
            let x = f64::from(*l);
            let terms = c[0].abs() * x * x + c[1].abs() * x + c[2].abs();
            let bound = (0.5 * 8.0 * f64::from(f32::EPSILON) * terms + 2e-6) * s.max_value();
            prop_assert!(v.is_finite(), "{l} nm: {v}");
            prop_assert!(
                (f64::from(v) - want).abs() <= bound + 1e-30,
                "{kind:?} {:?} at {l} nm: lanes {v}, definition {want}", [r, g, b]
            );
        }
    }
}
