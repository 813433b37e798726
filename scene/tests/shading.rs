//! Shading normals and texture coordinates: read from glTF, transformed by the inverse
//! transpose (mirroring and non-uniform scale included), interpolated at hits.

use glam::{Vec2, Vec3};
use prism_scene::geometry::Ray;
use prism_scene::load::{LoadedGeometry, load_geometry};
use prism_scene::world::{Scene, SceneOptions};
use serde_json::{Value, json};

/// One triangle with normals and UVs in one external buffer, placed by `node`.
fn doc(node: Value) -> (Value, Vec<u8>) {
    let positions = [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0];
    let h = std::f32::consts::FRAC_1_SQRT_2;
    let normals = [-h, 0.0, h, h, 0.0, h, 0.0, 0.0, 1.0];
    let uvs = [0.0f32, 0.0, 1.0, 0.0, 0.0, 1.0];
    let bin: Vec<u8> = positions
        .iter()
        .chain(&normals)
        .chain(&uvs)
        .flat_map(|f| f.to_le_bytes())
        .collect();
    let doc = json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [node, {"camera": 0, "translation": [0, 0, 5]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.5, "znear": 0.1}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"}
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 36},
            {"buffer": 0, "byteOffset": 36, "byteLength": 36},
            {"buffer": 0, "byteOffset": 72, "byteLength": 24}
        ],
        "buffers": [{"byteLength": 96, "uri": "tri.bin"}]
    });
    (doc, bin)
}

fn load(node: Value) -> LoadedGeometry {
    let (doc, bin) = doc(node);
    load_doc(&doc, bin)
}

fn load_doc(doc: &Value, bin: Vec<u8>) -> LoadedGeometry {
    load_geometry(
        &serde_json::to_vec(doc).unwrap(),
        &move |_| Ok(bin.clone()),
        None,
    )
    .unwrap()
}

#[test]
fn normals_follow_the_inverse_transpose() {
    let plain = load(json!({"mesh": 0}));
    let h = std::f32::consts::FRAC_1_SQRT_2;
    assert!((plain.normals[0][0] - Vec3::new(-h, 0.0, h)).length() < 1e-6);
    assert_eq!(plain.uvs[0], [Vec2::ZERO, Vec2::X, Vec2::Y]);
    // Mirrored and stretched in x: normals scale by the inverse (x / -2), and the swapped
    // winding swaps the vertices' attributes with them.
    let mirrored = load(json!({"mesh": 0, "scale": [-2, 1, 1]}));
    let t = mirrored.triangles[0];
    assert!(
        (t[1] - t[0]).cross(t[2] - t[0]).normalize().z > 0.99,
        "still faces +z"
    );
    for k in 0..3 {
        let i = [0, 2, 1][k];
        let expected = {
            let n = plain.normals[0][i];
            Vec3::new(-n.x / 2.0, n.y, n.z).normalize()
        };
        assert!(
            (mirrored.normals[0][k] - expected).length() < 1e-6,
            "vertex {k}"
        );
        assert_eq!(mirrored.uvs[0][k], plain.uvs[0][i]);
    }
}

#[test]
fn hits_interpolate_normals_and_uvs() {
    let loaded = load(json!({"mesh": 0}));
    let scene = Scene::from_loaded(loaded.clone(), &SceneOptions::default()).unwrap();
    // Barycentrics (0.5, 0.25, 0.25) at (0.25, 0.25).
    let ray = Ray::new(Vec3::new(0.25, 0.25, 1.0), -Vec3::Z, f32::INFINITY);
    let hit = scene.intersect(&ray).unwrap();
    let n = loaded.normals[0];
    let expected = (0.5 * n[0] + 0.25 * n[1] + 0.25 * n[2]).normalize();
    assert!(
        (hit.shading_normal - expected).length() < 1e-5,
        "{}",
        hit.shading_normal
    );
    assert_eq!(hit.normal, Vec3::Z);
    assert!((hit.tex.uv[0] - Vec2::new(0.25, 0.25)).length() < 1e-6);
}

#[test]
fn attribute_counts_must_match_the_vertices() {
    let (mut doc, bin) = doc(json!({"mesh": 0}));
    doc["accessors"][1]["count"] = json!(2);
    doc["bufferViews"][1]["byteLength"] = json!(24);
    let result = load_geometry(
        &serde_json::to_vec(&doc).unwrap(),
        &move |_| Ok(bin.clone()),
        None,
    );
    let Err(err) = result else {
        panic!("should fail")
    };
    let err = err.to_string();
    assert!(err.contains("NORMAL has 2 entries for 3 vertices"), "{err}");
}

#[test]
fn only_meshes_without_a_material_get_the_default() {
    use prism_scene::world::Material;
    // The triangle names no material: glTF's default (white, metallic 1, roughness 1).
    let loaded = load(json!({"mesh": 0}));
    let scene = Scene::from_loaded(loaded, &SceneOptions::default()).unwrap();
    let hit = scene
        .intersect(&Ray::new(
            Vec3::new(0.25, 0.25, 1.0),
            -Vec3::Z,
            f32::INFINITY,
        ))
        .unwrap();
    assert!(matches!(
        scene.material(&hit),
        Material::MetallicRoughness { metallic, roughness, .. } if *metallic == 1.0 && *roughness == 1.0
    ));
    // With a material named, the default (and its coating table) is not built.
    let (mut doc, bin) = doc(json!({"mesh": 0}));
    doc["meshes"][0]["primitives"][0]["material"] = json!(0);
    doc["materials"] = json!([{"pbrMetallicRoughness": {"metallicFactor": 0.0}}]);
    let named = load_geometry(
        &serde_json::to_vec(&doc).unwrap(),
        &move |_| Ok(bin.clone()),
        None,
    )
    .unwrap();
    let scene = Scene::from_loaded(named, &SceneOptions::default()).unwrap();
    assert_eq!(scene.materials().len(), 1);
}

