//! Evidence that the integrator converges to the right image: a white furnace, analytic
//! direct lighting from a point and an area light, agreement between wavelength samplers
//! and package sizes, and determinism across thread counts.

// Channel loops index several parallel arrays by k; iterators would hide that.
#![allow(clippy::needless_range_loop)]

mod common;

use common::{
    assert_image_mean, cornell, emitter_filling_the_view, furnace, furnace_scene, icosphere,
    mean_and_error, ortho_camera,
};
use glam::Vec3;
use prism_integrator::{ExrMetadata, Film, LambdaSampler, RenderSettings, encode_exr, render};
use prism_sampling::wavelength::PackageScheme;
use prism_scene::geometry::BvhQuality;
use prism_scene::world::{Light, Material, Scene, SceneParts, SceneSpectrum, SpotFalloff};
use prism_spectrum::color::RgbSpaceId;
use prism_spectrum::colorimetry::{Observer, emission_xyz};
use prism_spectrum::spectra::{Constant, Gaussian};
use std::sync::Arc;

fn constant_xyz(value: f64) -> [f64; 3] {
    emission_xyz(&Constant::new(value).unwrap(), Observer::Cie1931).to_array()
}

fn settings(size: u32, spp: u64, wavelengths: usize, sampler: LambdaSampler) -> RenderSettings {
    RenderSettings::default()
        .width(size)
        .height(size)
        .samples(0..spp)
        .wavelengths(wavelengths)
        .lambda_sampler(sampler)
}

const SAMPLERS: [LambdaSampler; 4] = [
    LambdaSampler::Uniform,
    LambdaSampler::Visible,
    LambdaSampler::Response,
    LambdaSampler::Spd,
];

/// A white (albedo 1) sphere in a uniform environment of radiance 1 is invisible: every
/// pixel sees radiance 1 at every wavelength, for every sampler and package size.
#[test]
fn white_furnace_returns_the_environment() {
    let scene = furnace_scene();
    let expected = constant_xyz(1.0);
    for sampler in SAMPLERS {
        for c in [1, 2, 4, 8, 16] {
            let (film, stats) = render(&scene, &settings(12, 32, c, sampler)).unwrap();
            assert_eq!(stats.nonfinite, 0);
            assert_image_mean(&film, expected, &format!("{sampler:?} C={c}"));
        }
    }
}

/// The irradiance at the origin (normal +z) from a Lambertian polygon of radiance `l`:
/// Lambert's formula E = L/2 sum_i gamma_i (n . (r_i x r_{i+1}) / |r_i x r_{i+1}|), with
/// gamma_i the angle between successive corner directions.
fn polygon_irradiance(corners: &[Vec3], l: f64) -> f64 {
    let n = corners.len();
    let mut sum = 0.0f64;
    for i in 0..n {
        let (a, b) = (
            corners[i].normalize().as_dvec3(),
            corners[(i + 1) % n].normalize().as_dvec3(),
        );
        let gamma = a.dot(b).clamp(-1.0, 1.0).acos();
        let c = a.cross(b).normalize();
        sum += gamma * c.z;
    }
    0.5 * l * sum.abs()
}

/// A large grey floor (albedo 0.5) at z = 0 seen straight down through a tiny orthographic
/// window at the origin, lit by `lights` and optionally by a black quad emitting radiance 3
/// downwards.
fn floor_render(lights: Vec<Light>, emitter: Option<[Vec3; 4]>, sampler: LambdaSampler) -> Film {
    let emitter = emitter.map(|q| (q, SceneSpectrum::Constant(3.0)));
    let scene = floor_scene(lights, emitter);
    render(&scene, &settings(4, 256, 4, sampler)).unwrap().0
}

