//! Mitsuba's shapes through the whole loader: mesh files through a resolver, their
//! normals, texture coordinates and mesh attributes in the loaded geometry, instances of
//! shape groups, and every refusal as one line naming the file and line.

use std::collections::HashMap;

use glam::{Vec2, Vec3, Vec4};

use super::ParseOptions;
use super::scene::{MitsubaScene, load};
use crate::LoadError;
use crate::load::LoadOptions;
use crate::materials::Material;
use crate::textures::SceneSpectrum;

const SENSOR: &str = r#"<sensor type="perspective"><film type="hdrfilm">
    <integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>"#;

/// Loads the scene whose shapes are `shapes`, with `files` to resolve.
fn scene(shapes: &str, files: &[(&str, Vec<u8>)]) -> Result<MitsubaScene, LoadError> {
    let files: HashMap<String, Vec<u8>> = files
        .iter()
        .map(|(n, b)| (n.to_string(), b.clone()))
        .collect();
    let resolve = move |name: &str| -> std::io::Result<Vec<u8>> {
        files
            .get(name)
            .cloned()
            .ok_or_else(|| std::io::Error::other(format!("no file {name}")))
    };
    let text = format!("<scene version=\"3.0.0\">\n{SENSOR}\n{shapes}\n</scene>");
    let options = ParseOptions {
        defines: &[],
        resolve: &resolve,
    };
    load(&text, "s.xml", &options, &LoadOptions::default())
}

fn error(shapes: &str, files: &[(&str, Vec<u8>)]) -> String {
    let e = scene(shapes, files).unwrap_err().to_string();
    assert!(!e.contains('\n'), "{e}");
    e
}

fn surface(desc: &crate::load::MaterialDesc) -> Option<&Material> {
    desc.spectral.as_ref().and_then(|s| s.surface.as_ref())
}

/// The unit normal a triangle's winding faces.
fn facing(t: &[Vec3; 3]) -> Vec3 {
    (t[1] - t[0]).cross(t[2] - t[0]).normalize()
}

const QUAD_OBJ: &[u8] = b"v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
                          f 1/1 2/2 3/3 4/4\n";

