//! Adaptive sampling (`RenderSettings::adaptive`): the samples spread by a pilot leave the
//! image unbiased (the blocks of a box agree with a uniform render's, with and without
//! path reuse, and with light paths), the image still depends only on scene, settings and
//! seed, and renders that cannot be spread are left uniform.

mod common;

use common::{assert_blocks_agree, block_statistics, cornell, repository_scene};
use prism_integrator::{Aov, Aovs, RenderSettings, Reuse, Splits, render};

fn settings(size: u32, spp: u64, reuse: u32, adaptive: bool) -> RenderSettings {
    RenderSettings::default()
        .width(size)
        .height(size)
        .samples(0..spp)
        .splits(Splits::Fixed(1))
        .reuse(Reuse::Fixed(reuse))
        .adaptive(adaptive)
}

/// Spread and uniform samples estimate the same image: the Cornell box's 4 x 4 blocks
/// agree within five standard errors (eight seeds each), with each pixel's own paths and
/// with paths sharing second vertices in tiles of two. A tile's samples weighted by
/// anything but 4 / count, or a pilot's sample kept in the image, would shift the blocks
/// where the rates differ.
#[test]
fn spread_samples_estimate_the_uniform_image() {
    let scene = cornell();
    for reuse in [1, 2] {
        let statistics = |adaptive: bool| {
            block_statistics(&scene, |seed| {
                settings(16, 16, reuse, adaptive).seed(700 + seed)
            })
        };
        assert_blocks_agree(
            &statistics(false),
            &statistics(true),
            &format!("uniform and adaptive, reuse {reuse}"),
        );
    }
}

/// The same with light paths (the caustic box: glass, a small light), whose splats are
/// not spread and must keep their own weight.
#[test]
fn spread_samples_keep_light_paths_unbiased() {
    let scene = repository_scene("cornell-caustic.gltf", |_| {});
    let statistics = |adaptive: bool| {
        block_statistics(&scene, |seed| {
            settings(16, 16, 1, adaptive).seed(900 + seed)
        })
    };
    assert_blocks_agree(
        &statistics(false),
        &statistics(true),
        "caustic box, uniform and adaptive",
    );
}

/// The map differs from uniform where the error does, and the render is the same on one
/// thread or two.
#[test]
fn adaptive_renders_are_deterministic() {
    let scene = repository_scene("cornell-specular.gltf", |_| {});
    let s = settings(16, 16, 1, true);
    let (a, stats) = render(&scene, &s.clone().threads(1)).unwrap();
    assert!(stats.adaptive);
    let (b, _) = render(&scene, &s.clone().threads(2)).unwrap();
    assert_eq!(a.sums(), b.sums());
    let (uniform, stats) = render(&scene, &s.clone().adaptive(false)).unwrap();
    assert!(!stats.adaptive);
    assert_ne!(a.sums(), uniform.sums());
}

/// Renders whose samples cannot be spread stay uniform, image for image: fewer than 16
/// samples, a count that is not whole groups of 4, a range that does not start at 0 (a
/// farm's piece) and the variance AOV.
#[test]
fn renders_that_cannot_be_spread_stay_uniform() {
    let scene = cornell();
    let cases = [
        settings(8, 12, 1, true),
        settings(8, 18, 1, true),
        settings(8, 16, 1, true).samples(4..20),
        settings(8, 16, 1, true).aovs(Aovs::NONE.with(Aov::Variance)),
    ];
    for (i, s) in cases.into_iter().enumerate() {
        let (a, stats) = render(&scene, &s).unwrap();
        assert!(!stats.adaptive, "case {i}");
        let (b, _) = render(&scene, &s.adaptive(false)).unwrap();
        assert_eq!(a.sums(), b.sums(), "case {i}");
    }
}
