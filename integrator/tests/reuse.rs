//! Path reuse across tiles of pixels: the estimate stays unbiased (a closed glowing
//! enclosure returns its closed form, the Cornell box's blocks agree with plain paths'),
//! the shared continuations lower the error, the image still depends only on scene,
//! settings and seed, and renders that cannot share second vertices are left alone.

#![allow(clippy::needless_range_loop)]

mod common;

use common::{
    assert_blocks_agree, assert_deterministic_and_merges, assert_image_mean, block_statistics,
    cornell, ortho_camera, relative_mse, repository_scene,
};
use glam::Vec3;
use prism_integrator::{RenderSettings, Renderer, Reuse, Splits, render};
use prism_scene::geometry::BvhQuality;
use prism_scene::world::{Light, Material, Scene, SceneParts, SceneSpectrum};
use prism_spectrum::colorimetry::{Observer, emission_xyz};
use prism_spectrum::spectra::Constant;

fn settings(size: u32, spp: u64, reuse: u32) -> RenderSettings {
    RenderSettings::default()
        .width(size)
        .height(size)
        .samples(0..spp)
        .splits(Splits::Fixed(1))
        .reuse(Reuse::Fixed(reuse))
}

/// The inside of a closed cube whose every wall is Lambertian of reflectance `rho` and
/// glows with radiance 1 from both faces, seen by an orthographic camera inside it: the
/// radiance is 1 / (1 - rho) everywhere (the Neumann series of a uniform enclosure), and
/// every second vertex of every path is one that reuse shares.
fn glowing_enclosure(rho: f32) -> Scene {
    let corners = |x: f32, y: f32, z: f32| Vec3::new(x, y, z);
    let mut triangles = vec![];
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let point = |u: f32, v: f32| {
                let mut p = [0.0f32; 3];
                p[axis] = sign;
                p[(axis + 1) % 3] = u;
                p[(axis + 2) % 3] = v;
                corners(p[0], p[1], p[2])
            };
            triangles.push([point(-1.0, -1.0), point(1.0, -1.0), point(1.0, 1.0)]);
            triangles.push([point(-1.0, -1.0), point(1.0, 1.0), point(-1.0, 1.0)]);
        }
    }
    let count = triangles.len() as u32;
    Scene::new(SceneParts {
        attributes: Default::default(),
        triangle_material: vec![0; triangles.len()],
        triangles,
        materials: vec![Material::Diffuse {
            reflectance: SceneSpectrum::Constant(f64::from(rho)),
        }],
        emission: vec![SceneSpectrum::Constant(1.0)],
        lights: (0..count)
            .map(|triangle| Light::Triangle {
                triangle,
                emission: 0,
                two_sided: true,
            })
            .collect(),
        camera: ortho_camera(Vec3::new(0.1, -0.2, 0.5), 0.6),
        quality: BvhQuality::Medium,
    })
    .unwrap()
}

/// Every pixel of the enclosure estimates 1 / (1 - rho) with reuse of any tile size: a
/// weight that did not sum to one over the techniques, a second vertex counted from its
/// hidden side, or its own emission shared, would show at once. Tiles that do not divide
/// the image (3 of 10) and the depth limits that stop at the second vertex are included.
#[test]
fn a_reused_glowing_enclosure_returns_its_closed_form() {
    for rho in [0.5f32, 0.8] {
        let scene = glowing_enclosure(rho);
        let expected = emission_xyz(
            &Constant::new(1.0 / (1.0 - f64::from(rho))).unwrap(),
            Observer::Cie1931,
        )
        .to_array();
        for reuse in [1, 2, 3, 4] {
            let s = settings(10, 64, reuse);
            let renderer = Renderer::new(&scene, &s).unwrap();
            assert_eq!(renderer.reuse(), reuse);
            let (film, stats) = render(&scene, &s).unwrap();
            assert_eq!(stats.nonfinite, 0);
            assert_image_mean(&film, expected, &format!("rho {rho} reuse {reuse}"));
        }
        // One bounce: emission seen directly, and the first vertex's light only.
        let one = emission_xyz(
            &Constant::new(1.0 + f64::from(rho)).unwrap(),
            Observer::Cie1931,
        )
        .to_array();
        let (film, _) = render(&scene, &settings(10, 64, 3).max_depth(Some(1))).unwrap();
        assert_image_mean(&film, one, &format!("rho {rho} depth 1"));
    }
}