/// The floor of [`floor_render`], lit by `lights` and a black quad emitting the given
/// radiance downwards.
fn floor_scene(lights: Vec<Light>, emitter: Option<([Vec3; 4], SceneSpectrum)>) -> Scene {
    let s = 100.0;
    let mut triangles = common::square_z0(s);
    let mut triangle_material = vec![0, 0];
    let mut lights = lights;
    let mut emission = vec![SceneSpectrum::Constant(0.0)];
    if let Some((q, spectrum)) = emitter {
        emission[0] = spectrum;
        // Facing down (-z): wound clockwise seen from above.
        triangles.push([q[0], q[2], q[1]]);
        triangles.push([q[0], q[3], q[2]]);
        // Black, so that it does not reflect the floor's light back down.
        triangle_material.extend([1, 1]);
        for t in [2, 3] {
            lights.push(Light::Triangle {
                triangle: t,
                emission: 0,
                two_sided: false,
            });
        }
    }
    Scene::new(SceneParts {
        attributes: Default::default(),
        triangles,
        triangle_material,
        materials: vec![
            Material::Diffuse {
                reflectance: SceneSpectrum::Constant(0.5),
            },
            Material::Diffuse {
                reflectance: SceneSpectrum::Constant(0.0),
            },
        ],
        emission,
        lights,
        // Looking down from between the floor and the emitter.
        camera: ortho_camera(Vec3::new(0.0, 0.0, 0.5), 1e-3),
        quality: BvhQuality::Medium,
    })
    .unwrap()
}

#[test]
fn point_light_direct_lighting_is_analytic() {
    // A point light of intensity 2 at height 2 over a floor of albedo 0.5: the floor's
    // radiance is rho / pi * I / h^2.
    let lights = vec![Light::Point {
        position: Vec3::new(0.0, 0.0, 2.0),
        intensity: SceneSpectrum::Constant(2.0),
    }];
    for sampler in [LambdaSampler::Uniform, LambdaSampler::Visible] {
        let film = floor_render(lights.clone(), None, sampler);
        let radiance = 0.5 / std::f64::consts::PI * 2.0 / 4.0;
        assert_floor_radiance(&film, radiance, &format!("{sampler:?}"));
    }
}

/// Asserts that every XYZ channel of `film` is the floor's radiance `radiance` (of a
/// constant spectrum) within Monte Carlo error.
fn assert_floor_radiance(film: &Film, radiance: f64, what: &str) {
    assert_floor_xyz(film, constant_xyz(radiance), what);
}

/// Asserts that every channel of `film` is `expected` within Monte Carlo error.
fn assert_floor_xyz(film: &Film, expected: [f64; 3], what: &str) {
    for k in 0..3 {
        let (mean, error) = mean_and_error(film, k);
        assert!(
            (mean - expected[k]).abs() < 5.0 * error + 2e-3 * expected[k] + 1e-12,
            "{what}, channel {k}: {mean} vs {}",
            expected[k]
        );
    }
}

#[test]
fn spot_light_direct_lighting_follows_its_cone() {
    // A spot of intensity 2 at height 2 over the floor of albedo 0.5, its axis tilted so
    // that the origin (the pixel) lies `off` radians from it: the floor's radiance is
    // rho / pi * I * falloff / h^2, with KHR_lights_punctual's falloff, the square of a
    // linear ramp in cos from the outer cone (0) to the inner one (1).
    let (inner, outer) = (0.3f64, 0.5f64);
    let falloff = |off: f64| {
        let t = ((off.cos() - outer.cos()) / (inner.cos() - outer.cos())).clamp(0.0, 1.0);
        t * t
    };
    let spot = |inner: f64, outer: f64, off: f64| Light::Spot {
        position: Vec3::new(0.0, 0.0, 2.0),
        direction: Vec3::new(off.sin() as f32, 0.0, -off.cos() as f32),
        cos_inner: inner.cos() as f32,
        cos_outer: outer.cos() as f32,
        intensity: SceneSpectrum::Constant(2.0),
        falloff: SpotFalloff::Smooth,
        texture: None,
    };
    for off in [0.0, 0.2, 0.35, 0.42, 0.49, 0.6] {
        let film = floor_render(vec![spot(inner, outer, off)], None, LambdaSampler::Visible);
        let radiance = 0.5 / std::f64::consts::PI * 2.0 * falloff(off) / 4.0;
        assert_floor_radiance(&film, radiance, &format!("{off} rad off the axis"));
    }
    // A pencil beam (cone 0.3 degrees): full intensity on its axis. The extension's sample
    // code floors the ramp's width at 1e-3 in cos, which would leave 2.6e-4 of it here.
    let film = floor_render(vec![spot(0.002, 0.006, 0.0)], None, LambdaSampler::Visible);
    assert_floor_radiance(&film, 0.5 / std::f64::consts::PI * 2.0 / 4.0, "pencil beam");
}

