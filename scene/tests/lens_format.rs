//! The scene format's lenses: `PRISM_spectral` on a glTF camera (a thin lens, or a lens
//! system read from a prescription file), and its errors.

use prism_scene::camera::{ApertureShape, ApertureSize, Camera};

/// A glTF document with one perspective camera (or an orthographic one) described by
/// `spectral`, loaded.
fn load_camera(spectral: serde_json::Value, orthographic: bool) -> Result<Camera, String> {
    load_camera_with(spectral, orthographic, &|_| {
        Err(std::io::Error::other("no files"))
    })
}

/// [`load_camera`] with files read through `resolve`.
fn load_camera_with(
    spectral: serde_json::Value,
    orthographic: bool,
    resolve: &prism_scene::load::Resolver,
) -> Result<Camera, String> {
    let projection = if orthographic {
        serde_json::json!({"type": "orthographic", "orthographic": {"xmag": 1.0, "ymag": 1.0, "znear": 0.1, "zfar": 10.0}})
    } else {
        serde_json::json!({"type": "perspective", "perspective": {"yfov": 0.7, "znear": 0.1}})
    };
    let mut camera = projection;
    camera["extensions"] = serde_json::json!({ "PRISM_spectral": spectral });
    let doc = serde_json::json!({
        "asset": {"version": "2.0"},
        "extensionsUsed": ["PRISM_spectral"],
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"name": "eye", "camera": 0}, {"mesh": 0}],
        "cameras": [camera],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
            "min": [0.0, 0.0, -5.0], "max": [1.0, 1.0, -5.0]}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAKDAAACAPwAAAAAAAKDAAAAAAAAAgD8AAKDA"}],
    });
    let bytes = serde_json::to_vec(&doc).unwrap();
    let loaded =
        prism_scene::load::load_geometry(&bytes, resolve, None).map_err(|e| e.to_string())?;
    Ok(loaded.cameras[0].clone())
}

#[test]
fn cameras_describe_their_lens_in_the_scene_format() {
    let lens = |v| load_camera(v, false).unwrap().lens.unwrap();
    let l = lens(serde_json::json!({"aperture": {"f_number": 2.8}}));
    assert_eq!(l.size, ApertureSize::FNumber(2.8));
    assert_eq!(
        (l.shape, l.focus_distance, l.sensor_width),
        (ApertureShape::Disk, None, 0.036)
    );
    let l = lens(
        serde_json::json!({"aperture": {"radius": 0.01, "blades": 6, "rotation": 90},
        "focus_distance": 2.5, "sensor_width": 0.024}),
    );
    assert_eq!(l.size, ApertureSize::Radius(0.01));
    assert_eq!(
        l.shape,
        ApertureShape::Polygon {
            blades: 6,
            rotation: 90f32.to_radians()
        }
    );
    assert_eq!((l.focus_distance, l.sensor_width), (Some(2.5), 0.024));
    assert!(
        load_camera(serde_json::json!({}), false)
            .unwrap()
            .lens
            .is_none()
    );
    for (spectral, words) in [
        (
            serde_json::json!({"aperture": {"f_number": 0}}),
            "f-number 0",
        ),
        (serde_json::json!({"aperture": {"radius": -1}}), "radius -1"),
        (
            serde_json::json!({"aperture": {"f_number": 2, "radius": 0.1}}),
            "one of",
        ),
        (
            serde_json::json!({"aperture": {"f_number": 2, "blades": 2}}),
            "blades 2",
        ),
        (
            serde_json::json!({"aperture": {"f_number": 2, "rotation": 3}}),
            "needs 'blades'",
        ),
        (
            serde_json::json!({"aperture": {"f_number": 2}, "focus_distance": -3}),
            "focus distance -3",
        ),
        (
            serde_json::json!({"aperture": {"f_number": 2}, "sensor_width": 36}),
            "0.036",
        ),
        (
            serde_json::json!({"focus_distance": 3}),
            "need an 'aperture'",
        ),
        (
            serde_json::json!({"aperture": {"fnumber": 2}}),
            "unknown key 'fnumber'",
        ),
    ] {
        let e = load_camera(spectral.clone(), false).unwrap_err();
        assert!(
            e.contains("camera eye") && e.contains(words),
            "{spectral}: {e}"
        );
    }
    let e = load_camera(serde_json::json!({"aperture": {"f_number": 2}}), true).unwrap_err();
    assert!(e.contains("perspective"), "{e}");
}

/// Files a scene may name: the double Gauss, and a file that is no prescription.
fn lens_files(name: &str) -> std::io::Result<Vec<u8>> {
    match name {
        "dgauss.dat" => Ok(include_bytes!("../../scenes/lenses/dgauss.50mm.dat").to_vec()),
        "broken.dat" => Ok(b"29.4 3.7 1.67\n".to_vec()),
        "star.png" => Ok(include_bytes!("data/aperture/star.png").to_vec()),
        "black.png" => Ok(black_png()),
        _ => Err(std::io::Error::new(
            std::io::ErrorKind::NotFound,
            "not found",
        )),
    }
}

