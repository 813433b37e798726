//! Mitsuba's emitters through the converter: where an environment image's texels light
//! the sphere (Mitsuba's `uv_to_direction`, written out here as envmap.cpp has it), how
//! its spectra interpolate, the punctual lights' placement and units, and the errors; and
//! the sensor's default field of view, which the suite's directional-light scene shows.

use std::collections::HashMap;

use glam::{Mat3, Vec2, Vec3};
use prism_spectrum::{SampledWavelengths, Spectrum};

use super::ParseOptions;
use super::scene::{MitsubaScene, load};
use crate::lights::{Environment, EnvironmentMap, SpotFalloff, unit_d65};
use crate::load::{LightDesc, LoadOptions};

/// A Radiance RGBE image (flat scanlines) of `width` x `height` texels, rows from the top.
fn hdr(width: usize, height: usize, texel: impl Fn(usize, usize) -> [f32; 3]) -> Vec<u8> {
    let mut out =
        format!("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y {height} +X {width}\n").into_bytes();
    for y in 0..height {
        for x in 0..width {
            let c = texel(x, y);
            let m = c[0].max(c[1]).max(c[2]);
            if m < 1e-30 {
                out.extend([0, 0, 0, 0]);
            } else {
                let e = m.log2().floor() as i32 + 1;
                let f = 256.0 / 2f32.powi(e);
                out.extend(c.map(|v| (v * f) as u8));
                out.push((e + 128) as u8);
            }
        }
    }
    out
}

fn read(text: &str, files: HashMap<&'static str, Vec<u8>>) -> Result<MitsubaScene, String> {
    let resolve = move |name: &str| -> std::io::Result<Vec<u8>> {
        files
            .get(name.trim_start_matches("dir/"))
            .cloned()
            .ok_or_else(|| std::io::Error::other(format!("no file {name}")))
    };
    let options = ParseOptions {
        defines: &[],
        resolve: &resolve,
    };
    load(text, "dir/t.xml", &options, &LoadOptions::default()).map_err(|e| e.to_string())
}

const SENSOR: &str = r#"<sensor type="perspective"><film type="hdrfilm">
    <integer name="width" value="4"/><integer name="height" value="4"/></film></sensor>"#;

fn scene(emitters: &str, files: HashMap<&'static str, Vec<u8>>) -> Result<MitsubaScene, String> {
    read(
        &format!(r#"<scene version="3.0.0">{SENSOR}{emitters}</scene>"#),
        files,
    )
}

fn map(scene: &MitsubaScene) -> &EnvironmentMap {
    match &scene.geometry.spectral.environment {
        Some(Environment::Map(m)) => m,
        other => panic!("{other:?}"),
    }
}

/// Mitsuba's `uv_to_direction` (src/emitters/envmap.cpp).
fn mitsuba_direction(u: f32, v: f32) -> Vec3 {
    let (sin_theta, cos_theta) = (std::f32::consts::PI * v).sin_cos();
    let (sin_phi, cos_phi) = (2.0 * std::f32::consts::PI * u).sin_cos();
    Vec3::new(sin_phi * sin_theta, cos_theta, -cos_phi * sin_theta)
}

fn at_560(map: &EnvironmentMap, d: Vec3) -> f32 {
    let w = SampledWavelengths::new([560.0; 1], [1.0; 1]).unwrap();
    map.radiance(d, &w).0[0]
}

/// A 16 x 8 image, black but for texel (4, 3) of grey `value`.
fn one_texel(value: f32) -> HashMap<&'static str, Vec<u8>> {
    HashMap::from([(
        "sky.hdr",
        hdr(16, 8, |x, y| {
            if (x, y) == (4, 3) {
                [value; 3]
            } else {
                [0.0; 3]
            }
        }),
    )])
}

