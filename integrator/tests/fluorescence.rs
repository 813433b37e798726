//! Fluorescence end to end: energy conservation in an analytic setup, identity with the
//! ordinary render when nothing is re-radiated, and the specialization a scene picks.

mod common;

use std::f64::consts::PI;
use std::sync::Arc;

use glam::Vec3;
use prism_integrator::{
    Film, LambdaSampler, RenderSettings, Renderer, Reuse, SpectralBands, render,
};
use prism_sampling::wavelength::{ReradiationSampler, WavelengthRange};
use prism_scene::bsdf::fluorescence_matrix;
use prism_scene::geometry::BvhQuality;
use prism_scene::spectral::SpectralMaterial;
use prism_scene::world::{Light, Material, Scene, SceneParts, SceneSpectrum};
use prism_spectrum::Spectrum;
use prism_spectrum::spectra::Gaussian;

const RANGE: (f32, f32) = (300.0, 830.0);
const BINS: usize = 265;

fn fluorescent(reflectance: f64, absorption: &Gaussian, reemission: &Gaussian, q: f64) -> Material {
    let range = WavelengthRange::new(RANGE.0, RANGE.1).unwrap();
    let r = SceneSpectrum::Constant(reflectance);
    let m = fluorescence_matrix(range, BINS, &r, absorption, reemission, q).unwrap();
    Material::Fluorescent {
        reflectance: r,
        reradiation: Arc::new(ReradiationSampler::new(range, BINS, &m).unwrap()),
    }
}

/// A large floor of `material` at z = 0 under a directional UV source (a 365 nm LED band
/// of peak irradiance `peak` per nm, arriving straight down), seen straight down.
fn floor_under_uv(material: Material, peak: f64, c: usize, sampler: LambdaSampler) -> Film {
    let s = 100.0;
    let scene = Scene::new(SceneParts {
        attributes: Default::default(),
        triangles: common::square_z0(s),
        triangle_material: vec![0, 0],
        materials: vec![material],
        emission: vec![],
        lights: vec![Light::Directional {
            direction: -Vec3::Z,
            irradiance: SceneSpectrum::Scaled(
                Arc::new(SceneSpectrum::Gaussian(
                    Gaussian::new(365.0, 10.0, 1.0).unwrap(),
                )),
                peak,
            ),
        }],
        camera: common::ortho_camera(Vec3::new(0.0, 0.0, 1.0), 1.0),
        quality: BvhQuality::Medium,
    })
    .unwrap();
    assert!(scene.features().fluorescence);
    let settings = RenderSettings::default()
        .width(8)
        .height(8)
        .samples(0..128)
        .wavelengths(c)
        .lambda_sampler(sampler)
        .max_depth(Some(1))
        .bands(Some(SpectralBands::new(400.0, 700.0, 12).unwrap()));
    render(&scene, &settings).unwrap().0
}

