//! Mitsuba's textures through the converter: the repository's scenes/mitsuba/textures.xml
//! (images from scenes/tools/make_mitsuba_textures.py), texture coordinates of the shapes
//! that carry them, and the errors bad textures give.

use glam::Vec2;
use prism_spectrum::SampledWavelengths;

use super::ParseOptions;
use super::scene::{MitsubaScene, load};
use crate::load::LoadOptions;
use crate::materials::Material;
use crate::textures::{Pattern, SceneSpectrum};

fn folder() -> String {
    format!("{}/../scenes/mitsuba", env!("CARGO_MANIFEST_DIR"))
}

/// Loads `text` as if it were a file in scenes/mitsuba/, reading that folder's files.
fn read(text: &str) -> Result<MitsubaScene, String> {
    let dir = folder();
    let resolve = move |name: &str| -> std::io::Result<Vec<u8>> {
        std::fs::read(format!(
            "{dir}/{}",
            name.trim_start_matches("scenes/mitsuba/")
        ))
    };
    let options = ParseOptions {
        defines: &[],
        resolve: &resolve,
    };
    load(
        text,
        "scenes/mitsuba/t.xml",
        &options,
        &LoadOptions::default(),
    )
    .map_err(|e| e.to_string())
}

fn surface(scene: &MitsubaScene, material: usize) -> &Material {
    scene.geometry.materials[material]
        .spectral
        .as_ref()
        .and_then(|s| s.surface.as_ref())
        .unwrap()
}

fn reflectance(material: &Material) -> &SceneSpectrum {
    match material {
        Material::Diffuse { reflectance } => reflectance,
        other => panic!("{other:?}"),
    }
}

#[test]
fn the_textures_scene_reads_bitmaps_checkerboards_and_masks() {
    let text = std::fs::read_to_string(format!("{}/textures.xml", folder())).unwrap();
    let scene = read(&text).unwrap();
    let g = &scene.geometry;
    // Rectangles carry Mitsuba's texture coordinates: (x + 1) / 2, (y + 1) / 2.
    assert_eq!(g.uvs.len(), g.triangles.len());
    // The first rectangle's two triangles hold its four corners (0, 0) to (1, 1).
    let mut corners: Vec<[i32; 2]> = g.uvs[..2]
        .iter()
        .flatten()
        .map(|c| [(c.x * 2.0) as i32, (c.y * 2.0) as i32])
        .collect();
    corners.sort();
    corners.dedup();
    assert_eq!(corners, [[0, 0], [0, 2], [2, 0], [2, 2]]);
    let w = SampledWavelengths::new([450.0, 550.0, 600.0, 650.0], [0.01; 4]).unwrap();
    let SceneSpectrum::Pattern(bitmap) = reflectance(surface(&scene, 0)) else {
        panic!("a bitmap is a pattern")
    };
    assert!(matches!(**bitmap, Pattern::Sigmoid { .. }));
    // The 6 x 5 bitmap's first texel is red, through to_uv (1.5 u - 0.2, 1.2 v + 0.1):
    // its centre (1/12, 1/10) is at u = (1/12 + 0.2) / 1.5, v = (1/10 - 0.1) / 1.2.
    let red = bitmap.at(Vec2::new((1.0 / 12.0 + 0.2) / 1.5, 0.0), &w);
    assert!(red[3] > 0.6 && red[0] < 0.2, "{red:?}");
    let SceneSpectrum::Pattern(board) = reflectance(surface(&scene, 1)) else {
        panic!("a checkerboard is a pattern")
    };
    assert!(matches!(**board, Pattern::Checkerboard { .. }));
    // The mask's opacity is the grey disc: opaque in the middle, clear at the corners.
    let alpha = g.materials[2].alpha.as_ref().unwrap();
    let at = |u: f32, v: f32| alpha.at(&crate::textures::TexCoords::new(Vec2::new(u, v)), 1.0);
    assert_eq!((at(0.5, 0.5), at(0.02, 0.02)), (1.0, 0.0));
}

#[test]
fn bad_textures_are_one_line_errors() {
    let scene = |bsdf: &str| {
        format!(
            r#"<scene version="3.0.0">
                <sensor type="perspective"/>
                <shape type="rectangle">{bsdf}</shape>
            </scene>"#
        )
    };
    let cases = [
        (
            r#"<bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="textures/none.png"/></texture></bsdf>"#,
            "t.xml:3: cannot read",
        ),
        (
            r#"<bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="textures/ramp.png"/><string name="wrap_mode" value="wrap"/></texture></bsdf>"#,
            "wrap_mode \"wrap\": expected repeat, mirror or clamp",
        ),
        (
            r#"<bsdf type="diffuse"><texture type="bitmap" name="reflectance"><string name="filename" value="textures/colours.png"/><boolean name="raw" value="true"/></texture></bsdf>"#,
            "a raw colour bitmap cannot be a spectrum",
        ),
        (
            r#"<bsdf type="mask"><texture type="bitmap" name="opacity"><string name="filename" value="textures/colours.png"/></texture><bsdf type="diffuse"/></bsdf>"#,
            "must be raw",
        ),
        (
            r#"<bsdf type="diffuse"><texture type="mesh_attribute" name="reflectance"/></bsdf>"#,
            "texture 'mesh_attribute' needs 'name'",
        ),
        (
            r#"<bsdf type="diffuse"><texture type="checkerboard" name="reflectance"><float name="scale" value="2"/></texture></bsdf>"#,
            "texture checkerboard: parameter 'scale' is not read",
        ),
        (
            r#"<bsdf type="mask"><float name="opacity" value="0.5"/></bsdf>"#,
            "mask needs a nested BSDF",
        ),
    ];
    for (bsdf, expected) in cases {
        let e = read(&scene(bsdf)).unwrap_err();
        assert!(e.contains(expected), "{bsdf}: {e}");
        assert!(!e.contains('\n'), "{e}");
    }
    // A constant opacity below 1 is uniform stochastic alpha; 1 is opaque.
    let half = read(&scene(
        r#"<bsdf type="mask"><float name="opacity" value="0.25"/><bsdf type="diffuse"/></bsdf>"#,
    ))
    .unwrap();
    assert_eq!(
        half.geometry.materials[0].alpha.as_ref().unwrap().factor,
        0.25
    );
    let opaque = read(&scene(
        r#"<bsdf type="mask"><float name="opacity" value="1"/><bsdf type="diffuse"/></bsdf>"#,
    ))
    .unwrap();
    assert!(opaque.geometry.materials[0].alpha.is_none());
}
