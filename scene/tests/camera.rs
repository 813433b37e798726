//! Cameras from glTF, their rays, and the default framing camera.

use glam::{Mat4, Vec2, Vec3};
use prism_scene::camera::{Camera, Projection};
use prism_scene::geometry::{Bvh, BvhQuality};
use prism_scene::load::load_geometry;

fn cornell() -> prism_scene::load::LoadedGeometry {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenes");
    let bytes = std::fs::read(dir.join("cornell-box.gltf")).unwrap();
    load_geometry(&bytes, &|uri| std::fs::read(dir.join(uri)), None).unwrap()
}

#[test]
fn the_cornell_camera_looks_at_the_back_wall() {
    let scene = cornell();
    let camera = scene.camera(None).unwrap();
    assert_eq!(camera.name, "camera");
    let bvh = Bvh::build(&scene.triangles, BvhQuality::Medium);
    let centre = camera.generate_ray(Vec2::splat(0.5), 1.0);
    assert!((centre.origin - Vec3::new(0.0, 0.0, 3.9)).length() < 1e-6);
    assert!((centre.direction - -Vec3::Z).length() < 1e-6);
    let node_of = |triangle: usize| {
        scene
            .instances
            .iter()
            .find(|i| (i.first..i.first + i.count).contains(&triangle))
            .unwrap()
            .node
            .clone()
    };
    // The large box spans x in [-0.71, 0.05] in front of the back wall: the centre ray
    // meets its front face.
    let hit = bvh.intersect(&centre).unwrap();
    assert_eq!(node_of(hit.triangle), "large-box");
    assert!(hit.hit.t > 3.8 && hit.hit.t < 4.0, "t = {}", hit.hit.t);
    // A ray through the point (0, 0.6, -1), above the boxes, reaches the back wall there.
    let prism_scene::camera::Projection::Perspective { yfov } = camera.projection else {
        panic!()
    };
    let ndc_y = (0.6 / 4.9) / (yfov / 2.0).tan();
    let up = camera.generate_ray(Vec2::new(0.5, 0.5 - 0.5 * ndc_y), 1.0);
    let wall = bvh.intersect(&up).unwrap();
    assert_eq!(node_of(wall.triangle), "back");
    let p = up.at(wall.hit.t);
    assert!((p - Vec3::new(0.0, 0.6, -1.0)).length() < 1e-4, "{p}");
    let err = scene.camera(Some("nope")).unwrap_err().to_string();
    assert!(err.contains("cameras: camera"), "{err}");
}

#[test]
fn perspective_rays_span_the_field_of_view() {
    let yfov = 0.7f32;
    let camera = Camera {
        name: "c".into(),
        to_world: Mat4::IDENTITY,
        aspect_ratio: None,
        lens: None,
        system: None,
        projection: Projection::Perspective { yfov },
    };
    let top = camera.generate_ray(Vec2::new(0.5, 0.0), 2.0).direction;
    assert!(
        (top.angle_between(-Vec3::Z) - yfov / 2.0).abs() < 1e-5,
        "top edge at yfov / 2"
    );
    assert!(top.y > 0.0, "film y runs down, world y up");
    let right = camera.generate_ray(Vec2::new(1.0, 0.5), 2.0).direction;
    assert!(
        (right.angle_between(-Vec3::Z) - (2.0 * (yfov / 2.0).tan()).atan()).abs() < 1e-5,
        "aspect widens x"
    );
}

#[test]
fn orthographic_rays_are_parallel() {
    let camera = Camera {
        name: "o".into(),
        to_world: Mat4::from_translation(Vec3::new(1.0, 2.0, 3.0)),
        aspect_ratio: None,
        lens: None,
        system: None,
        projection: Projection::Orthographic {
            xmag: 2.0,
            ymag: 1.0,
        },
    };
    let a = camera.generate_ray(Vec2::new(0.0, 0.0), 1.0);
    let b = camera.generate_ray(Vec2::new(1.0, 1.0), 1.0);
    assert_eq!(a.direction, b.direction);
    assert!((a.origin - Vec3::new(-1.0, 3.0, 3.0)).length() < 1e-6);
    assert!((b.origin - Vec3::new(3.0, 1.0, 3.0)).length() < 1e-6);
}

/// A scene without a camera gets one that sees its whole bounding box, and fills most of
/// the view with it (as the glTF Sample Viewer frames a model), not a sliver of it.
#[test]
fn the_default_camera_frames_the_scene() {
    let (lo, hi) = (Vec3::new(-3.0, -1.0, -2.0), Vec3::new(5.0, 4.0, 0.5));
    let camera = Camera::framing(lo, hi);
    let eye = camera.to_world.transform_point3(Vec3::ZERO);
    let Projection::Perspective { yfov } = camera.projection else {
        panic!()
    };
    let mut widest = 0.0f32;
    for i in 0..8 {
        let corner = Vec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        let d = corner - eye;
        assert!(d.z < 0.0, "corner {corner} behind the camera");
        assert!(
            (d.y / -d.z).abs() <= (yfov / 2.0).tan() + 1e-6,
            "corner {corner} above or below the view"
        );
        assert!(
            (d.x / -d.z).abs() <= (yfov / 2.0).tan() + 1e-6,
            "corner {corner} beside the view"
        );
        widest = widest.max(d.x.abs().max(d.y.abs()) / -d.z);
    }
    assert!(
        widest > 0.9 * (yfov / 2.0).tan(),
        "the box spans {widest} of {}",
        (yfov / 2.0).tan()
    );
}

/// `Camera::look_at` points the film's centre at the target from the eye, keeps `up`
/// upwards on the film, and survives degenerate input (no NaN in its matrix).
#[test]
fn look_at_points_the_view_at_the_target() {
    let eye = Vec3::new(3.0, 2.0, 4.0);
    let target = Vec3::new(-1.0, 0.5, -2.0);
    let camera = Camera::look_at(eye, target, Vec3::Y, 0.6);
    let centre = camera.generate_ray(Vec2::splat(0.5), 1.5);
    assert!((centre.origin - eye).length() < 1e-5);
    assert!((centre.direction.normalize() - (target - eye).normalize()).length() < 1e-5);
    // The top of the film looks higher than its bottom.
    let top = camera
        .generate_ray(Vec2::new(0.5, 0.0), 1.5)
        .direction
        .normalize();
    let bottom = camera
        .generate_ray(Vec2::new(0.5, 1.0), 1.5)
        .direction
        .normalize();
    assert!(top.y > bottom.y);
    // The target projects to the film's centre.
    let seen = camera.project(target, 1.5).expect("in view");
    assert!(
        (seen.film - Vec2::splat(0.5)).length() < 1e-4,
        "{}",
        seen.film
    );
    for (eye, target, up, yfov) in [
        (Vec3::ZERO, Vec3::ZERO, Vec3::Y, 0.6),
        (Vec3::ZERO, Vec3::Y, Vec3::Y, 0.6),
        (Vec3::splat(f32::NAN), Vec3::ONE, Vec3::Y, f32::NAN),
        (Vec3::ZERO, Vec3::NEG_Z, Vec3::ZERO, 10.0),
    ] {
        let c = Camera::look_at(eye, target, up, yfov);
        assert!(c.to_world.is_finite(), "{eye} {target} {up}");
        assert!(c.generate_ray(Vec2::splat(0.5), 1.0).direction.is_finite());
    }
}
