//! Colour textures: decoding, wrapping, filtering, KHR_texture_transform, and upsampling
//! per lookup, loaded from a glTF with an embedded PNG.

use std::sync::Arc;

use glam::{Vec2, Vec3};
use prism_scene::bsdf::MetallicRoughness;
use prism_scene::geometry::Ray;
use prism_scene::load::{LoadedGeometry, decode_image, load_geometry};
use prism_scene::world::{
    EmissionCache, Encoding, Hit, Material, RgbTexture, Scene, SceneOptions, SceneSpectrum,
    UvTransform, Wrap,
};
use prism_spectrum::SampledWavelengths;
use prism_spectrum::Spectrum;
use prism_spectrum::color::RgbSpaceId;
use proptest::prelude::*;
use serde_json::json;

fn png(width: u32, height: u32, rgb: &[[u8; 3]]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, width, height);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().unwrap();
    writer.write_image_data(&rgb.concat()).unwrap();
    writer.finish().unwrap();
    out
}

fn texture(wrap: Wrap, transform: UvTransform) -> RgbTexture {
    // 2 x 2: red, green / blue, white.
    let texels = vec![[255, 0, 0], [0, 255, 0], [0, 0, 255], [255, 255, 255]];
    RgbTexture::new(2, 2, Arc::new(texels), [wrap; 2], transform, [1.0; 3]).unwrap()
}

fn close(a: [f32; 3], b: [f32; 3]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-5)
}

#[test]
fn texel_centres_return_their_texels_and_wrap_modes_differ() {
    let t = texture(Wrap::Repeat, UvTransform::default());
    assert!(close(t.sample(Vec2::new(0.25, 0.25)), [1.0, 0.0, 0.0]));
    assert!(close(t.sample(Vec2::new(0.75, 0.25)), [0.0, 1.0, 0.0]));
    assert!(close(t.sample(Vec2::new(0.25, 0.75)), [0.0, 0.0, 1.0]));
    // Halfway between red and green: the mean in linear RGB.
    assert!(close(t.sample(Vec2::new(0.5, 0.25)), [0.5, 0.5, 0.0]));
    // Repeat: u = 1.25 is u = 0.25; clamp: it is the right edge (green); mirror: the
    // mirrored copy starts with the right column again.
    assert!(close(t.sample(Vec2::new(1.25, 0.25)), [1.0, 0.0, 0.0]));
    let c = texture(Wrap::Clamp, UvTransform::default());
    assert!(close(c.sample(Vec2::new(1.25, 0.25)), [0.0, 1.0, 0.0]));
    let m = texture(Wrap::Mirror, UvTransform::default());
    assert!(close(m.sample(Vec2::new(1.25, 0.25)), [0.0, 1.0, 0.0]));
    assert!(close(m.sample(Vec2::new(1.75, 0.25)), [1.0, 0.0, 0.0]));
    // sRGB decoding: 128 is 0.2158 linear.
    let grey = RgbTexture::new(
        1,
        1,
        Arc::new(vec![[128; 3]]),
        [Wrap::Repeat; 2],
        UvTransform::default(),
        [1.0; 3],
    )
    .unwrap();
    assert!(close(grey.sample(Vec2::ZERO), [0.215_861; 3]));
}

/// glTF's NEAREST magnification: the texel under the point, so that between two texels'
/// centres there is no blend (LINEAR gives their mean there).
#[test]
fn nearest_filtering_takes_the_texel_under_the_point() {
    let t = texture(Wrap::Repeat, UvTransform::default()).nearest();
    assert!(close(t.sample(Vec2::new(0.49, 0.25)), [1.0, 0.0, 0.0]));
    assert!(close(t.sample(Vec2::new(0.51, 0.25)), [0.0, 1.0, 0.0]));
    assert!(close(t.sample(Vec2::new(0.99, 0.99)), [1.0, 1.0, 1.0]));
    // Wrapping applies as before: u = 1.1 is u = 0.1 (red).
    assert!(close(t.sample(Vec2::new(1.1, 0.25)), [1.0, 0.0, 0.0]));
}

#[test]
fn texture_transform_scales_rotates_then_offsets() {
    // Scale by 0.5 maps u = 0.5 to 0.25 (red); an offset of 0.5 moves it to green.
    let scaled = texture(
        Wrap::Repeat,
        UvTransform {
            scale: Vec2::splat(0.5),
            ..Default::default()
        },
    );
    assert!(close(scaled.sample(Vec2::new(0.5, 0.5)), [1.0, 0.0, 0.0]));
    let shifted = texture(
        Wrap::Repeat,
        UvTransform {
            offset: Vec2::new(0.5, 0.0),
            ..Default::default()
        },
    );
    assert!(close(
        shifted.sample(Vec2::new(0.25, 0.25)),
        [0.0, 1.0, 0.0]
    ));
    // The extension's rotation: (u, v) -> (cos u + sin v, -sin u + cos v); a quarter turn
    // takes (0.25, -0.75) to (-0.75, -0.25), which repeats to (0.25, 0.75): blue.
    let turned = texture(
        Wrap::Repeat,
        UvTransform {
            rotation: std::f32::consts::FRAC_PI_2,
            ..Default::default()
        },
    );
    assert!(
        close(turned.sample(Vec2::new(0.25, -0.75)), [0.0, 0.0, 1.0]),
        "{:?}",
        turned.sample(Vec2::new(0.25, -0.75))
    );
}

