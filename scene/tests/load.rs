//! glTF geometry loading: the canonical scenes, transforms, and a corpus of broken files.

use glam::Vec3;
use prism_scene::geometry::{Bvh, BvhQuality, Ray};
use prism_scene::load::{LoadError, LoadedGeometry, load_geometry};
use serde_json::{Value, json};

fn scenes_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes")
}

fn load_file(name: &str) -> Result<LoadedGeometry, LoadError> {
    let dir = scenes_dir();
    let bytes = std::fs::read(dir.join(name)).unwrap();
    load_geometry(&bytes, &|uri| std::fs::read(dir.join(uri)), None)
}

fn load_json(doc: &Value, bin: &[u8]) -> Result<LoadedGeometry, LoadError> {
    let text = serde_json::to_vec(doc).unwrap();
    let bin = bin.to_vec();
    load_geometry(&text, &move |_| Ok(bin.clone()), None)
}

#[test]
fn canonical_scenes_load() {
    let bunny = load_file("cornell-bunny.gltf").unwrap();
    let bunny_tris = bunny
        .instances
        .iter()
        .find(|i| i.node == "bunny")
        .unwrap()
        .count;
    assert_eq!(bunny_tris, 69_451);
    assert!(
        bunny
            .instances
            .iter()
            .all(|i| i.node != "small-box" && i.node != "large-box"),
        "only the scene's nodes"
    );
    // The bunny sits inside the box (walls at +-1) after its node transform.
    let inst = bunny.instances.iter().find(|i| i.node == "bunny").unwrap();
    for t in &bunny.triangles[inst.first..inst.first + inst.count] {
        for v in t {
            assert!(v.abs().max_element() <= 1.0 + 1e-4, "{v}");
        }
    }
    let boxes = load_file("cornell-box.gltf").unwrap();
    assert!(boxes.instances.iter().any(|i| i.node == "small-box"));
    // A ray from the camera position hits something.
    let bvh = Bvh::build(&boxes.triangles, BvhQuality::Medium);
    assert!(
        bvh.intersect(&Ray::new(Vec3::new(0.0, 0.0, 3.9), -Vec3::Z, f32::INFINITY))
            .is_some()
    );
}

/// A one-triangle document with its buffer as a data URI, for transform tests.
fn triangle_doc(node: Value) -> Value {
    // Three f32 positions: (0,0,0), (1,0,0), (0,1,0), base64-encoded.
    let bytes: Vec<u8> = [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]
        .iter()
        .flat_map(|f| f.to_le_bytes())
        .collect();
    let b64 = {
        const A: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        let mut s = String::new();
        for c in bytes.chunks(3) {
            let n = (u32::from(c[0]) << 16)
                | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
                | u32::from(*c.get(2).unwrap_or(&0));
            for k in 0..=c.len() {
                s.push(A[((n >> (18 - 6 * k)) & 63) as usize] as char);
            }
        }
        while !s.len().is_multiple_of(4) {
            s.push('=');
        }
        s
    };
    json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [node],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "buffers": [{"byteLength": 36, "uri": format!("data:application/octet-stream;base64,{b64}")}]
    })
}

#[test]
fn transforms_compose_and_mirroring_keeps_winding() {
    let normal = |g: &LoadedGeometry| {
        let t = g.triangles[0];
        (t[1] - t[0]).cross(t[2] - t[0]).normalize()
    };
    let plain = load_json(&triangle_doc(json!({"mesh": 0})), &[]).unwrap();
    assert_eq!(normal(&plain), Vec3::Z);
    let moved = load_json(
        &triangle_doc(json!({"mesh": 0, "translation": [1, 2, 3], "scale": [2, 2, 2]})),
        &[],
    )
    .unwrap();
    assert_eq!(moved.triangles[0][1], Vec3::new(3.0, 2.0, 3.0));
    let mirrored = load_json(&triangle_doc(json!({"mesh": 0, "scale": [-1, 1, 1]})), &[]).unwrap();
    assert_eq!(
        normal(&mirrored),
        Vec3::Z,
        "a mirrored triangle keeps facing +z"
    );
    let matrix = load_json(
        &triangle_doc(json!({"mesh": 0, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 5,0,0,1]})),
        &[],
    )
    .unwrap();
    assert_eq!(matrix.triangles[0][0], Vec3::new(5.0, 0.0, 0.0));
}

