//! A scene built in code (a floor, a dark panel standing on it, a lamp) rendered to a PNG:
//! `cargo run --release -p prism-integrator --example scene_in_code -- out.png`.

use prism_integrator::glam::Vec3;
use prism_integrator::prism_scene::camera::Camera;
use prism_integrator::prism_scene::world::{Material, SceneBuilder, SceneSpectrum};
use prism_integrator::{DisplaySettings, RenderSettings, encode_png, render};
use prism_spectrum::color::RgbSpaceId;

fn quad(a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> [[Vec3; 3]; 2] {
    [[a, b, c], [a, c, d]]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "scene_in_code.png".into());
    let eye = Vec3::new(0.0, 1.2, 4.0);
    let mut builder =
        SceneBuilder::new(Camera::look_at(eye, Vec3::new(0.0, 0.5, 0.0), Vec3::Y, 0.8));
    let grey = builder.material(Material::Diffuse {
        reflectance: SceneSpectrum::Constant(0.5),
    });
    let dark = builder.material(Material::Diffuse {
        reflectance: SceneSpectrum::Constant(0.2),
    });
    let v = |x, y, z| Vec3::new(x, y, z);
    builder.triangles(
        &quad(
            v(-3.0, 0.0, 3.0),
            v(3.0, 0.0, 3.0),
            v(3.0, 0.0, -3.0),
            v(-3.0, 0.0, -3.0),
        ),
        grey,
    );
    builder.triangles(
        &quad(
            v(-0.5, 0.0, 0.5),
            v(0.5, 0.0, 0.5),
            v(0.5, 1.0, 0.5),
            v(-0.5, 1.0, 0.5),
        ),
        dark,
    );
    // A lamp facing down: a flat spectrum of radiance 0.3 W m^-2 sr^-1 nm^-1.
    builder.emitter(
        &quad(
            v(-1.0, 3.0, -1.0),
            v(1.0, 3.0, -1.0),
            v(1.0, 3.0, 1.0),
            v(-1.0, 3.0, 1.0),
        ),
        SceneSpectrum::Constant(0.3),
        false,
    );
    let scene = builder.build()?;
    let settings = RenderSettings::default()
        .width(160)
        .height(120)
        .samples(0..32);
    let start = std::time::Instant::now();
    let (film, stats) = render(&scene, &settings)?;
    std::fs::write(
        &out,
        encode_png(&film, RgbSpaceId::Srgb.space(), DisplaySettings::default()),
    )?;
    println!(
        "{out}: {} paths in {:.2} s",
        stats.paths,
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