#[test]
fn cameras_mount_lens_systems_from_prescription_files() {
    let camera = |v| load_camera_with(v, false, &lens_files);
    let c = camera(serde_json::json!({"lens": "dgauss.dat"})).unwrap();
    assert!(c.lens.is_none());
    let m = c.system.unwrap();
    assert_eq!(m.source, "dgauss.dat");
    assert_eq!(m.system.interfaces().len(), 11);
    assert!(m.system.dispersive());
    assert_eq!(
        (m.f_number, m.focus_distance, m.sensor_width),
        (None, None, 0.036)
    );
    let m = camera(
        serde_json::json!({"lens": "dgauss.dat", "aperture": {"f_number": 4},
        "focus_distance": 2.5, "sensor_width": 0.024}),
    )
    .unwrap()
    .system
    .unwrap();
    assert_eq!(
        (m.f_number, m.focus_distance, m.sensor_width),
        (Some(4.0), Some(2.5), 0.024)
    );
    for (spectral, words) in [
        (
            serde_json::json!({"lens": "missing.dat"}),
            "lens missing.dat: not found",
        ),
        (
            serde_json::json!({"lens": "broken.dat"}),
            "lens broken.dat: line 1: 3 columns",
        ),
        (
            serde_json::json!({"lens": 3}),
            "'lens' must be a prescription's file name",
        ),
        (
            serde_json::json!({"lens": "dgauss.dat", "aperture": {"radius": 0.01}}),
            "closed by 'f_number'",
        ),
        (
            serde_json::json!({"lens": "dgauss.dat", "aperture": {"f_number": 2, "blades": 6}}),
            "unknown key 'blades'",
        ),
        (
            serde_json::json!({"lens": "dgauss.dat", "focus_distance": 0}),
            "focus_distance 0",
        ),
        (
            serde_json::json!({"lens": "dgauss.dat", "sensor_width": 36}),
            "0.036",
        ),
        (
            serde_json::json!({"lens": "dgauss.dat", "zoom": 2}),
            "unknown key 'zoom'",
        ),
    ] {
        let e = camera(spectral.clone()).unwrap_err();
        assert!(
            e.contains("camera eye") && e.contains(words),
            "{spectral}: {e}"
        );
    }
    let e =
        load_camera_with(serde_json::json!({"lens": "dgauss.dat"}), true, &lens_files).unwrap_err();
    assert!(e.contains("perspective"), "{e}");
}

/// A 1 x 1 black PNG (grey, 8 bits), from its bytes.
fn black_png() -> Vec<u8> {
    vec![
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
        0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x00, 0x00, 0x00, 0x00, 0x3a,
        0x7e, 0x9b, 0x55, 0x00, 0x00, 0x00, 0x0a, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x60,
        0x00, 0x00, 0x00, 0x02, 0x00, 0x01, 0x48, 0xaf, 0xa4, 0x71, 0x00, 0x00, 0x00, 0x00, 0x49,
        0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82,
    ]
}

#[test]
fn an_aperture_image_shapes_the_opening() {
    let camera = |v| load_camera_with(v, false, &lens_files);
    let lens = camera(serde_json::json!({"aperture": {"f_number": 2, "image": "star.png"}}))
        .unwrap()
        .lens
        .unwrap();
    let ApertureShape::Image(image) = &lens.shape else {
        panic!("{:?}", lens.shape)
    };
    // The star's centre and points let light through; its corners and the gaps between
    // its points do not.
    assert_eq!(image.transmission(glam::Vec2::ZERO), 1.0);
    assert_eq!(image.transmission(glam::Vec2::new(0.0, 0.9)), 1.0);
    assert_eq!(image.transmission(glam::Vec2::new(0.95, 0.95)), 0.0);
    assert_eq!(image.transmission(glam::Vec2::new(0.0, -0.8)), 0.0);
    for (spectral, words) in [
        (
            serde_json::json!({"aperture": {"f_number": 2, "image": "missing.png"}}),
            "aperture image missing.png: not found",
        ),
        (
            serde_json::json!({"aperture": {"f_number": 2, "image": "black.png"}}),
            "lets no light through",
        ),
        (
            serde_json::json!({"aperture": {"f_number": 2, "image": "broken.dat"}}),
            "not a PNG",
        ),
        (
            serde_json::json!({"aperture": {"f_number": 2, "image": "star.png", "blades": 5}}),
            "'blades' or 'image'",
        ),
        (
            serde_json::json!({"aperture": {"f_number": 2, "image": "star.png", "rotation": 5}}),
            "needs 'blades'",
        ),
    ] {
        let e = camera(spectral.clone()).unwrap_err();
        assert!(
            e.contains("camera eye") && e.contains(words),
            "{spectral}: {e}"
        );
    }
}
