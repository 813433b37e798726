//! The glTF material extensions as images show them (scenes/assets, from
//! scenes/tools/make_assets.py).

mod common;

use std::path::Path;

use common::{assert_success, prism, temp_dir};
use prism_integrator::decode_exr;

fn asset(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../scenes/assets")
        .join(name)
        .to_str()
        .unwrap()
        .to_string()
}

/// The normal-incidence reflectance of a film of index `n1`, `d` nm thick, between air
/// and a dielectric of index `n2`, at `lambda` nm: the closed form of the Airy sum
/// (Hecht, *Optics*, 5th ed., §9.7.1), independent of prism's complex-amplitude code.
fn airy_normal(n1: f64, n2: f64, d: f64, lambda: f64) -> f64 {
    let r01 = (1.0 - n1) / (1.0 + n1);
    let r12 = (n1 - n2) / (n1 + n2);
    let c = (4.0 * std::f64::consts::PI * n1 * d / lambda).cos();
    (r01 * r01 + r12 * r12 + 2.0 * r01 * r12 * c)
        / (1.0 + r01 * r01 * r12 * r12 + 2.0 * r01 * r12 * c)
}

/// KHR_materials_iridescence per wavelength: a smooth film (index 1.3, 500 nm) over a
/// black dielectric (1.5), seen head-on under a flat spectral environment of 1, reflects
/// in each 30 nm band the band's mean Airy reflectance. Its bands (the film's
/// interference) range from 0.6% to 4% here, so a film read as absent (the bare 4% in
/// every band) fails by far more than the tolerance.
#[test]
fn a_thin_film_reflects_its_airy_reflectance_band_by_band() {
    let dir = temp_dir("thin-film");
    let exr = dir.join("film.exr");
    let out = prism(&[
        "render",
        &asset("thin-film.gltf"),
        "--width",
        "16",
        "--height",
        "16",
        "--spp",
        "1024",
        "--lambda-sampler",
        "uniform",
        "--spectral-bands",
        "10",
        "--spectral-range",
        "400:700",
        "-q",
        "-o",
        exr.to_str().unwrap(),
    ]);
    assert_success(&out);
    let image = decode_exr(&std::fs::read(&exr).unwrap()).unwrap();
    let mut checked = 0;
    let (mut lowest, mut highest) = (f64::MAX, 0.0f64);
    for (name, values) in &image.channels {
        let Some(nm) = name.strip_prefix("S0.").and_then(|n| n.strip_suffix("nm")) else {
            continue;
        };
        let centre: f64 = nm.replace(',', ".").parse().unwrap();
        let (lo, hi) = (centre - 15.0, centre + 15.0);
        let steps = 300;
        let expected = (0..steps)
            .map(|k| {
                airy_normal(
                    1.3,
                    1.5,
                    500.0,
                    lo + (hi - lo) * (k as f64 + 0.5) / steps as f64,
                )
            })
            .sum::<f64>()
            / steps as f64;
        let mean = values.iter().map(|&v| f64::from(v)).sum::<f64>() / values.len() as f64;
        lowest = lowest.min(expected);
        highest = highest.max(expected);
        assert!(
            (mean - expected).abs() < 0.04 * expected + 1e-4,
            "band {centre} nm: prism {mean}, Airy {expected}"
        );
        checked += 1;
    }
    assert_eq!(checked, 10);
    assert!(lowest < 0.01 && highest > 0.03, "{lowest} {highest}");
}

/// The white furnace, rendered: seven white spheres, one per glTF material extension at
/// full strength (plain, clear coat, sheen, specular with a coloured F0 above 1,
/// anisotropy, a thin film, diffuse transmission into the sphere and out again), under a uniform white environment (`--environment 1`, which renders a white
/// Lambertian surface as RGB 1) and nothing else, each render as 1 in every channel wherever they are seen: every layer takes from those
/// below what it reflects. An extension that added energy (a coat or sheen without its
/// albedo scaling) or lost it fails. The sphere's rim, where a pixel also sees the
/// background, is left out.
#[test]
fn spheres_with_every_extension_pass_the_white_furnace() {
    let dir = temp_dir("furnace-spheres");
    let exr = dir.join("furnace.exr");
    let (width, height) = (280usize, 40usize);
    let out = prism(&[
        "render",
        &asset("furnace-spheres.gltf"),
        "--width",
        &width.to_string(),
        "--height",
        &height.to_string(),
        "--spp",
        "128",
        "--environment",
        "1",
        "-q",
        "-o",
        exr.to_str().unwrap(),
    ]);
    assert_success(&out);
    let image = decode_exr(&std::fs::read(&exr).unwrap()).unwrap();
    let names = [
        "plain",
        "clear coat",
        "sheen",
        "specular",
        "anisotropy",
        "iridescence",
        "diffuse transmission",
    ];
    for channel in ["R", "G", "B"] {
        let values = &image
            .channels
            .iter()
            .find(|(n, _)| n == channel)
            .unwrap_or_else(|| panic!("no channel {channel}"))
            .1;
        for (k, name) in names.iter().enumerate() {
            // Orthographic: 7 x 1 world units over the image; sphere k at x = -3 + k.
            let (cx, cy) = ((k as f64 + 0.5) * width as f64 / 7.0, height as f64 / 2.0);
            let radius = 0.45 * height as f64 * 0.8;
            let mut sum = 0.0f64;
            let mut count = 0;
            for y in 0..height {
                for x in 0..width {
                    let (dx, dy) = (x as f64 + 0.5 - cx, y as f64 + 0.5 - cy);
                    if dx * dx + dy * dy < radius * radius {
                        sum += f64::from(values[y * width + x]);
                        count += 1;
                    }
                }
            }
            let mean = sum / f64::from(count);
            assert!(count > 100, "{name}: {count} pixels");
            assert!(
                (mean - 1.0).abs() < 0.025,
                "{name} sphere, channel {channel}: {mean}"
            );
        }
    }
}
