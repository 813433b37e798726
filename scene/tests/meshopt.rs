//! EXT_meshopt_compression: a mesh compressed by meshoptimizer's own encoders (positions
//! as is, normals through the octahedral filter, triangle indices) loads as the same mesh,
//! and a corrupt compressed view is an error, not a panic.

use glam::Vec3;
use prism_scene::load::{LoadedGeometry, load_geometry};
use serde_json::{Value, json};

/// A unit quad in z = 0 facing +z (two triangles), compressed; its fallback buffer has no
/// data.
fn compressed_quad() -> (Value, Vec<u8>) {
    let positions: Vec<[f32; 3]> = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    let normals: Vec<[f32; 4]> = vec![[0.0, 0.0, 1.0, 0.0]; 4];
    let indices: Vec<u32> = vec![0, 1, 2, 0, 2, 3];
    let p = meshopt::encode_vertex_buffer(&positions).unwrap();
    let n_filtered: Vec<[i8; 4]> = meshopt::encode_filter_oct(&normals, 8);
    let n = meshopt::encode_vertex_buffer(&n_filtered).unwrap();
    let i = meshopt::encode_index_buffer(&indices, 4).unwrap();
    let pad = |v: &mut Vec<u8>| v.resize(v.len().div_ceil(4) * 4, 0);
    let mut bin = p.clone();
    pad(&mut bin);
    let n_at = bin.len();
    bin.extend(&n);
    pad(&mut bin);
    let i_at = bin.len();
    bin.extend(&i);
    pad(&mut bin);
    let ext =
        |offset: usize, length: usize, stride: usize, count: usize, mode: &str, filter: &str| {
            json!({"EXT_meshopt_compression": {
            "buffer": 0, "byteOffset": offset, "byteLength": length,
            "byteStride": stride, "count": count, "mode": mode, "filter": filter}})
        };
    let doc = json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": ["EXT_meshopt_compression", "KHR_mesh_quantization"],
        "extensionsRequired": ["EXT_meshopt_compression", "KHR_mesh_quantization"],
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5120, "normalized": true, "count": 4, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}
        ],
        "bufferViews": [
            {"buffer": 1, "byteOffset": 0, "byteLength": 48, "byteStride": 12,
             "extensions": ext(0, p.len(), 12, 4, "ATTRIBUTES", "NONE")},
            {"buffer": 1, "byteOffset": 48, "byteLength": 16, "byteStride": 4,
             "extensions": ext(n_at, n.len(), 4, 4, "ATTRIBUTES", "OCTAHEDRAL")},
            {"buffer": 1, "byteOffset": 64, "byteLength": 12,
             "extensions": ext(i_at, i.len(), 2, 6, "TRIANGLES", "NONE")}
        ],
        "buffers": [
            {"byteLength": bin.len(), "uri": "compressed.bin"},
            {"byteLength": 76, "extensions": {"EXT_meshopt_compression": {"fallback": true}}}
        ]
    });
    (doc, bin)
}

fn load(doc: &Value, bin: Vec<u8>) -> Result<LoadedGeometry, String> {
    load_geometry(
        &serde_json::to_vec(doc).unwrap(),
        &move |_| Ok(bin.clone()),
        None,
    )
    .map_err(|e| e.to_string())
}

#[test]
fn compressed_views_decode_to_the_mesh() {
    let (doc, bin) = compressed_quad();
    let loaded = load(&doc, bin).unwrap();
    assert_eq!(
        loaded.triangles,
        vec![
            [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0)],
            [Vec3::ZERO, Vec3::new(1.0, 1.0, 0.0), Vec3::Y],
        ]
    );
    for n in loaded.normals.iter().flatten() {
        assert!(n.abs_diff_eq(Vec3::Z, 1e-2), "{n}");
    }
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
}

#[test]
fn corrupt_compressed_views_are_errors() {
    let (doc, bin) = compressed_quad();
    for (what, edit) in [
        ("mode", json!("SOMETHING")),
        ("filter", json!("WAVELET")),
        ("byteStride", json!(6)),
        ("byteLength", json!(1_000_000)),
        ("count", json!(1u64 << 40)),
    ] {
        let mut doc = doc.clone();
        doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"][what] = edit;
        let e = load(&doc, bin.clone()).expect_err(what);
        assert!(e.contains("EXT_meshopt_compression"), "{what}: {e}");
    }
    // Garbage instead of the compressed stream.
    let garbage = vec![0xA5u8; bin.len()];
    let e = load(&doc, garbage).unwrap_err();
    assert!(e.contains("does not decode"), "{e}");
}
