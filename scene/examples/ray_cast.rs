//! A scene built in code (a floor, a box, a lamp), then looked at the way an integrator
//! does: a ray per character cell from the camera, printed as the hit's distance, with
//! shadow rays to the lamp deciding lit (`#` facing up, `|` facing sideways) or in
//! shadow (`+`).
//!
//! `cargo run -p prism-scene --example ray_cast`

use prism_scene::camera::Camera;
use prism_scene::glam::{Vec2, Vec3};
use prism_scene::world::{Material, SceneBuilder, SceneSpectrum};

fn quad(a: Vec3, b: Vec3, c: Vec3, d: Vec3) -> [[Vec3; 3]; 2] {
    [[a, b, c], [a, c, d]]
}

fn main() -> Result<(), prism_scene::LoadError> {
    let v = Vec3::new;
    let camera = Camera::look_at(v(0.0, 2.0, 5.0), v(0.0, 0.3, 0.0), Vec3::Y, 0.7);
    let mut builder = SceneBuilder::new(camera);
    let grey = builder.material(Material::Diffuse {
        reflectance: SceneSpectrum::Constant(0.5),
    });
    let floor = quad(
        v(-3.0, 0.0, 3.0),
        v(3.0, 0.0, 3.0),
        v(3.0, 0.0, -3.0),
        v(-3.0, 0.0, -3.0),
    );
    builder.triangles(&floor, grey);
    // A box's top and its four sides.
    let (lo, hi) = (v(-0.5, 0.0, -0.5), v(0.5, 1.0, 0.5));
    let corner = |x: bool, y: bool, z: bool| {
        v(
            if x { hi.x } else { lo.x },
            if y { hi.y } else { lo.y },
            if z { hi.z } else { lo.z },
        )
    };
    let c = |i: u8| corner(i & 1 != 0, i & 2 != 0, i & 4 != 0);
    for [a, b, cc, d] in [
        [2, 6, 7, 3],
        [4, 5, 7, 6],
        [1, 3, 7, 5],
        [0, 4, 6, 2],
        [0, 2, 3, 1],
    ] {
        builder.triangles(&quad(c(a), c(b), c(cc), c(d)), grey);
    }
    let lamp = v(1.5, 3.0, 1.0);
    let s = 0.2;
    builder.emitter(
        &quad(
            lamp + v(-s, 0.0, -s),
            lamp + v(s, 0.0, -s),
            lamp + v(s, 0.0, s),
            lamp + v(-s, 0.0, s),
        ),
        SceneSpectrum::Constant(10.0),
        false,
    );
    let scene = builder.build()?;

    let (columns, rows) = (64u32, 24u32);
    let aspect = columns as f32 / (2.0 * rows as f32); // character cells are tall
    for row in 0..rows {
        let line: String = (0..columns)
            .map(|column| {
                let film = Vec2::new(
                    (column as f32 + 0.5) / columns as f32,
                    (row as f32 + 0.5) / rows as f32,
                );
                let ray = scene.camera().generate_ray(film, aspect);
                match scene.intersect(&ray) {
                    None => ' ',
                    Some(hit) if hit.p.y > 2.9 => '*', // the lamp
                    Some(hit) => {
                        let to_lamp = lamp - hit.p;
                        let shadow = hit.spawn_to(to_lamp.normalize(), to_lamp.length() * 0.999);
                        match (scene.occluded(&shadow), hit.normal.y.abs() > 0.5) {
                            (true, _) => '+',
                            (false, true) => '#',
                            (false, false) => '|',
                        }
                    }
                }
            })
            .collect();
        println!("{line}");
    }
    Ok(())
}
