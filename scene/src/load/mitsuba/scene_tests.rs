//! The Mitsuba converter against the same scene in glTF: Mitsuba's `mi.cornell_box()`
//! (scenes/mitsuba/cornell-box.xml, written and checked by Mitsuba itself through
//! scenes/tools/make_mitsuba_scenes.py) and scenes/cornell-box.gltf, which reproduces it.

use glam::Vec3;
use prism_spectrum::Spectrum;

use super::ParseOptions;
use super::scene::load;
use crate::load::{LoadOptions, LoadedGeometry, load_geometry};

fn repository(file: &str) -> String {
    format!("{}/../scenes/{file}", env!("CARGO_MANIFEST_DIR"))
}

fn mitsuba_box() -> super::scene::MitsubaScene {
    let text = std::fs::read_to_string(repository("mitsuba/cornell-box.xml")).unwrap();
    let none = |name: &str| -> std::io::Result<Vec<u8>> {
        Err(std::io::Error::other(format!("no file {name}")))
    };
    let options = ParseOptions {
        defines: &[],
        resolve: &none,
    };
    load(&text, "cornell-box.xml", &options, &LoadOptions::default()).unwrap()
}

fn gltf_box() -> LoadedGeometry {
    let path = repository("cornell-box.gltf");
    let bytes = std::fs::read(&path).unwrap();
    let dir = std::path::PathBuf::from(path)
        .parent()
        .unwrap()
        .to_path_buf();
    load_geometry(&bytes, &move |uri| std::fs::read(dir.join(uri)), None).unwrap()
}

/// The faces `triangles` make: per plane and facing (unit normal of the winding, offset),
/// the corners on it and the area covered, quantized to 0.1 mm. Quads split along either
/// diagonal make the same face.
fn faces(triangles: &[[Vec3; 3]]) -> Vec<([i64; 4], Vec<[i64; 3]>, i64)> {
    let q = |v: f32| (v * 1e4).round() as i64;
    let mut out: std::collections::BTreeMap<[i64; 4], (Vec<[i64; 3]>, f32)> = Default::default();
    for t in triangles {
        let cross = (t[1] - t[0]).cross(t[2] - t[0]);
        let n = cross.normalize();
        let key = [q(n.x), q(n.y), q(n.z), q(n.dot(t[0]))];
        let face = out.entry(key).or_default();
        for v in t {
            let c = [q(v.x), q(v.y), q(v.z)];
            if !face.0.contains(&c) {
                face.0.push(c);
            }
        }
        face.1 += cross.length() / 2.0;
    }
    out.into_iter()
        .map(|(k, (mut corners, area))| {
            corners.sort();
            (k, corners, q(area))
        })
        .collect()
}

/// Both files make the same faces (to 0.1 mm), facing the same way: the light emits
/// downwards, and Mitsuba's rectangles and cubes are placed as the glTF's.
#[test]
fn the_box_has_the_gltf_boxs_faces() {
    let mitsuba = mitsuba_box();
    let gltf = gltf_box();
    assert_eq!(mitsuba.geometry.triangles.len(), gltf.triangles.len());
    assert_eq!(faces(&mitsuba.geometry.triangles), faces(&gltf.triangles));
}

/// The sensor is the glTF camera: the same place, direction and field of view.
#[test]
fn the_sensor_is_the_gltf_camera() {
    let mitsuba = mitsuba_box();
    let gltf = gltf_box();
    let (a, b) = (&mitsuba.geometry.cameras[0], &gltf.cameras[0]);
    assert!(
        a.to_world.abs_diff_eq(b.to_world, 1e-5),
        "{:?} {:?}",
        a.to_world,
        b.to_world
    );
    match (a.projection, b.projection) {
        (
            crate::camera::Projection::Perspective { yfov: x },
            crate::camera::Projection::Perspective { yfov: y },
        ) => assert!((x - y).abs() < 1e-5, "{x} {y}"),
        other => panic!("{other:?}"),
    }
    assert_eq!(
        (mitsuba.film.width, mitsuba.film.height, mitsuba.film.spp),
        (256, 256, Some(64))
    );
    assert_eq!(mitsuba.max_depth, Some(7));
}

/// The BSDFs are Lambertian with the glTF's base colours, upsampled alike, and the light
/// emits the glTF's emission spectrum.
#[test]
fn the_box_has_the_gltf_boxs_colours_and_light() {
    let mitsuba = mitsuba_box();
    let gltf = gltf_box();
    let by_name = |name: &str| gltf.materials.iter().find(|m| m.name == name).unwrap();
    let at = |s: &crate::textures::SceneSpectrum| -> Vec<f64> {
        (380..=780)
            .step_by(20)
            .map(|l| s.evaluate(f64::from(l)))
            .collect()
    };
    let rgb = |s: &prism_upsample::RgbSpectrum| -> Vec<f64> {
        at(&crate::textures::SceneSpectrum::Rgb(std::sync::Arc::new(
            s.clone(),
        )))
    };
    for name in ["white", "red", "green"] {
        let m = mitsuba
            .geometry
            .materials
            .iter()
            .find(|m| m.name == name)
            .unwrap();
        let surface = m.spectral.as_ref().and_then(|s| s.surface.clone());
        let Some(crate::materials::Material::Diffuse { reflectance }) = surface else {
            panic!("{name}: {surface:?}");
        };
        assert_eq!(at(&reflectance), rgb(&by_name(name).base_color), "{name}");
    }
    let emitting: Vec<_> = mitsuba
        .geometry
        .materials
        .iter()
        .filter(|m| m.emits())
        .collect();
    assert_eq!(emitting.len(), 1);
    let emission = emitting[0].emission_spectrum().unwrap();
    let gltf_emission = by_name("white-emitter").emission_spectrum().unwrap();
    // glTF's colour is its emissive factor times the strength, each a 32-bit float.
    for (a, b) in at(&emission).iter().zip(at(&gltf_emission)) {
        assert!((a - b).abs() <= 1e-6 * b, "{a} {b}");
    }
    assert_eq!(mitsuba.geometry.lights.len(), 1);
}
