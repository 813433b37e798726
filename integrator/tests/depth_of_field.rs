//! Depth of field through a thin lens: the blur of a small light off the plane in focus
//! has the thin-lens circle of confusion's size (its second moment, for a disk and for a
//! hexagonal aperture), and a light on the plane in focus stays sharp.

mod common;

use glam::{Mat4, Vec3};
use prism_integrator::{LambdaSampler, RenderSettings, render};
use prism_scene::camera::{
    ApertureImage, ApertureShape, ApertureSize, Camera, Projection, ThinLens,
};
use prism_scene::geometry::BvhQuality;
use prism_scene::world::{Light, Material, Scene, SceneParts, SceneSpectrum};

const SIZE: u32 = 64;
const YFOV_DEGREES: f32 = 30.0;
/// The emitter's side, scene units.
const SIDE: f32 = 0.1;

/// A square emitter of side SIDE facing a camera at the origin that looks down -z through
/// a thin lens of radius `radius` and shape `shape`, focused at `focus`; the emitter at
/// distance `depth`.
fn scene(depth: f32, focus: f32, radius: f32, shape: ApertureShape) -> Scene {
    let h = 0.5 * SIDE;
    let (a, b, c, d) = (
        Vec3::new(-h, -h, -depth),
        Vec3::new(h, -h, -depth),
        Vec3::new(h, h, -depth),
        Vec3::new(-h, h, -depth),
    );
    let triangles = vec![[a, b, c], [a, c, d]];
    Scene::new(SceneParts {
        attributes: Default::default(),
        triangle_material: vec![0, 0],
        triangles,
        materials: vec![Material::Diffuse {
            reflectance: SceneSpectrum::Constant(0.0),
        }],
        emission: vec![SceneSpectrum::Constant(1.0)],
        lights: (0..2)
            .map(|t| Light::Triangle {
                triangle: t,
                emission: 0,
                two_sided: false,
            })
            .collect(),
        camera: Camera {
            name: "lens".into(),
            to_world: Mat4::IDENTITY,
            projection: Projection::Perspective {
                yfov: YFOV_DEGREES.to_radians(),
            },
            aspect_ratio: None,
            lens: Some(ThinLens {
                shape,
                focus_distance: Some(focus),
                ..ThinLens::new(ApertureSize::Radius(radius))
            }),
            system: None,
        },
        quality: BvhQuality::Medium,
    })
    .unwrap()
}

fn blur(depth: f32, focus: f32, radius: f32, shape: ApertureShape) -> f64 {
    let settings = RenderSettings::default()
        .width(SIZE)
        .height(SIZE)
        .samples(0..1024)
        .wavelengths(4)
        .lambda_sampler(LambdaSampler::Visible);
    common::second_moment(
        &render(&scene(depth, focus, radius, shape), &settings)
            .unwrap()
            .0,
    )
}

/// Pixels per unit of tan(angle) across the image.
fn pixels_per_tan() -> f64 {
    f64::from(SIZE) / (2.0 * f64::from((0.5 * YFOV_DEGREES.to_radians()).tan()))
}

/// What the emitter's own sharp image adds to the mean r^2 (a square of side s: s^2 / 6),
/// less what measuring at pixel centres takes away (1/12 per axis).
fn sharp_part(depth: f32) -> f64 {
    let side = f64::from(SIDE / depth) * pixels_per_tan();
    side * side / 6.0 - 1.0 / 6.0
}

/// An aperture image of a ring (transmission 1 between radii 0.5 and 1 of the square
/// [-1, 1]^2 it fills, 0.5 on a thin circle inside, 0 elsewhere), and its second moment
/// about its centre, E[x^2 + y^2], summed exactly over its pixels.
fn ring_aperture() -> (ApertureShape, f64) {
    let side = 32usize;
    let cell = 2.0 / side as f64;
    let (mut values, mut mass, mut moment) = (Vec::new(), 0.0, 0.0);
    for j in 0..side {
        for i in 0..side {
            let (x0, y0) = (-1.0 + i as f64 * cell, 1.0 - (j + 1) as f64 * cell);
            let (cx, cy) = (x0 + 0.5 * cell, y0 + 0.5 * cell);
            let r = cx.hypot(cy);
            let t = if (0.5..1.0).contains(&r) {
                1.0
            } else if (0.3..0.36).contains(&r) {
                0.5
            } else {
                0.0
            };
            // The integral of x^2 + y^2 over the cell.
            let second = |a: f64| (a + cell).powi(3) / 3.0 - a.powi(3) / 3.0;
            moment += t * (second(x0) * cell + second(y0) * cell);
            mass += t * cell * cell;
            values.push(t as f32);
        }
    }
    let image = ApertureImage::new(side, side, values).unwrap();
    (
        ApertureShape::Image(std::sync::Arc::new(image)),
        moment / mass,
    )
}

#[test]
fn the_blur_of_a_point_off_focus_is_the_circle_of_confusion() {
    let (depth, focus, radius) = (4.0f32, 2.0f32, 0.25f32);
    // Rays from a lens point p meet the plane in focus at p (1 - focus / depth) off the
    // pinhole's: the blur is the aperture scaled by |1 / focus - 1 / depth| in tan units.
    let scale = f64::from(radius * (1.0 / focus - 1.0 / depth)) * pixels_per_tan();
    for (shape, unit_moment) in [
        (ApertureShape::Disk, 0.5),
        // A regular n-gon of circumradius 1: (2 + cos(2 pi / n)) / 6.
        (
            ApertureShape::Polygon {
                blades: 6,
                rotation: 0.0,
            },
            (2.0 + (std::f64::consts::PI / 3.0).cos()) / 6.0,
        ),
        ring_aperture(),
    ] {
        let want = scale * scale * unit_moment;
        let got = blur(depth, focus, radius, shape.clone()) - sharp_part(depth);
        let diameter = |m: f64| 2.0 * (m / unit_moment).sqrt();
        let name = match &shape {
            ApertureShape::Image(_) => "ring image".to_string(),
            other => format!("{other:?}"),
        };
        assert!(
            (diameter(got) / diameter(want) - 1.0).abs() < 0.03,
            "{name}: blur {:.2} px across, the circle of confusion {:.2}",
            diameter(got),
            diameter(want)
        );
    }
}

#[test]
fn a_point_in_focus_stays_sharp() {
    let m = blur(2.0, 2.0, 0.25, ApertureShape::Disk);
    let sharp = sharp_part(2.0);
    assert!(
        (m - sharp).abs() < 0.3,
        "in focus: mean r^2 {m:.3} px^2, the emitter's own image {sharp:.3}"
    );
}
