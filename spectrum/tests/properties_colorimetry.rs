//! Numerical stability of colorimetry and colour at the extremes.

use prism_spectrum::color::{RgbColorSpace, RgbSpaceId, ToneMap, TransferFunction, display_8bit};
use prism_spectrum::colorimetry::{
    Chromaticity, Lab, Observer, Uv, WhitePoint, Xyz, cct_ohno2013, ciede2000, emission_xyz,
};
use prism_spectrum::illuminant::daylight;
use prism_spectrum::spectra::Gaussian;
use proptest::prelude::*;

fn lab_component() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(-0.0),
        Just(1e-300),
        Just(-1e-300),
        Just(5e-324),
        Just(1e300),
        Just(-1e300),
        Just(f64::MAX),
        -200.0..200.0f64,
        any::<f64>().prop_filter("finite", |v| v.is_finite()),
    ]
}

fn lab() -> impl Strategy<Value = Lab> {
    (lab_component(), lab_component(), lab_component()).prop_map(|(l, a, b)| Lab::new(l, a, b))
}

fn finite3(v: [f64; 3]) -> bool {
    v.iter().all(|c| c.is_finite())
}

proptest! {
    /// CIEDE2000 is finite, non-negative, exactly symmetric and zero on identical colours
    /// for every finite Lab, including L = 0, achromatic colours and huge values.
    #[test]
    fn ciede2000_is_total_and_symmetric(p in lab(), q in lab()) {
        let d = ciede2000(p, q);
        prop_assert!(d.is_finite() && d >= 0.0, "{d}");
        prop_assert_eq!(d, ciede2000(q, p));
        prop_assert_eq!(ciede2000(p, p), 0.0);
    }

    /// Across the 0/360 degree hue wrap (a > 0, b crossing 0) the difference is
    /// continuous. CIEDE2000 is genuinely discontinuous where the two hues differ by 180
    /// degrees (Sharma, Wu and Dalal 2005, "Mathematical observations"), so partners whose
    /// hue lies within 10 degrees of 180 are excluded: that jump is the formula's, not ours.
    #[test]
    fn ciede2000_is_continuous_across_hue_wrap(
        l in 0.0..100.0f64,
        a in 0.1..100.0f64,
        b in 1e-9..1e-6f64,
        other_l in 0.0..100.0f64,
        other_c in 1.0..100.0f64,
        other_h in (0.0..340.0f64).prop_map(|h| if h >= 170.0 { h + 20.0 } else { h }),
    ) {
        let other = Lab::new(other_l, other_c * other_h.to_radians().cos(), other_c * other_h.to_radians().sin());
        let above = ciede2000(Lab::new(l, a, b), other);
        let below = ciede2000(Lab::new(l, a, -b), other);
        prop_assert!((above - below).abs() < 1e-3, "{above} vs {below}");
    }

    /// Lab of any finite XYZ under any valid white is finite, and round-trips.
    #[test]
    fn lab_is_total(x in -1e6..1e6f64, y in -1e6..1e6f64, z in -1e6..1e6f64, wx in 0.2..0.5f64, wy in 0.2..0.5f64) {
        let white = WhitePoint::from_xy(Chromaticity::new(wx, wy)).unwrap();
        let lab = Lab::from_xyz(Xyz::new(x, y, z), white);
        prop_assert!(lab.l.is_finite() && lab.a.is_finite() && lab.b.is_finite());
        let back = lab.to_xyz(white);
        for (g, e) in back.to_array().iter().zip([x, y, z]) {
            prop_assert!((g - e).abs() <= 1e-9 * (1.0 + e.abs()), "{g} vs {e}");
        }
    }

    /// CCT of any (u, v) is a finite answer inside the supported range or an error.
    #[test]
    fn cct_is_total(u in prop_oneof![Just(f64::NAN), -1.0..1.0f64], v in prop_oneof![Just(f64::INFINITY), -1.0..1.0f64]) {
        if let Ok(r) = cct_ohno2013(Uv { u, v }) {
            prop_assert!(r.kelvin.is_finite() && (999.0..=100_001.0).contains(&r.kelvin));
            prop_assert!(r.duv.is_finite());
        }
    }

    /// Daylight spectra are finite across the CIE locus and errors outside it.
    #[test]
    fn daylight_is_total(kelvin in prop_oneof![Just(f64::NAN), Just(-1.0), Just(0.0), 0.0..1e5f64]) {
        match daylight(kelvin) {
            Ok(spd) => {
                prop_assert!((4000.0..=25000.0).contains(&kelvin));
                prop_assert!(spd.values().iter().all(|v| v.is_finite()));
            }
            Err(_) => prop_assert!(!(4000.0..=25000.0).contains(&kelvin)),
        }
    }

    /// Emission XYZ of any valid narrow or wide band is finite.
    #[test]
    fn emission_xyz_is_finite(center in -1e4..1e4f64, fwhm in 1e-6..1e6f64, peak in -1e30..1e30f64, ten in any::<bool>()) {
        let g = Gaussian::new(center, fwhm, peak).unwrap();
        let observer = if ten { Observer::Cie1964 } else { Observer::Cie1931 };
        let xyz = emission_xyz(&g, observer);
        prop_assert!(finite3(xyz.to_array()));
    }

    /// User-defined colour spaces: either an error or finite matrices that invert each
    /// other.
    #[test]
    fn user_colour_spaces_are_valid_or_rejected(
        p in prop::array::uniform6(prop_oneof![Just(0.0), Just(1e-300), -0.5..1.5f64]),
        w in prop::array::uniform2(prop_oneof![Just(0.0), -0.5..1.5f64]),
    ) {
        let xy = Chromaticity::new;
        let primaries = [xy(p[0], p[1]), xy(p[2], p[3]), xy(p[4], p[5])];
        if let Ok(space) = RgbColorSpace::new("user", primaries, xy(w[0], w[1]), TransferFunction::Linear) {
            let round = space.rgb_to_xyz_matrix().mul(&space.xyz_to_rgb_matrix());
            for r in 0..3 {
                prop_assert!(finite3(round.0[r]));
            }
            let rgb = space.xyz_to_rgb(space.white().xyz());
            prop_assert!(finite3(rgb));
        }
    }

    /// Tone mapping and 8-bit display never panic and stay in [0, 1] for any input at all.
    #[test]
    fn tone_maps_are_total(
        rgb in prop::array::uniform3(prop_oneof![Just(f64::NAN), Just(f64::INFINITY), Just(-1.0), Just(1e308), 0.0..100.0f64]),
        exposure in prop_oneof![Just(f64::NAN), Just(1e6), -10.0..10.0f64],
        white in prop_oneof![Just(0.0), Just(1e300), 0.1..100.0f64],
    ) {
        let weights = RgbSpaceId::Srgb.space().luminance_weights();
        for tm in [ToneMap::Clamp, ToneMap::ReinhardExtended { white }, ToneMap::AcesFilmic, ToneMap::PbrNeutral] {
            let out = tm.apply(rgb, weights);
            prop_assert!(out.iter().all(|c| (0.0..=1.0).contains(c)), "{tm:?} {out:?}");
            let _ = display_8bit(rgb, exposure, tm, weights, TransferFunction::Srgb);
        }
    }

    /// Transfer functions are finite for finite input and invert each other.
    #[test]
    fn transfer_functions_round_trip(x in prop_oneof![Just(0.0), Just(-0.0), Just(5e-324), -1e6..1e6f64], g in 0.1..10.0f64) {
        for tf in [TransferFunction::Linear, TransferFunction::Srgb, TransferFunction::Rec709, TransferFunction::Gamma(g)] {
            let e = tf.encode(x);
            prop_assert!(e.is_finite());
            let back = tf.decode(e);
            prop_assert!((back - x).abs() <= 1e-9 * (1.0 + x.abs()), "{tf:?}: {x} -> {e} -> {back}");
        }
    }
}