proptest! {
    #[test]
    fn sampling_is_finite_anywhere(u in prop::num::f32::ANY, v in prop::num::f32::ANY, wrap in 0..3usize) {
        let wrap = [Wrap::Repeat, Wrap::Clamp, Wrap::Mirror][wrap];
        let t = texture(wrap, UvTransform { rotation: 0.3, scale: Vec2::new(1e30, -2.0), offset: Vec2::new(-1e-40, 7.0) });
        let c = t.sample(Vec2::new(u, v));
        prop_assert!(c.iter().all(|x| x.is_finite() && *x >= 0.0 && *x <= 1.0), "{c:?}");
    }
}

#[test]
fn broken_images_are_errors_not_panics() {
    let good = png(2, 1, &[[255, 0, 0], [0, 255, 0]]);
    let decoded = decode_image(&good).unwrap();
    assert_eq!((decoded.width, decoded.height), (2, 1));
    assert_eq!(decoded.rgb, vec![[255, 0, 0], [0, 255, 0]]);
    for (bytes, expected) in [
        (good[..good.len() / 2].to_vec(), "PNG"),
        (b"GIF89a".to_vec(), "not a PNG, JPEG or WebP"),
        (vec![0xFF, 0xD8, 0xFF, 0xE0, 0, 0, 1, 2, 3], "JPEG"),
        (vec![0xFF, 0xD8], "JPEG"),
    ] {
        let e = decode_image(&bytes).expect_err("should fail");
        assert!(e.to_string().contains(expected), "{e}");
    }
}

/// A glTF quad (u from 0 at the left to 1 at the right) with material 0 `material`, whose
/// texture 0 is `image` (a PNG) in the binary buffer.
fn textured_quad(image: &[u8], material: serde_json::Value) -> (serde_json::Value, Vec<u8>) {
    let mut bin: Vec<u8> = [
        0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0,
    ]
    .iter()
    .flat_map(|f| f.to_le_bytes())
    .collect();
    let uv_offset = bin.len();
    bin.extend(
        [
            0.0f32, 1.0, 1.0, 1.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0,
        ]
        .iter()
        .flat_map(|f| f.to_le_bytes()),
    );
    let image_offset = bin.len();
    bin.extend(image);
    let doc = json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
        "materials": [material],
        "textures": [{"source": 0}],
        "images": [{"bufferView": 2, "mimeType": "image/png"}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 6, "type": "VEC2"}
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": uv_offset},
            {"buffer": 0, "byteOffset": uv_offset, "byteLength": image_offset - uv_offset},
            {"buffer": 0, "byteOffset": image_offset, "byteLength": image.len()}
        ],
        "buffers": [{"byteLength": bin.len(), "uri": "quad.bin"}]
    });
    (doc, bin)
}

fn load_quad(doc: &serde_json::Value, bin: Vec<u8>) -> LoadedGeometry {
    load_geometry(
        &serde_json::to_vec(doc).unwrap(),
        &move |_| Ok(bin.clone()),
        None,
    )
    .unwrap()
}

/// A glTF quad whose base colour is a 2 x 1 PNG (red | green) in the binary buffer: the
/// loaded material's reflectance follows the texture, red at the left, green at the right.
#[test]
fn gltf_base_colour_textures_become_spectra() {
    let image = png(2, 1, &[[255, 0, 0], [0, 255, 0]]);
    let (doc, bin) = textured_quad(
        &image,
        json!({"name": "checker", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}}),
    );
    let loaded = load_quad(&doc, bin);
    assert!(loaded.materials[0].base_color_texture.is_some());
    let scene = Scene::from_loaded(loaded, &SceneOptions::default()).unwrap();
    let Material::Diffuse { reflectance } = &scene.materials()[0] else {
        panic!("a rough non-metal is Lambertian")
    };
    assert!(matches!(reflectance, SceneSpectrum::Texture(_)));
    let lambdas = SampledWavelengths::new([530.0, 650.0], [1.0, 1.0]).unwrap();
    let left = reflectance.at_uv(Vec2::new(0.25, 0.5), &lambdas);
    let right = reflectance.at_uv(Vec2::new(0.75, 0.5), &lambdas);
    assert!(left[1] > 0.8 && left[0] < 0.2, "red texel: {left:?}");
    assert!(right[0] > 0.6 && right[1] < 0.2, "green texel: {right:?}");
    // A missing image file is an error naming the image.
    let mut doc = doc.clone();
    doc["images"] = json!([{"uri": "missing.png"}]);
    let result = load_geometry(
        &serde_json::to_vec(&doc).unwrap(),
        &|uri| {
            if uri == "quad.bin" {
                Ok(vec![0; 4096])
            } else {
                Err(std::io::Error::other("no such file"))
            }
        },
        None,
    );
    let Err(e) = result else {
        panic!("should fail")
    };
    assert!(e.to_string().contains("image 0"), "{e}");
}

