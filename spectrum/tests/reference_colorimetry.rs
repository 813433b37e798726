//! prism-spectrum against an independent implementation: colour-science values in
//! `fixtures/colorimetry_reference.json`. Each tolerance says why it is that size.

mod common;

use common::{assert_mat3_close, fixture, mat3, num, nums};
use prism_spectrum::Spectrum;
use prism_spectrum::color::{AdaptationMethod, RgbSpaceId, TransferFunction, adaptation_matrix};
use prism_spectrum::colorimetry::{
    Chromaticity, Lab, Observer, Uv, WhitePoint, Xyz, cct_ohno2013, ciede2000, emission_xyz,
    reflectance_xyz,
};
use prism_spectrum::illuminant::{StandardIlluminant, daylight};
use prism_spectrum::spectra::{Blackbody, Extrapolation, PiecewiseLinear, planck_radiance};

fn observer(key: &str) -> Observer {
    Observer::from_name(key).unwrap()
}

/// Chromaticity to 1e-5 (the requirement). Both sides integrate the same tables
/// the same way, so the real agreement is ~1e-12; 1e-5 leaves room for nothing but bugs.
#[test]
fn chromaticities_of_illuminants_and_blackbodies() {
    let reference = fixture("colorimetry_reference.json");
    let mut checked = 0;
    for (key, entries) in reference["chromaticity_xy"].as_object().unwrap() {
        for (name, xy) in entries.as_object().unwrap() {
            let expected = nums(xy);
            let xyz = if let Some(t) = name.strip_prefix("blackbody:") {
                emission_xyz(&Blackbody::new(t.parse().unwrap()).unwrap(), observer(key))
            } else {
                emission_xyz(
                    &StandardIlluminant::from_name(name).unwrap().spectrum(),
                    observer(key),
                )
            };
            let got = xyz.chromaticity().unwrap();
            assert!(
                (got.x - expected[0]).abs() < 1e-5 && (got.y - expected[1]).abs() < 1e-5,
                "{key} {name}: got ({}, {}), colour-science ({}, {})",
                got.x,
                got.y,
                expected[0],
                expected[1]
            );
            checked += 1;
        }
    }
    assert!(
        checked >= 2 * (3 + 49),
        "all fixtures were checked ({checked})"
    );
}

/// Published CIE chromaticities (CIE 015:2018 Table 3, 2-degree): a check of the whole
/// pipeline against the standard itself. 5e-5 because the standard rounds to 5 digits.
#[test]
fn d65_and_a_match_the_published_white_points() {
    for (ill, x, y) in [("D65", 0.31272, 0.32903), ("A", 0.44758, 0.40745)] {
        let xy = StandardIlluminant::from_name(ill)
            .unwrap()
            .chromaticity(Observer::Cie1931);
        assert!(
            (xy.x - x).abs() < 5e-5 && (xy.y - y).abs() < 5e-5,
            "{ill}: {xy:?}"
        );
    }
}

/// Reflectance XYZ with perfect-white normalization, same convention: 1e-9.
#[test]
fn reflectance_under_d65() {
    let reference = fixture("colorimetry_reference.json");
    let expected = nums(&reference["reflectance_gaussian_under_d65_cie1931"]["XYZ"]);
    let lambdas: Vec<f64> = (360..=830).map(f64::from).collect();
    let values = lambdas
        .iter()
        .map(|l| 0.2 + 0.6 * (-0.5 * ((l - 550.0) / 40.0f64).powi(2)).exp())
        .collect();
    let refl = PiecewiseLinear::new(lambdas, values, Extrapolation::Zero).unwrap();
    let d65 = StandardIlluminant::D65.spectrum();
    let got = reflectance_xyz(&refl, &d65, Observer::Cie1931).unwrap();
    for (g, e) in got.to_array().iter().zip(&expected) {
        assert!((g - e).abs() < 1e-9, "{got:?} vs {expected:?}");
    }
    // A perfect white has Y = 1 exactly (to rounding).
    let white = prism_spectrum::spectra::Constant::new(1.0).unwrap();
    let y = reflectance_xyz(&white, &d65, Observer::Cie1931).unwrap().y;
    assert!((y - 1.0).abs() < 1e-14);
}