/// Reused and plain paths estimate the same image: the Cornell box's 4 x 4 blocks agree,
/// each within five standard errors (over eight seeds of each) of the other.
#[test]
fn reused_paths_estimate_the_plain_image() {
    let scene = cornell();
    let statistics =
        |reuse: u32| block_statistics(&scene, |seed| settings(16, 8, reuse).seed(700 + seed));
    let plain = statistics(1);
    for reuse in [2, 3] {
        assert_blocks_agree(
            &plain,
            &statistics(reuse),
            &format!("plain and reuse {reuse}"),
        );
    }
}

/// Each pixel gathers its tile's continuations: at 8 samples per pixel, tiles of four
/// lower the Cornell box's error against a converged image to a fraction of the plain
/// error (measured 0.13x; sharing nothing, or sharing one pixel's path with all, would
/// leave it near 1x).
#[test]
fn reuse_lowers_the_error() {
    let scene = cornell();
    let (reference, _) = render(&scene, &settings(16, 1024, 1).seed(99)).unwrap();
    let (plain, _) = render(&scene, &settings(16, 8, 1)).unwrap();
    let (shared, _) = render(&scene, &settings(16, 8, 4)).unwrap();
    let (e1, e4) = (
        relative_mse(&plain, &reference),
        relative_mse(&shared, &reference),
    );
    assert!(e4 < 0.4 * e1, "reuse {e4} vs plain {e1}");
}

/// Threads and sample ranges do not change a reused render.
#[test]
fn reused_renders_are_deterministic_and_merge() {
    assert_deterministic_and_merges(&cornell(), &settings(13, 6, 3));
}

/// The automatic choice shares second vertices where the error is in indirect light on
/// Lambertian surfaces (the Cornell box) and not where it is in what the camera ray finds
/// (the textured scene); renders report it.
#[test]
fn auto_reuses_where_indirect_light_dominates() {
    let auto = |scene: &Scene| {
        let s = RenderSettings::default().width(64).height(64).samples(0..4);
        let r = Renderer::new(scene, &s).unwrap();
        (r.splits(), r.reuse())
    };
    let box_ = cornell();
    assert_eq!(auto(&box_), (1, 4));
    assert_eq!(auto(&repository_scene("textured.gltf", |_| {})).1, 1);
    let (_, stats) = render(
        &box_,
        &RenderSettings::default().width(64).height(64).samples(0..1),
    )
    .unwrap();
    assert_eq!((stats.splits, stats.reuse), (1, 4));
}

/// Renders whose paths cannot share second vertices render without: polarized paths
/// (their Stokes vectors depend on the direction to the eye), timed ones, and scenes with
/// fluorescence.
#[test]
fn unsupported_renders_do_not_reuse() {
    let box_ = cornell();
    let polarized = settings(8, 1, 4).polarized(true);
    assert_eq!(Renderer::new(&box_, &polarized).unwrap().reuse(), 1);
    let timed = settings(8, 1, 4).at(Some(0.0));
    assert_eq!(Renderer::new(&box_, &timed).unwrap().reuse(), 1);
    let spectral = repository_scene("cornell-spectral.gltf", |_| {});
    assert!(spectral.features().fluorescence);
    assert_eq!(
        Renderer::new(&spectral, &settings(8, 1, 4))
            .unwrap()
            .reuse(),
        1
    );
}

/// Tile sides outside 1..=8, and reuse together with splitting, are refused with a
/// message naming them.
#[test]
fn bad_reuse_settings_are_refused() {
    for bad in [0, 9, u32::MAX] {
        let e = settings(4, 1, bad).validate().unwrap_err().to_string();
        assert!(e.contains("reuse"), "{e}");
    }
    assert!(settings(4, 1, 8).validate().is_ok());
    let both = settings(4, 1, 2).splits(Splits::Fixed(2));
    let e = both.validate().unwrap_err().to_string();
    assert!(e.contains("reuse") && e.contains("splits"), "{e}");
}