/// Metallic-roughness textures hold data, not colour: bytes read linearly.
#[test]
fn linear_textures_read_bytes_as_fractions() {
    let grey = RgbTexture::new(
        1,
        1,
        Arc::new(vec![[128, 51, 255]]),
        [Wrap::Repeat; 2],
        UvTransform::default(),
        [1.0; 3],
    )
    .unwrap()
    .encoded(Encoding::Linear);
    assert!(close(grey.sample(Vec2::ZERO), [128.0 / 255.0, 0.2, 1.0]));
    assert!(close(grey.mean(), [128.0 / 255.0, 0.2, 1.0]));
}

/// A quad whose metallic-roughness texture is matte dielectric at the left (green 255:
/// roughness 1, blue 0: metallic 0) and polished metal at the right (green 51, blue 255),
/// under factors metallic 1, roughness 0.5: each hit's BSDF is the glTF BSDF of the
/// texel's values times the factors, and the rough non-metal shortcut to Lambertian is
/// not taken.
#[test]
fn gltf_metallic_roughness_textures_vary_the_bsdf_across_the_surface() {
    let image = png(2, 1, &[[0, 255, 0], [0, 51, 255]]);
    let (doc, bin) = textured_quad(
        &image,
        json!({"pbrMetallicRoughness": {
            "baseColorFactor": [0.8, 0.6, 0.4, 1.0],
            "metallicFactor": 1.0,
            "roughnessFactor": 0.5,
            "metallicRoughnessTexture": {"index": 0}
        }}),
    );
    let loaded = load_quad(&doc, bin.clone());
    let texture = loaded.materials[0]
        .metallic_roughness_texture
        .clone()
        .unwrap();
    assert!(close(texture.sample(Vec2::new(0.25, 0.5)), [0.0, 0.5, 0.0]));
    assert!(close(texture.sample(Vec2::new(0.75, 0.5)), [0.0, 0.1, 1.0]));
    let scene = Scene::from_loaded(loaded, &SceneOptions::default()).unwrap();
    let material = &scene.materials()[0];
    let Material::MetallicRoughness {
        base,
        texture: Some(_),
        coating,
        ..
    } = material
    else {
        panic!("a textured metallic-roughness material: {material:?}")
    };
    let lambdas = SampledWavelengths::new([450.0, 550.0, 650.0], [1.0; 3]).unwrap();
    let (wo, wi) = (
        Vec3::new(0.3, 0.1, 0.95).normalize(),
        Vec3::new(-0.2, 0.25, 0.9).normalize(),
    );
    for (u, metallic, roughness) in [(0.25, 0.0, 0.5), (0.75, 1.0, 0.1)] {
        let uv = Vec2::new(u, 0.5);
        let expected =
            MetallicRoughness::new(base.at_uv(uv, &lambdas), metallic, roughness, coating);
        let got = material.bsdf(uv, &lambdas);
        for k in 0..3 {
            let (g, e) = (got.f(wo, wi)[k], expected.f(wo, wi)[k]);
            assert!(
                (g - e).abs() <= 1e-5 * e.abs().max(1.0),
                "u {u}, lane {k}: {g} vs {e}"
            );
        }
        assert!((got.pdf(wo, wi) - expected.pdf(wo, wi)).abs() <= 1e-5 * expected.pdf(wo, wi));
    }
    // The polished metal reflects far more near the mirror direction than the matte side.
    let mirror = Vec3::new(-wo.x, -wo.y, wo.z);
    let f = |u: f32| material.bsdf(Vec2::new(u, 0.5), &lambdas).f(wo, mirror)[1];
    assert!(f(0.75) > 10.0 * f(0.25), "{} vs {}", f(0.75), f(0.25));
    // Without the texture the same factors make one BSDF everywhere.
    let mut plain = doc.clone();
    plain["materials"][0]["pbrMetallicRoughness"]
        .as_object_mut()
        .unwrap()
        .remove("metallicRoughnessTexture");
    let plain = load_quad(&plain, bin);
    assert!(plain.materials[0].metallic_roughness_texture.is_none());
}

/// The textured quad with a normal texture of one texel `texel` (scale `scale`), placed by
/// `node`, with per-vertex `tangents` in the file if given.
fn normal_mapped_quad(
    texel: [u8; 3],
    scale: f32,
    node: serde_json::Value,
    tangents: Option<[f32; 4]>,
) -> Scene {
    let image = png(1, 1, &[texel]);
    let (mut doc, mut bin) = textured_quad(
        &image,
        json!({"normalTexture": {"index": 0, "scale": scale}, "pbrMetallicRoughness": {"metallicFactor": 0.0}}),
    );
    doc["nodes"][0] = node;
    if let Some(t) = tangents {
        let offset = bin.len();
        bin.extend((0..6).flat_map(|_| t).flat_map(f32::to_le_bytes));
        doc["bufferViews"]
            .as_array_mut()
            .unwrap()
            .push(json!({"buffer": 0, "byteOffset": offset, "byteLength": 96}));
        doc["accessors"]
            .as_array_mut()
            .unwrap()
            .push(json!({"bufferView": 3, "componentType": 5126, "count": 6, "type": "VEC4"}));
        doc["meshes"][0]["primitives"][0]["attributes"]["TANGENT"] = json!(3 - 1);
        doc["buffers"][0]["byteLength"] = json!(bin.len());
    }
    let loaded = load_quad(&doc, bin);
    assert_eq!(loaded.tangents.len(), loaded.triangles.len());
    Scene::from_loaded(loaded, &SceneOptions::default()).unwrap()
}