#[test]
fn directional_light_direct_lighting_is_analytic() {
    // Irradiance 3 on a surface square to the light, arriving 35 degrees from the
    // vertical: the floor's radiance is rho / pi * E cos(35 degrees).
    let theta = 35f64.to_radians();
    let sun = Light::Directional {
        direction: Vec3::new(theta.sin() as f32, 0.0, -theta.cos() as f32),
        irradiance: SceneSpectrum::Constant(3.0),
    };
    for sampler in [LambdaSampler::Uniform, LambdaSampler::Visible] {
        let film = floor_render(vec![sun.clone()], None, sampler);
        let radiance = 0.5 / std::f64::consts::PI * 3.0 * theta.cos();
        assert_floor_radiance(&film, radiance, &format!("{sampler:?}"));
    }
}

#[test]
fn area_light_direct_lighting_is_analytic() {
    // A square emitter of radiance 3 above the floor and offset in x so that the cosine
    // varies over it: the floor's radiance at the origin is rho / pi * E with E from
    // Lambert's polygon formula. MIS between light and BSDF sampling must reproduce it,
    // both for a near emitter (side 1 at height 1, about 0.6 sr: sampled by solid angle)
    // and for a far one (side 0.2 at height 1.2, about 0.025 sr: sampled by area).
    for (side, height) in [(1.0, 1.0), (0.2, 1.2)] {
        let (x0, h) = (-0.2 * side, 0.5 * side);
        let q = [
            Vec3::new(x0, -h, height),
            Vec3::new(x0 + side, -h, height),
            Vec3::new(x0 + side, h, height),
            Vec3::new(x0, h, height),
        ];
        let e = polygon_irradiance(&q, 3.0);
        let film = floor_render(vec![], Some(q), LambdaSampler::Visible);
        // The emitter is black, so direct lighting is the whole answer.
        assert_floor_radiance(
            &film,
            0.5 / std::f64::consts::PI * e,
            &format!("side {side} at {height} (E = {e})"),
        );
    }
}

#[test]
fn lights_of_different_spectra_light_the_floor_analytically() {
    // Three narrow bands: a point light overhead (blue), one off to the side (red), both
    // below an area light (green) that would otherwise shadow them. Lights of different spectra are chosen by their power at each
    // path's wavelengths, and MIS with BSDF sampling uses the same probabilities: the
    // floor's colour must still be rho / pi times the sum of the irradiances, band by band.
    let band = |centre: f64| Gaussian::new(centre, 20.0, 1.0).unwrap();
    let (blue, red, green) = (band(450.0), band(620.0), band(540.0));
    let lights = vec![
        Light::Point {
            position: Vec3::new(0.0, 0.0, 0.8),
            intensity: SceneSpectrum::Scaled(Arc::new(SceneSpectrum::Gaussian(blue)), 2.0),
        },
        Light::Point {
            position: Vec3::new(1.0, 0.0, 0.8),
            intensity: SceneSpectrum::Scaled(Arc::new(SceneSpectrum::Gaussian(red)), 5.0),
        },
    ];
    let q = [
        Vec3::new(-0.2, -0.5, 1.0),
        Vec3::new(0.8, -0.5, 1.0),
        Vec3::new(0.8, 0.5, 1.0),
        Vec3::new(-0.2, 0.5, 1.0),
    ];
    let scene = floor_scene(
        lights,
        Some((
            q,
            SceneSpectrum::Scaled(Arc::new(SceneSpectrum::Gaussian(green)), 3.0),
        )),
    );
    assert!(scene.lights().spectral_choice());
    let film = render(&scene, &settings(4, 1024, 4, LambdaSampler::Visible))
        .unwrap()
        .0;
    let irradiance = [
        (2.0 / 0.64, blue),
        (5.0 * 0.8 / 1.64f64.powf(1.5), red),
        (polygon_irradiance(&q, 3.0), green),
    ];
    let mut expected = [0.0f64; 3];
    for (e, spectrum) in irradiance {
        let xyz = emission_xyz(&spectrum, Observer::Cie1931).to_array();
        for k in 0..3 {
            expected[k] += 0.5 / std::f64::consts::PI * e * xyz[k];
        }
    }
    assert_floor_xyz(&film, expected, "three bands");
}

