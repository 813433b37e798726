//! Accumulation files: lossless round trip, clear errors for anything else, and merging
//! sample ranges into the film of the whole range.

mod common;

use common::cornell;
use prism_integrator::{
    RenderSettings, decode_accumulation, encode_accumulation, merge_accumulations, render,
};

fn part(range: std::ops::Range<u64>) -> prism_integrator::Accumulation {
    let settings = RenderSettings {
        width: 10,
        height: 6,
        samples: range.clone(),
        ..RenderSettings::default()
    };
    let (film, _) = render(&cornell(), &settings).unwrap();
    decode_accumulation(&encode_accumulation(&film, range, "box; seed=0").unwrap()).unwrap()
}

#[test]
fn round_trip_is_lossless() {
    let settings = RenderSettings {
        width: 7,
        height: 5,
        samples: 3..5,
        ..RenderSettings::default()
    };
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
}

#[test]
fn anything_else_is_an_error_not_a_panic() {
    let settings = RenderSettings {
        width: 4,
        height: 4,
        samples: 0..1,
        ..RenderSettings::default()
    };
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
