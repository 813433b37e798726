//! Dispersion measured against geometry: a camera looks through a 60-degree SF11 prism at
//! a distant white slit. Each wavelength bends by its own angle, so the slit is imaged at a
//! different column per wavelength; the column where each spectral band lands must be
//! where Snell's law with the glass's Sellmeier index puts it (computed here in 2D,
//! independently of the renderer's refraction).

mod common;

use common::refract_2d;

use std::f64::consts::PI;
use std::sync::Arc;

use glam::{DVec2, Mat4, Vec2, Vec3};
use prism_integrator::{LambdaSampler, RenderSettings, SpectralBands, render};
use prism_scene::camera::{Camera, Projection};
use prism_scene::geometry::BvhQuality;
use prism_scene::world::{Light, Material, Scene, SceneParts, SceneSpectrum};
use prism_spectrum::Spectrum;
use prism_spectrum::optics::named_glass;

const WIDTH: u32 = 200;
const HEIGHT: u32 = 8;
const SLIT_DISTANCE: f64 = 50.0;

/// Where the ray (origin, direction) in the prism's plane crosses the line through `a`
/// along `along`: the parameter t of the ray.
fn hit_line(origin: DVec2, dir: DVec2, a: DVec2, along: DVec2) -> f64 {
    let normal = DVec2::new(-along.y, along.x);
    normal.dot(a - origin) / normal.dot(dir)
}

/// The prism's cross-section in (u, v) = world (x, z): base from (-1, 0) to (1, 0), apex
/// (0, sqrt 3).
fn corners() -> [DVec2; 3] {
    [
        DVec2::new(-1.0, 0.0),
        DVec2::new(1.0, 0.0),
        DVec2::new(0.0, 3f64.sqrt()),
    ]
}