/// Nodes shared by several parents are instanced under each; a graph that multiplies a
/// mesh beyond what prism can index is an error before anything is allocated (forty levels
/// that each list one child twice: 2^40 instances from a file of a few kilobytes), and so
/// is a cycle, however long.
#[test]
fn shared_nodes_instance_and_exploding_or_cyclic_graphs_are_errors() {
    let with_nodes = |nodes: Vec<Value>| {
        let mut doc = triangle_doc(json!({"mesh": 0}));
        doc["nodes"] = Value::Array(nodes);
        doc
    };
    // One node listed twice, by two parents: the triangle twice.
    let shared = with_nodes(vec![
        json!({"children": [1, 2]}),
        json!({"children": [3], "translation": [1, 0, 0]}),
        json!({"children": [3]}),
        json!({"mesh": 0}),
    ]);
    assert_eq!(load_json(&shared, &[]).unwrap().triangles.len(), 2);
    let doubling: Vec<Value> = (0..40)
        .map(|i| json!({"children": [i + 1, i + 1]}))
        .chain([json!({"mesh": 0})])
        .collect();
    let e = load_json(&with_nodes(doubling), &[])
        .unwrap_err()
        .to_string();
    // 2^40 instances of one primitive of one triangle.
    assert!(
        e.contains("instances 2199023255552 triangles, primitives"),
        "{e}"
    );
    let cycle = with_nodes(vec![
        json!({"children": [1]}),
        json!({"children": [2], "mesh": 0}),
        json!({"children": [1]}),
    ]);
    let e = load_json(&cycle, &[]).unwrap_err().to_string();
    assert!(e.contains("node 1 is its own ancestor"), "{e}");
    // A chain longer than any recursion could follow: counted, then refused by depth.
    let chain: Vec<Value> = (0..100_000)
        .map(|i| json!({"children": [i + 1]}))
        .chain([json!({"mesh": 0})])
        .collect();
    let e = load_json(&with_nodes(chain), &[]).unwrap_err().to_string();
    assert!(e.contains("deeper than 256"), "{e}");
}

