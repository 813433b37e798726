//! Accumulation files: lossless round trip, clear errors for anything else, and merging
//! sample ranges into the film of the whole range.

mod common;

use common::cornell;
use prism_integrator::{
    RenderSettings, SpectralBands, decode_accumulation, encode_accumulation, merge_accumulations,
    render,
};

fn part(range: std::ops::Range<u64>) -> prism_integrator::Accumulation {
    let settings = RenderSettings::default()
        .width(10)
        .height(6)
        .samples(range.clone());
    let (film, _) = render(&cornell(), &settings).unwrap();
    decode_accumulation(&encode_accumulation(&film, range, "box; seed=0").unwrap()).unwrap()
}

#[test]
fn round_trip_is_lossless() {
    let settings = RenderSettings::default().width(7).height(5).samples(3..5);
    let (film, _) = render(&cornell(), &settings).unwrap();
    let back = decode_accumulation(&encode_accumulation(&film, 3..5, "a;b=c").unwrap()).unwrap();
    assert_eq!(back.film, film, "every f64 bit survives");
    assert_eq!(back.samples, 3..5);
    assert_eq!(
        back.settings, "a;b=c",
        "settings survive, separators and all"
    );
}

#[test]
fn merged_ranges_equal_the_whole_render() {
    let whole = part(0..5);
    // Given out of order; merged in sample order.
    let merged = merge_accumulations(&[part(3..5), part(0..1), part(1..3)]).unwrap();
    assert_eq!(merged.samples, 0..5);
    assert_eq!(merged.film.samples(), 5);
    for (a, b) in merged.film.sums().iter().zip(whole.film.sums()) {
        for k in 0..3 {
            // The same samples summed in another grouping: equal to rounding.
            assert!(
                (a[k] - b[k]).abs() <= 1e-12 * b[k].abs().max(1e-30),
                "{a:?} {b:?}"
            );
        }
    }
    let e = merge_accumulations(&[part(0..3), part(2..4)]).unwrap_err();
    assert!(e.to_string().contains("overlap"), "{e}");
    assert!(merge_accumulations(&[]).is_err());
    let mut other = part(5..6);
    other.settings = "bunny".into();
    let e = merge_accumulations(&[part(0..1), other]).unwrap_err();
    assert!(e.to_string().contains("different settings"), "{e}");
    // Records of key=value entries name only what differs.
    let mut a = part(0..1);
    a.settings = "scene=box.gltf;size=8x8;seed=0".into();
    let mut b = part(1..2);
    b.settings = "scene=box.gltf;size=16x8;seed=0;energy=true".into();
    let e = merge_accumulations(&[a, b]).unwrap_err().to_string();
    assert!(
        e.ends_with("different settings: size 8x8 vs 16x8, energy none vs true"),
        "{e}"
    );
}

#[test]
fn anything_else_is_an_error_not_a_panic() {
    let settings = RenderSettings::default().width(4).height(4).samples(0..1);
    let (film, _) = render(&cornell(), &settings).unwrap();
    let good = encode_accumulation(&film, 0..1, "").unwrap();
    // An ordinary RGB EXR is not an accumulation file.
    let rgb = prism_integrator::encode_exr(
        &film,
        prism_spectrum::color::RgbSpaceId::Srgb.space(),
        &Default::default(),
    )
    .unwrap();
    assert!(decode_accumulation(&rgb).is_err());
    assert!(decode_accumulation(b"not an exr").is_err());
    assert!(decode_accumulation(&[]).is_err());
    for cut in [8, good.len() / 2, good.len() - 1] {
        assert!(
            decode_accumulation(&good[..cut]).is_err(),
            "truncated at {cut}"
        );
    }
    // Flipped bytes anywhere: an error or a valid film, never a panic.
    for i in (0..good.len()).step_by(7) {
        let mut bad = good.clone();
        bad[i] ^= 0x5A;
        let _ = decode_accumulation(&bad);
    }
}

/// A spectral render that records energy: what `--spectral-bands` and `--energy` make.
fn spectral_settings(samples: std::ops::Range<u64>) -> RenderSettings {
    RenderSettings::default()
        .width(6)
        .height(4)
        .samples(samples)
        .bands(Some(SpectralBands::new(380.0, 780.5, 7).unwrap()))
        .energy(true)
}

#[test]
fn spectral_energy_and_raw_films_round_trip_and_merge() {
    let scene = cornell();
    let render_part = |range: std::ops::Range<u64>| {
        let (film, _) = render(&scene, &spectral_settings(range.clone())).unwrap();
        let bytes = encode_accumulation(&film, range, "s").unwrap();
        (film, decode_accumulation(&bytes).unwrap())
    };
    let (film, back) = render_part(0..3);
    assert!(film.bands().is_some() && film.has_energy());
    assert_eq!(
        back.film, film,
        "bands, spectral and energy sums survive bit for bit"
    );

    // Merged ranges equal the whole render in every band and in energy.
    let (whole, _) = render_part(0..5);
    let merged = merge_accumulations(&[render_part(3..5).1, back]).unwrap();
    assert_eq!(merged.film.bands(), whole.bands());
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1e-30);
    for y in 0..whole.height() {
        for x in 0..whole.width() {
            let (m, w) = (
                merged.film.spectrum(x, y).unwrap(),
                whole.spectrum(x, y).unwrap(),
            );
            assert!(m.iter().zip(&w).all(|(a, b)| close(*a, *b)), "{m:?} {w:?}");
            let (m, w) = (
                merged.film.energy(x, y).unwrap(),
                whole.energy(x, y).unwrap(),
            );
            assert!(close(m[0], w[0]) && close(m[1], w[1]), "{m:?} {w:?}");
        }
    }

    // A camera's raw channels stay raw, and do not merge with XYZ.
    let raw = film.clone().with_raw_channels();
    let raw_back = decode_accumulation(&encode_accumulation(&raw, 3..5, "s").unwrap()).unwrap();
    assert!(raw_back.film.is_raw());
    assert_eq!(raw_back.film, raw);
    let (xyz, _) = render_part(5..6);
    let e = merge_accumulations(&[
        raw_back,
        decode_accumulation(&encode_accumulation(&xyz, 5..6, "s").unwrap()).unwrap(),
    ])
    .unwrap_err();
    assert!(e.to_string().contains("raw"), "{e}");

    // Parts with other bands do not merge.
    let other = spectral_settings(6..7).bands(Some(SpectralBands::new(380.0, 780.5, 8).unwrap()));
    let (film8, _) = render(&scene, &other).unwrap();
    let e = merge_accumulations(&[
        render_part(0..1).1,
        decode_accumulation(&encode_accumulation(&film8, 6..7, "s").unwrap()).unwrap(),
    ])
    .unwrap_err();
    assert!(e.to_string().contains("bands"), "{e}");
}

#[test]
fn spectral_files_with_missing_or_broken_parts_are_errors() {
    let (film, _) = render(&cornell(), &spectral_settings(0..1)).unwrap();
    let good = encode_accumulation(&film, 0..1, "").unwrap();
    assert!(decode_accumulation(&good).is_ok());
    for cut in [good.len() / 3, good.len() - 9] {
        assert!(
            decode_accumulation(&good[..cut]).is_err(),
            "truncated at {cut}"
        );
    }
    for i in (0..good.len()).step_by(5) {
        let mut bad = good.clone();
        bad[i] ^= 0xA5;
        let _ = decode_accumulation(&bad);
    }
}
