//! Emissive textures in transport: a light whose texture is black on one half and white on
//! the other lights a floor as a light of the white half alone does. Light sampling reads
//! the texture where it samples the light, rays that hit the light where they hit it; MIS
//! combines the two, so a mismatch between them would show as a difference; a mirror beside
//! the light adds a caustic, which light paths leaving the textured light carry.

use prism_integrator::{RenderSettings, render};
use prism_scene::load::load_geometry;
use prism_scene::world::{Scene, SceneSpectrum};
use serde_json::{Value, json};

/// A `width` x 1 PNG, black on its left half and white on its right.
fn half_white_png(width: u32) -> Vec<u8> {
    let row: Vec<u8> = (0..width)
        .flat_map(|x| [if x < width / 2 { 0 } else { 255 }; 3])
        .collect();
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, width, 1);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().unwrap();
    writer.write_image_data(&row).unwrap();
    writer.finish().unwrap();
    out
}

/// A square in the plane z from (x0, y0) to (x1, y1), facing +z or -z, with u growing
/// along x and v down y (glTF's image layout).
fn square(x0: f32, y0: f32, x1: f32, y1: f32, z: f32, up: bool) -> (Vec<f32>, Vec<f32>) {
    let corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)];
    let order: [usize; 6] = if up {
        [0, 1, 2, 0, 2, 3]
    } else {
        [0, 2, 1, 0, 3, 2]
    };
    let mut positions = Vec::new();
    let mut uvs = Vec::new();
    for i in order {
        let (x, y) = corners[i];
        positions.extend([x, y, z]);
        uvs.extend([(x - x0) / (x1 - x0), (y1 - y) / (y1 - y0)]);
    }
    (positions, uvs)
}

/// A grey floor under a ceiling light at z = 1 facing down, seen from a pinhole camera
/// between them (light paths connect to pinholes only), with a silver mirror beside them:
/// the light is `light` (x0, x1 over y in [-0.5, 0.5]), emitting `emission` (a glTF
/// material's emissive properties).
fn scene(light: (f32, f32), emission: Value, image: Option<Vec<u8>>) -> Scene {
    let floor = square(-2.0, -2.0, 2.0, 2.0, 0.0, true);
    let lamp = square(light.0, -0.5, light.1, 0.5, 1.0, false);
    let mut bin: Vec<u8> = Vec::new();
    let mut views = Vec::new();
    let mut push = |data: Vec<u8>, bin: &mut Vec<u8>| {
        views.push(json!({"buffer": 0, "byteOffset": bin.len(), "byteLength": data.len()}));
        bin.extend(data);
        views.len() - 1
    };
    let bytes = |v: &[f32]| v.iter().flat_map(|f| f.to_le_bytes()).collect::<Vec<u8>>();
    // A mirror standing on the floor beside the light, facing it: light it reflects onto
    // the floor is a caustic, which light paths (leaving the light where its texture is
    // read at the sampled point) carry.
    let (x, z0, z1) = (1.2f32, 0.05f32, 1.2f32);
    let mirror: Vec<f32> = [
        [x, -1.0, z0],
        [x, 1.0, z1],
        [x, 1.0, z0],
        [x, -1.0, z0],
        [x, -1.0, z1],
        [x, 1.0, z1],
    ]
    .concat();
    let floor_p = push(bytes(&floor.0), &mut bin);
    let mirror_p = push(bytes(&mirror), &mut bin);
    let lamp_p = push(bytes(&lamp.0), &mut bin);
    let lamp_uv = push(bytes(&lamp.1), &mut bin);
    let image_view = image.map(|png| push(png, &mut bin));
    let accessor = |view: usize, kind: &str| json!({"bufferView": view, "componentType": 5126, "count": 6, "type": kind});
    let bounded = |view: usize, p: &[f32]| {
        let (lo, hi) = (0..3).fold(([f32::MAX; 3], [f32::MIN; 3]), |(mut lo, mut hi), k| {
            for v in p.chunks(3) {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
            (lo, hi)
        });
        let mut a = accessor(view, "VEC3");
        a["min"] = json!(lo);
        a["max"] = json!(hi);
        a
    };
    let mut lamp_material = emission;
    lamp_material["pbrMetallicRoughness"] = json!({"baseColorFactor": [0, 0, 0, 1]});
    let mut doc = json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 2, 3]}],
        "nodes": [
            {"mesh": 0},
            {"mesh": 1},
            {"camera": 0, "translation": [0, 0, 0.8]},
            {"mesh": 2}
        ],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 1.7, "znear": 0.01, "aspectRatio": 1.0}}],
        "meshes": [
            {"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]},
            {"primitives": [{"attributes": {"POSITION": 1, "TEXCOORD_0": 2}, "material": 1}]},
            {"primitives": [{"attributes": {"POSITION": 3}, "material": 2}]}
        ],
        "materials": [
            {"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1], "metallicFactor": 0, "roughnessFactor": 1}},
            lamp_material,
            {"extensions": {"PRISM_spectral": {"type": "conductor", "metal": "ag"}}}
        ],
        "accessors": [
            bounded(floor_p, &floor.0),
            bounded(lamp_p, &lamp.0),
            accessor(lamp_uv, "VEC2"),
            bounded(mirror_p, &mirror)
        ],
        "bufferViews": views,
        "buffers": [{"byteLength": bin.len(), "uri": "scene.bin"}],
        // The lamp's emission is no brighter than an emissive colour of 1, which alone
        // would not count as the scene's light: a black environment, stated, keeps the
        // default one out.
        "extensions": {"PRISM_spectral": {"environment": 0.0}}
    });
    if let Some(view) = image_view {
        doc["images"] = json!([{"bufferView": view, "mimeType": "image/png"}]);
        doc["samplers"] = json!([{"wrapS": 33071, "wrapT": 33071}]);
        doc["textures"] = json!([{"source": 0, "sampler": 0}]);
    }
    let loaded = load_geometry(
        &serde_json::to_vec(&doc).unwrap(),
        &move |_| Ok(bin.clone()),
        None,
    )
    .unwrap();
    Scene::from_loaded(loaded, &Default::default()).unwrap()
}