/// Matrices derived from primaries and white to 1e-6 (the requirement; actual
/// agreement is ~1e-15 because both invert the same 3x3 system).
#[test]
fn rgb_matrices_are_derived_correctly() {
    let reference = fixture("colorimetry_reference.json");
    for (key, entry) in reference["rgb_spaces"].as_object().unwrap() {
        let space = RgbSpaceId::from_name(key).unwrap().space();
        let white = nums(&entry["white"]);
        assert!(
            (space.white().xy().x - white[0]).abs() < 1e-12,
            "{key} white"
        );
        for (which, got) in [
            ("rgb_to_xyz", space.rgb_to_xyz_matrix()),
            ("xyz_to_rgb", space.xyz_to_rgb_matrix()),
        ] {
            assert_mat3_close(
                &got.0,
                &mat3(&entry[which]),
                1e-6,
                &format!("{key} {which}"),
            );
        }
    }
}

/// Adaptation matrices to 1e-6: same formula, same cone matrices (the test would catch a
/// mistyped cone matrix entry, which is the realistic failure).
#[test]
fn chromatic_adaptation_matrices() {
    let reference = fixture("colorimetry_reference.json");
    for (key, entry) in reference["chromatic_adaptation"].as_object().unwrap() {
        let method = AdaptationMethod::from_name(key.split(':').next().unwrap()).unwrap();
        let white = |v: &serde_json::Value| {
            let xy = nums(v);
            WhitePoint::from_xy(Chromaticity::new(xy[0], xy[1])).unwrap()
        };
        let got = adaptation_matrix(white(&entry["src_xy"]), white(&entry["dst_xy"]), method);
        assert_mat3_close(&got.0, &mat3(&entry["matrix"]), 1e-6, key);
    }
}

#[test]
fn cielab() {
    let reference = fixture("colorimetry_reference.json");
    for entry in reference["cielab"].as_array().unwrap() {
        let xyz = nums(&entry["XYZ"]);
        let wxy = nums(&entry["white_xy"]);
        let white = WhitePoint::from_xy(Chromaticity::new(wxy[0], wxy[1])).unwrap();
        let lab = Lab::from_xyz(Xyz::new(xyz[0], xyz[1], xyz[2]), white);
        let expected = nums(&entry["Lab"]);
        for (g, e) in [lab.l, lab.a, lab.b].iter().zip(&expected) {
            assert!((g - e).abs() < 1e-9, "{xyz:?}: {lab:?} vs {expected:?}");
        }
        // And back.
        let back = lab.to_xyz(white);
        for (g, e) in back.to_array().iter().zip(&xyz) {
            assert!((g - e).abs() < 1e-12, "round trip {xyz:?}: {back:?}");
        }
    }
}

/// The 34 Sharma pairs: the published values are rounded to 4 decimals, so 5e-5 is the
/// strictest honest tolerance; against colour-science's unrounded values, 1e-9.
#[test]
fn ciede2000_sharma_pairs() {
    let reference = fixture("colorimetry_reference.json");
    let pairs = reference["ciede2000"].as_array().unwrap();
    assert_eq!(pairs.len(), 34);
    for (i, pair) in pairs.iter().enumerate() {
        let (a, b) = (nums(&pair["lab1"]), nums(&pair["lab2"]));
        let (l1, l2) = (Lab::new(a[0], a[1], a[2]), Lab::new(b[0], b[1], b[2]));
        let de = ciede2000(l1, l2);
        assert!(
            (de - num(&pair["published"])).abs() <= 5e-5 + 1e-12,
            "pair {}: {de}",
            i + 1
        );
        assert!(
            (de - num(&pair["colour"])).abs() < 1e-9,
            "pair {} vs colour: {de}",
            i + 1
        );
        assert_eq!(de, ciede2000(l2, l1), "pair {} is symmetric", i + 1);
    }
}