fn shading_normal_at(scene: &Scene, x: f32) -> Vec3 {
    let ray = Ray::new(Vec3::new(x, 0.5, 1.0), -Vec3::Z, f32::INFINITY);
    scene.intersect(&ray).unwrap().shading_normal
}

/// A texel tilted 45 degrees toward +u tilts the quad's normal toward +x (where u grows),
/// one tilted toward +y (green) toward the top of the image (+y: glTF's v runs down);
/// mirroring the quad by its node moves u to -x but keeps the image's top up, whether the
/// tangents come from the file or from the texture coordinates; scale 0 flattens the map.
#[test]
fn gltf_normal_textures_tilt_shading_normals_in_the_tangent_frame() {
    let s = std::f32::consts::FRAC_1_SQRT_2;
    let close3 = |a: Vec3, b: Vec3| (a - b).length() < 0.02;
    let plain = json!({"mesh": 0});
    let mirror = json!({"mesh": 0, "scale": [-1, 1, 1]});
    let (toward_u, toward_top) = ([218, 128, 218], [128, 218, 218]);

    let n = shading_normal_at(&normal_mapped_quad(toward_u, 1.0, plain.clone(), None), 0.5);
    assert!(close3(n, Vec3::new(s, 0.0, s)), "{n}");
    let n = shading_normal_at(
        &normal_mapped_quad(toward_top, 1.0, plain.clone(), None),
        0.5,
    );
    assert!(close3(n, Vec3::new(0.0, s, s)), "{n}");
    let n = shading_normal_at(&normal_mapped_quad(toward_u, 0.0, plain.clone(), None), 0.5);
    assert!(close3(n, Vec3::Z), "{n}");

    for tangents in [None, Some([1.0, 0.0, 0.0, 1.0])] {
        let n = shading_normal_at(
            &normal_mapped_quad(toward_u, 1.0, mirror.clone(), tangents),
            -0.5,
        );
        assert!(close3(n, Vec3::new(-s, 0.0, s)), "{tangents:?}: {n}");
        let n = shading_normal_at(
            &normal_mapped_quad(toward_top, 1.0, mirror.clone(), tangents),
            -0.5,
        );
        assert!(close3(n, Vec3::new(0.0, s, s)), "{tangents:?}: {n}");
    }
    // Without a normal texture no tangents are kept.
    let image = png(1, 1, &[[255; 3]]);
    let (doc, bin) = textured_quad(
        &image,
        json!({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}),
    );
    assert!(load_quad(&doc, bin).tangents.is_empty());
}

/// An emissive quad (facing +z) whose emissive texture is black at the left and white at
/// the right, under emissiveFactor 1 and strength 3: it emits three times the sRGB
/// illuminant (D65, luminance 1) from its right half and nothing from its left, seen by
/// rays that hit it and by light samples alike; as one spectrum (light choice, reports) it
/// is its mean colour's.
#[test]
fn gltf_emissive_textures_emit_per_texel() {
    let image = png(2, 1, &[[0, 0, 0], [255, 255, 255]]);
    let (doc, bin) = textured_quad(
        &image,
        json!({
            "emissiveFactor": [1.0, 1.0, 1.0],
            "emissiveTexture": {"index": 0},
            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 3.0}},
            "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0]}
        }),
    );
    assert_emits_per_texel(doc, bin);
}

/// The same emissive quad with its texture read through TEXCOORD_1, while a base colour
/// texture reads TEXCOORD_0, which points at the black texel everywhere: the emission
/// must follow the second set on rays that hit it and in light samples.
#[test]
fn gltf_emissive_textures_read_their_own_texture_coordinate_set() {
    let image = png(2, 1, &[[0, 0, 0], [255, 255, 255]]);
    let (mut doc, mut bin) = textured_quad(
        &image,
        json!({
            "emissiveFactor": [1.0, 1.0, 1.0],
            "emissiveTexture": {"index": 0, "texCoord": 1},
            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 3.0}},
            "pbrMetallicRoughness": {
                "baseColorFactor": [0.0, 0.0, 0.0, 1.0],
                "baseColorTexture": {"index": 0, "texCoord": 0}
            }
        }),
    );
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let offset = bin.len();
    bin.extend([0u8; 48]);
    doc["bufferViews"]
        .as_array_mut()
        .unwrap()
        .push(json!({"buffer": 0, "byteOffset": offset, "byteLength": 48}));
    doc["accessors"]
        .as_array_mut()
        .unwrap()
        .push(json!({"bufferView": 3, "componentType": 5126, "count": 6, "type": "VEC2"}));
    doc["buffers"][0]["byteLength"] = json!(bin.len());
    doc["meshes"][0]["primitives"][0]["attributes"] =
        json!({"POSITION": 0, "TEXCOORD_0": 2, "TEXCOORD_1": 1});
    assert_emits_per_texel(doc, bin);
}

