//! Environment images lighting scenes: a furnace (a white sphere in a constant image is
//! invisible, and the image means what `--environment` of the same value means), and a
//! plane under a sky with a small, very bright sun against the integral of L cos(theta),
//! with the low noise that importance sampling gives.

mod common;
#[path = "../../scene/tests/support/rgbe.rs"]
mod rgbe;
mod sky;

use common::{ortho_camera, square_z0};
use glam::{Vec2, Vec3};
use prism_integrator::{Film, RenderSettings, render};
use prism_scene::geometry::BvhQuality;
use prism_scene::load::environment_map;
use prism_scene::world::{
    EnvironmentMap, Light, Material, Scene, SceneParts, SceneSpectrum, grey_environment,
};
use rgbe::rgbe_file;
use sky::sunny_sky;

fn white() -> Material {
    Material::Diffuse {
        reflectance: SceneSpectrum::Constant(1.0),
    }
}

/// `triangles` of white diffuse under `light`, seen from +z by an orthographic camera of
/// half-size `half`.
fn scene(triangles: Vec<[Vec3; 3]>, light: Light, half: f32) -> Scene {
    Scene::new(SceneParts {
        attributes: Default::default(),
        triangle_material: vec![0; triangles.len()],
        triangles,
        materials: vec![white()],
        emission: vec![],
        lights: vec![light],
        camera: ortho_camera(Vec3::new(0.0, 0.0, 3.0), half),
        quality: BvhQuality::Medium,
    })
    .unwrap()
}

fn settings(size: u32, spp: u64) -> RenderSettings {
    RenderSettings::default()
        .width(size)
        .height(size)
        .samples(0..spp)
}

/// Every pixel's luminance Y.
fn luminances(film: &Film) -> Vec<f64> {
    (0..film.height())
        .flat_map(|y| (0..film.width()).map(move |x| (x, y)))
        .map(|(x, y)| film.xyz(x, y).y)
        .collect()
}

/// The mean of `values` and its standard error.
fn mean_and_error(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// A closed box of white diffuse faces around the origin, half-size `h`, facing out.
fn cube(h: f32) -> Vec<[Vec3; 3]> {
    let mut out = Vec::new();
    for axis in 0..3 {
        for sign in [-1.0f32, 1.0] {
            let n = Vec3::from_array(std::array::from_fn(|k| if k == axis { sign } else { 0.0 }));
            let (u, v) = n.any_orthonormal_pair();
            let c = n * h;
            let q = [
                c - u * h - v * h,
                c + u * h - v * h,
                c + u * h + v * h,
                c - u * h + v * h,
            ];
            // Counter-clockwise seen from outside: (u x v) = n.
            out.push([q[0], q[1], q[2]]);
            out.push([q[0], q[2], q[3]]);
        }
    }
    out
}

/// An albedo-1 box in an image whose texels are all 0.5 is invisible: every pixel is Y
/// 0.5, as under `--environment 0.5` (the grey environment of the same value).
#[test]
fn a_constant_image_is_a_furnace_and_means_what_a_number_means() {
    let map = environment_map(&rgbe_file(16, 8, |_, _| [0.5; 3]), 40.0, 1.0).unwrap();
    let lights = [
        Light::EnvironmentMap { map },
        Light::Environment {
            radiance: grey_environment(0.5),
        },
    ];
    for light in lights {
        let (film, stats) = render(&scene(cube(0.5), light, 0.8), &settings(12, 64)).unwrap();
        assert_eq!(stats.nonfinite, 0);
        let (mean, error) = mean_and_error(&luminances(&film));
        assert!(
            (mean - 0.5).abs() < 5.0 * error + 2e-3,
            "Y {mean} +- {error}, expected 0.5"
        );
    }
}

/// (1 / pi) times the integral of the map's luminance times cos(theta) over the hemisphere
/// around +z: the radiance of a white Lambertian plane facing +z, by a fine midpoint rule
/// over the image (independent of how the renderer samples it).
fn lambertian_radiance(map: &EnvironmentMap) -> f64 {
    let (nu, nv) = (2048usize, 1024usize);
    let mut sum = 0.0;
    for j in 0..nv {
        for i in 0..nu {
            let uv = Vec2::new((i as f32 + 0.5) / nu as f32, (j as f32 + 0.5) / nv as f32);
            let (d, sin_theta) = map.direction(uv);
            if d.z <= 0.0 {
                continue;
            }
            let rgb = map.rgb(uv);
            let y = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
            sum += f64::from(y * d.z * sin_theta);
        }
    }
    let dudv = 1.0 / (nu * nv) as f64;
    sum * dudv * 2.0 * std::f64::consts::PI.powi(2) / std::f64::consts::PI
}

/// A white plane under a sky with a small, very bright sun has the radiance the integral
/// of L cos(theta) says, and importance sampling finds the sun: at 16 samples per pixel
/// pixels spread by under a tenth of their mean (by far more than their mean if the sun,
/// 0.03 sr, were found by uniform or cosine sampling: most pixels would miss it).
#[test]
fn a_plane_under_a_sun_gets_the_integral_of_l_cos_theta() {
    let map = sunny_sky();
    let expected = lambertian_radiance(&map);
    // The sun is most of the light.
    let sky_only = 0.2 * 0.7 + 0.1;
    assert!(expected > 3.0 * sky_only, "expected {expected}");
    let plane = scene(square_z0(1000.0), Light::EnvironmentMap { map }, 0.01);
    let (film, stats) = render(&plane, &settings(16, 16)).unwrap();
    assert_eq!(stats.nonfinite, 0);
    let y = luminances(&film);
    let (mean, error) = mean_and_error(&y);
    assert!(
        (mean - expected).abs() < 5.0 * error + 5e-3 * expected,
        "Y {mean} +- {error}, expected {expected}"
    );
    let spread = (y.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / y.len() as f64).sqrt();
    assert!(
        spread < 0.1 * mean,
        "per-pixel spread {spread} of {mean}: the sun is not importance sampled"
    );
}
