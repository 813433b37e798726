//! Images hold finite values even where the film's f64 sums exceed f32's range: a light of
//! radiance near f32::MAX renders without non-finite pixels in any channel.

mod common;

use prism_integrator::{
    DisplaySettings, ExrMetadata, Film, RenderSettings, SpectralBands, decode_exr, encode_exr,
    encode_png, render,
};
use prism_scene::world::SceneSpectrum;
use prism_spectrum::color::RgbSpaceId;

fn assert_finite_exr(film: &Film) -> Vec<(String, Vec<f32>)> {
    let space = RgbSpaceId::Srgb.space();
    let exr = encode_exr(film, space, &ExrMetadata::default()).unwrap();
    let decoded = decode_exr(&exr).unwrap();
    for (name, values) in &decoded.channels {
        assert!(
            values.iter().all(|v| v.is_finite()),
            "channel {name} holds a non-finite value"
        );
    }
    let _ = encode_png(film, space, DisplaySettings::default());
    decoded.channels
}

#[test]
fn sums_past_f32_saturate_instead_of_becoming_infinite() {
    let film =
        Film::from_parts(2, 1, vec![[1e300, 1e300, 1e300], [-1e300, 0.0, 1.0]], 1, 0).unwrap();
    let channels = assert_finite_exr(&film);
    let red = &channels.iter().find(|(n, _)| n == "R").unwrap().1;
    // Pixel 0 is XYZ (1e300, 1e300, 1e300): its red saturates; pixel 1's X of -1e300 too.
    assert_eq!(red[0].abs(), f32::MAX);
    assert_eq!(red[1].abs(), f32::MAX);
}

#[test]
fn a_light_near_f32_max_renders_finite_in_every_channel() {
    let scene = common::emitter_filling_the_view(SceneSpectrum::Constant(3e38));
    let settings = RenderSettings::default()
        .width(4)
        .height(4)
        .samples(0..4)
        .bands(Some(SpectralBands::new(400.0, 700.0, 4).unwrap()))
        .energy(true);
    let (film, _) = render(&scene, &settings).unwrap();
    assert_finite_exr(&film);
}
