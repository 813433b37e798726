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

/// Each material extension changes what a sphere looks like: the furnace spheres made grey
/// and lit by a point light and a dim environment render differently, sphere by sphere,
/// from the same file with the extensions removed (a factor read and then ignored
/// fails). Sphere 0, with no extension, is the control.
#[test]
fn every_extension_changes_its_sphere() {
    let dir = temp_dir("extension-spheres");
    let mut doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(asset("furnace-spheres.gltf")).unwrap())
            .unwrap();
    for m in doc["materials"].as_array_mut().unwrap() {
        m["pbrMetallicRoughness"]["baseColorFactor"] = serde_json::json!([0.3, 0.3, 0.3, 1.0]);
        // Anisotropy shapes a highlight: on metal, the highlight is what there is.
        if m["name"] == "anisotropy" {
            m["pbrMetallicRoughness"]["metallicFactor"] = serde_json::json!(1.0);
        }
        // A film colours the coating's reflection: over a black base, it is all there is.
        if m["name"] == "iridescence" {
            m["pbrMetallicRoughness"]["baseColorFactor"] = serde_json::json!([0.0, 0.0, 0.0, 1.0]);
        }
    }
    doc["extensions"]["KHR_lights_punctual"] =
        serde_json::json!({"lights": [{"type": "point", "intensity": 300.0}]});
    doc["extensionsUsed"]
        .as_array_mut()
        .unwrap()
        .push(serde_json::json!("KHR_lights_punctual"));
    let light = doc["nodes"].as_array().unwrap().len();
    doc["nodes"]
        .as_array_mut()
        .unwrap()
        .push(serde_json::json!({
            "translation": [-1.5, 1.5, 2.5],
            "extensions": {"KHR_lights_punctual": {"light": 0}}
        }));
    doc["scenes"][0]["nodes"]
        .as_array_mut()
        .unwrap()
        .push(serde_json::json!(light));
    let mut plain = doc.clone();
    for m in plain["materials"].as_array_mut().unwrap() {
        m.as_object_mut().unwrap().remove("extensions");
    }
    let (width, height) = (280usize, 40usize);
    let render = |doc: &serde_json::Value, name: &str| {
        let gltf = dir.join(format!("{name}.gltf"));
        std::fs::write(&gltf, serde_json::to_vec(doc).unwrap()).unwrap();
        let exr = dir.join(format!("{name}.exr"));
        let out = prism(&[
            "render",
            gltf.to_str().unwrap(),
            "--width",
            &width.to_string(),
            "--height",
            &height.to_string(),
            "--spp",
            "64",
            "--environment",
            "0.1",
            "-q",
            "-o",
            exr.to_str().unwrap(),
        ]);
        assert_success(&out);
        decode_exr(&std::fs::read(&exr).unwrap()).unwrap()
    };
    let (with, without) = (render(&doc, "with"), render(&plain, "without"));
    // Over sphere k's disk (as in the furnace test), pixel by pixel: sum |a - b| / sum b.
    // The same seed gives a sphere whose material did not change the same samples, so an
    // extension read and ignored shows as (nearly) no difference, noise or not.
    let difference = |k: usize| {
        let (cx, cy) = ((k as f64 + 0.5) * width as f64 / 7.0, height as f64 / 2.0);
        let radius = 0.45 * height as f64 * 0.8;
        let (mut changed, mut total) = (0.0f64, 0.0f64);
        for c in ["R", "G", "B"] {
            let a = &with.channels.iter().find(|(n, _)| n == c).unwrap().1;
            let b = &without.channels.iter().find(|(n, _)| n == c).unwrap().1;
            for y in 0..height {
                for x in 0..width {
                    let (dx, dy) = (x as f64 + 0.5 - cx, y as f64 + 0.5 - cy);
                    if dx * dx + dy * dy < radius * radius {
                        let i = y * width + x;
                        changed += f64::from((a[i] - b[i]).abs());
                        total += f64::from(b[i]);
                    }
                }
            }
        }
        changed / total.max(1e-9)
    };
    let names = [
        "plain",
        "clear coat",
        "sheen",
        "specular",
        "anisotropy",
        "iridescence",
        "diffuse transmission",
    ];
    for (k, name) in names.iter().enumerate() {
        let change = difference(k);
        if k == 0 {
            assert!(change < 0.02, "{name} changed by {change}");
        } else {
            assert!(change > 0.05, "{name} changed by only {change}");
        }
        eprintln!("{name}: {change:.3}");
    }
}