/// The texel (4, 3) of 16 x 8 is at u = 4.5 / 16 (columns centred), v = 3 / 7 (rows on
/// the corners): lit there, in the emitter's frame, and dark at the direction the glTF
/// convention gives the same coordinates.
#[test]
fn a_lit_texel_shows_where_mitsuba_puts_it() {
    let (u, v) = (4.5 / 16.0, 3.0 / 7.0);
    let d = mitsuba_direction(u, v);
    let d65 = unit_d65().evaluate(560.0) as f32;
    let plain = scene(
        r#"<emitter type="envmap"><string name="filename" value="sky.hdr"/>
           <float name="scale" value="2"/></emitter>"#,
        one_texel(1.0),
    )
    .unwrap();
    let m = map(&plain);
    assert!(
        (at_560(m, d) / (2.0 * d65) - 1.0).abs() < 2e-3,
        "{}",
        at_560(m, d)
    );
    assert!((m.uv(d) - Vec2::new(u, v)).length() < 1e-5);
    let (back, _) = m.direction(Vec2::new(u, v));
    assert!((back - d).length() < 1e-5);
    let theta = std::f32::consts::PI * v;
    let phi = 2.0 * std::f32::consts::PI * (u - 0.5);
    let gltf = Vec3::new(
        theta.sin() * phi.cos(),
        theta.cos(),
        theta.sin() * phi.sin(),
    );
    assert_eq!(at_560(m, gltf), 0.0);

    // Turned by to_world: a quarter turn about +y takes the texel with it.
    let turned = scene(
        r#"<emitter type="envmap"><string name="filename" value="sky.hdr"/>
           <transform name="to_world"><rotate y="1" angle="90"/></transform></emitter>"#,
        one_texel(1.0),
    )
    .unwrap();
    let r = Mat3::from_rotation_y(90f32.to_radians());
    let m = map(&turned);
    assert!((at_560(m, r * d) / d65 - 1.0).abs() < 2e-3);
    assert_eq!(at_560(m, d), 0.0);
}

/// Halfway between the lit texel and a black one, Mitsuba interpolates the sigmoid
/// spectra and the scales apart and multiplies them: a quarter of the light, not half.
#[test]
fn spectra_and_scales_interpolate_apart_as_in_mitsuba() {
    let lit = scene(
        r#"<emitter type="envmap"><string name="filename" value="sky.hdr"/></emitter>"#,
        one_texel(3.0),
    )
    .unwrap();
    let m = map(&lit);
    let d65 = unit_d65().evaluate(560.0) as f32;
    let between = mitsuba_direction(5.0 / 16.0, 3.0 / 7.0);
    assert!((at_560(m, between) / (0.75 * d65) - 1.0).abs() < 2e-3);
}