/// Mean and standard error of band `b` over the film's pixels.
fn band(film: &Film, b: usize) -> (f64, f64) {
    let values: Vec<f64> = (0..film.height())
        .flat_map(|y| (0..film.width()).map(move |x| (x, y)))
        .map(|(x, y)| film.spectrum(x, y).unwrap()[b])
        .collect();
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// Light absorbed at 365 nm comes back at 550 nm: per band, the radiance of a Lambertian
/// re-emitter, L(l_o) = Q e(l_o) / (pi l_o) * integral a(l_i) E(l_i) l_i dl_i, and in
/// total the re-emitted power is the absorbed power times Q times the photon-energy
/// ratio. The absorption is an excitation band around the source, as in real dyes (with
/// absorption everywhere, sampling l_i from the material alone rarely finds the source).
#[test]
fn fluorescence_conserves_energy_per_photon() {
    let (q, peak) = (0.7, 2.0);
    let absorption = Gaussian::new(370.0, 40.0, 0.8).unwrap();
    let reemission = Gaussian::new(550.0, 40.0, 1.0).unwrap();
    let irradiance = Gaussian::new(365.0, 10.0, peak).unwrap();
    // Fine quadrature of the continuous model.
    let quad = |f: &dyn Fn(f64) -> f64, lo: f64, hi: f64| {
        let n = 4000;
        let h = (hi - lo) / f64::from(n);
        (0..n)
            .map(|k| f(lo + (f64::from(k) + 0.5) * h))
            .sum::<f64>()
            * h
    };
    let e_area = quad(&|l| reemission.evaluate(l), 300.0, 830.0);
    let absorbed_photon_weight = quad(
        &|l| absorption.evaluate(l) * irradiance.evaluate(l) * l,
        300.0,
        830.0,
    );
    let radiance =
        |lo: f64| q * reemission.evaluate(lo) / e_area / (PI * lo) * absorbed_photon_weight;
    let bands = SpectralBands::new(400.0, 700.0, 12).unwrap();
    for (c, sampler) in [(4, LambdaSampler::Visible), (1, LambdaSampler::Uniform)] {
        let film = floor_under_uv(
            fluorescent(0.1, &absorption, &reemission, q),
            peak,
            c,
            sampler,
        );
        let mut exitance = 0.0;
        for b in 0..bands.count() {
            let lo = bands.center(b) - 0.5 * bands.width();
            let expected = quad(&radiance, lo, lo + bands.width()) / bands.width();
            let (mean, error) = band(&film, b);
            assert!(
                (mean - expected).abs() < 5.0 * error + 1e-2 * expected + 1e-6,
                "C={c} {sampler:?} band {b} ({} nm): {mean} vs {expected} (+-{error})",
                bands.center(b)
            );
            exitance += PI * mean * bands.width();
        }
        // Energy: re-emitted = absorbed * Q * E[l_i / l_o] (400-700 nm holds all but a
        // sliver of the 550 nm band).
        let absorbed = quad(
            &|l| absorption.evaluate(l) * irradiance.evaluate(l),
            300.0,
            830.0,
        );
        let mean_incident = absorbed_photon_weight / absorbed;
        let ratio = quad(
            &|lo| reemission.evaluate(lo) / e_area * mean_incident / lo,
            400.0,
            700.0,
        );
        let expected = absorbed * q * ratio;
        assert!(
            (exitance - expected).abs() < 0.02 * expected,
            "C={c}: re-emitted {exitance} W/m^2 vs {expected}"
        );
    }
}

/// A fluorescent material with quantum yield 0 is its elastic reflectance: the Cornell
/// box renders the same through the fluorescent path tracer as through the ordinary one
/// (without path reuse, which the fluorescent one cannot do).
#[test]
fn zero_quantum_yield_renders_like_diffuse() {
    let settings = RenderSettings::default()
        .width(16)
        .height(16)
        .samples(0..4)
        .wavelengths(4)
        .reuse(Reuse::Fixed(1));
    let reemission = Gaussian::new(550.0, 40.0, 1.0).unwrap();
    let plain = common::cornell();
    let reflectance = match &plain.materials()[1] {
        Material::Diffuse { reflectance } => reflectance.clone(),
        m => panic!("white is {m:?}"),
    };
    let identity = common::cornell_with(|loaded| {
        let range = WavelengthRange::new(RANGE.0, RANGE.1).unwrap();
        let m = fluorescence_matrix(
            range,
            BINS,
            &reflectance,
            &SceneSpectrum::Constant(0.0),
            &reemission,
            0.0,
        )
        .unwrap();
        loaded.materials[1].spectral = Some(SpectralMaterial {
            surface: Some(Material::Fluorescent {
                reflectance: reflectance.clone(),
                reradiation: Arc::new(ReradiationSampler::new(range, BINS, &m).unwrap()),
            }),
            emission: None,
            ..SpectralMaterial::default()
        });
    });
    assert!(!Renderer::new(&plain, &settings).unwrap().fluorescence());
    assert!(Renderer::new(&identity, &settings).unwrap().fluorescence());
    let (a, _) = render(&plain, &settings).unwrap();
    let (b, _) = render(&identity, &settings).unwrap();
    let mut worst = 0.0f64;
    for (p, q) in a.sums().iter().zip(b.sums()) {
        for k in 0..3 {
            worst = worst.max((p[k] - q[k]).abs() / p[k].abs().max(1e-3));
        }
    }
    assert!(worst < 1e-4, "worst relative difference {worst}");
}

/// A 340 nm LED among a much brighter visible light, over a fluorescent floor. The light
/// choice weighs power over the fluorescent range, so NEE finds the LED (by visible power
/// alone it has almost none), and the floor's incident-wavelength guide puts its mass
/// where the LED's light is absorbed, not across the visible light's spectrum.
#[test]
fn an_ultraviolet_source_is_found_among_brighter_visible_light() {
    let absorption = Gaussian::new(370.0, 60.0, 0.9).unwrap();
    let reemission = Gaussian::new(515.0, 35.0, 1.0).unwrap();
    let s = 10.0;
    let scene = Scene::new(SceneParts {
        attributes: Default::default(),
        triangles: common::square_z0(s),
        triangle_material: vec![0, 0],
        materials: vec![fluorescent(0.05, &absorption, &reemission, 0.9)],
        emission: vec![],
        lights: vec![
            Light::Point {
                position: Vec3::new(0.0, 0.0, 1.0),
                intensity: SceneSpectrum::Gaussian(Gaussian::new(340.0, 10.0, 1.0).unwrap()),
            },
            Light::Point {
                position: Vec3::new(1.0, 0.0, 1.0),
                intensity: SceneSpectrum::Constant(0.05),
            },
        ],
        camera: common::ortho_camera(Vec3::new(0.0, 0.0, 1.0), 1.0),
        quality: BvhQuality::Medium,
    })
    .unwrap();
    // The LED's mean over 300-830 nm is about 10.6 / 530 = 0.02 against the lamp's 0.05:
    // chosen about 2 times in 7. Over 360-830 it would be chosen about once in 10^4.
    let pmf = scene.lights().pmf(0);
    assert!(
        (0.2..0.4).contains(&pmf),
        "the LED's choice probability {pmf}"
    );

    let ray = prism_scene::geometry::Ray::new(Vec3::new(0.3, 0.2, 1.0), -Vec3::Z, f32::INFINITY);
    let hit = scene.intersect(&ray).expect("the floor");
    let guide = scene.light_wavelengths(&hit).expect("the floor fluoresces");
    // The lamp's flux over 300-830 nm is 2.5 times the LED's, but the floor absorbs only
    // below about 420 nm: absorbed, the LED's light is about 60% of the total and its band
    // holds about 75% of the guide (a guide of the lights' spectra alone, or weighted by
    // visible power, puts under 15% there).
    let led_band: f64 = (315..365).map(|nm| guide.pdf(f64::from(nm) + 0.5)).sum();
    assert!(led_band > 0.6, "guide mass in the LED's band: {led_band}");
}