#[test]
fn a_half_white_emissive_texture_lights_as_its_white_half() {
    let textured = scene(
        (-0.5, 0.5),
        json!({"emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0}}),
        Some(half_white_png(64)),
    );
    assert!(matches!(
        textured.emission_spectra(),
        [SceneSpectrum::Texture(_)]
    ));
    assert!(
        textured.features().specular,
        "the mirror's caustics go to light paths"
    );
    let half = scene((0.0, 0.5), json!({"emissiveFactor": [1, 1, 1]}), None);
    let settings = RenderSettings::default()
        .width(16)
        .height(16)
        .samples(0..256);
    let (a, _) = render(&textured, &settings).unwrap();
    let (b, _) = render(&half, &settings).unwrap();
    // Means of 4 x 4 blocks of pixels: the floor is brightest under the white half, and
    // the two images agree block by block within Monte Carlo error (~1% at this count).
    let block = |film: &prism_integrator::Film, bx: u32, by: u32| {
        let mut y = 0.0;
        for py in 4 * by..4 * by + 4 {
            for px in 4 * bx..4 * bx + 4 {
                y += film.xyz(px, py).y;
            }
        }
        y / 16.0
    };
    let (mut left, mut right) = (0.0, 0.0);
    for by in 0..4 {
        for bx in 0..4 {
            let (ya, yb) = (block(&a, bx, by), block(&b, bx, by));
            assert!(
                (ya - yb).abs() < 0.03 * yb + 1e-3,
                "block ({bx}, {by}): {ya} vs {yb}"
            );
            if bx < 2 {
                left += ya;
            } else {
                right += ya;
            }
        }
    }
    assert!(
        right > 1.5 * left,
        "brighter under the white half: {right} vs {left}"
    );
}