#[test]
fn point_directional_and_spot_lights_read_as_mitsuba_places_them() {
    let s = scene(
        r#"<emitter type="point"><point name="position" value="1, 2, 3"/>
             <float name="intensity" value="3"/></emitter>
           <emitter type="point"><transform name="to_world"><translate value="0, 5, 0"/>
             </transform><rgb name="intensity" value="1, 0.5, 0.25"/></emitter>
           <emitter type="directional"><vector name="direction" value="0, 0, -2"/>
             <rgb name="irradiance" value="2"/></emitter>
           <emitter type="directional"><transform name="to_world">
             <lookat origin="0, 0, 0" target="1, 0, 0" up="0, 1, 0"/></transform></emitter>
           <emitter type="spot"><float name="cutoff_angle" value="30"/>
             <transform name="to_world"><lookat origin="0, 1, 0" target="0, 0, 0" up="0, 0, 1"/>
             </transform></emitter>"#,
        HashMap::new(),
    )
    .unwrap();
    let lights = &s.geometry.lights;
    assert_eq!(lights.len(), 5);
    let d65 = unit_d65().evaluate(560.0);
    let near = |a: Vec3, b: Vec3| (a - b).length() < 1e-5;
    match &lights[0] {
        // A number is a grey colour under D65.
        LightDesc::Point {
            position,
            spectrum,
            scale,
        } => {
            assert!(near(*position, Vec3::new(1.0, 2.0, 3.0)));
            assert!((spectrum.evaluate(560.0) * scale / (3.0 * d65) - 1.0).abs() < 1e-3);
        }
        other => panic!("{other:?}"),
    }
    match &lights[1] {
        LightDesc::Point { position, .. } => assert!(near(*position, Vec3::new(0.0, 5.0, 0.0))),
        other => panic!("{other:?}"),
    }
    match &lights[2] {
        LightDesc::Directional { direction, .. } => assert!(near(*direction, -Vec3::Z)),
        other => panic!("{other:?}"),
    }
    match &lights[3] {
        LightDesc::Directional {
            direction,
            spectrum,
            ..
        } => {
            assert!(near(*direction, Vec3::X));
            // No irradiance: D65 of luminance 1.
            assert!((spectrum.evaluate(560.0) / d65 - 1.0).abs() < 1e-3);
        }
        other => panic!("{other:?}"),
    }
    match &lights[4] {
        LightDesc::Spot {
            position,
            direction,
            inner,
            outer,
            falloff,
            ..
        } => {
            assert!(near(*position, Vec3::Y));
            assert!(near(*direction, -Vec3::Y));
            // beam_width defaults to 3/4 of the cutoff.
            assert!((inner.to_degrees() - 22.5).abs() < 1e-4);
            assert!((outer.to_degrees() - 30.0).abs() < 1e-4);
            assert_eq!(*falloff, SpotFalloff::LinearAngle);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn emitters_prism_does_not_follow_are_errors_with_their_line() {
    let cases = [
        (
            r#"<emitter type="spot"><rgb name="texture" value="0.5"/></emitter>"#,
            "'texture' must be a texture",
        ),
        (
            r#"<emitter type="point"><point name="position" value="0, 0, 0"/>
               <transform name="to_world"><translate value="1, 0, 0"/></transform></emitter>"#,
            "only one of",
        ),
        (
            r#"<emitter type="point"><float name="power" value="1"/></emitter>"#,
            "'power' is not read",
        ),
        (
            r#"<emitter type="spot"><float name="beam_width" value="40"/></emitter>"#,
            "beam_width",
        ),
        (
            r#"<emitter type="envmap"><string name="filename" value="sky.hdr"/>
               <transform name="to_world"><scale value="2"/></transform></emitter>"#,
            "rotation",
        ),
        (
            r#"<emitter type="envmap"><string name="filename" value="missing.exr"/></emitter>"#,
            "missing.exr",
        ),
    ];
    for (xml, expected) in cases {
        let e = scene(xml, one_texel(1.0)).unwrap_err();
        assert!(e.contains(expected) && e.contains("t.xml:"), "{e}");
    }
}

/// An area emitter's bitmap radiance is the bitmap as Mitsuba reads any texture: the
/// same spectra as the bitmap gives a diffuse reflectance (no D65), varying over the shape.
#[test]
fn an_area_emitters_bitmap_radiance_is_the_bitmaps_reflectance_spectrum() {
    let png = std::fs::read(format!(
        "{}/../scenes/mitsuba/textures/colours.png",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let s = read(
        &format!(
            r#"<scene version="3.0.0">{SENSOR}<shape type="rectangle">
                <bsdf type="diffuse"><texture name="reflectance" type="bitmap">
                    <string name="filename" value="c.png"/></texture></bsdf>
                <emitter type="area"><texture name="radiance" type="bitmap">
                    <string name="filename" value="c.png"/></texture></emitter>
               </shape></scene>"#
        ),
        HashMap::from([("c.png", png)]),
    )
    .unwrap();
    let spectral = s.geometry.materials[0].spectral.as_ref().unwrap();
    let radiance = spectral.emission.as_ref().unwrap();
    let reflectance = match spectral.surface.as_ref().unwrap() {
        crate::materials::Material::Diffuse { reflectance } => reflectance,
        other => panic!("{other:?}"),
    };
    let w = SampledWavelengths::new([450.0, 550.0, 650.0, 700.0], [0.01; 4]).unwrap();
    let mut values = Vec::new();
    for uv in [
        Vec2::new(0.1, 0.1),
        Vec2::new(0.5, 0.3),
        Vec2::new(0.9, 0.7),
    ] {
        let (e, r) = (radiance.at_uv(uv, &w), reflectance.at_uv(uv, &w));
        assert_eq!(e.0, r.0);
        values.push(e.0);
    }
    assert!(values[0] != values[1] && values[1] != values[2]);
    assert!(matches!(s.geometry.lights[0], LightDesc::Area { .. }));
}

/// A spot light's texture fills the cutoff cone: the axis looks at its centre, and a
/// direction at the cutoff angle along the light's +x at the right edge (u = 1).
#[test]
fn a_spot_projects_its_texture_over_the_cutoff_cone() {
    let png = std::fs::read(format!(
        "{}/../scenes/mitsuba/textures/colours.png",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let s = scene(
        r#"<emitter type="spot"><float name="cutoff_angle" value="30"/>
             <texture name="texture" type="bitmap"><string name="filename" value="c.png"/></texture>
             <transform name="to_world"><lookat origin="0, 1, 0" target="0, 0, 0" up="0, 0, 1"/>
             </transform></emitter>"#,
        HashMap::from([("c.png", png)]),
    )
    .unwrap();
    let LightDesc::Spot {
        texture: Some(t), ..
    } = &s.geometry.lights[0]
    else {
        panic!("{:?}", s.geometry.lights[0]);
    };
    assert!((t.uv(-Vec3::Y) - Vec2::splat(0.5)).length() < 1e-6);
    // The light's +x is up × axis: lookat's frame, (0, 0, 1) × (0, -1, 0) = (1, 0, 0).
    let edge = Vec3::new(30f32.to_radians().sin(), -30f32.to_radians().cos(), 0.0);
    assert!(
        (t.uv(edge) - Vec2::new(1.0, 0.5)).length() < 1e-5,
        "{}",
        t.uv(edge)
    );
}

/// A sensor without a `fov` has Mitsuba's 50mm focal length on a 36 x 24 mm frame, along
/// the diagonal (`parse_fov`): 46.8 degrees across the diagonal.
#[test]
fn a_sensor_without_fov_has_mitsubas_fifty_millimetres() {
    let s = read(
        r#"<scene version="3.0.0"><sensor type="perspective"><film type="hdrfilm">
           <integer name="width" value="30"/><integer name="height" value="40"/></film>
           </sensor></scene>"#,
        HashMap::new(),
    )
    .unwrap();
    let crate::camera::Projection::Perspective { yfov } = s.geometry.cameras[0].projection else {
        panic!();
    };
    let tan_diagonal = (36.0f64.hypot(24.0) / 100.0) as f32;
    let tan_y = tan_diagonal * 40.0 / 50.0;
    assert!(((yfov / 2.0).tan() - tan_y).abs() < 1e-5, "{yfov}");
}

/// Mitsuba's `direct` integrator is a path of one bounce (the suite's directional-light
/// scene lights a sphere's underside from the floor otherwise).
#[test]
fn a_direct_integrator_is_one_bounce() {
    let s = scene(r#"<integrator type="direct"/>"#, HashMap::new()).unwrap();
    assert_eq!(s.max_depth, Some(1));
    assert!(s.geometry.warnings.iter().all(|w| !w.contains("direct")));
}

/// A spectrum of 1 everywhere has luminance 1 in Mitsuba's films: an emitted spectrum
/// given as values is scaled by Mitsuba's CIE Y normalization, a colour is not.
#[test]
fn emitted_spectra_are_in_mitsubas_units() {
    let s = scene(
        r#"<emitter type="point"><spectrum name="intensity" value="400:2, 700:2"/></emitter>
           <emitter type="point"><spectrum name="intensity" value="3"/></emitter>"#,
        HashMap::new(),
    )
    .unwrap();
    let value = |i: usize| match &s.geometry.lights[i] {
        LightDesc::Point { spectrum, .. } => spectrum.evaluate(550.0),
        other => panic!("{other:?}"),
    };
    assert!((value(0) * 106.750_259_4 - 2.0).abs() < 1e-6);
    assert!((value(1) * 106.750_259_4 - 3.0).abs() < 1e-6);
}

/// Mitsuba's projector: at `to_world`'s translation along its +z, pi scale times its
/// irradiance with the 1 / cos^3 falloff, and its image over the frustum of `fov` along x
/// with the image's aspect (6 x 5 texels), u growing towards the light's -x and v
/// towards its -y (the perspective camera's film, `perspective_projection`), and nothing
/// outside the frustum.
#[test]
fn a_projector_projects_its_image_through_a_frustum() {
    let png = std::fs::read(format!(
        "{}/../scenes/mitsuba/textures/colours.png",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap();
    let s = scene(
        r#"<emitter type="projector"><float name="fov" value="90"/><float name="scale" value="2"/>
             <texture name="irradiance" type="bitmap"><string name="filename" value="c.png"/></texture>
             <transform name="to_world"><lookat origin="0, 1, 0" target="0, 0, 0" up="0, 0, 1"/>
             </transform></emitter>
           <emitter type="projector"><float name="fov" value="90"/>
             <rgb name="irradiance" value="0.5"/></emitter>"#,
        HashMap::from([("c.png", png.clone())]),
    )
    .unwrap();
    let LightDesc::Spot {
        position,
        direction,
        scale,
        falloff,
        texture: Some(t),
        spectrum,
        outer,
        ..
    } = &s.geometry.lights[0]
    else {
        panic!("{:?}", s.geometry.lights[0]);
    };
    assert_eq!(*position, Vec3::Y);
    assert!((*direction + Vec3::Y).length() < 1e-6);
    assert!((scale - 2.0 * std::f64::consts::PI).abs() < 1e-12);
    assert_eq!(*falloff, SpotFalloff::InverseCosCubed);
    assert!((spectrum.evaluate(550.0) * 106.750_259_4 - 1.0).abs() < 1e-6);
    // The cone holds the frustum's corner: tan = hypot(1, 5 / 6).
    assert!(outer.tan() >= 1f32.hypot(5.0 / 6.0));
    assert!((t.uv(-Vec3::Y) - Vec2::splat(0.5)).length() < 1e-6);
    // The light's +x is up x axis = (1, 0, 0), +y its up (0, 0, 1); tan_x = 1,
    // tan_y = 5 / 6.
    let at = |x: f32, z: f32| Vec3::new(x, -1.0, z).normalize();
    assert!((t.uv(at(1.0, 0.0)) - Vec2::new(0.0, 0.5)).length() < 1e-5);
    assert!((t.uv(at(-1.0, 0.0)) - Vec2::new(1.0, 0.5)).length() < 1e-5);
    assert!((t.uv(at(0.0, 5.0 / 6.0)) - Vec2::new(0.5, 0.0)).length() < 1e-5);
    // Which texel lights a direction: the image's at that uv, read as the spot reads
    // its texture (whose uv is 1/2 + 1/2 (x, y) / (z tan 45)); none beyond the frustum.
    let spot = scene(
        r#"<emitter type="spot"><float name="cutoff_angle" value="45"/>
             <texture name="texture" type="bitmap"><string name="filename" value="c.png"/></texture>
             <transform name="to_world"><lookat origin="0, 1, 0" target="0, 0, 0" up="0, 0, 1"/>
             </transform></emitter>"#,
        HashMap::from([("c.png", png)]),
    )
    .unwrap();
    let LightDesc::Spot {
        texture: Some(spot),
        ..
    } = &spot.geometry.lights[0]
    else {
        panic!();
    };
    let w = SampledWavelengths::new([450.0, 550.0, 650.0, 700.0], [0.01; 4]).unwrap();
    let mut seen = Vec::new();
    for uv in [
        Vec2::new(0.1, 0.1),
        Vec2::new(0.9, 0.15),
        Vec2::new(0.3, 0.85),
    ] {
        let from_projector = t.at(at(1.0 - 2.0 * uv.x, (1.0 - 2.0 * uv.y) * 5.0 / 6.0), &w);
        let from_spot = spot.at(at(2.0 * uv.x - 1.0, 2.0 * uv.y - 1.0), &w);
        assert!((spot.uv(at(2.0 * uv.x - 1.0, 2.0 * uv.y - 1.0)) - uv).length() < 1e-5);
        for (p, q) in from_projector.0.iter().zip(from_spot.0) {
            assert!(
                (p - q).abs() < 1e-5,
                "{uv}: {from_projector:?} {from_spot:?}"
            );
        }
        seen.push(from_projector.0);
    }
    assert!(seen[0] != seen[1] && seen[1] != seen[2]);
    assert_eq!(t.at(at(1.1, 0.0), &w).0, [0.0; 4]);
    assert_eq!(t.at(at(0.0, 0.9), &w).0, [0.0; 4]);
    assert_eq!(t.at(Vec3::Y, &w).0, [0.0; 4]);
    // A constant irradiance: an illuminant, the image a square of tan 1.
    let LightDesc::Spot {
        texture: Some(t),
        spectrum,
        scale,
        ..
    } = &s.geometry.lights[1]
    else {
        panic!("{:?}", s.geometry.lights[1]);
    };
    assert!((scale - std::f64::consts::PI).abs() < 1e-12);
    assert!(spectrum.evaluate(550.0) > 0.0);
    let ahead = |x: f32, y: f32| Vec3::new(-x, y, 1.0).normalize();
    assert!((t.uv(ahead(1.0, 1.0)) - Vec2::new(1.0, 0.0)).length() < 1e-5);
    assert_eq!(t.at(ahead(0.5, 0.5), &w).0, [1.0; 4]);
    assert_eq!(t.at(ahead(1.01, 0.0), &w).0, [0.0; 4]);
}
