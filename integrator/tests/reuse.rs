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
use prism_scene::medium::{Media, Medium, Phase};
use prism_scene::world::{Light, Material, Scene, SceneParts, SceneSpectrum};
use prism_spectrum::colorimetry::{Observer, emission_xyz};
use prism_spectrum::spectra::{Constant, Extrapolation, PiecewiseLinear};

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
    enclosure_with(rho, Vec::new(), Vec::new())
}

/// The triangles of an axis-aligned cube of half side `half` around `centre`.
fn cube(centre: Vec3, half: f32) -> Vec<[Vec3; 3]> {
    let mut triangles = vec![];
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let point = |u: f32, v: f32| {
                let mut p = [0.0f32; 3];
                p[axis] = sign;
                p[(axis + 1) % 3] = u;
                p[(axis + 2) % 3] = v;
                centre + half * Vec3::from(p)
            };
            triangles.push([point(-1.0, -1.0), point(1.0, -1.0), point(1.0, 1.0)]);
            triangles.push([point(-1.0, -1.0), point(1.0, 1.0), point(-1.0, 1.0)]);
        }
    }
    triangles
}

/// The glowing enclosure with more triangles inside it, of `materials` 1, 2, ...
fn enclosure_with(rho: f32, inside: Vec<([Vec3; 3], u32)>, materials: Vec<Material>) -> Scene {
    let mut triangles = cube(Vec3::ZERO, 1.0);
    let count = triangles.len() as u32;
    let mut triangle_material = vec![0; triangles.len()];
    for (triangle, material) in inside {
        triangles.push(triangle);
        triangle_material.push(material);
    }
    let mut all = vec![Material::Diffuse {
        reflectance: SceneSpectrum::Constant(f64::from(rho)),
    }];
    all.extend(materials);
    Scene::new(SceneParts {
        attributes: Default::default(),
        triangle_material,
        triangles,
        materials: all,
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

/// The glowing enclosure with two cubes of media in it (interfaces holding a scattering
/// medium of albedo 1, sigma_s varying tenfold across the spectrum, Henyey-Greenstein g
/// 0.5, and one that also absorbs and glows as much as it absorbs): neither changes the
/// uniform radiance 1 / (1 - rho).
/// Some pixels see the walls past the cube in vacuum (their paths share second vertices),
/// some through it, and some connections between tiles cross it (they share none): a
/// partition that missed a case, or ratios not one at a shared vertex, would show.
#[test]
fn a_reused_glowing_enclosure_with_a_medium_returns_its_closed_form() {
    let rho = 0.6f32;
    // Cubes of side 0.8 off the centre, each half in the camera's view, one of a
    // scattering medium, one of a medium that absorbs and glows.
    let inside = [
        (Vec3::new(0.45, 0.1, -0.2), 1),
        (Vec3::new(-0.5, -0.5, -0.4), 2),
    ]
    .into_iter()
    .flat_map(|(centre, material)| cube(centre, 0.4).into_iter().map(move |t| (t, material)))
    .collect();
    let mut scene = enclosure_with(rho, inside, vec![Material::Interface, Material::Interface]);
    let sigma_s = SceneSpectrum::Table(std::sync::Arc::new(
        PiecewiseLinear::new(vec![400.0, 700.0], vec![0.5, 5.0], Extrapolation::Clamp).unwrap(),
    ));
    let radiance = 1.0 / (1.0 - f64::from(rho));
    let scattering = Medium::new(
        SceneSpectrum::Constant(0.0),
        sigma_s.clone(),
        Phase::henyey_greenstein(0.5).unwrap(),
        None,
    )
    .unwrap();
    // Absorbing red light strongly and blue light hardly (a chromatic transmittance that
    // a shared vertex reached through it would get wrong), and glowing as much as it
    // absorbs of the uniform radiance (Kirchhoff).
    let table = |scale: f64| {
        SceneSpectrum::Table(std::sync::Arc::new(
            PiecewiseLinear::new(
                vec![500.0, 600.0],
                vec![0.05 * scale, 8.0 * scale],
                Extrapolation::Clamp,
            )
            .unwrap(),
        ))
    };
    let glowing = Medium::new(
        table(1.0),
        SceneSpectrum::Constant(0.0),
        Phase::henyey_greenstein(0.0).unwrap(),
        Some(table(radiance)),
    )
    .unwrap();
    scene
        .set_media(
            Media::new(
                vec![scattering, glowing],
                vec![None, Some(0), Some(1)],
                None,
            )
            .unwrap(),
        )
        .unwrap();
    let expected = emission_xyz(&Constant::new(radiance).unwrap(), Observer::Cie1931).to_array();
    for reuse in [1, 2, 4] {
        let s = settings(16, 256, reuse);
        assert_eq!(Renderer::new(&scene, &s).unwrap().reuse(), reuse);
        let (film, stats) = render(&scene, &s).unwrap();
        assert_eq!(stats.nonfinite, 0);
        assert_image_mean(&film, expected, &format!("medium, reuse {reuse}"));
    }
}

/// The Cornell box with a block of chromatic scattering medium (scenes/cornell-medium.gltf):
/// reused and plain paths agree block by block, and reuse lowers the error of the walls.
#[test]
fn reused_paths_with_media_estimate_the_plain_image() {
    let scene = repository_scene("cornell-medium.gltf", |_| {});
    assert!(scene.features().media);
    assert_reuse_agrees_with_plain(&scene, 8, 900, &[2, 4], "media");
}

/// Renders `scene` at 16 x 16 and `spp` under eight seeds from `seed`, plainly and with
/// each of `tiles`, and asserts that their 4 x 4 blocks agree within five standard errors.
fn assert_reuse_agrees_with_plain(scene: &Scene, spp: u64, seed: u64, tiles: &[u32], what: &str) {
    let statistics =
        |reuse: u32| block_statistics(scene, |s| settings(16, spp, reuse).seed(seed + s));
    let plain = statistics(1);
    for &reuse in tiles {
        assert_blocks_agree(
            &plain,
            &statistics(reuse),
            &format!("{what}: plain and reuse {reuse}"),
        );
    }
}

/// Rough plastics' first vertices gather their tiles' second vertices with their own
/// densities (both lobes): a cube of rough blue plastic (GGX alpha 0.05, 0.3) in the
/// glowing enclosure, most of the view, renders the same blocks reused and plain, and so
/// does the plastic box (scenes/cornell-plastic.gltf, whose smooth plastic does not share).
#[test]
fn reused_paths_from_plastic_estimate_the_plain_image() {
    for alpha in [0.05f32, 0.3] {
        let inside = cube(Vec3::new(0.1, -0.2, -0.3), 0.5)
            .into_iter()
            .map(|t| (t, 1))
            .collect();
        let plastic = Material::Plastic {
            reflectance: SceneSpectrum::Table(std::sync::Arc::new(
                PiecewiseLinear::new(vec![450.0, 600.0], vec![0.8, 0.1], Extrapolation::Clamp)
                    .unwrap(),
            )),
            nonlinear: false,
            coating: std::sync::Arc::new(prism_scene::bsdf::PlasticCoating::new(1.5, alpha)),
        };
        let scene = enclosure_with(0.6, inside, vec![plastic]);
        let what = format!("plastic alpha {alpha}");
        assert_reuse_agrees_with_plain(&scene, 32, 1100, &[2, 4], &what);
    }
    let scene = repository_scene("cornell-plastic.gltf", |_| {});
    assert_reuse_agrees_with_plain(&scene, 8, 1200, &[4], "plastic box");
}

/// Reused and plain paths estimate the same image: the Cornell box's 4 x 4 blocks agree,
/// each within five standard errors (over eight seeds of each) of the other.
#[test]
fn reused_paths_estimate_the_plain_image() {
    assert_reuse_agrees_with_plain(&cornell(), 8, 700, &[2, 3], "Cornell box");
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
/// Lambertian surfaces (the Cornell box, the medium box) and not where it is in what the
/// camera ray finds (the textured scene); renders report it.
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
    // The medium box's walls are lit through and beside its medium: reuse pays there too
    // (its gathers counted at what they cost, a third of a path's ray).
    assert!(auto(&repository_scene("cornell-medium.gltf", |_| {})).1 > 1);
    let (_, stats) = render(
        &box_,
        &RenderSettings::default().width(64).height(64).samples(0..1),
    )
    .unwrap();
    assert_eq!((stats.splits, stats.reuse), (1, 4));
}

/// A render that samples adaptively shares vertices in tiles of four wherever the pilot
/// chooses reuse (with adaptive sampling's spread, four measured better than two where the
/// uniform pilot chose two: docs/trade-offs.md, "Path reuse across tiles of pixels");
/// without it, the pilot still chooses between two and four.
#[test]
fn adaptive_renders_reuse_in_the_widest_tiles() {
    let medium = repository_scene("cornell-medium.gltf", |_| {});
    let choice = |adaptive: bool| {
        let s = RenderSettings::default()
            .width(32)
            .height(32)
            .samples(0..16)
            .adaptive(adaptive);
        let r = Renderer::new(&medium, &s).unwrap();
        assert_eq!(r.adaptive(), adaptive);
        (r.splits(), r.reuse())
    };
    assert_eq!(choice(false), (1, 2));
    assert_eq!(choice(true), (1, 4));
}

/// With adaptive sampling reuse also wins by a wider margin over continuations: the
/// glossy box's pilot splits a uniform render in two and reuses in an adaptive one; the
/// textured scene, where nothing is shared, reuses in neither.
#[test]
fn adaptive_renders_reuse_by_a_wider_margin() {
    let choice = |scene: &Scene, adaptive: bool| {
        let s = RenderSettings::default()
            .width(32)
            .height(32)
            .samples(0..16)
            .adaptive(adaptive);
        let r = Renderer::new(scene, &s).unwrap();
        (r.splits(), r.reuse())
    };
    let glossy = repository_scene("cornell-glossy.gltf", |_| {});
    assert_eq!(choice(&glossy, false), (2, 1));
    assert_eq!(choice(&glossy, true), (1, 4));
    let textured = repository_scene("textured.gltf", |_| {});
    assert_eq!(choice(&textured, true), (1, 1));
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