#[test]
fn threads_do_not_change_the_image() {
    let scene = cornell();
    let mut one = settings(24, 4, 4, LambdaSampler::Visible);
    one.threads = 1;
    let two = one.clone().threads(2);
    let (a, _) = render(&scene, &one).unwrap();
    let (b, _) = render(&scene, &two).unwrap();
    assert_eq!(a.sums(), b.sums());
    let space = RgbSpaceId::Srgb.space();
    let meta = ExrMetadata::default();
    assert_eq!(
        encode_exr(&a, space, &meta).unwrap(),
        encode_exr(&b, space, &meta).unwrap(),
        "byte-identical EXR"
    );
}

#[test]
fn sample_ranges_merge_into_the_whole_render() {
    let scene = cornell();
    let whole = settings(8, 6, 4, LambdaSampler::Visible);
    let (full, _) = render(&scene, &whole).unwrap();
    let (mut first, _) = render(&scene, &whole.clone().samples(0..2)).unwrap();
    let (second, _) = render(&scene, &whole.clone().samples(2..6)).unwrap();
    first.merge(&second).unwrap();
    assert_eq!(first.samples(), 6);
    for (a, b) in first.sums().iter().zip(full.sums()) {
        for k in 0..3 {
            assert!(
                (a[k] - b[k]).abs() <= 1e-12 * b[k].abs().max(1.0),
                "{a:?} {b:?}"
            );
        }
    }
}

/// The Cornell box's mean colour, estimated from `batches` independent seeds: the mean of
/// the batch means and its standard error.
fn cornell_mean(
    scene: &Scene,
    wavelengths: usize,
    sampler: LambdaSampler,
    scheme: PackageScheme,
) -> ([f64; 3], [f64; 3]) {
    let batches = 6;
    let mut means = vec![];
    for seed in 0..batches {
        let s = (settings(12, 8, wavelengths, sampler))
            .seed(1000 + seed)
            .scheme(scheme);
        let (film, _) = render(scene, &s).unwrap();
        means.push([0, 1, 2].map(|k| mean_and_error(&film, k).0));
    }
    let n = batches as f64;
    let mean = [0, 1, 2].map(|k| means.iter().map(|m| m[k]).sum::<f64>() / n);
    let error = [0, 1, 2].map(|k| {
        let var = means.iter().map(|m| (m[k] - mean[k]).powi(2)).sum::<f64>() / (n - 1.0);
        (var / n).sqrt()
    });
    (mean, error)
}

/// Every wavelength sampler, every package size and both package schemes estimate the same
/// image: their mean colours over the Cornell box agree within statistical error.
#[test]
fn samplers_and_package_sizes_agree() {
    let scene = cornell();
    let (reference, reference_error) = cornell_mean(
        &scene,
        4,
        LambdaSampler::Visible,
        PackageScheme::HeroRotation,
    );
    let mut configurations = vec![];
    for sampler in SAMPLERS {
        configurations.push((1, sampler, PackageScheme::HeroRotation));
    }
    for c in [2, 8, 16] {
        configurations.push((c, LambdaSampler::Uniform, PackageScheme::HeroRotation));
    }
    configurations.push((4, LambdaSampler::Visible, PackageScheme::Stratified));
    for (c, sampler, scheme) in configurations {
        let (mean, error) = cornell_mean(&scene, c, sampler, scheme);
        for k in 0..3 {
            let sigma = (error[k].powi(2) + reference_error[k].powi(2)).sqrt();
            assert!(
                (mean[k] - reference[k]).abs() < 5.0 * sigma,
                "C={c} {sampler:?} {scheme:?} channel {k}: {} vs {} (sigma {sigma})",
                mean[k],
                reference[k]
            );
        }
    }
}

