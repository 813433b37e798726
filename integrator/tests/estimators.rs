//! Every combination of settings renders the same expectation, in every output.
//!
//! - A furnace, the sphere of chromatic scattering medium under a uniform sky: with
//!   adaptive sampling (and path reuse) every band stays the sky's within its noise, and
//!   the bands of the sky seen directly are no noisier than a uniform render's. Adaptive
//!   sampling's pilot once judged colour alone and left them four times as noisy.
//! - The estimator matrix (`common::matrix`): every combination of adaptive sampling,
//!   splits and reuse, tracer, light paths and wavelength count that the resolution step
//!   allows, against the reference mode (uniform samples, unsplit, no reuse, the path
//!   tracer), by Welch's t-test per block and output channel over seeds at a stated
//!   family-wise false-alarm rate. The default run renders a slice: the Cornell box and
//!   the medium furnace at 8 wavelengths. `PRISM_ESTIMATOR_MATRIX=1` runs all of it: the
//!   repository's scenes of every estimator, at 1, 4 and 8 wavelengths, and light paths off
//!   against on where they carry caustics (docs/guide/building.md records its last run).
//! - The test's power: a combination 3% off in one channel of one scene fails it.

mod common;

use common::matrix::{
    Blocks, Case, allowed, combinations, compare, reference, render_blocks, scaled,
};
use common::{icosphere, repository_scene};
use glam::Vec3;
use prism_integrator::{LambdaSampler, RenderSettings, Reuse, SpectralBands, Splits, render};
use prism_sampling::stats::welch_t_test;
use prism_scene::medium::{Media, Medium, Phase};
use prism_scene::world::{Environment, Light, Material, Scene, SceneParts, SceneSpectrum};
use prism_spectrum::spectra::{Extrapolation, PiecewiseLinear};

/// The furnace of the issue that found adaptive sampling's pilot judging colour alone: an
/// interface sphere (radius 0.5) of medium with sigma_a 0 and sigma_s falling from 8/m at
/// 400 nm to 2/m at 700 nm (g 0.6), under a uniform sky of 0.5, seen by a perspective
/// camera 2.2 away (yfov 0.5). Every pixel sees 0.5 at every wavelength.
fn medium_furnace() -> Scene {
    let sphere: Vec<[Vec3; 3]> = icosphere(4)
        .into_iter()
        .map(|t| t.map(|v| v * 0.5))
        .collect();
    let mut camera = common::ortho_camera(Vec3::new(0.0, 0.0, 2.2), 1.0);
    camera.projection = prism_scene::camera::Projection::Perspective { yfov: 0.5 };
    let mut scene = Scene::new(SceneParts {
        attributes: Default::default(),
        triangle_material: vec![0; sphere.len()],
        triangles: sphere,
        materials: vec![Material::Interface],
        emission: vec![],
        lights: vec![Light::Environment {
            radiance: SceneSpectrum::Constant(0.5),
        }],
        camera,
        quality: prism_scene::geometry::BvhQuality::Medium,
    })
    .unwrap();
    let sigma_s = SceneSpectrum::Table(std::sync::Arc::new(
        PiecewiseLinear::new(vec![400.0, 700.0], vec![8.0, 2.0], Extrapolation::Clamp).unwrap(),
    ));
    let medium = Medium::new(
        SceneSpectrum::Constant(0.0),
        sigma_s,
        Phase::henyey_greenstein(0.6).unwrap(),
        None,
    )
    .unwrap();
    scene
        .set_media(Media::new(vec![medium], vec![Some(0)], None).unwrap())
        .unwrap();
    scene
}

/// Per band, (the centre block's mean, the mean squared error of the sky's pixels about
/// 0.5) of a 48 x 48 render of the furnace.
fn furnace_bands(scene: &Scene, settings: &RenderSettings) -> Vec<(f64, f64)> {
    let (film, stats) = render(scene, settings).unwrap();
    assert_eq!(stats.nonfinite, 0);
    let bands = film.bands().unwrap().count();
    (0..bands)
        .map(|b| {
            let value = |x: u32, y: u32| film.spectrum(x, y).unwrap()[b];
            let centre = (16..32)
                .flat_map(|y| (16..32).map(move |x| (x, y)))
                .map(|(x, y)| value(x, y))
                .sum::<f64>()
                / 256.0;
            // The sky: the image's outer ring of 3 pixels, beyond the sphere.
            let sky: Vec<f64> = (0..48)
                .flat_map(|y| (0..48).map(move |x| (x, y)))
                .filter(|&(x, y)| x.min(y).min(47 - x).min(47 - y) < 3)
                .map(|(x, y)| (value(x, y) - 0.5).powi(2))
                .collect();
            (centre, sky.iter().sum::<f64>() / sky.len() as f64)
        })
        .collect()
}