#[test]
fn each_wavelength_leaves_the_prism_where_snell_puts_it() {
    let glass = named_glass("sf11").unwrap().ior;
    let n0 = glass.evaluate(550.0);
    // Minimum deviation at 550 nm: inside, the ray runs parallel to the base.
    let theta = (n0 * (PI / 6.0).sin()).asin();
    let alpha = theta - PI / 6.0;
    let incident = DVec2::new(alpha.cos(), alpha.sin());
    let exit0 = DVec2::new(alpha.cos(), -alpha.sin());
    let [b0, b1, apex] = corners();
    let left_mid = 0.5 * (b0 + apex);
    let right_mid = 0.5 * (b1 + apex);
    let eye = left_mid - 3.0 * incident;
    let slit = right_mid + SLIT_DISTANCE * exit0;

    // The prism, extruded along y, faces wound outward.
    let w = |p: DVec2, y: f64| Vec3::new(p.x as f32, y as f32, p.y as f32);
    let centroid = (b0 + b1 + apex) / 3.0;
    let mut triangles = Vec::new();
    for (a, b) in [(b0, b1), (b1, apex), (apex, b0)] {
        let mut quad = [w(a, -5.0), w(b, -5.0), w(b, 5.0), w(a, 5.0)];
        let mid = 0.5 * (a + b);
        let outward = Vec3::new((mid - centroid).x as f32, 0.0, (mid - centroid).y as f32);
        if (quad[1] - quad[0]).cross(quad[2] - quad[0]).dot(outward) < 0.0 {
            quad.reverse();
        }
        triangles.push([quad[0], quad[1], quad[2]]);
        triangles.push([quad[0], quad[2], quad[3]]);
    }
    // A thin, tall, two-sided white slit facing back along the exit direction.
    let across = DVec2::new(-exit0.y, exit0.x) * 0.0125;
    let s = [
        w(slit - across, -20.0),
        w(slit + across, -20.0),
        w(slit + across, 20.0),
        w(slit - across, 20.0),
    ];
    triangles.push([s[0], s[1], s[2]]);
    triangles.push([s[0], s[2], s[3]]);
    let mut triangle_material = vec![0; 6];
    triangle_material.extend([1, 1]);

    // Camera looking along `incident`: its -z rotated about y onto (incident.x, incident.y).
    let phi = (-incident.x).atan2(-incident.y) as f32;
    let hfov = 12f32.to_radians();
    let aspect = WIDTH as f32 / HEIGHT as f32;
    let yfov = 2.0 * ((hfov / 2.0).tan() / aspect).atan();
    let camera = Camera {
        name: "eye".into(),
        to_world: Mat4::from_translation(w(eye, 0.0)) * Mat4::from_rotation_y(phi),
        aspect_ratio: None,
        lens: None,
        system: None,
        projection: Projection::Perspective { yfov },
    };
    let scene = Scene::new(SceneParts {
        attributes: Default::default(),
        triangles,
        triangle_material,
        materials: vec![
            Material::Dielectric {
                ior: SceneSpectrum::Sellmeier(Arc::new(glass.clone())),
                roughness: 0.0,
                absorption: None,
            },
            Material::Diffuse {
                reflectance: SceneSpectrum::Constant(0.0),
            },
        ],
        emission: vec![SceneSpectrum::Constant(1.0)],
        lights: [6, 7]
            .map(|t| Light::Triangle {
                triangle: t,
                emission: 0,
                two_sided: true,
            })
            .to_vec(),
        camera,
        quality: BvhQuality::Medium,
    })
    .unwrap();
    assert!(scene.features().dispersion);

    // Predicted column of each wavelength: where the exit ray passes the slit's centre.
    let column_of = |lambda: f64| -> f64 {
        let n = glass.evaluate(lambda);
        let miss = |x: f64| -> f64 {
            let ray = scene
                .camera()
                .generate_ray(Vec2::new((x / f64::from(WIDTH)) as f32, 0.5), aspect);
            let d = DVec2::new(f64::from(ray.direction.x), f64::from(ray.direction.z)).normalize();
            let o = DVec2::new(f64::from(ray.origin.x), f64::from(ray.origin.z));
            let p1 = o + hit_line(o, d, b0, apex - b0) * d;
            let in_normal = DVec2::new(-(3f64.sqrt()) / 2.0, 0.5);
            let inside = refract_2d(d, in_normal, 1.0 / n).unwrap();
            let p2 = p1 + hit_line(p1, inside, b1, apex - b1) * inside;
            let out_normal = DVec2::new(3f64.sqrt() / 2.0, 0.5);
            let out = refract_2d(inside, -out_normal, n).unwrap();
            // Signed distance of the slit's centre from the exit ray.
            let to_slit = slit - p2;
            out.x * to_slit.y - out.y * to_slit.x
        };
        // The miss distance changes sign once across the image: bisect for it.
        let (mut lo, mut hi) = (0.0, f64::from(WIDTH));
        assert!(miss(lo) * miss(hi) < 0.0, "{lambda} nm leaves the view");
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if miss(lo) * miss(mid) <= 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        0.5 * (lo + hi)
    };

    let bands = SpectralBands::new(440.0, 660.0, 11).unwrap();
    let settings = RenderSettings::default()
        .width(WIDTH)
        .height(HEIGHT)
        .samples(0..2048)
        .wavelengths(4)
        .lambda_sampler(LambdaSampler::Uniform)
        .max_depth(Some(4))
        .bands(Some(bands));
    let (film, _) = render(&scene, &settings).unwrap();
    let mut previous = f64::INFINITY;
    for b in 0..bands.count() {
        // The band's energy per column, and its centroid in pixel units.
        let energy: Vec<f64> = (0..WIDTH)
            .map(|x| (0..HEIGHT).map(|y| film.spectrum(x, y).unwrap()[b]).sum())
            .collect();
        let total: f64 = energy.iter().sum();
        assert!(total > 0.0, "band {b} never reached the slit");
        let measured = energy
            .iter()
            .enumerate()
            .map(|(x, e)| (x as f64 + 0.5) * e)
            .sum::<f64>()
            / total;
        // A white slit spreads each band uniformly in wavelength: its centroid is the mean
        // column over the band.
        let lo = bands.center(b) - 0.5 * bands.width();
        let predicted = (0..32)
            .map(|k| column_of(lo + (k as f64 + 0.5) / 32.0 * bands.width()))
            .sum::<f64>()
            / 32.0;
        // Within half a pixel (at 2048 samples the centroids' noise is about 0.15 px; a
        // 1% error in the index moves the bands by tens of pixels).
        assert!(
            (measured - predicted).abs() < 0.5,
            "band {b} ({} nm): column {measured:.2}, Snell says {predicted:.2}",
            bands.center(b)
        );
        // Longer wavelengths bend less, toward lower columns here.
        assert!(
            predicted < previous,
            "band {b} is not dispersed past band {}",
            b.max(1) - 1
        );
        previous = predicted;
    }
}