/// The checks of [`gltf_emissive_textures_emit_per_texel`] on quad `doc`.
fn assert_emits_per_texel(mut doc: serde_json::Value, bin: Vec<u8>) {
    doc["extensionsUsed"] = json!(["KHR_materials_emissive_strength"]);
    // Clamped at the edges: the outer quarters are the texels' own colours.
    doc["samplers"] = json!([{"wrapS": 33071, "wrapT": 33071}]);
    doc["textures"][0]["sampler"] = json!(0);
    let scene = Scene::from_loaded(load_quad(&doc, bin), &SceneOptions::default()).unwrap();
    assert!(matches!(
        scene.emission_spectra(),
        [SceneSpectrum::Texture(_)]
    ));
    let d65 = prism_upsample::normalized_illuminant(&RgbSpaceId::Srgb.illuminant()).unwrap();
    let lambdas = SampledWavelengths::new([450.0, 550.0, 650.0], [1.0; 3]).unwrap();
    let white = |k: usize| 3.0 * d65.evaluate(f64::from(lambdas.lambda(k)));
    let mut cache = EmissionCache::new();

    // Seen by rays from above.
    let seen = |x: f32, cache: &mut EmissionCache<3>| {
        let ray = Ray::new(Vec3::new(x, 0.5, 1.0), -Vec3::Z, f32::INFINITY);
        let hit = scene.intersect(&ray).unwrap();
        scene.emitted(&hit, Vec3::Z, &lambdas, cache)
    };
    assert!(seen(0.25, &mut cache).is_black());
    let right = seen(0.75, &mut cache);
    for k in 0..3 {
        assert!(
            (f64::from(right[k]) - white(k)).abs() < 1e-3 * white(k),
            "lane {k}: {}",
            right[k]
        );
    }
    // The cache must not hand the right half's value to the left half.
    assert!(seen(0.25, &mut cache).is_black());

    // Sampled from points above the quad's centre, near (by solid angle) and far (by
    // area): dark exactly where the sampled point lies on the left half.
    for height in [0.3, 30.0] {
        let above = Hit {
            p: Vec3::new(0.5, 0.5, height),
            error: Vec3::ZERO,
            normal: -Vec3::Z,
            shading_normal: -Vec3::Z,
            tex: prism_scene::world::TexCoords::default(),
            color: glam::Vec4::ONE,
            t: 1.0,
            triangle: 0,
        };
        let (mut dark, mut lit) = (0, 0);
        for i in 0..16 {
            for j in 0..16 {
                let u = Vec2::new((i as f32 + 0.5) / 16.0, (j as f32 + 0.5) / 16.0);
                let Some(s) = scene.sample_light(&above, u, &lambdas, &mut cache) else {
                    continue;
                };
                let x = above.p.x + s.wi.x * s.distance;
                if (x - 0.5).abs() < 0.25 {
                    continue; // the texels blend between their centres
                }
                if x < 0.5 {
                    assert!(s.radiance.is_black(), "x {x}: {:?}", s.radiance);
                    dark += 1;
                } else {
                    assert!(
                        (f64::from(s.radiance[1]) - white(1)).abs() < 1e-3 * white(1),
                        "x {x}"
                    );
                    lit += 1;
                }
            }
        }
        assert!(dark > 20 && lit > 20, "{dark} {lit}");
    }

    // As one spectrum: the mean colour, grey 0.5 of 255 after sRGB decoding (0.5 x 3 x D65).
    let mean = scene.emission_spectra()[0].evaluate(550.0);
    assert!(
        (mean - 0.5 * 3.0 * d65.evaluate(550.0)).abs() < 1e-3 * mean,
        "{mean}"
    );
}

/// Emission at the extremes of glTF's numbers stays finite: a strength of 3e38 saturates
/// rather than overflowing to infinity (no NaN or inf leaves a spectrum).
#[test]
fn extreme_emissive_strengths_stay_finite() {
    let image = png(2, 1, &[[0, 0, 0], [255, 128, 255]]);
    for strength in [0.0f32, 1e-38, 1.0, 3e38] {
        let (mut doc, bin) = textured_quad(
            &image,
            json!({
                "emissiveFactor": [1.0, 1.0, 1.0],
                "emissiveTexture": {"index": 0},
                "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
            }),
        );
        doc["extensionsUsed"] = json!(["KHR_materials_emissive_strength"]);
        let Ok(loaded) = load_geometry(
            &serde_json::to_vec(&doc).unwrap(),
            &move |_| Ok(bin.clone()),
            None,
        ) else {
            continue; // refused as an error: also fine
        };
        let scene = Scene::from_loaded(loaded, &SceneOptions::default()).unwrap();
        let lambdas = SampledWavelengths::new([380.0, 550.0, 780.0], [1.0; 3]).unwrap();
        for spectrum in scene.emission_spectra() {
            for u in [0.0, 0.25, 0.5, 0.75, 1.0] {
                let e = spectrum.at_uv(Vec2::new(u, 0.5), &lambdas);
                assert!(
                    e.0.iter().all(|v| v.is_finite() && *v >= 0.0),
                    "strength {strength}: {e:?}"
                );
            }
            assert!(spectrum.evaluate(550.0).is_finite() && spectrum.max_value().is_finite());
        }
    }
}

