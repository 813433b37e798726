//! Light paths aimed at the surfaces that focus light: light from infinity crosses their
//! bounding sphere only, from outside the scene, and lights are chosen by the power that
//! can reach it.

use glam::{Vec2, Vec3};
use prism_scene::camera::Camera;
use prism_scene::geometry::BvhQuality;
use prism_scene::world::{Light, Material, Scene, SceneParts, SceneSpectrum};
use prism_spectrum::SampledWavelengths;

/// A floor 20 wide, a mirror 1 wide above it, a point light and a faint uniform sky
/// (whose power over the whole scene's disk is still most of the lights').
fn scene() -> Scene {
    let f = 10.0;
    let m = 0.5;
    let triangles = vec![
        [
            Vec3::new(-f, 0.0, -f),
            Vec3::new(f, 0.0, f),
            Vec3::new(f, 0.0, -f),
        ],
        [
            Vec3::new(-f, 0.0, -f),
            Vec3::new(-f, 0.0, f),
            Vec3::new(f, 0.0, f),
        ],
        [
            Vec3::new(-m, 1.0, -m),
            Vec3::new(m, 1.0, m),
            Vec3::new(m, 1.0, -m),
        ],
        [
            Vec3::new(-m, 1.0, -m),
            Vec3::new(-m, 1.0, m),
            Vec3::new(m, 1.0, m),
        ],
    ];
    Scene::new(SceneParts {
        attributes: Default::default(),
        triangle_material: vec![0, 0, 1, 1],
        triangles,
        materials: vec![
            Material::Diffuse {
                reflectance: SceneSpectrum::Constant(0.5),
            },
            Material::Conductor {
                eta: SceneSpectrum::Constant(0.2),
                k: SceneSpectrum::Constant(3.0),
                roughness: 0.0,
            },
        ],
        emission: vec![],
        lights: vec![
            Light::Point {
                position: Vec3::new(0.0, 3.0, 0.0),
                intensity: SceneSpectrum::Constant(1.0),
            },
            Light::Environment {
                radiance: SceneSpectrum::Constant(0.05),
            },
        ],
        camera: Camera::look_at(Vec3::new(0.0, 2.0, 8.0), Vec3::ZERO, Vec3::Y, 0.8),
        quality: BvhQuality::Medium,
    })
    .unwrap()
}

fn is_mirror(m: &Material) -> bool {
    matches!(m, Material::Conductor { .. })
}

/// The share of `n` light paths (stratified choices) that leave the sky, and every sky
/// ray's distance from `centre` at its closest and its origin's from the scene's centre.
fn sky_paths(
    scene: &Scene,
    aim: Option<&prism_scene::world::CausticTarget>,
    n: u32,
) -> (f64, Vec<(f32, f32)>) {
    let lambdas = SampledWavelengths::<4>::new([450.0, 500.0, 550.0, 600.0], [1.0; 4]).unwrap();
    let mut sky = 0u32;
    let mut rays = Vec::new();
    for i in 0..n {
        let u = (i as f32 + 0.5) / n as f32;
        let v = Vec2::new(
            (i as f32 * 0.618_034).fract(),
            (i as f32 * 0.754_878).fract(),
        );
        let w = Vec2::new(
            (i as f32 * 0.569_840).fract(),
            (i as f32 * 0.324_718).fract(),
        );
        let Some(s) = scene.sample_emission(u, v, w, &lambdas, aim) else {
            continue;
        };
        if s.light == 1 {
            sky += 1;
            let d = s.ray.direction.normalize();
            let to = Vec3::new(0.0, 1.0, 0.0) - s.ray.origin;
            let closest = (to - d * to.dot(d)).length();
            rays.push((closest, s.ray.origin.distance(Vec3::ZERO)));
        }
    }
    (f64::from(sky) / f64::from(n), rays)
}

#[test]
fn light_from_infinity_crosses_the_focusing_surfaces_from_outside_the_scene() {
    let scene = scene();
    let aim = scene.aim(is_mirror).unwrap();
    let (centre, radius) = scene.bounding_sphere_where(is_mirror).unwrap();
    assert!(centre.distance(Vec3::new(0.0, 1.0, 0.0)) < 1e-6);
    // The mirror's corners, not its bounding box's.
    assert!((radius - 0.5f32.hypot(0.5)).abs() < 1e-4, "{radius}");
    let (_, rays) = sky_paths(&scene, Some(&aim), 4000);
    assert!(!rays.is_empty());
    for (closest, origin) in rays {
        assert!(
            closest <= radius * 1.001,
            "a sky ray passes {closest} from the mirror"
        );
        // The scene's bounding sphere has radius 10 sqrt(2) about (0, 0.5, 0).
        assert!(
            origin > 10.0 * 2f32.sqrt(),
            "a sky ray starts inside the scene, {origin} out"
        );
    }
}

#[test]
fn light_paths_choose_the_sky_by_the_power_that_reaches_the_mirror() {
    let scene = scene();
    let aim = scene.aim(is_mirror).unwrap();
    let (whole, _) = sky_paths(&scene, None, 20000);
    let (aimed, _) = sky_paths(&scene, Some(&aim), 20000);
    // The sky's weight shrinks by (r / R)^2, the point light's stays.
    let (_, r) = scene.bounding_sphere_where(is_mirror).unwrap();
    let share = f64::from(r / scene.radius()).powi(2);
    let expected = whole * share / (whole * share + (1.0 - whole));
    assert!(
        whole > 0.5,
        "the sky's power over the whole scene is most of it: {whole}"
    );
    assert!(
        (aimed - expected).abs() < 0.01,
        "aimed sky share {aimed}, expected {expected}"
    );
}