/// CCT within 1 K up to 10 000 K (the requirement) against both the true
/// temperature of a blackbody and colour-science's Ohno 2013; above 10 000 K the locus
/// flattens and 1e-4 relative is what either method resolves.
#[test]
fn cct_of_blackbodies_and_daylight() {
    let reference = fixture("colorimetry_reference.json");
    let mut worst: f64 = 0.0;
    for series in ["blackbody", "daylight"] {
        for entry in reference["cct"][series].as_array().unwrap() {
            let kelvin = num(&entry["kelvin"]);
            let uv = nums(&entry["uv"]);
            let got = cct_ohno2013(Uv { u: uv[0], v: uv[1] }).unwrap();
            let colour = num(&entry["ohno2013_cct"]);
            let tolerance = if kelvin <= 10_000.0 {
                1.0
            } else {
                1e-4 * kelvin
            };
            assert!(
                (got.kelvin - colour).abs() < tolerance,
                "{series} {kelvin} K: {got:?} vs colour {colour}"
            );
            if series == "blackbody" {
                assert!(
                    (got.kelvin - kelvin).abs() < tolerance,
                    "{series} {kelvin} K: {got:?}"
                );
                assert!(
                    got.duv.abs() < 1e-6,
                    "a blackbody lies on the locus: {got:?}"
                );
            } else {
                assert!(
                    (got.duv - num(&entry["duv"])).abs() < 1e-5,
                    "{series} {kelvin} K duv {got:?}"
                );
            }
            if kelvin <= 10_000.0 {
                worst = worst.max((got.kelvin - colour).abs());
            }
        }
    }
    eprintln!("worst CCT difference to colour-science up to 10000 K: {worst:.4} K");
}

#[test]
fn daylight_spectra() {
    let reference = fixture("colorimetry_reference.json");
    for (kelvin, entry) in reference["daylight_spd"].as_object().unwrap() {
        let spd = daylight(kelvin.parse().unwrap()).unwrap();
        let first = num(&entry["first_nm"]);
        let step = num(&entry["step_nm"]);
        for (i, expected) in nums(&entry["values"]).iter().enumerate() {
            let l = first + step * i as f64;
            assert!(
                (spd.evaluate(l) - expected).abs() < 1e-9,
                "{kelvin} K at {l} nm"
            );
        }
    }
    // CIE 015: daylight at 6504 K reproduces the tabulated D65 (to its 3 printed decimals).
    let d65 = StandardIlluminant::D65.spectrum();
    let computed = daylight(6500.0 * 1.4388 / 1.4380).unwrap();
    for l in (300..=780).step_by(5).map(f64::from) {
        assert!(
            (d65.evaluate(l) - computed.evaluate(l)).abs() < 0.03,
            "{l} nm"
        );
    }
}

#[test]
fn transfer_functions() {
    let reference = fixture("colorimetry_reference.json");
    let t = &reference["transfer"];
    let xs = nums(&t["x"]);
    for (name, function) in [
        ("srgb_encode", TransferFunction::Srgb),
        ("rec709_oetf", TransferFunction::Rec709),
        ("gamma_2_2_encode", TransferFunction::Gamma(2.2)),
    ] {
        for (x, expected) in xs.iter().zip(nums(&t[name])) {
            let got = function.encode(*x);
            assert!(
                (got - expected).abs() < 1e-9,
                "{name}({x}) = {got}, expected {expected}"
            );
            assert!(
                (function.decode(got) - x).abs() < 1e-12,
                "{name} round trip at {x}"
            );
        }
    }
}

/// Absolute Planck radiance to 1e-12 relative: both sides evaluate the same closed form
/// with the same exact constants.
#[test]
fn planck_absolute_radiance() {
    let reference = fixture("colorimetry_reference.json");
    for entry in reference["planck"].as_array().unwrap() {
        let (t, nm, expected) = (
            num(&entry["kelvin"]),
            num(&entry["nm"]),
            num(&entry["radiance"]),
        );
        let got = planck_radiance(nm * 1e-9, t);
        assert!(
            ((got - expected) / expected).abs() < 1e-12,
            "{t} K, {nm} nm: {got} vs {expected}"
        );
        // The Spectrum form is the same per nm.
        let per_nm = Blackbody::new(t).unwrap().evaluate(nm);
        assert!(((per_nm * 1e9 - expected) / expected).abs() < 1e-12);
    }
}

/// Each space's illuminant is close to its nominal white (the spectrum is what reflectances
/// are seen under; small offsets are inherent in tabulated illuminants).
#[test]
fn space_illuminants_match_their_whites() {
    for id in RgbSpaceId::ALL {
        let xy = emission_xyz(&id.illuminant(), Observer::Cie1931)
            .chromaticity()
            .unwrap();
        let white = id.space().white().xy();
        // The DCI theatrical white is a projector white 0.019 above the daylight locus in
        // y; no CIE illuminant has it, and the daylight stand-in is that far off.
        let tolerance = if id == RgbSpaceId::DciP3 { 2e-2 } else { 1e-3 };
        assert!(
            (xy.x - white.x).abs() < tolerance && (xy.y - white.y).abs() < tolerance,
            "{}: {xy:?} vs {white:?}",
            id.name()
        );
    }
}