/// `doc`'s triangle twice: first as a primitive with positions only, then (if `both`) as
/// the primitive with normals and UVs.
fn bare_then_full(both: bool) -> LoadedGeometry {
    let (mut doc, bin) = doc(json!({"mesh": 0}));
    let bare = json!({"attributes": {"POSITION": 0}});
    let full = doc["meshes"][0]["primitives"][0].clone();
    doc["meshes"][0]["primitives"] = if both {
        json!([bare, full])
    } else {
        json!([bare])
    };
    load_doc(&doc, bin)
}

#[test]
fn attributes_are_kept_only_where_a_primitive_has_them() {
    // No primitive has normals or UVs: no lists, flat shading and uv 0 at hits.
    let bare = bare_then_full(false);
    assert_eq!(bare.triangles.len(), 1);
    assert!(bare.normals.is_empty() && bare.uvs.is_empty());
    let scene = Scene::from_loaded(bare, &SceneOptions::default()).unwrap();
    let ray = Ray::new(Vec3::new(0.25, 0.25, 1.0), -Vec3::Z, f32::INFINITY);
    let hit = scene.intersect(&ray).unwrap();
    assert_eq!(
        (hit.normal, hit.shading_normal, hit.tex.uv[0]),
        (Vec3::Z, Vec3::Z, Vec2::ZERO)
    );

    // A later primitive with them: the earlier triangle gets the face normal and uv 0.
    let mixed = bare_then_full(true);
    assert_eq!(mixed.triangles.len(), 2);
    assert_eq!(mixed.normals[0], [Vec3::Z; 3]);
    assert_eq!(mixed.uvs[0], [Vec2::ZERO; 3]);
    let h = std::f32::consts::FRAC_1_SQRT_2;
    assert!((mixed.normals[1][0] - Vec3::new(-h, 0.0, h)).length() < 1e-6);
    assert_eq!(mixed.uvs[1], [Vec2::ZERO, Vec2::X, Vec2::Y]);
}

/// A normal-mapped strip bent around a cylinder without TANGENT gets MikkTSpace tangents:
/// at a vertex two faces share, both faces have the same tangent (along the cylinder's
/// circumference there, where u grows), not each face's own chord direction.
#[test]
fn normal_mapped_meshes_without_tangents_get_smooth_mikktspace_tangents() {
    // Columns at 0, 30 and 60 degrees around +y, rows at y = 0 and 1; u follows the angle.
    let angles = [0.0f32, 30.0, 60.0].map(f32::to_radians);
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    for y in [0.0f32, 1.0] {
        for (k, a) in angles.iter().enumerate() {
            positions.extend([a.sin(), y, a.cos()]);
            normals.extend([a.sin(), 0.0, a.cos()]);
            uvs.extend([k as f32 / 2.0, 1.0 - y]);
        }
    }
    // Counter-clockwise seen from outside (+z side).
    let indices: [u16; 12] = [0, 1, 4, 0, 4, 3, 1, 2, 5, 1, 5, 4];
    let mut bin: Vec<u8> = positions
        .iter()
        .chain(&normals)
        .chain(&uvs)
        .flat_map(|f| f.to_le_bytes())
        .collect();
    bin.extend(indices.iter().flat_map(|i| i.to_le_bytes()));
    let png = {
        let mut out = Vec::new();
        let mut encoder = png::Encoder::new(&mut out, 1, 1);
        encoder.set_color(png::ColorType::Rgb);
        let mut writer = encoder.write_header().unwrap();
        writer.write_image_data(&[128, 128, 255]).unwrap();
        writer.finish().unwrap();
        out
    };
    let image_offset = bin.len();
    bin.extend(&png);
    let doc = json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_0": 2}, "indices": 3, "material": 0}]}],
        "materials": [{"normalTexture": {"index": 0}}],
        "textures": [{"source": 0}],
        "images": [{"bufferView": 4, "mimeType": "image/png"}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 6, "type": "VEC3", "min": [0, 0, 0.5], "max": [0.87, 1, 1]},
            {"bufferView": 1, "componentType": 5126, "count": 6, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5126, "count": 6, "type": "VEC2"},
            {"bufferView": 3, "componentType": 5123, "count": 12, "type": "SCALAR"}
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 72},
            {"buffer": 0, "byteOffset": 72, "byteLength": 72},
            {"buffer": 0, "byteOffset": 144, "byteLength": 48},
            {"buffer": 0, "byteOffset": 192, "byteLength": 24},
            {"buffer": 0, "byteOffset": image_offset, "byteLength": png.len()}
        ],
        "buffers": [{"byteLength": bin.len(), "uri": "strip.bin"}]
    });
    let loaded = load_doc(&doc, bin);
    assert_eq!(loaded.tangents.len(), 4);
    // Vertex 1 (30 degrees, y = 0) is corner 1 of face 0 and corner 0 of face 2.
    let (a, b) = (loaded.tangents[0][1], loaded.tangents[2][0]);
    assert!(a.abs_diff_eq(b, 1e-5), "{a} vs {b}");
    // There u grows along the circumference: (cos 30, 0, -sin 30); glTF's handedness: +1
    // (normal x tangent points up the image, +y, where v decreases).
    let along = Vec3::new(30f32.to_radians().cos(), 0.0, -30f32.to_radians().sin());
    assert!(a.truncate().abs_diff_eq(along, 1e-4), "{a}");
    assert_eq!(a.w, 1.0);
}