/// Light choice follows the texels: of a quad light whose emissive texture is white over
/// one triangle and black over the other, the white triangle is chosen far more often, and
/// the black one still sometimes (a tenth of the mean keeps every emitter in reach).
#[test]
fn textured_emitters_are_chosen_by_the_light_of_their_own_texels() {
    // White where u + v > 1: the quad's first triangle (y <= x, v = 1 - y).
    let texels: Vec<[u8; 3]> = (0..32 * 32)
        .map(|k| {
            if k % 32 + k / 32 + 1 > 32 {
                [255; 3]
            } else {
                [0; 3]
            }
        })
        .collect();
    let image = png(32, 32, &texels);
    let (doc, bin) = textured_quad(
        &image,
        json!({"emissiveFactor": [1.0, 1.0, 1.0], "emissiveTexture": {"index": 0}}),
    );
    // The quad's emission is no brighter than an emissive colour of 1: a black
    // environment, stated, keeps the default one out of the light choice.
    let options = SceneOptions::default().environment(Some(
        prism_scene::world::Environment::Uniform(prism_scene::world::SceneSpectrum::Constant(0.0)),
    ));
    let scene = Scene::from_loaded(load_quad(&doc, bin), &options).unwrap();
    let (white, black) = (scene.lights().pmf(0), scene.lights().pmf(1));
    assert!((white + black - 1.0).abs() < 1e-6);
    assert!(black > 0.0 && white > 8.0 * black, "{white} vs {black}");
}

/// A material whose textures read more texture coordinate sets than prism keeps, or a set
/// the primitive lacks, loads with one warning saying which set they read instead.
#[test]
fn unkept_or_missing_texture_coordinate_sets_are_warned_about() {
    let image = png(2, 1, &[[0, 0, 0], [255, 255, 255]]);
    let (doc, bin) = textured_quad(
        &image,
        json!({
            "pbrMetallicRoughness": {
                "baseColorTexture": {"index": 0, "texCoord": 0},
                "metallicRoughnessTexture": {"index": 0, "texCoord": 1}
            },
            "emissiveTexture": {"index": 0, "texCoord": 2},
            "emissiveFactor": [0.5, 0.5, 0.5]
        }),
    );
    let loaded = load_quad(&doc, bin);
    let warnings = loaded.warnings.join("\n");
    assert!(
        warnings.contains("TEXCOORD_0, TEXCOORD_1, TEXCOORD_2")
            && warnings.contains("prism keeps 2"),
        "{warnings}"
    );
    assert!(
        warnings.contains("reads TEXCOORD_1, which the primitive does not have"),
        "{warnings}"
    );
    assert_eq!(loaded.warnings.len(), 2, "{warnings}");
    // Without the second set, none is kept: textures on it read the first set's.
    assert!(loaded.uvs1.is_empty() && !loaded.uvs.is_empty());
}

/// KHR_materials_iridescence reads its defaults (index 1.3, 400 nm without a thickness
/// texture) and its thickness texture (green mixes minimum to maximum), and a factor out
/// of its range is an error naming the extension.
#[test]
fn gltf_iridescence_reads_its_film() {
    // Green 0 at the left texel, 255 at the right.
    let image = png(2, 1, &[[0, 0, 0], [0, 255, 0]]);
    let material = |ext: serde_json::Value| {
        json!({
            "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0},
            "extensions": {"KHR_materials_iridescence": ext}
        })
    };
    let film = |ext: serde_json::Value| {
        let (doc, bin) = textured_quad(&image, material(ext));
        let mut doc = doc;
        doc["samplers"] = json!([{"wrapS": 33071, "wrapT": 33071, "magFilter": 9728}]);
        doc["textures"][0]["sampler"] = json!(0);
        let loaded = load_quad(&doc, bin);
        loaded.materials[0].iridescence.clone()
    };
    let plain = film(json!({"iridescenceFactor": 0.5})).expect("a film");
    assert_eq!(
        (
            plain.factor,
            plain.ior,
            plain.thickness_min_nm,
            plain.thickness_max_nm
        ),
        (0.5, 1.3, 100.0, 400.0)
    );
    let lambdas = SampledWavelengths::new([500.0, 600.0], [1.0; 2]).unwrap();
    let at = |x: f32| prism_scene::world::TexCoords::new(Vec2::new(x, 0.5));
    assert_eq!(plain.at(&at(0.1), &lambdas).film.thickness_nm, 400.0);
    let textured = film(json!({
        "iridescenceFactor": 1.0,
        "iridescenceThicknessMinimum": 200.0,
        "iridescenceThicknessMaximum": 600.0,
        "iridescenceThicknessTexture": {"index": 0}
    }))
    .unwrap();
    assert!((textured.at(&at(0.1), &lambdas).film.thickness_nm - 200.0).abs() < 1e-3);
    assert!((textured.at(&at(0.9), &lambdas).film.thickness_nm - 600.0).abs() < 1e-3);
    assert!(film(json!({"iridescenceFactor": 0.0})).is_none());
    // On glass it is not rendered, and the load says so.
    let mut glass = material(json!({"iridescenceFactor": 1.0}));
    glass["extensions"]["KHR_materials_transmission"] = json!({"transmissionFactor": 1.0});
    let (doc, bin) = textured_quad(&image, glass);
    let warnings = load_quad(&doc, bin).warnings.join("\n");
    assert!(
        warnings.contains("transmissive material is not rendered"),
        "{warnings}"
    );
    let (doc, bin) = textured_quad(&image, material(json!({"iridescenceFactor": 2.0})));
    let error = load_geometry(
        &serde_json::to_vec(&doc).unwrap(),
        &move |_| Ok(bin.clone()),
        None,
    )
    .unwrap_err()
    .to_string();
    assert!(
        error.contains("KHR_materials_iridescence") && error.contains("iridescenceFactor"),
        "{error}"
    );
}