/// With adaptive sampling, alone and with path reuse in tiles of 4, every band of the
/// furnace's centre stays the sky's within its noise over seeds, and the sky's bands are
/// no noisier than in a uniform render of as many samples (on the pilot that judged colour
/// alone they were 8-10 times as noisy in squared error, and the centre's bands, compared
/// with the sky's, 13% off).
#[test]
fn adaptive_sampling_serves_every_band_of_a_furnace() {
    let scene = medium_furnace();
    let settings = RenderSettings::default()
        .width(48)
        .height(48)
        .samples(0..128)
        .wavelengths(8)
        .lambda_sampler(LambdaSampler::Uniform)
        .range((400.0, 700.0))
        .bands(Some(SpectralBands::new(400.0, 700.0, 10).unwrap()));
    let uniform = settings
        .clone()
        .adaptive(false)
        .splits(Splits::Fixed(1))
        .reuse(Reuse::Fixed(1));
    let seeds = 0..5u64;
    let reference: Vec<Vec<(f64, f64)>> = seeds
        .clone()
        .map(|seed| furnace_bands(&scene, &uniform.clone().seed(seed)))
        .collect();
    for (what, combination) in [
        (
            "adaptive, reuse 4",
            settings.clone().adaptive(true).reuse(Reuse::Fixed(4)),
        ),
        (
            "adaptive, reuse 1",
            settings.clone().adaptive(true).reuse(Reuse::Fixed(1)),
        ),
        ("adaptive, auto", settings.clone().adaptive(true)),
    ] {
        let runs: Vec<Vec<(f64, f64)>> = seeds
            .clone()
            .map(|seed| furnace_bands(&scene, &combination.clone().seed(seed)))
            .collect();
        for b in 0..10 {
            let centre: Vec<f64> = runs.iter().map(|r| r[b].0).collect();
            let test = welch_t_test(&centre, &[0.5, 0.5]);
            assert!(
                test.p_value > 1e-3 / 10.0,
                "{what}, band {b}: the centre's mean {centre:?} is not the sky's 0.5 ({test:?})"
            );
            let sky = |r: &[Vec<(f64, f64)>]| r.iter().map(|r| r[b].1).sum::<f64>() / 5.0;
            let (mine, theirs) = (sky(&runs), sky(&reference));
            assert!(
                mine < 2.0 * theirs,
                "{what}, band {b}: the sky's squared error {mine:.3e} vs {theirs:.3e} uniform"
            );
        }
    }
}

/// The repository's scene `file`, under a uniform sky of `sky` where given.
fn case(name: &'static str, file: &str, sky: Option<f64>, size: u32, spp: u64) -> Case {
    let scene = match sky {
        None => repository_scene(file, |_| {}),
        Some(value) => {
            let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
            let bytes = std::fs::read(dir.join(file)).unwrap();
            let loaded = prism_scene::load::load_geometry(
                &bytes,
                &|uri| std::fs::read(dir.join(file).parent().unwrap().join(uri)),
                None,
            )
            .unwrap();
            let options = prism_scene::world::SceneOptions::default()
                .environment(Some(Environment::Uniform(SceneSpectrum::Constant(value))));
            Scene::from_loaded(loaded, &options).unwrap()
        }
    };
    Case {
        name,
        scene,
        size,
        spp,
        seeds: 8,
        block: 8,
        polarized: false,
    }
}

