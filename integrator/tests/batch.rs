//! The batch tracer (`Tracing::Lanes`, issue 30): neighbouring pixels' paths in lanes
//! render the path tracer's image to the bit, at every lane width and with every setting
//! and material it serves (Lambertian vertices lane-wide; glass, metals, the glTF
//! materials, fluorescence, phosphors lane by lane), stay unbiased where the answer is
//! known in closed form, and refuse what they do not serve with an error rather than a
//! different image.

mod common;

use common::{assert_image_mean, cornell, furnace_scene, repository_scene};
use prism_integrator::{RenderSettings, Renderer, Reuse, Splits, Tracing, render};
use prism_spectrum::colorimetry::{Observer, emission_xyz};
use prism_spectrum::spectra::Constant;

fn settings(width: u32, height: u32, spp: u64) -> RenderSettings {
    RenderSettings::default()
        .width(width)
        .height(height)
        .samples(0..spp)
        .splits(Splits::Fixed(1))
        .reuse(Reuse::Fixed(1))
}

/// Every width, and the CPU's, against the path tracer: the films' sums to the bit and
/// the same rays. The image's width (37) is no multiple of a lane width, so the last
/// batch of each row runs with lanes empty.
#[test]
fn lanes_render_the_path_tracers_image() {
    let scene = cornell();
    let variants: Vec<(&str, RenderSettings)> = vec![
        ("default", settings(37, 23, 3)),
        ("transparent", settings(37, 23, 2).transparent(true)),
        ("depth 2", settings(37, 23, 2).max_depth(Some(2))),
        ("depth 0", settings(37, 23, 1).max_depth(Some(0))),
        ("4 wavelengths", settings(37, 23, 2).wavelengths(4)),
        ("16 wavelengths", settings(37, 23, 2).wavelengths(16)),
        ("energy", settings(37, 23, 2).energy(true)),
        ("samples 5..7", settings(37, 23, 0).samples(5..7).seed(11)),
    ];
    assert_lanes_match(&scene, variants);
}

/// The effects stage (dispersive glass, metals, a fluorescent and a phosphorescent
/// material, glTF materials, light paths for its caustics): the vertices the lanes handle
/// alone, a package of wavelengths split at dispersion, re-radiated wavelengths, an
/// instant and an exposure on the scene's clock.
#[test]
fn lanes_render_the_path_tracers_effects_stage() {
    let scene = repository_scene("effects.gltf", |_| {});
    assert_lanes_match(
        &scene,
        vec![
            ("effects", settings(32, 24, 6)),
            ("effects at 0.5 s", settings(21, 15, 1).at(Some(0.5))),
            (
                "effects, shutter",
                settings(21, 15, 1).shutter(Some((0.0, 2.0))),
            ),
        ],
    );
}

/// Renders each of `variants` with the path tracer and with the lanes at every width,
/// asserting equal films to the bit and equal counts.
fn assert_lanes_match(scene: &prism_scene::world::Scene, variants: Vec<(&str, RenderSettings)>) {
    for (what, paths) in variants {
        let (reference, reference_stats) = render(scene, &paths).unwrap();
        for width in [None, Some(4), Some(8), Some(16)] {
            let lanes = paths.clone().tracing(Tracing::Lanes(width));
            let (film, stats) = render(scene, &lanes).unwrap();
            let bits = |f: &prism_integrator::Film| -> Vec<[u64; 3]> {
                f.sums().iter().map(|s| s.map(f64::to_bits)).collect()
            };
            assert!(
                bits(&film) == bits(&reference),
                "{what}, {width:?} lanes: the film differs from the path tracer's"
            );
            assert_eq!(film, reference, "{what}, {width:?} lanes");
            assert_eq!(
                stats.estimators.tracer,
                prism_integrator::TracerKind::Lanes(width)
            );
            // The counts are the path tracer's; only the tracer named differs.
            let counts = prism_integrator::RenderStats {
                estimators: reference_stats.estimators,
                ..stats
            };
            assert_eq!(counts, reference_stats, "{what}, {width:?} lanes");
        }
    }
}

/// A white Lambertian sphere in a uniform environment of radiance 1 (a furnace): every
/// pixel sees radiance 1, which the lanes' paths must return whatever their depth.
#[test]
fn lanes_return_the_white_furnace() {
    let scene = furnace_scene();
    let expected = emission_xyz(&Constant::new(1.0).unwrap(), Observer::Cie1931).to_array();
    for width in [Some(4), Some(16)] {
        let lanes = settings(12, 12, 32).tracing(Tracing::Lanes(width));
        let (film, stats) = render(&scene, &lanes).unwrap();
        assert_eq!(stats.nonfinite, 0);
        assert_image_mean(&film, expected, &format!("{width:?} lanes"));
    }
}

/// What the batch tracer does not serve is an error naming why, never a render by the
/// path tracer under its name or a different image.
#[test]
fn lanes_refuse_what_they_do_not_serve() {
    let refusal = |scene: &prism_scene::world::Scene, settings: &RenderSettings| match Renderer::new(
        scene, settings,
    ) {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    };
    let lanes = settings(8, 8, 1).tracing(Tracing::Lanes(None));
    let scene = cornell();
    let split = lanes.clone().splits(Splits::Fixed(2));
    assert!(refusal(&scene, &split).contains("unsplit"));
    let reuse = lanes.clone().reuse(Reuse::Fixed(2));
    assert!(refusal(&scene, &reuse).contains("reuse"));
    assert!(refusal(&scene, &lanes.clone().polarized(true)).contains("polarization"));
    assert!(refusal(&scene, &lanes.clone().wavelengths(2)).contains("4, 8 or 16"));
    let odd = lanes.clone().tracing(Tracing::Lanes(Some(5)));
    assert!(refusal(&scene, &odd).contains("4, 8 or 16"));
    // Left to choose, splitting and reuse are off: the render is the unsplit one.
    let auto = settings(16, 16, 2)
        .splits(Splits::Auto)
        .reuse(Reuse::Auto)
        .tracing(Tracing::Lanes(None));
    let renderer = Renderer::new(&scene, &auto).unwrap();
    assert_eq!((renderer.splits(), renderer.reuse()), (1, 1));
}
