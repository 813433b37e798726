//! The scene format's thin lenses: `PRISM_spectral` on a glTF camera, and its errors.

use prism_scene::camera::{ApertureShape, ApertureSize, Camera};

/// A glTF document with one perspective camera (or an orthographic one) described by
/// `spectral`, loaded.
fn load_camera(spectral: serde_json::Value, orthographic: bool) -> Result<Camera, String> {
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
        prism_scene::load::load_geometry(&bytes, &|_| Err(std::io::Error::other("no files")), None)
            .map_err(|e| e.to_string())?;
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
