//! prism against an independent spectral renderer: the 8 x 8 region means of the Cornell
//! box, the bunny box, the volume box and the box's specular, glossy and caustic kinds
//! agree with Mitsuba 3's converged renders (the fixtures
//! `data/cornell-{box,bunny,medium,specular,glossy,caustic}-mitsuba-regions.json` and their
//! provenance) within 1% plus Monte Carlo error.
//!
//! Slow (millions of paths): `cargo test --release -p prism-integrator --test reference --
//! --ignored`.

// Channel loops index several parallel arrays by k.
#![allow(clippy::needless_range_loop)]

mod common;

use common::repository_scene;
use prism_integrator::{RenderSettings, render};
use prism_scene::world::Scene;
use prism_spectrum::color::RgbSpaceId;

/// Region means (grid x grid, row-major, linear sRGB) of a render at `size` x `size`.
fn region_means(scene: &Scene, size: u32, spp: u64, seed: u64, grid: usize) -> Vec<[f64; 3]> {
    let settings = RenderSettings::default()
        .width(size)
        .height(size)
        .samples(0..spp)
        .seed(seed);
    let (film, _) = render(scene, &settings).unwrap();
    let rgb = film.to_rgb(RgbSpaceId::Srgb.space());
    let cell = size as usize / grid;
    let mut means = vec![[0.0f64; 3]; grid * grid];
    for (i, p) in rgb.iter().enumerate() {
        let (x, y) = (i % size as usize, i / size as usize);
        let m = &mut means[(y / cell) * grid + x / cell];
        for k in 0..3 {
            m[k] += f64::from(p[k]) / (cell * cell) as f64;
        }
    }
    means
}

/// Asserts that `scene` (of the repository) agrees with the Mitsuba fixture `fixture`
/// region by region: 4 seeds of 64^2 x 256 paths, within 1% of the reference (2% of the
/// peak for the dark surround) beyond 4 sigma of their spread.
fn assert_agrees_with_mitsuba(scene: &str, fixture: &str) {
    assert_agrees_with_mitsuba_within(scene, fixture, 0.01);
}

/// [`assert_agrees_with_mitsuba`] with a relative `tolerance` beyond 4 sigma.
fn assert_agrees_with_mitsuba_within(scene: &str, fixture: &str, tolerance: f64) {
    let fixture: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("tests/data")
                .join(fixture),
        )
        .unwrap(),
    )
    .unwrap();
    let grid = fixture["grid"].as_u64().unwrap() as usize;
    let reference: Vec<[f64; 3]> = fixture["regions"]
        .as_array()
        .unwrap()
        .iter()
        .flat_map(|row| row.as_array().unwrap().iter())
        .map(|c| [0, 1, 2].map(|k| c[k].as_f64().unwrap()))
        .collect();
    let scene = repository_scene(scene, |_| {});
    let batches: Vec<Vec<[f64; 3]>> = (0..4)
        .map(|seed| region_means(&scene, 64, 256, 100 + seed, grid))
        .collect();
    let n = batches.len() as f64;
    let peak = reference.iter().flatten().cloned().fold(0.0, f64::max);
    let mut worst = (0.0f64, 0usize, 0usize);
    for (r, want) in reference.iter().enumerate() {
        for k in 0..3 {
            let values: Vec<f64> = batches.iter().map(|b| b[r][k]).collect();
            let mean = values.iter().sum::<f64>() / n;
            let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
            let sigma = (var / n).sqrt();
            // Regions with almost no light (the black surround) are judged absolutely.
            let scale = want[k].max(0.02 * peak);
            let excess = ((mean - want[k]).abs() - 4.0 * sigma).max(0.0) / scale;
            if excess > worst.0 {
                worst = (excess, r, k);
            }
            assert!(
                excess <= tolerance,
                "region {r} channel {k}: prism {mean} +- {sigma}, Mitsuba {}",
                want[k]
            );
        }
    }
    eprintln!(
        "worst relative excess beyond 4 sigma: {:.4} (region {}, channel {})",
        worst.0, worst.1, worst.2
    );
}

#[test]
#[ignore = "slow: renders 4 x 64^2 x 256 paths; run before resolving the integrator issue"]
fn cornell_box_agrees_with_mitsuba_within_one_percent() {
    assert_agrees_with_mitsuba("cornell-box.gltf", "cornell-box-mitsuba-regions.json");
}

#[test]
#[ignore = "slow: renders 4 x 64^2 x 256 paths; run before resolving the integrator issue"]
fn bunny_box_agrees_with_mitsuba_within_one_percent() {
    assert_agrees_with_mitsuba("cornell-bunny.gltf", "cornell-bunny-mitsuba-regions.json");
}

/// The volume scene: the Cornell box's large block a chromatic scattering medium (sigma_s
/// falling with wavelength, an absorption band at 600 nm, g = 0.5), against Mitsuba 3's
/// `volpathmis` (benches/peer/mitsuba_media.py builds it from the same glTF file).
#[test]
#[ignore = "slow: renders 4 x 64^2 x 256 paths; run before resolving the media issue"]
fn medium_box_agrees_with_mitsuba_volpathmis_within_one_percent() {
    assert_agrees_with_mitsuba("cornell-medium.gltf", "cornell-medium-mitsuba-regions.json");
}

/// The box's scene kinds (benches/peer/mitsuba_kinds.py builds each in Mitsuba from the
/// same glTF file): light through smooth glass and off smooth gold, glossy metals and
/// glass, and a caustic, where light paths and camera paths split the work.
#[test]
#[ignore = "slow: renders 4 x 64^2 x 256 paths; run before resolving the speed issue"]
fn specular_box_agrees_with_mitsuba_within_one_percent() {
    assert_agrees_with_mitsuba(
        "cornell-specular.gltf",
        "cornell-specular-mitsuba-regions.json",
    );
}

#[test]
#[ignore = "slow: renders 4 x 64^2 x 256 paths; run before resolving the speed issue"]
fn glossy_box_agrees_with_mitsuba_within_one_percent() {
    assert_agrees_with_mitsuba("cornell-glossy.gltf", "cornell-glossy-mitsuba-regions.json");
}

#[test]
#[ignore = "slow: renders 4 x 64^2 x 256 paths; run before resolving the speed issue"]
fn caustic_box_agrees_with_mitsuba_within_one_percent() {
    assert_agrees_with_mitsuba(
        "cornell-caustic.gltf",
        "cornell-caustic-mitsuba-regions.json",
    );
}

/// A textured asset under an HDR sky: sRGB textures and the sky upsampled per lookup, the
/// sun found by the sky's importance sampling, a rough gold sphere reflecting both. Within
/// 1.5% (the worst region measured 0.96% beyond 4 sigma): Mitsuba is given the sky four
/// times finer (`benches/peer/mitsuba_kinds.py`, `resampled_sky`), since its spectral
/// `envmap` blends neighbouring texels' colours apart from their brightness; given the sky
/// as it is, its horizon and the sun-lit floor differed from prism's (and from its own RGB
/// variant's, which prism matches within 0.2%) by 1.5-3.4%. What remains is the two
/// renderers' upsampling of the textures and, prism rendering at half the reference's
/// resolution, the textures' footprint filtering.
#[test]
#[ignore = "slow: renders 4 x 64^2 x 256 paths; run before resolving the speed issue"]
fn textured_sky_agrees_with_mitsuba_within_upsampling() {
    assert_agrees_with_mitsuba_within(
        "textured-sky.gltf",
        "textured-sky-mitsuba-regions.json",
        0.015,
    );
}
