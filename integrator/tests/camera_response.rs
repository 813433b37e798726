//! Cameras with their own response curves: a near-infrared camera sees a blackbody's
//! infrared as the integral of the spectrum against each curve, sampled over the curves'
//! band; malformed response files are errors.

mod common;

use std::sync::Arc;

use prism_integrator::{CameraResponse, LambdaSampler, RenderSettings, render};
use prism_scene::world::SceneSpectrum;
use prism_spectrum::Spectrum;
use prism_spectrum::spectra::Blackbody;

fn nir_camera() -> CameraResponse {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes/nir-camera.csv"),
    )
    .unwrap();
    CameraResponse::from_csv(&text).unwrap()
}

#[test]
fn a_near_infrared_camera_integrates_its_curves() {
    let camera = Arc::new(nir_camera());
    assert_eq!(camera.range(), (700.0, 1000.0));
    let blackbody = Blackbody::normalized(3000.0).unwrap();
    let scene = common::emitter_filling_the_view(SceneSpectrum::Blackbody(blackbody));
    // Expected channels by fine quadrature over the curves' band.
    let expected: [f64; 3] = std::array::from_fn(|k| {
        let n = 30_000;
        let h = 300.0 / f64::from(n);
        (0..n)
            .map(|i| {
                let l = 700.0 + (f64::from(i) + 0.5) * h;
                blackbody.evaluate(l) * camera.response(l)[k] * h
            })
            .sum()
    });
    for sampler in [LambdaSampler::Response, LambdaSampler::Uniform] {
        let settings = RenderSettings::default()
            .width(8)
            .height(8)
            .samples(0..64)
            .lambda_sampler(sampler)
            .range(camera.range())
            .camera(Some(camera.clone()));
        let (film, _) = render(&scene, &settings).unwrap();
        assert!(film.is_raw());
        let rgb = film.to_rgb(prism_spectrum::color::RgbSpaceId::Srgb.space());
        for k in 0..3 {
            let mean = rgb.iter().map(|p| f64::from(p[k])).sum::<f64>() / rgb.len() as f64;
            assert!(
                (mean - expected[k]).abs() < 0.02 * expected[k],
                "{sampler:?} channel {k}: {mean} vs {}",
                expected[k]
            );
        }
    }
}

#[test]
fn malformed_response_files_are_errors() {
    for (text, expected) in [
        ("nm,r,g,b\n", "at least two rows"),
        ("700,1,1,1\n", "at least two rows"),
        ("700,1,1\n800,1,1\n", "four numbers"),
        ("700,1,1,1\n800,-1,1,1\n", "finite and >= 0"),
        ("700,0,0,0\n800,0,0,0\n", "every response is zero"),
        ("800,1,1,1\n700,1,1,1\n", "camera response"),
        ("700,1,1,1\nx,1,1,1\n", "line 2"),
    ] {
        let e = CameraResponse::from_csv(text).expect_err(text).to_string();
        assert!(e.contains(expected), "{text:?}: {e}");
    }
    // Headers, comments and whitespace separators are fine.
    assert!(CameraResponse::from_csv("# a camera\nnm r g b\n700 1 0 0\n800 0 1 0 # end\n").is_ok());
}