#[test]
fn an_obj_mesh_has_computed_normals_and_flipped_texture_coordinates() {
    let s = scene(
        r#"<shape type="obj"><string name="filename" value="quad.obj"/></shape>"#,
        &[("quad.obj", QUAD_OBJ.to_vec())],
    )
    .unwrap();
    let g = &s.geometry;
    assert_eq!(g.triangles.len(), 2);
    assert_eq!(g.normals[0], [Vec3::Z; 3]);
    // v flipped, as Mitsuba reads OBJ by default.
    assert_eq!(
        g.uvs[0],
        [
            Vec2::new(0.0, 1.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(1.0, 0.0)
        ]
    );
    let unflipped = scene(
        r#"<shape type="obj"><string name="filename" value="quad.obj"/>
           <boolean name="flip_tex_coords" value="false"/></shape>"#,
        &[("quad.obj", QUAD_OBJ.to_vec())],
    )
    .unwrap();
    assert_eq!(unflipped.geometry.uvs[0][0], Vec2::ZERO);
}

#[test]
fn flip_normals_turns_an_emitter_around() {
    let shapes = |flip: bool| {
        format!(
            r#"<shape type="obj"><string name="filename" value="quad.obj"/>
               <boolean name="flip_normals" value="{flip}"/>
               <emitter type="area"><rgb name="radiance" value="1"/></emitter></shape>"#
        )
    };
    for (flip, z) in [(false, 1.0), (true, -1.0)] {
        let s = scene(&shapes(flip), &[("quad.obj", QUAD_OBJ.to_vec())]).unwrap();
        for (t, n) in s.geometry.triangles.iter().zip(&s.geometry.normals) {
            assert_eq!(facing(t).z, z, "flip {flip}");
            assert_eq!(n[0].z, z);
        }
    }
}

/// A PLY file with vertex and face colours, as Mitsuba's mesh_attributes test writes.
fn colored_ply() -> Vec<u8> {
    let mut text = String::from(
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
         property float z\nproperty float color_0\nproperty float color_1\n\
         property float color_2\nelement face 1\nproperty list uchar int vertex_indices\n\
         property float color_0\nproperty float color_1\nproperty float color_2\n\
         property float weight_0\nend_header\n",
    );
    text += "0 0 0 1 0 0\n1 0 0 0 1 0\n0 1 0 0 0 2\n3 0 1 2 0.25 0.5 0.75 0.3\n";
    text.into_bytes()
}

fn attribute_scene(name: &str, scale: &str) -> Result<MitsubaScene, LoadError> {
    scene(
        &format!(
            r#"<texture type="mesh_attribute" id="tex"><string name="name" value="{name}"/>
                 {scale}</texture>
               <bsdf type="diffuse" id="d"><ref name="reflectance" id="tex"/></bsdf>
               <shape type="ply"><string name="filename" value="m.ply"/><ref id="d"/></shape>"#
        ),
        &[("m.ply", colored_ply())],
    )
}

#[test]
fn vertex_colours_become_the_scenes_vertex_colours_over_a_white_diffuse() {
    let s = attribute_scene("vertex_color", "").unwrap();
    let g = &s.geometry;
    assert!(g.color_table.is_some() && g.colors_blend_spectra);
    // Clamped to [0, 1] as Mitsuba's upsampling clamps.
    assert_eq!(
        g.colors[0],
        [
            Vec4::new(1.0, 0.0, 0.0, 1.0),
            Vec4::new(0.0, 1.0, 0.0, 1.0),
            Vec4::new(0.0, 0.0, 1.0, 1.0)
        ]
    );
    match surface(&g.materials[0]) {
        Some(Material::Diffuse {
            reflectance: SceneSpectrum::Constant(v),
        }) => assert_eq!(*v, 1.0),
        other => panic!("{other:?}"),
    }
}

#[test]
fn face_colours_and_single_values_fill_the_triangle() {
    let s = attribute_scene("face_color", r#"<float name="scale" value="0.5"/>"#).unwrap();
    assert_eq!(s.geometry.colors[0], [Vec4::new(0.25, 0.5, 0.75, 1.0); 3]);
    match surface(&s.geometry.materials[0]) {
        Some(Material::Diffuse {
            reflectance: SceneSpectrum::Constant(v),
        }) => assert_eq!(*v, 0.5),
        other => panic!("{other:?}"),
    }
    let grey = attribute_scene("face_weight", "").unwrap();
    assert_eq!(grey.geometry.colors[0], [Vec4::new(0.3, 0.3, 0.3, 1.0); 3]);
}

#[test]
fn mesh_attribute_refusals_name_the_texture() {
    let missing = attribute_scene("vertex_nothing", "")
        .unwrap_err()
        .to_string();
    assert!(missing.starts_with("s.xml:4:"), "{missing}");
    assert!(
        missing.contains("it has: vertex_color, face_color, face_weight"),
        "{missing}"
    );
    let bad = attribute_scene("colour", "").unwrap_err().to_string();
    assert!(bad.contains("starts with 'vertex_' or 'face_'"), "{bad}");
}

#[test]
fn instances_copy_their_group_with_its_materials() {
    let s = scene(
        r#"<shape type="shapegroup" id="g">
             <shape type="rectangle"><bsdf type="diffuse"><rgb name="reflectance" value="0.2"/></bsdf></shape>
             <shape type="cube"/>
           </shape>
           <shape type="instance"><ref id="g"/></shape>
           <shape type="instance"><ref id="g"/>
             <transform name="to_world"><scale z="-1"/><translate z="5"/></transform></shape>"#,
        &[],
    )
    .unwrap();
    let g = &s.geometry;
    assert_eq!(g.triangles.len(), 2 * (2 + 12));
    assert_eq!(g.instances.len(), 4);
    // The mirrored rectangle: its normal (inverse transpose) faces -z, so does its winding.
    let mirrored = g.instances[2].first;
    assert_eq!(facing(&g.triangles[mirrored]).z, -1.0);
    assert_eq!(g.normals[mirrored][0], Vec3::NEG_Z);
    assert!((g.triangles[mirrored][0].z - 5.0).abs() < 1e-6);
    // The group's shapes keep their own BSDFs in every instance.
    assert_eq!(g.instances[0].material, g.instances[2].material);
    assert!(g.gltf_features.iter().any(|f| f.contains("instances")));
}

#[test]
fn analytic_shapes_are_tessellated_with_texture_coordinates() {
    let s = scene(
        r#"<shape type="sphere"><float name="radius" value="2"/></shape>
           <shape type="disk"/><shape type="cylinder"/>"#,
        &[],
    )
    .unwrap();
    let g = &s.geometry;
    let (sphere, disk, cylinder) = (&g.instances[0], &g.instances[1], &g.instances[2]);
    assert_eq!(sphere.count, 65_024);
    assert_eq!(disk.count, 256);
    assert_eq!(cylinder.count, 512);
    assert_eq!(g.uvs.len(), g.triangles.len());
    // Every sphere vertex on the true sphere, its normal radial and outward.
    for k in sphere.first..sphere.first + sphere.count {
        for (p, n) in g.triangles[k].iter().zip(g.normals[k]) {
            assert!((p.length() - 2.0).abs() < 1e-5);
            assert!((n - *p / 2.0).length() < 1e-5);
        }
        assert!(facing(&g.triangles[k]).dot(g.triangles[k][0]) > 0.0);
    }
    assert!(
        g.gltf_features
            .iter()
            .any(|f| f.contains("sphere tessellated"))
    );
}

#[test]
fn mesh_files_and_shapes_refused_are_one_line_errors() {
    let obj = error(
        r#"<shape type="obj"><string name="filename" value="bad.obj"/></shape>"#,
        &[("bad.obj", b"v 0 0 0\nf 1 2 3\n".to_vec())],
    );
    assert!(
        obj.starts_with("s.xml:4: bad.obj: OBJ line 2: face corner '2'"),
        "{obj}"
    );
    let missing = error(
        r#"<shape type="ply"><string name="filename" value="none.ply"/></shape>"#,
        &[],
    );
    assert!(
        missing.contains("cannot read \"none.ply\": no file none.ply"),
        "{missing}"
    );
    let sdf = error(r#"<shape type="sdfgrid"/>"#, &[]);
    assert!(sdf.contains("'sdfgrid' is not read"), "{sdf}");
    let nested = error(
        r#"<shape type="shapegroup"><shape type="shapegroup"/></shape>"#,
        &[],
    );
    assert!(nested.contains("do not nest"), "{nested}");
    let emitting = error(
        r#"<shape type="shapegroup"><shape type="cube">
             <emitter type="area"><rgb name="radiance" value="1"/></emitter></shape></shape>"#,
        &[],
    );
    assert!(emitting.contains("cannot emit"), "{emitting}");
    let lonely = error(r#"<shape type="instance"/>"#, &[]);
    assert!(
        lonely.contains("needs a reference to a shapegroup"),
        "{lonely}"
    );
    let flat = error(
        r#"<shape type="cube"><transform name="to_world"><scale z="0"/></transform></shape>"#,
        &[],
    );
    assert!(flat.contains("singular"), "{flat}");
    let radius = error(
        r#"<shape type="sphere"><float name="radius" value="0"/></shape>"#,
        &[],
    );
    assert!(radius.contains("positive"), "{radius}");
}