/// The corpus of broken files: each a named edit of the Cornell box, each an error that
/// names the problem, none a panic.
#[test]
fn broken_files_are_clear_errors() {
    let dir = scenes_dir();
    let base: Value =
        serde_json::from_slice(&std::fs::read(dir.join("cornell-box.gltf")).unwrap()).unwrap();
    let bin = std::fs::read(dir.join("cornell-box.bin")).unwrap();
    let edit = |f: &dyn Fn(&mut Value)| {
        let mut doc = base.clone();
        f(&mut doc);
        doc
    };
    let cases: Vec<(&str, Value, Vec<u8>, &str)> = vec![
        (
            "short buffer",
            base.clone(),
            bin[..bin.len() / 2].to_vec(),
            "declares",
        ),
        (
            "accessor past its view",
            edit(&|d| d["accessors"][0]["count"] = json!(100_000)),
            bin.clone(),
            "cannot be read",
        ),
        (
            "index past the vertices",
            edit(&|d| {
                // Point an indices accessor at a position accessor's view: indices become floats' bits.
                let idx = d["meshes"][0]["primitives"][0]["indices"].as_u64().unwrap() as usize;
                d["accessors"][idx]["count"] = json!(3);
                d["accessors"][idx]["bufferView"] = d["accessors"][0]["bufferView"].clone();
                d["accessors"][idx]["componentType"] = json!(5125);
                d["accessors"][idx]["type"] = json!("SCALAR");
            }),
            bin.clone(),
            "past the",
        ),
        (
            "unreadable indices",
            edit(&|d| {
                let idx = d["meshes"][0]["primitives"][0]["indices"].as_u64().unwrap() as usize;
                d["accessors"][idx]["count"] = json!(1_000_000);
            }),
            bin.clone(),
            "index accessor",
        ),
        (
            // The gltf crate's own validation indexes POSITION accessors unchecked.
            "POSITION accessor that does not exist",
            edit(&|d| d["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = json!(999)),
            bin.clone(),
            "accessor 999 does not exist",
        ),
        (
            "indices of floats",
            edit(&|d| d["meshes"][0]["primitives"][0]["indices"] = json!(1)),
            bin.clone(),
            "index accessor 1 is FLOAT VEC3, not UNSIGNED_BYTE or UNSIGNED_SHORT or UNSIGNED_INT SCALAR",
        ),
        (
            "normals of scalars",
            edit(&|d| d["accessors"][1]["type"] = json!("SCALAR")),
            bin.clone(),
            "NORMAL accessor 1 is FLOAT SCALAR, not FLOAT or BYTE or SHORT VEC3",
        ),
        (
            "no indices",
            edit(&|d| d["accessors"][2]["count"] = json!(0)),
            bin.clone(),
            "index accessor 2 has no elements",
        ),
        (
            "stride shorter than a position",
            edit(&|d| d["bufferViews"][0]["byteStride"] = json!(4)),
            bin.clone(),
            "POSITION accessor 0 cannot be read",
        ),
        (
            // (An index count this large is refused earlier, as instancing too much.)
            "position count that overflows a byte offset",
            edit(&|d| d["accessors"][0]["count"] = json!(1u64 << 62)),
            bin.clone(),
            "POSITION accessor 0 cannot be read",
        ),
        (
            "index count beyond what prism can instance",
            edit(&|d| d["accessors"][2]["count"] = json!(1u64 << 62)),
            bin.clone(),
            "more than prism's limit",
        ),
        (
            "sparse substitution of no elements",
            edit(&|d| {
                d["accessors"][0]["sparse"] = json!({
                    "count": 0,
                    "indices": {"bufferView": 2, "componentType": 5125},
                    "values": {"bufferView": 0},
                })
            }),
            bin.clone(),
            "POSITION accessor 0 has a sparse substitution",
        ),
        (
            "lines instead of triangles",
            edit(&|d| d["meshes"][0]["primitives"][0]["mode"] = json!(1)),
            bin.clone(),
            "TRIANGLES",
        ),
        (
            "no such scene",
            edit(&|d| d["scene"] = json!(3)),
            bin.clone(),
            "invalid glTF",
        ),
        (
            "empty scene",
            edit(&|d| d["scenes"][0]["nodes"] = json!([])),
            bin.clone(),
            "no triangles",
        ),
        (
            "malformed data URI",
            edit(&|d| d["buffers"][0]["uri"] = json!("data:application/octet-stream;base64,@@@@")),
            bin.clone(),
            "base64",
        ),
        (
            "not JSON",
            json!("this is not a glTF document"),
            bin.clone(),
            "invalid glTF",
        ),
    ];
    for (name, doc, bytes, needle) in cases {
        match load_json(&doc, &bytes) {
            Ok(_) => panic!("{name}: loaded"),
            Err(e) => {
                let e = e.to_string();
                assert!(e.contains(needle), "{name}: '{e}' lacks '{needle}'");
                assert!(
                    !e.contains("glTF: invalid glTF"),
                    "{name}: '{e}' repeats itself"
                );
            }
        }
    }
    // NaN positions.
    let mut nan_bin = bin.clone();
    nan_bin[0..4].copy_from_slice(&f32::NAN.to_le_bytes());
    let e = load_json(&base, &nan_bin).unwrap_err().to_string();
    assert!(e.contains("not finite") || e.contains("invalid"), "{e}");
    // A missing external buffer names the URI.
    let text = serde_json::to_vec(&base).unwrap();
    let missing = |_: &str| Err(std::io::Error::from(std::io::ErrorKind::NotFound));
    let e = load_geometry(&text, &missing, None).unwrap_err();
    assert!(e.to_string().contains("cornell-box.bin"), "{e}");
    // The resolver's error is the cause, for callers that look.
    let cause = std::error::Error::source(&e).expect("an I/O error as the source");
    let io = cause.downcast_ref::<std::io::Error>().unwrap();
    assert_eq!(io.kind(), std::io::ErrorKind::NotFound);
    assert!(
        matches!(e, prism_scene::load::LoadError::Resource { ref uri, .. } if uri == "cornell-box.bin")
    );
    // Garbage bytes.
    assert!(
        load_geometry(
            b"\x00\x01garbage",
            &|_| Err(std::io::Error::other("none")),
            None
        )
        .is_err()
    );
}

/// Materials become spectra at load time: reflectances by exact fits of the constant
/// colours, the light's emission as an illuminant spectrum whose colour is the emissive
/// factor times its strength.
#[test]
fn materials_become_spectra() {
    use prism_spectrum::Spectrum;
    use prism_spectrum::color::RgbSpaceId;
    use prism_spectrum::colorimetry::{Observer, emission_xyz, reflectance_xyz};
    let scene = load_file("cornell-box.gltf").unwrap();
    let names: Vec<&str> = scene.materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["white-emitter", "white", "green", "red"]);
    let red = &scene.materials[3];
    assert!(red.base_color.evaluate(650.0) > 5.0 * red.base_color.evaluate(450.0));
    assert_eq!((red.metallic, red.roughness, red.ior), (0.0, 1.0, 1.5));
    // The reflectance reproduces its RGB under D65 (the exact fit's accuracy).
    let srgb = RgbSpaceId::Srgb;
    let xyz = reflectance_xyz(&red.base_color, &srgb.illuminant(), Observer::Cie1931).unwrap();
    let rgb = srgb.space().xyz_to_rgb(xyz);
    for (got, want) in rgb.iter().zip([0.570068, 0.0430135, 0.0443706]) {
        assert!((got - want).abs() < 2e-3, "{rgb:?}");
    }
    assert!(red.emission.is_none());
    // The light: emissive (1, 0.7607, 0.3673) x 18.387; its spectrum's luminance is the
    // colour's (relative units: Y of the spectrum equals Y of the RGB).
    let light = scene.materials[0].emission.as_ref().unwrap();
    let y = emission_xyz(light, Observer::Cie1931).y;
    let weights = srgb.space().luminance_weights();
    let expected = 18.387
        * (weights[0]
            + weights[1] * 0.760_716_810_790_232_1
            + weights[2] * 0.367_301_354_217_653_75);
    assert!(
        ((y - expected) / expected).abs() < 5e-3,
        "Y {y} vs {expected}"
    );
}

#[test]
fn non_finite_material_factors_are_errors() {
    let dir = scenes_dir();
    let mut doc: Value =
        serde_json::from_slice(&std::fs::read(dir.join("cornell-box.gltf")).unwrap()).unwrap();
    doc["materials"][2]["pbrMetallicRoughness"]["roughnessFactor"] = json!(-1e39);
    let bin = std::fs::read(dir.join("cornell-box.bin")).unwrap();
    // -1e39 overflows f32 to -inf.
    let e = load_json(&doc, &bin).unwrap_err().to_string();
    assert!(e.contains("not finite") || e.contains("invalid"), "{e}");
}

#[test]
fn lights_are_emissive_instances_then_punctual_lights() {
    use prism_scene::load::LightDesc;
    use prism_spectrum::optics::luminous_flux;
    let scene = load_file("cornell-box.gltf").unwrap();
    let area: Vec<usize> = scene
        .lights
        .iter()
        .map(|l| match l {
            LightDesc::Area { instance, .. } => *instance,
            other => panic!("the Cornell box has only an area light, got {other:?}"),
        })
        .collect();
    assert_eq!(area.len(), 1);
    let emitter = &scene.instances[area[0]];
    assert_eq!(
        scene.materials[emitter.material.unwrap()].name,
        "white-emitter"
    );

    // A 100 cd orange point light and a 3 lx directional light, in photometric units.
    let mut doc = triangle_doc(json!({"children": [1, 2]}));
    let h = std::f32::consts::FRAC_1_SQRT_2;
    doc["nodes"] = json!([
        {"mesh": 0, "children": [1, 2]},
        {"translation": [0, 2, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}},
        {"rotation": [-h, 0, 0, h], "extensions": {"KHR_lights_punctual": {"light": 1}}}
    ]);
    doc["extensionsUsed"] = json!(["KHR_lights_punctual"]);
    doc["extensions"] = json!({"KHR_lights_punctual": {"lights": [
        {"type": "point", "color": [1.0, 0.5, 0.2], "intensity": 100.0},
        {"type": "directional", "intensity": 3.0}
    ]}});
    let loaded = load_json(&doc, &[]).unwrap();
    assert_eq!(loaded.lights.len(), 2);
    let find = |point: bool| {
        loaded
            .lights
            .iter()
            .find(|l| matches!(l, LightDesc::Point { .. }) == point)
            .unwrap()
    };
    match find(true) {
        LightDesc::Point {
            position,
            spectrum,
            scale,
        } => {
            assert!((*position - Vec3::new(0.0, 2.0, 0.0)).length() < 1e-6);
            let candela = luminous_flux(spectrum) * scale;
            assert!((candela - 100.0).abs() < 1e-6 * 100.0, "{candela}");
        }
        other => panic!("{other:?}"),
    }
    match find(false) {
        LightDesc::Directional {
            direction,
            spectrum,
            scale,
        } => {
            // -z rotated -90 degrees about x points down.
            assert!(
                (*direction - Vec3::new(0.0, -1.0, 0.0)).length() < 1e-5,
                "{direction}"
            );
            assert!((luminous_flux(spectrum) * scale - 3.0).abs() < 1e-6);
        }
        other => panic!("{other:?}"),
    }

    // Negative intensity is an error naming the light.
    doc["extensions"]["KHR_lights_punctual"]["lights"][0]["intensity"] = json!(-1.0);
    let e = load_json(&doc, &[]).unwrap_err().to_string();
    assert!(e.contains("light") && e.contains("intensity"), "{e}");
}

#[test]
fn dispersion_extension_is_read_from_raw_json_even_when_required() {
    use prism_scene::world::{Scene, SceneOptions};
    let dir = scenes_dir();
    let mut doc: Value =
        serde_json::from_slice(&std::fs::read(dir.join("cornell-box.gltf")).unwrap()).unwrap();
    // The small box becomes dispersive glass: V_d = 20 / 0.5 = 40, n_d = 1.5.
    doc["materials"][1]["extensions"] = json!({
        "KHR_materials_transmission": {"transmissionFactor": 1.0},
        "KHR_materials_dispersion": {"dispersion": 0.5}
    });
    doc["extensionsUsed"] = json!(["KHR_materials_transmission", "KHR_materials_dispersion"]);
    doc["extensionsRequired"] = json!(["KHR_materials_dispersion"]);
    let bin = std::fs::read(dir.join("cornell-box.bin")).unwrap();
    let loaded = load_json(&doc, &bin).unwrap();
    assert_eq!(loaded.materials[1].dispersion, 0.5);
    assert!(loaded.summary().uses_dispersion);
    let scene = Scene::from_loaded(loaded, &SceneOptions::default()).unwrap();
    assert!(scene.features().dispersion && scene.features().transmission);
    // Without the extension the same glass does not disperse.
    doc["materials"][1]["extensions"]
        .as_object_mut()
        .unwrap()
        .remove("KHR_materials_dispersion");
    doc["extensionsRequired"] = json!([]);
    let plain =
        Scene::from_loaded(load_json(&doc, &bin).unwrap(), &SceneOptions::default()).unwrap();
    assert!(!plain.features().dispersion && plain.features().transmission);
    // A negative dispersion is an error naming the material.
    doc["materials"][1]["extensions"]["KHR_materials_dispersion"] = json!({"dispersion": -1.0});
    let e = load_json(&doc, &bin).unwrap_err().to_string();
    assert!(e.contains("white") && e.contains("dispersion"), "{e}");
}