#[test]
fn black_has_no_chromaticity_and_no_normalization() {
    assert!(Xyz::default().chromaticity().is_err());
    assert!(Xyz::default().uv().is_err());
    assert!(Xyz::default().normalized_to_unit_y().is_err());
    assert!(WhitePoint::from_xy(Chromaticity::new(0.5, 0.6)).is_err());
}

mod more {
    use prism_spectrum::color::{AdaptationMethod, adaptation_matrix};
    use prism_spectrum::colorimetry::{Chromaticity, Observer, WhitePoint, Xyz, reflectance_xyz};
    use prism_spectrum::spectra::Gaussian;
    use proptest::prelude::*;

    proptest! {
        /// Adaptation between any two valid whites is finite and maps white to white.
        #[test]
        fn adaptation_is_finite(a in prop::array::uniform2(0.05..0.6f64), b in prop::array::uniform2(0.05..0.6f64), m in 0..3usize) {
            let (Ok(src), Ok(dst)) = (
                WhitePoint::from_xy(Chromaticity::new(a[0], a[1])),
                WhitePoint::from_xy(Chromaticity::new(b[0], b[1])),
            ) else { return Ok(()); };
            let method = [AdaptationMethod::Bradford, AdaptationMethod::Cat02, AdaptationMethod::VonKries][m];
            let matrix = adaptation_matrix(src, dst, method);
            let mapped = matrix.apply(src.xyz().to_array());
            for (g, e) in mapped.iter().zip(dst.xyz().to_array()) {
                prop_assert!(g.is_finite() && (g - e).abs() < 1e-9 * (1.0 + e.abs()), "{g} vs {e}");
            }
        }

        /// Reflectance under any illuminant band: finite XYZ or an error (no luminance).
        #[test]
        fn reflectance_xyz_is_finite_or_error(center in 100.0..1200.0f64, fwhm in 1e-3..1e3f64, r in -10.0..10.0f64) {
            let illuminant = Gaussian::new(center, fwhm, 1.0).unwrap();
            let reflectance = Gaussian::new(550.0, 100.0, r).unwrap();
            if let Ok(xyz) = reflectance_xyz(&reflectance, &illuminant, Observer::Cie1964) {
                prop_assert!(xyz.to_array().iter().all(|v| v.is_finite()));
            }
        }

        /// xyY to XYZ and back.
        #[test]
        fn xyy_round_trip(x in -1.0..1.0f64, y in prop_oneof![Just(0.0), Just(-0.1), Just(5e-324), 1e-300..1.0f64], big_y in prop_oneof![Just(1e300), -1e6..1e6f64]) {
            match Xyz::from_xy_luminance(Chromaticity::new(x, y), big_y) {
                Ok(xyz) => {
                    prop_assert!(y > 0.0);
                    prop_assert!(xyz.to_array().iter().all(|v| v.is_finite()), "{xyz:?}");
                    if big_y.abs() > 1e-9 && y > 1e-6 {
                        let xy = xyz.chromaticity().unwrap();
                        prop_assert!((xy.x - x).abs() < 1e-9 && (xy.y - y).abs() < 1e-9);
                    }
                }
                // Either no colour has this chromaticity or its XYZ overflows f64.
                Err(_) => prop_assert!(y <= 0.0 || big_y.abs() / y > 1e300),
            }
        }
    }
}