/// The firefly clamp caps every sample's luminance, so no pixel exceeds it; without it the
/// emitter seen directly is far brighter.
#[test]
fn clamp_bounds_every_sample() {
    let scene = cornell();
    let base = settings(16, 4, 4, LambdaSampler::Visible);
    let (free, _) = render(&scene, &base).unwrap();
    let (clamped, _) = render(&scene, &base.clone().clamp(Some(1.0))).unwrap();
    let max_y = |film: &Film| {
        (0..16)
            .flat_map(|y| (0..16).map(move |x| (x, y)))
            .map(|(x, y)| film.xyz(x, y).y)
            .fold(0.0f64, f64::max)
    };
    assert!(max_y(&free) > 2.0, "the light is bright: {}", max_y(&free));
    assert!(max_y(&clamped) <= 1.0 + 1e-9, "{}", max_y(&clamped));
    assert!(base.clamp(Some(f64::NAN)).validate().is_err());
}

/// A dispersive glass sphere (SF11, strongly dispersive) in a uniform environment is
/// invisible: a lossless interface only redirects light, so every pixel sees the
/// environment at every wavelength. Refraction through it sends each wavelength its own
/// way, so every path that refracts splits its package: this checks that the secondaries'
/// light before the split is counted once, with the package's densities, and the hero's
/// after it with its own.
#[test]
fn dispersive_glass_furnace_returns_the_environment() {
    let glass = prism_spectrum::optics::named_glass("sf11").unwrap();
    let ior = prism_spectrum::spectra::DenselySampled::from_spectrum(&glass.ior, 300, 900).unwrap();
    // The glass at the left, a white diffuse sphere at the right: paths gather light at
    // the diffuse sphere (next-event estimation) before refracting into the glass.
    let shift = |dx: f32| move |t: [Vec3; 3]| t.map(|v| v * 0.5 + Vec3::new(dx, 0.0, 0.0));
    let glass_sphere: Vec<[Vec3; 3]> = icosphere(2).into_iter().map(shift(-0.55)).collect();
    let white_sphere: Vec<[Vec3; 3]> = icosphere(2).into_iter().map(shift(0.55)).collect();
    let mut triangle_material = vec![0; glass_sphere.len()];
    triangle_material.extend(vec![1; white_sphere.len()]);
    let triangles = [glass_sphere, white_sphere].concat();
    let glass = Material::Dielectric {
        ior: SceneSpectrum::Dense(std::sync::Arc::new(ior)),
        roughness: 0.0,
        absorption: None,
    };
    let white = Material::Diffuse {
        reflectance: SceneSpectrum::Constant(1.0),
    };
    let scene = furnace(triangles, triangle_material, vec![glass, white], 1.1);
    assert!(scene.features().dispersion);
    let expected = constant_xyz(1.0);
    for (c, scheme) in [
        (4, PackageScheme::HeroRotation),
        (8, PackageScheme::HeroRotation),
        (4, PackageScheme::Stratified),
    ] {
        let s = (settings(24, 256, c, LambdaSampler::Visible)).scheme(scheme);
        let (film, _) = render(&scene, &s).unwrap();
        for k in 0..3 {
            let (mean, error) = mean_and_error(&film, k);
            let tolerance = 5.0 * error + 1e-3 * expected[k];
            assert!(
                (mean - expected[k]).abs() < tolerance,
                "C={c} {scheme:?} channel {k}: {mean} vs {} (+-{tolerance})",
                expected[k]
            );
        }
    }
}

/// White plastics vanish in the furnace: a smooth coating (its mirror a delta, sampled
/// with the substrate's lobe) and a rough one, nonlinear, side by side and lighting each
/// other. The coatings' tables are exact to a fraction of a percent.
#[test]
fn white_plastic_furnace_returns_the_environment() {
    let shift = |dx: f32| move |t: [Vec3; 3]| t.map(|v| v * 0.5 + Vec3::new(dx, 0.0, 0.0));
    let smooth: Vec<[Vec3; 3]> = icosphere(2).into_iter().map(shift(-0.55)).collect();
    let rough: Vec<[Vec3; 3]> = icosphere(2).into_iter().map(shift(0.55)).collect();
    let mut triangle_material = vec![0; smooth.len()];
    triangle_material.extend(vec![1; rough.len()]);
    let plastic = |roughness: f32, nonlinear: bool| Material::Plastic {
        reflectance: SceneSpectrum::Constant(1.0),
        nonlinear,
        coating: std::sync::Arc::new(prism_scene::bsdf::PlasticCoating::new(
            1.49,
            roughness * roughness,
        )),
    };
    let scene = furnace(
        [smooth, rough].concat(),
        triangle_material,
        vec![plastic(0.0, false), plastic(0.55, true)],
        1.1,
    );
    let (film, _) = render(&scene, &settings(24, 256, 8, LambdaSampler::Visible)).unwrap();
    let expected = constant_xyz(1.0);
    for k in 0..3 {
        let (mean, error) = mean_and_error(&film, k);
        let tolerance = 5.0 * error + 1e-2 * expected[k];
        assert!(
            (mean - expected[k]).abs() < tolerance,
            "channel {k}: {mean} vs {} (+-{tolerance})",
            expected[k]
        );
    }
}