/// Renders every allowed combination of `cases` at `wavelengths` against the reference
/// mode with the same light-path setting, and fails naming each combination whose
/// expectation differs. (Light paths off against on is a comparison of its own,
/// [`light_paths_agree`]: without them a caustic is found by camera paths alone, whose
/// rare bright samples make a block's mean over 64 samples skewed, and Welch's test,
/// which assumes it normal, then sees a difference where there is none.)
fn run_matrix(cases: Vec<Case>, wavelengths: &[usize], keep: impl Fn(&str) -> bool) {
    let mut failures = Vec::new();
    let mut compared = 0;
    for case in &cases {
        for &n in wavelengths {
            let mut references: [Option<Blocks>; 2] = [None, None];
            let all = combinations(case, &[n])
                .into_iter()
                .filter(|c| keep(&c.name))
                .collect();
            for combination in allowed(case, all) {
                let light_paths = combination.settings.light_paths;
                let reference = references[usize::from(light_paths)].get_or_insert_with(|| {
                    render_blocks(
                        case,
                        &reference(case).wavelengths(n).light_paths(light_paths),
                    )
                });
                let blocks = render_blocks(case, &combination.settings);
                let verdict = compare(&blocks, reference);
                compared += 1;
                println!(
                    "{}: {}: smallest p {:.2e} of {} tests ({})",
                    case.name, combination.name, verdict.smallest_p, verdict.tests, verdict.worst
                );
                if verdict.differs() {
                    failures.push(format!(
                        "{}: {}: {}",
                        case.name, combination.name, verdict.worst
                    ));
                }
            }
        }
    }
    assert!(compared > 0);
    assert!(
        failures.is_empty(),
        "{} of {compared} combinations differ from the reference mode:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Where light paths carry a scene's caustics, the reference mode renders the same
/// expectation without them (camera paths then find the caustics alone), at 32 times the
/// samples and 16 seeds, where a block's mean is no longer skewed by their rare bright
/// samples.
fn light_paths_agree(mut case: Case) {
    let on = reference(&case);
    let resolved = prism_integrator::Renderer::new(&case.scene, &on)
        .unwrap()
        .estimators();
    if !resolved.light_paths {
        return;
    }
    case.spp *= 32;
    case.seeds = 16;
    let with = render_blocks(&case, &reference(&case));
    let without = render_blocks(&case, &reference(&case).light_paths(false));
    let verdict = compare(&without, &with);
    println!(
        "{}: light paths off against on: smallest p {:.2e} of {} tests ({})",
        case.name, verdict.smallest_p, verdict.tests, verdict.worst
    );
    assert!(
        !verdict.differs(),
        "{}: light paths off differ: {verdict:?}",
        case.name
    );
}

/// The default run's slice of the matrix: the Cornell box (where reuse, splitting and
/// adaptive sampling all apply) and the medium furnace (the volumetric tracer, spectral
/// bands that differ from its colour), 8 wavelengths, light paths on.
#[test]
fn allowed_combinations_render_the_reference_expectation() {
    if std::env::var_os("PRISM_ESTIMATOR_MATRIX").is_some() {
        return run_full_matrix();
    }
    let cases = vec![
        case("Cornell box", "cornell-box.gltf", None, 24, 64),
        case(
            "medium furnace",
            "assets/medium-furnace.gltf",
            Some(0.5),
            24,
            16,
        ),
    ];
    run_matrix(cases, &[8], |name| name.contains("light paths true"));
}

/// The whole matrix: a scene of every estimator, every combination, 1, 4 and 8
/// wavelengths.
fn run_full_matrix() {
    let mut polarized = case(
        "specular box, polarized",
        "cornell-specular.gltf",
        None,
        24,
        16,
    );
    polarized.polarized = true;
    let cases = vec![
        case("Cornell box", "cornell-box.gltf", None, 24, 64),
        case("specular box", "cornell-specular.gltf", None, 24, 64),
        case("glossy box", "cornell-glossy.gltf", None, 24, 64),
        case("caustic box", "cornell-caustic.gltf", None, 24, 64),
        case(
            "medium furnace",
            "assets/medium-furnace.gltf",
            Some(0.5),
            24,
            16,
        ),
        case("medium box", "cornell-medium.gltf", None, 24, 64),
        case("fluorescent box", "cornell-spectral.gltf", None, 24, 64),
        case(
            "media showcase (fluorescent dye)",
            "media.gltf",
            None,
            24,
            16,
        ),
        case("textured sky", "textured-sky.gltf", None, 24, 64),
        case("thin lens", "bokeh.gltf", None, 24, 64),
        case("lens system", "lens-chart.gltf", None, 24, 64),
        polarized,
    ];
    run_matrix(cases, &[1, 4, 8], |_| true);
    for (name, file) in [
        ("specular box", "cornell-specular.gltf"),
        ("caustic box", "cornell-caustic.gltf"),
        ("textured sky", "textured-sky.gltf"),
    ] {
        light_paths_agree(case(name, file, None, 24, 64));
    }
}

/// The test has power, and knows its noise: the reference mode against itself under other
/// seeds passes, and the same renders with one channel a few percent off fail (the
/// smallest bias each channel's test catches is printed).
#[test]
fn the_matrix_test_passes_equal_expectations_and_fails_a_bias() {
    let mut case = case("Cornell box", "cornell-box.gltf", None, 24, 64);
    let settings = reference(&case);
    let a = render_blocks(&case, &settings);
    case.seeds = 16;
    let b: Vec<_> = render_blocks(&case, &settings)
        .into_iter()
        .map(|(name, seeds)| (name, seeds[8..].to_vec()))
        .collect();
    let verdict = compare(&a, &b);
    assert!(
        !verdict.differs(),
        "the reference mode differs from itself: {verdict:?}"
    );
    assert!(verdict.tests >= 9 * 18, "{} tests", verdict.tests);
    for (channel, bias) in [
        ("S0 band 525 nm", 0.05),
        ("energy", 0.03),
        ("Y", 0.03),
        ("albedo.G", 0.02),
    ] {
        // The smallest bias, in steps of 0.5%, that fails the test.
        let found = (1..=40)
            .map(|k| 0.005 * f64::from(k))
            .find(|f| compare(&scaled(&a, channel, 1.0 + f), &b).differs());
        println!("{channel}: a bias of {found:?} fails");
        assert!(
            found.is_some_and(|f| f <= bias),
            "{channel}: a bias of {bias} passed (the smallest that fails: {found:?})"
        );
    }
    // The outputs every render of the matrix writes.
    let names: Vec<&str> = a.iter().map(|(n, _)| n.as_str()).collect();
    for name in [
        "X",
        "S0 band 425 nm",
        "energy",
        "photons",
        "albedo.R",
        "normal.Z",
        "depth.Z",
    ] {
        assert!(names.contains(&name), "{name} missing from {names:?}");
    }
}

/// The batch tracer is not kept: asking for it (at any width) resolves to the path
/// tracer, says why, and renders the path tracer's film.
#[test]
fn the_batch_tracer_resolves_to_the_path_tracer() {
    let scene = common::cornell();
    let paths = RenderSettings::default().width(8).height(8).samples(0..4);
    let (reference, _) = render(&scene, &paths).unwrap();
    for width in [None, Some(4), Some(8), Some(16)] {
        let lanes = paths
            .clone()
            .tracing(prism_integrator::Tracing::Lanes(width));
        let (film, stats) = render(&scene, &lanes).unwrap();
        assert_eq!(stats.estimators.tracer, prism_integrator::TracerKind::Paths);
        assert!(
            stats.estimators.tracer_why.contains("not kept"),
            "{}",
            stats.estimators
        );
        assert!(
            film == reference,
            "{width:?}: the film differs from the path tracer's"
        );
    }
}

/// Combinations the resolution step refuses are refused in one line naming both settings.
#[test]
fn refused_combinations_name_both_settings() {
    let box_ = common::cornell();
    let medium = medium_furnace();
    for (scene, settings, words) in [
        (
            &medium,
            RenderSettings::default().splits(Splits::Fixed(2)),
            ["splits", "media"],
        ),
        (
            &box_,
            RenderSettings::default()
                .splits(Splits::Fixed(2))
                .reuse(Reuse::Fixed(2)),
            ["reuse", "splits"],
        ),
    ] {
        let Err(e) = prism_integrator::Renderer::new(scene, &settings) else {
            panic!("{words:?}: accepted");
        };
        let e = e.to_string();
        assert!(
            words.iter().all(|w| e.contains(w)) && !e.contains('\n'),
            "{words:?}: {e}"
        );
    }
}

/// What the resolution step decides is what the render does, with why: a fixed reuse that
/// the scene cannot share says so, adaptive sampling off says why, and the pilots' choices
/// say they are the pilots'.
#[test]
fn the_estimators_say_why() {
    let box_ = common::cornell();
    let small = RenderSettings::default()
        .width(16)
        .height(16)
        .samples(0..16);
    let e = prism_integrator::Renderer::new(&box_, &small.clone().adaptive(true))
        .unwrap()
        .estimators();
    assert_eq!(e.tracer, prism_integrator::TracerKind::Paths);
    assert!(e.adaptive, "{e}");
    assert!(
        e.reuse_why.contains("pilot") && e.splits_why.contains("pilot"),
        "{e}"
    );
    assert!(
        !e.light_paths && e.light_paths_why.contains("focuses"),
        "{e}"
    );
    let e = prism_integrator::Renderer::new(&box_, &small.clone().adaptive(true).samples(0..10))
        .unwrap()
        .estimators();
    assert!(!e.adaptive && e.adaptive_why.contains("16"), "{e}");
    let e = prism_integrator::Renderer::new(
        &box_,
        &small.clone().polarized(true).reuse(Reuse::Fixed(4)),
    )
    .unwrap()
    .estimators();
    assert_eq!(e.reuse, 1);
    assert!(e.reuse_why.contains("polarized"), "{e}");
    let medium = medium_furnace();
    let e = prism_integrator::Renderer::new(
        &medium,
        &small.clone().splits(Splits::Auto).reuse(Reuse::Fixed(1)),
    )
    .unwrap()
    .estimators();
    assert_eq!(e.tracer, prism_integrator::TracerKind::Volume);
    assert!(e.splits == 1 && e.splits_why.contains("volumetric"), "{e}");
    let e = prism_integrator::Renderer::new(&box_, &small.clone().adaptive(true).piece(true))
        .unwrap()
        .estimators();
    assert!(!e.adaptive && e.adaptive_why.contains("piece"), "{e}");
    let e = prism_integrator::Renderer::new(&box_, &small.clone().denoised(true))
        .unwrap()
        .estimators();
    assert!(e.reuse == 1 && e.reuse_why.contains("denoised"), "{e}");
}

/// The variance buffer estimates the variance of each combination's own pixel means (its
/// expectation differs between estimators, so it is checked against the spread over
/// seeds, not against the reference mode): over the Cornell box, the buffer's image mean
/// and the pixels' variance over 32 seeds agree within 15% for every combination the
/// variance AOV allows (it samples uniformly: adaptive sampling resolves off).
///
/// The renders clamp samples at Y = 2, so that the test knows its noise: both figures are
/// unbiased for the clamped estimator, but the box's rare bright paths make either one
/// swing by 0.86-1.27x between sets of 32 seeds unclamped, and by at most 3.5% clamped.
/// A buffer whose two replicates were correlated by a third would say about 0.7x.
#[test]
fn the_variance_buffer_estimates_each_combinations_own_variance() {
    let case = case("Cornell box", "cornell-box.gltf", None, 24, 64);
    let base = reference(&case)
        .aovs("variance".parse::<prism_integrator::Aovs>().unwrap())
        .clamp(Some(2.0));
    assert_variance_buffer(&case, &base, |base| {
        vec![
            ("reference mode", base.clone()),
            ("splits 2", base.clone().splits(Splits::Fixed(2))),
            ("reuse 2", base.clone().reuse(Reuse::Fixed(2))),
            ("adaptive asked", base.clone().adaptive(true)),
        ]
    });
}

/// Asserts, for each of `combinations(base)`, that the variance buffer's image mean and
/// the pixels' variance over 32 seeds agree within 15%.
fn assert_variance_buffer(
    case: &Case,
    base: &RenderSettings,
    combinations: impl Fn(&RenderSettings) -> Vec<(&'static str, RenderSettings)>,
) {
    for (what, settings) in combinations(base) {
        let space = prism_spectrum::color::RgbSpaceId::Srgb.space();
        let seeds = 32u64;
        let films: Vec<_> = (0..seeds)
            .map(|seed| render(&case.scene, &settings.clone().seed(seed)).unwrap().0)
            .collect();
        let channel = |film: &prism_integrator::Film, name: &str| -> Vec<f64> {
            let images = film.aov_images(space);
            let (_, values) = images.iter().find(|(n, _)| n == name).unwrap();
            values.iter().map(|&v| f64::from(v)).collect()
        };
        let red: Vec<Vec<f64>> = films
            .iter()
            .map(|f| f.to_rgb(space).iter().map(|p| f64::from(p[0])).collect())
            .collect();
        let pixels = red[0].len();
        let observed = (0..pixels)
            .map(|i| {
                let mean = red.iter().map(|r| r[i]).sum::<f64>() / seeds as f64;
                red.iter().map(|r| (r[i] - mean).powi(2)).sum::<f64>() / (seeds - 1) as f64
            })
            .sum::<f64>()
            / pixels as f64;
        let estimated = films
            .iter()
            .map(|f| channel(f, "variance.R").iter().sum::<f64>() / pixels as f64)
            .sum::<f64>()
            / seeds as f64;
        let ratio = estimated / observed;
        assert!(
            (0.85..1.18).contains(&ratio),
            "{what}: the variance buffer says {estimated:.3e}, the seeds {observed:.3e}"
        );
    }
}