/// KHR_materials_specular, _clearcoat, _sheen and _anisotropy: each read with its
/// factors and textures, and each changes the BSDF the loaded scene gives a hit (so an
/// extension read but dropped on the way fails); a factor texture that is 0 at a texel
/// removes the layer there; an out-of-range factor is an error naming the extension.
#[test]
fn gltf_material_extensions_reach_the_bsdf() {
    use prism_scene::bsdf::TransportMode;
    use prism_scene::world::{Scene, SceneOptions};
    // Red 1 and green 0 at the left texel, red 0 and green 1 at the right.
    let image = png(2, 1, &[[255, 0, 0], [0, 255, 0]]);
    let material = |name: &str, ext: serde_json::Value| {
        let mut m = json!({
            "pbrMetallicRoughness": {"baseColorFactor": [0.2, 0.3, 0.4, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.5},
        });
        if name != "none" {
            m["extensions"] = json!({ name: ext });
        }
        m
    };
    let lambdas = SampledWavelengths::new([450.0, 550.0, 650.0, 700.0], [1.0; 4]).unwrap();
    // The mirror direction, where a coat's highlight is.
    let wo = Vec3::new(0.6, 0.1, 0.79).normalize();
    let wi = Vec3::new(-wo.x, -wo.y, wo.z);
    let f_at = |name: &str, ext: serde_json::Value, x: f32| {
        let (mut doc, bin) = textured_quad(&image, material(name, ext));
        doc["samplers"] = json!([{"wrapS": 33071, "wrapT": 33071, "magFilter": 9728}]);
        doc["textures"][0]["sampler"] = json!(0);
        let loaded = load_quad(&doc, bin);
        let scene = Scene::from_loaded(loaded, &SceneOptions::default()).unwrap();
        // Through the scene's own hit, so that the tangent frame orients anisotropy.
        let ray = prism_scene::geometry::Ray::new(Vec3::new(x, 0.5, 1.0), -Vec3::Z, f32::INFINITY);
        let hit = scene.intersect(&ray).expect("the quad");
        scene
            .bsdf(&hit, &lambdas, TransportMode::Radiance)
            .f(wo, wi)
            .0
    };
    let bare = f_at("none", json!({}), 0.25);
    for (name, ext) in [
        (
            "KHR_materials_specular",
            json!({"specularFactor": 0.3, "specularColorFactor": [2.0, 1.0, 0.5]}),
        ),
        (
            "KHR_materials_clearcoat",
            json!({"clearcoatFactor": 1.0, "clearcoatRoughnessFactor": 0.2}),
        ),
        (
            "KHR_materials_sheen",
            json!({"sheenColorFactor": [1.0, 0.5, 0.2], "sheenRoughnessFactor": 0.5}),
        ),
        (
            "KHR_materials_anisotropy",
            json!({"anisotropyStrength": 0.9, "anisotropyRotation": 0.7}),
        ),
        (
            "KHR_materials_diffuse_transmission",
            json!({"diffuseTransmissionFactor": 0.8}),
        ),
    ] {
        let f = f_at(name, ext.clone(), 0.25);
        let change = f
            .iter()
            .zip(&bare)
            .map(|(a, b)| (a - b).abs() / b)
            .fold(0.0f32, f32::max);
        assert!(change > 0.05, "{name}: {f:?} vs bare {bare:?}");
    }
    // Factor textures: the coat's red channel is 0 at the right texel (no coat there),
    // the sheen's colour texture black there likewise.
    let coat = json!({"clearcoatFactor": 1.0, "clearcoatTexture": {"index": 0}});
    assert_ne!(f_at("KHR_materials_clearcoat", coat.clone(), 0.25), bare);
    let bare_right = f_at("none", json!({}), 0.75);
    assert_eq!(f_at("KHR_materials_clearcoat", coat, 0.75), bare_right);
    let sheen = json!({"sheenColorFactor": [1.0, 1.0, 1.0], "sheenColorTexture": {"index": 0}});
    // A red sheen texel changes the long wavelengths, not the short.
    let left = f_at("KHR_materials_sheen", sheen.clone(), 0.25);
    let (short, long) = ((left[0] - bare[0]).abs(), (left[3] - bare[3]).abs());
    assert!(
        long > 0.005 * bare[3] && short < 0.2 * long,
        "{left:?} vs {bare:?}"
    );
    // Out of range.
    for (name, ext) in [
        ("KHR_materials_clearcoat", json!({"clearcoatFactor": 2.0})),
        (
            "KHR_materials_sheen",
            json!({"sheenColorFactor": [1.0, -1.0, 0.0]}),
        ),
        ("KHR_materials_specular", json!({"specularFactor": "a"})),
        (
            "KHR_materials_anisotropy",
            json!({"anisotropyStrength": -0.5}),
        ),
        (
            "KHR_materials_diffuse_transmission",
            json!({"diffuseTransmissionFactor": 1.5}),
        ),
    ] {
        let (doc, bin) = textured_quad(&image, material(name, ext));
        let error = load_geometry(
            &serde_json::to_vec(&doc).unwrap(),
            &move |_| Ok(bin.clone()),
            None,
        )
        .err()
        .unwrap_or_else(|| panic!("{name} loaded"))
        .to_string();
        assert!(error.contains(name), "{error}");
    }
}

/// KHR_materials_transmission as glTF defines it: without KHR_materials_volume the glass
/// is thin-walled (light crosses straight through), with a volume it refracts; the base
/// colour tints what crosses; `transmissionFactor` and the red channel of
/// `transmissionTexture` give the glass its share of the surface.
#[test]
fn gltf_transmission_is_thin_walled_tinted_and_partial() {
    use prism_scene::bsdf::TransportMode;
    use prism_scene::world::{Scene, SceneOptions};
    let image = png(2, 1, &[[255, 0, 0], [0, 255, 0]]);
    let lambdas = SampledWavelengths::new([450.0, 550.0, 650.0, 700.0], [1.0; 4]).unwrap();
    let wo = Vec3::new(0.3, 0.0, 0.954).normalize();
    let sample = |base: [f32; 4], roughness: f32, ext: serde_json::Value, x: f32, uc: f32| {
        let material = json!({
            "pbrMetallicRoughness": {"baseColorFactor": base, "metallicFactor": 0.0, "roughnessFactor": roughness},
            "extensions": ext,
        });
        let (mut doc, bin) = textured_quad(&image, material);
        doc["samplers"] = json!([{"wrapS": 33071, "wrapT": 33071, "magFilter": 9728}]);
        doc["textures"][0]["sampler"] = json!(0);
        let scene = Scene::from_loaded(load_quad(&doc, bin), &SceneOptions::default()).unwrap();
        let ray = prism_scene::geometry::Ray::new(Vec3::new(x, 0.5, 1.0), -Vec3::Z, f32::INFINITY);
        let hit = scene.intersect(&ray).expect("the quad");
        scene
            .bsdf(&hit, &lambdas, TransportMode::Radiance)
            .sample(wo, uc, Vec2::new(0.3, 0.6))
            .expect("a direction")
    };
    let white = [1.0, 1.0, 1.0, 1.0];
    let glass = json!({"KHR_materials_transmission": {"transmissionFactor": 1.0}});
    let thin = sample(white, 0.0, glass.clone(), 0.25, 0.99);
    assert!(
        thin.delta && (thin.wi + wo).length() < 1e-5,
        "thin: {}",
        thin.wi
    );
    let mut thick_ext = glass.clone();
    thick_ext["KHR_materials_volume"] = json!({"thicknessFactor": 0.1});
    let thick = sample(white, 0.0, thick_ext, 0.25, 0.99);
    assert!(
        thick.wi.z < 0.0 && (thick.wi.x + wo.x / 1.5).abs() < 1e-4,
        "thick: {}",
        thick.wi
    );
    // A red base colour tints what crosses, not what is reflected.
    let red = [1.0, 0.02, 0.02, 1.0];
    let crossed = sample(red, 0.0, glass.clone(), 0.25, 0.99);
    assert!(crossed.f[0] < 0.2 * crossed.f[3], "{:?}", crossed.f);
    let reflected = sample(red, 0.0, glass.clone(), 0.25, 0.0);
    assert!((reflected.f[0] - reflected.f[1]).abs() < 1e-3 * reflected.f[1]);
    // Half glass: the lobe choice picks the glass or the (rough) base.
    let half = json!({"KHR_materials_transmission": {"transmissionFactor": 0.5}});
    assert!(sample(white, 0.5, half.clone(), 0.25, 0.3).wi.z < 0.0);
    let base = sample(white, 0.5, half, 0.25, 0.9);
    assert!(base.wi.z > 0.0 && !base.delta);
    // The texture's red channel: glass at the left texel, none at the right.
    let textured = json!({"KHR_materials_transmission": {"transmissionFactor": 1.0, "transmissionTexture": {"index": 0}}});
    assert!(sample(white, 0.5, textured.clone(), 0.25, 0.5).wi.z < 0.0);
    assert!(sample(white, 0.5, textured, 0.75, 0.5).wi.z > 0.0);
}