/// Russian roulette reads a path's throughput without the 1 / eta^2 that refraction gives
/// radiance. Three clear glass spheres of index 1.5 in a row in the furnace: a path through
/// them crosses six interfaces, and each that escapes returns the environment's radiance
/// exactly (energy output with uniform wavelengths: no spectral noise), so only roulette
/// leaves noise (the 0.95 cap on survival from the third bounce). Reading 1 / 2.25 inside
/// the glass as lost energy ended 56% of the paths there at every such bounce and weighted
/// the rest by 2.25: the pixels' relative spread was 0.20, against 0.088 now (16 spp), the
/// mean right either way.
#[test]
fn roulette_does_not_end_paths_for_being_inside_glass() {
    let triangles: Vec<[Vec3; 3]> = [0.0f32, -2.5, -5.0]
        .into_iter()
        .flat_map(|z| {
            icosphere(2)
                .into_iter()
                .map(move |t| t.map(|v| v + Vec3::new(0.0, 0.0, z)))
        })
        .collect();
    let glass = Material::Dielectric {
        ior: SceneSpectrum::Constant(1.5),
        roughness: 0.0,
        absorption: None,
    };
    let triangle_material = vec![0; triangles.len()];
    let scene = furnace(triangles, triangle_material, vec![glass], 0.6);
    let settings = (settings(16, 16, 4, LambdaSampler::Uniform)).energy(true);
    let (film, _) = render(&scene, &settings).unwrap();
    let values: Vec<f64> = (0..16)
        .flat_map(|y| (0..16).map(move |x| (x, y)))
        .map(|(x, y)| film.energy(x, y).unwrap()[0])
        .collect();
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let sd = (values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    let expected = 830.0 - 360.0;
    assert!(
        (mean - expected).abs() < 5.0 * sd / n.sqrt() + 1e-3 * expected,
        "{mean} vs {expected}"
    );
    let spread = sd / mean;
    assert!(spread < 0.13, "relative spread of the pixels {spread}");
}

/// A 3000 K blackbody filling the view is recovered band by band from the spectral film,
/// whatever the wavelength sampler (non-uniform densities) and package size (MIS over the
/// package), and the spectral EXR carries the layout's channels and attributes.
#[test]
fn spectral_film_recovers_a_blackbody_per_band() {
    use prism_integrator::SpectralBands;
    use prism_spectrum::Spectrum;
    use prism_spectrum::spectra::Blackbody;
    let blackbody = Blackbody::normalized(3000.0).unwrap();
    let scene = emitter_filling_the_view(SceneSpectrum::Blackbody(blackbody));
    let bands = SpectralBands::new(380.0, 780.0, 16).unwrap();
    // The band means of the blackbody, by fine quadrature.
    let expected: Vec<f64> = (0..bands.count())
        .map(|b| {
            let lo = bands.center(b) - 0.5 * bands.width();
            let n = 400;
            (0..n)
                .map(|k| blackbody.evaluate(lo + (k as f64 + 0.5) * bands.width() / n as f64))
                .sum::<f64>()
                / n as f64
        })
        .collect();
    // Not the response or SPD samplers: both follow the colour matching functions, so
    // bands the eye barely sees (740-780 nm) get almost no samples in a short test. They
    // stay unbiased there, with far more variance; spectral output wants a sampler that
    // covers its bands.
    for (c, sampler) in [
        (4, LambdaSampler::Visible),
        (1, LambdaSampler::Uniform),
        (16, LambdaSampler::Visible),
    ] {
        let s = (settings(8, 64, c, sampler)).bands(Some(bands));
        let (film, _) = render(&scene, &s).unwrap();
        for b in 0..bands.count() {
            let values: Vec<f64> = (0..8)
                .flat_map(|y| (0..8).map(move |x| (x, y)))
                .map(|(x, y)| film.spectrum(x, y).unwrap()[b])
                .collect();
            let n = values.len() as f64;
            let mean = values.iter().sum::<f64>() / n;
            let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
            let error = (var / n).sqrt();
            assert!(
                (mean - expected[b]).abs() < 5.0 * error + 5e-3 * expected[b],
                "C={c} {sampler:?} band {b} ({} nm): {mean} vs {} (+-{error})",
                bands.center(b),
                expected[b]
            );
        }
        let exr = encode_exr(&film, RgbSpaceId::Srgb.space(), &ExrMetadata::default()).unwrap();
        let text = String::from_utf8_lossy(&exr[..exr.len().min(8192)]).to_string();
        for needle in [
            "spectralLayoutVersion",
            "emissiveUnits",
            "W.m^-2.sr^-1",
            "S0.392,500000nm",
            "S0.767,500000nm",
            "chromaticities",
        ] {
            assert!(text.contains(needle), "{needle} missing from the header");
        }
        let decoded = prism_integrator::decode_exr(&exr).unwrap();
        // R, G, B, A and the bands.
        assert_eq!(decoded.channels.len(), 4 + 16);
    }
}

/// Beer-Lambert: through an index-matched (n = 1) cube of side 2 whose inside absorbs
/// sigma = 0.5 per unit, a uniform environment of radiance 1 is seen as exp(-1); the
/// front faces and the path inside see no absorption until the ray leaves.
#[test]
fn absorbing_volumes_follow_beer_lambert() {
    let c = [
        Vec3::new(-1.0, -1.0, -1.0),
        Vec3::new(1.0, -1.0, -1.0),
        Vec3::new(1.0, 1.0, -1.0),
        Vec3::new(-1.0, 1.0, -1.0),
        Vec3::new(-1.0, -1.0, 1.0),
        Vec3::new(1.0, -1.0, 1.0),
        Vec3::new(1.0, 1.0, 1.0),
        Vec3::new(-1.0, 1.0, 1.0),
    ];
    // Outward-wound faces (counter-clockwise seen from outside).
    let faces = [
        [0, 3, 2, 1],
        [4, 5, 6, 7],
        [0, 1, 5, 4],
        [2, 3, 7, 6],
        [1, 2, 6, 5],
        [0, 4, 7, 3],
    ];
    let triangles: Vec<[Vec3; 3]> = faces
        .iter()
        .flat_map(|f| [[c[f[0]], c[f[1]], c[f[2]]], [c[f[0]], c[f[2]], c[f[3]]]])
        .collect();
    for t in &triangles {
        let n = (t[1] - t[0]).cross(t[2] - t[0]);
        assert!(n.dot(t[0] + t[1] + t[2]) > 0.0, "faces wound outward");
    }
    let scene = Scene::new(SceneParts {
        attributes: Default::default(),
        triangle_material: vec![0; triangles.len()],
        triangles,
        materials: vec![Material::Dielectric {
            ior: SceneSpectrum::Constant(1.0),
            roughness: 0.0,
            absorption: Some(SceneSpectrum::Constant(0.5)),
        }],
        emission: vec![],
        lights: vec![Light::Environment {
            radiance: SceneSpectrum::Constant(1.0),
        }],
        camera: ortho_camera(Vec3::new(0.0, 0.0, 3.0), 0.5),
        quality: BvhQuality::Medium,
    })
    .unwrap();
    let (film, _) = render(&scene, &settings(8, 16, 4, LambdaSampler::Visible)).unwrap();
    let expected = constant_xyz((-1.0f64).exp());
    for k in 0..3 {
        let (mean, error) = mean_and_error(&film, k);
        assert!(
            (mean - expected[k]).abs() < 5.0 * error + 2e-3 * expected[k],
            "channel {k}: {mean} vs {}",
            expected[k]
        );
    }
}
