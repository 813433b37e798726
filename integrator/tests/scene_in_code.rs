//! A scene built in code through `SceneBuilder` renders as its lights say: the floor
//! under a lamp is lit, its emitters are lights (next-event estimation finds them), and
//! the lamp seen directly shows its radiance.

use prism_integrator::glam::{Vec2, Vec3};
use prism_integrator::prism_scene::camera::Camera;
use prism_integrator::prism_scene::world::{Material, SceneBuilder, SceneSpectrum};
use prism_integrator::{RenderSettings, render};

fn quad(a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> [[Vec3; 3]; 2] {
    [[a, b, c], [a, c, d]]
}

#[test]
fn a_scene_built_in_code_is_lit_by_its_emitters() {
    let v = Vec3::new;
    // Looking straight down at the floor through the lamp's hole-free side: the lamp is
    // above the camera, facing down.
    let camera = Camera::look_at(v(0.0, 2.0, 0.0), v(0.0, 0.0, 0.0), Vec3::NEG_Z, 0.5);
    let mut builder = SceneBuilder::new(camera);
    let white = builder.material(Material::Diffuse {
        reflectance: SceneSpectrum::Constant(1.0),
    });
    builder.triangles(
        &quad(
            v(-10.0, 0.0, 10.0),
            v(10.0, 0.0, 10.0),
            v(10.0, 0.0, -10.0),
            v(-10.0, 0.0, -10.0),
        ),
        white,
    );
    // A small lamp of radiance L facing down at height h, above the camera: at the centre
    // of the floor below it the irradiance is about L * A / h^2 (A its area).
    let (h, half, radiance) = (3.0f32, 0.05f32, 100.0f32);
    builder.emitter(
        &quad(
            v(-half, h, half),
            v(-half, h, -half),
            v(half, h, -half),
            v(half, h, half),
        ),
        SceneSpectrum::Constant(f64::from(radiance)),
        false,
    );
    let scene = builder.build().unwrap();
    assert!(
        scene
            .camera()
            .generate_ray(Vec2::splat(0.5), 1.0)
            .direction
            .y
            < -0.99
    );
    let settings = RenderSettings::default().width(8).height(8).samples(0..64);
    let (film, _) = render(&scene, &settings).unwrap();
    // Radiance of the white floor at the centre: L A / (pi h^2), as XYZ's Y of a flat
    // spectrum of that value (Y = value x integral of y-bar, 106.86).
    let expected =
        f64::from(radiance * (2.0 * half).powi(2) / (std::f32::consts::PI * h * h)) * 106.856;
    let centre = film.xyz(3, 3).y + film.xyz(4, 4).y + film.xyz(3, 4).y + film.xyz(4, 3).y;
    let centre = centre / 4.0;
    assert!(
        (centre - expected).abs() < 0.1 * expected,
        "centre Y {centre}, expected {expected}"
    );
}
